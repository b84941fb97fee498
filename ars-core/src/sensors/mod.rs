//! Sensors: declared on a simulation, sampled automatically after every step (or at a
//! period), each sample stamped with the simulated time at the end of the step.
//!
//! ```
//! use ars_core::{Mass, Simulation, sensors::{Gps, Velometer}};
//!
//! let mut sim = Simulation::builder().floor_plane(nalgebra::Vector3::y(), 0.0).build()?;
//! let ball = sim.scene_mut().add_sphere(0.5, [1.0, 1.0, 1.0], Mass::Total(1.0))?;
//! let gps = sim.add_sensor(Gps::new(ball))?;
//! let speed = sim.add_sensor(Velometer::new(ball))?;
//! sim.run_for(0.1)?;
//! let log = sim.records(gps)?;
//! assert_eq!(log.len(), 250);
//! assert!((log.last().unwrap().time - 0.1).abs() < 1e-12);
//! assert!(sim.records(speed)?.last().unwrap().record.linear.y < 0.0);
//! let mut csv = Vec::new();
//! log.write_csv(&mut csv).unwrap();
//! assert!(String::from_utf8(csv).unwrap().starts_with("time [s],step,x [m],y [m],z [m]\n"));
//! # Ok::<(), ars_core::Error>(())
//! ```

mod body;
mod depth_camera;
mod energy;
mod joint;
mod kind;
mod laser;
mod lidar;
mod log;
mod magnetometer;
mod momentum;
mod mount;
mod noise;
mod probe;
mod touch;

use std::any::Any;
use std::marker::PhantomData;

pub use body::{
    Acceleration, Accelerometer, Attitude, ContactForceReading, ContactForces, ContactReading, ContactSensor, Gps, Imu,
    ImuReading, Inclination, Inclinometer, Orientation, Position, Velocimeter, Velocity, Velometer,
};
pub use depth_camera::{DepthCamera, DepthImage};
pub use energy::{Energy, Kinetic, KineticEnergy, Potential, PotentialEnergy, SystemTotalEnergy, TotalEnergy};
pub use joint::{
    Effort, HingeReading, HingeSensor, JointForce, JointPositions, JointPower, JointReaction, JointTorque,
    JointVelocities, Positions, Power, Rates, Reaction,
};
pub use kind::{SensorKind, SensorTarget};
pub use laser::{Laser, LaserReading};
pub use lidar::{Lidar, Scan};
pub use log::{CsvColumns, Record, Sample, SensorLog, write_csv_table};
pub use magnetometer::{MagneticField, Magnetometer};
pub use momentum::{Momentum, MomentumReading};
pub use mount::Mount;
pub use noise::{Noisy, Perturb};
pub use probe::Probe;
pub use touch::{Touch, TouchReading, TouchZone};

use nalgebra::Point3;

use crate::error::{Error, Result};
use crate::handle::{Arena, JointId, ObjectId, RawHandle, WorldId};
use crate::panic::contain;
use crate::scene::Scene;

