//! A browser replay: one self-contained HTML file holding every object's shape, colour
//! and pose over time, with its own small WebGL player (orbit camera, play/pause, a
//! time slider, speed, plots of chosen sensor columns). It needs no network and no
//! library: the player is ARS's own JavaScript (`player.js`), inlined.
//!
//! The data is one deflated block, base64 in the page: a JSON header (the view, the
//! objects and their parts, where the arrays are) followed by the arrays, `float32`,
//! `uint32`, `uint16` and `int8` little-endian. Every shape is sent as triangles with
//! normals, made once here (`tessellate.rs`) and shared by the parts of that shape:
//! the player draws them as they are. The browser inflates it with
//! `DecompressionStream`.

mod encode;
mod tessellate;

use std::collections::HashMap;
use std::io::Write;
use std::path::{Path, PathBuf};

use ars_core::nalgebra::Isometry3;
use ars_core::{ObjectId, Program, Shape, Simulation, WindowSettings};
use serde_json::{Value, json};

use crate::driver::{BareSimulation, Driver};
use crate::error::{Result, ViewerError};
use crate::look::{Look, look_of};
use crate::recorder::{frames_in, run_program};
use encode::Blob;
use tessellate::tessellate;

/// The page around the player, with the places for the title, the script and the data.
const PAGE: &str = include_str!("player.html");
/// The player.
const PLAYER: &str = include_str!("player.js");
/// The most points kept for a plot (a longer log is thinned evenly).
const PLOT_POINTS: usize = 5000;
/// The kiss3d orbit camera's lens, which the off-screen renderer and the window use:
/// vertical field of view (rad), near and far planes (m).
const FOV_Y: f64 = std::f64::consts::FRAC_PI_4;
const NEAR: f64 = 0.1;
const FAR: f64 = 1000.0;

/// Records a browser replay of a running simulation: every object's shape and colour
/// once, and the poses of the moving ones at a frame rate (one sample per simulation
/// frame at most, at the first frame ending at or after each `k / fps` seconds after
/// the start), with the plots of chosen sensor columns.
///
/// ```no_run
/// use ars_core::{Hooks, Mass, Program, Result, Simulation};
/// use ars_viewer::ReplayRecorder;
///
/// struct Ball;
/// impl Hooks for Ball {}
/// impl Program for Ball {
///     fn create_sim_objects(&mut self, sim: &mut Simulation) -> Result<()> {
///         sim.scene_mut().add_sphere(0.5, [0.0, 2.0, 0.0], Mass::Total(1.0)).map(drop)
///     }
/// }
/// let (_, replay) = ReplayRecorder::new().fps(30.0).record_to(&mut Ball, 5.0, "ball.html").unwrap();
/// println!("{} frames, {} bytes", replay.frames(), replay.html().len());
/// ```
#[derive(Clone, Debug, Default)]
pub struct ReplayRecorder {
    fps: Option<f64>,
    plots: Vec<String>,
    size: Option<(u32, u32)>,
}

/// A recorded replay: the HTML page.
#[derive(Clone, Debug)]
pub struct Replay {
    html: String,
    frames: usize,
    start: f64,
    end: f64,
}

impl Replay {
    /// The page, self-contained.
    pub fn html(&self) -> &str {
        &self.html
    }

    /// The number of pose samples.
    pub fn frames(&self) -> usize {
        self.frames
    }

    /// The simulated time of the first and of the last sample, s.
    pub fn span(&self) -> (f64, f64) {
        (self.start, self.end)
    }

    /// Writes the page to `path` (through a temporary file in the same folder, renamed
    /// when complete: never a half-written file).
    pub fn save(&self, path: impl AsRef<Path>) -> Result<()> {
        let mut file = PendingFile::create(path.as_ref())?;
        file.write(self.html.as_bytes())?;
        file.commit()
    }
}

impl ReplayRecorder {
    /// A recorder at the simulation's frame rate, plotting nothing.
    pub fn new() -> Self {
        ReplayRecorder::default()
    }

    /// Pose samples per second of simulated time (default: the simulation's frame
    /// rate, `1 / (time_step × steps_per_frame)`; at most one per simulation frame).
    #[must_use]
    pub fn fps(mut self, fps: f64) -> Self {
        self.fps = Some(fps);
        self
    }

