//! Video files (H.264 in MP4) of a simulation, at the simulation's own time: frame
//! `k` of a video at `fps` frames a second shows the simulation at `k / fps` simulated
//! seconds from the start of the recording, whatever the wall clock does.
//!
//! The codec is Cisco's OpenH264 (`h264.rs`, compiled from its bundled source: no
//! system ffmpeg or library needed; feature `video`); the MP4 container is ARS's own writer
//! (`mp4.rs`). A worker thread converts each frame to YUV 4:2:0, encodes it and
//! writes it while the next one is drawn. The file appears whole at the end or not
//! at all: frames go to hidden files beside it, renamed into place when the video is
//! finished and removed on failure.

use std::fs::File;
use std::io::{BufReader, BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::mpsc::{Receiver, SyncSender, sync_channel};
use std::thread::JoinHandle;

use ars_core::{Simulation, WindowSettings};

use crate::driver::Driver;
use crate::error::{Result, ThreadEnd, ViewerError};
use crate::frames::RawFrame;
use crate::h264::H264;
use crate::mp4::Mp4Track;
use crate::offscreen::OffscreenRenderer;
use crate::recorder::{Recorder, RecordingOutput, frames_in};

/// The encoder's thread, as its errors name it.
const ENCODER: &str = "the video encoder";

/// The largest frame rate a video can have, frames per second.
pub const MAX_VIDEO_FPS: f64 = 1000.0;
/// The largest width or height of a video, pixels (H.264 level 5.2).
pub const MAX_VIDEO_SIDE: u32 = 4096;

/// How a simulated time is matched to a step: a step whose time is this close below
/// the time wanted counts as reaching it (the simulated time is a sum of steps).
const TIME_TOLERANCE: f64 = 1e-9;

/// Checks a video's frame rate and size; the message says what is wrong.
pub fn check_video_settings(fps: f64, width: u32, height: u32) -> Result<()> {
    if !(fps.is_finite() && fps > 0.0 && fps <= MAX_VIDEO_FPS) {
        return Err(ViewerError::InvalidSetting(format!(
            "a video's frame rate must be a number of frames per second above 0 and at most {MAX_VIDEO_FPS}, got {fps}"
        )));
    }
    if !width.is_multiple_of(2) || !height.is_multiple_of(2) {
        return Err(ViewerError::InvalidSetting(format!(
            "a video's width and height must be even (H.264 stores colour at half resolution), got {width}×{height}: \
             use {}×{}",
            width + width % 2,
            height + height % 2
        )));
    }
    if !(2..=MAX_VIDEO_SIDE).contains(&width) || !(2..=MAX_VIDEO_SIDE).contains(&height) {
        return Err(ViewerError::InvalidSetting(format!(
            "a video's width and height must be between 2 and {MAX_VIDEO_SIDE} pixels, got {width}×{height}"
        )));
    }
    // H.264 level 5.2 holds up to 36,864 macroblocks of 16×16 pixels a frame.
    if u64::from(width.div_ceil(16)) * u64::from(height.div_ceil(16)) > 36_864 {
        return Err(ViewerError::InvalidSetting(format!(
            "a video of {width}×{height} pixels is larger than H.264 allows (about 4096×2304)"
        )));
    }
    Ok(())
}

/// The number of frames of a video of `duration` simulated seconds at `fps`: the
/// frames `k` with `k / fps` before `duration` (5 s at 30 frames/s: 150 frames, the
/// last at 4.967 s, and the video lasts 5.0 s).
pub fn video_frame_count(duration: f64, fps: f64) -> Result<u64> {
    if !(duration.is_finite() && duration > 0.0) {
        return Err(ViewerError::InvalidSetting(format!("a video needs a positive duration, got {duration} s")));
    }
    Ok((duration * fps - 1e-9).ceil().max(1.0) as u64)
}

/// What a finished video holds.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct RecordedVideo {
    /// The file.
    pub path: PathBuf,
    /// Frames in it.
    pub frames: u64,
    /// Frames per second.
    pub fps: f64,
    /// Its length, s: `frames / fps`.
    pub duration: f64,
    /// Width and height, pixels.
    pub size: (u32, u32),
    /// The file's size, bytes.
    pub bytes: u64,
}

/// A frame for the encoder.
enum Frame {
    /// A finished image, top row first.
    Image(image::RgbImage),
    /// As read back from the renderer, bottom row first.
    Raw(RawFrame),
}

/// The hidden files beside the video while it is written; removed unless the video
/// is finished.
struct PartialFiles {
    /// The frames' bytes.
    frames: PathBuf,
    /// The whole file, before it is renamed into place.
    whole: PathBuf,
}

