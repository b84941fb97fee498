//! The command-line options that the `ars` command and the examples share, defined
//! once with `clap`: how long to run and what to write ([`RunArgs`]), and what to draw
//! ([`PictureArgs`]). Each value is checked as it is read, and a wrong one is refused
//! with a message naming the option (`invalid value '-1' for '--duration <S>': must be a
//! positive number of seconds, got "-1"`).
//!
//! ```
//! use ars::cli::{PictureArgs, RunArgs};
//! use clap::Parser;
//!
//! #[derive(Parser)]
//! struct Cli {
//!     #[command(flatten)]
//!     run: RunArgs,
//!     #[command(flatten)]
//!     pictures: PictureArgs,
//! }
//!
//! let cli = Cli::try_parse_from(["demo", "--duration", "2", "--size", "640x480"]).unwrap();
//! assert_eq!((cli.run.duration, cli.pictures.size), (Some(2.0), Some((640, 480))));
//! assert_eq!((cli.run.every, cli.pictures.frame_every, cli.pictures.views), (1, 5, 1));
//! let wrong = Cli::try_parse_from(["demo", "--views", "5"]).err().unwrap().to_string();
//! assert!(wrong.contains("'--views <N>': must be 1, 2, 3 or 4, got \"5\""), "{wrong}");
//! ```

use std::path::PathBuf;

/// Runs what `runner` runs for `duration` simulated seconds, recording the ROS 2
/// messages into the MCAP file at `path` (`--mcap`; finished with what was recorded
/// when Ctrl-C stops it), and says what it wrote: what the `ars` command and the
/// examples do with `--mcap`. Without the `ros` feature, an error saying so.
pub fn record_mcap<P: crate::Program>(
    runner: &mut crate::ProgramRunner<'_, P>,
    path: &std::path::Path,
    duration: f64,
) -> crate::Result<()> {
    #[cfg(feature = "ros")]
    {
        let options = crate::ros::RosOptions::for_scene(runner.simulation().scene());
        match crate::ros::record_mcap(runner, path, duration, &options, crate::interrupt::requested) {
            Ok(summary) => {
                eprintln!("wrote {} ROS 2 messages into {}", summary.total(), path.display());
                Ok(())
            }
            Err(crate::ros::RosError::Simulation(e)) => Err(e),
            Err(other) => Err(crate::Error::User(other.to_string())),
        }
    }
    #[cfg(not(feature = "ros"))]
    {
        let _ = (runner, path, duration);
        Err(crate::Error::User("--mcap needs the ros feature: build ars with its default features".into()))
    }
}

/// `--ros`: the examples' run as a live ROS 2 node, with the bridge's options (those of
/// `ars ros`, [`ros::bridge::cli::RosArgs`](crate::ros::bridge::cli::RosArgs)).
#[derive(clap::Args, Clone, Debug)]
pub struct BridgeArgs {
    /// Run as a live ROS 2 node (docs/ros2.md; no ROS install needed): real time until
    /// Ctrl-C or --duration, or --lock-step
    #[arg(long)]
    pub ros: bool,
    /// The bridge's options (with --ros).
    #[cfg(feature = "ros")]
    #[command(flatten)]
    pub options: crate::ros::bridge::cli::RosArgs,
}

/// Runs what `runner` runs as a live ROS 2 node ([`ros::bridge`](crate::ros::bridge))
/// with `args`' options, until Ctrl-C, a `SetSimulationState` to quit, or `duration`
/// simulated seconds; gives the simulation back as it is then, and says what ran:
/// what the examples do with `--ros`. Without the `ros` feature, an error saying so.
pub fn run_ros<P: crate::Program>(
    runner: crate::ProgramRunner<'_, P>,
    args: &BridgeArgs,
    duration: Option<f64>,
) -> crate::Result<crate::Simulation> {
    #[cfg(feature = "ros")]
    {
        use crate::ros::bridge;
        let options = args.options.options(duration).map_err(crate::Error::User)?;
        let refused = |e: bridge::BridgeError| match e {
            bridge::BridgeError::Simulation(e) => e,
            other => crate::Error::User(format!("--ros: {other}")),
        };
        bridge::log_to_stderr();
        let core = bridge::prepare(runner, &options).map_err(refused)?;
        eprintln!("{}", bridge::describe(&core, &options));
        let sim = bridge::run_prepared(core, &options).map_err(refused)?.into_simulation();
        if crate::interrupt::requested() {
            eprintln!("interrupted (Ctrl-C) at t = {:.6} s", sim.scene().time());
        }
        eprintln!("ran to t = {:.6} s ({} steps)", sim.scene().time(), sim.scene().step_count());
        Ok(sim)
    }
    #[cfg(not(feature = "ros"))]
    {
        let _ = (runner, args, duration);
        Err(crate::Error::User("--ros needs the ros feature: build ars with its default features".into()))
    }
}