    /// Plots a sensor column under the 3D view: `"Gps 1: y [m]"`, the sensor's type,
    /// its number among the simulation's sensors (from 1) and its column, as the CSV
    /// of `ars run --csv` heads it; the unit may be left out (`"Gps 1: y"`).
    #[must_use]
    pub fn plot(mut self, column: impl Into<String>) -> Self {
        self.plots.push(column.into());
        self
    }

    /// The view's size instead of the program's (the player's canvas, pixels).
    #[must_use]
    pub fn size(mut self, width: u32, height: u32) -> Self {
        self.size = Some((width, height));
        self
    }

    /// Runs `program` for `duration` seconds of simulated time and writes its replay
    /// to `path` (see [`Replay::save`]); returns the simulation and the replay. Bad
    /// settings, a program with no objects, an unknown plot column or a folder that
    /// cannot be written are refused before the run, and no file is left behind.
    pub fn record_to<P: Program>(
        &self,
        program: &mut P,
        duration: f64,
        path: impl AsRef<Path>,
    ) -> Result<(Simulation, Replay)> {
        run_program(program, |runner, view| self.record_driven_to(runner, view, duration, path.as_ref()))
    }

    /// Runs `program` for `duration` seconds of simulated time; returns the simulation
    /// and the replay, in memory.
    pub fn record<P: Program>(&self, program: &mut P, duration: f64) -> Result<(Simulation, Replay)> {
        run_program(program, |runner, view| self.record_driven(runner, view, duration))
    }

    /// Runs `sim` itself (its own hooks; no program) for `duration` seconds, seen as
    /// `view` says, and writes the replay to `path` as [`record_to`](Self::record_to)
    /// does. What front ends with simulations of their own (the Python package) call.
    pub fn record_simulation_to(
        &self,
        sim: &mut Simulation,
        view: &WindowSettings,
        duration: f64,
        path: &Path,
    ) -> Result<Replay> {
        self.record_driven_to(&mut BareSimulation(sim), view, duration, path)
    }

    /// As [`record_simulation_to`](Self::record_simulation_to), in memory.
    pub fn record_simulation(&self, sim: &mut Simulation, view: &WindowSettings, duration: f64) -> Result<Replay> {
        self.record_driven(&mut BareSimulation(sim), view, duration)
    }

    /// Runs what `driver` drives for `duration` seconds (whole frames), seen as `view`
    /// says, and writes the replay to `path`.
    pub fn record_driven_to<D: Driver>(
        &self,
        driver: &mut D,
        view: &WindowSettings,
        duration: f64,
        path: &Path,
    ) -> Result<Replay> {
        let frames = frames_in(&driver.simulation(), duration)?;
        let recording = self.begin_to(&driver.simulation(), view, path)?;
        run(driver, recording, frames)
    }

    /// Runs what `driver` drives for `duration` seconds (whole frames), seen as `view`
    /// says; returns the replay, in memory. A stop requested through
    /// [`ars_core::interrupt`] (Ctrl-C) ends it after the frame being run.
    pub fn record_driven<D: Driver>(&self, driver: &mut D, view: &WindowSettings, duration: f64) -> Result<Replay> {
        let frames = frames_in(&driver.simulation(), duration)?;
        let recording = self.begin(&driver.simulation(), view)?;
        run(driver, recording, frames)
    }

    /// Starts a replay of `sim` as it is now, seen as `view` says, for a loop of your
    /// own: call [`ReplayInProgress::frame`] after every frame, then
    /// [`finish`](ReplayInProgress::finish). The settings are checked here: a frame
    /// rate that is not positive, no objects, an unknown plot column are refused.
    pub fn begin(&self, sim: &Simulation, view: &WindowSettings) -> Result<ReplayInProgress> {
        let frame_rate = 1.0 / (sim.scene().time_step() * f64::from(sim.scene().steps_per_frame()));
        let fps = self.fps.unwrap_or(frame_rate);
        if !(fps.is_finite() && fps > 0.0) {
            return Err(ViewerError::InvalidSetting(format!("a replay's frame rate must be positive, got {fps}")));
        }
        let mut view = view.clone();
        if let Some(size) = self.size {
            view.size = size;
        }
        let (w, h) = view.size;
        if w == 0 || h == 0 || w > 8192 || h > 8192 {
            return Err(ViewerError::InvalidSetting(format!(
                "a replay's size {w}×{h} must be between 1 and 8192 pixels"
            )));
        }
        if sim.scene().objects().next().is_none() {
            return Err(ViewerError::InvalidSetting("nothing to replay: the simulation has no objects".into()));
        }
        let columns = self.plots.iter().map(|p| find_column(sim, p)).collect::<Result<Vec<_>>>()?;
        let ids: Vec<ObjectId> = sim.scene().objects().map(|(_, id)| id).collect();
        let looks = ids.iter().enumerate().map(|(i, id)| look_of(sim, *id, i)).collect::<ars_core::Result<_>>()?;
        let mut recording = ReplayInProgress {
            view,
            objects: Objects::new(ids, looks),
            track: Track::default(),
            columns,
            fps,
            start: sim.scene().time(),
            next: 1,
            file: None,
        };
        recording.track.sample(sim, &recording.objects);
        Ok(recording)
    }

