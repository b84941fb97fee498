//! Video files (issue 24): 5 s of the conical pendulum recorded to MP4 off screen, read
//! back by ffmpeg's `ffprobe` and `ffmpeg` (Debian's `ffmpeg` package, installed by
//! `make deps`; these tests fail, not skip, without it), and bad settings refused
//! before anything is written.

use std::path::{Path, PathBuf};
use std::process::Command;

use ars::viewer::{OffscreenRenderer, VideoRecorder, ViewerError};
use ars::{Hooks, Program, ProgramRunner, WindowSettings};
use ars_programs::ConicalPendulum;

/// A fresh empty folder for one test.
fn folder(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("ars-video-test-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The names of the files in `dir`.
fn files_in(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect()
}

/// Runs an ffmpeg tool; its standard output.
fn run_tool(tool: &str, args: &[&str]) -> String {
    let output = Command::new(tool).args(args).output().unwrap_or_else(|e| {
        panic!("{tool} could not run ({e}): install Debian's ffmpeg package (`make deps` does) for the video tests")
    });
    assert!(output.status.success(), "{tool} {args:?} failed: {}", String::from_utf8_lossy(&output.stderr));
    String::from_utf8(output.stdout).unwrap()
}

/// What ffprobe says of the first video stream of `path` (frames counted by decoding
/// them): the `entries` asked for, as `key=value` lines.
fn ffprobe(path: &Path, entries: &str) -> String {
    let path = path.to_str().unwrap();
    let args = ["-v", "error", "-count_frames", "-select_streams", "v:0", "-show_entries", entries];
    run_tool("ffprobe", &[&args[..], &["-of", "flat=s=_", path]].concat())
}

/// The value of `key=value` in ffprobe's flat output.
fn probed<'a>(probe: &'a str, key: &str) -> &'a str {
    probe
        .lines()
        .find_map(|l| l.strip_prefix(key).and_then(|rest| rest.strip_prefix('=')))
        .unwrap_or_else(|| panic!("no {key} in ffprobe's output:\n{probe}"))
        .trim_matches('"')
}

/// Peak signal-to-noise ratio of `b` against `a`, dB, over the RGB channels.
fn psnr(a: &image::RgbImage, b: &image::RgbImage) -> f64 {
    assert_eq!(a.dimensions(), b.dimensions());
    let squared: f64 = a.as_raw().iter().zip(b.as_raw()).map(|(&x, &y)| (f64::from(x) - f64::from(y)).powi(2)).sum();
    let mse = squared / a.as_raw().len() as f64;
    10.0 * (255.0 * 255.0 / mse).log10()
}

const SIZE: (u32, u32) = (400, 300);

