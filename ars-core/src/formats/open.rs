//! Opening any file ARS reads as a new simulation, by its extension: a scene file
//! (`.json`), a URDF robot (`.urdf`) or a MuJoCo model (`.xml`, `.mjcf`). What the
//! viewer's Open button and `ars view FILE` open.

use std::path::Path;

use nalgebra::{Isometry3, Vector3};

use crate::error::{Error, Result};
use crate::formats::mjcf::{CONTACT_PARAMETERS_UNUSED, MUJOCO_TIMESTEP, MjcfFile, MjcfOptions};
use crate::formats::urdf::UrdfOptions;
use crate::simulation::{DEFAULT_STEPS_PER_FRAME, DEFAULT_TIME_STEP, Simulation};
use crate::world::SpaceKind;

/// The kinds of file [`Simulation::open`] reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FileFormat {
    /// A scene file (`.json`), as [`Simulation::save_scene_to`] writes it.
    Scene,
    /// A URDF robot (`.urdf`).
    Urdf,
    /// A MuJoCo model (`.xml` or `.mjcf`).
    Mjcf,
}

impl FileFormat {
    /// The extensions read, with their formats.
    pub const EXTENSIONS: [(&'static str, FileFormat); 4] = [
        ("json", FileFormat::Scene),
        ("urdf", FileFormat::Urdf),
        ("xml", FileFormat::Mjcf),
        ("mjcf", FileFormat::Mjcf),
    ];

    /// The format of `path`, by its extension (in any case).
    pub fn of(path: impl AsRef<Path>) -> Result<FileFormat> {
        let extension = path.as_ref().extension().and_then(|e| e.to_str()).unwrap_or_default().to_ascii_lowercase();
        FileFormat::EXTENSIONS.iter().find(|(e, _)| *e == extension).map(|(_, format)| *format).ok_or_else(|| {
            Error::UnknownKind {
                what: "file extension",
                name: format!("{}", path.as_ref().display()),
                known: FileFormat::EXTENSIONS.iter().map(|(e, _)| format!(".{e}")).collect(),
            }
        })
    }
}

/// A file opened by [`Simulation::open`].
#[derive(Debug)]
pub struct OpenedFile {
    /// Its simulation.
    pub simulation: Simulation,
    /// What it holds that ARS skipped (MJCF elements it cannot read), said as
    /// sentences: empty for scene files and URDF robots.
    pub skipped: Vec<String>,
    /// What ARS corrected to load it (a URDF link's inertia no body can have), said as
    /// sentences naming what was corrected.
    pub adjusted: Vec<String>,
}

impl OpenedFile {
    /// One line for what ARS skipped (`None` when it skipped nothing): how many items,
    /// and how many of each kind, by the element they are on (a geom's or a pair's
    /// unused contact parameters are their own kind). The whole list is
    /// [`skipped`](Self::skipped), a line per item: one per geom for a model such as
    /// Gymnasium's ant, too many for a terminal.
    pub fn skipped_summary(&self) -> Option<String> {
        if self.skipped.is_empty() {
            return None;
        }
        // (what, element, count), in the order first met.
        let mut kinds: Vec<(&str, &str, usize)> = Vec::new();
        for item in &self.skipped {
            let element = match item.strip_prefix('<').and_then(|rest| rest.find('>')) {
                Some(end) => &item[..end + 2],
                None => item.split_whitespace().next().unwrap_or("item"),
            };
            let what = if item.ends_with(CONTACT_PARAMETERS_UNUSED) { "contact parameters of " } else { "" };
            match kinds.iter_mut().find(|(w, e, _)| *w == what && *e == element) {
                Some((_, _, n)) => *n += 1,
                None => kinds.push((what, element, 1)),
            }
        }
        let kinds: Vec<String> = kinds.iter().map(|(what, element, n)| format!("{what}{n} {element}")).collect();
        Some(format!(
            "skipped {} unsupported MJCF items ({}); each is listed in the opened file's `skipped`",
            self.skipped.len(),
            kinds.join(", ")
        ))
    }
}

impl Simulation {
    /// Opens `path` as a new simulation, by its [`FileFormat`]:
    /// - a scene file as saved, where it was saved (mid-run: exactly);
    /// - a URDF robot, Z up, its root at the origin over a floor plane at y = 0 (default
    ///   [`UrdfOptions`]: raised to rest on the floor if it would reach into it), in a
    ///   simple space;
    /// - a MuJoCo model as its file says: its own floor, gravity and time step
    ///   (MuJoCo's [`MUJOCO_TIMESTEP`] if it gives none; frames of about 20 ms), in a
    ///   simple space, what ARS cannot read skipped and listed in
    ///   [`OpenedFile::skipped`].
    ///
    /// ```
    /// # let dir = std::env::temp_dir().join(format!("ars-open-doc-{}", std::process::id()));
    /// # std::fs::create_dir_all(&dir).unwrap();
    /// use ars_core::{Mass, Simulation};
    /// let mut sim = Simulation::new()?;
    /// sim.scene_mut().add_sphere(0.1, [0.0, 1.0, 0.0], Mass::Total(1.0))?;
    /// sim.save_scene_to(dir.join("ball.json"))?;
    /// let opened = Simulation::open(dir.join("ball.json"))?;
    /// assert_eq!(opened.simulation.scene().objects().count(), 1);
    /// assert!(Simulation::open(dir.join("ball.txt")).is_err());
    /// # std::fs::remove_dir_all(&dir).unwrap();
    /// # Ok::<(), ars_core::Error>(())
    /// ```
    pub fn open(path: impl AsRef<Path>) -> Result<OpenedFile> {
        Simulation::open_at(path, Isometry3::identity())
    }

