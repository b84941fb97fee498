//! Shapes as the browser replay draws them: triangles with normals, made here once
//! for every shape. The player (`player.js`) only uploads and draws them.

use std::collections::HashMap;
use std::f64::consts::{FRAC_PI_2, PI};

use ars_core::Shape;
use ars_core::nalgebra::{Point3, Vector3};

use crate::look::PLANE_HALF_SIZE;

/// Segments around a round shape (sphere, capsule, cylinder, cone).
const SEGMENTS: usize = 32;
/// Steps of a sphere's profile from pole to pole (a capsule's cap takes half as many).
const SPHERE_STEPS: usize = 16;
/// The radius of the dot drawn for a shape with no surface (a ray's origin), m: what
/// the window draws for it.
const DOT_RADIUS: f64 = 0.05;

/// A shape's surface in its own frame: vertices with normals, and triangles.
#[derive(Clone, Debug, Default)]
pub(super) struct Triangles {
    /// Vertex positions, m.
    pub(super) positions: Vec<[f32; 3]>,
    /// Unit normals, one a vertex (zero for the corners of a degenerate mesh triangle).
    pub(super) normals: Vec<[f32; 3]>,
    /// Vertex indices, three a triangle, counter-clockwise seen from outside.
    pub(super) indices: Vec<[u32; 3]>,
}

impl Triangles {
    /// Appends a vertex; returns its index.
    fn vertex(&mut self, position: Vector3<f64>, normal: Vector3<f64>) -> u32 {
        let index = self.positions.len() as u32;
        self.positions.push(position.map(|v| v as f32).into());
        self.normals.push(normal.map(|v| v as f32).into());
        index
    }

    /// A flat quadrilateral `a b c d` (counter-clockwise seen from outside) as two
    /// triangles, `a b c` and `a c d`.
    fn quad(&mut self, corners: [Vector3<f64>; 4], normal: Vector3<f64>) {
        let [a, b, c, d] = corners.map(|p| self.vertex(p, normal));
        self.indices.push([a, b, c]);
        self.indices.push([a, c, d]);
    }
}

/// `shape`'s triangles: round shapes [`SEGMENTS`] around with smooth normals (a
/// sphere in [`SPHERE_STEPS`] rings, a capsule's caps in half as many each), a box's
/// six faces, a plane as a square of half side [`PLANE_HALF_SIZE`] centred where it
/// meets its normal, a mesh's own triangles with their face normals; a shape with no
/// surface (a ray) as a small sphere at its origin.
pub(super) fn tessellate(shape: &Shape) -> Triangles {
    let mut t = Triangles::default();
    match shape {
        Shape::Sphere { radius } => revolve(&mut t, &arc(*radius, 0.0, -FRAC_PI_2, FRAC_PI_2, SPHERE_STEPS)),
        Shape::Capsule { radius, length } => {
            let h = length / 2.0;
            let mut profile = arc(*radius, -h, -FRAC_PI_2, 0.0, SPHERE_STEPS / 2);
            profile.extend(arc(*radius, h, 0.0, FRAC_PI_2, SPHERE_STEPS / 2));
            revolve(&mut t, &profile);
        }
        Shape::Cylinder { radius: r, length } => {
            let h = length / 2.0;
            revolve(&mut t, &[[0.0, -h, 0.0, -1.0], [*r, -h, 0.0, -1.0]]);
            revolve(&mut t, &[[*r, -h, 1.0, 0.0], [*r, h, 1.0, 0.0]]);
            revolve(&mut t, &[[*r, h, 0.0, 1.0], [0.0, h, 0.0, 1.0]]);
        }
        Shape::Cone { radius: r, height: h } => {
            // The origin is the centre of mass, a quarter of the height above the base.
            // The side's normals are horizontal, as the player has always lit it: the
            // slope's true normals light it brighter, further from kiss3d's cone (the
            // off-screen renderer's), which is darker still.
            revolve(&mut t, &[[0.0, -h / 4.0, 0.0, -1.0], [*r, -h / 4.0, 0.0, -1.0]]);
            revolve(&mut t, &[[*r, -h / 4.0, 1.0, 0.0], [0.0, 3.0 * h / 4.0, 1.0, 0.0]]);
        }
        Shape::Box { edges } => cuboid(&mut t, edges / 2.0),
        Shape::Plane { normal, distance } => plane(&mut t, normal, *distance),
        Shape::TriMesh { vertices, triangles } | Shape::ConvexHull { vertices, triangles } => {
            mesh(&mut t, vertices, triangles)
        }
        _ => return tessellate(&Shape::Sphere { radius: DOT_RADIUS }),
    }
    t
}

