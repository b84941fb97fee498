//! Which pairs of geoms the collision hands to ODE's colliders: not two static geoms,
//! not two bodies joined by a joint, not two rays (`pair_may_touch`); not a plane and a
//! geom whose box lies wholly above it (`above_plane`; a simple space leaves those out
//! before the near callback, `simple_space.c`); and never a pair of cylinders and
//! capsules whose sizes are too far apart for libccd to finish (`convex_pair_ratio`,
//! with `ConvexSizes` telling the plain collision in C when no pair can be).

use ode_sys as ffi;

/// For the pairs that ODE collides with libccd (cylinder–cylinder, capsule–cylinder):
/// the ratio of their largest to their smallest dimension.
#[inline]
pub(super) fn convex_pair_ratio(a: &crate::shape::Shape, b: &crate::shape::Shape) -> Option<f64> {
    use crate::shape::Shape::{Capsule, Cylinder};
    let dims = |s: &crate::shape::Shape| match *s {
        Cylinder { radius, length } | Capsule { radius, length } => Some((radius, length)),
        _ => None,
    };
    let cylinder = |s: &crate::shape::Shape| matches!(s, Cylinder { .. });
    if !(cylinder(a) || cylinder(b)) {
        return None;
    }
    let ((r1, l1), (r2, l2)) = (dims(a)?, dims(b)?);
    let max = r1.max(l1).max(r2).max(l2);
    let min = r1.min(l1).min(r2).min(l2);
    Some(max / min)
}

/// The sizes of a world's cylinders and capsules, for the plain collision: while the
/// largest over the smallest of them is within
/// [`MAX_CONVEX_PAIR_RATIO`](crate::limits::MAX_CONVEX_PAIR_RATIO), no pair of them can
/// be refused by [`convex_pair_ratio`]'s check. A bound: it never shrinks.
pub(crate) struct ConvexSizes {
    /// Whether the world has had a cylinder (the check is for pairs with one).
    cylinders: bool,
    smallest: f64,
    largest: f64,
}

impl Default for ConvexSizes {
    fn default() -> Self {
        ConvexSizes { cylinders: false, smallest: f64::INFINITY, largest: 0.0 }
    }
}

impl ConvexSizes {
    /// A geom of this shape is added.
    pub(crate) fn note(&mut self, shape: &crate::shape::Shape) {
        use crate::shape::Shape::{Capsule, Cylinder};
        if let Cylinder { radius, length } | Capsule { radius, length } = *shape {
            self.cylinders |= matches!(shape, Cylinder { .. });
            self.smallest = self.smallest.min(radius).min(length);
            self.largest = self.largest.max(radius).max(length);
        }
    }

    /// No pair can exceed the ratio (division is monotone: a pair's ratio is at most
    /// this one).
    #[inline]
    pub(crate) fn all_pairs_fine(&self) -> bool {
        !self.cylinders || self.largest / self.smallest <= crate::limits::MAX_CONVEX_PAIR_RATIO
    }
}

/// Whether a pair can make contacts or ray hits: not two static geoms, not two
/// bodies joined by a joint, not two rays.
///
/// # Safety
/// `b1` and `b2` are live bodies or null.
#[inline]
pub(super) unsafe fn pair_may_touch(b1: ffi::dBodyID, b2: ffi::dBodyID, ray1: bool, ray2: bool) -> bool {
    if b1.is_null() && b2.is_null() && !ray1 && !ray2 {
        // Two static geoms (a static box on the floor): contact joints between no
        // bodies would change nothing and cost a collision every step.
        return false;
    }
    if !b1.is_null() && !b2.is_null() {
        // SAFETY: both bodies are live (the caller's contract) and non-null (ODE
        // asserts on null).
        let connected = unsafe { ffi::dAreConnectedExcluding(b1, b2, ffi::dJointType_dJointTypeContact as i32) };
        if connected != 0 {
            return false;
        }
    }
    if ray1 && ray2 {
        return false;
    }
    true
}

/// Whether `plane` is a plane and `other`'s bounding box lies wholly on its open side,
/// where no collider of ODE's finds a point (each reports only depths ≥ 0): a robot's
/// links above the floor then cost no pass over their hulls' vertices each step.
/// Nothing else changes: those pairs made no contact.
///
/// # Safety
/// Both geoms are live.
#[inline]
pub(super) unsafe fn above_plane(plane: ffi::dGeomID, shape: &crate::shape::Shape, other: ffi::dGeomID) -> bool {
    if !matches!(shape, crate::shape::Shape::Plane { .. }) {
        return false;
    }
    let (mut p, mut b) = ([0.0; 4], [0.0; 6]);
    // SAFETY: `plane` is a live plane geom and `other` a live geom (the caller's
    // contract); both buffers are as long as ODE writes, and as the test reads (the
    // simple space's own, one definition for both).
    unsafe {
        ffi::dGeomPlaneGetParams(plane, p.as_mut_ptr());
        ffi::dGeomGetAABB(other, b.as_mut_ptr());
        ffi::odesys_box_above_plane(p.as_ptr(), b.as_ptr()) != 0
    }
}
