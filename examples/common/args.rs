//! The examples' command line (the options shared with the `ars` command are
//! [`ars::cli`]'s): `[--duration S] [--csv PATH] [--plot DIR] [--every N]`, and
//! the viewer's `[--window | --screenshots DIR [--frame-every N]] [--video OUT.mp4 [--fps N]] [--size WxH]
//! [--axes] [--views N]`, the browser replay's `[--html OUT.html [--html-plot COLUMN]...]`,
//! the ROS 2 recording's `[--mcap OUT.mcap]` and the live ROS 2 node's `[--ros
//! [--lock-step] [--domain-id ID] [--rate HZ] [--drive L,R] ...]`.

use std::path::PathBuf;

use ars::cli::{BridgeArgs, PictureArgs, RunArgs};
use clap::error::ErrorKind;
use clap::{CommandFactory, FromArgMatches};

/// Parsed options.
#[derive(Debug, Clone)]
pub struct Args {
    /// Simulated seconds to run.
    pub duration: f64,
    /// Where to write the CSV, if asked.
    pub csv: Option<PathBuf>,
    /// Where to record the run's ROS 2 messages, if asked.
    pub mcap: Option<PathBuf>,
    /// Folder to write the PNG plots into, if asked.
    pub plot: Option<PathBuf>,
    /// Keep one CSV row every N steps.
    pub every: usize,
    /// Record off-screen frames into this folder.
    pub screenshots: Option<PathBuf>,
    /// One frame every N frames.
    pub frame_every: u32,
    /// Frame (or window) size, pixels.
    pub size: Option<(u32, u32)>,
    /// Show the program in a window (until it is closed) instead of running headless.
    pub window: bool,
    /// Draw the world axes (in the window, or in the frames).
    pub axes: bool,
    /// Record an MP4 video off screen into this file.
    pub video: Option<PathBuf>,
    /// The video's frames per second (of simulated time).
    pub fps: f64,
    /// How many views (1 to 4): the free camera, following, top, camera sensor.
    pub views: usize,
    /// Write a browser replay (one self-contained HTML file) here.
    pub html: Option<PathBuf>,
    /// The sensor columns the replay plots (`"Gps 1: y"`).
    pub html_plots: Vec<String>,
    /// `--ros`: run as a live ROS 2 node with these options, for `--duration` if given
    /// (else until Ctrl-C).
    pub ros: Option<(BridgeArgs, Option<f64>)>,
}

impl Args {
    /// Whether the program runs live, in a window or as a ROS 2 node (`--ros`), rather
    /// than through an example's own recorded loop: [`run`] runs it then.
    pub fn live(&self) -> bool {
        self.window || self.ros.is_some()
    }
}

/// The examples' own options around the shared ones ([`ars::cli`]).
#[derive(clap::Parser)]
#[command(about = "An ARS example: runs headless unless asked for pictures, a window or a replay")]
struct ExampleCli {
    #[command(flatten)]
    run: RunArgs,
    /// Write the figures as PNG into DIR
    #[arg(long, value_name = "DIR")]
    plot: Option<PathBuf>,
    /// Show the program in a window instead (records off screen if there is no display)
    #[arg(long)]
    window: bool,
    #[command(flatten)]
    pictures: PictureArgs,
    #[command(flatten)]
    bridge: BridgeArgs,
}

/// Parses the command line; prints the usage and exits on `--help` or a mistake.
pub fn parse(default_duration: f64) -> Args {
    parse_except(default_duration, &[])
}