    /// As [`begin`](Self::begin), the replay to be written to `path` when it
    /// finishes: the folder is tried now (a temporary file is made in it), so that a
    /// long run is not lost to a bad path; nothing is left there if the replay never
    /// finishes.
    pub fn begin_to(&self, sim: &Simulation, view: &WindowSettings, path: &Path) -> Result<ReplayInProgress> {
        let mut recording = self.begin(sim, view)?;
        recording.file = Some(PendingFile::create(path)?);
        Ok(recording)
    }
}

/// Runs `frames` frames of what `driver` drives into `recording`, then finishes it.
fn run<D: Driver>(driver: &mut D, mut recording: ReplayInProgress, frames: u64) -> Result<Replay> {
    for _ in 0..frames {
        if ars_core::interrupt::requested() {
            break;
        }
        driver.step_frame()?;
        recording.frame(&driver.simulation());
    }
    recording.finish(&driver.simulation())
}

/// A replay being recorded (see [`ReplayRecorder::begin`]).
pub struct ReplayInProgress {
    view: WindowSettings,
    objects: Objects,
    track: Track,
    columns: Vec<Column>,
    fps: f64,
    /// The simulated time of the first sample, s.
    start: f64,
    /// The number of the next sample due (at `start + next / fps`).
    next: u64,
    /// Where it goes, if it is written when it finishes.
    file: Option<PendingFile>,
}

impl ReplayInProgress {
    /// Samples the poses of `sim` if a sample is due (at most one a call).
    pub fn frame(&mut self, sim: &Simulation) {
        let elapsed = sim.scene().time() - self.start + 0.5 * sim.scene().time_step();
        if elapsed >= self.next as f64 / self.fps {
            self.track.sample(sim, &self.objects);
            self.next = (elapsed * self.fps).floor() as u64 + 1;
        }
    }

    /// Samples `sim` if due, takes the plotted columns from its sensors' records, and
    /// makes the page (written to its file, if it has one).
    pub fn finish(mut self, sim: &Simulation) -> Result<Replay> {
        self.frame(sim);
        let end = self.track.times.last().copied().unwrap_or(self.start);
        let plots = self.columns.iter().map(|c| c.points(sim, self.start, end)).collect();
        let html = page(&self.view, &self.objects, &self.track, plots);
        if let Some(mut file) = self.file.take() {
            file.write(html.as_bytes())?;
            file.commit()?;
        }
        Ok(Replay { html, frames: self.track.times.len(), start: self.start, end })
    }
}

/// A plotted sensor column: which table, which column, and its label.
struct Column {
    table: usize,
    column: usize,
    label: String,
}

impl Column {
    /// The column's samples from `start` to `end` (s), at most [`PLOT_POINTS`].
    fn points(&self, sim: &Simulation, start: f64, end: f64) -> (String, Vec<f32>, Vec<f32>) {
        let tables = sim.sensor_tables();
        let Some((_, log)) = tables.get(self.table) else { return (self.label.clone(), Vec::new(), Vec::new()) };
        let slack = 0.5 * sim.scene().time_step();
        let kept: Vec<usize> =
            (0..log.len()).filter(|i| (start - slack..=end + slack).contains(&log.stamp(*i).0)).collect();
        let every = kept.len().div_ceil(PLOT_POINTS).max(1);
        let (mut times, mut values) = (Vec::new(), Vec::new());
        for i in kept.into_iter().step_by(every) {
            if let Some(v) = log.cells(i).get(self.column).copied().flatten() {
                times.push(log.stamp(i).0 as f32);
                values.push(v as f32);
            }
        }
        (self.label.clone(), times, values)
    }
}

