//! Sensors on one body: position, velocity, acceleration, orientation, inclination,
//! IMU, contacts. Those that read a point or a frame fixed on the body (a GPS, a
//! velometer, an accelerometer, an IMU, an orientation sensor) read its origin (the
//! centre of mass, where ODE keeps the body's frame) unless given an offset from it.

use nalgebra::{Isometry3, Point3, UnitQuaternion, Vector3};

use super::{Record, Sensor, SensorSettings};
use crate::BodyRef;
use crate::ContactPoint;
use crate::error::Result;
use crate::handle::ObjectId;
use crate::scene::ObjectView;
use crate::scene::Scene;

fn xyz(v: &Vector3<f64>) -> [Option<f64>; 3] {
    [Some(v.x), Some(v.y), Some(v.z)]
}

/// The world position of the point at `offset` (body frame) from a body's origin:
/// `p + R·offset`; the origin itself, as read, without an offset (the sensors' default,
/// on every sample).
fn point_position(body: &BodyRef<'_>, offset: &Vector3<f64>) -> Point3<f64> {
    if *offset == Vector3::zeros() { body.position() } else { body.position() + body.rotation() * offset }
}

/// The world velocity of the point at `offset` (body frame) from a body's origin:
/// `v + ω × R·offset`; the body's own, as read, without an offset.
fn point_velocity(body: &BodyRef<'_>, offset: &Vector3<f64>) -> Vector3<f64> {
    if *offset == Vector3::zeros() {
        body.linear_velocity()
    } else {
        body.linear_velocity() + body.angular_velocity().cross(&(body.rotation() * offset))
    }
}

/// What a scene file keeps of a sensor's offset: nothing when it has none.
fn offset_settings(pose: Isometry3<f64>) -> Option<SensorSettings> {
    (pose != Isometry3::identity()).then_some(SensorSettings::Offset { pose })
}

/// [`offset_settings`] of a point's offset.
fn point_settings(offset: &Vector3<f64>) -> Option<SensorSettings> {
    offset_settings(Isometry3::translation(offset.x, offset.y, offset.z))
}

/// Position of a point fixed on a body, world frame (the original's GPS): its centre
/// of mass, or the point at [`at`](Self::at) from it.
#[derive(Clone, Debug)]
pub struct Gps {
    object: ObjectId,
    offset: Vector3<f64>,
}

impl Gps {
    /// A GPS on `object`, at its centre of mass.
    pub fn new(object: ObjectId) -> Self {
        Gps { object, offset: Vector3::zeros() }
    }

    /// At `offset` from the object's origin (its centre of mass), in the object's frame.
    #[must_use]
    pub fn at(mut self, offset: Vector3<f64>) -> Self {
        self.offset = offset;
        self
    }
}

/// A [`Gps`] measurement.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Position {
    /// Position, m.
    pub position: Point3<f64>,
}

impl Record for Position {
    fn columns() -> Vec<&'static str> {
        vec!["x [m]", "y [m]", "z [m]"]
    }
    fn values(&self) -> Vec<Option<f64>> {
        xyz(&self.position.coords).to_vec()
    }
}

impl Sensor for Gps {
    type Record = Position;
    fn measure(&mut self, sim: &Scene) -> Result<Position> {
        let b = sim.body(self.object)?;
        Ok(Position { position: point_position(&b, &self.offset) })
    }
    fn objects(&self) -> Vec<ObjectId> {
        vec![self.object]
    }
    fn settings(&self) -> Option<SensorSettings> {
        point_settings(&self.offset)
    }
}

/// Linear velocity of a point fixed on a body (its centre of mass, or the point at
/// [`at`](Self::at) from it) and the body's angular velocity, world frame.
#[derive(Clone, Debug)]
pub struct Velometer {
    object: ObjectId,
    offset: Vector3<f64>,
}

impl Velometer {
    /// A velometer on `object`, at its centre of mass.
    pub fn new(object: ObjectId) -> Self {
        Velometer { object, offset: Vector3::zeros() }
    }

