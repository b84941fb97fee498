//! Writing rendered frames as PNG files on worker threads, so that recording runs at
//! the speed of drawing: the render thread hands each frame over and draws the next
//! while workers flip, encode and write it.

use std::path::{Path, PathBuf};
use std::sync::mpsc::{Receiver, SyncSender, sync_channel};
use std::sync::{Arc, Mutex, PoisonError};
use std::thread::JoinHandle;

use crate::error::{Result, ThreadEnd, ViewerError};

/// A frame as read back from the renderer: RGB rows, bottom row first.
pub(crate) struct RawFrame {
    pub(crate) width: u32,
    pub(crate) height: u32,
    pub(crate) bottom_up: Vec<u8>,
}

impl RawFrame {
    /// The image, top row first.
    pub(crate) fn into_image(self) -> image::RgbImage {
        let row = self.width as usize * 3;
        let mut top_down = Vec::with_capacity(self.bottom_up.len());
        for r in self.bottom_up.chunks_exact(row).rev() {
            top_down.extend_from_slice(r);
        }
        image::RgbImage::from_raw(self.width, self.height, top_down).expect("a whole frame of RGB rows")
    }
}

/// One frame to write.
enum Job {
    /// A finished image.
    Image(PathBuf, image::RgbImage),
    /// A frame still bottom row first.
    Raw(PathBuf, RawFrame),
}

/// Writes one image as PNG, exactly as `RgbImage::save` does.
pub(crate) fn write_png(path: &Path, image: &image::RgbImage) -> Result<()> {
    image.save(path).map_err(|e| ViewerError::image_write(path, e))
}

/// PNG files written by worker threads in the background. Nothing is dropped: when
/// the workers fall behind by a few frames, [`write`](Self::write) waits for them
/// (the queue is bounded, so memory stays bounded). The first failure is returned by
/// the next `write` or by [`finish`](Self::finish); after it, nothing more is written.
pub struct FrameWriter {
    jobs: Option<SyncSender<Job>>,
    workers: Vec<JoinHandle<()>>,
    failure: Arc<Mutex<Option<ViewerError>>>,
}

impl FrameWriter {
    /// Workers for this machine: one core is left to drawing (the software rasteriser
    /// uses every core it has), at most four.
    pub fn new() -> Self {
        let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
        Self::with_workers((cores.saturating_sub(1)).clamp(1, 4))
    }

    /// `workers` threads (at least one), with two frames waiting per worker at most.
    pub fn with_workers(workers: usize) -> Self {
        let workers = workers.max(1);
        let (jobs, queue) = sync_channel::<Job>(2 * workers);
        let queue = Arc::new(Mutex::new(queue));
        let failure = Arc::new(Mutex::new(None));
        let workers = (0..workers)
            .map(|i| {
                let (queue, failure) = (Arc::clone(&queue), Arc::clone(&failure));
                std::thread::Builder::new()
                    .name(format!("ars-frame-writer-{i}"))
                    .spawn(move || work(&queue, &failure))
                    .expect("a frame-writer thread")
            })
            .collect();
        FrameWriter { jobs: Some(jobs), workers, failure }
    }

    /// Queues `image` to be written to `path`.
    pub fn write(&mut self, path: PathBuf, image: image::RgbImage) -> Result<()> {
        self.send(Job::Image(path, image))
    }

    /// Queues a bottom-up frame, flipped by the worker.
    pub(crate) fn write_raw(&mut self, path: PathBuf, frame: RawFrame) -> Result<()> {
        self.send(Job::Raw(path, frame))
    }

    fn send(&mut self, job: Job) -> Result<()> {
        self.check()?;
        let sent = self.jobs.as_ref().map(|jobs| jobs.send(job));
        match sent {
            Some(Ok(())) => Ok(()),
            // The workers are gone: one of them panicked.
            _ => {
                self.join();
                self.check()?;
                Err(ViewerError::thread_ended("the frame writers", ThreadEnd::Stopped))
            }
        }
    }

    /// The first failure so far, if any: itself the first time, then a copy (every
    /// later call fails the same way).
    fn check(&self) -> Result<()> {
        let mut failure = self.failure.lock().unwrap_or_else(PoisonError::into_inner);
        match failure.take() {
            Some(e) => {
                *failure = Some(e.again());
                Err(e)
            }
            None => Ok(()),
        }
    }