impl PartialFiles {
    fn beside(path: &Path) -> Self {
        let dir = path.parent().unwrap_or(Path::new(""));
        let name = path.file_name().map_or_else(|| "video".into(), |n| n.to_string_lossy().into_owned());
        let id = std::process::id();
        PartialFiles {
            frames: dir.join(format!(".{name}.{id}.frames")),
            whole: dir.join(format!(".{name}.{id}.partial")),
        }
    }

    fn remove(&self) {
        for f in [&self.frames, &self.whole] {
            let _ = std::fs::remove_file(f);
        }
    }
}

/// An MP4 video written frame by frame: [`add_frame`](Self::add_frame), then
/// [`finish`](Self::finish). A worker thread encodes the frames while the caller draws
/// the next; at most a few frames wait (memory stays bounded). The file appears only
/// when the video is finished: dropped unfinished or failed, nothing is left behind.
pub struct VideoWriter {
    path: PathBuf,
    partial: PartialFiles,
    size: (u32, u32),
    fps: f64,
    frames: Option<SyncSender<Frame>>,
    worker: Option<JoinHandle<Result<Mp4Track>>>,
}

impl VideoWriter {
    /// A video of `width × height` pixels at `fps` frames a second into `path`
    /// (replaced if it exists). Refuses an odd or too large size, a frame rate that is
    /// not a positive number, and a path that cannot be written, before writing
    /// anything.
    pub fn create(path: impl Into<PathBuf>, width: u32, height: u32, fps: f64) -> Result<Self> {
        let path = path.into();
        check_video_settings(fps, width, height)?;
        if path.is_dir() {
            let why = std::io::Error::new(
                std::io::ErrorKind::IsADirectory,
                "it is a folder; give a file name such as video.mp4",
            );
            return Err(ViewerError::write(&path, why));
        }
        let dir = path.parent().filter(|d| !d.as_os_str().is_empty()).unwrap_or(Path::new("."));
        if !dir.is_dir() {
            let why = std::io::Error::new(
                std::io::ErrorKind::NotFound,
                format!("the folder {} does not exist", dir.display()),
            );
            return Err(ViewerError::write(&path, why));
        }
        let partial = PartialFiles::beside(&path);
        let file = File::create(&partial.frames).map_err(|e| ViewerError::write(&path, e))?;
        let encoder = match H264::new(width, height, fps) {
            Ok(e) => e,
            Err(e) => {
                partial.remove();
                return Err(e);
            }
        };
        let track = match Mp4Track::new(width, height, fps) {
            Ok(t) => t,
            Err(e) => {
                partial.remove();
                return Err(ViewerError::write(&path, e));
            }
        };
        let (frames, queue) = sync_channel(4);
        let shown = path.clone();
        let worker = std::thread::Builder::new()
            .name("ars-video-encoder".into())
            .spawn(move || encode(queue, encoder, track, BufWriter::new(file), (width, height), &shown));
        let worker = match worker {
            Ok(w) => w,
            Err(e) => {
                partial.remove();
                return Err(ViewerError::thread_not_started(ENCODER, e));
            }
        };
        Ok(VideoWriter { path, partial, size: (width, height), fps, frames: Some(frames), worker: Some(worker) })
    }

    /// The video's file.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Queues the next frame; it must be of the video's size.
    pub fn add_frame(&mut self, image: image::RgbImage) -> Result<()> {
        if image.dimensions() != self.size {
            return Err(ViewerError::InvalidSetting(format!(
                "a frame of {}×{} pixels for a video of {}×{}",
                image.width(),
                image.height(),
                self.size.0,
                self.size.1
            )));
        }
        self.send(Frame::Image(image))
    }

    /// Queues a frame as read back from the renderer.
    pub(crate) fn add_raw(&mut self, frame: RawFrame) -> Result<()> {
        if (frame.width, frame.height) != self.size {
            return Err(ViewerError::InvalidSetting(format!(
                "a frame of {}×{} pixels for a video of {}×{}",
                frame.width, frame.height, self.size.0, self.size.1
            )));
        }
        self.send(Frame::Raw(frame))
    }

    fn send(&mut self, frame: Frame) -> Result<()> {
        let sent = self.frames.as_ref().is_some_and(|f| f.send(frame).is_ok());
        if sent {
            return Ok(());
        }
        // The worker stopped: its error says why.
        self.frames = None;
        match self.join() {
            Err(e) => Err(e),
            Ok(_) => Err(ViewerError::thread_ended(ENCODER, ThreadEnd::Stopped)),
        }
    }

