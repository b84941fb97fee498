//! The exact state of a [`World`]: what a snapshot holds of it, and how it is put back
//! so that every later step is the same to the bit.
//!
//! ODE keeps, besides what its getters return, things that decide the last bits of a
//! step: a joint's anchors, axes and zero reference are kept in its bodies' frames as
//! they were when the joint was made; the bodies, joints and geoms sit in linked lists
//! whose order is the order of the rows of the constraint problem and of the collision
//! pairs. A [`WorldState`] therefore holds:
//! - every body's pose as ODE keeps it (position, quaternion and rotation matrix, which
//!   ODE's setters would renormalise), velocities, force and torque accumulators, mass,
//!   and flags;
//! - every joint's kind as created and where its bodies were then
//!   ([`JointReference`]): restoring makes every joint again, in creation order, with
//!   its bodies put back there first, so that ODE computes the same frames, and the
//!   world's and bodies' joint lists come out in the order of a world built afresh;
//! - every joint's parameters (limits, motors...) and the forces of its last step;
//! - the pose of every geom without a body and the offset of every geom on one, every
//!   geom's switch and collision bits, and the order of the geoms in each space (ODE's
//!   spaces test pairs in that order);
//! - the world's parameters, clock and random seed.
//!
//! Bodies, geoms and spaces are not made again: a state is restored into a world with
//! the same ones, created in the same order (the world it came from, or one built the
//! same way).

use nalgebra::Vector3;
use ode_sys as ffi;
use serde::{Deserialize, Serialize};

use super::World;
use super::body::ExactPose;
use super::joint::{JointKind, JointReference, create_ode_joint, set_raw_param};
use crate::contact::ContactSurface;
use crate::error::{Error, Result};
use crate::world::Stepper;

/// A body's state.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
struct BodyState {
    pose: ExactPose,
    linear_velocity: [f64; 3],
    angular_velocity: [f64; 3],
    force: [f64; 3],
    torque: [f64; 3],
    /// ODE's `dMass`: mass, centre (4 reals), inertia (12 reals).
    mass: Vec<f64>,
    enabled: bool,
    kinematic: bool,
    gravity: bool,
}

/// A geom's state: what can change about it after it is made.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
struct GeomState {
    /// Its shape's kind, to check that a state goes into the same world.
    kind: String,
    /// Its body (index into the bodies in creation order), if any.
    body: Option<u32>,
    /// Position and rotation matrix of a geom without a body (not a plane).
    pose: Option<([f64; 3], [f64; 12])>,
    /// Position and rotation matrix relative to its body, if it has an offset.
    #[serde(default)]
    offset: Option<([f64; 3], [f64; 12])>,
    enabled: bool,
    category_bits: u64,
    collide_bits: u64,
}

/// A joint as it was made, and its parameters and forces now.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
struct JointState {
    kind: JointKind,
    body1: u32,
    body2: Option<u32>,
    reference: JointReference,
    /// Every parameter of every axis, in the order of its kind's parameters.
    params: Vec<f64>,
    /// The forces of the last step (`dJointFeedback`: f1, t1, f2, t2, 4 reals each).
    feedback: Option<Vec<f64>>,
}

/// The exact state of a world (see the [module docs](self)).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub(crate) struct WorldState {
    gravity: Vector3<f64>,
    erp: f64,
    cfm: f64,
    stepper: Stepper,
    surface: ContactSurface,
    random_seed: std::ffi::c_ulong,
    time: f64,
    bodies: Vec<BodyState>,
    geoms: Vec<GeomState>,
    joints: Vec<JointState>,
    /// For each space (in creation order), its geoms (indices into `geoms`) in ODE's
    /// order.
    spaces: Vec<Vec<u32>>,
}

/// Each ODE id's place in `ids` (the world's objects in creation order), by address:
/// one look-up per id instead of a search, so that a restore stays linear in the
/// scene.
fn positions<T>(ids: impl Iterator<Item = *mut T>) -> std::collections::HashMap<usize, u32> {
    ids.enumerate().map(|(i, id)| (id as usize, i as u32)).collect()
}