    fn join(&mut self) {
        self.jobs = None;
        for worker in self.workers.drain(..) {
            if worker.join().is_err() {
                let mut failure = self.failure.lock().unwrap_or_else(PoisonError::into_inner);
                failure.get_or_insert(ViewerError::thread_ended("a frame writer", ThreadEnd::Panicked));
            }
        }
    }

    /// Waits until every queued frame is written; the first failure, if any.
    pub fn finish(mut self) -> Result<()> {
        self.join();
        self.check()
    }
}

impl Default for FrameWriter {
    fn default() -> Self {
        Self::new()
    }
}

impl Drop for FrameWriter {
    /// Writes what is queued (a recorder that stops on an error still leaves whole
    /// files behind).
    fn drop(&mut self) {
        self.join();
    }
}

fn work(queue: &Mutex<Receiver<Job>>, failure: &Mutex<Option<ViewerError>>) {
    loop {
        // The lock is held only while taking a job.
        let job = queue.lock().unwrap_or_else(PoisonError::into_inner).recv();
        let Ok(job) = job else { return };
        if failure.lock().unwrap_or_else(PoisonError::into_inner).is_some() {
            continue; // after a failure, nothing more is written
        }
        let written = match job {
            Job::Image(path, image) => write_png(&path, &image),
            Job::Raw(path, frame) => write_png(&path, &frame.into_image()),
        };
        if let Err(e) = written {
            failure.lock().unwrap_or_else(PoisonError::into_inner).get_or_insert(e);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn image(shade: u8) -> image::RgbImage {
        image::RgbImage::from_fn(4, 3, |x, y| image::Rgb([shade, x as u8 * 60, y as u8 * 80]))
    }

    #[test]
    fn frames_are_written_whole_and_in_number() {
        let dir = std::env::temp_dir().join(format!("ars-frame-writer-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let mut writer = FrameWriter::with_workers(3);
        for i in 0..20u8 {
            writer.write(dir.join(format!("{i}.png")), image(i)).unwrap();
        }
        writer.finish().unwrap();
        for i in 0..20u8 {
            let read = image::open(dir.join(format!("{i}.png"))).unwrap().to_rgb8();
            assert_eq!(read, image(i));
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_bottom_up_frame_is_flipped() {
        let top_down = image(7);
        let bottom_up: Vec<u8> = top_down.rows().rev().flat_map(|r| r.flat_map(|p| p.0)).collect();
        let frame = RawFrame { width: 4, height: 3, bottom_up };
        assert_eq!(frame.into_image(), top_down);
    }

    #[test]
    fn a_write_that_fails_is_reported_and_stops_the_writing() {
        let mut writer = FrameWriter::with_workers(1);
        let missing = std::env::temp_dir().join("ars-no-such-folder-for-frames").join("a.png");
        writer.write(missing.clone(), image(1)).unwrap();
        let error = writer.finish().unwrap_err();
        assert!(matches!(&error, ViewerError::Write { path, .. } if *path == missing), "{error}");
        let source = std::error::Error::source(&error).and_then(|s| s.downcast_ref::<std::io::Error>());
        assert_eq!(source.map(std::io::Error::kind), Some(std::io::ErrorKind::NotFound), "{error:?}");
        assert!(error.to_string().starts_with(&format!("could not write {}: ", missing.display())), "{error}");
    }

    #[test]
    fn every_call_after_a_failure_fails_the_same_way() {
        let mut writer = FrameWriter::with_workers(1);
        let missing = std::env::temp_dir().join("ars-no-such-folder-for-frames-again").join("a.png");
        writer.write(missing.clone(), image(1)).unwrap();
        writer.join();
        let first = writer.write(missing.with_file_name("b.png"), image(2)).unwrap_err();
        let second = writer.write(missing.with_file_name("c.png"), image(3)).unwrap_err();
        let last = writer.finish().unwrap_err();
        for error in [&first, &second, &last] {
            assert_eq!(error.to_string(), first.to_string());
            assert!(
                matches!(error, ViewerError::Write { path, source } if *path == missing
                    && source.kind() == std::io::ErrorKind::NotFound),
                "{error:?}"
            );
        }
    }
}
