//! `<asset><mesh>`es: read with their class's defaults (a file, or vertices and faces
//! given in the element), loaded once, collided as their convex hull and weighed as
//! MuJoCo's compiler weighs them (`inertia`: legacy, exact, convex or shell).

use std::collections::HashMap;
use std::path::Path;

use nalgebra::{Point3, Vector3};

use super::defaults::{Attrs, Defaults};
use super::model::MeshGeom;
use super::problem::{Parsed, problem};
use crate::mesh_mass::{MeshInertia, mujoco_mass_properties};
use crate::shape::Shape;

/// Where a mesh's triangles come from.
#[derive(Clone, Debug)]
pub(super) enum MeshSource {
    /// A file, as written (relative to the compiler's `meshdir`).
    File(String),
    /// `vertex` (and `face`, else the faces of the vertices' convex hull) in the element.
    Inline { vertices: Vec<Point3<f64>>, faces: Option<Vec<[u32; 3]>> },
}

/// An `<asset><mesh>` as read.
#[derive(Clone, Debug)]
pub(super) struct MeshAsset {
    pub(super) source: MeshSource,
    pub(super) scale: Vector3<f64>,
    /// How it is weighed.
    pub(super) inertia: MeshInertia,
}

/// The `<asset><mesh>` elements by name, with their classes' defaults (read by now,
/// wherever they are in the file).
pub(super) fn mesh_assets(
    nodes: &[roxmltree::Node<'_, '_>],
    defaults: &Defaults,
) -> Parsed<HashMap<String, MeshAsset>> {
    let mut meshes = HashMap::new();
    for &node in nodes {
        let (name, asset) = mesh_asset(node, defaults)?;
        meshes.insert(name, asset);
    }
    Ok(meshes)
}

/// An `<asset><mesh>`: its name (else its file's stem) and what it is.
fn mesh_asset(node: roxmltree::Node<'_, '_>, defaults: &Defaults) -> Parsed<(String, MeshAsset)> {
    let a = Attrs::new(node, defaults, "main");
    if let Some(builtin) = node.attribute("builtin").filter(|b| *b != "none") {
        return Err(problem(&node, format!("a builtin mesh ({builtin:?}) is not supported")));
    }
    let source = match (node.attribute("file"), a.numbers("vertex")?) {
        (Some(file), None) => MeshSource::File(file.to_string()),
        (None, Some(vertex)) => MeshSource::Inline { vertices: points(&node, &vertex)?, faces: faces(&a)? },
        (Some(_), Some(_)) => return Err(problem(&node, "has both a file and vertex data")),
        (None, None) => return Err(problem(&node, "needs a file or vertex data")),
    };
    let name = match (node.attribute("name"), &source) {
        (Some(name), _) => name.to_string(),
        (None, MeshSource::File(file)) => {
            Path::new(file).file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default()
        }
        (None, MeshSource::Inline { .. }) => return Err(problem(&node, "a mesh of vertex data needs a name")),
    };
    let scale = a.fixed::<3>("scale")?.map_or(Vector3::repeat(1.0), Vector3::from);
    let inertia = match a.get("inertia") {
        None => MeshInertia::default(),
        Some(method) => MeshInertia::from_name(method).ok_or_else(|| {
            problem(&node, format!("inertia=\"{method}\" is none of convex, exact, legacy and shell"))
        })?,
    };
    Ok((name, MeshAsset { source, scale, inertia }))
}

/// `vertex`'s numbers, three a point.
fn points(node: &roxmltree::Node<'_, '_>, numbers: &[f64]) -> Parsed<Vec<Point3<f64>>> {
    if numbers.len() < 12 || !numbers.len().is_multiple_of(3) {
        return Err(problem(
            node,
            format!("vertex has {} numbers: three a point, at least four points", numbers.len()),
        ));
    }
    Ok(numbers.chunks_exact(3).map(|p| Point3::new(p[0], p[1], p[2])).collect())
}

/// `face`'s vertex indices, three a triangle, if it is given.
fn faces(a: &Attrs<'_, '_>) -> Parsed<Option<Vec<[u32; 3]>>> {
    let Some(numbers) = a.numbers("face")? else { return Ok(None) };
    let index = |x: f64| (x >= 0.0 && x.fract() == 0.0 && x <= f64::from(u32::MAX)).then_some(x as u32);
    if !numbers.len().is_multiple_of(3) {
        return Err(problem(&a.node, format!("face has {} numbers, not three a triangle", numbers.len())));
    }
    numbers
        .chunks_exact(3)
        .map(|t| match (index(t[0]), index(t[1]), index(t[2])) {
            (Some(i), Some(j), Some(k)) => Ok([i, j, k]),
            _ => Err(problem(&a.node, format!("face {t:?} is not three vertex indices"))),
        })
        .collect::<Parsed<Vec<_>>>()
        .map(Some)
}

/// The mesh `asset` loaded (its file looked for in `folder`, read once through
/// `files`), its hull made and its mass computed; the error says what is wrong with it.
pub(super) fn load_mesh(
    asset: &MeshAsset,
    folder: &Path,
    files: &mut crate::formats::MeshCache,
) -> Result<MeshGeom, String> {
    let (vertices, mut triangles) = match &asset.source {
        MeshSource::File(file) => {
            let path = crate::formats::first_file(file, &[folder.join(file)])?;
            match files.load(&path, asset.scale).map_err(|e| e.to_string())? {
                Shape::TriMesh { vertices, triangles } => (vertices, triangles),
                _ => return Err("it is not a triangle mesh".into()),
            }
        }
        MeshSource::Inline { vertices, faces } => {
            let scaled: Vec<Point3<f64>> =
                vertices.iter().map(|p| Point3::from(p.coords.component_mul(&asset.scale))).collect();
            let faces = match faces {
                Some(faces) => faces.clone(),
                // No faces: the hull's, as MuJoCo makes them.
                None => crate::hull::convex_hull(&scaled).map_err(|e| e.to_string())?.1,
            };
            (scaled, faces)
        }
    };
    // A mirroring scale turns the triangles inside out: MuJoCo winds them back.
    if asset.scale.x * asset.scale.y * asset.scale.z < 0.0 {
        triangles.iter_mut().for_each(|t| t.swap(1, 2));
    }
    // MuJoCo collides a mesh as its convex hull; a flat one has none (MuJoCo refuses
    // it in a geom that collides: see `Reader::geom`).
    let hull = crate::hull::convex_hull(&vertices).ok();
    if asset.inertia == MeshInertia::Convex && hull.is_none() {
        return Err("it has no convex hull to weigh (its points are flat)".into());
    }
    let no_hull: (&[Point3<f64>], &[[u32; 3]]) = (&[], &[]);
    let hull_triangles = hull.as_ref().map_or(no_hull, |(v, t)| (v.as_slice(), t.as_slice()));
    let mass = mujoco_mass_properties((&vertices, &triangles), hull_triangles, asset.inertia)
        .map_err(|e| if hull.is_none() { format!("{e}; its points are flat, with no convex hull") } else { e })?;
    let hull = hull.map(|(vertices, triangles)| Shape::ConvexHull { vertices, triangles });
    Ok(MeshGeom { shape: Shape::TriMesh { vertices, triangles }, hull, mass })
}
