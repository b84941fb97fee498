//! `ars`: run, view and record a scene file or a URDF robot from the command line.
//!
//! `cargo install --path .` puts it on the `PATH`; `cargo run --release --bin ars --
//! run FILE` runs it from the workspace. `ars --help` lists the commands.

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use ars::nalgebra::{Point3, Vector3};
use ars::sensors::{CsvColumns, Gps, JointPositions};
use ars::{FileFormat, Hooks, JointType, Program, Simulation, SimulationBuilder, SpaceKind, UrdfOptions, ViewSettings};

const USAGE: &str = "\
ars: run, view and record ARS scenes and URDF robots

usage:
  ars run FILE [--duration S] [--csv OUT] [--every N]
  ars view FILE [--screenshots DIR | --video OUT.mp4] [--duration S] [--frame-every N]
           [--size WxH] [--axes] [--views N] [--csv OUT]
  ars record FILE --screenshots DIR [--duration S] [--frame-every N] [--size WxH] [--axes]
           [--views N] [--csv OUT]
  ars record FILE --video OUT.mp4 [--fps N] [--duration S] [--size WxH] [--axes] ...
  ars record FILE --html OUT.html [--html-plot COLUMN]... [--duration S] [--size WxH]
  ars --help | --version

FILE is a scene file (.json: Simulation::save_scene_to, sim.save_scene_to in Python,
Ctrl+S in the window; saved at any step, it goes on exactly where it was), a robot
(.urdf, its root at --at over the floor y = 0; --fixed-base bolts it to the world) or a
MuJoCo model (.xml, MJCF; what ARS cannot read is skipped and said).

  run       simulate without graphics and print a summary; --csv writes the scene's
            sensors (or, if it has none, every body's position) every N steps; with
            view and record, --csv writes what was simulated until the end
  view      open a window (Escape closes it; --video records it); without a display,
            record off screen into --screenshots or --video
  record    render off screen (no display or GPU needed) into DIR/frame_00001.png...,
            into an H.264 MP4 video (frame k at k/fps simulated seconds), or into a
            browser replay: one HTML file that plays the run back in any browser, no
            network needed (--html-plot \"Gps 1: y\" plots a sensor column, as ars run
            --csv heads it)

  --duration S      simulated seconds (default: run and record 10, view until closed)
  --every N         one CSV row every N steps (default 1)
  --frame-every N   one picture every N frames (default 5)
  --fps N           the video's frames per second (default 30)
  --size WxH        picture or window size in pixels (default 1024x768)
  --axes            draw the world axes
  --views N         split the picture into N views (1-4): free, following, top, camera
  --fixed-base      (URDF) fix the robot's root to the world
  --y-up            (URDF) the file is written Y up (URDF's convention is Z up)
  --at X,Y,Z        (URDF, MJCF) where its root starts, m (default 0,0,0)";

/// What was asked.
struct Command {
    verb: String,
    file: PathBuf,
    duration: Option<f64>,
    csv: Option<PathBuf>,
    every: usize,
    screenshots: Option<PathBuf>,
    html: Option<PathBuf>,
    html_plots: Vec<String>,
    frame_every: u32,
    video: Option<PathBuf>,
    fps: f64,
    size: Option<(u32, u32)>,
    axes: bool,
    views: usize,
    fixed_base: bool,
    y_up: bool,
    at: Vector3<f64>,
}

/// Parses the command line; `Err` is the message to print.
fn parse(args: &[String]) -> Result<Command, String> {
    let mut args = args.iter();
    let verb = args.next().ok_or("a command is needed: run, view or record")?.clone();
    if !["run", "view", "record"].contains(&verb.as_str()) {
        return Err(format!("unknown command {verb:?}: run, view or record"));
    }
    let file = PathBuf::from(args.next().ok_or(format!("ars {verb} needs a FILE (a scene .json or a .urdf)"))?);
    let mut command = Command {
        verb,
        file,
        duration: None,
        csv: None,
        every: 1,
        screenshots: None,
        html: None,
        html_plots: Vec::new(),
        frame_every: 5,
        video: None,
        fps: 30.0,
        size: None,
        axes: false,
        views: 1,
        fixed_base: false,
        y_up: false,
        at: Vector3::zeros(),
    };
    while let Some(flag) = args.next() {
        let mut value = |name: &str| args.next().cloned().ok_or(format!("{name} needs a value"));
        let positive = |name: &str, v: String| match v.parse::<u64>() {
            Ok(n) if n > 0 => Ok(n),
            _ => Err(format!("{name} must be a positive whole number, got {v:?}")),
        };
        match flag.as_str() {
            "--duration" => {
                let v = value("--duration")?;
                command.duration = match v.parse::<f64>() {
                    Ok(d) if d.is_finite() && d > 0.0 => Some(d),
                    _ => return Err(format!("--duration must be a positive number of seconds, got {v:?}")),
                };
            }
            "--csv" => command.csv = Some(value("--csv")?.into()),
            "--every" => command.every = positive("--every", value("--every")?)? as usize,
            "--screenshots" => command.screenshots = Some(value("--screenshots")?.into()),
            "--video" => command.video = Some(value("--video")?.into()),
            "--fps" => {
                let v = value("--fps")?;
                command.fps = match v.parse::<f64>() {
                    Ok(f) if f.is_finite() && f > 0.0 => f,
                    _ => return Err(format!("--fps must be a positive number of frames per second, got {v:?}")),
                };
            }
            "--html" => command.html = Some(value("--html")?.into()),
            "--html-plot" => command.html_plots.push(value("--html-plot")?),
            "--frame-every" => {
                let n = positive("--frame-every", value("--frame-every")?)?;
                command.frame_every = u32::try_from(n).map_err(|_| format!("--frame-every is too large: {n}"))?;
            }
            "--size" => {
                let v = value("--size")?;
                let parsed =
                    v.split_once('x').and_then(|(w, h)| Some((w.parse::<u32>().ok()?, h.parse::<u32>().ok()?)));
                command.size = match parsed {
                    Some((w, h)) if w > 0 && h > 0 => Some((w, h)),
                    _ => return Err(format!("--size must look like 800x600, got {v:?}")),
                };
            }
            "--axes" => command.axes = true,
            "--views" => {
                let v = value("--views")?;
                command.views = match v.parse::<usize>() {
                    Ok(n) if (1..=4).contains(&n) => n,
                    _ => return Err(format!("--views must be 1, 2, 3 or 4, got {v:?}")),
                };
            }
            "--fixed-base" => command.fixed_base = true,
            "--y-up" => command.y_up = true,
            "--at" => {
                let v = value("--at")?;
                let xyz: Vec<f64> = v.split(',').filter_map(|c| c.trim().parse().ok()).collect();
                command.at = match xyz[..] {
                    [x, y, z] if xyz.iter().all(|c| c.is_finite()) => Vector3::new(x, y, z),
                    _ => return Err(format!("--at must look like 0,0.5,0, got {v:?}")),
                };
            }
            other => return Err(format!("unknown option {other:?}")),
        }
    }
    if command.verb == "record" && command.screenshots.is_none() && command.html.is_none() && command.video.is_none() {
        return Err("ars record needs --screenshots DIR, --video OUT.mp4 or --html OUT.html".into());
    }
    if command.html.is_some() && (command.verb != "record" || command.screenshots.is_some()) {
        return Err("--html goes with ars record, without --screenshots".into());
    }
    if !command.html_plots.is_empty() && command.html.is_none() {
        return Err("--html-plot goes with --html".into());
    }
    if command.video.is_some() && (command.verb == "run" || command.screenshots.is_some() || command.html.is_some()) {
        return Err("--video goes with ars record or ars view, without --screenshots or --html".into());
    }
    Ok(command)
}

/// A file as a program: its scene (a scene file as saved, or a robot on the floor),
/// with a sensor to write when the scene has none.
struct FileProgram {
    path: PathBuf,
    urdf: UrdfOptions,
    summary: String,
}

impl FileProgram {
    fn is_urdf(&self) -> bool {
        FileFormat::of(&self.path).is_ok_and(|f| f == FileFormat::Urdf)
    }

    /// MuJoCo's MJCF: `.xml` (or `.mjcf`).
    fn is_mjcf(&self) -> bool {
        FileFormat::of(&self.path).is_ok_and(|f| f == FileFormat::Mjcf)
    }
}

impl Hooks for FileProgram {}

impl Program for FileProgram {
    fn configure(&self, builder: SimulationBuilder) -> SimulationBuilder {
        builder.space(SpaceKind::Simple).floor_plane(Vector3::y(), 0.0)
    }

    fn view_settings(&self) -> ViewSettings {
        ViewSettings {
            title: format!("ARS: {}", self.path.display()),
            camera_position: Point3::new(3.0, 2.0, 3.0),
            camera_target: Point3::new(0.0, 0.4, 0.0),
            ..Default::default()
        }
    }

    fn create_simulation(&mut self) -> ars::Result<Simulation> {
        FileFormat::of(&self.path)?;
        let mut sim = if self.is_mjcf() {
            // As the viewer's Open button opens it (with the model's gravity).
            let opened = Simulation::open_at(&self.path, self.urdf.base_pose)?;
            if let Some(line) = opened.skipped_summary() {
                eprintln!("{line}");
            }
            opened.simulation
        } else if self.is_urdf() {
            let mut sim = self.configure(Simulation::builder()).build()?;
            self.create_sim_objects(&mut sim)?;
            sim
        } else {
            Simulation::load_scene_from(&self.path)?
        };
        if sim.sensor_tables().is_empty() {
            // Something to write: every body's position, or a robot's joints.
            let moving: Vec<_> = sim.scene().joints().map(|(_, id)| id).filter(|id| is_moving(&sim, *id)).collect();
            if self.is_urdf() && !moving.is_empty() {
                let positions = JointPositions::new(sim.scene(), &moving)?;
                sim.add_sensor(positions)?;
            } else {
                let bodies: Vec<_> = sim.scene().bodies().map(|(id, _)| id).collect();
                for id in bodies {
                    sim.add_sensor(Gps::new(id))?;
                }
            }
        }
        self.summary = format!(
            "{}: {} objects, {} joints, t = {} s",
            self.path.display(),
            sim.scene().objects().count(),
            sim.scene().joints().count(),
            sim.scene().time()
        );
        Ok(sim)
    }

    fn create_sim_objects(&mut self, sim: &mut Simulation) -> ars::Result<()> {
        sim.load_urdf(&self.path, &self.urdf).map(drop)
    }
}

/// A joint with one position to write (a hinge, slider or piston).
fn is_moving(sim: &Simulation, joint: ars::JointId) -> bool {
    sim.scene()
        .joint(joint)
        .is_ok_and(|j| matches!(j.joint_type(), JointType::Hinge | JointType::Slider | JointType::Piston))
}

/// Writes every sensor's records as one CSV table.
fn write_csv(sim: &Simulation, path: &Path, every: usize) -> Result<(), Box<dyn std::error::Error>> {
    use std::io::Write;
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir)?;
    }
    let tables = sim.sensor_tables();
    let names: Vec<String> = tables.iter().enumerate().map(|(i, (kind, _))| format!("{kind} {}", i + 1)).collect();
    let logs: Vec<(&str, &dyn CsvColumns)> =
        names.iter().zip(&tables).map(|(name, (_, table))| (name.as_str(), *table)).collect();
    let mut out = std::io::BufWriter::new(std::fs::File::create(path)?);
    ars::sensors::write_csv_table(&mut out, &logs, every)?;
    out.flush()?;
    eprintln!("wrote {}", path.display());
    Ok(())
}

