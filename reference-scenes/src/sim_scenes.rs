//! The reference scenes through the `Simulation` layer (named objects, hooks, sensors),
//! as a user writes them: what that layer costs over native ODE is measured on these.

use ars_core::nalgebra::Vector3;
use ars_core::{Mass, Program, Simulation, SpaceKind};
use ars_programs::{ConicalPendulum, SpeedProfile};

use crate::native::drop_pile_position;

/// A simulation built as its C twin builds the scene.
pub struct SimScene {
    /// The simulation; its program (if any) runs as added hooks.
    pub sim: Simulation,
}

impl SimScene {
    fn with_floor(space: SpaceKind) -> Simulation {
        Simulation::builder().space(space).floor_plane(Vector3::y(), 0.0).build().expect("a valid simulation")
    }

    /// The thesis' falling ball (C twin: `falling_sphere.c`).
    pub fn falling_sphere() -> Self {
        let mut sim = Self::with_floor(SpaceKind::Simple);
        sim.scene_mut().add_sphere(0.5, [1.0, 1.0, 1.0], Mass::Total(1.0)).expect("a valid sphere");
        SimScene { sim }
    }

    /// `count` spheres and boxes dropped in a hash space (C twin: `drop_pile.c`).
    pub fn drop_pile(count: usize) -> Self {
        let mut sim = Self::with_floor(SpaceKind::HASH);
        for i in 0..count {
            let p = drop_pile_position(i);
            if i % 2 == 0 {
                sim.scene_mut().add_sphere(0.2, p, Mass::Total(1.0)).expect("a valid sphere");
            } else {
                sim.scene_mut().add_box([0.3, 0.3, 0.3], p, Mass::Total(1.0)).expect("a valid box");
            }
        }
        SimScene { sim }
    }

    /// The 2-DOF arm of IROS example 2, its waist driven by a hook (C twin:
    /// `conical_pendulum.c`, which records nothing: neither does this one).
    pub fn conical_pendulum() -> Self {
        let mut program = ConicalPendulum::default();
        let mut sim = program.create_simulation().expect("the program builds");
        sim.remove_sensor(program.record.take().expect("created")).expect("its record");
        sim.add_hooks(program).expect("hooks");
        SimScene { sim }
    }

    /// The mobile manipulator of IROS example 3 following its speed profile, recording
    /// its row every step (C twin: `mobile_manipulator.c`, which records it too).
    pub fn mobile_manipulator() -> Self {
        let mut program = SpeedProfile::default();
        let mut sim = program.create_simulation().expect("the program builds");
        sim.add_hooks(program).expect("hooks");
        SimScene { sim }
    }

    /// Runs `n` steps.
    pub fn step(&mut self, n: usize) {
        for _ in 0..n {
            self.sim.step().expect("a valid step");
        }
    }

    /// Position, quaternion and velocities of the `i`-th body in creation order, as
    /// [`CScene::body_state`](crate::CScene::body_state) has them.
    pub fn body_state(&self, i: usize) -> crate::BodyState {
        let (_, handle) = self.sim.scene().bodies().nth(i).expect("a body of the scene");
        let b = self.sim.scene().world().body(handle).expect("a live body");
        let (p, q, v, w) = (b.position(), b.quaternion(), b.linear_velocity(), b.angular_velocity());
        [p.x, p.y, p.z, q.w, q.i, q.j, q.k, v.x, v.y, v.z, w.x, w.y, w.z]
    }
}
