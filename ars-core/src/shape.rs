//! Shapes: one vocabulary for geoms ([`GeomBuilder`](crate::GeomBuilder)), masses
//! ([`MassSpec`](crate::MassSpec)) and a simulation's objects.

use nalgebra::{Point3, Vector3};

use crate::error::{Error, Result};
use crate::limits;
use crate::mesh_mass::Triangles;
pub use crate::mesh_mass::{MeshMass, mass_properties};
use crate::validate;

/// Facets of the triangle mesh a cone collides as.
pub const CONE_SEGMENTS: u32 = 24;

/// The shape of a geom, of a body's mass and of a simulation's object: one vocabulary
/// for every layer. Lengths along an axis are local Z (capsules, cylinders, cones, rays,
/// as in ODE); radii come before lengths; a box is given by its full edge lengths.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[non_exhaustive]
pub enum Shape {
    /// Sphere of this radius, m.
    Sphere {
        /// Radius, m.
        radius: f64,
    },
    /// Box with these full edge lengths, m (not half-extents).
    Box {
        /// Full edge lengths along local X, Y, Z, m.
        edges: Vector3<f64>,
    },
    /// Capsule along local Z; `length` excludes the caps.
    Capsule {
        /// Radius, m.
        radius: f64,
        /// Length of the cylindrical part, m.
        length: f64,
    },
    /// Cylinder along local Z.
    Cylinder {
        /// Radius, m.
        radius: f64,
        /// Length, m.
        length: f64,
    },
    /// Solid cone along local +Z, apex up, whose origin is its centre of mass (a
    /// quarter of the height above the base). ODE has no cone collider: its geom is a
    /// triangle mesh of [`CONE_SEGMENTS`] facets.
    Cone {
        /// Base radius, m.
        radius: f64,
        /// Height, m.
        height: f64,
    },
    /// Infinite plane `normal · x = distance` (not placeable: cannot be attached or moved).
    Plane {
        /// Plane normal (normalised by ODE).
        normal: Vector3<f64>,
        /// Offset along the normal, m.
        distance: f64,
    },
    /// Ray of this length from the geom's origin along its local +Z axis.
    Ray {
        /// Length, m.
        length: f64,
    },
    /// Triangle mesh (vertices in the geom's frame; faces wound counter-clockwise seen
    /// from outside). A mesh of one triangle is handed to ODE with that triangle twice
    /// (ODE's mesh–mesh collider crashes on a one-triangle tree).
    TriMesh {
        /// Vertex positions, m.
        vertices: Vec<Point3<f64>>,
        /// Vertex indices, three per triangle.
        triangles: Vec<[u32; 3]>,
    },
    /// A convex polyhedron, collided by ODE's convex colliders (`dCreateConvex`; its
    /// geom's bounding box costs O(1) per step, not one per vertex): how MuJoCo
    /// collides every mesh, and PyBullet a URDF's collision meshes. Make it from any
    /// points (a mesh's vertices) with [`Shape::convex_hull`]; one given directly must
    /// be a convex hull: a closed surface of triangles wound counter-clockwise seen
    /// from outside, convex at every edge, enclosing a volume (checked when a geom or
    /// mass is made of it). Rays hit it as the solid it bounds.
    ConvexHull {
        /// Its corners, m (in the geom's frame).
        vertices: Vec<Point3<f64>>,
        /// Its faces: vertex indices, three per triangle.
        triangles: Vec<[u32; 3]>,
    },
}