/// A surface of revolution about Z, [`SEGMENTS`] around: profile points `[radius, z,
/// the normal's radial part, the normal's z]`, bottom to top. A point on the axis
/// (radius 0) makes no degenerate triangles, only those towards its neighbour ring.
fn revolve(t: &mut Triangles, profile: &[[f64; 4]]) {
    let first = t.positions.len();
    for &[r, z, nr, nz] in profile {
        for i in 0..SEGMENTS {
            let (s, c) = (2.0 * PI * i as f64 / SEGMENTS as f64).sin_cos();
            t.vertex(Vector3::new(r * c, r * s, z), Vector3::new(nr * c, nr * s, nz));
        }
    }
    let at = |ring: usize, i: usize| (first + ring * SEGMENTS + i % SEGMENTS) as u32;
    for (j, rings) in profile.windows(2).enumerate() {
        for i in 0..SEGMENTS {
            let [a, b, c, d] = [at(j, i), at(j, i + 1), at(j + 1, i + 1), at(j + 1, i)];
            if rings[0][0] != 0.0 {
                t.indices.push([a, b, c]);
            }
            if rings[1][0] != 0.0 {
                t.indices.push([a, c, d]);
            }
        }
    }
}

/// Profile points (as [`revolve`] takes them) on a circle of radius `r` centred on the
/// axis at height `zc`, from latitude `from` to `to` (rad) in `steps` steps; the poles
/// lie on the axis exactly.
fn arc(r: f64, zc: f64, from: f64, to: f64, steps: usize) -> Vec<[f64; 4]> {
    (0..=steps)
        .map(|i| {
            let (s, c) = (from + (to - from) * i as f64 / steps as f64).sin_cos();
            let c = if c.abs() < 1e-12 { 0.0 } else { c };
            [r * c, zc + r * s, c, s]
        })
        .collect()
}

/// A box of these half edges: six faces of two triangles, flat normals.
fn cuboid(t: &mut Triangles, half: Vector3<f64>) {
    const FACES: [[[f64; 3]; 4]; 6] = [
        [[1.0, -1.0, -1.0], [1.0, 1.0, -1.0], [1.0, 1.0, 1.0], [1.0, -1.0, 1.0]],
        [[-1.0, -1.0, -1.0], [-1.0, -1.0, 1.0], [-1.0, 1.0, 1.0], [-1.0, 1.0, -1.0]],
        [[-1.0, 1.0, -1.0], [-1.0, 1.0, 1.0], [1.0, 1.0, 1.0], [1.0, 1.0, -1.0]],
        [[-1.0, -1.0, -1.0], [1.0, -1.0, -1.0], [1.0, -1.0, 1.0], [-1.0, -1.0, 1.0]],
        [[-1.0, -1.0, 1.0], [1.0, -1.0, 1.0], [1.0, 1.0, 1.0], [-1.0, 1.0, 1.0]],
        [[-1.0, -1.0, -1.0], [-1.0, 1.0, -1.0], [1.0, 1.0, -1.0], [1.0, -1.0, -1.0]],
    ];
    for face in FACES {
        let corners = face.map(|c| Vector3::from(c).component_mul(&half));
        t.quad(corners, face_normal(&corners[0], &corners[1], &corners[2]));
    }
}

/// The plane `normal · x = distance` as a square of half side [`PLANE_HALF_SIZE`]
/// centred where it meets its normal.
fn plane(t: &mut Triangles, normal: &Vector3<f64>, distance: f64) {
    let n = normal.try_normalize(0.0).unwrap_or_else(Vector3::zeros);
    let helper = if n.y.abs() < 0.9 { Vector3::y() } else { Vector3::x() };
    let u = helper.cross(&n).try_normalize(0.0).unwrap_or_else(Vector3::zeros);
    let v = n.cross(&u);
    let (origin, s) = (n * distance, f64::from(PLANE_HALF_SIZE));
    let at = |i: f64, j: f64| origin + (u * i + v * j) * s;
    t.quad([at(-1.0, -1.0), at(1.0, -1.0), at(1.0, 1.0), at(-1.0, 1.0)], n);
}

