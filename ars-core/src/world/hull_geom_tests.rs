//! The hull geom of ode-sys (`hull.c`) against ODE's plain convex: its bounding box holds
//! the hull however it turns, and it collides with every kind of geom exactly as a
//! plain `dConvex` of the same arrays at the same pose does.

use nalgebra::{Point3, UnitQuaternion, Vector3};
use ode_sys as ffi;

use super::ConvexStorage;
use crate::convert;
use crate::init::{ensure_ode_ready, lock_ode_global_state};
use crate::shape::Shape;

/// A deterministic sequence of numbers in [0, 1) (no random crate in ars-core).
struct Sequence(u64);

impl Sequence {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
    fn rotation(&mut self) -> UnitQuaternion<f64> {
        let axis = Vector3::new(self.next() - 0.5, self.next() - 0.5, self.next() - 0.5);
        UnitQuaternion::from_scaled_axis(axis.normalize() * (self.next() * 2.0 * std::f64::consts::PI))
    }
}

/// An irregular hull: a squashed, offset blob of 60 points (its centre of volume is
/// not its origin, its box not a cube).
fn blob() -> Shape {
    let mut s = Sequence(7);
    let points: Vec<Point3<f64>> = (0..60)
        .map(|_| {
            let d = Vector3::new(s.next() - 0.5, s.next() - 0.5, s.next() - 0.5).normalize();
            Point3::new(0.02 + 0.09 * d.x, -0.01 + 0.05 * d.y, 0.03 + 0.03 * d.z)
        })
        .collect();
    Shape::convex_hull(&points).expect("a hull of 60 points on an ellipsoid")
}

/// The two geoms of one hull: the hull geom, and ODE's plain convex of the same arrays.
struct Pair {
    hull: ffi::dGeomID,
    plain: ffi::dGeomID,
    _storage: ConvexStorage,
}

impl Pair {
    fn new(shape: &Shape) -> Pair {
        ensure_ode_ready();
        let Shape::ConvexHull { vertices, triangles } = shape else { panic!("a hull") };
        let (storage, _centre) = ConvexStorage::build(vertices, triangles);
        // SAFETY: ODE is ready; both geoms are destroyed (Drop) before the arrays.
        let (hull, plain) = unsafe {
            let hull = storage.create(std::ptr::null_mut());
            let plain = ffi::dCreateConvex(
                std::ptr::null_mut(),
                storage._planes.as_ptr(),
                (storage._planes.len() / 4) as u32,
                storage._points.as_ptr(),
                (storage._points.len() / 3) as u32,
                storage._polygons.as_ptr(),
            );
            (hull, plain)
        };
        assert!(!hull.is_null());
        Pair { hull, plain, _storage: storage }
    }

    /// Both geoms at `p`, turned by `q` (ODE's pose of the geom).
    fn place(&self, p: Vector3<f64>, q: &UnitQuaternion<f64>) {
        let q = convert::quaternion_to_ode(q);
        for g in [self.hull, self.plain] {
            // SAFETY: the geom is live and placeable; `q` is a dQuaternion.
            unsafe {
                ffi::dGeomSetPosition(g, p.x, p.y, p.z);
                ffi::dGeomSetQuaternion(g, q.as_ptr());
            }
        }
    }
}

impl Drop for Pair {
    fn drop(&mut self) {
        // SAFETY: both geoms are live, in no space, destroyed once, before the arrays.
        unsafe {
            ffi::dGeomDestroy(self.hull);
            ffi::dGeomDestroy(self.plain);
        }
    }
}

/// A geom's bounding box, brought up to date as a space does before colliding.
fn aabb(g: ffi::dGeomID) -> [f64; 6] {
    let mut a = [0.0; 6];
    // SAFETY: the geom is live; `a` holds 6 reals.
    unsafe { ffi::dGeomGetAABB(g, a.as_mut_ptr()) };
    a
}

#[test]
fn a_hull_geoms_box_holds_the_hull_and_odes_box_for_any_rotation() {
    let shape = blob();
    let pair = Pair::new(&shape);
    let radius = {
        let Shape::ConvexHull { vertices, .. } = &shape else { unreachable!() };
        let (lo, hi) = vertices.iter().fold((Vector3::repeat(f64::MAX), Vector3::repeat(f64::MIN)), |(lo, hi), v| {
            (lo.inf(&v.coords), hi.sup(&v.coords))
        });
        (hi - lo).norm() / 2.0
    };
    let mut s = Sequence(11);
    for k in 0..500 {
        // Quarter turns first, where the turned box is the hull's own box: tight.
        let q = match k {
            0..8 => UnitQuaternion::from_scaled_axis(Vector3::ith(k % 3, std::f64::consts::FRAC_PI_2 * (k / 3) as f64)),
            _ => s.rotation(),
        };
        let p = Vector3::new(s.next() - 0.5, s.next() - 0.5, s.next() - 0.5) * 200.0;
        pair.place(p, &q);
        let (hull, plain) = (aabb(pair.hull), aabb(pair.plain));
        for axis in 0..3 {
            let (lo, hi) = (2 * axis, 2 * axis + 1);
            assert!(hull[lo] <= plain[lo] && plain[hi] <= hull[hi], "axis {axis}: {hull:?} holds not {plain:?}");
            // Never wider than the sphere about the hull's box (plus the slack).
            assert!(hull[hi] - hull[lo] <= 2.0 * radius * (1.0 + 1e-9) + 1e-9, "axis {axis}: {hull:?}");
        }
    }
}