    /// Waits for the worker; its track, or what went wrong.
    fn join(&mut self) -> Result<Mp4Track> {
        self.frames = None;
        match self.worker.take().map(|w| w.join()) {
            Some(Ok(outcome)) => outcome,
            Some(Err(_)) => Err(ViewerError::thread_ended(ENCODER, ThreadEnd::Panicked)),
            None => Err(ViewerError::thread_ended(ENCODER, ThreadEnd::AlreadyStopped)),
        }
    }

    /// Encodes what is queued and writes the file; what it holds. A video needs at
    /// least one frame.
    pub fn finish(mut self) -> Result<RecordedVideo> {
        let track = self.join()?;
        if track.frames() == 0 {
            return Err(ViewerError::InvalidSetting("a video needs at least one frame".into()));
        }
        let written = (|| -> std::io::Result<u64> {
            let mut payload = BufReader::new(File::open(&self.partial.frames)?);
            let mut out = BufWriter::new(File::create(&self.partial.whole)?);
            track.write_file(&mut out, &mut payload)?;
            out.into_inner().map_err(|e| e.into_error())?.sync_all()?;
            std::fs::rename(&self.partial.whole, &self.path)?;
            Ok(std::fs::metadata(&self.path)?.len())
        })();
        let bytes = written.map_err(|e| ViewerError::write(&self.path, e))?;
        let frames = track.frames() as u64;
        Ok(RecordedVideo {
            path: self.path.clone(),
            frames,
            fps: self.fps,
            duration: frames as f64 / self.fps,
            size: self.size,
            bytes,
        })
    }
}

impl Drop for VideoWriter {
    /// Stops the worker and removes the hidden files (after [`finish`](Self::finish),
    /// the frames' file; otherwise everything: no half-written video is left).
    fn drop(&mut self) {
        self.frames = None;
        if let Some(worker) = self.worker.take() {
            let _ = worker.join();
        }
        self.partial.remove();
    }
}

/// A video of a window: what it shows, at the simulation's time. Frame k is the
/// window's picture at the first window frame at or after k/fps simulated seconds
/// from its first picture (a frame shown longer than 1/fps repeats; while paused,
/// simulated time stands still and so does the video).
pub(crate) struct WindowVideo {
    writer: VideoWriter,
    start: Option<f64>,
    taken: u64,
}

impl WindowVideo {
    /// Into `writer`.
    pub(crate) fn new(writer: VideoWriter) -> Self {
        WindowVideo { writer, start: None, taken: 0 }
    }

    /// The window shows the simulation at `time`: the video frames due by then are
    /// its picture, taken by `snap` (scaled to the video's size if the window's
    /// differs: resized, or on a screen of another scale).
    pub(crate) fn shown(&mut self, time: f64, snap: impl FnOnce() -> image::RgbImage) -> Result<()> {
        let start = *self.start.get_or_insert(time);
        let fps = self.writer.fps;
        let mut due = 0;
        while time - start >= (self.taken + due) as f64 / fps - TIME_TOLERANCE {
            due += 1;
        }
        if due == 0 {
            return Ok(());
        }
        let mut picture = snap();
        let (w, h) = self.writer.size;
        if picture.dimensions() != (w, h) {
            picture = image::imageops::resize(&picture, w, h, image::imageops::FilterType::Triangle);
        }
        for _ in 1..due {
            self.writer.add_frame(picture.clone())?;
        }
        self.writer.add_frame(picture)?;
        self.taken += due;
        Ok(())
    }

    /// Writes the video.
    pub(crate) fn finish(self) -> Result<RecordedVideo> {
        self.writer.finish()
    }
}

/// The worker: converts, encodes and writes each frame until the queue closes.
fn encode(
    queue: Receiver<Frame>,
    mut encoder: H264,
    mut track: Mp4Track,
    mut payload: BufWriter<File>,
    (width, height): (u32, u32),
    shown: &Path,
) -> Result<Mp4Track> {
    let mut yuv = vec![0u8; (width * height * 3 / 2) as usize];
    for frame in queue {
        match &frame {
            Frame::Image(image) => rgb_to_yuv420(image.as_raw(), width as usize, height as usize, false, &mut yuv),
            Frame::Raw(raw) => rgb_to_yuv420(&raw.bottom_up, width as usize, height as usize, true, &mut yuv),
        }
        let (bytes, storage) = encoder.encode(std::mem::take(&mut yuv), track.frames() as u64 + 1)?;
        track.add_frame(&bytes, &mut payload).map_err(|e| ViewerError::write(shown, e))?;
        yuv = storage;
    }
    payload.flush().map_err(|e| ViewerError::write(shown, e))?;
    Ok(track)
}

