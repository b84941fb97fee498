//! A sensor made of a closure: whatever a program wants to record, as typed records.

use std::fmt;
use std::marker::PhantomData;

use super::{Record, SampleAt, Sensor};
use crate::error::Result;
use crate::handle::{JointId, ObjectId};
use crate::scene::Scene;

/// A sensor that records what its closure reads of the simulation: the way a program
/// declares the rows it records (a state, a set-point, the torques it put), with the
/// sensors' timing, CSV export and records. Its id, `SensorId<Probe<R>>`, names the
/// record type, so a program can keep it in a field.
///
/// ```
/// use ars_core::sensors::{Probe, Record};
/// use ars_core::{Mass, Scene, Simulation};
///
/// #[derive(Clone)]
/// struct Height {
///     y: f64,
///     vy: f64,
/// }
/// impl Record for Height {
///     fn columns() -> Vec<&'static str> {
///         vec!["y [m]", "vy [m/s]"]
///     }
///     fn values(&self) -> Vec<Option<f64>> {
///         vec![Some(self.y), Some(self.vy)]
///     }
/// }
///
/// let mut sim = Simulation::new()?;
/// let ball = sim.scene_mut().add_sphere(0.1, [0.0, 10.0, 0.0], Mass::Total(1.0))?;
/// let probe = sim.add_sensor(
///     Probe::new(move |sim: &Scene| {
///         let b = sim.body(ball)?;
///         Ok(Height { y: b.position().y, vy: b.linear_velocity().y })
///     })
///     .reads_objects([ball]),
/// )?;
/// sim.step_n(10)?;
/// let log = sim.records(probe)?;
/// assert_eq!(log.len(), 10);
/// assert!(log.last().unwrap().record.vy < 0.0);
/// # Ok::<(), ars_core::Error>(())
/// ```
pub struct Probe<R> {
    read: Box<ReadFn<R>>,
    at: SampleAt,
    objects: Vec<ObjectId>,
    joints: Vec<JointId>,
    _record: PhantomData<fn() -> R>,
}

/// What a probe calls to measure.
type ReadFn<R> = dyn FnMut(&Scene) -> Result<R> + Send;

impl<R: Record> Probe<R> {
    /// Records `read(sim)` at the end of every step.
    pub fn new(read: impl FnMut(&Scene) -> Result<R> + Send + 'static) -> Self {
        Probe {
            read: Box::new(read),
            at: SampleAt::EndOfStep,
            objects: Vec::new(),
            joints: Vec::new(),
            _record: PhantomData,
        }
    }

    /// Records `read(sim)` at the start of every step, after the pre-step hooks (see
    /// [`SampleAt::StartOfStep`]).
    pub fn at_step_start(read: impl FnMut(&Scene) -> Result<R> + Send + 'static) -> Self {
        Probe { at: SampleAt::StartOfStep, ..Self::new(read) }
    }

    /// The objects the closure reads: the probe is refused if one is not in the
    /// simulation, and stops when one is removed.
    #[must_use]
    pub fn reads_objects(mut self, objects: impl IntoIterator<Item = ObjectId>) -> Self {
        self.objects.extend(objects);
        self
    }

    /// The joints the closure reads (as [`reads_objects`](Self::reads_objects)).
    #[must_use]
    pub fn reads_joints(mut self, joints: impl IntoIterator<Item = JointId>) -> Self {
        self.joints.extend(joints);
        self
    }
}

impl<R> fmt::Debug for Probe<R> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Probe")
            .field("at", &self.at)
            .field("objects", &self.objects)
            .field("joints", &self.joints)
            .finish()
    }
}

impl<R: Record> Sensor for Probe<R> {
    type Record = R;

    fn measure(&mut self, sim: &Scene) -> Result<R> {
        (self.read)(sim)
    }

    fn objects(&self) -> Vec<ObjectId> {
        self.objects.clone()
    }

    fn joints(&self) -> Vec<JointId> {
        self.joints.clone()
    }

    fn sample_at(&self) -> SampleAt {
        self.at
    }
}