impl Shape {
    /// Short name of the shape kind, as used in error messages.
    pub fn kind_name(&self) -> &'static str {
        match self {
            Shape::Sphere { .. } => "sphere",
            Shape::Box { .. } => "box",
            Shape::Capsule { .. } => "capsule",
            Shape::Cylinder { .. } => "cylinder",
            Shape::Cone { .. } => "cone",
            Shape::Plane { .. } => "plane",
            Shape::Ray { .. } => "ray",
            Shape::TriMesh { .. } => "trimesh",
            Shape::ConvexHull { .. } => "hull",
        }
    }

    /// The convex hull of `points` (a mesh's vertices, say), as a
    /// [`Shape::ConvexHull`] of the points it keeps, computed with Qhull as MuJoCo
    /// computes its mesh hulls. `Err` ([`Error::InvalidMesh`]) names the problem:
    /// fewer than 4 points, a coordinate that is not finite or beyond
    /// [`MAX_COORDINATE`](limits::MAX_COORDINATE), or points that bound no solid (all
    /// on one line or one plane).
    ///
    /// ```
    /// use ars_core::Shape;
    /// use nalgebra::Point3;
    /// // A cube's corners and its centre: the hull keeps the 8 corners, 12 triangles.
    /// let mut points: Vec<Point3<f64>> = (0..8).map(|i| Point3::new(f64::from(i & 1), f64::from(i >> 1 & 1), f64::from(i >> 2))).collect();
    /// points.push(Point3::new(0.5, 0.5, 0.5));
    /// let Shape::ConvexHull { vertices, triangles } = Shape::convex_hull(&points).unwrap() else { unreachable!() };
    /// assert_eq!((vertices.len(), triangles.len()), (8, 12));
    /// assert!(Shape::convex_hull(&points[..3]).is_err());
    /// ```
    pub fn convex_hull(points: &[Point3<f64>]) -> Result<Shape> {
        crate::hull::convex_hull(points).map(|(vertices, triangles)| Shape::ConvexHull { vertices, triangles })
    }

    /// The volume it encloses, m³: `None` for a plane or a ray. A triangle mesh's is
    /// that of the solid its triangles close (counter-clockwise seen from outside; `None`
    /// when they enclose nothing: see [`mass_properties`]).
    ///
    /// ```
    /// use ars_core::Shape;
    /// let cube = Shape::Box { edges: [1.0, 2.0, 3.0].into() };
    /// assert_eq!(cube.volume(), Some(6.0));
    /// assert_eq!(Shape::Ray { length: 1.0 }.volume(), None);
    /// ```
    pub fn volume(&self) -> Option<f64> {
        use std::f64::consts::PI;
        match self {
            Shape::Sphere { radius } => Some(4.0 / 3.0 * PI * radius.powi(3)),
            Shape::Box { edges } => Some(edges.product()),
            Shape::Capsule { radius, length } => Some(PI * radius.powi(2) * (length + 4.0 / 3.0 * radius)),
            Shape::Cylinder { radius, length } => Some(PI * radius.powi(2) * length),
            Shape::Cone { radius, height } => Some(PI * radius.powi(2) * height / 3.0),
            Shape::Plane { .. } | Shape::Ray { .. } => None,
            Shape::TriMesh { vertices, triangles } | Shape::ConvexHull { vertices, triangles } => {
                mass_properties(vertices, triangles).map(|m| m.volume)
            }
        }
    }

    pub(crate) fn validate(&self) -> Result<()> {
        match self {
            Shape::Sphere { radius } => limits::size("sphere radius", *radius).map(drop),
            Shape::Box { edges } => limits::sizes("box edges", edges).map(drop),
            Shape::Capsule { radius, length } => {
                limits::size("capsule radius", *radius)?;
                limits::size("capsule length", *length).map(drop)
            }
            Shape::Cylinder { radius, length } => {
                limits::size("cylinder radius", *radius)?;
                limits::size("cylinder length", *length).map(drop)
            }
            Shape::Cone { radius, height } => {
                limits::size("cone radius", *radius)?;
                limits::size("cone height", *height).map(drop)
            }
            Shape::Plane { normal, distance } => {
                validate::direction("plane normal", normal)?;
                limits::coordinate("plane distance", *distance).map(drop)
            }
            Shape::Ray { length } => limits::size("ray length", *length).map(drop),
            Shape::TriMesh { vertices, triangles } | Shape::ConvexHull { vertices, triangles } => {
                if triangles.is_empty() {
                    return Err(Error::InvalidMesh("it has no triangles".into()));
                }
                for (i, v) in vertices.iter().enumerate() {
                    if let Err(e) = limits::point("mesh vertex", v) {
                        return Err(Error::InvalidMesh(format!("vertex {i}: {e}")));
                    }
                }
                for (i, t) in triangles.iter().enumerate() {
                    if let Some(bad) = t.iter().find(|&&k| k as usize >= vertices.len()) {
                        return Err(Error::InvalidMesh(format!(
                            "triangle {i} uses vertex {bad}, but there are only {} vertices",
                            vertices.len()
                        )));
                    }
                }
                let limit = i32::MAX as usize / 3;
                if vertices.len() > limit || triangles.len() > limit {
                    return Err(Error::InvalidMesh("too many vertices or triangles".into()));
                }
                if matches!(self, Shape::ConvexHull { .. }) {
                    crate::hull::check_convex(vertices, triangles)?;
                }
                Ok(())
            }
        }
    }
}

/// Vertices and triangles of a cone along +Z with its centre of mass at the origin
/// (what a [`Shape::Cone`] collides as).
pub(crate) fn cone_mesh(radius: f64, height: f64) -> Triangles {
    let base_z = -height / 4.0;
    let n = CONE_SEGMENTS;
    let mut vertices = vec![Point3::new(0.0, 0.0, base_z + height), Point3::new(0.0, 0.0, base_z)];
    for i in 0..n {
        let a = std::f64::consts::TAU * f64::from(i) / f64::from(n);
        vertices.push(Point3::new(radius * a.cos(), radius * a.sin(), base_z));
    }
    let mut triangles = Vec::new();
    for i in 0..n {
        let (a, b) = (2 + i, 2 + (i + 1) % n);
        triangles.push([0, a, b]); // side, outward
        triangles.push([1, b, a]); // base, facing -Z
    }
    (vertices, triangles)
}
