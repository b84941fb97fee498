//! The file formats ARS reads and writes, in one place: URDF robots ([`urdf`]), MuJoCo's
//! MJCF models ([`mjcf`]), ARS's own scene files ([`scene_file`]), the meshes they name
//! ([`mesh`]: STL and OBJ), and opening any of them by its extension ([`open`]).

pub mod mesh;
pub mod mjcf;
pub mod open;
pub mod scene_file;
pub mod urdf;
