//! Rigid bodies: creation, mass, pose, velocities, forces.

use nalgebra::{Isometry3, Matrix3, Point3, Rotation3, Translation3, UnitQuaternion, Vector3};
use ode_sys as ffi;
use serde::{Deserialize, Serialize};

use super::World;
use crate::convert;
use crate::error::{Error, Result};
use crate::handle::BodyHandle;
use crate::init::ensure_ode_ready;
use crate::limits;
use crate::shape::Shape;
use crate::validate;

/// Writes ODE's quaternion and rotation matrix of `body` as given, without the
/// renormalisation of ODE's setters (call a setter first: it tells the body's geoms
/// that it moved). The two must describe the same rotation.
///
/// # Safety
/// `body` is a live body, and nothing else uses it during the call.
pub(crate) unsafe fn write_orientation(body: ffi::dBodyID, q: &[f64; 4], r: &[f64; 12]) {
    // SAFETY: the caller's contract; dBodyGetQuaternion and dBodyGetRotation point into
    // the body's own heap-allocated state (4 and 12 reals, which ODE itself writes at
    // every step).
    unsafe {
        std::ptr::copy_nonoverlapping(q.as_ptr(), ffi::dBodyGetQuaternion(body).cast_mut(), 4);
        std::ptr::copy_nonoverlapping(r.as_ptr(), ffi::dBodyGetRotation(body).cast_mut(), 12);
    }
}

pub(crate) struct BodyData {
    pub(crate) raw: ffi::dBodyID,
    /// Where ODE keeps the body's state, read by the checks around every step.
    pub(crate) state: StatePointers,
    /// Its place in the world's creation order (see [`World::next_serial`]).
    pub(crate) serial: u64,
}

/// Pointers to a body's position, orientation quaternion, linear and angular velocity,
/// and force and torque accumulators, inside ODE's body.
///
/// ODE's getters (`dBodyGetPosition`...) return the addresses of members of the
/// `dxBody` object, which `dBodyCreate` allocates with `new` and which stays in place
/// until `dBodyDestroy` (ODE 0.16's ode.cpp; ode-sys insists on 0.16). Taking them
/// once saves six library calls per body and step.
pub(crate) struct StatePointers {
    pub(crate) position: *const [f64; 3],
    pub(crate) quaternion: *const [f64; 4],
    pub(crate) linear_velocity: *const [f64; 3],
    pub(crate) angular_velocity: *const [f64; 3],
    pub(crate) force: *const [f64; 3],
    pub(crate) torque: *const [f64; 3],
}

impl StatePointers {
    /// # Safety
    /// `raw` must be a live body.
    unsafe fn of(raw: ffi::dBodyID) -> Self {
        // SAFETY: the caller's contract; each getter returns a pointer to at least as
        // many reals as the array type says (dVector3 has 4, dQuaternion 4).
        unsafe {
            StatePointers {
                position: ffi::dBodyGetPosition(raw).cast(),
                quaternion: ffi::dBodyGetQuaternion(raw).cast(),
                linear_velocity: ffi::dBodyGetLinearVel(raw).cast(),
                angular_velocity: ffi::dBodyGetAngularVel(raw).cast(),
                force: ffi::dBodyGetForce(raw).cast(),
                torque: ffi::dBodyGetTorque(raw).cast(),
            }
        }
    }
}

/// How the mass of a shape is given: the total mass in kg, or a density in kg/m³.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub enum Mass {
    /// Total mass, kg.
    Total(f64),
    /// Density, kg/m³.
    Density(f64),
}