fn run(command: &Command) -> Result<(), Box<dyn std::error::Error>> {
    let mut urdf = UrdfOptions::new().fixed_base(command.fixed_base).base_pose(ars::nalgebra::Isometry3::translation(
        command.at.x,
        command.at.y,
        command.at.z,
    ));
    if command.y_up {
        urdf = urdf.up_axis(ars::UpAxis::Y);
    }
    let mut program = FileProgram { path: command.file.clone(), urdf, summary: String::new() };
    match command.verb.as_str() {
        "run" => {
            ars::interrupt::stop_on_ctrl_c()?;
            let duration = command.duration.unwrap_or(10.0);
            let mut runner = ars::ProgramRunner::new(&mut program)?;
            let start = Instant::now();
            let ran = runner.run_for(duration);
            let wall = start.elapsed().as_secs_f64();
            if let Err(ars::Error::Interrupted { time, .. }) = &ran {
                eprintln!("interrupted (Ctrl-C) at t = {time} s");
            } else {
                ran?;
            }
            let sim = runner.into_simulation();
            println!("{}", program.summary);
            println!(
                "ran to t = {} s ({} steps) in {wall:.3} s of wall time",
                sim.scene().time(),
                sim.scene().step_count()
            );
            if let Some(path) = &command.csv {
                write_csv(&sim, path, command.every)?;
            }
            Ok(())
        }
        _ => show(&mut program, command),
    }
}

