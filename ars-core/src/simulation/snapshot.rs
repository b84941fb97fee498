//! Exact snapshots: [`Simulation::snapshot`] takes the whole state of a simulation at
//! any step, [`Simulation::restore`] puts it back, and every later step is the same to
//! the bit as the run that was never interrupted.
//!
//! ```
//! use ars_core::{Mass, Simulation};
//!
//! let mut sim = Simulation::builder().floor_plane(nalgebra::Vector3::y(), 0.0).build()?;
//! let ball = sim.scene_mut().add_sphere(0.1, [0.0, 1.0, 0.0], Mass::Total(1.0))?;
//! sim.step_n(500)?;
//! let state = sim.snapshot()?;
//! sim.step_n(1000)?;
//! let later = sim.scene().body(ball)?.position();
//! sim.restore(&state)?;
//! sim.step_n(1000)?;
//! assert_eq!(sim.scene().body(ball)?.position(), later);
//! // Into a simulation of its own (in this process or another: `to_bytes`).
//! let mut copy = Simulation::from_snapshot(&ars_core::Snapshot::from_bytes(&state.to_bytes())?)?;
//! copy.step_n(1000)?;
//! let copied_ball = copy.scene().object("sphere")?.id();
//! assert_eq!(copy.scene().body(copied_ball)?.position(), later);
//! # Ok::<(), ars_core::Error>(())
//! ```
//!
//! ## What a snapshot holds
//! - The scene as a [`SceneFile`] holds it (objects, joints, sensors ARS builds from a
//!   kind, parameters), which [`Simulation::from_snapshot`] builds from.
//! - The world's exact state (see `world::state`): every body's pose as ODE keeps it,
//!   velocities, accumulated forces and torques (the forces queued for the next step),
//!   mass and flags; every joint's anchors, axes and zero reference (each joint is made
//!   again where its bodies were when it was made) and its parameters; the geoms'
//!   switches and bits, and the order ODE's spaces test them in; the clock and
//!   QuickStep's random seed.
//! - Every joint's drive: viscous and dry friction, spring, actuator limits, mimic, and its
//!   controller with its state (a PID's integral and previous error, a DC motor's
//!   previous rate); the efforts booked so far in the step.
//! - Every sensor's schedule (when its next sample is due), whether it is detached, and
//!   its own state ([`Sensor::save_state`](crate::Sensor::save_state): a noise
//!   generator's).
//!
//! ## What it does not hold
//! - Code: hooks and closure sensors. [`restore`](Simulation::restore) keeps the
//!   simulation's hooks and sensors and puts back what ARS holds of them: hooks that
//!   implement [`Hooks::save_state`](crate::Hooks::save_state) get their state back;
//!   other hooks' own variables (a closure's captures, a Python hook's variables) are
//!   not in the snapshot and must be reset by their owner.
//! - Records: restoring clears every sensor's records (read them before).
//! - The contact points and ray hits of the last step (the next step finds them again).
//! - A joint controller of a type of your own that does not implement
//!   [`JointController::saved`](crate::JointController::saved): taking the snapshot is
//!   an [`Error::NotCapturable`].
//!
//! [`Simulation::from_snapshot`] builds the scene from its [`SceneFile`] and can
//! therefore rebuild what a scene file holds: the objects and joints (those made
//! through the world too), the sensors of every [`SensorKind`](crate::SensorKind), lidars
//! and depth cameras, noisy or not. A snapshot of a scene with other sensors (closures,
//! lasers, your own types), with robots whose links have several collision shapes, or
//! with bodies that are not objects, is restored into a simulation built by your own
//! code ([`Simulation::restore`]), which is what a reset does anyway.
//!
//! ## Bytes
//! [`Snapshot::to_bytes`]: `ARSSNAP\0`, the format version (u32, little-endian), the
//! payload's length (u64) and CRC-32 (u32), then the payload in CBOR. Doubles are kept
//! as their bits. [`Snapshot::from_bytes`] refuses another version
//! ([`Error::SnapshotVersion`]) and truncated or altered bytes
//! ([`Error::SnapshotCorrupt`]); [`Simulation::restore`] refuses a snapshot of another
//! scene ([`Error::SnapshotMismatch`]) before it changes anything.

use serde::{Deserialize, Serialize};

use super::Simulation;
use super::scene_state::{SceneState, decode, encode};
use crate::error::{Error, Result};
use crate::formats::scene_file::SceneFile;

/// The whole state of a simulation at one step (see the [module docs](self)).
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Snapshot {
    scene: SceneFile,
    state: SceneState,
}

impl Snapshot {
    /// Simulated time when it was taken, s.
    pub fn time(&self) -> f64 {
        self.scene.time
    }

    /// Steps taken when it was taken.
    pub fn step_count(&self) -> u64 {
        self.scene.step_count
    }

    /// The scene as a scene file holds it (without the exact state).
    pub fn scene(&self) -> &SceneFile {
        &self.scene
    }

    /// The snapshot as bytes (see the [module docs](self#bytes)).
    pub fn to_bytes(&self) -> Vec<u8> {
        encode(self)
    }

    /// A snapshot from bytes written by [`to_bytes`](Self::to_bytes).
    pub fn from_bytes(bytes: &[u8]) -> Result<Snapshot> {
        decode(bytes)
    }
}