/// The mass distribution of a body, computed with ODE's mass functions (so the numbers
/// are ODE's own). Capsules and cylinders lie along the body's local Z axis; box sizes
/// are full edge lengths; a capsule's length excludes its two hemispherical caps.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum MassSpec {
    /// A uniformly dense solid of this shape: sphere, box, capsule, cylinder (ODE's
    /// formulas) or cone (3/10 m r² about its axis, 3/20 m r² + 3/80 m h² across, about
    /// its centre of mass), or convex hull (the solid it bounds, whose centre of volume
    /// must be its origin). Planes, rays and triangle meshes have no mass.
    Solid {
        /// The shape.
        shape: Shape,
        /// Mass or density.
        amount: Mass,
    },
    /// A mass with its inertia tensor about the body origin (the centre of mass).
    Custom {
        /// Mass, kg.
        mass: f64,
        /// Symmetric, positive definite inertia tensor in the body frame, kg·m².
        inertia: Matrix3<f64>,
    },
}

impl MassSpec {
    /// A solid `shape` of total mass or density `amount`.
    pub fn solid(shape: Shape, amount: Mass) -> Self {
        MassSpec::Solid { shape, amount }
    }
    /// Sphere of total mass `mass` (kg) and radius `radius` (m).
    pub fn sphere_total(mass: f64, radius: f64) -> Self {
        Self::solid(Shape::Sphere { radius }, Mass::Total(mass))
    }
    /// Box of total mass `mass` and full edge lengths `edges`.
    pub fn box_total(mass: f64, edges: Vector3<f64>) -> Self {
        Self::solid(Shape::Box { edges }, Mass::Total(mass))
    }
    /// Capsule along Z of total mass `mass`.
    pub fn capsule_total(mass: f64, radius: f64, length: f64) -> Self {
        Self::solid(Shape::Capsule { radius, length }, Mass::Total(mass))
    }
    /// Cylinder along Z of total mass `mass`.
    pub fn cylinder_total(mass: f64, radius: f64, length: f64) -> Self {
        Self::solid(Shape::Cylinder { radius, length }, Mass::Total(mass))
    }

    /// The ODE mass structure, after checking every number.
    pub(crate) fn to_ode(&self) -> Result<ffi::dMass> {
        let (shape, amount) = match self {
            MassSpec::Solid { shape, amount } => (shape, *amount),
            MassSpec::Custom { mass, inertia } => {
                limits::mass("mass", *mass)?;
                limits::inertia(inertia)?;
                return finish(custom(*mass, inertia));
            }
        };
        // Check every number first; the ODE calls below then cannot fail.
        let amount = match amount {
            Mass::Total(m) => Mass::Total(limits::mass("mass", m)?),
            // The resulting mass is checked at the end.
            Mass::Density(d) => Mass::Density(validate::positive("density", d)?),
        };
        if matches!(shape, Shape::Plane { .. } | Shape::Ray { .. } | Shape::TriMesh { .. }) {
            return Err(Error::Invalid {
                what: "a mass from a density",
                problem: format!(
                    "needs a volume, and a {} has none: give the body a solid shape or a total mass",
                    shape.kind_name()
                ),
            });
        }
        shape.validate()?;
        use Mass::{Density, Total};
        let mut m = ffi::dMass::default();
        // SAFETY: `m` is a valid dMass to fill; every size and amount was checked
        // positive and finite above, which is all ODE's mass functions need.
        unsafe {
            match (shape, amount) {
                (Shape::Sphere { radius: r }, Total(t)) => ffi::dMassSetSphereTotal(&mut m, t, *r),
                (Shape::Sphere { radius: r }, Density(d)) => ffi::dMassSetSphere(&mut m, d, *r),
                (Shape::Box { edges: e }, Total(t)) => ffi::dMassSetBoxTotal(&mut m, t, e.x, e.y, e.z),
                (Shape::Box { edges: e }, Density(d)) => ffi::dMassSetBox(&mut m, d, e.x, e.y, e.z),
                (Shape::Capsule { radius: r, length: l }, Total(t)) => ffi::dMassSetCapsuleTotal(&mut m, t, 3, *r, *l),
                (Shape::Capsule { radius: r, length: l }, Density(d)) => ffi::dMassSetCapsule(&mut m, d, 3, *r, *l),
                (Shape::Cylinder { radius: r, length: l }, Total(t)) => {
                    ffi::dMassSetCylinderTotal(&mut m, t, 3, *r, *l)
                }
                (Shape::Cylinder { radius: r, length: l }, Density(d)) => ffi::dMassSetCylinder(&mut m, d, 3, *r, *l),
                (Shape::ConvexHull { vertices, triangles }, amount) => {
                    // Validated above: a closed hull with a volume.
                    let solid = crate::shape::mass_properties(vertices, triangles)
                        .ok_or_else(|| Error::InvalidMesh("the convex hull encloses no volume".into()))?;
                    let mass = match amount {
                        Total(t) => t,
                        Density(d) => d * solid.volume,
                    };
                    let mass = limits::mass("mass (from the density and the shape)", mass)?;
                    // ODE's body origin is its centre of mass.
                    if solid.centre.coords.norm() > 1e-9 * solid.volume.cbrt() {
                        return Err(Error::Invalid {
                            what: "a mass from a convex hull",
                            problem: format!(
                                "puts the centre of mass at the body origin, but the hull's centre of volume is at {:?}: move its vertices by the opposite, or give a custom mass",
                                solid.centre.coords.as_slice()
                            ),
                        });
                    }
                    m = custom(mass, &(solid.inertia * (mass / solid.volume)));
                }
                (Shape::Cone { radius: r, height: h }, amount) => {
                    let volume = std::f64::consts::PI * r * r * h / 3.0;
                    let mass = match amount {
                        Total(t) => t,
                        Density(d) => d * volume,
                    };
                    let mass = limits::mass("mass (from the density and the shape)", mass)?;
                    // Solid cone about its centre of mass.
                    let axial = 0.3 * mass * r * r;
                    let transverse = 0.15 * mass * r * r + 0.0375 * mass * h * h;
                    m = custom(mass, &Matrix3::from_diagonal(&Vector3::new(transverse, transverse, axial)));
                }
                _ => unreachable!("massless shapes were refused above"),
            }
        }
        finish(m)
    }
}

