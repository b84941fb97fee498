//! The `ars` command: a scene saved mid-run and run by `ars run` goes on to the same
//! bits as in the process that saved it; its help fits a screen; mistakes are said.

use std::process::Command;

use ars::nalgebra::Vector3;
use ars::sensors::Gps;
use ars::{JointEnd, Mass, Simulation};

const ARS: &str = env!("CARGO_BIN_EXE_ars");

/// A pendulum knocking a ball along the floor, with a GPS on the ball.
fn scene() -> Simulation {
    let mut sim = Simulation::builder().floor_plane(Vector3::y(), 0.0).build().unwrap();
    let bob = sim.scene_mut().add_sphere(0.1, [0.6, 0.8, 0.0], Mass::Total(2.0)).unwrap();
    sim.scene_mut().add_hinge_joint("pivot", bob, JointEnd::World, Some([0.0, 0.8, 0.0].into()), Vector3::z()).unwrap();
    let ball = sim.scene_mut().add_sphere(0.05, [0.0, 0.05, 0.0], Mass::Total(0.3)).unwrap();
    sim.add_sensor_every(Gps::new(ball), 0.01).unwrap();
    sim
}

#[test]
fn a_scene_saved_mid_run_goes_on_to_the_same_bits_under_ars_run() {
    let dir = std::env::temp_dir().join(format!("ars-command-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (file, csv) = (dir.join("scene.json"), dir.join("out.csv"));
    let mut sim = scene();
    sim.run_for(0.7).unwrap();
    sim.save_scene_to(&file).unwrap();
    sim.run_for(1.0).unwrap();
    let out = Command::new(ARS)
        .args(["run", file.to_str().unwrap(), "--duration", "1", "--csv", csv.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    // The time to the nanosecond: a sum of steps of 0.4 ms, not 1.7000000000000272.
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.contains("ran to t = 1.7 s (4250 steps)"), "{stdout}");
    let text = std::fs::read_to_string(&csv).unwrap();
    let last: Vec<f64> = text.lines().last().unwrap().split(',').map(|c| c.parse().unwrap()).collect();
    let ball = sim.scene().object("sphere/1").unwrap().id();
    let here = sim.scene().body(ball).unwrap().position();
    // time, step, x, y, z: the CSV's numbers are written to round-trip.
    assert_eq!(last[1] as u64, sim.scene().step_count());
    assert_eq!([last[2], last[3], last[4]].map(f64::to_bits), [here.x, here.y, here.z].map(f64::to_bits));
    assert!(here.x.abs() > 0.05, "the ball was knocked: {here}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn its_help_fits_a_screen_and_mistakes_are_said() {
    let help = Command::new(ARS).arg("--help").output().unwrap();
    assert!(help.status.success());
    let text = String::from_utf8(help.stdout).unwrap();
    assert!(text.lines().count() <= 40 && text.lines().all(|l| l.chars().count() <= 100), "{text}");
    for (args, says) in [
        (vec!["fly", "x.json"], "unknown command"),
        (vec!["run"], "needs a FILE"),
        (vec!["run", "x.json", "--duration", "-1"], "--duration must be a positive number"),
        (vec!["record", "x.urdf"], "needs --screenshots DIR, --video OUT.mp4, --html OUT.html or --mcap OUT.mcap"),
        (vec!["view", "x.urdf", "--mcap", "a.mcap"], "--mcap goes with ars record or ars run"),
        (vec!["record", "x.urdf", "--mcap", "a.mcap", "--video", "a.mp4"], "--mcap goes with ars record or ars run"),
        (vec!["run", "x.urdf", "--video", "a.mp4"], "--video goes with ars record or ars view"),
        (vec!["record", "x.urdf", "--video", "a.mp4", "--fps", "0"], "--fps must be a positive number"),
        (vec!["run", "x.json", "--frobnicate"], "unknown option"),
    ] {
        let out = Command::new(ARS).args(&args).output().unwrap();
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        assert!(String::from_utf8_lossy(&out.stderr).contains(says), "{args:?}");
    }
    let missing = Command::new(ARS).args(["run", "/nonexistent/scene.json"]).output().unwrap();
    assert_eq!(missing.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&missing.stderr).contains("/nonexistent/scene.json"));
}

#[test]
fn ars_record_writes_the_ros_2_messages_into_an_mcap_file() {
    let dir = std::env::temp_dir().join(format!("ars-command-mcap-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (file, mcap) = (dir.join("scene.json"), dir.join("run.mcap"));
    scene().save_scene_to(&file).unwrap();
    let out = Command::new(ARS)
        .args(["record", file.to_str().unwrap(), "--mcap", mcap.to_str().unwrap(), "--duration", "0.1"])
        .output()
        .unwrap();
    let said = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{said}");
    // 0.1 s at 50 a second: /clock and /tf 6 each, /joint_states 5, /tf_static 1.
    assert!(said.contains("wrote 18 ROS 2 messages into"), "{said}");
    let bytes = std::fs::read(&mcap).unwrap();
    assert!(bytes.starts_with(b"\x89MCAP0\r\n") && bytes.ends_with(b"\x89MCAP0\r\n"), "an MCAP file, finished");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn ars_record_writes_a_browser_replay_with_a_plot() {
    let dir = std::env::temp_dir().join(format!("ars-command-html-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (file, page) = (dir.join("scene.json"), dir.join("replay.html"));
    scene().save_scene_to(&file).unwrap();
    let record = |page: &std::path::Path, plot: &str| {
        Command::new(ARS)
            .args(["record", file.to_str().unwrap(), "--html", page.to_str().unwrap(), "--duration", "1"])
            .args(["--html-plot", plot])
            .output()
            .unwrap()
    };
    let out = record(&page, "Gps 1: x");
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(String::from_utf8_lossy(&out.stdout).contains("a replay of 51 frames"));
    let html = std::fs::read_to_string(&page).unwrap();
    assert!(html.starts_with("<!DOCTYPE html>") && html.contains("id=\"ars-data\""));
    // An unknown column and a folder that is not there: said, and nothing written.
    let unknown = record(&dir.join("other.html"), "Gps 1: w");
    assert_eq!(unknown.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&unknown.stderr).contains("no sensor column \"Gps 1: w\""));
    let nowhere = record(&dir.join("missing/replay.html"), "Gps 1: x");
    assert_eq!(nowhere.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&nowhere.stderr).contains("missing/replay.html"));
    let mut left: Vec<_> = std::fs::read_dir(&dir).unwrap().map(|e| e.unwrap().file_name()).collect();
    left.sort();
    assert_eq!(left, ["replay.html", "scene.json"]);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Opening Gymnasium's ant, whose every geom has contact parameters ARS does not use,
/// says so in one line on stderr, not one per geom.
#[test]
fn what_a_model_skipped_is_said_in_one_line() {
    let ant = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/ant.xml");
    let opened = Simulation::open(ant).unwrap();
    assert!(opened.skipped.len() > 5, "{:?}", opened.skipped);
    let out = Command::new(ARS).args(["run", ant, "--duration", "0.05"]).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let stderr = String::from_utf8_lossy(&out.stderr);
    let said: Vec<&str> = stderr.lines().filter(|l| l.contains("skipped")).collect();
    assert_eq!(said.len(), 1, "{stderr}");
    let n = opened.skipped.len();
    assert!(said[0].starts_with(&format!("skipped {n} unsupported MJCF items (contact parameters of ")), "{stderr}");
}

/// A robot whose links have neither visuals nor collision geometry (the dynamics test
/// arm) has nothing to draw: `ars record --video` says so and writes nothing, where it
/// used to write 60 frames of the floor.
#[test]
fn a_video_of_a_robot_with_nothing_to_draw_is_refused() {
    let dir = std::env::temp_dir().join(format!("ars-command-invisible-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let arm = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/rnea_arm.urdf");
    let video = dir.join("arm.mp4");
    let out = Command::new(ARS)
        .args(["record", arm, "--fixed-base", "--video", video.to_str().unwrap(), "--duration", "0.1"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1), "{}", String::from_utf8_lossy(&out.stdout));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("nothing to record") && stderr.contains("without visuals or collision geometry"),
        "{stderr}"
    );
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 0, "nothing is written");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `ars ros` (the ROS 2 bridge): in real time, --duration simulated seconds take as
/// long on the wall clock; its mistakes are said.
#[cfg(feature = "ros")]
#[test]
fn ars_ros_runs_in_real_time_and_refuses_bad_options() {
    let dir = std::env::temp_dir().join(format!("ars-command-ros-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("scene.json");
    scene().save_scene_to(&file).unwrap();
    let domain = (51 + std::process::id() % 50).to_string();
    let start = std::time::Instant::now();
    let args = ["ros", file.to_str().unwrap(), "--duration", "0.3", "--domain-id", &domain];
    let out = Command::new(ARS).args(args).output().unwrap();
    let wall = start.elapsed().as_secs_f64();
    let (stdout, stderr) = (String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
    assert!(out.status.success(), "{stderr}");
    assert!(stdout.contains("ran to t = 0.3 s (750 steps)"), "{stdout}");
    assert!(
        stderr.contains("real time") && stderr.contains("joints (the forward controllers' order): pivot"),
        "{stderr}"
    );
    assert!(wall >= 0.3, "paced to the wall clock: 0.3 s simulated in {wall} s");
    for (args, says) in [
        (vec!["ros"], "needs a FILE"),
        (vec!["ros", "x.json", "--drive", "one"], "must name two wheel joints"),
        (vec!["ros", "x.json", "--services", "zenoh"], "must be fastrtps or cyclonedds"),
    ] {
        let out = Command::new(ARS).args(&args).output().unwrap();
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        assert!(String::from_utf8_lossy(&out.stderr).contains(says), "{args:?}");
    }
    let bad_domain = Command::new(ARS).args(["ros", file.to_str().unwrap(), "--domain-id", "300"]).output().unwrap();
    assert_eq!(bad_domain.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&bad_domain.stderr).contains("ROS 2 domains are 0 to 232"));
    let no_drive = Command::new(ARS).args(["ros", file.to_str().unwrap(), "--drive", "a,b"]).output().unwrap();
    assert!(String::from_utf8_lossy(&no_drive.stderr).contains("no hinge joint named \"a\""));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[cfg(feature = "ros")]
#[test]
fn ars_ros_without_a_network_says_so() {
    // A network namespace of its own has no interface up, not even the loopback.
    let isolated = Command::new("unshare").args(["-n", "true"]).status().is_ok_and(|s| s.success());
    if !isolated {
        println!("skipped: `unshare -n` is not allowed here (no network namespace to run in)");
        return;
    }
    let file = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/rnea_arm.urdf");
    let out = Command::new("unshare").args(["-n", ARS, "ros", file, "--duration", "1"]).output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("ars: no network: no network interface is up, not even the loopback"), "{stderr}");
}