/// `Error::SnapshotMismatch` with this detail.
fn mismatch(detail: String) -> Error {
    Error::SnapshotMismatch { detail }
}

/// `Error::SnapshotCorrupt` unless every number of `values` is finite and within `bound`.
fn within(what: &str, values: &[f64], bound: f64) -> Result<()> {
    match values.iter().find(|v| !v.is_finite() || v.abs() > bound) {
        Some(v) => Err(Error::SnapshotCorrupt { detail: format!("{what} holds {v}, beyond ±{bound}") }),
        None => Ok(()),
    }
}

impl WorldState {
    /// Every number of the state within what ODE takes: the limits the API holds
    /// bodies to, a unit quaternion, a positive mass, parameters that are not NaN.
    fn check_numbers(&self) -> Result<()> {
        use crate::limits::{MAX_ANGULAR_SPEED, MAX_COORDINATE, MAX_FORCE, MAX_SPEED, MAX_TORQUE};
        let corrupt = |detail: String| Error::SnapshotCorrupt { detail };
        within("the gravity", self.gravity.as_slice(), MAX_FORCE)?;
        within("the world's ERP, CFM and clock", &[self.erp, self.cfm, self.time], f64::MAX)?;
        let pose = |what: &str, p: &ExactPose| -> Result<()> {
            within(what, &p.position, MAX_COORDINATE)?;
            within(what, &p.rotation, 1.5)?;
            within(what, &p.quaternion, 1.5)?;
            let norm = p.quaternion.iter().map(|x| x * x).sum::<f64>().sqrt();
            if (norm - 1.0).abs() > 1e-6 {
                return Err(corrupt(format!("{what} has a quaternion of norm {norm}")));
            }
            Ok(())
        };
        for b in &self.bodies {
            pose("a body's pose", &b.pose)?;
            within("a body's velocity", &b.linear_velocity, MAX_SPEED)?;
            within("a body's angular velocity", &b.angular_velocity, MAX_ANGULAR_SPEED)?;
            within("a body's force", &b.force, MAX_FORCE)?;
            within("a body's torque", &b.torque, MAX_TORQUE)?;
            if b.mass.len() != 17 || b.mass[0].is_nan() || b.mass[0] <= 0.0 {
                return Err(corrupt("a body's mass is not a positive mass with its centre and inertia".into()));
            }
            within("a body's mass", &b.mass, f64::MAX)?;
        }
        for g in &self.geoms {
            for (p, r) in g.pose.iter().chain(&g.offset) {
                within("a geom's pose", p, MAX_COORDINATE)?;
                within("a geom's pose", r, 1.5)?;
            }
        }
        for j in &self.joints {
            pose("a joint's reference pose", &j.reference.body1)?;
            if let Some(p) = &j.reference.body2 {
                pose("a joint's reference pose", p)?;
            }
            if j.params.len() != j.kind.params().len() * j.kind.param_axes() || j.params.iter().any(|v| v.is_nan()) {
                return Err(corrupt("a joint's parameters are not the ones of its kind".into()));
            }
            if j.feedback.as_ref().is_some_and(|f| f.len() != 16) {
                return Err(corrupt("a joint's forces are not four vectors".into()));
            }
            j.kind.validate().map_err(|e| corrupt(format!("a joint's kind: {e}")))?;
        }
        Ok(())
    }
}