/// ODE's mass structure of a mass and inertia tensor about the body origin.
fn custom(mass: f64, i: &Matrix3<f64>) -> ffi::dMass {
    let mut m = ffi::dMass::default();
    // SAFETY: `m` is a valid dMass to fill; dMassSetParameters only writes it.
    unsafe {
        ffi::dMassSetParameters(
            &mut m,
            mass,
            0.0,
            0.0,
            0.0,
            i[(0, 0)],
            i[(1, 1)],
            i[(2, 2)],
            i[(0, 1)],
            i[(0, 2)],
            i[(1, 2)],
        )
    };
    m
}

/// Checks what ODE computed: a density gives a mass (and every shape an inertia) that
/// must be in range too (a density of 1e10 kg/m³ in a sphere of radius 1e150 m
/// overflows to infinity).
fn finish(m: ffi::dMass) -> Result<ffi::dMass> {
    limits::mass("mass (from the density and the shape)", m.mass)?;
    limits::inertia(&convert::matrix_from_ode(&m.I))?;
    // SAFETY: `m` is a valid dMass; dMassCheck only reads it.
    if unsafe { ffi::dMassCheck(&m) } == 0 {
        return Err(Error::Invalid { what: "the mass parameters", problem: "are rejected by ODE (dMassCheck)".into() });
    }
    Ok(m)
}

/// How a body moves.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum BodyKind {
    /// Moved by forces, gravity, joints and contacts.
    #[default]
    Dynamic,
    /// Moved only by its velocity; pushes dynamic bodies, is not pushed (infinite mass).
    Kinematic,
}

/// Description of a body to insert with [`World::insert_body`].
///
/// ODE calls happen in this order: create, set mass, position, rotation, velocities,
/// kinematic flag. With no mass given the body keeps ODE's default (1 kg, identity
/// inertia), as in the original ARS.
#[derive(Clone, Debug, Default)]
#[must_use]
pub struct BodyBuilder {
    kind: BodyKind,
    mass: Option<MassSpec>,
    position: Option<Point3<f64>>,
    rotation: Option<Rotation3<f64>>,
    linear_velocity: Option<Vector3<f64>>,
    angular_velocity: Option<Vector3<f64>>,
}