    /// At `offset` from the object's origin (its centre of mass), in the object's
    /// frame: it reads that point's velocity, `v + ω × R·offset`.
    #[must_use]
    pub fn at(mut self, offset: Vector3<f64>) -> Self {
        self.offset = offset;
        self
    }
}

/// A [`Velometer`] measurement (world frame), or a [`Velocimeter`]'s (its frame).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Velocity {
    /// Linear velocity of the point read (the centre of mass by default), m/s.
    pub linear: Vector3<f64>,
    /// Angular velocity, rad/s.
    pub angular: Vector3<f64>,
}

impl Record for Velocity {
    fn columns() -> Vec<&'static str> {
        vec!["vx [m/s]", "vy [m/s]", "vz [m/s]", "wx [rad/s]", "wy [rad/s]", "wz [rad/s]"]
    }
    fn values(&self) -> Vec<Option<f64>> {
        [xyz(&self.linear), xyz(&self.angular)].concat()
    }
}

impl Sensor for Velometer {
    type Record = Velocity;
    fn measure(&mut self, sim: &Scene) -> Result<Velocity> {
        let b = sim.body(self.object)?;
        Ok(Velocity { linear: point_velocity(&b, &self.offset), angular: b.angular_velocity() })
    }
    fn objects(&self) -> Vec<ObjectId> {
        vec![self.object]
    }
    fn settings(&self) -> Option<SensorSettings> {
        point_settings(&self.offset)
    }
}

/// Linear velocity of a point fixed on a body and the body's angular velocity, in a
/// frame fixed on the body (MuJoCo's `velocimeter`, with its `gyro`): `Rᵀ v` and
/// `Rᵀ ω`, `R` the frame's rotation in the world, `v` the point's velocity. At the
/// body's centre of mass and turned as the body unless mounted at an offset
/// ([`at`](Self::at)). A [`Velometer`] reads the same in the world frame.
#[derive(Clone, Debug)]
pub struct Velocimeter {
    object: ObjectId,
    offset: Isometry3<f64>,
}

impl Velocimeter {
    /// A velocimeter on `object`, at its centre of mass, turned as the object.
    pub fn new(object: ObjectId) -> Self {
        Velocimeter { object, offset: Isometry3::identity() }
    }

    /// Mounted at `offset` from the object's origin (its centre of mass), in the
    /// object's frame: it reads that point's velocity, in that frame.
    #[must_use]
    pub fn at(mut self, offset: Isometry3<f64>) -> Self {
        self.offset = offset;
        self
    }
}

impl Sensor for Velocimeter {
    type Record = Velocity;
    fn measure(&mut self, sim: &Scene) -> Result<Velocity> {
        let b = sim.body(self.object)?;
        let v = point_velocity(&b, &self.offset.translation.vector);
        // Into the body's frame, then the sensor's.
        let (to_body, to_frame) = (b.rotation().inverse(), self.offset.rotation.inverse());
        Ok(Velocity { linear: to_frame * (to_body * v), angular: to_frame * (to_body * b.angular_velocity()) })
    }
    fn objects(&self) -> Vec<ObjectId> {
        vec![self.object]
    }
    fn settings(&self) -> Option<SensorSettings> {
        offset_settings(self.offset)
    }
}

/// Linear acceleration of a point fixed on a body (its centre of mass, or the point at
/// [`at`](Self::at) from it) and the body's angular acceleration, world frame: the
/// change of velocity over the step divided by the time step, `(v_end − v_start) / dt`.
/// Off the centre of mass the point's velocity is `v + ω × R·offset`, so the reading
/// converges to the point's acceleration with its centripetal and tangential terms as
/// the step shrinks.
///
/// The sensor keeps its own state (the velocity at the start of each step, noted just
/// before collision), so several accelerometers on one body do not interfere, and its
/// first sample is well defined: the change over the first step. At a bounce it reads
/// `(1 + e) · v_impact / dt`, as in the thesis.
#[derive(Clone, Debug)]
pub struct Accelerometer {
    object: ObjectId,
    offset: Vector3<f64>,
    start: Option<(Vector3<f64>, Vector3<f64>)>,
}