/// As [`parse`], ignoring the example's own flags `extra` (flags without values).
pub fn parse_except(default_duration: f64, extra: &[&str]) -> Args {
    let argv: Vec<String> = std::env::args().filter(|a| !extra.contains(&a.as_str())).collect();
    let program = argv.first().and_then(|p| std::path::Path::new(p).file_stem()).map(|p| p.to_string_lossy());
    let command = ExampleCli::command()
        .bin_name(program.map_or_else(|| "example".into(), String::from))
        .mut_arg("duration", |a| a.help(format!("Simulated seconds to run (default {default_duration})")));
    let matches = command.clone().try_get_matches_from(&argv).unwrap_or_else(|e| e.exit());
    let cli = ExampleCli::from_arg_matches(&matches).unwrap_or_else(|e| e.exit());
    let mut command = command;
    let mut fail = |message: &str| -> ! { command.error(ErrorKind::ArgumentConflict, message).exit() };
    if cli.pictures.html.is_some() && (cli.window || cli.pictures.screenshots.is_some()) {
        fail("--html records a run of its own: give it without --window and --screenshots");
    }
    if !cli.pictures.html_plots.is_empty() && cli.pictures.html.is_none() {
        fail("--html-plot goes with --html");
    }
    if cli.run.mcap.is_some() && cli.window {
        fail("--mcap records a run of its own: give it without --window");
    }
    let pictures = &cli.pictures;
    let drawn = cli.window || pictures.screenshots.is_some() || pictures.video.is_some() || pictures.html.is_some();
    if cli.bridge.ros && (drawn || cli.run.mcap.is_some()) {
        fail(
            "--ros runs the simulation as a ROS 2 node: give it without --window, --screenshots, --video, --html and --mcap",
        );
    }
    #[cfg(feature = "ros")]
    for option in ["lock_step", "domain_id", "rate", "drive", "wheel_torque", "services"] {
        if !cli.bridge.ros && matches.value_source(option) == Some(clap::parser::ValueSource::CommandLine) {
            fail(&format!("--{} goes with --ros", option.replace('_', "-")));
        }
    }
    let ros = cli.bridge.ros.then(|| (cli.bridge.clone(), cli.run.duration));
    let PictureArgs { screenshots, frame_every, video, fps, size, axes, views, html, html_plots } = cli.pictures;
    Args {
        duration: cli.run.duration.unwrap_or(default_duration),
        csv: cli.run.csv,
        mcap: cli.run.mcap,
        plot: cli.plot,
        every: cli.run.every,
        screenshots,
        frame_every,
        size,
        window: cli.window,
        axes,
        video,
        fps,
        views,
        html,
        html_plots,
        ros,
    }
}

/// Writes a sensor's records as CSV to `path` (one sample in every `every`; the
/// header names each column and unit) and says so.
pub fn export_csv<R: ars::Record>(
    path: &std::path::Path,
    log: &ars::SensorLog<R>,
    every: usize,
) -> std::io::Result<()> {
    export_csv_table(path, &[("", log)], every)
}

/// Writes several sensors' records as one CSV table to `path` (see
/// [`ars::sensors::write_csv_table`]) and says so.
pub fn export_csv_table(
    path: &std::path::Path,
    logs: &[(&str, &dyn ars::sensors::CsvColumns)],
    every: usize,
) -> std::io::Result<()> {
    use std::io::Write;
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir)?;
    }
    let mut out = std::io::BufWriter::new(std::fs::File::create(path)?);
    ars::sensors::write_csv_table(&mut out, logs, every)?;
    out.flush()?;
    eprintln!("wrote {}", path.display());
    Ok(())
}

/// Runs `program` for the requested duration: headless, or recording off-screen
/// frames when `--screenshots` was given. Returns the simulation for its records.
/// Ctrl-C stops the run between two frames and what was recorded until then is
/// returned (and written by the example); a second Ctrl-C ends the process at once.
pub fn run<P: ars::Program>(program: &mut P, args: &Args) -> Result<ars::Simulation, Box<dyn std::error::Error>> {
    ars::interrupt::stop_on_ctrl_c()?;
    if let Some((bridge, duration)) = &args.ros {
        return Ok(ars::cli::run_ros(ars::ProgramRunner::new(program)?, bridge, *duration)?);
    }
    if args.window {
        return show(program, args);
    }
    if let Some(path) = &args.video {
        return record_video(program, args, path);
    }
    if let Some(path) = &args.html {
        return replay(program, args, path);
    }
    match (&args.screenshots, &args.mcap) {
        (None, None) => {
            let mut runner = ars::ProgramRunner::new(program)?;
            stopped_early(runner.run_for(args.duration))?;
            Ok(runner.into_simulation())
        }
        (None, Some(path)) => {
            let mut runner = ars::ProgramRunner::new(program)?;
            stopped_early(ars::cli::record_mcap(&mut runner, path, args.duration))?;
            Ok(runner.into_simulation())
        }
        (Some(dir), _) => record(program, args, dir),
    }
}

