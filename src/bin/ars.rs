//! `ars`: run, view and record a scene file or a URDF robot from the command line.
//!
//! `cargo install --path .` puts it on the `PATH`; `cargo run --release --bin ars --
//! run FILE` runs it from the workspace. `ars --help` lists the commands.

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use ars::cli::{PictureArgs, RunArgs};
use ars::nalgebra::{Point3, Vector3};
use ars::sensors::{CsvColumns, Gps, JointPositions};
use ars::{
    FileFormat, Hooks, JointType, Program, Simulation, SimulationBuilder, SpaceKind, UrdfOptions, WindowSettings,
};
use clap::{CommandFactory, FromArgMatches, Parser, Subcommand};

/// What the verbs read, said under `ars --help`.
const FILES: &str = "\
FILE is a scene file (.json: Simulation::save_scene_to, sim.save_scene_to in Python,
Ctrl+S in the window; saved at any step, it goes on exactly where it was), a robot
(.urdf, its root at --at over the floor y = 0; --fixed-base bolts it to the world) or a
MuJoCo model (.xml, MJCF; what ARS cannot read is skipped and said). `ars VERB --help`
lists a verb's options; with view and record, --csv writes what was simulated until the
end.";

/// The command line: a verb and its file.
#[derive(Parser)]
#[command(name = "ars", version, about = "ars: run, view and record ARS scenes and URDF robots", after_help = FILES)]
#[command(arg_required_else_help = true)]
struct Cli {
    #[command(subcommand)]
    verb: Verb,
}

/// The verbs, each with its file and options.
#[derive(Subcommand)]
enum Verb {
    /// Simulate without graphics and print a summary
    ///
    /// --csv writes the scene's sensors (or, if it has none, every body's position) every N
    /// steps.
    Run(FileArgs),
    /// Open a window, or record off screen where there is no display
    ///
    /// Escape closes the window; --duration is wall seconds there, and --video records it.
    /// Without a display, it records off screen into --screenshots or --video.
    View(FileArgs),
    /// Render off screen into pictures, an MP4 video or a browser replay
    ///
    /// No display or GPU is needed. --html-plot "Gps 1: y" plots a sensor column under the
    /// replay.
    Record(FileArgs),
    /// Run as a live ROS 2 node: /tf, /joint_states, /odom, /scan...; /cmd_vel; services
    ///
    /// No ROS install is needed. Real time until Ctrl-C, or --lock-step (advances only
    /// through /ars/step_simulation). docs/ros2.md ("Live topics") lists the topics and services.
    #[cfg(feature = "ros")]
    Ros(RosFileArgs),
}

/// `ars ros`'s file and options.
#[cfg(feature = "ros")]
#[derive(clap::Args)]
struct RosFileArgs {
    /// A scene file (.json), a robot (.urdf) or a MuJoCo model (.xml)
    file: PathBuf,
    #[command(flatten)]
    placement: Placement,
    /// Stop after this many simulated seconds (default: until Ctrl-C)
    #[arg(long, value_name = "S", value_parser = ars::cli::positive_seconds)]
    duration: Option<f64>,
    #[command(flatten)]
    ros: ars_ros::bridge::cli::RosArgs,
}

/// A verb's file and options.
#[derive(clap::Args)]
struct FileArgs {
    /// A scene file (.json), a robot (.urdf) or a MuJoCo model (.xml)
    file: PathBuf,
    #[command(flatten)]
    run: RunArgs,
    #[command(flatten)]
    pictures: PictureArgs,
    #[command(flatten)]
    placement: Placement,
}

/// How a robot or model file is placed: every verb's, `ars ros`'s too.
#[derive(clap::Args)]
struct Placement {
    /// (URDF) fix the robot's root to the world
    #[arg(long)]
    fixed_base: bool,
    /// (URDF) the file is written Y up (URDF's convention is Z up)
    #[arg(long)]
    y_up: bool,
    /// (URDF, MJCF) where its root starts, m (default 0,0,0)
    #[arg(long, value_name = "X,Y,Z", value_parser = position, allow_hyphen_values = true)]
    at: Option<Vector3<f64>>,
}