impl BodyBuilder {
    /// A dynamic body at the origin.
    pub fn new() -> Self {
        BodyBuilder::default()
    }
    /// A kinematic body at the origin.
    pub fn kinematic() -> Self {
        BodyBuilder { kind: BodyKind::Kinematic, ..Default::default() }
    }
    /// Its mass distribution.
    pub fn mass(mut self, mass: MassSpec) -> Self {
        self.mass = Some(mass);
        self
    }
    /// Its position (of the centre of mass), m.
    pub fn position(mut self, position: Point3<f64>) -> Self {
        self.position = Some(position);
        self
    }
    /// Its orientation.
    pub fn rotation(mut self, rotation: Rotation3<f64>) -> Self {
        self.rotation = Some(rotation);
        self
    }
    /// Its initial linear velocity, m/s.
    pub fn linear_velocity(mut self, v: Vector3<f64>) -> Self {
        self.linear_velocity = Some(v);
        self
    }
    /// Its initial angular velocity (world frame), rad/s.
    pub fn angular_velocity(mut self, w: Vector3<f64>) -> Self {
        self.angular_velocity = Some(w);
        self
    }
}

/// Read access to one body, from [`World::body`].
#[derive(Clone, Copy)]
pub struct BodyRef<'w> {
    raw: ffi::dBodyID,
    handle: BodyHandle,
    _world: &'w World,
}

/// Write access to one body, from [`World::body_mut`].
pub struct BodyMut<'w> {
    raw: ffi::dBodyID,
    handle: BodyHandle,
    world: &'w mut World,
}

impl World {
    /// Creates a body as described by `builder`.
    pub fn insert_body(&mut self, builder: BodyBuilder) -> Result<BodyHandle> {
        self.check_usable()?;
        ensure_ode_ready();
        // Check everything first, so that a bad argument leaves the world untouched.
        let mass = builder.mass.as_ref().map(MassSpec::to_ode).transpose()?;
        let position = builder.position.map(|p| limits::point("body position", &p)).transpose()?;
        let rotation = builder.rotation.map(|r| validate::rotation("body rotation", &r)).transpose()?;
        let lin = builder.linear_velocity.map(|v| linear_velocity(&v)).transpose()?;
        let ang = builder.angular_velocity.map(|v| angular_velocity(&v)).transpose()?;
        // SAFETY: the world is live; the new body is owned by the arena entry below and
        // destroyed by `remove_body` or the world's Drop.
        let raw = unsafe { ffi::dBodyCreate(self.raw) };
        // SAFETY: the body was just created.
        let state = unsafe { StatePointers::of(raw) };
        let serial = self.next_serial();
        let handle = BodyHandle(self.bodies.insert(BodyData { raw, state, serial }));
        // SAFETY: the body id was just created by this world.
        unsafe {
            ffi::dBodySetData(raw, handle.0.index as usize as *mut _);
        }
        let mut body = self.body_mut(handle)?;
        if let Some(m) = mass {
            body.set_ode_mass(&m);
        }
        if let Some(p) = position {
            body.set_position(p)?;
        }
        if let Some(r) = rotation {
            body.set_rotation(r)?;
        }
        if let Some(v) = lin {
            body.set_linear_velocity(v)?;
        }
        if let Some(w) = ang {
            body.set_angular_velocity(w)?;
        }
        if builder.kind == BodyKind::Kinematic {
            body.set_kinematic(true);
        }
        Ok(handle)
    }

    /// Removes a body together with the geoms attached to it and the joints that use it.
    pub fn remove_body(&mut self, body: BodyHandle) -> Result<()> {
        self.check_usable()?;
        self.body(body)?;
        let geoms: Vec<_> = self.geoms_of_body(body);
        for g in geoms {
            self.remove_geom(g)?;
        }
        let joints: Vec<_> = self.joints_of_body(body);
        for j in joints {
            self.remove_joint(j)?;
        }
        let data = self.bodies.remove(body.0, BodyHandle::KIND)?;
        if self.diverged == Some(body) {
            self.set_diverged(None);
        }
        // SAFETY: the body was created by this world; its geoms and joints are gone and
        // contact joints only live within a step.
        unsafe { ffi::dBodyDestroy(data.raw) };
        Ok(())
    }