/// A run's outcome, where Ctrl-C is not an error: it is said, and the example goes on
/// to write what was recorded.
pub fn stopped_early(run: ars::Result<()>) -> ars::Result<()> {
    match run {
        Err(ars::Error::Interrupted { time, .. }) => {
            eprintln!("interrupted (Ctrl-C) at t = {time} s: writing what was recorded until then");
            Ok(())
        }
        other => other,
    }
}

/// What the viewer draws, from `--axes`.
#[cfg(feature = "viewer")]
pub fn viewer_options(args: &Args) -> ars::viewer::ViewerOptions {
    ars::viewer::ViewerOptions::default().with_axes(args.axes).with_views(args.views)
}

#[cfg(feature = "viewer")]
fn show<P: ars::Program>(program: &mut P, args: &Args) -> Result<ars::Simulation, Box<dyn std::error::Error>> {
    use ars::viewer::ProgramViewer;
    eprintln!("{}", ars::viewer::VIEWER_KEYS);
    let options = viewer_options(args);
    if let Some(path) = &args.video {
        if !ars::viewer::has_display() {
            eprintln!("no display: recording the video off screen");
            return record_video(program, args, path);
        }
        // The window's pictures, at the simulation's time.
        let view = ars::WindowSettings {
            size: args.size.unwrap_or(program.window_settings().size),
            ..program.window_settings()
        };
        let mut runner = ars::ProgramRunner::new(program)?;
        let (_, video) = ars::viewer::run_window_recording(&mut runner, &view, &options, None, path, args.fps)?;
        say_video(&video);
        return Ok(runner.into_simulation());
    }
    match args.size {
        // The program's view at the size asked for.
        Some(size) if ars::viewer::has_display() => {
            let view = ars::WindowSettings { size, ..program.window_settings() };
            let mut runner = ars::ProgramRunner::new(program)?;
            ars::viewer::run_window_with(&mut runner, &view, &options, None)?;
            Ok(runner.into_simulation())
        }
        _ => Ok(program.show_with(&options)?),
    }
}

#[cfg(not(feature = "viewer"))]
fn show<P: ars::Program>(_: &mut P, _: &Args) -> Result<ars::Simulation, Box<dyn std::error::Error>> {
    Err("--window needs the viewer: build with the default features".into())
}

#[cfg(feature = "viewer")]
fn record<P: ars::Program>(
    program: &mut P,
    args: &Args,
    dir: &std::path::Path,
) -> Result<ars::Simulation, Box<dyn std::error::Error>> {
    let mut recorder = ars::viewer::ScreenshotRecorder::new(dir).every(args.frame_every).options(viewer_options(args));
    if let Some((w, h)) = args.size {
        recorder = recorder.size(w, h);
    }
    let (sim, written) = recorder.record(program, args.duration)?;
    if ars::interrupt::requested() {
        eprintln!("interrupted (Ctrl-C) at t = {} s", sim.scene().time());
    }
    eprintln!("wrote {} frames into {}", written.len(), dir.display());
    Ok(sim)
}

#[cfg(not(feature = "viewer"))]
fn record<P: ars::Program>(
    _: &mut P,
    _: &Args,
    _: &std::path::Path,
) -> Result<ars::Simulation, Box<dyn std::error::Error>> {
    Err("--screenshots needs the viewer: build with the default features".into())
}

#[cfg(feature = "viewer")]
fn record_video<P: ars::Program>(
    program: &mut P,
    args: &Args,
    path: &std::path::Path,
) -> Result<ars::Simulation, Box<dyn std::error::Error>> {
    let mut recorder = ars::viewer::VideoRecorder::new(path).fps(args.fps).options(viewer_options(args));
    if let Some((w, h)) = args.size {
        recorder = recorder.size(w, h);
    }
    let (sim, video) = recorder.record(program, args.duration)?;
    say_video(&video);
    Ok(sim)
}

#[cfg(feature = "viewer")]
fn say_video(video: &ars::viewer::RecordedVideo) {
    eprintln!(
        "wrote {}: {} frames, {} s at {} frames/s, {}x{}, {} kB",
        video.path.display(),
        video.frames,
        video.duration,
        video.fps,
        video.size.0,
        video.size.1,
        video.bytes / 1000
    );
}

#[cfg(not(feature = "viewer"))]
fn record_video<P: ars::Program>(
    _: &mut P,
    _: &Args,
    _: &std::path::Path,
) -> Result<ars::Simulation, Box<dyn std::error::Error>> {
    Err("--video needs the viewer: build with the default features".into())
}

