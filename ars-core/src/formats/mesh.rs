//! Triangle meshes from files (STL, OBJ, COLLADA), made fit for ODE's trimesh
//! collider: every sub-mesh of a file merged into one, duplicate vertices welded,
//! degenerate triangles dropped, the scale applied.

use std::collections::HashMap;
use std::path::Path;

use nalgebra::{Point3, Vector3};

use crate::error::{Error, Result};
use crate::shape::Shape;

/// Loads the mesh of a file as a [`Shape::TriMesh`], each vertex scaled by `scale`
/// (per axis). Errors name the file.
///
/// ```
/// # let dir = std::env::temp_dir().join("ars-mesh-doc");
/// # std::fs::create_dir_all(&dir).unwrap();
/// # let path = dir.join("tetra.stl");
/// std::fs::write(&path, "solid t\nfacet normal 0 0 -1\nouter loop\nvertex 0 0 0\nvertex 0 1 0\nvertex 1 0 0\nendloop\nendfacet\n\
///     facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 0 1\nendloop\nendfacet\nendsolid t\n")?;
/// let shape = ars_core::formats::mesh::load_mesh(&path, nalgebra::Vector3::new(2.0, 2.0, 2.0))?;
/// let ars_core::Shape::TriMesh { vertices, triangles } = shape else { unreachable!() };
/// assert_eq!((vertices.len(), triangles.len()), (4, 2), "the shared vertices are welded");
/// assert!(vertices.contains(&nalgebra::Point3::new(2.0, 0.0, 0.0)));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn load_mesh(path: &Path, scale: Vector3<f64>) -> Result<Shape> {
    let bad = |problem: String| Error::InvalidMesh(format!("{}: {problem}", path.display()));
    if !scale.iter().all(|s| s.is_finite() && *s != 0.0) {
        return Err(bad(format!("scale {scale:?} must be finite and non-zero")));
    }
    // The loader is a dependency: a panic in it must not reach the caller.
    let loaded = std::panic::catch_unwind(|| mesh_loader::Loader::default().merge_meshes(false).load(path))
        .map_err(|_| bad("the mesh loader failed on this file".into()))?
        .map_err(|e| bad(format!("cannot be loaded: {e}")))?;
    let mut vertices: Vec<Point3<f64>> = Vec::new();
    let mut welded: HashMap<[u64; 3], u32> = HashMap::new();
    let mut triangles = Vec::new();
    for mesh in &loaded.meshes {
        let mut index = Vec::with_capacity(mesh.vertices.len());
        for v in &mesh.vertices {
            let p = Point3::new(f64::from(v[0]) * scale.x, f64::from(v[1]) * scale.y, f64::from(v[2]) * scale.z);
            if !p.iter().all(|x| x.is_finite()) {
                return Err(bad(format!("a vertex is not finite: {p}")));
            }
            // +0.0 keeps 0.0 and -0.0 one vertex.
            let key = [p.x + 0.0, p.y + 0.0, p.z + 0.0].map(f64::to_bits);
            let next = vertices.len() as u32;
            let i = *welded.entry(key).or_insert_with(|| {
                vertices.push(p);
                next
            });
            index.push(i);
        }
        for face in &mesh.faces {
            let Some(t) = face.iter().map(|&k| index.get(k as usize).copied()).collect::<Option<Vec<u32>>>() else {
                return Err(bad(format!("a face uses vertex {face:?}, beyond the mesh's {}", index.len())));
            };
            let [a, b, c] = [t[0], t[1], t[2]];
            let (pa, pb, pc) = (vertices[a as usize], vertices[b as usize], vertices[c as usize]);
            let area2 = (pb - pa).cross(&(pc - pa)).norm();
            if a == b || b == c || a == c || area2 <= f64::EPSILON * (pb - pa).norm() * (pc - pa).norm() {
                continue; // degenerate: no surface to collide with
            }
            triangles.push([a, b, c]);
        }
    }
    if triangles.is_empty() {
        return Err(bad("it has no triangle with an area".into()));
    }
    Ok(Shape::TriMesh { vertices, triangles })
}

/// The mass properties of the solid a closed triangle mesh bounds (counter-clockwise
/// triangles seen from outside), at a density of 1: its volume, its centre of mass,
/// and its inertia tensor about that centre, in the mesh's frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeshMass {
    /// Volume, m³ (the mass at a density of 1 kg/m³).
    pub volume: f64,
    /// Centre of mass, m.
    pub centre: Point3<f64>,
    /// Inertia tensor about the centre of mass per kg/m³ of density, kg·m² per kg/m³.
    pub inertia: nalgebra::Matrix3<f64>,
}

/// The [`MeshMass`] of a mesh: `None` when it encloses no volume (open, flat, or wound
/// the wrong way round) or a triangle names a vertex it does not have. Exact for a
/// closed mesh: each triangle's tetrahedron from the origin, with its signed volume and
/// second moments.
///
/// ```
/// use ars_core::formats::mesh::mass_properties;
/// use nalgebra::Point3;
/// // The unit cube [0, 1]³, two triangles a face, wound outwards.
/// let v: Vec<Point3<f64>> = (0..8).map(|i| Point3::new(f64::from(i & 1), f64::from(i >> 1 & 1), f64::from(i >> 2))).collect();
/// let t = [[0, 2, 1], [1, 2, 3], [4, 5, 6], [5, 7, 6], [0, 1, 4], [1, 5, 4],
///          [2, 6, 3], [3, 6, 7], [0, 4, 2], [2, 4, 6], [1, 3, 5], [3, 7, 5]];
/// let m = mass_properties(&v, &t).unwrap();
/// assert!((m.volume - 1.0).abs() < 1e-12);
/// assert!((m.centre - Point3::new(0.5, 0.5, 0.5)).norm() < 1e-12);
/// assert!((m.inertia[(0, 0)] - 1.0 / 6.0).abs() < 1e-12 && m.inertia[(0, 1)].abs() < 1e-12);
/// ```
pub fn mass_properties(vertices: &[Point3<f64>], triangles: &[[u32; 3]]) -> Option<MeshMass> {
    use nalgebra::Matrix3;
    // ∫ x xᵀ over a tetrahedron (0, a, b, c) is det/120 · (A·K·Aᵀ) with A = [a b c] and
    // K = [[2,1,1],[1,2,1],[1,1,2]].
    let canonical = Matrix3::new(2.0, 1.0, 1.0, 1.0, 2.0, 1.0, 1.0, 1.0, 2.0);
    let (mut volume, mut first, mut second) = (0.0, Vector3::zeros(), Matrix3::zeros());
    for t in triangles {
        let corner = |k: u32| vertices.get(k as usize).map(|p| p.coords);
        let (a, b, c) = (corner(t[0])?, corner(t[1])?, corner(t[2])?);
        let columns = Matrix3::from_columns(&[a, b, c]);
        let det = columns.determinant();
        volume += det / 6.0;
        first += (a + b + c) * (det / 24.0);
        second += columns * canonical * columns.transpose() * (det / 120.0);
    }
    if !(volume.is_finite() && volume > 0.0) {
        return None;
    }
    let centre = first / volume;
    // Second moments about the centre, then the inertia tensor tr(C)·1 − C.
    let about_centre = second - centre * centre.transpose() * volume;
    let inertia = Matrix3::identity() * about_centre.trace() - about_centre;
    Some(MeshMass { volume, centre: Point3::from(centre), inertia })
}