#[test]
fn five_seconds_of_the_conical_pendulum_make_150_frames_and_the_frame_at_2_s_matches_the_renderer() {
    let dir = folder("pendulum");
    let path = dir.join("pendulum.mp4");
    let recorder = VideoRecorder::new(&path).fps(30.0).size(SIZE.0, SIZE.1);
    let (sim, video) = recorder.record(&mut ConicalPendulum::default(), 5.0).unwrap();
    assert_eq!(video.frames, 150);
    assert_eq!(video.duration, 5.0);
    assert!((sim.scene().time() - 5.0).abs() < 1e-9, "the simulation ran {} s", sim.scene().time());
    assert_eq!(files_in(&dir), ["pendulum.mp4"], "only the video is left");
    assert_eq!(std::fs::metadata(&path).unwrap().len(), video.bytes);

    let probe = ffprobe(&path, "stream=codec_name,pix_fmt,width,height,nb_read_frames,avg_frame_rate:format=duration");
    assert_eq!(probed(&probe, "streams_stream_0_codec_name"), "h264");
    assert_eq!(probed(&probe, "streams_stream_0_pix_fmt"), "yuv420p");
    assert_eq!(probed(&probe, "streams_stream_0_width"), "400");
    assert_eq!(probed(&probe, "streams_stream_0_height"), "300");
    assert_eq!(probed(&probe, "streams_stream_0_nb_read_frames"), "150");
    assert_eq!(probed(&probe, "streams_stream_0_avg_frame_rate"), "30/1");
    let duration: f64 = probed(&probe, "format_duration").parse().unwrap();
    assert!((duration - 5.0).abs() < 1e-3, "ffprobe says {duration} s");

    // Frame 60 is the picture at 2 s of simulated time.
    let decoded = dir.join("frame_at_2s.png");
    run_tool(
        "ffmpeg",
        &[
            "-v",
            "error",
            "-y",
            "-i",
            path.to_str().unwrap(),
            "-vf",
            "select=eq(n\\,60)",
            "-fps_mode",
            "passthrough",
            "-frames:v",
            "1",
            decoded.to_str().unwrap(),
        ],
    );
    let decoded = image::open(&decoded).unwrap().to_rgb8();

    // The renderer's pictures at 2 s and at 2.1 s, on a thread of its own (one
    // rendering context per thread).
    let (expected, later) = std::thread::spawn(|| {
        let mut program = ConicalPendulum::default();
        let view = WindowSettings { size: SIZE, ..program.window_settings() };
        let mut renderer = OffscreenRenderer::new(&view).unwrap();
        let mut runner = ProgramRunner::new(&mut program).unwrap();
        runner.run_for(2.0).unwrap();
        let expected = renderer.render(runner.simulation()).unwrap();
        runner.run_for(0.1).unwrap();
        (expected, renderer.render(runner.simulation()).unwrap())
    })
    .join()
    .unwrap();
    expected.save(dir.join("rendered_at_2s.png")).unwrap();
    let db = psnr(&expected, &decoded);
    println!("PSNR of the frame at 2 s: {db:.1} dB ({} bytes for 150 frames)", video.bytes);
    assert!(db >= 30.0, "PSNR {db:.1} dB");
    // Not the picture of another time: the pendulum moves a visible amount in 0.1 s.
    let other = psnr(&later, &decoded);
    println!("PSNR against the picture at 2.1 s: {other:.1} dB");
    assert!(other < db - 3.0, "the frame at 2 s looks as much like the one at 2.1 s");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Expects `record` to fail with a message containing `words`, leaving `dir` empty.
fn refused(dir: &Path, recorder: VideoRecorder, program: &mut impl Program, words: &str) {
    let error = recorder.record(program, 1.0).map(drop).unwrap_err();
    assert!(error.to_string().contains(words), "{error}");
    assert!(files_in(dir).is_empty(), "left behind: {:?}", files_in(dir));
}

#[test]
fn bad_settings_are_refused_before_anything_is_written() {
    let dir = folder("bad");
    let path = dir.join("bad.mp4");
    let pendulum = &mut ConicalPendulum::default();
    refused(&dir, VideoRecorder::new(&path).size(401, 300), pendulum, "must be even");
    refused(&dir, VideoRecorder::new(&path).size(400, 299), pendulum, "must be even");
    refused(&dir, VideoRecorder::new(&path).size(5000, 300), pendulum, "between 2 and 4096");
    for fps in [0.0, -30.0, f64::NAN, f64::INFINITY] {
        refused(&dir, VideoRecorder::new(&path).fps(fps).size(64, 48), pendulum, "frame rate");
    }
    let error = VideoRecorder::new(&path).size(64, 48).record(pendulum, 0.0).map(drop).unwrap_err();
    assert!(error.to_string().contains("positive duration"), "{error}");
    refused(&dir, VideoRecorder::new(&dir).size(64, 48), pendulum, "folder");
    refused(&dir, VideoRecorder::new(dir.join("missing").join("a.mp4")).size(64, 48), pendulum, "does not exist");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn an_unwritable_path_is_refused() {
    // Not even root may create files in /proc.
    let error = VideoRecorder::new("/proc/ars-video.mp4").size(64, 48).record(&mut ConicalPendulum::default(), 1.0);
    let error = error.map(drop).unwrap_err();
    assert!(
        matches!(&error, ViewerError::Write { path, .. } if path.as_path() == Path::new("/proc/ars-video.mp4")),
        "{error}"
    );
}

/// A program with nothing in it.
struct Empty;
impl Hooks for Empty {}
impl Program for Empty {
    fn create_sim_objects(&mut self, _: &mut ars::Simulation) -> ars::Result<()> {
        Ok(())
    }
}

#[test]
fn a_simulation_with_no_objects_is_refused() {
    let dir = folder("empty");
    refused(&dir, VideoRecorder::new(dir.join("empty.mp4")).size(64, 48), &mut Empty, "no objects");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_short_video_at_an_odd_frame_rate_has_its_frames_where_the_rule_says() {
    let dir = folder("odd-rate");
    let path = dir.join("short.mp4");
    // 0.5 s at 7 frames/s: frames at 0, 1/7, ... 3/7 s (4 frames), lasting 4/7 s.
    let (_, video) =
        VideoRecorder::new(&path).fps(7.0).size(64, 48).record(&mut ConicalPendulum::default(), 0.5).unwrap();
    assert_eq!(video.frames, 4);
    let probe = ffprobe(&path, "stream=nb_read_frames:format=duration");
    assert_eq!(probed(&probe, "streams_stream_0_nb_read_frames"), "4");
    let duration: f64 = probed(&probe, "format_duration").parse().unwrap();
    assert!((duration - 4.0 / 7.0).abs() < 1e-3, "ffprobe says {duration} s");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn ars_record_writes_a_video_of_a_robot() {
    let dir = folder("ars-record");
    let path = dir.join("arm.mp4");
    let urdf = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/conical_pendulum_arm.urdf");
    let out = Command::new(env!("CARGO_BIN_EXE_ars"))
        .args(["record", urdf, "--video", path.to_str().unwrap(), "--duration", "1", "--fps", "20", "--size", "96x64"])
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(String::from_utf8_lossy(&out.stdout).contains("20 frames"));
    let probe = ffprobe(&path, "stream=nb_read_frames");
    assert_eq!(probed(&probe, "streams_stream_0_nb_read_frames"), "20");
    std::fs::remove_dir_all(&dir).unwrap();
}