/// The replay recorder `--html-plot` asks for.
#[cfg(feature = "viewer")]
fn replay_recorder(args: &Args) -> ars::viewer::ReplayRecorder {
    let mut recorder = ars::viewer::ReplayRecorder::new();
    for column in &args.html_plots {
        recorder = recorder.plot(column.clone());
    }
    if let Some((w, h)) = args.size {
        recorder = recorder.size(w, h);
    }
    recorder
}

#[cfg(feature = "viewer")]
fn replay<P: ars::Program>(
    program: &mut P,
    args: &Args,
    path: &std::path::Path,
) -> Result<ars::Simulation, Box<dyn std::error::Error>> {
    let (sim, replay) = replay_recorder(args).record_to(program, args.duration, path)?;
    eprintln!("wrote the replay {} ({} frames, {} bytes)", path.display(), replay.frames(), replay.html().len());
    Ok(sim)
}

#[cfg(not(feature = "viewer"))]
fn replay<P: ars::Program>(
    _: &mut P,
    _: &Args,
    _: &std::path::Path,
) -> Result<ars::Simulation, Box<dyn std::error::Error>> {
    Err("--html needs the viewer: build with the default features".into())
}

/// A video taken by [`Capture`]: the writer, its renderer, the frames wanted, the
/// frames taken and the simulated time it started at.
#[cfg(feature = "viewer")]
struct CapturedVideo {
    writer: ars::viewer::VideoWriter,
    renderer: ars::viewer::OffscreenRenderer,
    fps: f64,
    count: u64,
    taken: u64,
    start: Option<f64>,
}

#[cfg(feature = "viewer")]
impl CapturedVideo {
    /// Takes the video frames due by the simulation's time now.
    fn take(&mut self, sim: &ars::Simulation) -> Result<(), Box<dyn std::error::Error>> {
        let start = *self.start.get_or_insert(sim.scene().time());
        while self.taken < self.count && sim.scene().time() - start >= self.taken as f64 / self.fps - 1e-9 {
            self.writer.add_frame(self.renderer.render(sim)?)?;
            self.taken += 1;
        }
        Ok(())
    }
}

/// Off-screen frames (and the replay of `--html`, the video of `--video`) for examples
/// that drive their own [`ars::ProgramRunner`]: call [`Capture::frame`] at the start of
/// every frame and [`Capture::finish`] at the end. These examples step their own
/// frames: video frame k is the picture at the first frame start at or after k/fps
/// simulated seconds (at most a frame late; the other examples take it at the first
/// step).
pub struct Capture {
    #[cfg(feature = "viewer")]
    inner: Option<(ars::viewer::OffscreenRenderer, PathBuf, u32, u64, u32)>,
    /// The replay: its recorder, view and file, then the recording once begun.
    #[cfg(feature = "viewer")]
    replay: Option<(ars::viewer::ReplayRecorder, ars::WindowSettings, PathBuf, Option<ars::viewer::ReplayInProgress>)>,
    #[cfg(feature = "viewer")]
    video: Option<CapturedVideo>,
    /// `--mcap`: the file, then its recorder once begun ([`Capture::record_ros`]).
    #[cfg(feature = "ros")]
    mcap: Option<(PathBuf, Option<ars::ros::McapRecorder>)>,
}

