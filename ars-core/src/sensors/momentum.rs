//! The momentum of a group of bodies: their centre of mass, its velocity and their
//! angular momentum about it (MuJoCo's `subtreecom`, `subtreelinvel` and
//! `subtreeangmom` of a body and the bodies below it).

use nalgebra::{Point3, Vector3};

use super::{Record, Sensor};
use crate::error::{Error, Result};
use crate::handle::ObjectId;
use crate::scene::Scene;

/// The centre of mass of a group of objects with bodies, the velocity of that centre
/// and the group's angular momentum about it, in the world frame:
/// `c = Σ mᵢ pᵢ / M`, `v = Σ mᵢ vᵢ / M`, `L = Σ (I_w,ᵢ ωᵢ + mᵢ (pᵢ − c) × (vᵢ − v))`,
/// each body's position `pᵢ` and velocity `vᵢ` those of its centre of mass and
/// `I_w,ᵢ = R I Rᵀ` its inertia in the world frame.
#[derive(Clone, Debug)]
pub struct Momentum {
    objects: Vec<ObjectId>,
}

impl Momentum {
    /// Of `objects`, each with a body (at least one; each once).
    pub fn new(objects: &[ObjectId]) -> Result<Self> {
        let problem = if objects.is_empty() {
            Some("needs at least one object")
        } else if objects.iter().enumerate().any(|(k, o)| objects[..k].contains(o)) {
            Some("names an object twice")
        } else {
            None
        };
        match problem {
            Some(problem) => Err(Error::Invalid { what: "a momentum sensor", problem: problem.into() }),
            None => Ok(Momentum { objects: objects.to_vec() }),
        }
    }
}

/// A [`Momentum`] measurement, world frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MomentumReading {
    /// The group's centre of mass, m.
    pub centre: Point3<f64>,
    /// Its velocity, m/s.
    pub velocity: Vector3<f64>,
    /// The group's angular momentum about it, kg·m²/s.
    pub angular_momentum: Vector3<f64>,
}

impl Record for MomentumReading {
    fn columns() -> Vec<&'static str> {
        vec![
            "x [m]",
            "y [m]",
            "z [m]",
            "vx [m/s]",
            "vy [m/s]",
            "vz [m/s]",
            "Lx [kg m2/s]",
            "Ly [kg m2/s]",
            "Lz [kg m2/s]",
        ]
    }
    fn values(&self) -> Vec<Option<f64>> {
        [self.centre.coords, self.velocity, self.angular_momentum]
            .iter()
            .flat_map(|v| v.iter().map(|x| Some(*x)))
            .collect()
    }
}

impl Sensor for Momentum {
    type Record = MomentumReading;
    fn measure(&mut self, sim: &Scene) -> Result<MomentumReading> {
        // Two passes over the bodies (it samples every step: nothing is allocated).
        let (mut mass, mut moment, mut momentum) = (0.0, Vector3::zeros(), Vector3::zeros());
        for o in &self.objects {
            let b = sim.body(*o)?;
            mass += b.mass();
            moment += b.mass() * b.position().coords;
            momentum += b.mass() * b.linear_velocity();
        }
        let (centre, velocity) = (moment / mass, momentum / mass);
        let mut angular_momentum = Vector3::zeros();
        for o in &self.objects {
            let b = sim.body(*o)?;
            let (r, v) = (b.position().coords - centre, b.linear_velocity() - velocity);
            angular_momentum += b.inertia_world() * b.angular_velocity() + b.mass() * r.cross(&v);
        }
        Ok(MomentumReading { centre: Point3::from(centre), velocity, angular_momentum })
    }
    fn objects(&self) -> Vec<ObjectId> {
        self.objects.clone()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::body::Mass;
    use crate::simulation::Simulation;

    /// Two spheres in free flight (no gravity): the centre, its velocity and the angular
    /// momentum about it, computed by hand, before and after a step (momentum is kept).
    #[test]
    fn two_bodies_read_their_centre_velocity_and_angular_momentum() {
        let mut sim = Simulation::new().unwrap();
        sim.scene_mut().world_mut().set_gravity([0.0; 3].into()).unwrap();
        let a = sim.scene_mut().add_sphere(0.1, [0.0, 1.0, 0.0], Mass::Total(1.0)).unwrap();
        let b = sim.scene_mut().add_sphere(0.2, [3.0, 1.0, 0.0], Mass::Total(2.0)).unwrap();
        sim.scene_mut().body_mut(a).unwrap().set_linear_velocity([0.0, 0.0, 3.0].into()).unwrap();
        sim.scene_mut().body_mut(b).unwrap().set_angular_velocity([0.0, 5.0, 0.0].into()).unwrap();
        let id = sim.add_sensor(Momentum::new(&[a, b]).unwrap()).unwrap();
        sim.step().unwrap();
        let reading = sim.records(id).unwrap().last().unwrap().record;
        // The centre starts at x = 2 and moves with v = (0, 0, 1).
        let dt = sim.scene().time_step();
        assert!((reading.centre - Point3::new(2.0, 1.0, dt)).norm() < 1e-12, "{reading:?}");
        assert!((reading.velocity - Vector3::new(0.0, 0.0, 1.0)).norm() < 1e-12);
        // About the centre: a at r = (−2, 0, ·) moving (0, 0, 2) relative to it gives
        // m r × v = (0, 4, 0); b at (1, 0, ·) moving (0, 0, −1) gives 2·(0, 1, 0); b spins
        // at 5 rad/s about y with I = 2/5·2·0.2² = 0.032: 0.16.
        let expected_y = 4.0 + 2.0 + 0.16;
        assert!((reading.angular_momentum - Vector3::new(0.0, expected_y, 0.0)).norm() < 1e-9, "{reading:?}");
    }

    #[test]
    fn no_objects_or_one_twice_is_refused() {
        assert!(Momentum::new(&[]).is_err());
        let mut sim = Simulation::new().unwrap();
        let a = sim.scene_mut().add_sphere(0.1, [0.0, 1.0, 0.0], Mass::Total(1.0)).unwrap();
        let err = Momentum::new(&[a, a]).unwrap_err().to_string();
        assert!(err.contains("names an object twice"), "{err}");
    }
}