/// The sensor column `spec` names (see [`ReplayRecorder::plot`]).
fn find_column(sim: &Simulation, spec: &str) -> Result<Column> {
    let tables = sim.sensor_tables();
    let mut known = Vec::new();
    for (i, (kind, log)) in tables.iter().enumerate() {
        for (c, header) in log.headers().iter().enumerate() {
            let full = format!("{kind} {}: {header}", i + 1);
            let bare = header.split(" [").next().unwrap_or(header);
            if spec == full || spec == format!("{kind} {}: {bare}", i + 1) {
                return Ok(Column { table: i, column: c, label: full });
            }
            known.push(full);
        }
    }
    let choices = if known.is_empty() { "the simulation has no sensors".to_string() } else { known.join(", ") };
    Err(ViewerError::InvalidSetting(format!("no sensor column {spec:?} to plot; the columns are: {choices}")))
}

/// The objects of a replay, as they looked when it started.
struct Objects {
    ids: Vec<ObjectId>,
    looks: Vec<Look>,
}

impl Objects {
    fn new(ids: Vec<ObjectId>, looks: Vec<Look>) -> Self {
        Objects { ids, looks }
    }

    /// The moving ones.
    fn dynamic(&self) -> impl Iterator<Item = ObjectId> + '_ {
        self.ids.iter().zip(&self.looks).filter(|(_, l)| l.dynamic).map(|(id, _)| *id)
    }
}

/// The samples: their times, and per sample the moving objects' poses (position and
/// quaternion x, y, z, w; NaN once an object is gone).
#[derive(Default)]
struct Track {
    times: Vec<f64>,
    poses: Vec<f32>,
}

impl Track {
    fn sample(&mut self, sim: &Simulation, objects: &Objects) {
        self.times.push(sim.scene().time());
        for id in objects.dynamic() {
            match sim.scene().pose(id) {
                Ok(pose) => self.poses.extend(pose_values(&pose)),
                Err(_) => self.poses.extend([f32::NAN; 7]),
            }
        }
    }
}

/// A pose as position and quaternion (x, y, z, w).
fn pose_values(pose: &Isometry3<f64>) -> [f32; 7] {
    let (t, q) = (pose.translation.vector, pose.rotation);
    [t.x, t.y, t.z, q.i, q.j, q.k, q.w].map(|v| v as f32)
}

/// The triangles of a replay's parts, each shape's sent once (parts of the same shape
/// share them), as the player reads them: positions (`f32`), unit normals (`i8`,
/// WebGL's normalized bytes) and three vertex indices a triangle (`u16`, or `u32`
/// for a mesh of more than 65536 vertices), each sent as its difference from the one
/// before, wrapping (a grid's indices are the same few steps over and over: they
/// deflate to half the size); the player sums them back.
#[derive(Default)]
struct Meshes {
    json: Vec<Value>,
    /// The number of each shape's, by the shape (its `Debug` form: every number exact).
    known: HashMap<String, usize>,
}

impl Meshes {
    /// The number of `shape`'s triangles in [`json`](Self::json), their arrays put
    /// into `blob` if they are new.
    fn of(&mut self, shape: &Shape, blob: &mut Blob) -> usize {
        let key = format!("{shape:?}");
        if let Some(index) = self.known.get(&key) {
            return *index;
        }
        let t = tessellate(shape);
        let positions: Vec<f32> = t.positions.iter().flatten().copied().collect();
        let normals: Vec<i8> = t.normals.iter().flatten().map(|v| (v.clamp(-1.0, 1.0) * 127.0).round() as i8).collect();
        let mut last = 0u32;
        let indices = t.indices.iter().flatten().map(|i| {
            let difference = i.wrapping_sub(last);
            last = *i;
            difference
        });
        let indices = if t.positions.len() <= 1 << 16 {
            // A difference's low 16 bits are the difference of the indices' as `u16`s.
            blob.u16s(&indices.map(|i| i as u16).collect::<Vec<_>>())
        } else {
            blob.u32s(&indices.collect::<Vec<_>>())
        };
        self.json
            .push(json!({ "positions": blob.f32s(&positions), "normals": blob.i8s(&normals), "indices": indices }));
        self.known.insert(key, self.json.len() - 1);
        self.json.len() - 1
    }
}