/// A sensor: measures something of a simulation after every step it samples.
pub trait Sensor: Send + 'static {
    /// What one measurement holds.
    type Record: Record;

    /// Called once when the sensor is added (a laser creates its ray here).
    fn attach(&mut self, scene: &mut Scene) -> Result<()> {
        let _ = scene;
        Ok(())
    }

    /// Called before every step, after the pre-step hooks, on the state before the
    /// step (an accelerometer remembers the velocity here).
    fn before_step(&mut self, sim: &Scene) -> Result<()> {
        let _ = sim;
        Ok(())
    }

    /// One measurement, after a step.
    fn measure(&mut self, sim: &Scene) -> Result<Self::Record>;

    /// Objects the sensor reads; it stops sampling when one is removed.
    fn objects(&self) -> Vec<ObjectId> {
        Vec::new()
    }

    /// Joints the sensor reads; it stops sampling when one is removed.
    fn joints(&self) -> Vec<JointId> {
        Vec::new()
    }

    /// When the sensor samples (default: at the end of each step).
    fn sample_at(&self) -> SampleAt {
        SampleAt::EndOfStep
    }

    /// Line segments (world frame) that show a record in a viewer: a lidar's beams to
    /// their hits, say. None by default.
    fn lines(record: &Self::Record) -> Vec<(Point3<f64>, Point3<f64>)> {
        let _ = record;
        Vec::new()
    }

    /// Whether [`measure`](Sensor::measure) must run every step even when the sensor
    /// samples at a slower rate (a sensor with state). Costly stateless sensors (a
    /// lidar, a camera) say `false` and are measured only when a sample is due.
    fn measures_every_step(&self) -> bool {
        true
    }

    /// What the sensor carries from one step to the next that its configuration does
    /// not give (a noise generator's state), for [snapshots](crate::Snapshot): nothing
    /// by default. A sensor of your own with such state overrides this and
    /// [`restore_state`](Sensor::restore_state); a closure sensor's captured variables
    /// are not seen by ARS and are not in a snapshot.
    fn save_state(&self) -> Vec<u64> {
        Vec::new()
    }

    /// What a scene file keeps of the sensor beyond its kind, what it reads and its
    /// period, to build it again: a lidar's or camera's settings. `None` (the default)
    /// for a sensor made from its kind alone.
    fn settings(&self) -> Option<SensorSettings> {
        None
    }

    /// The noise the sensor adds, if it is a noise wrapper ([`Noisy`]): the standard
    /// deviation and its generator's state. `None` by default.
    fn noise(&self) -> Option<(f64, u64)> {
        None
    }

    /// Puts back what [`save_state`](Sensor::save_state) returned.
    fn restore_state(&mut self, state: &[u64]) -> Result<()> {
        if state.is_empty() {
            Ok(())
        } else {
            Err(Error::SnapshotCorrupt {
                detail: format!("a stateless sensor was given {} numbers of state", state.len()),
            })
        }
    }
}

/// The settings of a sensor that its kind and what it reads do not give, as scene
/// files keep them (see [`Sensor::settings`]). The pose is relative to the object the
/// sensor is mounted on when it reads one, otherwise in the world.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[non_exhaustive]
pub enum SensorSettings {
    /// A [`Lidar`].
    Lidar {
        /// Beams per plane.
        beams: u32,
        /// Field of view, rad.
        fov: f64,
        /// Nearest range seen, m.
        min_range: f64,
        /// Farthest range seen, m.
        max_range: f64,
        /// The planes' elevations, rad.
        elevations: Vec<f64>,
        /// Where it is.
        pose: nalgebra::Isometry3<f64>,
    },
    /// A [`DepthCamera`].
    DepthCamera {
        /// Image width, pixels.
        width: u32,
        /// Image height, pixels.
        height: u32,
        /// Vertical field of view, rad.
        fov_y: f64,
        /// Nearest depth seen, m.
        near: f64,
        /// Farthest depth seen, m.
        far: f64,
        /// Where it is.
        pose: nalgebra::Isometry3<f64>,
    },
    /// A sensor that reads a point or a frame fixed on its object at an offset from the
    /// object's origin: a [`Gps`], [`Velometer`] or [`Accelerometer`] (the offset's
    /// translation), an [`Orientation`] (its rotation) or an [`Imu`] (both).
    Offset {
        /// The offset, in the object's frame.
        pose: nalgebra::Isometry3<f64>,
    },
    /// A [`Touch`] sensor that feels only a zone of its object.
    Touch {
        /// The zone.
        zone: TouchZone,
        /// Where the zone is, in the object's frame.
        pose: nalgebra::Isometry3<f64>,
    },
    /// A [`Magnetometer`]: the world's field and the sensor's frame on its object.
    Magnetometer {
        /// The world's field.
        field: nalgebra::Vector3<f64>,
        /// The sensor's frame, in the object's frame.
        pose: nalgebra::Isometry3<f64>,
    },
}

/// A sensor's place in its schedule and its own state, as a snapshot keeps them.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub(crate) struct SensorState {
    /// Its type's name (`"Gps"`, `"Noisy<Gps>"`).
    pub(crate) kind: String,
    /// When its next periodic sample is due, s.
    next_sample: f64,
    detached: bool,
    /// What [`Sensor::save_state`] returned.
    own: Vec<u64>,
}

/// When in the step a sensor samples.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum SampleAt {
    /// After the step, stamped with the time at its end and its number (1 for the first).
    #[default]
    EndOfStep,
    /// At the start of the step, after the pre-step hooks, the joint controllers and
    /// friction (the state the hooks read and the efforts they put), stamped with the
    /// time at the start and the number of steps taken before (0 for the first). This
    /// is where the original's programs printed their lines.
    StartOfStep,
}