impl Accelerometer {
    /// An accelerometer on `object`, at its centre of mass.
    pub fn new(object: ObjectId) -> Self {
        Accelerometer { object, offset: Vector3::zeros(), start: None }
    }

    /// At `offset` from the object's origin (its centre of mass), in the object's frame.
    #[must_use]
    pub fn at(mut self, offset: Vector3<f64>) -> Self {
        self.offset = offset;
        self
    }
}

/// An [`Accelerometer`] measurement.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Acceleration {
    /// Linear acceleration, m/s².
    pub linear: Vector3<f64>,
    /// Angular acceleration, rad/s².
    pub angular: Vector3<f64>,
}

impl Record for Acceleration {
    fn columns() -> Vec<&'static str> {
        vec!["ax [m/s^2]", "ay [m/s^2]", "az [m/s^2]", "alpha_x [rad/s^2]", "alpha_y [rad/s^2]", "alpha_z [rad/s^2]"]
    }
    fn values(&self) -> Vec<Option<f64>> {
        [xyz(&self.linear), xyz(&self.angular)].concat()
    }
}

impl Sensor for Accelerometer {
    type Record = Acceleration;
    fn before_step(&mut self, sim: &Scene) -> Result<()> {
        let b = sim.body(self.object)?;
        self.start = Some((point_velocity(&b, &self.offset), b.angular_velocity()));
        Ok(())
    }
    fn measure(&mut self, sim: &Scene) -> Result<Acceleration> {
        let b = sim.body(self.object)?;
        let (v0, w0) = self.start.expect("before_step runs before every measurement");
        let dt = sim.time_step();
        Ok(Acceleration {
            linear: (point_velocity(&b, &self.offset) - v0) / dt,
            angular: (b.angular_velocity() - w0) / dt,
        })
    }
    fn objects(&self) -> Vec<ObjectId> {
        vec![self.object]
    }
    fn settings(&self) -> Option<SensorSettings> {
        point_settings(&self.offset)
    }
}

/// The orientation of a frame fixed on a body, world frame: the body's own (turned as
/// its frame: for a body from an MJCF file, the MJCF body's frame), or that of the frame
/// at [`at`](Self::at) from it.
#[derive(Clone, Debug)]
pub struct Orientation {
    object: ObjectId,
    offset: UnitQuaternion<f64>,
}

impl Orientation {
    /// An orientation sensor on `object`, reading the object's own frame.
    pub fn new(object: ObjectId) -> Self {
        Orientation { object, offset: UnitQuaternion::identity() }
    }

    /// Reads the frame turned by `offset` from the object's (in the object's frame).
    #[must_use]
    pub fn at(mut self, offset: UnitQuaternion<f64>) -> Self {
        self.offset = offset;
        self
    }
}

/// An [`Orientation`] measurement.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Attitude {
    /// The frame's rotation from the world's, as a unit quaternion with `w ≥ 0` (of `q`
    /// and `−q`, the same rotation, the one with the non-negative scalar part).
    pub rotation: UnitQuaternion<f64>,
}

impl Record for Attitude {
    fn columns() -> Vec<&'static str> {
        vec!["qw [1]", "qx [1]", "qy [1]", "qz [1]"]
    }
    fn values(&self) -> Vec<Option<f64>> {
        let q = self.rotation.quaternion();
        vec![Some(q.w), Some(q.i), Some(q.j), Some(q.k)]
    }
}

impl Sensor for Orientation {
    type Record = Attitude;
    fn measure(&mut self, sim: &Scene) -> Result<Attitude> {
        let b = sim.body(self.object)?;
        let q = b.quaternion() * self.offset;
        let q = if q.w < 0.0 { UnitQuaternion::new_unchecked(-q.into_inner()) } else { q };
        Ok(Attitude { rotation: q })
    }
    fn objects(&self) -> Vec<ObjectId> {
        vec![self.object]
    }
    fn settings(&self) -> Option<SensorSettings> {
        offset_settings(Isometry3::from_parts(nalgebra::Translation3::identity(), self.offset))
    }
}