impl Simulation {
    /// The whole state of the simulation now (see the [module docs](self)); any time,
    /// between two steps. [`Error::NotCapturable`] names what cannot be saved.
    pub fn snapshot(&self) -> Result<Snapshot> {
        Ok(Snapshot { scene: self.scene_structure(true)?, state: self.capture_state()? })
    }

    /// The exact state beyond the scene file.
    pub(crate) fn capture_state(&self) -> Result<SceneState> {
        Ok(SceneState {
            world: self.scene.world().capture_state(),
            joints: self.scene.save_joint_drives()?,
            sensors: self.sensors.save(),
            hooks: self.hooks.save()?,
            frame_count: self.scene.frame_count(),
            actuator_order: self.scene.actuated_joint_names(),
        })
    }

    /// Puts the simulation back in the state of `snapshot`: every later step is the
    /// same to the bit as after the snapshot was taken. The simulation must have the
    /// same objects, joints and sensors, made in the same order (the one the snapshot
    /// was taken of, or one built by the same code); otherwise
    /// [`Error::SnapshotMismatch`], and nothing changed. Hooks stay; records are
    /// cleared.
    pub fn restore(&mut self, snapshot: &Snapshot) -> Result<()> {
        self.check_objects_fit(&snapshot.scene)?;
        self.restore_state(&snapshot.state)?;
        self.restore_scene_settings(&snapshot.scene)
    }

    /// A new simulation in the state of `snapshot`, built from its scene (see the
    /// [module docs](self) for what can be rebuilt).
    pub fn from_snapshot(snapshot: &Snapshot) -> Result<Simulation> {
        let mut sim = Simulation::from_scene_file(&snapshot.scene)?;
        if !snapshot.scene.unsaved_sensors.is_empty() {
            return Err(Error::SnapshotMismatch {
                detail: format!(
                    "its sensors {:?} cannot be rebuilt from a snapshot: build the scene with your code and restore the snapshot into it (Simulation::restore)",
                    snapshot.scene.unsaved_sensors
                ),
            });
        }
        sim.restore(snapshot)?;
        Ok(sim)
    }

    /// Checks everything a state must fit, then puts it back.
    pub(crate) fn restore_state(&mut self, state: &SceneState) -> Result<()> {
        self.scene.world().check_usable()?;
        self.scene.world().check_state_fits(&state.world)?;
        self.scene.check_joint_drives_fit(&state.joints)?;
        self.sensors.check_fits(&state.sensors)?;
        self.hooks.check_fits(&state.hooks)?;
        self.scene.world_mut().restore_state(&state.world)?;
        self.scene.restore_joint_drives(&state.joints)?;
        self.scene.order_actuators(&state.actuator_order);
        self.sensors.restore(&state.sensors)?;
        self.hooks.restore(&state.hooks)?;
        self.scene.frame_count = state.frame_count;
        Ok(())
    }

    /// The objects of `scene` (names, shapes, bodies) are this simulation's.
    fn check_objects_fit(&self, scene: &SceneFile) -> Result<()> {
        let mut here: Vec<(String, &str, bool)> = self
            .scene
            .objects_in_creation_order()
            .map(|(_, d)| (d.name.clone(), d.shape.kind_name(), d.body.is_some()))
            .collect();
        let mut there: Vec<(String, &str, bool)> =
            scene.objects.iter().map(|o| (o.name.clone(), o.shape.kind_name(), o.body.is_some())).collect();
        here.sort();
        there.sort();
        if here != there {
            let names = |v: &[(String, &str, bool)]| v.iter().map(|(n, k, _)| format!("{n} ({k})")).collect::<Vec<_>>();
            return Err(Error::SnapshotMismatch {
                detail: format!("the snapshot has the objects {:?}, this simulation {:?}", names(&there), names(&here)),
            });
        }
        Ok(())
    }

    /// The settings a scene file holds beyond the world's state: clock, time step,
    /// steps per frame, the surfaces of pairs, colours and visuals.
    fn restore_scene_settings(&mut self, scene: &SceneFile) -> Result<()> {
        self.scene.set_time_step(scene.time_step)?;
        if scene.steps_per_frame == 0 {
            return Err(Error::SnapshotCorrupt { detail: "its scene has 0 steps per frame".into() });
        }
        self.scene.steps_per_frame = scene.steps_per_frame;
        self.scene.set_clock(scene.time, scene.step_count);
        for (a, b, _) in self.scene.contact_surfaces() {
            self.scene.clear_contact_surface(a, b)?;
        }
        for pair in &scene.pair_surfaces {
            let (a, b) = (self.scene.object(pair.a.as_str())?.id(), self.scene.object(pair.b.as_str())?.id());
            self.scene.set_contact_surface(a, b, pair.surface)?;
        }
        self.scene.clear_geom_contacts();
        for g in &scene.geom_contacts {
            let object = self.scene.object(g.object.as_str())?.id();
            self.scene.set_geom_contact(object, g.geom, g.contact)?;
        }
        for p in &scene.geom_pair_contacts {
            let (a, b) = (self.scene.object(p.a.0.as_str())?.id(), self.scene.object(p.b.0.as_str())?.id());
            self.scene.set_geom_pair_contact((a, p.a.1), (b, p.b.1), p.contact)?;
        }
        for o in &scene.objects {
            let id = self.scene.object(o.name.as_str())?.id();
            if let Some(c) = o.color {
                self.scene.set_color(id, c)?;
            }
            self.scene.set_visuals(id, o.visuals.clone())?;
        }
        Ok(())
    }
}