/// RGB rows (top row first, or bottom row first if `bottom_up`) to planar YUV 4:2:0
/// in limited range with BT.601 coefficients (what the video says it holds), each
/// chroma sample the mean of its 2×2 pixels.
fn rgb_to_yuv420(rgb: &[u8], width: usize, height: usize, bottom_up: bool, out: &mut [u8]) {
    let (y_plane, chroma) = out.split_at_mut(width * height);
    let (u_plane, v_plane) = chroma.split_at_mut(width * height / 4);
    let row = |r: usize| {
        let source = if bottom_up { height - 1 - r } else { r };
        &rgb[source * width * 3..(source + 1) * width * 3]
    };
    for r in (0..height).step_by(2) {
        let (top, bottom) = (row(r), row(r + 1));
        for c in (0..width).step_by(2) {
            let (mut rs, mut gs, mut bs) = (0i32, 0i32, 0i32);
            for (line, y_row) in [(top, r), (bottom, r + 1)] {
                for x in [c, c + 1] {
                    let (red, green, blue) =
                        (i32::from(line[3 * x]), i32::from(line[3 * x + 1]), i32::from(line[3 * x + 2]));
                    y_plane[y_row * width + x] = (((66 * red + 129 * green + 25 * blue + 128) >> 8) + 16) as u8;
                    rs += red;
                    gs += green;
                    bs += blue;
                }
            }
            let (red, green, blue) = (rs as f32 / 4.0, gs as f32 / 4.0, bs as f32 / 4.0);
            let at = (r / 2) * (width / 2) + c / 2;
            u_plane[at] = (-0.148_223 * red - 0.290_993 * green + 0.439_216 * blue + 128.5) as u8;
            v_plane[at] = (0.439_216 * red - 0.367_788 * green - 0.071_427 * blue + 128.5) as u8;
        }
    }
}

/// Records MP4 videos of a running simulation, off screen, at its own time: frame `k`
/// is the picture at the first step at or after `k / fps` simulated seconds from the
/// start (with the default step of 0.4 ms, at most 0.4 ms late); a program's frames
/// run as usual around it.
///
/// ```no_run
/// # fn main() -> ars_viewer::Result<()> {
/// # struct P; impl ars_core::Hooks for P {}
/// # impl ars_core::Program for P {
/// #     fn create_sim_objects(&mut self, sim: &mut ars_core::Simulation) -> ars_core::Result<()> {
/// #         sim.scene_mut().add_sphere(0.5, [1.0, 1.0, 1.0], ars_core::Mass::Total(1.0)).map(drop)
/// #     }
/// # }
/// let recorder = ars_viewer::VideoRecorder::new("pendulum.mp4").fps(30.0).size(800, 600);
/// let (_sim, video) = recorder.record(&mut P, 5.0)?;
/// assert_eq!(video.frames, 150);
/// # Ok(()) }
/// ```
pub type VideoRecorder = Recorder<VideoFile>;

/// Where a [`VideoRecorder`] writes: an MP4 file, at a frame rate.
#[derive(Clone, Debug)]
pub struct VideoFile {
    path: PathBuf,
    fps: f64,
}

impl Recorder<VideoFile> {
    /// A video into `path` at 30 frames a second.
    pub fn new(path: impl Into<PathBuf>) -> Self {
        Recorder::with_output(VideoFile { path: path.into(), fps: 30.0 })
    }
    /// Frames per second of video (and of simulated time).
    #[must_use]
    pub fn fps(mut self, fps: f64) -> Self {
        self.output.fps = fps;
        self
    }
    /// The video's file.
    pub fn path(&self) -> &Path {
        &self.output.path
    }
}

impl RecordingOutput for VideoFile {
    /// The video.
    type Recorded = RecordedVideo;