fn position(v: &str) -> Result<Vector3<f64>, String> {
    let xyz: Vec<f64> = v.split(',').filter_map(|c| c.trim().parse().ok()).collect();
    match xyz[..] {
        [x, y, z] if xyz.iter().all(|c| c.is_finite()) => Ok(Vector3::new(x, y, z)),
        _ => Err(format!("must look like 0,0.5,0, got {v:?}")),
    }
}

/// What was asked.
struct Command {
    verb: String,
    file: PathBuf,
    duration: Option<f64>,
    csv: Option<PathBuf>,
    every: usize,
    mcap: Option<PathBuf>,
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
    /// `ars ros`'s options.
    #[cfg(feature = "ros")]
    ros: Option<ars_ros::bridge::cli::RosArgs>,
}

/// What the command line asks (`Err`: what clap said, help and version included).
fn parse(args: &[String]) -> Result<Command, clap::Error> {
    let duration = |a: clap::Arg| a.help("Simulated seconds (default: run and record 10, view until closed)");
    let mut command = Cli::command();
    for verb in ["run", "view", "record"] {
        command = command.mut_subcommand(verb, |c| c.mut_arg("duration", duration));
    }
    let matches = command.try_get_matches_from(std::iter::once("ars").chain(args.iter().map(String::as_str)))?;
    let cli = Cli::from_arg_matches(&matches)?;
    let (verb, file) = match cli.verb {
        Verb::Run(file) => ("run", file),
        Verb::View(file) => ("view", file),
        Verb::Record(file) => ("record", file),
        #[cfg(feature = "ros")]
        Verb::Ros(args) => return Ok(ros_command(args)),
    };
    let FileArgs { file, run, pictures, placement: Placement { fixed_base, y_up, at } } = file;
    Ok(Command {
        verb: verb.into(),
        file,
        duration: run.duration,
        csv: run.csv,
        every: run.every,
        mcap: run.mcap,
        screenshots: pictures.screenshots,
        html: pictures.html,
        html_plots: pictures.html_plots,
        frame_every: pictures.frame_every,
        video: pictures.video,
        fps: pictures.fps,
        size: pictures.size,
        axes: pictures.axes,
        views: pictures.views,
        fixed_base,
        y_up,
        at: at.unwrap_or_else(Vector3::zeros),
        #[cfg(feature = "ros")]
        ros: None,
    })
}

/// `ars ros`'s command: its file, and no pictures.
#[cfg(feature = "ros")]
fn ros_command(
    RosFileArgs { file, placement: Placement { fixed_base, y_up, at }, duration, ros }: RosFileArgs,
) -> Command {
    Command {
        verb: "ros".into(),
        file,
        duration,
        csv: None,
        every: 1,
        mcap: None,
        screenshots: None,
        html: None,
        html_plots: Vec::new(),
        frame_every: 1,
        video: None,
        fps: 30.0,
        size: None,
        axes: false,
        views: 1,
        fixed_base,
        y_up,
        at: at.unwrap_or_else(Vector3::zeros),
        ros: Some(ros),
    }
}

