//! Two hull geoms (ode-sys's `hull.c`) collide as two plain ODE convexes of the same
//! arrays at the same poses, bit for bit, including the pairs whose bounding boxes
//! overlap while the hulls' own boxes lie apart (which the hull collider skips without
//! asking ODE's convex collider: that skip must never drop a point ODE would find).

use ars_core::Shape;
use nalgebra::{Point3, UnitQuaternion, Vector3};
use ode_sys as ffi;

/// A hull's arrays as ODE's convex takes them (planes, points, polygons).
struct Arrays {
    planes: Vec<f64>,
    points: Vec<f64>,
    polygons: Vec<u32>,
}

fn arrays(points: &[Point3<f64>]) -> Arrays {
    let Shape::ConvexHull { vertices, triangles } = Shape::convex_hull(points).unwrap() else {
        panic!("a hull");
    };
    let (mut planes, mut polygons) = (Vec::new(), Vec::new());
    for t in &triangles {
        let [a, b, c] = t.map(|k| vertices[k as usize].coords);
        let n = (b - a).cross(&(c - a)).normalize();
        planes.extend([n.x, n.y, n.z, n.dot(&a)]);
        polygons.extend([3, t[0], t[1], t[2]]);
    }
    Arrays { planes, points: vertices.iter().flat_map(|p| [p.x, p.y, p.z]).collect(), polygons }
}

/// A box of half-extents `h` (its hull is its own box: the tightest case for the
/// skip) and a squashed ball of 98 points (its box leaves room at the corners).
fn shapes() -> Vec<Arrays> {
    let h = [0.3, 0.1, 0.2];
    let corners: Vec<_> = (0..8)
        .map(|i| {
            let s = |bit: i32, e: f64| if i >> bit & 1 == 1 { e } else { -e };
            Point3::new(s(0, h[0]), s(1, h[1]), s(2, h[2]))
        })
        .collect();
    let mut ball = vec![Point3::new(0.0, 0.0, 0.15), Point3::new(0.0, 0.0, -0.15)];
    for i in 1..9 {
        let polar = std::f64::consts::PI * f64::from(i) / 9.0;
        for j in 0..12 {
            let azimuth = std::f64::consts::TAU * f64::from(j) / 12.0;
            ball.push(Point3::new(
                0.25 * polar.sin() * azimuth.cos(),
                0.1 * polar.sin() * azimuth.sin(),
                0.15 * polar.cos(),
            ));
        }
    }
    vec![arrays(&corners), arrays(&ball)]
}

/// xorshift64: the same poses on every run.
struct Random(u64);

impl Random {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
    fn rotation(&mut self) -> [f64; 12] {
        let axis = Vector3::new(self.next() - 0.5, self.next() - 0.5, self.next() - 0.5);
        let q = UnitQuaternion::from_scaled_axis(axis.normalize() * self.next() * std::f64::consts::TAU);
        let m = q.to_rotation_matrix().into_inner();
        let mut r = [0.0; 12];
        for i in 0..3 {
            for j in 0..3 {
                r[4 * i + j] = m[(i, j)];
            }
        }
        r
    }
}

fn place(g: ffi::dGeomID, p: [f64; 3], r: &[f64; 12]) {
    // SAFETY: `g` is a live geom; `r` is a dMatrix3 (12 reals).
    unsafe {
        ffi::dGeomSetPosition(g, p[0], p[1], p[2]);
        ffi::dGeomSetRotation(g, r.as_ptr());
    }
}

fn boxes_overlap(a: ffi::dGeomID, b: ffi::dGeomID) -> bool {
    let (mut x, mut y) = ([0.0; 6], [0.0; 6]);
    // SAFETY: live geoms; each buffer holds the six reals ODE writes.
    unsafe {
        ffi::dGeomGetAABB(a, x.as_mut_ptr());
        ffi::dGeomGetAABB(b, y.as_mut_ptr());
    }
    (0..3).all(|i| x[2 * i] <= y[2 * i + 1] && y[2 * i] <= x[2 * i + 1])
}

fn collide(a: ffi::dGeomID, b: ffi::dGeomID) -> Vec<ffi::dContactGeom> {
    let mut contacts = vec![ffi::dContactGeom::default(); 8];
    let size = std::mem::size_of::<ffi::dContactGeom>() as i32;
    // SAFETY: live geoms in no space; the buffer holds 8 contacts of `size` bytes.
    let n = unsafe { ffi::dCollide(a, b, 8, contacts.as_mut_ptr(), size) };
    contacts.truncate(n as usize);
    contacts
}