/// Inclination of a body with Y up: writing its rotation as `Rx(roll) · Ry(yaw) ·
/// Rz(pitch)` (the original's XYZ roll-pitch-yaw with pitch and yaw swapped because Y
/// is up), `roll` turns about X and `pitch` about Z.
#[derive(Clone, Debug)]
pub struct Inclinometer {
    object: ObjectId,
}

impl Inclinometer {
    /// An inclinometer on `object`.
    pub fn new(object: ObjectId) -> Self {
        Inclinometer { object }
    }
}

/// An [`Inclinometer`] measurement.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Inclination {
    /// Rotation about Z, rad.
    pub pitch: f64,
    /// Rotation about X, rad.
    pub roll: f64,
}

impl Record for Inclination {
    fn columns() -> Vec<&'static str> {
        vec!["pitch [rad]", "roll [rad]"]
    }
    fn values(&self) -> Vec<Option<f64>> {
        vec![Some(self.pitch), Some(self.roll)]
    }
}

impl Sensor for Inclinometer {
    type Record = Inclination;
    fn measure(&mut self, sim: &Scene) -> Result<Inclination> {
        let r = sim.body(self.object)?.rotation();
        let m = r.matrix();
        Ok(Inclination { pitch: (-m[(0, 1)]).atan2(m[(0, 0)]), roll: (-m[(1, 2)]).atan2(m[(2, 2)]) })
    }
    fn objects(&self) -> Vec<ObjectId> {
        vec![self.object]
    }
}

/// An inertial measurement unit fixed on a body, at its centre of mass and turned as
/// the body unless mounted at an offset ([`at`](Self::at)), reading in its own frame:
/// the specific force `Rᵀ (a − g)` (what a real accelerometer feels: +9.81 m/s² up at
/// rest; `a` the acceleration of the IMU's point) and the angular velocity `Rᵀ ω`, `R`
/// the IMU's rotation in the world. The acceleration is the change of the point's
/// velocity over the step, as for [`Accelerometer`].
#[derive(Clone, Debug)]
pub struct Imu {
    inner: Accelerometer,
    turn: UnitQuaternion<f64>,
}

impl Imu {
    /// An IMU on `object`, at its centre of mass, turned as the object.
    pub fn new(object: ObjectId) -> Self {
        Imu { inner: Accelerometer::new(object), turn: UnitQuaternion::identity() }
    }

    /// Mounted at `offset` from the object's origin (its centre of mass), in the
    /// object's frame: it reads at that point, in that frame.
    #[must_use]
    pub fn at(self, offset: Isometry3<f64>) -> Self {
        Imu { inner: self.inner.at(offset.translation.vector), turn: offset.rotation }
    }
}

/// An [`Imu`] measurement, in the IMU's frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ImuReading {
    /// Specific force, m/s².
    pub specific_force: Vector3<f64>,
    /// Angular velocity, rad/s.
    pub angular_velocity: Vector3<f64>,
}

impl Record for ImuReading {
    fn columns() -> Vec<&'static str> {
        vec!["fx [m/s^2]", "fy [m/s^2]", "fz [m/s^2]", "gx [rad/s]", "gy [rad/s]", "gz [rad/s]"]
    }
    fn values(&self) -> Vec<Option<f64>> {
        [xyz(&self.specific_force), xyz(&self.angular_velocity)].concat()
    }
}

impl Sensor for Imu {
    type Record = ImuReading;
    fn before_step(&mut self, sim: &Scene) -> Result<()> {
        self.inner.before_step(sim)
    }
    fn measure(&mut self, sim: &Scene) -> Result<ImuReading> {
        let a = self.inner.measure(sim)?.linear;
        let b = sim.body(self.inner.object)?;
        // Into the body's frame, then the IMU's (the identity, exactly, unless mounted).
        let (to_body, to_imu) = (b.rotation().inverse(), self.turn.inverse());
        Ok(ImuReading {
            specific_force: to_imu * (to_body * (a - sim.gravity())),
            angular_velocity: to_imu * (to_body * b.angular_velocity()),
        })
    }
    fn objects(&self) -> Vec<ObjectId> {
        vec![self.inner.object]
    }
    fn settings(&self) -> Option<SensorSettings> {
        offset_settings(Isometry3::from_parts(self.inner.offset.into(), self.turn))
    }
}