/// Puts a body back in its saved state: mass, kinematic flag, pose, velocities,
/// accumulators, enabled and gravity flags.
///
/// # Safety
/// `raw` is a live body.
unsafe fn restore_body(raw: ffi::dBodyID, s: &BodyState) {
    let mut mass = ffi::dMass::default();
    // SAFETY: the body is live; the mass was read from ODE (a valid dMass).
    unsafe {
        ffi::dBodyGetMass(raw, &mut mass);
        let now: Vec<f64> = std::iter::once(mass.mass).chain(mass.c).chain(mass.I).collect();
        if now.iter().zip(&s.mass).any(|(a, b)| a.to_bits() != b.to_bits()) {
            mass.mass = s.mass[0];
            mass.c.copy_from_slice(&s.mass[1..5]);
            mass.I.copy_from_slice(&s.mass[5..17]);
            ffi::dBodySetMass(raw, &mass);
        }
        if s.kinematic {
            ffi::dBodySetKinematic(raw);
        } else if ffi::dBodyIsKinematic(raw) != 0 {
            ffi::dBodySetDynamic(raw);
        }
        s.pose.put(raw);
        let (v, w, f, t) = (s.linear_velocity, s.angular_velocity, s.force, s.torque);
        ffi::dBodySetLinearVel(raw, v[0], v[1], v[2]);
        ffi::dBodySetAngularVel(raw, w[0], w[1], w[2]);
        ffi::dBodySetForce(raw, f[0], f[1], f[2]);
        ffi::dBodySetTorque(raw, t[0], t[1], t[2]);
        if s.enabled {
            ffi::dBodyEnable(raw)
        } else {
            ffi::dBodyDisable(raw)
        }
        ffi::dBodySetGravityMode(raw, s.gravity.into());
    }
}

/// Puts a geom back in its saved pose or offset, enabled flag and collision bits.
///
/// # Safety
/// `raw` is a live geom, of the kind and body its state was saved from.
unsafe fn restore_geom(raw: ffi::dGeomID, s: &GeomState) {
    // SAFETY: the geom is live; a pose is kept only for a placeable geom
    // without a body, an offset only for a geom on a body (checked to fit
    // above); dGeomSetRotation and dGeomSetOffsetRotation copy the matrix as
    // given.
    unsafe {
        if let Some((p, r)) = &s.pose {
            ffi::dGeomSetPosition(raw, p[0], p[1], p[2]);
            ffi::dGeomSetRotation(raw, r.as_ptr());
        }
        match &s.offset {
            Some((p, r)) => {
                ffi::dGeomSetOffsetPosition(raw, p[0], p[1], p[2]);
                ffi::dGeomSetOffsetRotation(raw, r.as_ptr());
            }
            None if s.body.is_some() && ffi::dGeomIsOffset(raw) != 0 => ffi::dGeomClearOffset(raw),
            None => {}
        }
        if s.enabled {
            ffi::dGeomEnable(raw)
        } else {
            ffi::dGeomDisable(raw)
        }
        ffi::dGeomSetCategoryBits(raw, s.category_bits);
        ffi::dGeomSetCollideBits(raw, s.collide_bits);
    }
}

/// Puts a space's geoms back in their saved order.
///
/// # Safety
/// `space` and every geom of `geoms` are live.
unsafe fn restore_space_order(space: ffi::dSpaceID, order: &[u32], geoms: &[ffi::dGeomID]) -> Result<()> {
    // Each geom taken out and put back at the front, last first: the space's
    // list comes out in the saved order.
    for &g in order.iter().rev() {
        let raw = *geoms
            .get(g as usize)
            .ok_or_else(|| Error::SnapshotCorrupt { detail: format!("a space lists geom {g}, of {}", geoms.len()) })?;
        // SAFETY: the space and the geom are live; the geom is in that space
        // (checked by ODE's own bookkeeping: dSpaceRemove of a geom of the
        // space, then dSpaceAdd of a geom in no space).
        unsafe {
            if ffi::dGeomGetSpace(raw) == space {
                ffi::dSpaceRemove(space, raw);
                ffi::dSpaceAdd(space, raw);
            }
        }
    }
    Ok(())
}

/// A body's pose, velocities, accumulators, mass and flags, for [`World::capture_state`].
fn body_state(b: &super::body::BodyData) -> BodyState {
    let mut mass = ffi::dMass::default();
    // SAFETY: every body in the arena is live; its state pointers too.
    unsafe {
        ffi::dBodyGetMass(b.raw, &mut mass);
        BodyState {
            pose: ExactPose::of(b.raw),
            linear_velocity: *b.state.linear_velocity,
            angular_velocity: *b.state.angular_velocity,
            force: *b.state.force,
            torque: *b.state.torque,
            mass: std::iter::once(mass.mass).chain(mass.c).chain(mass.I).collect(),
            enabled: ffi::dBodyIsEnabled(b.raw) != 0,
            kinematic: ffi::dBodyIsKinematic(b.raw) != 0,
            gravity: ffi::dBodyGetGravityMode(b.raw) != 0,
        }
    }
}

