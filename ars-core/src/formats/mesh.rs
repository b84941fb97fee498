//! Triangle meshes from files (STL, text or binary, OBJ, COLLADA, and MuJoCo's legacy binary `.msh`),
//! made fit for ODE's trimesh collider: every sub-mesh of a file merged into one, duplicate vertices welded,
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
    let extension = |name: &str| path.extension().is_some_and(|e| e.eq_ignore_ascii_case(name));
    let stl = if extension("stl") {
        Some(std::fs::read(path).map_err(|e| bad(format!("cannot be read: {e}")))?)
    } else {
        None
    };
    let meshes = if extension("msh") {
        let bytes = std::fs::read(path).map_err(|e| bad(format!("cannot be read: {e}")))?;
        vec![read_msh(&bytes).map_err(bad)?]
    } else if let Some(binary) = stl.as_deref().and_then(read_binary_stl) {
        vec![binary]
    } else {
        // The loader is a dependency: a panic in it must not reach the caller.
        std::panic::catch_unwind(|| mesh_loader::Loader::default().merge_meshes(false).load(path))
            .map_err(|_| bad("the mesh loader failed on this file".into()))?
            .map_err(|e| bad(format!("cannot be loaded: {e}")))?
            .meshes
            .into_iter()
            .map(|m| RawMesh { vertices: m.vertices, faces: m.faces })
            .collect()
    };
    let mut vertices: Vec<Point3<f64>> = Vec::new();
    let mut welded: HashMap<[u64; 3], u32> = HashMap::new();
    let mut triangles = Vec::new();
    for mesh in &meshes {
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

/// A mesh as a file gives it: vertices and triangles (indices into them).
#[derive(Debug)]
struct RawMesh {
    vertices: Vec<[f32; 3]>,
    faces: Vec<[u32; 3]>,
}

/// A binary STL file: an 80-byte header, a little-endian `u32` count of triangles, then
/// 50 bytes a triangle (a normal and three corners, 3 `f32` each, and 2 bytes of
/// attributes); `None` when the file's size is not that of its count (it is text).
/// Told apart by its size, not by its first bytes: some binary files' headers start
/// with `solid`, as a text STL does (robosuite's Jaco shoulder).
fn read_binary_stl(bytes: &[u8]) -> Option<RawMesh> {
    let count = u32::from_le_bytes(bytes.get(80..84)?.try_into().ok()?) as usize;
    if count.checked_mul(50).and_then(|n| n.checked_add(84)) != Some(bytes.len()) {
        return None;
    }
    let float = |at: usize| f32::from_le_bytes(bytes[at..at + 4].try_into().expect("four bytes"));
    let mut vertices = Vec::with_capacity(3 * count);
    for t in 0..count {
        let corners = 84 + 50 * t + 12;
        vertices.extend((0..3).map(|c| [0, 1, 2].map(|k| float(corners + 12 * c + 4 * k))));
    }
    let faces = (0..count as u32).map(|t| [3 * t, 3 * t + 1, 3 * t + 2]).collect();
    Some(RawMesh { vertices, faces })
}

/// MuJoCo's legacy binary mesh (`.msh`, dm_control's and robosuite's older assets): four
/// little-endian `i32` counts (vertices, normals, texture coordinates, faces), then
/// the vertices (3 `f32` each), the normals (3 `f32`), the texture coordinates (2
/// `f32`) and the faces (3 `i32`); the file's size must be exactly that.
fn read_msh(bytes: &[u8]) -> std::result::Result<RawMesh, String> {
    let word = |i: usize| -> [u8; 4] { bytes[4 * i..4 * i + 4].try_into().expect("four bytes") };
    if bytes.len() < 16 {
        return Err(format!("a .msh file starts with four counts (16 bytes); it has {} bytes", bytes.len()));
    }
    let counts: Vec<usize> = (0..4)
        .map(|i| usize::try_from(i32::from_le_bytes(word(i))).map_err(|_| "a .msh count is negative".to_string()))
        .collect::<std::result::Result<_, _>>()?;
    let (nv, nn, nt, nf) = (counts[0], counts[1], counts[2], counts[3]);
    let words = [3 * nv, 3 * nn, 2 * nt, 3 * nf].iter().try_fold(4usize, |sum, n| sum.checked_add(*n));
    if words.and_then(|w| w.checked_mul(4)) != Some(bytes.len()) {
        return Err(format!(
            "a .msh file of {nv} vertices, {nn} normals, {nt} texture coordinates and {nf} faces \
             cannot have {} bytes",
            bytes.len()
        ));
    }
    let vertices = (0..nv).map(|v| [0, 1, 2].map(|k| f32::from_le_bytes(word(4 + 3 * v + k)))).collect();
    let first_face = 4 + 3 * nv + 3 * nn + 2 * nt;
    let faces = (0..nf)
        .map(|f| {
            let face = [0, 1, 2].map(|k| i32::from_le_bytes(word(first_face + 3 * f + k)));
            match face.map(u32::try_from) {
                [Ok(a), Ok(b), Ok(c)] => Ok([a, b, c]),
                _ => Err(format!("a .msh face has a negative vertex index: {face:?}")),
            }
        })
        .collect::<std::result::Result<_, _>>()?;
    Ok(RawMesh { vertices, faces })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn msh(counts: [i32; 4], floats: &[f32], faces: &[i32]) -> Vec<u8> {
        let mut bytes: Vec<u8> = counts.iter().flat_map(|c| c.to_le_bytes()).collect();
        bytes.extend(floats.iter().flat_map(|f| f.to_le_bytes()));
        bytes.extend(faces.iter().flat_map(|f| f.to_le_bytes()));
        bytes
    }

    /// A tetrahedron with normals: its vertices and faces come back, the normals skipped.
    #[test]
    fn a_msh_file_is_read_past_its_normals() {
        let corners = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0];
        let mut floats = corners.to_vec();
        floats.extend([9.0; 12]); // four normals
        let bytes = msh([4, 4, 0, 4], &floats, &[0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3]);
        let mesh = read_msh(&bytes).unwrap();
        assert_eq!(mesh.vertices, [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]);
        assert_eq!(mesh.faces, [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]);
    }

    /// A binary STL whose header starts with `solid`, as a text STL does (robosuite's
    /// Jaco shoulder): told apart by its size, 84 + 50 bytes a triangle.
    #[test]
    fn a_binary_stl_whose_header_says_solid_is_read_as_binary() {
        let dir = std::env::temp_dir().join(format!("ars-binary-stl-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let corners = [[0.0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        let faces = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];
        let mut bytes = b"solid exported by a CAD program".to_vec();
        bytes.resize(80, b' ');
        bytes.extend(4u32.to_le_bytes());
        for face in faces {
            bytes.extend([0.0f32; 3].iter().flat_map(|x| x.to_le_bytes()));
            bytes.extend(face.iter().flat_map(|&k| corners[k]).flat_map(f32::to_le_bytes));
            bytes.extend([0u8, 0]);
        }
        let path = dir.join("tetra.stl");
        std::fs::write(&path, &bytes).unwrap();
        let shape = load_mesh(&path, Vector3::repeat(2.0)).unwrap();
        let Shape::TriMesh { vertices, triangles } = shape else { panic!("a triangle mesh") };
        assert_eq!((vertices.len(), triangles.len()), (4, 4), "its shared corners welded");
        assert!(vertices.contains(&Point3::new(0.0, 0.0, 2.0)), "scaled");
        // A byte more or less is no binary STL: the text reader refuses it.
        std::fs::write(&path, &bytes[..bytes.len() - 1]).unwrap();
        assert!(load_mesh(&path, Vector3::repeat(1.0)).is_err());
        std::fs::remove_dir_all(&dir).unwrap();
    }

    /// Truncated, padded, negative or absurd counts and negative indices are errors, not
    /// panics or huge allocations.
    #[test]
    fn a_broken_msh_file_is_an_error() {
        let good = msh([3, 0, 0, 1], &[0.0; 9], &[0, 1, 2]);
        assert!(read_msh(&good).is_ok());
        assert!(read_msh(&good[..good.len() - 1]).unwrap_err().contains("cannot have"));
        assert!(read_msh(&[good.clone(), vec![0]].concat()).unwrap_err().contains("cannot have"));
        assert!(read_msh(&good[..10]).unwrap_err().contains("16 bytes"));
        assert!(read_msh(&msh([-1, 0, 0, 0], &[], &[])).unwrap_err().contains("negative"));
        assert!(
            read_msh(&msh([i32::MAX, i32::MAX, i32::MAX, i32::MAX], &[], &[])).unwrap_err().contains("cannot have")
        );
        assert!(read_msh(&msh([3, 0, 0, 1], &[0.0; 9], &[0, -1, 2])).unwrap_err().contains("negative"));
    }
}