    /// Read access to a body.
    pub fn body(&self, body: BodyHandle) -> Result<BodyRef<'_>> {
        let raw = self.bodies.get(body.0, BodyHandle::KIND)?.raw;
        Ok(BodyRef { raw, handle: body, _world: self })
    }

    /// Write access to a body.
    pub fn body_mut(&mut self, body: BodyHandle) -> Result<BodyMut<'_>> {
        self.check_usable()?;
        let raw = self.bodies.get(body.0, BodyHandle::KIND)?.raw;
        Ok(BodyMut { raw, handle: body, world: self })
    }

    /// Every body of the world, in slot order.
    pub fn bodies(&self) -> impl Iterator<Item = BodyHandle> + '_ {
        self.bodies.iter().map(|(h, _)| BodyHandle(h))
    }

    pub(crate) fn body_raw(&self, body: BodyHandle) -> Result<ffi::dBodyID> {
        Ok(self.bodies.get(body.0, BodyHandle::KIND)?.raw)
    }
}

macro_rules! body_getters {
    () => {
        /// The handle of this body.
        pub fn handle(&self) -> BodyHandle {
            self.handle
        }

        /// Position of the body origin (its centre of mass), m.
        pub fn position(&self) -> Point3<f64> {
            // SAFETY: the body is live (its handle was checked when this view was
            // made, and the view borrows the world); ODE returns a pointer to 3 reals.
            convert::point_from_ode(unsafe { std::slice::from_raw_parts(ffi::dBodyGetPosition(self.raw), 3) })
        }

        /// Orientation as a rotation matrix (body to world).
        pub fn rotation(&self) -> Rotation3<f64> {
            // SAFETY: as for `position`; ODE returns a dMatrix3 (12 reals).
            convert::rotation_from_ode(unsafe { std::slice::from_raw_parts(ffi::dBodyGetRotation(self.raw), 12) })
        }

        /// Orientation as a unit quaternion.
        pub fn quaternion(&self) -> UnitQuaternion<f64> {
            // SAFETY: as for `position`; ODE returns a dQuaternion (4 reals).
            convert::quaternion_from_ode(unsafe { std::slice::from_raw_parts(ffi::dBodyGetQuaternion(self.raw), 4) })
        }

        /// Pose (body to world).
        pub fn pose(&self) -> Isometry3<f64> {
            Isometry3::from_parts(Translation3::from(self.position().coords), self.quaternion())
        }

        /// Linear velocity of the centre of mass, world frame, m/s.
        pub fn linear_velocity(&self) -> Vector3<f64> {
            // SAFETY: as for `position`.
            convert::vector_from_ode(unsafe { std::slice::from_raw_parts(ffi::dBodyGetLinearVel(self.raw), 3) })
        }

        /// Angular velocity, world frame, rad/s.
        pub fn angular_velocity(&self) -> Vector3<f64> {
            // SAFETY: as for `position`.
            convert::vector_from_ode(unsafe { std::slice::from_raw_parts(ffi::dBodyGetAngularVel(self.raw), 3) })
        }

        /// Mass, kg.
        pub fn mass(&self) -> f64 {
            self.ode_mass().mass
        }

        /// Inertia tensor about the centre of mass, in the body frame, kg·m².
        pub fn inertia(&self) -> Matrix3<f64> {
            convert::matrix_from_ode(&self.ode_mass().I)
        }

        /// Inertia tensor about the centre of mass, in the world frame: R I Rᵀ.
        pub fn inertia_world(&self) -> Matrix3<f64> {
            let r = self.rotation();
            r.matrix() * self.inertia() * r.matrix().transpose()
        }

        /// Force accumulated for the next step, world frame, N.
        pub fn force(&self) -> Vector3<f64> {
            // SAFETY: as for `position`.
            convert::vector_from_ode(unsafe { std::slice::from_raw_parts(ffi::dBodyGetForce(self.raw), 3) })
        }

        /// Torque accumulated for the next step, world frame, N·m.
        pub fn torque(&self) -> Vector3<f64> {
            // SAFETY: as for `position`.
            convert::vector_from_ode(unsafe { std::slice::from_raw_parts(ffi::dBodyGetTorque(self.raw), 3) })
        }

        /// Whether the body takes part in the simulation.
        pub fn is_enabled(&self) -> bool {
            // SAFETY: the body is live.
            unsafe { ffi::dBodyIsEnabled(self.raw) != 0 }
        }

        /// Whether the body is kinematic.
        pub fn is_kinematic(&self) -> bool {
            // SAFETY: the body is live.
            unsafe { ffi::dBodyIsKinematic(self.raw) != 0 }
        }

        /// World coordinates of a point given in the body frame.
        pub fn point_to_world(&self, local: Point3<f64>) -> Point3<f64> {
            self.pose() * local
        }

        /// Velocity of a point fixed to the body, given in world coordinates, m/s.
        pub fn point_velocity(&self, world_point: Point3<f64>) -> Vector3<f64> {
            self.linear_velocity() + self.angular_velocity().cross(&(world_point - self.position()))
        }

        fn ode_mass(&self) -> ffi::dMass {
            let mut m = ffi::dMass::default();
            // SAFETY: the body is live; `m` is a valid out-parameter.
            unsafe { ffi::dBodyGetMass(self.raw, &mut m) };
            m
        }
    };
}