/// A geom's kind, body (by index), pose or offset and collision flags, for
/// [`World::capture_state`].
fn geom_state(g: &super::geom::GeomData, body_index: &impl Fn(ffi::dBodyID) -> Option<u32>) -> GeomState {
    let placeable = !matches!(g.shape, crate::shape::Shape::Plane { .. });
    // SAFETY: every geom in the arena is live; a placeable geom's position
    // and rotation pointers hold 3 and 12 reals.
    unsafe {
        GeomState {
            kind: g.shape.kind_name().to_string(),
            body: if g.body_raw.is_null() { None } else { body_index(g.body_raw) },
            pose: (placeable && g.body_raw.is_null()).then(|| {
                let mut p = [0.0; 3];
                let mut r = [0.0; 12];
                p.copy_from_slice(std::slice::from_raw_parts(ffi::dGeomGetPosition(g.raw), 3));
                r.copy_from_slice(std::slice::from_raw_parts(ffi::dGeomGetRotation(g.raw), 12));
                (p, r)
            }),
            offset: (!g.body_raw.is_null() && ffi::dGeomIsOffset(g.raw) != 0).then(|| {
                let mut p = [0.0; 3];
                let mut r = [0.0; 12];
                p.copy_from_slice(std::slice::from_raw_parts(ffi::dGeomGetOffsetPosition(g.raw), 3));
                r.copy_from_slice(std::slice::from_raw_parts(ffi::dGeomGetOffsetRotation(g.raw), 12));
                (p, r)
            }),
            enabled: ffi::dGeomIsEnabled(g.raw) != 0,
            category_bits: ffi::dGeomGetCategoryBits(g.raw),
            collide_bits: ffi::dGeomGetCollideBits(g.raw),
        }
    }
}

/// The geoms of a space, by their index in the captured state.
fn space_members(s: &super::SpaceData, geom_indices: &std::collections::HashMap<usize, u32>) -> Vec<u32> {
    // SAFETY: the space is live; indices below its count.
    let n = unsafe { ffi::dSpaceGetNumGeoms(s.raw) };
    (0..n)
        .filter_map(|i| {
            // SAFETY: as above.
            let g = unsafe { ffi::dSpaceGetGeom(s.raw, i) };
            geom_indices.get(&(g as usize)).copied()
        })
        .collect()
}

impl World {
    /// The next number in the world's creation order of bodies, geoms and joints.
    pub(crate) fn next_serial(&mut self) -> u64 {
        self.serials += 1;
        self.serials
    }

    /// The exact state of the world (see the [module docs](self)).
    pub(crate) fn capture_state(&self) -> WorldState {
        let mut bodies: Vec<_> = self.bodies.iter().collect();
        bodies.sort_by_key(|(_, b)| b.serial);
        let body_indices = positions(bodies.iter().map(|(_, b)| b.raw));
        let body_index = |raw: ffi::dBodyID| body_indices.get(&(raw as usize)).copied();
        let mut geoms: Vec<_> = self.geoms.iter().collect();
        geoms.sort_by_key(|(_, g)| g.serial);
        let mut joints: Vec<_> = self.joints.iter().collect();
        joints.sort_by_key(|(_, j)| j.serial);
        let body_states = bodies.iter().map(|(_, b)| body_state(b)).collect();
        let geom_states = geoms.iter().map(|(_, g)| geom_state(g, &body_index)).collect();
        let joint_states = joints.iter().map(|(h, j)| self.joint_state(*h, j, &body_index)).collect();
        let geom_indices = positions(geoms.iter().map(|(_, g)| g.raw));
        let spaces = self.spaces.values().map(|s| space_members(s, &geom_indices)).collect();
        WorldState {
            gravity: self.gravity(),
            erp: self.erp(),
            cfm: self.cfm(),
            stepper: self.stepper(),
            surface: self.default_surface(),
            random_seed: self.random_seed,
            time: self.time,
            bodies: body_states,
            geoms: geom_states,
            joints: joint_states,
            spaces,
        }
    }

