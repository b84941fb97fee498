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