/// How long to run and which data to write.
#[derive(clap::Args, Clone, Debug, PartialEq)]
pub struct RunArgs {
    /// Simulated seconds to run (default: the program's own)
    #[arg(long, value_name = "S", value_parser = positive_seconds, allow_negative_numbers = true)]
    pub duration: Option<f64>,
    /// Write the sensors' data as CSV
    #[arg(long, value_name = "OUT")]
    pub csv: Option<PathBuf>,
    /// One CSV row every N steps
    #[arg(long, value_name = "N", default_value_t = 1, value_parser = positive_every, allow_negative_numbers = true)]
    pub every: usize,
    /// Record the run's ROS 2 messages (/tf, /joint_states, /scan...) into an MCAP file
    #[arg(long, value_name = "OUT.mcap")]
    pub mcap: Option<PathBuf>,
}

/// What to draw and where: off-screen frames, a video, a browser replay, and how the
/// pictures look.
#[derive(clap::Args, Clone, Debug, PartialEq)]
pub struct PictureArgs {
    /// Render off screen (no display or GPU needed) into DIR/frame_00001.png...
    #[arg(long, value_name = "DIR")]
    pub screenshots: Option<PathBuf>,
    /// One picture every N frames
    #[arg(long, value_name = "N", default_value_t = 5, value_parser = positive_frame_every, allow_negative_numbers = true)]
    pub frame_every: u32,
    /// Record an H.264 MP4 video, frame k at k/fps simulated seconds
    #[arg(long, value_name = "OUT.mp4")]
    pub video: Option<PathBuf>,
    /// The video's frames per second
    #[arg(long, value_name = "N", default_value_t = 30.0, value_parser = positive_fps, allow_negative_numbers = true)]
    pub fps: f64,
    /// Picture or window size in pixels, WxH (default: the program's window size)
    #[arg(long, value_name = "WxH", value_parser = picture_size)]
    pub size: Option<(u32, u32)>,
    /// Draw the world axes (X red, Y green, Z blue)
    #[arg(long)]
    pub axes: bool,
    /// Split the picture into N views (1-4): free, following, top, camera
    #[arg(long, value_name = "N", default_value_t = 1, value_parser = view_count, allow_negative_numbers = true)]
    pub views: usize,
    /// Write a browser replay: one HTML file that plays the run back, no network needed
    #[arg(long, value_name = "OUT.html")]
    pub html: Option<PathBuf>,
    /// Plot a sensor column under the replay ("Gps 1: y", as --csv heads it; repeatable)
    #[arg(long = "html-plot", value_name = "COLUMN")]
    pub html_plots: Vec<String>,
}

/// Reads a positive, finite number of seconds (`--duration`'s check), or says what is
/// wrong.
pub fn positive_seconds(v: &str) -> Result<f64, String> {
    match v.parse::<f64>() {
        Ok(d) if d.is_finite() && d > 0.0 => Ok(d),
        _ => Err(format!("must be a positive number of seconds, got {v:?}")),
    }
}

fn positive_fps(v: &str) -> Result<f64, String> {
    match v.parse::<f64>() {
        Ok(f) if f.is_finite() && f > 0.0 => Ok(f),
        _ => Err(format!("must be a positive number of frames per second, got {v:?}")),
    }
}

fn positive_whole(v: &str) -> Result<u64, String> {
    match v.parse::<u64>() {
        Ok(n) if n > 0 => Ok(n),
        _ => Err(format!("must be a positive whole number, got {v:?}")),
    }
}

fn positive_every(v: &str) -> Result<usize, String> {
    let n = positive_whole(v)?;
    usize::try_from(n).map_err(|_| format!("is too large: {n}"))
}

fn positive_frame_every(v: &str) -> Result<u32, String> {
    let n = positive_whole(v)?;
    u32::try_from(n).map_err(|_| format!("is too large: {n}"))
}

fn picture_size(v: &str) -> Result<(u32, u32), String> {
    match v.split_once('x').and_then(|(w, h)| Some((w.parse::<u32>().ok()?, h.parse::<u32>().ok()?))) {
        Some((w, h)) if w > 0 && h > 0 => Ok((w, h)),
        _ => Err(format!("must look like 800x600, got {v:?}")),
    }
}

fn view_count(v: &str) -> Result<usize, String> {
    match v.parse::<usize>() {
        Ok(n) if (1..=4).contains(&n) => Ok(n),
        _ => Err(format!("must be 1, 2, 3 or 4, got {v:?}")),
    }
}