    /// A joint's kind, bodies (by index) and every parameter, for [`World::capture_state`].
    fn joint_state(
        &self,
        handle: crate::handle::RawHandle,
        j: &super::joint::JointData,
        body_index: &impl Fn(ffi::dBodyID) -> Option<u32>,
    ) -> JointState {
        let joint = self.joint(crate::handle::JointHandle(handle)).expect("a joint of the arena");
        let params = (0..j.kind.param_axes())
            .flat_map(|axis| j.kind.params().iter().map(move |p| (axis, *p)))
            .map(|(axis, p)| joint.param(p, axis).expect("a parameter of the joint's kind"))
            .collect();
        let feedback = j.feedback.as_ref().map(|f| [f.f1, f.t1, f.f2, f.t2].concat());
        let index = |b: Option<crate::handle::BodyHandle>| {
            b.and_then(|b| self.bodies.get(b.0, "body").ok()).and_then(|d| body_index(d.raw))
        };
        JointState {
            kind: j.kind.clone(),
            body1: index(j.body1).expect("a joint has a first body"),
            body2: index(j.body2),
            reference: j.reference,
            params,
            feedback,
        }
    }

    /// Checks that `state` fits this world: the same bodies, geoms (kinds, bodies),
    /// joints (kinds, bodies) and spaces, created in the same order; and that its
    /// numbers are ones ODE can take (bytes that pass the checksum may still have been
    /// made by hand).
    pub(crate) fn check_state_fits(&self, state: &WorldState) -> Result<()> {
        state.check_numbers()?;
        let counts = [
            ("bodies", self.bodies.len(), state.bodies.len()),
            ("geoms", self.geoms.len(), state.geoms.len()),
            ("joints", self.joints.len(), state.joints.len()),
            ("spaces", self.spaces.len(), state.spaces.len()),
        ];
        for (what, here, there) in counts {
            if here != there {
                return Err(mismatch(format!("the snapshot's world has {there} {what}, this one {here}")));
            }
        }
        let mut geoms: Vec<_> = self.geoms.values().collect();
        geoms.sort_by_key(|g| g.serial);
        let mut bodies: Vec<_> = self.bodies.values().collect();
        bodies.sort_by_key(|b| b.serial);
        let body_indices = positions(bodies.iter().map(|b| b.raw));
        let body_index = |raw: ffi::dBodyID| body_indices.get(&(raw as usize)).copied();
        for (i, (g, s)) in geoms.iter().zip(&state.geoms).enumerate() {
            let body = if g.body_raw.is_null() { None } else { body_index(g.body_raw) };
            if g.shape.kind_name() != s.kind || body != s.body {
                return Err(mismatch(format!(
                    "geom {i} (in creation order) is a {} on body {body:?} here, a {} on body {:?} in the snapshot",
                    g.shape.kind_name(),
                    s.kind,
                    s.body
                )));
            }
        }
        let mut joints: Vec<_> = self.joints.values().collect();
        joints.sort_by_key(|j| j.serial);
        for (i, (j, s)) in joints.iter().zip(&state.joints).enumerate() {
            let index = |b: Option<crate::handle::BodyHandle>| {
                b.and_then(|b| self.bodies.get(b.0, "body").ok()).and_then(|d| body_index(d.raw))
            };
            if j.kind.name() != s.kind.name() || index(j.body1) != Some(s.body1) || index(j.body2) != s.body2 {
                return Err(mismatch(format!(
                    "joint {i} (in creation order) is {} joint here and {} joint in the snapshot, or joins other bodies",
                    crate::error::article(j.kind.name()),
                    crate::error::article(s.kind.name()),
                )));
            }
        }
        Ok(())
    }

