//! Sensors on one body: position, velocity, acceleration, inclination, IMU, contacts.

use nalgebra::{Point3, Vector3};

use super::{Record, Sensor};
use crate::error::Result;
use crate::handle::ObjectId;
use crate::scene::Scene;

fn xyz(v: &Vector3<f64>) -> [Option<f64>; 3] {
    [Some(v.x), Some(v.y), Some(v.z)]
}

/// Position of a body's centre of mass, world frame (the original's GPS).
#[derive(Clone, Debug)]
pub struct Gps {
    object: ObjectId,
}

impl Gps {
    /// A GPS on `object`.
    pub fn new(object: ObjectId) -> Self {
        Gps { object }
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
        Ok(Position { position: sim.body(self.object)?.position() })
    }
    fn objects(&self) -> Vec<ObjectId> {
        vec![self.object]
    }
}

/// Linear and angular velocity of a body, world frame.
#[derive(Clone, Debug)]
pub struct Velometer {
    object: ObjectId,
}

impl Velometer {
    /// A velometer on `object`.
    pub fn new(object: ObjectId) -> Self {
        Velometer { object }
    }
}

/// A [`Velometer`] measurement.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Velocity {
    /// Linear velocity of the centre of mass, m/s.
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
        Ok(Velocity { linear: b.linear_velocity(), angular: b.angular_velocity() })
    }
    fn objects(&self) -> Vec<ObjectId> {
        vec![self.object]
    }
}

/// Linear and angular acceleration of a body, world frame: the change of velocity over
/// the step divided by the time step, `(v_end − v_start) / dt`.
///
/// The sensor keeps its own state (the velocity at the start of each step, noted just
/// before collision), so several accelerometers on one body do not interfere, and its
/// first sample is well defined: the change over the first step. At a bounce it reads
/// `(1 + e) · v_impact / dt`, as in the thesis.
#[derive(Clone, Debug)]
pub struct Accelerometer {
    object: ObjectId,
    start: Option<(Vector3<f64>, Vector3<f64>)>,
}

impl Accelerometer {
    /// An accelerometer on `object`.
    pub fn new(object: ObjectId) -> Self {
        Accelerometer { object, start: None }
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
        self.start = Some((b.linear_velocity(), b.angular_velocity()));
        Ok(())
    }
    fn measure(&mut self, sim: &Scene) -> Result<Acceleration> {
        let b = sim.body(self.object)?;
        let (v0, w0) = self.start.expect("before_step runs before every measurement");
        let dt = sim.time_step();
        Ok(Acceleration { linear: (b.linear_velocity() - v0) / dt, angular: (b.angular_velocity() - w0) / dt })
    }
    fn objects(&self) -> Vec<ObjectId> {
        vec![self.object]
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

/// An inertial measurement unit fixed at a body's centre of mass, reading in the body
/// frame: the specific force `Rᵀ (a − g)` (what a real accelerometer feels: +9.81 m/s²
/// up at rest) and the angular velocity `Rᵀ ω`. The acceleration is the change of
/// velocity over the step, as for [`Accelerometer`].
#[derive(Clone, Debug)]
pub struct Imu {
    inner: Accelerometer,
}

impl Imu {
    /// An IMU on `object`.
    pub fn new(object: ObjectId) -> Self {
        Imu { inner: Accelerometer::new(object) }
    }
}

/// An [`Imu`] measurement, body frame.
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
        let to_body = b.rotation().inverse();
        Ok(ImuReading {
            specific_force: to_body * (a - sim.gravity()),
            angular_velocity: to_body * b.angular_velocity(),
        })
    }
    fn objects(&self) -> Vec<ObjectId> {
        vec![self.inner.object]
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
        let (body, geom) = (object.body_handle(), object.geom_handle());
        let mut reading = ContactForceReading { contacts: 0, force: Vector3::zeros() };
        for c in sim.world().contacts() {
            // On a body, every geom of the object; without one, its geom.
            let (first, second) = match body {
                Some(b) => (c.pair.body1 == Some(b), c.pair.body2 == Some(b)),
                None => (Some(c.pair.geom1) == geom, Some(c.pair.geom2) == geom),
            };
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