impl BodyRef<'_> {
    body_getters!();
}

impl std::fmt::Debug for BodyRef<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Body").field("handle", &self.handle).field("position", &self.position()).finish()
    }
}

impl BodyMut<'_> {
    body_getters!();

    /// Sets the position of the body origin, m.
    pub fn set_position(&mut self, p: Point3<f64>) -> Result<()> {
        let p = limits::point("body position", &p)?;
        self.world.note_body_coordinate(p.coords.amax());
        // SAFETY: the body is live (checked handle, exclusive borrow of the world).
        unsafe { ffi::dBodySetPosition(self.raw, p.x, p.y, p.z) };
        Ok(())
    }

    /// Sets the orientation from a rotation matrix (ODE's `dBodySetRotation`).
    pub fn set_rotation(&mut self, r: Rotation3<f64>) -> Result<()> {
        let r = validate::rotation("body rotation", &r)?;
        let m = convert::rotation_to_ode(&r);
        // SAFETY: the body is live; `m` is a dMatrix3.
        unsafe { ffi::dBodySetRotation(self.raw, m.as_ptr()) };
        Ok(())
    }

    /// Sets the orientation from a unit quaternion (ODE's `dBodySetQuaternion`).
    pub fn set_quaternion(&mut self, q: UnitQuaternion<f64>) -> Result<()> {
        let q = validate::quaternion("body orientation", &q)?;
        let q = convert::quaternion_to_ode(&q);
        // SAFETY: the body is live; `q` is a dQuaternion.
        unsafe { ffi::dBodySetQuaternion(self.raw, q.as_ptr()) };
        Ok(())
    }

    /// Restores a saved orientation to the bit: ODE keeps a quaternion and a rotation
    /// matrix and its setters renormalise, so both are written as saved (after
    /// [`set_quaternion`](Self::set_quaternion), which tells the body's geoms that it
    /// moved). The two must describe the same rotation.
    pub(crate) fn restore_orientation(&mut self, q: &UnitQuaternion<f64>, r: &Rotation3<f64>) -> Result<()> {
        let r = validate::rotation("body rotation", r)?;
        if (q.to_rotation_matrix().matrix() - r.matrix()).amax() > 1e-9 {
            return Err(Error::Invalid {
                what: "a saved body orientation",
                problem: "has a quaternion and a rotation matrix that disagree".into(),
            });
        }
        self.set_quaternion(*q)?;
        let (q, r) = (convert::quaternion_to_ode(q), convert::rotation_to_ode(&r));
        // SAFETY: the body is live (checked handle, exclusive borrow of the world).
        unsafe { write_orientation(self.raw, &q, &r) };
        Ok(())
    }

    /// Sets position and orientation.
    pub fn set_pose(&mut self, pose: Isometry3<f64>) -> Result<()> {
        validate::quaternion("body orientation", &pose.rotation)?;
        self.set_position(Point3::from(pose.translation.vector))?;
        self.set_quaternion(pose.rotation)
    }

    /// Sets the linear velocity, m/s.
    pub fn set_linear_velocity(&mut self, v: Vector3<f64>) -> Result<()> {
        let v = linear_velocity(&v)?;
        // SAFETY: the body is live.
        unsafe { ffi::dBodySetLinearVel(self.raw, v.x, v.y, v.z) };
        Ok(())
    }

    /// Sets the angular velocity (world frame), rad/s.
    pub fn set_angular_velocity(&mut self, w: Vector3<f64>) -> Result<()> {
        let w = angular_velocity(&w)?;
        // SAFETY: the body is live.
        unsafe { ffi::dBodySetAngularVel(self.raw, w.x, w.y, w.z) };
        Ok(())
    }

    /// Replaces the mass distribution.
    pub fn set_mass(&mut self, mass: MassSpec) -> Result<()> {
        let m = mass.to_ode()?;
        self.set_ode_mass(&m);
        Ok(())
    }

    fn set_ode_mass(&mut self, m: &ffi::dMass) {
        // SAFETY: the body is live and `m` passed dMassCheck with its centre at the origin.
        unsafe { ffi::dBodySetMass(self.raw, m) };
    }

    /// Adds a force (world frame, N) at the centre of mass, for the next step.
    pub fn add_force(&mut self, f: Vector3<f64>) -> Result<()> {
        let f = force(&f)?;
        self.world.gate.forces_added = true;
        // SAFETY: the body is live.
        unsafe { ffi::dBodyAddForce(self.raw, f.x, f.y, f.z) };
        Ok(())
    }

    /// Adds a force given in the body frame, at the centre of mass.
    pub fn add_relative_force(&mut self, f: Vector3<f64>) -> Result<()> {
        let f = force(&f)?;
        self.world.gate.forces_added = true;
        // SAFETY: the body is live.
        unsafe { ffi::dBodyAddRelForce(self.raw, f.x, f.y, f.z) };
        Ok(())
    }

    /// Adds a torque (world frame, N·m), for the next step.
    pub fn add_torque(&mut self, t: Vector3<f64>) -> Result<()> {
        let t = torque(&t)?;
        self.world.gate.forces_added = true;
        // SAFETY: the body is live.
        unsafe { ffi::dBodyAddTorque(self.raw, t.x, t.y, t.z) };
        Ok(())
    }

    /// Adds a torque given in the body frame.
    pub fn add_relative_torque(&mut self, t: Vector3<f64>) -> Result<()> {
        let t = torque(&t)?;
        self.world.gate.forces_added = true;
        // SAFETY: the body is live.
        unsafe { ffi::dBodyAddRelTorque(self.raw, t.x, t.y, t.z) };
        Ok(())
    }

    /// Adds a world-frame force at a point given in world coordinates.
    pub fn add_force_at_point(&mut self, f: Vector3<f64>, point: Point3<f64>) -> Result<()> {
        let f = force(&f)?;
        let p = limits::point("force application point", &point)?;
        self.world.gate.forces_added = true;
        // SAFETY: the body is live.
        unsafe { ffi::dBodyAddForceAtPos(self.raw, f.x, f.y, f.z, p.x, p.y, p.z) };
        Ok(())
    }

    /// Adds a body-frame force at a point given in body coordinates.
    pub fn add_relative_force_at_relative_point(&mut self, f: Vector3<f64>, point: Point3<f64>) -> Result<()> {
        let f = force(&f)?;
        let p = limits::point("force application point", &point)?;
        self.world.gate.forces_added = true;
        // SAFETY: the body is live.
        unsafe { ffi::dBodyAddRelForceAtRelPos(self.raw, f.x, f.y, f.z, p.x, p.y, p.z) };
        Ok(())
    }

    /// Clears the force and torque accumulated for the next step.
    pub fn clear_forces(&mut self) {
        // SAFETY: the body is live.
        unsafe {
            ffi::dBodySetForce(self.raw, 0.0, 0.0, 0.0);
            ffi::dBodySetTorque(self.raw, 0.0, 0.0, 0.0);
        }
    }

    /// Enables or disables the body (a disabled body does not move).
    pub fn set_enabled(&mut self, enabled: bool) {
        // SAFETY: the body is live.
        unsafe { if enabled { ffi::dBodyEnable(self.raw) } else { ffi::dBodyDisable(self.raw) } }
    }

    /// Makes the body kinematic (moved only by its velocity) or dynamic again (with the
    /// mass it had).
    pub fn set_kinematic(&mut self, kinematic: bool) {
        // SAFETY: the body is live.
        unsafe { if kinematic { ffi::dBodySetKinematic(self.raw) } else { ffi::dBodySetDynamic(self.raw) } }
    }

    /// Whether gravity acts on the body.
    pub fn set_gravity_enabled(&mut self, on: bool) {
        // SAFETY: the body is live.
        unsafe { ffi::dBodySetGravityMode(self.raw, on.into()) };
    }
}