    /// Puts the world in `state` (checked with [`World::check_state_fits`] first): every
    /// joint is made again where it was made, then every body, geom and space is put
    /// back (see the [module docs](self)).
    pub(crate) fn restore_state(&mut self, state: &WorldState) -> Result<()> {
        self.check_usable()?;
        self.check_state_fits(state)?;
        self.set_gravity(state.gravity)?;
        self.set_erp(state.erp)?;
        self.set_cfm(state.cfm)?;
        self.set_stepper(state.stepper)?;
        self.set_default_surface(state.surface)?;
        let mut bodies: Vec<_> = self.bodies.values().map(|b| (b.serial, b.raw)).collect();
        bodies.sort_unstable();
        let bodies: Vec<ffi::dBodyID> = bodies.into_iter().map(|(_, raw)| raw).collect();
        let mut joints: Vec<_> = self.joints.iter().map(|(h, j)| (j.serial, h)).collect();
        joints.sort_unstable_by_key(|(serial, _)| *serial);
        // No contact joint may hold on to a body while joints are made again.
        self.clear_contacts();
        for ((_, h), s) in joints.iter().zip(&state.joints) {
            self.restore_joint(*h, s, &bodies)?;
        }
        for (raw, s) in bodies.iter().zip(&state.bodies) {
            // SAFETY: the bodies of this world, live.
            unsafe { restore_body(*raw, s) };
        }
        let mut geoms: Vec<_> =
            self.geoms.values().map(|g| (g.serial, g.raw, self.space_data(g.space).map(|s| s.raw))).collect::<Vec<_>>();
        geoms.sort_unstable_by_key(|(serial, ..)| *serial);
        for ((_, raw, space), s) in geoms.iter().zip(&state.geoms) {
            // SAFETY: the geoms of this world, live, checked to fit their states above;
            // their spaces live (a geom's space outlives it); no collision under way.
            unsafe {
                restore_geom(*raw, s);
                if let Ok(space) = space {
                    super::geom::keep_in_space(*raw, *space);
                }
            }
        }
        let geoms: Vec<ffi::dGeomID> = geoms.into_iter().map(|(_, raw, _)| raw).collect();
        let spaces: Vec<ffi::dSpaceID> = self.spaces.values().map(|s| s.raw).collect();
        for (space, order) in spaces.iter().zip(&state.spaces) {
            // SAFETY: the spaces and geoms of this world, live.
            unsafe { restore_space_order(*space, order, &geoms)? };
        }
        self.random_seed = state.random_seed;
        self.time = state.time;
        self.gate.forces_added = true;
        self.set_diverged(None);
        self.restored_coordinates();
        Ok(())
    }

    /// Makes a joint again from its saved state (its kind, bodies, parameters and
    /// feedback), in place of the live one.
    fn restore_joint(
        &mut self,
        handle: crate::handle::RawHandle,
        s: &JointState,
        bodies: &[ffi::dBodyID],
    ) -> Result<()> {
        let b1 = bodies[s.body1 as usize];
        let b2 = s.body2.map_or(std::ptr::null_mut(), |b| bodies[b as usize]);
        let data = self.joints.get_mut(handle, "joint")?;
        // SAFETY: the joint is live and destroyed once here; its bodies are live
        // bodies of this world (checked to fit above); the kind was validated when
        // it was first made; the feedback buffer outlives the new joint (it stays
        // in the joint's data).
        unsafe {
            ffi::dJointDestroy(data.raw);
            s.reference.body1.put(b1);
            if let Some(p) = &s.reference.body2 {
                p.put(b2);
            }
            data.raw = create_ode_joint(self.raw, &s.kind, b1, b2);
            let axes = s.kind.param_axes();
            let mut values = s.params.iter();
            for axis in 0..axes {
                for &p in s.kind.params() {
                    if let Some(v) = values.next() {
                        set_raw_param(data.raw, &s.kind, p, axis, *v);
                    }
                }
            }
            if let Some(f) = data.feedback.as_mut() {
                ffi::dJointSetFeedback(data.raw, &mut **f);
                if let Some(saved) = &s.feedback {
                    for (dst, src) in [&mut f.f1, &mut f.t1, &mut f.f2, &mut f.t2].into_iter().zip(saved.chunks(4)) {
                        dst.copy_from_slice(src);
                    }
                }
            }
        }
        data.kind = s.kind.clone();
        data.reference = s.reference;
        Ok(())
    }
}