    /// Runs what `driver` drives for `duration` seconds of simulated time (whole
    /// frames of the simulation), seen as `view` says, recording
    /// [`video_frame_count`] frames. Everything is checked before anything is
    /// written: the frame rate, the size, the path, and that the simulation has
    /// objects to show. A stop requested through [`ars_core::interrupt`] (Ctrl-C)
    /// ends the recording after the frame being drawn, with a shorter video.
    fn record_driven<D: Driver>(
        recorder: &Recorder<Self>,
        driver: &mut D,
        view: &WindowSettings,
        duration: f64,
        started: Option<OffscreenRenderer>,
    ) -> Result<RecordedVideo> {
        let (width, height) = recorder.size.unwrap_or(view.size);
        let VideoFile { path, fps } = &recorder.output;
        let fps = *fps;
        check_video_settings(fps, width, height)?;
        let count = video_frame_count(duration, fps)?;
        let (frames, start) = {
            let sim = driver.simulation();
            if !sim.scene().objects().any(|(_, id)| drawn(&sim, id)) {
                return Err(ViewerError::InvalidSetting(
                    "nothing to record: the simulation has nothing to draw but a floor (no objects, or robot links \
                     without visuals or collision geometry)"
                        .into(),
                ));
            }
            (frames_in(&sim, duration)?, sim.scene().time())
        };
        let mut writer = VideoWriter::create(path, width, height, fps)?;
        let mut renderer = recorder.renderer(driver, view, started)?;
        let mut next = 0u64;
        let mut failure: Option<ViewerError> = None;
        // Pictures for every video frame due by the simulation's time now.
        let mut take = |sim: &Simulation, next: &mut u64| -> Result<()> {
            while *next < count && sim.scene().time() - start >= *next as f64 / fps - TIME_TOLERANCE {
                writer.add_raw(renderer.render_raw(sim)?)?;
                *next += 1;
            }
            Ok(())
        };
        take(&driver.simulation(), &mut next)?;
        for _ in 0..frames {
            if ars_core::interrupt::requested() {
                break;
            }
            let stepped = driver.step_frame_observed(&mut |sim| {
                take(sim, &mut next).map_err(|e| {
                    let message = e.to_string();
                    failure = Some(e);
                    ars_core::Error::User(message)
                })
            });
            if let Some(e) = failure.take() {
                return Err(e);
            }
            stepped?;
        }
        writer.finish()
    }
}

/// Whether object `id` shows in a picture: it has visuals, or a geom that is not a
/// plane (a robot link with neither is only a 1 mm placeholder).
fn drawn(sim: &Simulation, id: ars_core::ObjectId) -> bool {
    let world = sim.scene().world();
    sim.scene().object(id).is_ok_and(|o| {
        !o.visuals().is_empty()
            || o.geoms().filter_map(|g| world.geom(g).ok()).any(|g| !matches!(g.shape(), ars_core::Shape::Plane { .. }))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frames_are_counted_from_the_start_up_to_the_duration() {
        assert_eq!(video_frame_count(5.0, 30.0).unwrap(), 150);
        assert_eq!(video_frame_count(0.5, 7.0).unwrap(), 4);
        assert_eq!(video_frame_count(1.01, 30.0).unwrap(), 31);
        assert!(video_frame_count(0.0, 30.0).is_err());
    }

    #[test]
    fn a_missing_folder_or_a_folder_is_a_write_error_and_a_bad_rate_an_invalid_setting() {
        let missing = std::env::temp_dir().join("ars-no-such-folder-for-videos").join("a.mp4");
        let error = VideoWriter::create(&missing, 64, 48, 30.0).err().expect("refused");
        assert!(
            matches!(&error, ViewerError::Write { path, source } if *path == missing
                && source.kind() == std::io::ErrorKind::NotFound),
            "{error:?}"
        );
        assert!(error.to_string().ends_with("ars-no-such-folder-for-videos does not exist"), "{error}");
        let folder = std::env::temp_dir();
        let error = VideoWriter::create(&folder, 64, 48, 30.0).err().expect("refused");
        assert!(
            matches!(&error, ViewerError::Write { source, .. } if source.kind() == std::io::ErrorKind::IsADirectory),
            "{error:?}"
        );
        let error = VideoWriter::create(&missing, 64, 48, 0.0).err().expect("refused");
        assert!(matches!(&error, ViewerError::InvalidSetting(m) if m.contains("frame rate")), "{error:?}");
    }

    #[test]
    fn grey_white_and_red_convert_to_their_limited_range_values() {
        let rgb: Vec<u8> = [[128u8, 128, 128], [255, 255, 255], [255, 0, 0], [255, 0, 0]].concat();
        let mut out = vec![0u8; 6];
        // 2×2: a grey and a white row above a red row (bottom up: red on top).
        rgb_to_yuv420(&rgb, 2, 2, false, &mut out);
        assert_eq!(&out[..4], [126, 235, 82, 82]);
        rgb_to_yuv420(&rgb, 2, 2, true, &mut out);
        assert_eq!(&out[..4], [82, 82, 126, 235]);
    }
}