/// Contacts of an object in the last step: how many contact points touch it and the
/// deepest penetration.
#[derive(Clone, Debug)]
pub struct ContactSensor {
    object: ObjectId,
}

impl ContactSensor {
    /// A contact (touch) sensor on `object`.
    pub fn new(object: ObjectId) -> Self {
        ContactSensor { object }
    }
}

/// A [`ContactSensor`] measurement.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactReading {
    /// Contact points on the object.
    pub contacts: usize,
    /// Deepest penetration, m (0 with no contact).
    pub max_depth: f64,
}

impl ContactReading {
    /// Whether anything touches the object.
    pub fn touching(&self) -> bool {
        self.contacts > 0
    }
}

impl Record for ContactReading {
    fn columns() -> Vec<&'static str> {
        vec!["contacts [1]", "max depth [m]"]
    }
    fn values(&self) -> Vec<Option<f64>> {
        vec![Some(self.contacts as f64), Some(self.max_depth)]
    }
}

impl Sensor for ContactSensor {
    type Record = ContactReading;
    fn measure(&mut self, sim: &Scene) -> Result<ContactReading> {
        let geom = sim.object(self.object)?.geom_handle();
        let mut reading = ContactReading { contacts: 0, max_depth: 0.0 };
        for c in sim.world().contacts() {
            if Some(c.pair.geom1) == geom || Some(c.pair.geom2) == geom {
                reading.contacts += 1;
                reading.max_depth = reading.max_depth.max(c.depth);
            }
        }
        Ok(reading)
    }
    fn objects(&self) -> Vec<ObjectId> {
        vec![self.object]
    }
}

/// Whether a contact's geom 1 and its geom 2 are `object`'s: on a body, every geom of
/// the object; without one, its geom.
pub(super) fn sides_touched(c: &ContactPoint, object: &ObjectView<'_>) -> (bool, bool) {
    match object.body_handle() {
        Some(b) => (c.pair.body1 == Some(b), c.pair.body2 == Some(b)),
        None => {
            let geom = object.geom_handle();
            (Some(c.pair.geom1) == geom, Some(c.pair.geom2) == geom)
        }
    }
}

/// The forces of the contacts on an object in the last step: their sum (world frame,
/// N) and how many contact points there were. Attaching it turns on the world's contact
/// feedback ([`World::set_contact_feedback`](crate::World::set_contact_feedback)): ODE
/// then reports each contact joint's force, read before the contact joints are
/// destroyed at the end of the step.
#[derive(Clone, Debug)]
pub struct ContactForces {
    object: ObjectId,
}

impl ContactForces {
    /// The contact forces on `object`.
    pub fn new(object: ObjectId) -> Self {
        ContactForces { object }
    }
}

/// A [`ContactForces`] measurement.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactForceReading {
    /// Contact points on the object.
    pub contacts: usize,
    /// The sum of their forces on the object, world frame, N.
    pub force: Vector3<f64>,
}

impl Record for ContactForceReading {
    fn columns() -> Vec<&'static str> {
        vec!["contacts [1]", "Fx [N]", "Fy [N]", "Fz [N]"]
    }
    fn values(&self) -> Vec<Option<f64>> {
        std::iter::once(Some(self.contacts as f64)).chain(xyz(&self.force)).collect()
    }
}

impl Sensor for ContactForces {
    type Record = ContactForceReading;
    fn attach(&mut self, scene: &mut Scene) -> Result<()> {
        scene.world_mut().set_contact_feedback(true);
        Ok(())
    }
    fn measure(&mut self, sim: &Scene) -> Result<ContactForceReading> {
        let object = sim.object(self.object)?;
        let mut reading = ContactForceReading { contacts: 0, force: Vector3::zeros() };
        for c in sim.world().contacts() {
            let (first, second) = sides_touched(c, &object);
            if first {
                reading.force += c.force;
            } else if second {
                reading.force -= c.force;
            } else {
                continue;
            }
            reading.contacts += 1;
        }
        Ok(reading)
    }
    fn objects(&self) -> Vec<ObjectId> {
        vec![self.object]
    }
}