/// What dCollide gives: each point's position, normal and depth as exact bits, and
/// its two geoms, each plain convex in `as_hulls` named as the hull geom it stands for.
fn collide(
    o1: ffi::dGeomID,
    o2: ffi::dGeomID,
    as_hulls: &[(ffi::dGeomID, ffi::dGeomID)],
) -> Vec<(Vec<u64>, [usize; 2])> {
    for g in [o1, o2] {
        aabb(g);
    }
    let mut contacts = vec![ffi::dContactGeom::default(); 16];
    // SAFETY: both geoms are live; room for 16 points of stride dContactGeom.
    let n = unsafe { ffi::dCollide(o1, o2, 16, contacts.as_mut_ptr(), size_of::<ffi::dContactGeom>() as i32) };
    let name = |g: ffi::dGeomID| as_hulls.iter().find(|(plain, _)| *plain == g).map_or(g, |(_, hull)| *hull) as usize;
    contacts[..n as usize]
        .iter()
        .map(|c| {
            let bits = c.pos[..3].iter().chain(&c.normal[..3]).chain([&c.depth]).map(|x| x.to_bits()).collect();
            (bits, [name(c.g1), name(c.g2)])
        })
        .collect()
}

/// Every kind of geom ODE collides a convex with, in no space, near the origin.
struct Others {
    geoms: Vec<(&'static str, ffi::dGeomID)>,
    _mesh: super::TriMeshStorage,
    heightfield: ffi::dHeightfieldDataID,
    _heights: Vec<f64>,
    _blob: Pair,
}

impl Others {
    fn new() -> Others {
        ensure_ode_ready();
        let (vertices, triangles) = crate::shape::cone_mesh(0.08, 0.1);
        let mesh = super::TriMeshStorage::build(&vertices, &triangles);
        let heights: Vec<f64> = (0..36).map(|k| 0.01 * ((k * 7 % 5) as f64)).collect();
        let blob = Pair::new(&blob());
        // SAFETY: ODE is ready; every geom is made in no space and destroyed in Drop,
        // the mesh and heightfield data after their geoms; the heights outlive them.
        let (geoms, heightfield) = unsafe {
            let null = std::ptr::null_mut();
            let heightfield = ffi::dGeomHeightfieldDataCreate();
            ffi::dGeomHeightfieldDataBuildDouble(heightfield, heights.as_ptr(), 0, 0.3, 0.3, 6, 6, 1.0, 0.0, 0.0, 0);
            let geoms = vec![
                ("plane", ffi::dCreatePlane(null, 0.0, 0.0, 1.0, -0.02)),
                ("box", ffi::dCreateBox(null, 0.1, 0.08, 0.06)),
                ("sphere", ffi::dCreateSphere(null, 0.05)),
                ("capsule", ffi::dCreateCapsule(null, 0.03, 0.1)),
                ("cylinder", ffi::dCreateCylinder(null, 0.04, 0.1)),
                ("hull", blob.hull),
                ("trimesh", ffi::dCreateTriMesh(null, mesh.data, None, None, None)),
                ("heightfield", ffi::dCreateHeightfield(null, heightfield, 1)),
                ("ray", ffi::dCreateRay(null, 0.5)),
            ];
            (geoms, heightfield)
        };
        Others { geoms, _mesh: mesh, heightfield, _heights: heights, _blob: blob }
    }
}

impl Drop for Others {
    fn drop(&mut self) {
        // SAFETY: each geom is live and destroyed once (the blob's by its Pair), the
        // heightfield's data after its geom.
        unsafe {
            for &(name, g) in &self.geoms {
                if name != "hull" {
                    ffi::dGeomDestroy(g);
                }
            }
            ffi::dGeomHeightfieldDataDestroy(self.heightfield);
        }
    }
}

#[test]
fn a_hull_geom_collides_with_every_shape_as_odes_convex_does() {
    let _lock = lock_ode_global_state(); // the trimesh collider's cache
    let pair = Pair::new(&blob());
    let others = Others::new();
    let mut s = Sequence(3);
    for &(name, other) in &others.geoms {
        // The plain counterpart of `other`: itself, or for the hull, the blob's convex.
        let plain_other = if name == "hull" { others._blob.plain } else { other };
        let as_hulls = [(pair.plain, pair.hull), (others._blob.plain, others._blob.hull)];
        let mut touching = 0;
        for pose in 0..6 {
            pair.place(Vector3::new(s.next() - 0.5, s.next() - 0.5, s.next() - 0.5) * 0.06, &s.rotation());
            if name == "hull" {
                others._blob.place(Vector3::new(-0.02 * pose as f64, 0.01, -0.03), &s.rotation());
            } else if name != "plane" && name != "heightfield" {
                let p = [-0.02 * pose as f64, 0.01, -0.03];
                let q = convert::quaternion_to_ode(&s.rotation());
                // SAFETY: the geom is live and placeable (not the plane or heightfield).
                unsafe {
                    ffi::dGeomSetPosition(other, p[0], p[1], p[2]);
                    ffi::dGeomSetQuaternion(other, q.as_ptr());
                }
            }
            let via_hull = collide(pair.hull, other, &as_hulls);
            assert_eq!(via_hull, collide(pair.plain, plain_other, &as_hulls), "{name}, pose {pose}");
            let reversed = collide(other, pair.hull, &as_hulls);
            assert_eq!(reversed, collide(plain_other, pair.plain, &as_hulls), "{name} first, pose {pose}");
            touching += usize::from(!via_hull.is_empty());
        }
        assert!(touching >= 2, "{name}: {touching} of 6 poses touch; the test would prove little");
    }
}