/// A mesh's own triangles, in order, each with its face normal (flat shading); corners
/// equal in position and normal are one vertex (a flat region's triangles share
/// theirs). A triangle naming a vertex the mesh lacks is left out.
fn mesh(t: &mut Triangles, vertices: &[Point3<f64>], triangles: &[[u32; 3]]) {
    let mut known: HashMap<([u32; 3], [u32; 3]), u32> = HashMap::new();
    for triangle in triangles {
        let [Some(a), Some(b), Some(c)] = triangle.map(|i| vertices.get(i as usize).map(|p| p.coords)) else {
            continue;
        };
        let normal = face_normal(&a, &b, &c);
        let corners = [a, b, c].map(|p| {
            let key = (p.map(|v| (v as f32).to_bits()).into(), normal.map(|v| (v as f32).to_bits()).into());
            *known.entry(key).or_insert_with(|| t.vertex(p, normal))
        });
        t.indices.push(corners);
    }
}

/// The unit normal of the triangle `a b c` (counter-clockwise seen from its front);
/// zero if it has no area.
fn face_normal(a: &Vector3<f64>, b: &Vector3<f64>, c: &Vector3<f64>) -> Vector3<f64> {
    (b - a).cross(&(c - a)).try_normalize(0.0).unwrap_or_else(Vector3::zeros)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(t: &Triangles, i: u32) -> (Vector3<f64>, Vector3<f64>) {
        let (p, n) = (t.positions[i as usize], t.normals[i as usize]);
        (Vector3::from(p).cast(), Vector3::from(n).cast())
    }

    /// The volume the triangles enclose (the divergence theorem; outward triangles
    /// count positive).
    fn enclosed_volume(t: &Triangles) -> f64 {
        t.indices.iter().map(|[a, b, c]| at(t, *a).0.dot(&at(t, *b).0.cross(&at(t, *c).0)) / 6.0).sum()
    }

    #[test]
    fn solid_shapes_face_outward_with_smooth_or_flat_normals_and_enclose_their_volume() {
        let shapes = [
            Shape::Sphere { radius: 0.3 },
            Shape::Capsule { radius: 0.1, length: 0.4 },
            Shape::Cylinder { radius: 0.15, length: 0.3 },
            Shape::Cone { radius: 0.12, height: 0.3 },
            Shape::Box { edges: Vector3::new(0.8, 0.08, 0.2) },
        ];
        for shape in shapes {
            let t = tessellate(&shape);
            assert_eq!(t.positions.len(), t.normals.len());
            for &[a, b, c] in &t.indices {
                let [(pa, _), (pb, _), (pc, _)] = [a, b, c].map(|i| at(&t, i));
                let face = (pb - pa).cross(&(pc - pa));
                assert!(face.norm() > 1e-9, "{shape:?}: a degenerate triangle {:?}", [pa, pb, pc]);
                // Every one of these is convex around its origin.
                assert!(face.dot(&(pa + pb + pc)) > 0.0, "{shape:?}: a triangle faces inwards: {:?}", [pa, pb, pc]);
                for i in [a, b, c] {
                    let n = at(&t, i).1;
                    assert!((n.norm() - 1.0).abs() < 1e-6, "{shape:?}: a normal {n} is not a unit");
                    assert!(n.dot(&face) > 0.0, "{shape:?}: a normal {n} against its triangle's {face}");
                }
            }
            let (volume, exact) = (enclosed_volume(&t), shape.volume().unwrap());
            assert!(volume <= exact * (1.0 + 1e-6) && volume > 0.97 * exact, "{shape:?}: {volume} m³ of {exact}");
        }
    }

    #[test]
    fn a_sphere_is_32_around_in_16_rings_on_its_radius_and_a_ray_a_dot() {
        let t = tessellate(&Shape::Sphere { radius: 0.3 });
        // 16 bands of 32 quads, the two at the poles one triangle each.
        assert_eq!(t.indices.len(), 16 * 32 * 2 - 2 * 32);
        assert_eq!(t.positions.len(), 17 * 32);
        for i in 0..t.positions.len() as u32 {
            let (p, n) = at(&t, i);
            assert!((p.norm() - 0.3).abs() < 1e-6, "{p} is off the radius");
            assert!((p / 0.3 - n).norm() < 1e-6, "{n} is not {p}'s radial direction");
        }
        let dot = tessellate(&Shape::Ray { length: 2.0 });
        assert_eq!(dot.indices.len(), t.indices.len());
        assert!(dot.positions.iter().all(|p| (Vector3::from(*p).norm() - 0.05).abs() < 1e-6));
    }

    #[test]
    fn a_box_is_12_triangles_on_its_corners_with_the_faces_normals() {
        let t = tessellate(&Shape::Box { edges: Vector3::new(0.8, 0.08, 0.2) });
        assert_eq!((t.indices.len(), t.positions.len()), (12, 24));
        for (p, n) in t.positions.iter().zip(&t.normals) {
            assert!(p.iter().zip([0.4, 0.04, 0.1]).all(|(v, h)| v.abs() == h), "{p:?} is no corner");
            // The normal is the axis of the face the corner is on, at the corner's side.
            let axis = n.iter().position(|v| *v != 0.0).unwrap();
            assert_eq!(n.iter().filter(|v| **v != 0.0).count(), 1, "{n:?}");
            assert_eq!(n[axis], p[axis].signum(), "{n:?} at {p:?}");
        }
    }

    #[test]
    fn a_plane_is_a_square_in_it_centred_where_it_meets_its_normal() {
        let t = tessellate(&Shape::Plane { normal: Vector3::new(0.0, 2.0, 0.0), distance: 0.5 });
        assert_eq!((t.indices.len(), t.positions.len()), (2, 4));
        let half = PLANE_HALF_SIZE;
        for (p, n) in t.positions.iter().zip(&t.normals) {
            assert_eq!(*n, [0.0, 1.0, 0.0]);
            assert_eq!(p[1], 0.5);
            assert_eq!((p[0].abs(), p[2].abs()), (half, half), "{p:?}");
        }
        // Counter-clockwise seen from above.
        let [a, b, c] = t.indices[0].map(|i| at(&t, i).0);
        assert!((b - a).cross(&(c - a)).y > 0.0);
    }

    #[test]
    fn a_mesh_keeps_its_triangles_in_order_with_their_face_normals() {
        // A tetrahedron (counter-clockwise from outside), a triangle naming a missing
        // vertex, and a flat square of two triangles.
        let vertices = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 1.0, 0.0]];
        let vertices: Vec<Point3<f64>> = vertices.into_iter().map(Point3::from).collect();
        let tetrahedron = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];
        let mut triangles = tetrahedron.to_vec();
        triangles.push([0, 1, 9]);
        let t = tessellate(&Shape::TriMesh { vertices: vertices.clone(), triangles });
        assert_eq!(t.indices.len(), 4);
        // No two faces share a normal: every corner is its own vertex.
        assert_eq!(t.positions.len(), 12);
        for (kept, original) in t.indices.iter().zip(tetrahedron) {
            let corners = original.map(|i| vertices[i as usize].coords);
            let normal = (corners[1] - corners[0]).cross(&(corners[2] - corners[0])).normalize();
            for (i, corner) in kept.iter().zip(corners) {
                let (p, n) = at(&t, *i);
                assert_eq!(p, corner);
                assert!((n - normal).norm() < 1e-6, "{n} is not the face's normal {normal}");
            }
        }
        assert!((enclosed_volume(&t) - 1.0 / 6.0).abs() < 1e-9);
        // A flat region's triangles share their corners.
        let square = tessellate(&Shape::TriMesh { vertices, triangles: vec![[0, 1, 4], [0, 4, 2]] });
        assert_eq!((square.indices.len(), square.positions.len()), (2, 4));
        assert!(square.normals.iter().all(|n| *n == [0.0, 0.0, 1.0]));
    }

    #[test]
    fn a_convex_hull_is_drawn_as_its_faces() {
        // The hull of a 2 × 1 × 1 box's corners: its 12 triangles, enclosing the box.
        let corners: Vec<Point3<f64>> =
            (0..8).map(|i| Point3::new(2.0 * f64::from(i & 1), f64::from(i >> 1 & 1), f64::from(i >> 2))).collect();
        let hull = Shape::convex_hull(&corners).unwrap();
        let t = tessellate(&hull);
        assert_eq!(t.indices.len(), 12);
        assert!((enclosed_volume(&t) - 2.0).abs() < 1e-9, "{}", enclosed_volume(&t));
    }
}
