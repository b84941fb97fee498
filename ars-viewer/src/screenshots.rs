//! The screenshot recorder: numbered PNG frames of a running simulation, written by a
//! [`FrameWriter`] while the next frames are drawn.

use std::path::{Path, PathBuf};

use ars_core::{Simulation, WindowSettings};

use crate::driver::Driver;
use crate::error::{Result, ViewerError};
use crate::frames::FrameWriter;
use crate::offscreen::OffscreenRenderer;
use crate::recorder::{Recorder, RecordingOutput, frames_in};

/// Where a [`ScreenshotRecorder`] writes: numbered PNG frames (`frame_00001.png`,
/// `frame_00002.png`...) in a folder, the first before any step, then one every
/// `every` frames.
#[derive(Clone, Debug)]
pub struct ScreenshotFrames {
    dir: PathBuf,
    every: u32,
}

/// Writes numbered PNG frames of a running simulation into a folder (see
/// [`ScreenshotFrames`]); the size and the options are [`Recorder`]'s.
pub type ScreenshotRecorder = Recorder<ScreenshotFrames>;

impl Recorder<ScreenshotFrames> {
    /// Frames into `dir` (created if missing), one every frame.
    pub fn new(dir: impl Into<PathBuf>) -> Self {
        Recorder::with_output(ScreenshotFrames { dir: dir.into(), every: 1 })
    }
    /// One image every `frames` frames.
    #[must_use]
    pub fn every(mut self, frames: u32) -> Self {
        self.output.every = frames;
        self
    }
    /// The folder.
    pub fn dir(&self) -> &Path {
        &self.output.dir
    }
}

impl ScreenshotFrames {
    /// Renders the simulation and queues the frame numbered `index` (from 1).
    fn write(
        &self,
        writer: &mut FrameWriter,
        renderer: &mut OffscreenRenderer,
        sim: &Simulation,
        index: u32,
    ) -> Result<PathBuf> {
        let path = self.dir.join(format!("frame_{index:05}.png"));
        writer.write_raw(path.clone(), renderer.render_raw(sim)?)?;
        Ok(path)
    }
}

impl RecordingOutput for ScreenshotFrames {
    /// The files written.
    type Recorded = Vec<PathBuf>;

    /// The PNG files are encoded and written by a [`FrameWriter`] while the next
    /// frames are drawn; every one is written when this returns.
    fn record_driven<D: Driver>(
        recorder: &Recorder<Self>,
        driver: &mut D,
        view: &WindowSettings,
        duration: f64,
        started: Option<OffscreenRenderer>,
    ) -> Result<Vec<PathBuf>> {
        let output = &recorder.output;
        if output.every == 0 {
            return Err(ViewerError::InvalidSetting("the screenshot period must be at least one frame".into()));
        }
        let frames = frames_in(&driver.simulation(), duration)?;
        std::fs::create_dir_all(&output.dir).map_err(|e| ViewerError::write(&output.dir, e))?;
        let mut renderer = recorder.renderer(driver, view, started)?;
        let mut writer = FrameWriter::new();
        let mut written = vec![output.write(&mut writer, &mut renderer, &driver.simulation(), 1)?];
        for frame in 1..=frames {
            if ars_core::interrupt::requested() {
                break;
            }
            driver.step_frame()?;
            if frame % u64::from(output.every) == 0 {
                let index = written.len() as u32 + 1;
                written.push(output.write(&mut writer, &mut renderer, &driver.simulation(), index)?);
            }
        }
        writer.finish()?;
        Ok(written)
    }
}