/// What clap refused, said as ARS says it: an unknown verb or option, or a missing
/// file, in one line.
fn refusal(args: &[String], e: &clap::Error) -> String {
    use clap::error::{ContextKind, ErrorKind};
    let context = |kind| e.get(kind).map(|v| v.to_string()).unwrap_or_default();
    match e.kind() {
        ErrorKind::InvalidSubcommand => format!("unknown command {:?}: run, view, record or ros", args[0]),
        ErrorKind::UnknownArgument => match context(ContextKind::InvalidArg) {
            option if option.starts_with('-') => format!("unknown option {option:?}"),
            extra => format!("unexpected argument {extra:?}: a command takes one FILE"),
        },
        ErrorKind::MissingRequiredArgument => {
            format!("ars {} needs a FILE (a scene .json, a .urdf or an MJCF .xml)", args[0])
        }
        // "--duration must be a positive number of seconds, got \"-1\"".
        ErrorKind::ValueValidation if std::error::Error::source(e).is_some() => {
            let flag = context(ContextKind::InvalidArg);
            let why = std::error::Error::source(e).map(|why| why.to_string()).unwrap_or_default();
            format!("{} {why}", flag.split_whitespace().next().unwrap_or_default())
        }
        _ => e.render().to_string().trim().trim_start_matches("error: ").lines().next().unwrap_or_default().into(),
    }
}

