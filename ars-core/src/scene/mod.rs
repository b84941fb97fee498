//! The [`Scene`] of a simulation: its named objects and joints on a [`World`], and its
//! clock. Sensors read a scene; a [`Simulation`](crate::Simulation) is a scene with
//! its sensors and hooks, and the step loop (`sim.scene_mut().add_sphere(..)`,
//! `sim.scene().body(..)`).
//!
//! - objects: bodies with their [`Shape`](crate::Shape), static shapes, floors;
//! - joints: named joints with their efforts, friction and controllers;
//! - floors: heightfield terrains.

mod actuators;
mod armature;
pub mod colors;
mod floor;
mod geom_contact;
mod insert;
pub(crate) mod joint_group;
pub(crate) mod joints;
pub(crate) mod names;
pub(crate) mod objects;
mod sim_joint;
mod surfaces;
mod views;

use nalgebra::Vector3;

pub use floor::{Heightfield, MAX_GRID_VERTICES, heightfield_triangles};
pub use geom_contact::{GeomContact, GeomOf};
pub(crate) use geom_contact::{impedance_cfm, reduced_mass};
pub(crate) use insert::{NewObject, ObjectName};
pub use joint_group::{GroupJoint, GroupRest};
pub use joints::{ActuatorLimits, JointEfforts, JointEnd, JointType, Mimic};
pub use objects::{Color, Visual};
pub use sim_joint::SimJoint;
pub use views::{JointKey, JointView, ObjectKey, ObjectView};

use crate::error::{Error, Result};
use crate::handle::{Arena, JointId, ObjectId, SpaceHandle, WorldId};
use crate::limits;
use crate::world::{SpaceKind, World};
use joints::JointData;
use names::Names;
use objects::ObjectData;
use surfaces::PairSurfaces;

/// The objects, joints and world of a simulation, and its clock: everything a sensor
/// reads. Built by [`SimulationBuilder::build`](crate::SimulationBuilder::build).
pub struct Scene {
    world: World,
    space: SpaceHandle,
    space_kind: SpaceKind,
    objects: Arena<ObjectData>,
    object_names: Names<ObjectId>,
    joints: Arena<JointData>,
    joint_names: Names<JointId>,
    /// Joint groups (see [`joint_group`]), each with its joints.
    groups: Vec<joint_group::JointGroup>,
    /// Each group's kinematics while the drives of a step are applied (`kept`; else
    /// stale, the room kept for the next step).
    group_kinematics_now: Vec<joint_group::GroupKinematics>,
    group_kinematics_kept: bool,
    /// The one-sided rows of the groups' slides at their stops, made each step (its
    /// room kept from one step to the next).
    group_stops: Vec<crate::world::limit_rows::LimitRow>,
    /// Joints with viscous friction or a controller, in creation order.
    driven_joints: Vec<JointId>,
    /// Joints driven by an [`Actuator`](crate::Actuator), in the order their actuators
    /// were attached (an MJCF file's order of `<actuator>`s).
    actuated_joints: Vec<JointId>,
    /// Robots loaded so far (each gets its own collision category).
    pub(crate) robots_loaded: u32,
    /// The URDF robots loaded, as ROS describes them.
    pub(crate) robot_descriptions: Vec<crate::formats::urdf::RobotDescription>,
    /// The mocap bodies of the MJCF models loaded (moved by `set_mocap_pose`).
    pub(crate) mocap_bodies: Vec<crate::formats::mjcf::MjcfMocap>,
    pair_surfaces: PairSurfaces,
    pub(crate) time: f64,
    pub(crate) step_count: u64,
    pub(crate) frame_count: u64,
    time_step: limits::TimeStep,
    pub(crate) steps_per_frame: u32,
}

impl std::fmt::Debug for Scene {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Scene")
            .field("time", &self.time)
            .field("steps", &self.step_count)
            .field("objects", &self.objects.len())
            .field("joints", &self.joints.len())
            .finish()
    }
}