#[cfg(feature = "viewer")]
fn show(program: &mut FileProgram, command: &Command) -> Result<(), Box<dyn std::error::Error>> {
    use ars::viewer::{ProgramViewer, ScreenshotRecorder, ViewerOptions};
    let options = ViewerOptions::default().with_axes(command.axes).with_views(command.views);
    let window = command.verb == "view" && ars::viewer::has_display();
    if window {
        eprintln!("{}", ars::viewer::VIEWER_KEYS);
        let sim = match (command.size, command.duration, &command.video) {
            (size, limit, Some(path)) => {
                let view =
                    ViewSettings { size: size.unwrap_or(program.view_settings().size), ..program.view_settings() };
                let mut runner = ars::ProgramRunner::new(program)?;
                // The window runs in real time: a duration is wall seconds here.
                let limit = limit.map(std::time::Duration::from_secs_f64);
                let (_, video) =
                    ars::viewer::run_window_recording(&mut runner, &view, &options, limit, path, command.fps)?;
                println!("recorded the window: {} frames ({} s) into {}", video.frames, video.duration, path.display());
                runner.into_simulation()
            }
            (None, None, None) => program.show_with(&options)?,
            (size, limit, None) => {
                let view =
                    ViewSettings { size: size.unwrap_or(program.view_settings().size), ..program.view_settings() };
                let mut runner = ars::ProgramRunner::new(program)?;
                // The window runs in real time: a duration is wall seconds here.
                let limit = limit.map(std::time::Duration::from_secs_f64);
                ars::viewer::run_window_with(&mut runner, &view, &options, limit)?;
                runner.into_simulation()
            }
        };
        println!("{}", program.summary);
        println!("closed at t = {} s ({} steps)", sim.scene().time(), sim.scene().step_count());
        if let Some(path) = &command.csv {
            write_csv(&sim, path, command.every)?;
        }
        return Ok(());
    }
    if let Some(path) = &command.video {
        // Off screen (ars record, or ars view with no display).
        let mut recorder = ars::viewer::VideoRecorder::new(path).fps(command.fps).options(options);
        if let Some((w, h)) = command.size {
            recorder = recorder.size(w, h);
        }
        let (sim, video) = recorder.record(program, command.duration.unwrap_or(10.0))?;
        println!("{}", program.summary);
        println!(
            "recorded t = {} s: {} frames ({} s at {} frames/s, {} bytes) into {}",
            sim.scene().time(),
            video.frames,
            video.duration,
            video.fps,
            video.bytes,
            path.display()
        );
        if let Some(csv) = &command.csv {
            write_csv(&sim, csv, command.every)?;
        }
        return Ok(());
    }
    if let Some(path) = &command.html {
        let mut recorder = ars::viewer::ReplayRecorder::new();
        for column in &command.html_plots {
            recorder = recorder.plot(column.clone());
        }
        if let Some((w, h)) = command.size {
            recorder = recorder.size(w, h);
        }
        let (sim, replay) = recorder.record_to(program, command.duration.unwrap_or(10.0), path)?;
        println!("{}", program.summary);
        println!(
            "recorded t = {} s: a replay of {} frames into {}",
            sim.scene().time(),
            replay.frames(),
            path.display()
        );
        if let Some(csv) = &command.csv {
            write_csv(&sim, csv, command.every)?;
        }
        return Ok(());
    }
    let Some(dir) = &command.screenshots else {
        return Err(
            "no display (DISPLAY and WAYLAND_DISPLAY are unset): give --screenshots DIR to record off screen".into()
        );
    };
    let mut recorder = ScreenshotRecorder::new(dir).every(command.frame_every).options(options);
    if let Some((w, h)) = command.size {
        recorder = recorder.size(w, h);
    }
    let (sim, written) = recorder.record(program, command.duration.unwrap_or(10.0))?;
    println!("{}", program.summary);
    println!("recorded t = {} s: {} frames into {}", sim.scene().time(), written.len(), dir.display());
    if let Some(path) = &command.csv {
        write_csv(&sim, path, command.every)?;
    }
    Ok(())
}

#[cfg(not(feature = "viewer"))]
fn show(_: &mut FileProgram, command: &Command) -> Result<(), Box<dyn std::error::Error>> {
    Err(format!("ars {} needs the viewer: build ars with its default features", command.verb).into())
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match args.first().map(String::as_str) {
        None | Some("-h" | "--help" | "help") => {
            println!("{USAGE}");
            return if args.is_empty() { ExitCode::from(2) } else { ExitCode::SUCCESS };
        }
        Some("-V" | "--version") => {
            println!("ars {}", env!("CARGO_PKG_VERSION"));
            return ExitCode::SUCCESS;
        }
        _ => {}
    }
    let command = match parse(&args) {
        Ok(command) => command,
        Err(message) => {
            eprintln!("ars: {message}\n(ars --help lists the commands)");
            return ExitCode::from(2);
        }
    };
    match run(&command) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("ars: {e}");
            ExitCode::FAILURE
        }
    }
}