/// The page of a replay.
fn page(view: &WindowSettings, objects: &Objects, track: &Track, plots: Vec<(String, Vec<f32>, Vec<f32>)>) -> String {
    let mut blob = Blob::default();
    let mut meshes = Meshes::default();
    let mut next_track = 0;
    let objects_json: Vec<Value> = objects
        .looks
        .iter()
        .map(|look| {
            let parts: Vec<Value> = look
                .parts
                .iter()
                .map(|p| json!({ "mesh": meshes.of(&p.shape, &mut blob), "pose": pose_values(&p.local), "color": p.color }))
                .collect();
            let track_index = look.dynamic.then(|| {
                next_track += 1;
                next_track - 1
            });
            json!({ "floor": look.floor, "pose": pose_values(&look.pose), "track": track_index, "parts": parts })
        })
        .collect();
    let times: Vec<f32> = track.times.iter().map(|t| *t as f32).collect();
    let plots_json: Vec<Value> = plots
        .iter()
        .map(|(label, t, v)| json!({ "label": label, "times": blob.f32s(t), "values": blob.f32s(v) }))
        .collect();
    let header = json!({
        "version": 2,
        "title": view.title,
        "view": {
            "size": [view.size.0, view.size.1],
            "eye": [view.camera_position.x, view.camera_position.y, view.camera_position.z],
            "target": [view.camera_target.x, view.camera_target.y, view.camera_target.z],
            "up": [0.0, 1.0, 0.0],
            "fov_y": FOV_Y,
            "near": NEAR,
            "far": FAR,
            "background": view.background,
        },
        "times": blob.f32s(&times),
        "poses": blob.f32s(&track.poses),
        "tracks": next_track,
        "meshes": meshes.json,
        "objects": objects_json,
        "plots": plots_json,
    });
    let data = encode::pack(&header, &blob);
    PAGE.replace("{{TITLE}}", &encode::html_escape(&view.title))
        .replace("{{PLAYER}}", PLAYER)
        .replace("{{DATA}}", &data)
}

/// A file being written: a temporary file beside the target, renamed over it when
/// complete, removed if it never is.
struct PendingFile {
    target: PathBuf,
    temporary: PathBuf,
    file: std::fs::File,
}

impl PendingFile {
    /// Creates the temporary file (the folder must exist and be writable).
    fn create(target: &Path) -> Result<Self> {
        let failed = |kind, message| ViewerError::write(target, std::io::Error::new(kind, message));
        let name =
            target.file_name().ok_or_else(|| failed(std::io::ErrorKind::InvalidInput, "the path names no file"))?;
        if target.is_dir() {
            return Err(failed(std::io::ErrorKind::IsADirectory, "it is a folder"));
        }
        let mut temporary_name = std::ffi::OsString::from(".");
        temporary_name.push(name);
        temporary_name.push(format!(".{}.partial", std::process::id()));
        let temporary = target.with_file_name(temporary_name);
        let file = std::fs::File::create(&temporary).map_err(|e| ViewerError::write(target, e))?;
        Ok(PendingFile { target: target.to_path_buf(), temporary, file })
    }

    fn failed(&self, e: std::io::Error) -> ViewerError {
        ViewerError::write(&self.target, e)
    }

    fn write(&mut self, bytes: &[u8]) -> Result<()> {
        self.file.write_all(bytes).map_err(|e| self.failed(e))
    }

    /// Renames the complete temporary file over the target.
    fn commit(self) -> Result<()> {
        self.file.sync_all().map_err(|e| self.failed(e))?;
        std::fs::rename(&self.temporary, &self.target).map_err(|e| self.failed(e))
    }
}

