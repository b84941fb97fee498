//! How a URDF `<geometry>` becomes a shape: its primitives, and the mesh files it names
//! found (`package://` and `file://` paths, the search paths) and loaded once each.

use std::path::{Path, PathBuf};

use nalgebra::Vector3;

use super::{UrdfOptions, model};
use crate::shape::Shape;

/// How many folders above the URDF's a `package://` path's rest is looked for in (as
/// PyBullet looks up to five).
const PACKAGE_LEVELS_UP: usize = 5;

/// Finds and loads the meshes a file names (each file once).
pub(super) struct Meshes<'o> {
    pub(super) options: &'o UrdfOptions,
    /// The URDF file's folder.
    pub(super) base_dir: Option<PathBuf>,
    pub(super) loaded: crate::formats::MeshCache,
    /// Collision meshes kept as triangle meshes because they bound no solid (a line
    /// each, for [`UrdfRobot::adjusted`](super::UrdfRobot::adjusted)).
    pub(super) notes: Vec<String>,
}

impl Meshes<'_> {
    /// The first existing path for a URDF mesh filename, or every path tried.
    pub(super) fn resolve(&self, filename: &str) -> std::result::Result<PathBuf, String> {
        let name = filename.strip_prefix("file://").unwrap_or(filename);
        let mut tried = Vec::new();
        if let Some(rest) = name.strip_prefix("package://") {
            let (package, rest) = rest.split_once('/').unwrap_or((rest, ""));
            for (p, dir) in &self.options.package_dirs {
                if p == package {
                    tried.push(dir.join(rest));
                }
            }
            for var in ["ROS_PACKAGE_PATH", "AMENT_PREFIX_PATH"] {
                if let Some(paths) = std::env::var_os(var) {
                    for dir in std::env::split_paths(&paths) {
                        tried.push(dir.join(package).join(rest));
                        tried.push(dir.join("share").join(package).join(rest));
                    }
                }
            }
            if let Some(base) = &self.base_dir {
                tried.push(base.join(package).join(rest));
                for ancestor in base.ancestors() {
                    if ancestor.file_name().is_some_and(|n| n == package) {
                        tried.push(ancestor.join(rest));
                    }
                }
                tried.push(base.join(rest));
            }
            for dir in &self.options.search_paths {
                tried.push(dir.join(package).join(rest));
                tried.push(dir.join(rest));
            }
            // The package's folder under another name (a `_support` package whose
            // meshes a `_description` folder holds), or no name (`package:///a/b`):
            // `REST` in each folder above the URDF's.
            if let Some(base) = &self.base_dir {
                tried.extend(base.ancestors().skip(1).take(PACKAGE_LEVELS_UP).map(|dir| dir.join(rest)));
            }
        } else if Path::new(name).is_absolute() {
            tried.push(PathBuf::from(name));
        } else {
            if let Some(base) = &self.base_dir {
                tried.push(base.join(name));
            }
            for dir in &self.options.search_paths {
                tried.push(dir.join(name));
            }
        }
        let mut seen = std::collections::HashSet::new();
        tried.retain(|path| seen.insert(path.clone()));
        crate::formats::first_file(filename, &tried)
    }

    /// Why a mesh geometry cannot be found (every path tried); `None` for one that is
    /// found, or a primitive.
    pub(super) fn missing(&self, geometry: &model::Geometry) -> Option<String> {
        let model::Geometry::Mesh { filename, .. } = geometry else { return None };
        self.resolve(filename).err()
    }

    pub(super) fn shape(&mut self, geometry: &model::Geometry) -> std::result::Result<Shape, String> {
        let model::Geometry::Mesh { filename, scale } = geometry else {
            return Ok(primitive_shape(geometry).expect("a geometry that is not a mesh is a primitive"));
        };
        let path = self.resolve(filename)?;
        let scale = Vector3::from(scale.as_ref().map_or([1.0; 3], |s| s.0));
        self.loaded.load(&path, scale).map_err(|e| e.to_string())
    }
}

/// The shape of a primitive geometry (box, cylinder, capsule, sphere), unchecked;
/// `None` for a mesh, which must be found and loaded.
pub(super) fn primitive_shape(geometry: &model::Geometry) -> Option<Shape> {
    use model::Geometry as G;
    Some(match geometry {
        G::Box { size } => Shape::Box { edges: Vector3::from(size.0) },
        G::Cylinder { radius, length } => Shape::Cylinder { radius: *radius, length: *length },
        G::Capsule { radius, length } => Shape::Capsule { radius: *radius, length: *length },
        G::Sphere { radius } => Shape::Sphere { radius: *radius },
        G::Mesh { .. } => return None,
    })
}