#[test]
fn hull_pairs_find_the_points_of_odes_own_convexes_bit_for_bit_and_none_where_their_boxes_lie_apart() {
    // SAFETY: ODE set up once for this test binary; the hull class registered once
    // ODE is (what ars-core's own set-up does).
    unsafe {
        ffi::dInitODE2(0);
        assert!(ffi::odesys_hull_register() >= 0);
    }
    let shapes = shapes();
    let make = |s: &Arrays| {
        // SAFETY: the arrays describe a valid hull (`planes.len() / 4` planes, as many
        // polygons, `points.len() / 3` points) and outlive the geoms (destroyed below).
        unsafe {
            let (planes, points) = ((s.planes.len() / 4) as u32, (s.points.len() / 3) as u32);
            let (none, arrays) = (std::ptr::null_mut(), (s.planes.as_ptr(), s.points.as_ptr(), s.polygons.as_ptr()));
            let hull = ffi::odesys_hull_create(none, arrays.0, planes, arrays.1, points, arrays.2);
            let convex = ffi::dCreateConvex(none, arrays.0, planes, arrays.1, points, arrays.2);
            (hull, convex)
        }
    };
    let made: Vec<_> = shapes.iter().map(make).collect();
    let twins: Vec<_> = shapes.iter().map(make).collect();
    // SAFETY: plain ODE geoms of valid sizes, in no space (destroyed below).
    let primitives = unsafe {
        [
            ffi::dCreateBox(std::ptr::null_mut(), 0.4, 0.2, 0.3),
            ffi::dCreateSphere(std::ptr::null_mut(), 0.12),
            ffi::dCreateCapsule(std::ptr::null_mut(), 0.05, 0.3),
            ffi::dCreateCylinder(std::ptr::null_mut(), 0.1, 0.25),
        ]
    };
    // The second of a pair: another hull (its own twin convex), or a primitive (the
    // same geom on both sides).
    let others: Vec<(ffi::dGeomID, ffi::dGeomID)> =
        twins.iter().copied().chain(primitives.iter().map(|&g| (g, g))).collect();
    let mut random = Random(0x9e37_79b9_7f4a_7c15);
    let bits = |c: &ffi::dContactGeom| {
        (c.pos.map(f64::to_bits), c.normal.map(f64::to_bits), c.depth.to_bits(), c.side1, c.side2)
    };
    for (i, &(hull_a, convex_a)) in made.iter().enumerate() {
        for (j, &(geom_b, twin_b)) in others.iter().enumerate() {
            let (mut touching, mut apart_in_overlapping_boxes) = (0, 0);
            for _ in 0..1500 {
                let (ra, rb) = (random.rotation(), random.rotation());
                let pa = [random.next() * 0.1, random.next() * 0.1, random.next() * 0.1];
                let pb = [random.next() * 0.7 - 0.35, random.next() * 0.7 - 0.35, random.next() * 0.7 - 0.35];
                for (g, p, r) in [(hull_a, pa, &ra), (convex_a, pa, &ra), (geom_b, pb, &rb), (twin_b, pb, &rb)] {
                    place(g, p, r);
                }
                // Either way round, as a space may report the pair.
                for (hulls, convexes) in
                    [((hull_a, geom_b), (convex_a, twin_b)), ((geom_b, hull_a), (twin_b, convex_a))]
                {
                    let (by_hulls, by_convexes) = (collide(hulls.0, hulls.1), collide(convexes.0, convexes.1));
                    assert_eq!(by_hulls.len(), by_convexes.len(), "pair {i}-{j} at {pa:?} {pb:?}");
                    for (h, c) in by_hulls.iter().zip(&by_convexes) {
                        assert_eq!(bits(h), bits(c), "pair {i}-{j} at {pa:?} {pb:?}");
                        assert_eq!((h.g1, h.g2), hulls);
                    }
                    if by_hulls.is_empty() && boxes_overlap(hull_a, geom_b) {
                        apart_in_overlapping_boxes += 1;
                    } else if !by_hulls.is_empty() {
                        touching += 1;
                    }
                }
            }
            // Both kinds of pair were met many times.
            assert!(touching > 300, "pair {i}-{j}: {touching} touching");
            assert!(
                apart_in_overlapping_boxes > 300,
                "pair {i}-{j}: {apart_in_overlapping_boxes} apart with overlapping boxes"
            );
        }
    }
    for g in made.into_iter().chain(twins).flat_map(|(h, c)| [h, c]).chain(primitives) {
        // SAFETY: geoms made above, in no space, used no more.
        unsafe { ffi::dGeomDestroy(g) };
    }
}