/// The choices that go together, checked once the options are read.
fn check(command: &Command) -> Result<(), String> {
    let pictures = command.screenshots.is_some() || command.html.is_some() || command.video.is_some();
    if command.verb == "record" && !pictures && command.mcap.is_none() {
        return Err("ars record needs --screenshots DIR, --video OUT.mp4, --html OUT.html or --mcap OUT.mcap".into());
    }
    if command.mcap.is_some() && (command.verb == "view" || pictures) {
        return Err("--mcap goes with ars record or ars run, without --screenshots, --video or --html".into());
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
    Ok(())
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

    fn window_settings(&self) -> WindowSettings {
        WindowSettings {
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
        let robot = sim.load_urdf(&self.path, &self.urdf)?;
        if let [first, ..] = robot.adjusted.as_slice() {
            let n = robot.adjusted.len();
            eprintln!(
                "adjusted {n} item(s) of the file to load it (inertias no body can have, empty visuals, hinge limits \
                 beyond ±π, the robot raised onto the floor); the first: {first}"
            );
        }
        Ok(())
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
        "run" => run_headless(&mut program, command),
        "record" if command.mcap.is_some() => run_headless(&mut program, command),
        #[cfg(feature = "ros")]
        "ros" => ros(&mut program, command),
        _ => show(&mut program, command),
    }
}

/// `ars run`, and `ars record --mcap`: runs without graphics, says how it went, and
/// writes what was asked.
fn run_headless(program: &mut FileProgram, command: &Command) -> Result<(), Box<dyn std::error::Error>> {
    ars::interrupt::stop_on_ctrl_c()?;
    let duration = command.duration.unwrap_or(10.0);
    let mut runner = ars::ProgramRunner::new(program)?;
    let start = Instant::now();
    let ran = match &command.mcap {
        None => runner.run_for(duration),
        Some(path) => ars::cli::record_mcap(&mut runner, path, duration),
    };
    let wall = start.elapsed().as_secs_f64();
    if let Err(ars::Error::Interrupted { time, .. }) = &ran {
        eprintln!("interrupted (Ctrl-C) at t = {} s", seconds(*time));
    } else {
        ran?;
    }
    let sim = runner.into_simulation();
    println!("{}", program.summary);
    println!(
        "ran to t = {} s ({} steps) in {wall:.3} s of wall time",
        seconds(sim.scene().time()),
        sim.scene().step_count()
    );
    if let Some(path) = &command.csv {
        write_csv(&sim, path, command.every)?;
    }
    Ok(())
}

/// `ars ros`: the file's simulation as a ROS 2 node until Ctrl-C (or --duration).
#[cfg(feature = "ros")]
fn ros(program: &mut FileProgram, command: &Command) -> Result<(), Box<dyn std::error::Error>> {
    use ars_ros::bridge;
    let args = command.ros.as_ref().ok_or("ars ros without its options")?;
    let options = args.options(command.duration)?;
    ars::interrupt::stop_on_ctrl_c()?;
    bridge::log_to_stderr();
    let sim = program.create_simulation()?;
    let core = bridge::prepare(sim, &options)?;
    eprintln!("{}\n{}", program.summary, bridge::describe(&core, &options));
    let sim = bridge::run_prepared(core, &options)?;
    if ars::interrupt::requested() {
        eprintln!("interrupted (Ctrl-C) at t = {} s", seconds(sim.scene().time()));
    }
    println!("ran to t = {} s ({} steps)", seconds(sim.scene().time()), sim.scene().step_count());
    Ok(())
}

#[cfg(feature = "viewer")]
fn show(program: &mut FileProgram, command: &Command) -> Result<(), Box<dyn std::error::Error>> {
    use ars::viewer::{ScreenshotRecorder, ViewerOptions};
    let options = ViewerOptions::default().with_axes(command.axes).with_views(command.views);
    let window = command.verb == "view" && ars::viewer::has_display();
    if window {
        return show_in_window(program, command, &options);
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
            seconds(sim.scene().time()),
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
            seconds(sim.scene().time()),
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
    println!("recorded t = {} s: {} frames into {}", seconds(sim.scene().time()), written.len(), dir.display());
    if let Some(path) = &command.csv {
        write_csv(&sim, path, command.every)?;
    }
    Ok(())
}

/// `ars view` in a window: until it is closed or for `--duration` wall seconds,
/// recording it with `--video`.
#[cfg(feature = "viewer")]
fn show_in_window(
    program: &mut FileProgram,
    command: &Command,
    options: &ars::viewer::ViewerOptions,
) -> Result<(), Box<dyn std::error::Error>> {
    use ars::viewer::ProgramViewer;
    eprintln!("{}", ars::viewer::VIEWER_KEYS);
    let sim = match (command.size, command.duration, &command.video) {
        (size, limit, Some(path)) => {
            let view =
                WindowSettings { size: size.unwrap_or(program.window_settings().size), ..program.window_settings() };
            let mut runner = ars::ProgramRunner::new(program)?;
            // The window runs in real time: a duration is wall seconds here.
            let limit = limit.map(std::time::Duration::from_secs_f64);
            let (_, video) = ars::viewer::run_window_recording(&mut runner, &view, options, limit, path, command.fps)?;
            println!("recorded the window: {} frames ({} s) into {}", video.frames, video.duration, path.display());
            runner.into_simulation()
        }
        (None, None, None) => program.show_with(options)?,
        (size, limit, None) => {
            let view =
                WindowSettings { size: size.unwrap_or(program.window_settings().size), ..program.window_settings() };
            let mut runner = ars::ProgramRunner::new(program)?;
            // The window runs in real time: a duration is wall seconds here.
            let limit = limit.map(std::time::Duration::from_secs_f64);
            ars::viewer::run_window_with(&mut runner, &view, options, limit)?;
            runner.into_simulation()
        }
    };
    println!("{}", program.summary);
    println!("closed at t = {} s ({} steps)", sim.scene().time(), sim.scene().step_count());
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
    let command = match parse(&args) {
        Ok(command) => command,
        Err(e) if !e.use_stderr() => {
            // --help, --version: printed as asked.
            let _ = e.print();
            return ExitCode::SUCCESS;
        }
        Err(e) if e.kind() == clap::error::ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => {
            let _ = e.print();
            return ExitCode::from(2);
        }
        Err(e) => {
            eprintln!("ars: {}\n(ars --help lists the commands)", refusal(&args, &e));
            return ExitCode::from(2);
        }
    };
    if let Err(message) = check(&command) {
        eprintln!("ars: {message}\n(ars --help lists the commands)");
        return ExitCode::from(2);
    }
    match run(&command) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("ars: {e}");
            ExitCode::FAILURE
        }
    }
}

/// A simulated time as the messages print it: to the nanosecond, so that the sum of
/// 5000 steps of 0.4 ms prints as 2, not 1.999999999999845.
fn seconds(time: f64) -> f64 {
    (time * 1e9).round() / 1e9
}