/// A typed handle to a sensor of a simulation (stale once the sensor is removed).
pub struct SensorId<S> {
    handle: RawHandle,
    _sensor: PhantomData<fn() -> S>,
}

impl<S> Clone for SensorId<S> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<S> Copy for SensorId<S> {}
impl<S> std::fmt::Debug for SensorId<S> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "sensor#{}v{}@{:?}", self.handle.index, self.handle.generation, self.handle.world)
    }
}

/// A handle to a sensor of any type: what [`Simulation::add_sensor_of_kind`]
/// returns, and what any [`SensorId`] converts to. Its records are read through
/// [`Simulation::sensor_table`].
///
/// [`Simulation::add_sensor_of_kind`]: crate::Simulation::add_sensor_of_kind
/// [`Simulation::sensor_table`]: crate::Simulation::sensor_table
#[derive(Clone, Copy, PartialEq, Eq)]
pub struct AnySensorId {
    handle: RawHandle,
}

impl<S> From<SensorId<S>> for AnySensorId {
    fn from(id: SensorId<S>) -> Self {
        AnySensorId { handle: id.handle }
    }
}

impl std::fmt::Debug for AnySensorId {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "sensor#{}v{}@{:?}", self.handle.index, self.handle.generation, self.handle.world)
    }
}

struct Slot<S: Sensor> {
    sensor: S,
    at: SampleAt,
    period: Option<f64>,
    next_sample: f64,
    detached: bool,
    log: SensorLog<S::Record>,
}

/// A type's name without module paths: `Noisy<Gps>` for
/// `ars_core::sensors::noise::Noisy<ars_core::sensors::body::Gps>`.
fn short_type_name(full: &str) -> String {
    let mut out = String::new();
    let mut segment = String::new();
    let mut chars = full.chars().peekable();
    while let Some(c) = chars.next() {
        if c == ':' && chars.peek() == Some(&':') {
            chars.next();
            segment.clear();
        } else if c.is_alphanumeric() || c == '_' {
            segment.push(c);
        } else {
            out.push_str(&segment);
            segment.clear();
            out.push(c);
        }
    }
    out.push_str(&segment);
    out
}

/// What a sensor is, for a scene file: its type's name, what it reads, its period.
pub(crate) struct SensorDescription {
    pub(crate) kind: String,
    pub(crate) objects: Vec<ObjectId>,
    pub(crate) joints: Vec<JointId>,
    pub(crate) period: Option<f64>,
    pub(crate) settings: Option<SensorSettings>,
    pub(crate) noise: Option<(f64, u64)>,
}

trait ErasedSlot: Send {
    fn describe(&self) -> SensorDescription;
    fn lines(&self) -> Vec<(Point3<f64>, Point3<f64>)>;
    fn table(&self) -> (String, &dyn CsvColumns);
    fn before_step(&mut self, sim: &Scene) -> Result<()>;
    fn after_step(&mut self, sim: &Scene) -> Result<()>;
    /// Whether `after_step` does anything (it samples a sensor that is not detached
    /// and samples at the end of the step); otherwise it is `Ok(())` without running
    /// any sensor code.
    fn acts_after_step(&self) -> bool;
    fn forget_object(&mut self, id: ObjectId);
    fn forget_joint(&mut self, id: JointId);
    /// Whether it samples at the end of the step (detached or not).
    fn at_end_of_step(&self) -> bool;
    fn is_detached(&self) -> bool;
    fn clear_log(&mut self);
    fn save(&self) -> SensorState;
    /// Puts back a state of a sensor of the same kind (checked by the caller); the
    /// records are cleared.
    fn restore(&mut self, state: &SensorState) -> Result<()>;
    fn as_any(&self) -> &dyn Any;
    fn as_any_mut(&mut self) -> &mut dyn Any;
    fn into_any(self: Box<Self>) -> Box<dyn Any>;
}

