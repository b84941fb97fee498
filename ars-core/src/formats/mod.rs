//! The file formats ARS reads and writes, in one place: URDF robots ([`urdf`]), MuJoCo's
//! MJCF models ([`mjcf`]), ARS's own scene files ([`scene_file`]), the meshes they name
//! ([`mesh`]: STL and OBJ), and opening any of them by its extension ([`open`]).
//!
//! What they share is here: the turn from a Z-up file to ARS's Y up
//! ([`z_up_to_y_up`]), finding a file among the folders a format searches
//! (`first_file`), loading each mesh file once (`MeshCache`), inertia tensors
//! (`inertia_tensor`, `turned_inertia`), and rigid bodies made one (`RigidMass`,
//! `moved_mass`, `combined_mass`: MJCF's welds, URDF's fused fixed links). Their errors are
//! [`Error::Format`](crate::Error::Format) (a file, an element, a line where the
//! format has one) and [`Error::Io`](crate::Error::Io).

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use nalgebra::{Isometry3, Matrix3, Point3, Rotation3, Vector3};

use crate::error::Result;
use crate::shape::Shape;

mod balance;
pub mod mesh;
pub mod mjcf;
pub mod open;
pub mod scene_file;
pub mod urdf;

/// A Z-up file's frame in ARS's Y-up simulation: −90° about X, exactly (every entry 0
/// or ±1): the file's (x, y, z) is the simulation's (x, z, −y).
pub fn z_up_to_y_up() -> Rotation3<f64> {
    Rotation3::from_matrix_unchecked(Matrix3::new(1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, -1.0, 0.0))
}

/// The symmetric inertia tensor of three moments and three products, as URDF
/// (`ixx iyy izz ixy ixz iyz`) and MJCF (`fullinertia`) write them, kg·m².
pub(crate) fn inertia_tensor([ixx, iyy, izz, ixy, ixz, iyz]: [f64; 6]) -> Matrix3<f64> {
    Matrix3::new(ixx, ixy, ixz, ixy, iyy, iyz, ixz, iyz, izz)
}

/// A rigid body's mass (kg), centre of mass and inertia about it, in some frame.
pub(crate) type RigidMass = (f64, Vector3<f64>, Matrix3<f64>);

/// A mass given in a frame `frame` (relative to another), in that other frame.
pub(crate) fn moved_mass((mass, com, inertia): RigidMass, frame: &Isometry3<f64>) -> RigidMass {
    let r = frame.rotation.to_rotation_matrix();
    (mass, (frame * Point3::from(com)).coords, turned_inertia(&r, &inertia))
}

/// Two masses in one frame as one rigid body: the mass summed, the centre of mass
/// weighted, the inertias moved to it (parallel axes) and summed.
pub(crate) fn combined_mass(a: Option<RigidMass>, b: RigidMass) -> RigidMass {
    let Some(a) = a else { return b };
    let mass = a.0 + b.0;
    let com = (a.1 * a.0 + b.1 * b.0) / mass;
    let about = |(m, c, inertia): RigidMass| {
        let d = c - com;
        inertia + (Matrix3::identity() * d.norm_squared() - d * d.transpose()) * m
    };
    (mass, com, about(a) + about(b))
}

/// An inertia tensor given in a frame turned by `rotation`, in the outer frame: `R I Rᵀ`.
pub(crate) fn turned_inertia(rotation: &Rotation3<f64>, inertia: &Matrix3<f64>) -> Matrix3<f64> {
    rotation.matrix() * inertia * rotation.matrix().transpose()
}

/// The first of `candidates` that is a file; if none is, a message naming `name`
/// and every path tried.
pub(crate) fn first_file(name: &str, candidates: &[PathBuf]) -> std::result::Result<PathBuf, String> {
    match candidates.iter().find(|p| p.is_file()) {
        Some(found) => Ok(found.clone()),
        None => {
            let list: Vec<String> = candidates.iter().map(|p| p.display().to_string()).collect();
            Err(format!(
                "mesh {name:?} not found; tried: {}",
                if list.is_empty() { "nothing (no folder to look in)".into() } else { list.join(", ") }
            ))
        }
    }
}

/// Mesh files loaded once for each file and scale, however many elements name them.
#[derive(Default)]
pub(crate) struct MeshCache {
    loaded: HashMap<(PathBuf, [u64; 3]), Shape>,
}

impl MeshCache {
    /// The triangle mesh in `path`, scaled along each axis (see [`mesh::load_mesh`]).
    pub(crate) fn load(&mut self, path: &Path, scale: Vector3<f64>) -> Result<Shape> {
        let key = (path.to_path_buf(), [scale.x, scale.y, scale.z].map(f64::to_bits));
        if let Some(shape) = self.loaded.get(&key) {
            return Ok(shape.clone());
        }
        let shape = mesh::load_mesh(path, scale)?;
        self.loaded.insert(key, shape.clone());
        Ok(shape)
    }
}