fn linear_velocity(v: &Vector3<f64>) -> Result<Vector3<f64>> {
    limits::vector_within("linear velocity", v, limits::MAX_SPEED, "m/s")
}

fn angular_velocity(w: &Vector3<f64>) -> Result<Vector3<f64>> {
    limits::vector_within("angular velocity", w, limits::MAX_ANGULAR_SPEED, "rad/s")
}

fn force(f: &Vector3<f64>) -> Result<Vector3<f64>> {
    limits::vector_within("force", f, limits::MAX_FORCE, "N")
}

fn torque(t: &Vector3<f64>) -> Result<Vector3<f64>> {
    limits::vector_within("torque", t, limits::MAX_TORQUE, "N·m")
}

/// A body's pose exactly as ODE keeps it.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub(crate) struct ExactPose {
    pub(super) position: [f64; 3],
    pub(super) quaternion: [f64; 4],
    /// ODE's 3×4 rotation matrix (the fourth column is padding).
    pub(super) rotation: [f64; 12],
}

impl ExactPose {
    /// # Safety
    /// `body` is a live body.
    pub(super) unsafe fn of(body: ffi::dBodyID) -> ExactPose {
        let mut pose = ExactPose { position: [0.0; 3], quaternion: [0.0; 4], rotation: [0.0; 12] };
        // SAFETY: the caller's contract; ODE's getters point at 4, 4 and 12 reals.
        unsafe {
            pose.position.copy_from_slice(std::slice::from_raw_parts(ffi::dBodyGetPosition(body), 3));
            pose.quaternion.copy_from_slice(std::slice::from_raw_parts(ffi::dBodyGetQuaternion(body), 4));
            pose.rotation.copy_from_slice(std::slice::from_raw_parts(ffi::dBodyGetRotation(body), 12));
        }
        pose
    }

    /// Puts the body there, to the bit: ODE's quaternion and rotation setters
    /// renormalise, so both are written in place, after `dBodySetPosition` (which tells
    /// the body's geoms that it moved).
    ///
    /// # Safety
    /// `body` is a live body.
    pub(super) unsafe fn put(&self, body: ffi::dBodyID) {
        let p = self.position;
        // SAFETY: the caller's contract.
        unsafe {
            ffi::dBodySetPosition(body, p[0], p[1], p[2]);
            write_orientation(body, &self.quaternion, &self.rotation);
        }
    }
}