impl Capture {
    /// Records when `--screenshots`, `--html` or `--video` was given, with `view` (the
    /// program's settings).
    pub fn new(args: &Args, view: ars::WindowSettings) -> Result<Self, Box<dyn std::error::Error>> {
        if args.ros.is_some() {
            return Err("--ros: this example runs a loop of its own, not a program a ROS 2 node can step".into());
        }
        #[cfg(feature = "viewer")]
        {
            let replay = args.html.as_ref().map(|path| (replay_recorder(args), view.clone(), path.clone(), None));
            let mut view = view;
            if let Some(size) = args.size {
                view.size = size;
            }
            let video = match &args.video {
                Some(path) => {
                    ars::viewer::check_video_settings(args.fps, view.size.0, view.size.1)?;
                    let count = ars::viewer::video_frame_count(args.duration, args.fps)?;
                    let writer = ars::viewer::VideoWriter::create(path, view.size.0, view.size.1, args.fps)?;
                    let renderer = ars::viewer::OffscreenRenderer::with_options(&view, &viewer_options(args))?;
                    Some(CapturedVideo { writer, renderer, fps: args.fps, count, taken: 0, start: None })
                }
                None => None,
            };
            #[cfg(feature = "ros")]
            let mcap = args.mcap.clone().map(|path| (path, None));
            let Some(dir) = &args.screenshots else {
                return Ok(Capture {
                    inner: None,
                    replay,
                    video,
                    #[cfg(feature = "ros")]
                    mcap,
                });
            };
            std::fs::create_dir_all(dir)?;
            let renderer = ars::viewer::OffscreenRenderer::with_options(&view, &viewer_options(args))?;
            Ok(Capture {
                inner: Some((renderer, dir.clone(), args.frame_every, 0, 0)),
                replay,
                video,
                #[cfg(feature = "ros")]
                mcap,
            })
        }
        #[cfg(not(feature = "viewer"))]
        {
            let _ = view;
            if args.screenshots.is_some() || args.html.is_some() || args.video.is_some() {
                return Err("--screenshots, --html and --video need the viewer: build with the default features".into());
            }
            Ok(Capture {
                #[cfg(feature = "ros")]
                mcap: args.mcap.clone().map(|path| (path, None)),
            })
        }
    }

    /// Begins the `--mcap` recording of `sim` (it gets the recorder's joint states
    /// sensor); call it once the simulation is built, before the first
    /// [`frame`](Self::frame). Nothing without `--mcap`.
    pub fn record_ros(&mut self, sim: &mut ars::Simulation) -> Result<(), Box<dyn std::error::Error>> {
        #[cfg(feature = "ros")]
        if let Some((path, recorder)) = &mut self.mcap {
            let options = ars::ros::RosOptions::for_scene(sim.scene());
            *recorder = Some(ars::ros::McapRecorder::create(path, sim, &options)?);
        }
        #[cfg(not(feature = "ros"))]
        let _ = sim;
        Ok(())
    }

    /// Writes the current frame if one is due (the first, then every N frames), and
    /// samples the replay, the video and the ROS 2 messages.
    pub fn frame(&mut self, sim: &ars::Simulation) -> Result<(), Box<dyn std::error::Error>> {
        #[cfg(feature = "ros")]
        match &mut self.mcap {
            Some((_, Some(recorder))) => recorder.record(sim)?,
            Some((_, None)) => {
                return Err("--mcap: this example did not begin its recording (Capture::record_ros)".into());
            }
            None => {}
        }
        #[cfg(feature = "viewer")]
        if let Some((recorder, view, path, recording)) = &mut self.replay {
            match recording {
                Some(recording) => recording.frame(sim),
                None => *recording = Some(recorder.begin_to(sim, view, path)?),
            }
        }
        #[cfg(feature = "viewer")]
        if let Some((renderer, dir, every, frame, index)) = &mut self.inner {
            if *frame % u64::from(*every) == 0 {
                *index += 1;
                renderer.render(sim)?.save(dir.join(format!("frame_{:05}.png", index)))?;
            }
            *frame += 1;
        }
        #[cfg(feature = "viewer")]
        if let Some(video) = &mut self.video {
            video.take(sim)?;
        }
        #[cfg(not(feature = "viewer"))]
        let _ = sim;
        Ok(())
    }

    /// Ends the recording with `sim` as it is at the end: writes the replay, if
    /// `--html` asked for one, and the video, if `--video` did (with the frames still
    /// due).
    pub fn finish(self, sim: &ars::Simulation) -> Result<(), Box<dyn std::error::Error>> {
        #[cfg(feature = "ros")]
        if let Some((path, Some(mut recorder))) = self.mcap {
            recorder.record(sim)?;
            let summary = recorder.finish()?;
            eprintln!("wrote {} ROS 2 messages into {}", summary.total(), path.display());
        }
        #[cfg(feature = "viewer")]
        {
            if let Some((_, _, path, Some(recording))) = self.replay {
                let replay = recording.finish(sim)?;
                eprintln!("wrote the replay {} ({} frames)", path.display(), replay.frames());
            }
            if let Some(mut video) = self.video {
                video.take(sim)?;
                say_video(&video.writer.finish()?);
            }
        }
        #[cfg(not(feature = "viewer"))]
        let _ = sim;
        Ok(())
    }
}
