//! Two vehicles side by side, their wheels driven by velocity servos, and a box that a
//! hook drops in front of one of them and later removes: several robots in one
//! simulation, controllers attached to joints, objects added and removed at run time.

use ars_core::nalgebra::Vector3;
use ars_core::{
    Hooks, Mass, ObjectId, Profile, Program, Result, Simulation, SimulationBuilder, SpaceKind, VelocityServo,
};

use crate::vehicles::{VehicleParts, VehicleSpec, build_vehicle};

/// Two differential-drive vehicles (joint names `left/…` and `right/…`), 3 m apart,
/// driving along +X: each wheel has a velocity servo whose set-point ramps to
/// `wheel_speed` (rad/s) in 1 s. At `drop_time` a hook drops a 0.4 m, 2 kg box 1.5 m in
/// front of the left vehicle; at `remove_time` it removes it again.
#[derive(Clone, Debug)]
pub struct Convoy {
    /// Wheel joint speed set-point, rad/s (positive drives +X).
    pub wheel_speed: f64,
    /// When the box is dropped, s.
    pub drop_time: f64,
    /// When the box is removed, s.
    pub remove_time: f64,
    /// The two vehicles, left then right.
    pub vehicles: Vec<VehicleParts>,
    /// The box while it exists.
    pub obstacle: Option<ObjectId>,
    /// Whether the box was dropped, and removed.
    pub events: (bool, bool),
}

impl Default for Convoy {
    fn default() -> Self {
        Convoy {
            wheel_speed: 4.0,
            drop_time: 2.0,
            remove_time: 5.0,
            vehicles: Vec::new(),
            obstacle: None,
            events: (false, false),
        }
    }
}

impl Hooks for Convoy {
    fn post_step(&mut self, sim: &mut Simulation) -> Result<()> {
        let t = sim.scene().time();
        if !self.events.0 && t >= self.drop_time {
            let front = sim.scene().position(self.vehicles[0].chassis)?;
            let b = sim.scene_mut().add_box([0.4, 0.4, 0.4], [front.x + 1.5, 1.0, front.z], Mass::Total(2.0))?;
            sim.scene_mut().set_name(b, "obstacle")?;
            self.obstacle = Some(b);
            self.events.0 = true;
        }
        if !self.events.1 && t >= self.remove_time {
            if let Some(b) = self.obstacle.take() {
                sim.remove_object(b)?;
            }
            self.events.1 = true;
        }
        Ok(())
    }
}

impl Program for Convoy {
    fn configure(&self, builder: SimulationBuilder) -> SimulationBuilder {
        // The original's simple space: the thesis' results, bit for bit.
        builder.space(SpaceKind::Simple).floor_plane(Vector3::y(), 0.0)
    }

    fn create_sim_objects(&mut self, sim: &mut Simulation) -> Result<()> {
        for (prefix, z) in [("left/", 0.0), ("right/", 3.0)] {
            let spec = VehicleSpec { offset: Vector3::new(0.0, 0.31, z), prefix: prefix.into(), ..Default::default() };
            let v = build_vehicle(sim, &spec)?;
            for wheel in [v.w1, v.w2] {
                let setpoint = Profile::ramp(0.0, 1.0, 0.0, self.wheel_speed)?;
                sim.scene_mut().joint_mut(wheel)?.set_controller(VelocityServo { setpoint, gain: 5.0 })?;
            }
            self.vehicles.push(v);
        }
        Ok(())
    }
}