impl Scene {
    /// A scene on `world` (already configured) colliding in `space`.
    pub(crate) fn new(
        world: World,
        space: (SpaceHandle, SpaceKind),
        time_step: limits::TimeStep,
        steps_per_frame: u32,
    ) -> Scene {
        let (space, space_kind) = space;
        let id = world.id();
        Scene {
            world,
            space,
            space_kind,
            objects: Arena::new(id),
            object_names: Names::new("object"),
            joints: Arena::new(id),
            joint_names: Names::new("joint"),
            groups: Vec::new(),
            group_kinematics_now: Vec::new(),
            group_kinematics_kept: false,
            group_stops: Vec::new(),
            driven_joints: Vec::new(),
            actuated_joints: Vec::new(),
            robots_loaded: 0,
            robot_descriptions: Vec::new(),
            mocap_bodies: Vec::new(),
            pair_surfaces: PairSurfaces::default(),
            time: 0.0,
            step_count: 0,
            frame_count: 0,
            time_step,
            steps_per_frame,
        }
    }

    /// The underlying world (for everything the simulation layer does not wrap).
    pub fn world(&self) -> &World {
        &self.world
    }

    /// The underlying world, mutably. Objects and joints created directly in it are
    /// not named or tracked by the simulation.
    pub fn world_mut(&mut self) -> &mut World {
        &mut self.world
    }

    /// The collision space of the simulation.
    pub fn space(&self) -> SpaceHandle {
        self.space
    }

    /// Id of the world (and of every handle of this simulation).
    pub fn world_id(&self) -> WorldId {
        self.world.id()
    }

    /// Simulated time, s: the sum of the time steps taken so far.
    pub fn time(&self) -> f64 {
        self.time
    }

    /// Time step, s.
    pub fn time_step(&self) -> f64 {
        self.time_step.get()
    }

    /// Changes the time step for the next steps.
    pub fn set_time_step(&mut self, dt: f64) -> Result<()> {
        self.time_step = limits::TimeStep::new(dt)?;
        Ok(())
    }

    /// Steps per frame.
    pub fn steps_per_frame(&self) -> u32 {
        self.steps_per_frame
    }

    /// Steps taken so far.
    pub fn step_count(&self) -> u64 {
        self.step_count
    }

    /// Frames started so far.
    pub fn frame_count(&self) -> u64 {
        self.frame_count
    }

    /// Gravity, m/s².
    pub fn gravity(&self) -> Vector3<f64> {
        self.world.gravity()
    }

    /// Sets the clock (a loaded scene goes on from its saved time).
    pub(crate) fn set_clock(&mut self, time: f64, steps: u64) {
        self.time = time;
        self.step_count = steps;
    }

    /// The URDF robots and MJCF models loaded into this scene, in the order loaded (see
    /// [`RobotDescription`](crate::formats::urdf::RobotDescription)). Not kept by scene
    /// files or snapshots.
    pub fn robot_descriptions(&self) -> &[crate::formats::urdf::RobotDescription] {
        &self.robot_descriptions
    }

    /// The kind of its collision space.
    pub fn space_kind(&self) -> SpaceKind {
        self.space_kind
    }

    /// Number of whole steps in `duration` seconds (rounded to the nearest).
    pub fn steps_in(&self, duration: f64) -> Result<u64> {
        crate::validate::non_negative("duration", duration)?;
        Ok((duration / self.time_step.get()).round() as u64)
    }

    /// `error` from the world with the handles its message shows (a diverged body, two
    /// colliding geoms...) replaced by the names of their objects: `object "ball"`.
    pub(crate) fn name_handles(&self, error: Error) -> Error {
        let name = |text: String| {
            if !text.contains('#') {
                return text;
            }
            let mut text = text;
            for (_, o) in self.objects.iter() {
                let named = format!("object {:?}", o.name);
                let geoms = o.geom.iter().chain(&o.extra_geoms).map(|g| g.to_string());
                for shown in o.body.map(|b| b.to_string()).into_iter().chain(geoms) {
                    text = text.replace(&shown, &named);
                }
            }
            text
        };
        match error {
            Error::Diverged { body, time, detail } => Error::Diverged { body: name(body), time, detail },
            Error::OutOfRange { what, detail } => Error::OutOfRange { what, detail: name(detail) },
            Error::Invalid { what, problem } => Error::Invalid { what, problem: name(problem) },
            Error::OdeInternal { during, message } => Error::OdeInternal { during, message: name(message) },
            other => other,
        }
    }
}
