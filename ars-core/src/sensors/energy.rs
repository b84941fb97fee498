//! Energy sensors: kinetic, potential and total energy of a body or of the system.

use nalgebra::Vector3;

use super::{Record, Sensor};
use crate::body::BodyRef;
use crate::error::Result;
use crate::handle::ObjectId;
use crate::scene::Scene;

/// Translational `½ m v·v` and rotational `½ ωᵀ I_w ω` kinetic energy, with the
/// world-frame inertia `I_w = R I Rᵀ` (correct for rotated bodies, unlike the
/// original, which used the body-frame inertia).
fn kinetic(b: &BodyRef<'_>) -> Kinetic {
    let v = b.linear_velocity();
    let w = b.angular_velocity();
    Kinetic { translational: 0.5 * b.mass() * v.dot(&v), rotational: 0.5 * w.dot(&(b.inertia_world() * w)) }
}

/// `−m g·(p − p_ref)` with `p_ref = (0, reference_height, 0)`.
fn potential(b: &BodyRef<'_>, gravity: &Vector3<f64>, reference_height: f64) -> f64 {
    let p = b.position().coords - Vector3::new(0.0, reference_height, 0.0);
    -b.mass() * gravity.dot(&p)
}

/// Kinetic energy of a body.
#[derive(Clone, Debug)]
pub struct KineticEnergy {
    object: ObjectId,
}

impl KineticEnergy {
    /// On `object`.
    pub fn new(object: ObjectId) -> Self {
        KineticEnergy { object }
    }
}

/// A [`KineticEnergy`] measurement, J.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Kinetic {
    /// `½ m v·v`, J.
    pub translational: f64,
    /// `½ ωᵀ I_w ω`, J.
    pub rotational: f64,
}

impl Kinetic {
    /// Translational plus rotational, J.
    pub fn total(&self) -> f64 {
        self.translational + self.rotational
    }
}

impl Record for Kinetic {
    fn columns() -> Vec<&'static str> {
        vec!["translational energy [J]", "rotational energy [J]"]
    }
    fn values(&self) -> Vec<Option<f64>> {
        vec![Some(self.translational), Some(self.rotational)]
    }
}

impl Sensor for KineticEnergy {
    type Record = Kinetic;
    fn measure(&mut self, sim: &Scene) -> Result<Kinetic> {
        Ok(kinetic(&sim.body(self.object)?))
    }
    fn objects(&self) -> Vec<ObjectId> {
        vec![self.object]
    }
}

/// Gravitational potential energy of a body, `m g (y − reference height)` with the
/// default gravity (reference height 0 by default, as the original's world origin).
#[derive(Clone, Debug)]
pub struct PotentialEnergy {
    object: ObjectId,
    reference_height: f64,
}

impl PotentialEnergy {
    /// On `object`, zero at y = 0.
    pub fn new(object: ObjectId) -> Self {
        PotentialEnergy { object, reference_height: 0.0 }
    }
    /// Zero at `y = height` instead.
    #[must_use]
    pub fn reference_height(mut self, height: f64) -> Self {
        self.reference_height = height;
        self
    }
}

/// A [`PotentialEnergy`] measurement.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Potential {
    /// Potential energy, J.
    pub potential: f64,
}

impl Record for Potential {
    fn columns() -> Vec<&'static str> {
        vec!["potential energy [J]"]
    }
    fn values(&self) -> Vec<Option<f64>> {
        vec![Some(self.potential)]
    }
}

impl Sensor for PotentialEnergy {
    type Record = Potential;
    fn measure(&mut self, sim: &Scene) -> Result<Potential> {
        Ok(Potential { potential: potential(&sim.body(self.object)?, &sim.gravity(), self.reference_height) })
    }
    fn objects(&self) -> Vec<ObjectId> {
        vec![self.object]
    }
}

/// Kinetic, potential and total energy (the disaggregated form of the original).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Energy {
    /// Kinetic energy (translational + rotational), J.
    pub kinetic: f64,
    /// Potential energy, J.
    pub potential: f64,
}

impl Energy {
    /// Kinetic plus potential, J.
    pub fn total(&self) -> f64 {
        self.kinetic + self.potential
    }
}

impl Record for Energy {
    fn columns() -> Vec<&'static str> {
        vec!["kinetic energy [J]", "potential energy [J]", "total energy [J]"]
    }
    fn values(&self) -> Vec<Option<f64>> {
        vec![Some(self.kinetic), Some(self.potential), Some(self.total())]
    }
}

/// Total energy of one body.
#[derive(Clone, Debug)]
pub struct TotalEnergy {
    object: ObjectId,
    reference_height: f64,
}

impl TotalEnergy {
    /// On `object`, potential zero at y = 0.
    pub fn new(object: ObjectId) -> Self {
        TotalEnergy { object, reference_height: 0.0 }
    }
    /// Potential zero at `y = height` instead.
    #[must_use]
    pub fn reference_height(mut self, height: f64) -> Self {
        self.reference_height = height;
        self
    }
}

impl Sensor for TotalEnergy {
    type Record = Energy;
    fn measure(&mut self, sim: &Scene) -> Result<Energy> {
        let b = sim.body(self.object)?;
        Ok(Energy { kinetic: kinetic(&b).total(), potential: potential(&b, &sim.gravity(), self.reference_height) })
    }
    fn objects(&self) -> Vec<ObjectId> {
        vec![self.object]
    }
}

/// Total energy of every dynamic body of the simulation (every body counts, a heavy
/// base box included, as in the original).
#[derive(Clone, Debug, Default)]
pub struct SystemTotalEnergy {
    reference_height: f64,
}

impl SystemTotalEnergy {
    /// Potential zero at y = 0.
    pub fn new() -> Self {
        SystemTotalEnergy::default()
    }
    /// Potential zero at `y = height` instead.
    #[must_use]
    pub fn reference_height(mut self, height: f64) -> Self {
        self.reference_height = height;
        self
    }
}

impl Sensor for SystemTotalEnergy {
    type Record = Energy;
    fn measure(&mut self, sim: &Scene) -> Result<Energy> {
        let g = sim.gravity();
        let mut e = Energy { kinetic: 0.0, potential: 0.0 };
        for (_, body) in sim.bodies() {
            let b = sim.world().body(body)?;
            e.kinetic += kinetic(&b).total();
            e.potential += potential(&b, &g, self.reference_height);
        }
        Ok(e)
    }
}