impl<S: Sensor> Slot<S> {
    /// Measures, and keeps the record if a sample is due.
    fn sample(&mut self, sim: &Scene, step: u64) -> Result<()> {
        let time = sim.time();
        if let Some(period) = self.period {
            // Half a step of slack absorbs the drift of the accumulated time.
            if time + 0.5 * sim.time_step() < self.next_sample {
                // Still measure, so that stateful sensors see every step.
                if self.sensor.measures_every_step() {
                    self.sensor.measure(sim)?;
                }
                return Ok(());
            }
            self.next_sample += period;
        }
        let record = self.sensor.measure(sim)?;
        self.log.samples.push(Sample { time, step, record });
        Ok(())
    }
}

impl<S: Sensor> ErasedSlot for Slot<S> {
    fn describe(&self) -> SensorDescription {
        SensorDescription {
            kind: short_type_name(std::any::type_name::<S>()),
            objects: self.sensor.objects(),
            joints: self.sensor.joints(),
            period: self.period,
            settings: self.sensor.settings(),
            noise: self.sensor.noise(),
        }
    }
    fn table(&self) -> (String, &dyn CsvColumns) {
        (short_type_name(std::any::type_name::<S>()), &self.log)
    }
    fn lines(&self) -> Vec<(Point3<f64>, Point3<f64>)> {
        match (self.detached, self.log.samples.last()) {
            (false, Some(sample)) => S::lines(&sample.record),
            _ => Vec::new(),
        }
    }
    fn before_step(&mut self, sim: &Scene) -> Result<()> {
        match (self.detached, self.at) {
            (true, _) => Ok(()),
            (false, SampleAt::EndOfStep) => self.sensor.before_step(sim),
            (false, SampleAt::StartOfStep) => {
                self.sensor.before_step(sim)?;
                self.sample(sim, sim.step_count())
            }
        }
    }
    fn after_step(&mut self, sim: &Scene) -> Result<()> {
        match (self.detached, self.at) {
            (false, SampleAt::EndOfStep) => self.sample(sim, sim.step_count()),
            _ => Ok(()),
        }
    }
    fn acts_after_step(&self) -> bool {
        !self.detached && matches!(self.at, SampleAt::EndOfStep)
    }
    fn forget_object(&mut self, id: ObjectId) {
        if self.sensor.objects().contains(&id) {
            self.detached = true;
        }
    }
    fn forget_joint(&mut self, id: JointId) {
        if self.sensor.joints().contains(&id) {
            self.detached = true;
        }
    }
    fn at_end_of_step(&self) -> bool {
        matches!(self.at, SampleAt::EndOfStep)
    }
    fn is_detached(&self) -> bool {
        self.detached
    }
    fn clear_log(&mut self) {
        self.log.samples.clear();
    }
    fn save(&self) -> SensorState {
        SensorState {
            kind: short_type_name(std::any::type_name::<S>()),
            next_sample: self.next_sample,
            detached: self.detached,
            own: self.sensor.save_state(),
        }
    }
    fn restore(&mut self, state: &SensorState) -> Result<()> {
        self.sensor.restore_state(&state.own)?;
        self.next_sample = state.next_sample;
        self.detached = state.detached;
        self.log.samples.clear();
        Ok(())
    }
    fn as_any(&self) -> &dyn Any {
        self
    }
    fn as_any_mut(&mut self) -> &mut dyn Any {
        self
    }
    fn into_any(self: Box<Self>) -> Box<dyn Any> {
        self
    }
}

/// The sensors of a simulation.
pub(crate) struct SensorSet {
    slots: Arena<Box<dyn ErasedSlot>>,
    /// How many of the sensors sample at the end of the step (detached or not): when
    /// none does, there is nothing to do after a step.
    end_of_step: usize,
}