    /// As [`open`](Self::open), a robot or model's root placed at `base` (a scene file
    /// is where it was saved, whatever `base` says).
    pub fn open_at(path: impl AsRef<Path>, base: Isometry3<f64>) -> Result<OpenedFile> {
        let path = path.as_ref();
        match FileFormat::of(path)? {
            FileFormat::Scene => Ok(OpenedFile {
                simulation: Simulation::load_scene_from(path)?,
                skipped: Vec::new(),
                adjusted: Vec::new(),
            }),
            FileFormat::Urdf => {
                let mut simulation =
                    Simulation::builder().space(SpaceKind::Simple).floor_plane(Vector3::y(), 0.0).build()?;
                let robot = simulation.load_urdf(path, &UrdfOptions::new().base_pose(base))?;
                Ok(OpenedFile { simulation, skipped: Vec::new(), adjusted: robot.adjusted })
            }
            FileFormat::Mjcf => {
                let options = MjcfOptions::new().base_pose(base).skip_unsupported(true);
                let file = MjcfFile::read(path, &options)?;
                // MuJoCo compiles any time step; ARS steps only within its limits: a file
                // outside them is said as the file's problem, naming it.
                let dt = file.timestep().unwrap_or(MUJOCO_TIMESTEP);
                crate::limits::time_step(dt).map_err(|e| Error::Format {
                    format: "MJCF",
                    file: path.display().to_string(),
                    element: "<option timestep>".into(),
                    line: None,
                    column: None,
                    problem: format!("ARS cannot step at it: {e}"),
                })?;
                let mut simulation = Simulation::builder()
                    .space(SpaceKind::Simple)
                    .time_step(dt)
                    .steps_per_frame(steps_per_frame(dt))
                    .build()?;
                let model = file.insert(&mut simulation, &options)?;
                if let Some(gravity) = model.gravity {
                    simulation.scene_mut().world_mut().set_gravity(gravity)?;
                }
                Ok(OpenedFile { simulation, skipped: model.skipped, adjusted: Vec::new() })
            }
        }
    }
}

/// The steps of a frame at a time step of `dt`: as near ARS's frame (50 steps of 0.4
/// ms, 20 ms) as whole steps come, at least one.
fn steps_per_frame(dt: f64) -> u32 {
    let frame = DEFAULT_TIME_STEP * f64::from(DEFAULT_STEPS_PER_FRAME);
    // A time step the builder accepts is positive and finite; 1 to 50,000 steps.
    (frame / dt).round().clamp(1.0, 50_000.0) as u32
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn what_was_skipped_is_said_in_one_line_by_kind() {
        let skipped = [
            format!("<geom> at line 12: friction, condim {CONTACT_PARAMETERS_UNUSED}"),
            format!("<geom> at line 14: margin {CONTACT_PARAMETERS_UNUSED}"),
            "<motor> at line 40: gear 150 is read as ...".to_string(),
        ];
        let opened =
            |skipped: Vec<String>| OpenedFile { simulation: Simulation::new().unwrap(), skipped, adjusted: Vec::new() };
        assert_eq!(
            opened(skipped.to_vec()).skipped_summary().unwrap(),
            "skipped 3 unsupported MJCF items (contact parameters of 2 <geom>, 1 <motor>); \
             each is listed in the opened file's `skipped`"
        );
        assert_eq!(opened(Vec::new()).skipped_summary(), None);
    }
}