impl Drop for PendingFile {
    /// Removes the temporary file if it was not renamed (a failed write, an error
    /// during the run).
    fn drop(&mut self) {
        if self.temporary.exists() {
            let _ = std::fs::remove_file(&self.temporary);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use ars_core::Mass;
    use ars_core::nalgebra::{Point3, Vector3};

    /// A mesh of the page's header, read back from its arrays: positions, normals
    /// (as `i8`) and indices (summed back from their differences).
    fn read_mesh(arrays: &[u8], mesh: &Value) -> (Vec<f32>, Vec<i8>, Vec<u32>) {
        let at = |name: &str, size: usize| {
            let (offset, count) = (mesh[name]["offset"].as_u64().unwrap(), mesh[name]["count"].as_u64().unwrap());
            arrays[offset as usize..(offset + count * size as u64) as usize].chunks(size)
        };
        let positions = at("positions", 4).map(|b| f32::from_le_bytes(b.try_into().unwrap())).collect();
        let normals = at("normals", 1).map(|b| b[0] as i8).collect();
        let mut sum = 0u32;
        let indices = if mesh["indices"]["type"] == "u16" {
            at("indices", 2)
                .map(|b| {
                    sum = u32::from((sum as u16).wrapping_add(u16::from_le_bytes(b.try_into().unwrap())));
                    sum
                })
                .collect()
        } else {
            assert_eq!(mesh["indices"]["type"], "u32");
            at("indices", 4)
                .map(|b| {
                    sum = sum.wrapping_add(u32::from_le_bytes(b.try_into().unwrap()));
                    sum
                })
                .collect()
        };
        (positions, normals, indices)
    }

    /// `mesh` (read back) is `shape`'s tessellation, its normals to the nearest byte.
    fn assert_sent_as_tessellated(arrays: &[u8], mesh: &Value, shape: &Shape) {
        let t = tessellate(shape);
        let (positions, normals, indices) = read_mesh(arrays, mesh);
        assert_eq!(positions, t.positions.iter().flatten().copied().collect::<Vec<_>>());
        assert_eq!(normals.len(), positions.len());
        for (byte, normal) in normals.iter().zip(t.normals.iter().flatten()) {
            assert!((f32::from(*byte) / 127.0 - normal).abs() <= 0.5 / 127.0, "{byte} for {normal}");
        }
        assert_eq!(indices, t.indices.iter().flatten().copied().collect::<Vec<_>>());
    }

    #[test]
    fn parts_of_one_shape_share_its_triangles_and_the_arrays_are_the_tessellation() {
        let mut sim = Simulation::new().unwrap();
        for x in [0.0, 1.0] {
            sim.scene_mut().add_sphere(0.2, [x, 1.0, 0.0], Mass::Total(1.0)).unwrap();
        }
        sim.scene_mut().add_sphere(0.3, [2.0, 1.0, 0.0], Mass::Total(1.0)).unwrap();
        sim.scene_mut().add_floor_plane(Vector3::y(), 0.0).unwrap();
        let replay = ReplayRecorder::new().record_simulation(&mut sim, &WindowSettings::default(), 0.1).unwrap();
        let data = replay.html().split("id=\"ars-data\">").nth(1).unwrap().split("</script>").next().unwrap();
        let (header, arrays) = encode::tests::unpack(data);
        let meshes: Vec<u64> =
            header["objects"].as_array().unwrap().iter().map(|o| o["parts"][0]["mesh"].as_u64().unwrap()).collect();
        // The objects in the replay's order, each shape's triangles sent the first time.
        let mut shapes: Vec<Shape> = Vec::new();
        let mut expected = Vec::new();
        for (_, id) in sim.scene().objects() {
            let shape = sim.scene().object(id).unwrap().shape().clone();
            expected.push(shapes.iter().position(|s| *s == shape).unwrap_or_else(|| {
                shapes.push(shape);
                shapes.len() - 1
            }) as u64);
        }
        assert_eq!(shapes.len(), 3);
        assert_eq!(meshes, expected);
        assert_eq!(header["meshes"].as_array().unwrap().len(), shapes.len());
        for (mesh, shape) in header["meshes"].as_array().unwrap().iter().zip(&shapes) {
            assert_eq!(mesh["indices"]["type"], "u16");
            assert_sent_as_tessellated(&arrays, mesh, shape);
        }
    }

    #[test]
    fn a_mesh_of_more_than_65536_vertices_has_u32_indices() {
        // 22000 triangles apart: 66000 vertices.
        let vertices: Vec<Point3<f64>> = (0..22000)
            .flat_map(|k| [[k as f64, 0.0, 0.0], [k as f64 + 0.5, 0.0, 0.0], [k as f64, 1.0, 0.0]])
            .map(Point3::from)
            .collect();
        let triangles = (0..22000).map(|k| [3 * k, 3 * k + 1, 3 * k + 2]).collect();
        let (big, small) = (Shape::TriMesh { vertices, triangles }, Shape::Sphere { radius: 1.0 });
        let (mut meshes, mut blob) = (Meshes::default(), Blob::default());
        assert_eq!([&big, &small, &big].map(|s| meshes.of(s, &mut blob)), [0, 1, 0]);
        let (header, arrays) = encode::tests::unpack(&encode::pack(&json!(meshes.json), &blob));
        assert_eq!(header[0]["indices"]["type"], "u32");
        assert_sent_as_tessellated(&arrays, &header[0], &big);
        assert_sent_as_tessellated(&arrays, &header[1], &small);
    }
}
