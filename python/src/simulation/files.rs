//! `ars.Simulation`'s methods that read and write files and states: URDF and MJCF
//! models, scene files, snapshots.

use crate::errors::{Checked, guarded};
use ars_core::Simulation;
use pyo3::prelude::*;
use std::collections::HashMap;

use super::{PySimulation, Vec3};

#[pymethods]
impl PySimulation {
    /// Loads a robot from a URDF file (Z up unless `y_up`; see the Rust
    /// `Scene::load_urdf` for the rules). Returns `{"name", "links", "joints",
    /// "base_joint", "adjusted"}`, links and joints by their URDF names in file order;
    /// `adjusted` says, a line each, what was corrected to load it: an inertia no body
    /// can have (refused instead with `strict_inertia=True`), a hinge's limits beyond
    /// ±π, the robot raised onto a floor. Collision meshes collide
    /// as their convex hulls, as PyBullet's do (`triangle_mesh_collisions=True`: as
    /// triangle meshes). A floating robot that would reach into a floor at
    /// `base_position` is raised to rest on it, with a line in `adjusted`
    /// (`exact_base_pose=True` keeps the position given). A link with mass on a fixed
    /// joint is fused into the body it is fixed to, as MuJoCo does
    /// (`keep_fixed_links=True`: each its own body, held by a fixed joint).
    #[pyo3(signature = (path, *, fixed_base=false, base_position=Checked([0.0; 3]), self_collision=false, y_up=false,
                        initial_positions=None, packages=None, search_paths=None, ignore_visuals=false,
                        strict_inertia=false, triangle_mesh_collisions=false, exact_base_pose=false,
                        keep_fixed_links=false))]
    fn load_urdf<'py>(
        &self,
        py: Python<'py>,
        path: std::path::PathBuf,
        fixed_base: bool,
        base_position: Vec3,
        self_collision: bool,
        y_up: bool,
        initial_positions: Option<HashMap<String, f64>>,
        packages: Option<HashMap<String, std::path::PathBuf>>,
        search_paths: Option<Vec<std::path::PathBuf>>,
        ignore_visuals: bool,
        strict_inertia: bool,
        triangle_mesh_collisions: bool,
        exact_base_pose: bool,
        keep_fixed_links: bool,
    ) -> PyResult<Bound<'py, pyo3::types::PyDict>> {
        let mut options = ars_core::UrdfOptions::new()
            .exact_base_pose(exact_base_pose)
            .keep_fixed_links(keep_fixed_links)
            .strict_inertia(strict_inertia)
            .triangle_mesh_collisions(triangle_mesh_collisions)
            .fixed_base(fixed_base)
            .self_collision(self_collision)
            .ignore_visuals(ignore_visuals)
            .base_pose(ars_core::nalgebra::Isometry3::translation(
                base_position.0[0],
                base_position.0[1],
                base_position.0[2],
            ));
        if y_up {
            options = options.up_axis(ars_core::UpAxis::Y);
        }
        let mut positions: Vec<(String, f64)> = initial_positions.unwrap_or_default().into_iter().collect();
        positions.sort_by(|a, b| a.0.cmp(&b.0));
        for (name, q) in positions {
            options = options.initial_position(&name, q);
        }
        for (name, dir) in packages.unwrap_or_default() {
            options = options.package(&name, dir);
        }
        for dir in search_paths.unwrap_or_default() {
            options = options.search_path(dir);
        }
        let (name, links, joints, base, adjusted) = self.with(py, move |sim| {
            let robot = sim.load_urdf(&path, &options)?;
            let base = robot.base_joint.map(|id| sim.scene().joint(id).map(|j| j.name().to_string())).transpose()?;
            let links: Vec<String> = robot.links.into_iter().map(|(n, _)| n).collect();
            let joints: Vec<String> = robot.joints.into_iter().map(|(n, _)| n).collect();
            Ok((robot.name, links, joints, base, robot.adjusted))
        })?;
        let dict = pyo3::types::PyDict::new(py);
        dict.set_item("adjusted", adjusted)?;
        dict.set_item("name", name)?;
        dict.set_item("links", links)?;
        dict.set_item("joints", joints)?;
        dict.set_item("base_joint", base)?;
        Ok(dict)
    }

    /// Loads a MuJoCo model from an MJCF file (see the Rust `Scene::load_mjcf` for what
    /// is read). Returns `{"name", "bodies", "joints", "timestep", "gravity",
    /// "actuators", "welded", "sensors", "sites", "armature", "keyframes", "mocap", "skipped"}`:
    /// `keyframes` are the file's `<key>`s as dicts (`name`, `time`, `qpos`, `qvel`,
    /// `ctrl`, `mpos`, `mquat`; read, not applied, as MuJoCo applies none); bodies and joints by
    /// their MJCF names in file order, the file's time step and gravity (not applied),
    /// the file's sensors made (`ars.Sensor`s by name; see the Rust `MjcfSensor` for the
    /// columns that hold MuJoCo's values), the bodies' named sites (`{name: body}`), the
    /// inertia (3×3, body frame) each object carries for its ball joint's armature, the
    /// mocap bodies (moved by `set_mocap_pose`), what was skipped; `welded` maps each jointless body to the body it was merged
    /// into (`None`: the world). `prefix` goes before every name of the model, so that
    /// two copies of a model share a simulation (as MuJoCo's `attach`).
    #[pyo3(signature = (path, *, base_position=Checked([0.0; 3]), skip_unsupported=false, prefix=String::new()))]
    fn load_mjcf<'py>(
        slf: Bound<'py, Self>,
        path: std::path::PathBuf,
        base_position: Vec3,
        skip_unsupported: bool,
        prefix: String,
    ) -> PyResult<Bound<'py, pyo3::types::PyDict>> {
        let py = slf.py();
        let [x, y, z] = base_position.0;
        let options = ars_core::MjcfOptions::new()
            .base_pose(ars_core::nalgebra::Isometry3::translation(x, y, z))
            .skip_unsupported(skip_unsupported)
            .prefix(prefix);
        let model = slf.get().with(py, move |sim| sim.load_mjcf(&path, &options))?;
        let dict = pyo3::types::PyDict::new(py);
        dict.set_item("name", &model.name)?;
        dict.set_item("bodies", model.bodies.iter().map(|(n, _)| n.clone()).collect::<Vec<_>>())?;
        dict.set_item("joints", model.joints.iter().map(|(n, _)| n.clone()).collect::<Vec<_>>())?;
        dict.set_item("timestep", model.timestep)?;
        dict.set_item("gravity", model.gravity.map(|g| (g.x, g.y, g.z)))?;
        let actuators: Vec<(String, String, String)> =
            model.actuators.iter().map(|a| (a.name.clone(), a.kind.clone(), a.joint.clone())).collect();
        dict.set_item("actuators", actuators)?;
        // Each jointless body merged into the body it is welded to (None: the world).
        let welded = pyo3::types::PyDict::new(py);
        for w in &model.welded {
            welded.set_item(&w.body, w.into.clone())?;
        }
        dict.set_item("welded", welded)?;
        let sensors = pyo3::types::PyDict::new(py);
        for sensor in &model.sensors {
            let Some(id) = sensor.id else { continue };
            // The kind's Python name (`"joint_positions"`), from the one list of kinds.
            let kind = sensor.ars_kind().map_or_else(|| "laser".to_string(), |k| crate::sensors::snake_case(k.name()));
            let typed = crate::sensors::Typed::Table(id);
            sensors.set_item(&sensor.name, crate::sensors::PySensor::new(slf.clone().unbind(), kind, typed))?;
        }
        dict.set_item("sensors", sensors)?;
        let sites = pyo3::types::PyDict::new(py);
        for site in &model.sites {
            sites.set_item(&site.name, &site.body)?;
        }
        dict.set_item("sites", sites)?;
        let keyframes = pyo3::types::PyList::empty(py);
        for key in &model.keyframes {
            let k = pyo3::types::PyDict::new(py);
            k.set_item("name", &key.name)?;
            k.set_item("time", key.time)?;
            for (field, values) in [
                ("qpos", &key.qpos),
                ("qvel", &key.qvel),
                ("ctrl", &key.ctrl),
                ("mpos", &key.mpos),
                ("mquat", &key.mquat),
            ] {
                k.set_item(field, values.clone())?;
            }
            keyframes.append(k)?;
        }
        dict.set_item("keyframes", keyframes)?;
        let armature = pyo3::types::PyDict::new(py);
        for (name, inertia) in &model.armature {
            let rows: Vec<Vec<f64>> = (0..3).map(|r| (0..3).map(|c| inertia[(r, c)]).collect()).collect();
            armature.set_item(name, rows)?;
        }
        dict.set_item("armature", armature)?;
        dict.set_item("mocap", model.mocap.iter().map(|m| m.body.clone()).collect::<Vec<_>>())?;
        dict.set_item("skipped", &model.skipped)?;
        Ok(dict)
    }

    /// Puts the MJCF mocap body `body` (its name in the file, with the model's
    /// `prefix`) at `position`, turned by `quaternion` (w, x, y, z; normalised), both in
    /// the file's world frame: what MuJoCo's `data.mocap_pos` and `data.mocap_quat` hold.
    /// A mocap body is kinematic: it stays there, still, until moved again, and what a
    /// `weld` or `connect` joins to it follows. `load_mjcf` lists them as `"mocap"`.
    #[pyo3(signature = (body, position, quaternion=Checked([1.0, 0.0, 0.0, 0.0])))]
    fn set_mocap_pose(
        &self,
        py: Python<'_>,
        body: String,
        position: Vec3,
        quaternion: Checked<[f64; 4]>,
    ) -> PyResult<()> {
        self.with(py, move |sim| sim.set_mocap_pose(&body, position.0, quaternion.0))
    }

    /// Where the MJCF mocap body `body` is: `(position, quaternion)` (w, x, y, z) in the
    /// file's world frame (see `set_mocap_pose`).
    #[allow(clippy::type_complexity)]
    fn mocap_pose(&self, py: Python<'_>, body: String) -> PyResult<([f64; 3], [f64; 4])> {
        self.with(py, move |sim| sim.mocap_pose(&body))
    }

    /// Writes the scene (see `save_scene`) to the file `path`.
    fn save_scene_to(&self, py: Python<'_>, path: std::path::PathBuf) -> PyResult<()> {
        self.with(py, move |sim| sim.save_scene_to(&path))
    }

    /// The whole state of the simulation now, as bytes (picklable): `restore` puts it
    /// back, in this simulation or in one built by the same code (in any process), and
    /// every later step is the same to the bit. Hooks' own variables are not in it;
    /// records are cleared by `restore`.
    fn snapshot<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, pyo3::types::PyBytes>> {
        let bytes = self.with(py, |sim| sim.snapshot().map(|s| s.to_bytes()))?;
        Ok(pyo3::types::PyBytes::new(py, &bytes))
    }

    /// Puts back the state `snapshot()` returned (see `snapshot`). A snapshot of
    /// another scene raises `ars.SnapshotMismatchError` and changes nothing.
    fn restore(&self, py: Python<'_>, state: &[u8]) -> PyResult<()> {
        let snapshot = guarded(py, || ars_core::Snapshot::from_bytes(state))?;
        self.with(py, move |sim| sim.restore(&snapshot))
    }

    /// A new simulation in the state `snapshot()` returned, built from the scene it
    /// holds (objects, joints, `add_sensor`'s sensors, lidars and depth cameras; a
    /// robot whose links have several collision shapes needs the scene built by your
    /// code, then `restore`).
    #[staticmethod]
    fn from_snapshot(py: Python<'_>, state: &[u8]) -> PyResult<Self> {
        let sim = guarded(py, || ars_core::Snapshot::from_bytes(state).and_then(|s| Simulation::from_snapshot(&s)))?;
        Ok(PySimulation::wrap(sim))
    }

    /// A simulation from a file written by `save_scene_to`.
    #[staticmethod]
    fn load_scene_from(py: Python<'_>, path: std::path::PathBuf) -> PyResult<Self> {
        let sim = guarded(py, || Simulation::load_scene_from(&path))?;
        Ok(PySimulation::wrap(sim))
    }

    /// A simulation from any file ARS reads, by its extension: a scene file (`.json`), a
    /// URDF robot with its root at the origin over a floor, raised to rest on it
    /// (`.urdf`), or a MuJoCo model (`.xml`, `.mjcf`; what ARS cannot read is
    /// skipped, said in one `UserWarning` that counts them by kind:
    /// `load_mjcf(path, skip_unsupported=True)["skipped"]` lists each). What ARS
    /// corrected is said in a `UserWarning` each. What the viewer's Open button and
    /// `ars view FILE` open.
    #[staticmethod]
    fn open(py: Python<'_>, path: std::path::PathBuf) -> PyResult<Self> {
        let opened = guarded(py, || Simulation::open(&path))?;
        let summary = opened
            .skipped_summary()
            .map(|line| format!("{line} (in Python: load_mjcf(path, skip_unsupported=True)[\"skipped\"])"));
        for line in summary.into_iter().chain(opened.adjusted.iter().map(|a| format!("adjusted: {a}"))) {
            let message = std::ffi::CString::new(line).unwrap_or_default();
            PyErr::warn(py, &py.get_type::<pyo3::exceptions::PyUserWarning>(), &message, 1)?;
        }
        Ok(PySimulation::wrap(opened.simulation))
    }

    /// The scene as JSON text (objects, joints, parameters, state).
    fn save_scene(&self, py: Python<'_>) -> PyResult<String> {
        self.with(py, |sim| sim.save_scene())
    }

    /// A simulation from JSON text written by `save_scene`.
    #[staticmethod]
    fn load_scene(py: Python<'_>, text: &str) -> PyResult<Self> {
        let sim = guarded(py, || Simulation::load_scene(text))?;
        Ok(PySimulation::wrap(sim))
    }
}