impl SensorSet {
    pub(crate) fn new(world: WorldId) -> Self {
        SensorSet { slots: Arena::new(world), end_of_step: 0 }
    }
    /// Every sensor notes the state before the step; a failing or panicking sensor
    /// does not keep the others from it. The first error is returned.
    #[inline]
    pub(crate) fn before_step(&mut self, scene: &Scene) -> Result<()> {
        if self.slots.len() == 0 {
            return Ok(());
        }
        self.each(|_| true, |s| s.before_step(scene))
    }
    /// Whether any sensor samples at the end of a step.
    #[inline]
    pub(crate) fn sample_after_step(&self) -> bool {
        self.end_of_step != 0
    }
    /// Every sensor samples; as [`SensorSet::before_step`].
    #[inline]
    pub(crate) fn after_step(&mut self, scene: &Scene) -> Result<()> {
        if self.end_of_step == 0 {
            return Ok(());
        }
        // A sensor sampled at the start of the step has nothing to do after it: skip
        // it without the panic containment around its (empty) call.
        self.each(|s| s.acts_after_step(), |s| s.after_step(scene))
    }
    #[inline(never)]
    fn each(
        &mut self,
        acts: impl Fn(&dyn ErasedSlot) -> bool,
        mut f: impl FnMut(&mut dyn ErasedSlot) -> Result<()>,
    ) -> Result<()> {
        // The first error only: a sensor that succeeds leaves nothing to keep or drop.
        let mut first = None;
        for (h, slot) in self.slots.iter_mut() {
            if !acts(&**slot) {
                continue;
            }
            let result = contain(|| format!("sensor#{}v{}", h.index, h.generation), || f(&mut **slot));
            if let Err(e) = result
                && first.is_none()
            {
                first = Some(e);
            }
        }
        first.map_or(Ok(()), Err)
    }
    pub(crate) fn forget_object(&mut self, id: ObjectId) {
        self.slots.values_mut().for_each(|s| s.forget_object(id));
    }
    pub(crate) fn forget_joint(&mut self, id: JointId) {
        self.slots.values_mut().for_each(|s| s.forget_joint(id));
    }
}

impl SensorSet {
    /// The lines of every sensor's latest record.
    /// Every sensor's log as CSV columns, with the sensor's type name, in the order
    /// the sensors were added.
    pub(crate) fn descriptions(&self) -> Vec<SensorDescription> {
        self.slots.values().map(|s| s.describe()).collect()
    }

    /// One sensor's log, whatever its type, with the type's name.
    pub(crate) fn table(&self, id: AnySensorId) -> Result<(String, &dyn CsvColumns)> {
        Ok(self.slots.get(id.handle, "sensor")?.table())
    }

    /// Removes a sensor whatever its type (its records go with it).
    pub(crate) fn remove_any(&mut self, id: AnySensorId) -> Result<()> {
        let slot = self.slots.remove(id.handle, "sensor")?;
        if slot.at_end_of_step() {
            self.end_of_step -= 1;
        }
        Ok(())
    }

    /// Forgets a sensor's records, whatever its type.
    pub(crate) fn clear_any(&mut self, id: AnySensorId) -> Result<()> {
        self.slots.get_mut(id.handle, "sensor")?.clear_log();
        Ok(())
    }

    /// Whether a sensor, whatever its type, stopped sampling (see
    /// [`Simulation::is_sensor_detached`](crate::Simulation::is_sensor_detached)).
    pub(crate) fn is_detached_any(&self, id: AnySensorId) -> Result<bool> {
        Ok(self.slots.get(id.handle, "sensor")?.is_detached())
    }

    pub(crate) fn tables(&self) -> Vec<(String, &dyn CsvColumns)> {
        self.slots.values().map(|s| s.table()).collect()
    }

    pub(crate) fn lines(&self) -> Vec<(Point3<f64>, Point3<f64>)> {
        self.slots.values().flat_map(|s| s.lines()).collect()
    }

    pub(crate) fn len(&self) -> usize {
        self.slots.len()
    }

    /// Every sensor's schedule and state, in the order added.
    pub(crate) fn save(&self) -> Vec<SensorState> {
        self.slots.values().map(|s| s.save()).collect()
    }

    /// Checks that `states` are of sensors of the same kinds, in the same order.
    pub(crate) fn check_fits(&self, states: &[SensorState]) -> Result<()> {
        let here: Vec<String> = self.slots.values().map(|s| s.save().kind).collect();
        let there: Vec<&str> = states.iter().map(|s| s.kind.as_str()).collect();
        if here != there {
            return Err(Error::SnapshotMismatch {
                detail: format!("the snapshot has the sensors {there:?}, this simulation {here:?}"),
            });
        }
        Ok(())
    }

    /// Puts back every sensor's schedule and state (checked with `check_fits`); the
    /// records are cleared.
    pub(crate) fn restore(&mut self, states: &[SensorState]) -> Result<()> {
        for (slot, state) in self.slots.values_mut().zip(states) {
            slot.restore(state)?;
        }
        Ok(())
    }

    /// Refuses a sensor that reads an object or joint that is not (or no longer) in
    /// the scene, then attaches it.
    pub(crate) fn insert<S: Sensor>(
        &mut self,
        scene: &mut Scene,
        mut sensor: S,
        period: Option<f64>,
    ) -> Result<SensorId<S>> {
        for object in sensor.objects() {
            scene.object(object)?;
        }
        for joint in sensor.joints() {
            scene.joint(joint)?;
        }
        sensor.attach(scene)?;
        let at = sensor.sample_at();
        // The first sample: the first step ending a period from now, or the first step
        // starting now.
        let next_sample = scene.time() + if at == SampleAt::EndOfStep { period.unwrap_or(0.0) } else { 0.0 };
        let slot = Slot { sensor, at, period, next_sample, detached: false, log: SensorLog { samples: Vec::new() } };
        let handle = self.slots.insert(Box::new(slot));
        if at == SampleAt::EndOfStep {
            self.end_of_step += 1;
        }
        Ok(SensorId { handle, _sensor: PhantomData })
    }

    pub(crate) fn remove<S: Sensor>(&mut self, id: SensorId<S>) -> Result<SensorLog<S::Record>> {
        self.slot(id)?;
        let slot = self.slots.remove(id.handle, "sensor")?;
        match slot.into_any().downcast::<Slot<S>>() {
            Ok(slot) => {
                if slot.at == SampleAt::EndOfStep {
                    self.end_of_step -= 1;
                }
                Ok(slot.log)
            }
            Err(_) => unreachable!("the slot's type was checked above"),
        }
    }

    fn slot<S: Sensor>(&self, id: SensorId<S>) -> Result<&Slot<S>> {
        self.slots
            .get(id.handle, "sensor")?
            .as_any()
            .downcast_ref::<Slot<S>>()
            .ok_or(Error::StaleHandle { kind: "sensor" })
    }

    fn slot_mut<S: Sensor>(&mut self, id: SensorId<S>) -> Result<&mut Slot<S>> {
        self.slots
            .get_mut(id.handle, "sensor")?
            .as_any_mut()
            .downcast_mut::<Slot<S>>()
            .ok_or(Error::StaleHandle { kind: "sensor" })
    }

    pub(crate) fn log<S: Sensor>(&self, id: SensorId<S>) -> Result<&SensorLog<S::Record>> {
        Ok(&self.slot(id)?.log)
    }

    pub(crate) fn period<S: Sensor>(&self, id: SensorId<S>) -> Result<Option<f64>> {
        Ok(self.slot(id)?.period)
    }

    pub(crate) fn clear<S: Sensor>(&mut self, id: SensorId<S>) -> Result<()> {
        self.slot_mut(id)?.log.samples.clear();
        Ok(())
    }

    pub(crate) fn sensor<S: Sensor>(&self, id: SensorId<S>) -> Result<&S> {
        Ok(&self.slot(id)?.sensor)
    }

    /// Every sensor of type `S`, in the order added.
    pub(crate) fn of_type<S: Sensor>(&self) -> impl Iterator<Item = &S> + '_ {
        self.slots.values().filter_map(|slot| slot.as_any().downcast_ref::<Slot<S>>()).map(|slot| &slot.sensor)
    }

    /// The id of every sensor of type `S`, in the order of their slots.
    pub(crate) fn ids_of<S: Sensor>(&self) -> Vec<SensorId<S>> {
        self.slots
            .iter()
            .filter(|(_, slot)| slot.as_any().downcast_ref::<Slot<S>>().is_some())
            .map(|(handle, _)| SensorId { handle, _sensor: PhantomData })
            .collect()
    }

    pub(crate) fn is_detached<S: Sensor>(&self, id: SensorId<S>) -> Result<bool> {
        Ok(self.slot(id)?.detached)
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn type_names_lose_their_module_paths() {
        assert_eq!(super::short_type_name("ars_core::sensors::body::Gps"), "Gps");
        assert_eq!(
            super::short_type_name("ars_core::sensors::noise::Noisy<ars_core::sensors::body::Gps>"),
            "Noisy<Gps>"
        );
        assert_eq!(super::short_type_name("a::Probe<b::c::Row, u32>"), "Probe<Row, u32>");
    }
}
