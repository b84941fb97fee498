//! The viewer's errors.

use std::io;
use std::path::{Path, PathBuf};

/// What can go wrong in the viewer: one variant per cause, so that a caller can tell
/// a setting to fix from a machine without a display or a file that cannot be written.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ViewerError {
    /// No window can be opened: neither `DISPLAY` nor `WAYLAND_DISPLAY` names a display
    /// (`reason` is `None`), or the windowing system would not open one (`reason` says
    /// what it said). Off-screen rendering needs no display.
    #[error("{}", no_display(.display, .reason.as_deref()))]
    NoDisplay {
        /// `DISPLAY` when the window was asked for (empty when unset).
        display: String,
        /// Why the window did not open; `None` when no display is named at all.
        reason: Option<String>,
    },
    /// No GPU adapter (not even Mesa's software rasterisers) could be found.
    #[error(
        "no graphics adapter found ({0}); for off-screen rendering with no GPU install Mesa's software drivers: \
         sudo apt-get install libvulkan1 mesa-vulkan-drivers libegl1 libegl-mesa0 libgl1-mesa-dri"
    )]
    NoAdapter(String),
    /// This thread already had a window or renderer, now closed: kiss3d 0.47 can make
    /// one rendering context per thread. Keep the first renderer, render on a new
    /// thread, or call [`keep_rendering_context`](crate::keep_rendering_context) before
    /// the first window.
    #[error(
        "this thread already had a window or renderer, now closed: kiss3d 0.47 can make only one rendering \
         context per thread; keep the first renderer, render on a new thread (std::thread::spawn), or call \
         ars_viewer::keep_rendering_context() before the first window"
    )]
    SecondContext,
    /// A thread of the viewer's (the video encoder, a frame writer) could not start,
    /// stopped before its work was done, or panicked: nothing the caller passed was
    /// wrong.
    #[error("{}", thread_died(.thread, *.end, .source.as_ref()))]
    ThreadDied {
        /// The thread's work, as the message names it: `"the video encoder"`, `"the
        /// frame writers"`, `"a frame writer"`...
        thread: &'static str,
        /// What happened to it.
        end: ThreadEnd,
        /// Why it could not start (the system's refusal), for
        /// [`ThreadEnd::NotStarted`].
        source: Option<io::Error>,
    },
    /// The H.264 encoder failed: it could not start, or could not encode a frame. The
    /// message says which (and at which frame).
    #[error("{0}")]
    Encoder(String),
    /// A file or folder could not be written (a frame, a video, a replay, a camera's
    /// images): `source` says why, with its kind (`NotFound` for a missing folder,
    /// `IsADirectory` for a path that is a folder...) and the system's error number
    /// when there is one.
    #[error("could not write {}: {source}", .path.display())]
    Write {
        /// The file (or folder).
        path: PathBuf,
        /// Why.
        source: io::Error,
    },
    /// A bad value the caller passed: a duration that is not positive, an image size
    /// beyond 8192 pixels, a frame rate of zero, an odd video size, a plot column that
    /// does not exist, a simulation with nothing to show... The message says which and
    /// what is allowed.
    #[error("{0}")]
    InvalidSetting(String),
    /// The call needs a part of the viewer this build left out: the interactive
    /// window (`feature` is `"window"`) or the video encoder (`"video"`), both on by
    /// default.
    #[error(
        "{what} needs the viewer's `{feature}` feature, which this build of ARS left out; build with the \
         default features (or `--features {feature}`)"
    )]
    NotBuilt {
        /// The cargo feature, `"window"` or `"video"`.
        feature: &'static str,
        /// What was asked: "a window", "an MP4 video".
        what: &'static str,
    },
    /// The simulation failed.
    #[error(transparent)]
    Simulation(#[from] ars_core::Error),
}

/// How a thread of the viewer's ended early (see [`ViewerError::ThreadDied`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum ThreadEnd {
    /// It could not be started.
    NotStarted,
    /// It stopped before its work was done.
    Stopped,
    /// It had already stopped (after an earlier failure, reported then).
    AlreadyStopped,
    /// It panicked.
    Panicked,
}

/// The message of [`ViewerError::NoDisplay`].
fn no_display(display: &str, reason: Option<&str>) -> String {
    match reason {
        None => "no display: DISPLAY and WAYLAND_DISPLAY are unset".into(),
        Some(reason) => format!("could not open a window (DISPLAY={display:?}): {reason}"),
    }
}

/// The message of [`ViewerError::ThreadDied`].
fn thread_died(thread: &str, end: ThreadEnd, source: Option<&io::Error>) -> String {
    match (end, source) {
        (ThreadEnd::NotStarted, Some(e)) => format!("could not start {thread}'s thread: {e}"),
        (ThreadEnd::NotStarted, None) => format!("could not start {thread}'s thread"),
        (ThreadEnd::Stopped, _) => format!("{thread} stopped"),
        (ThreadEnd::AlreadyStopped, _) => format!("{thread} already stopped"),
        (ThreadEnd::Panicked, _) => format!("{thread} panicked"),
    }
}

impl ViewerError {
    /// [`ViewerError::Write`] of `path`.
    pub(crate) fn write(path: &Path, source: io::Error) -> Self {
        ViewerError::Write { path: path.to_path_buf(), source }
    }

    /// [`ViewerError::Write`] of `path` for the image crate's `error`: its `io::Error`
    /// when it is one (a missing folder stays `NotFound`), otherwise the image error
    /// inside an [`io::Error::other`].
    pub(crate) fn image_write(path: &Path, error: image::ImageError) -> Self {
        let source = match error {
            image::ImageError::IoError(e) => e,
            other => io::Error::other(other),
        };
        ViewerError::write(path, source)
    }

    /// A thread that could not be started: `source` is the system's refusal.
    pub(crate) fn thread_not_started(thread: &'static str, source: io::Error) -> Self {
        ViewerError::ThreadDied { thread, end: ThreadEnd::NotStarted, source: Some(source) }
    }

    /// A thread that ended early as `end` says.
    pub(crate) fn thread_ended(thread: &'static str, end: ThreadEnd) -> Self {
        ViewerError::ThreadDied { thread, end, source: None }
    }

    /// The same error again, for a later call that must fail the same way (the frame
    /// writers'): an `io::Error` cannot be cloned, so its copy keeps the kind, the
    /// system's error number and the message, not what it wraps.
    pub(crate) fn again(&self) -> Self {
        match self {
            ViewerError::NoDisplay { display, reason } => {
                ViewerError::NoDisplay { display: display.clone(), reason: reason.clone() }
            }
            ViewerError::NoAdapter(m) => ViewerError::NoAdapter(m.clone()),
            ViewerError::SecondContext => ViewerError::SecondContext,
            ViewerError::ThreadDied { thread, end, source } => {
                ViewerError::ThreadDied { thread, end: *end, source: source.as_ref().map(copy_io) }
            }
            ViewerError::Encoder(m) => ViewerError::Encoder(m.clone()),
            ViewerError::Write { path, source } => ViewerError::Write { path: path.clone(), source: copy_io(source) },
            ViewerError::InvalidSetting(m) => ViewerError::InvalidSetting(m.clone()),
            ViewerError::NotBuilt { feature, what } => ViewerError::NotBuilt { feature, what },
            ViewerError::Simulation(e) => ViewerError::Simulation(e.clone()),
        }
    }
}

/// A copy of `e` of the same kind, error number and message.
fn copy_io(e: &io::Error) -> io::Error {
    match e.raw_os_error() {
        Some(code) => io::Error::from_raw_os_error(code),
        None => io::Error::new(e.kind(), e.to_string()),
    }
}

/// `Result` with [`ViewerError`].
pub type Result<T, E = ViewerError> = std::result::Result<T, E>;

#[cfg(test)]
mod tests {
    use std::error::Error as _;

    use super::*;

    #[test]
    fn the_messages_are_the_ones_users_saw_before() {
        let unset = ViewerError::NoDisplay { display: String::new(), reason: None };
        assert_eq!(unset.to_string(), "no display: DISPLAY and WAYLAND_DISPLAY are unset");
        let refused = ViewerError::NoDisplay { display: ":7".into(), reason: Some("no X server".into()) };
        assert_eq!(refused.to_string(), "could not open a window (DISPLAY=\":7\"): no X server");
        let gone = ViewerError::thread_ended("the video encoder", ThreadEnd::Panicked);
        assert_eq!(gone.to_string(), "the video encoder panicked");
        assert_eq!(
            ViewerError::thread_ended("the frame writers", ThreadEnd::Stopped).to_string(),
            "the frame writers stopped"
        );
        let refused = io::Error::new(io::ErrorKind::OutOfMemory, "no memory");
        let not_started = ViewerError::thread_not_started("the video encoder", refused);
        assert_eq!(not_started.to_string(), "could not start the video encoder's thread: no memory");
        let missing = io::Error::new(io::ErrorKind::NotFound, "the folder /x does not exist");
        let write = ViewerError::write(Path::new("/x/a.mp4"), missing);
        assert_eq!(write.to_string(), "could not write /x/a.mp4: the folder /x does not exist");
    }

    #[test]
    fn a_write_error_keeps_its_io_error_as_its_source_and_in_its_copy() {
        let error = ViewerError::write(Path::new("/x/a.png"), io::Error::from_raw_os_error(2));
        let source = error.source().and_then(|s| s.downcast_ref::<io::Error>()).expect("an io::Error");
        assert_eq!((source.kind(), source.raw_os_error()), (io::ErrorKind::NotFound, Some(2)));
        let again = error.again();
        assert_eq!(again.to_string(), error.to_string());
        assert!(matches!(&again, ViewerError::Write { source, .. } if source.raw_os_error() == Some(2)));
        let custom = ViewerError::write(Path::new("/x"), io::Error::new(io::ErrorKind::IsADirectory, "it is a folder"));
        assert!(
            matches!(custom.again(), ViewerError::Write { source, .. } if source.kind() == io::ErrorKind::IsADirectory)
        );
    }

    #[test]
    fn an_image_error_that_is_an_io_error_keeps_its_kind() {
        let io = image::ImageError::IoError(io::Error::from(io::ErrorKind::PermissionDenied));
        let error = ViewerError::image_write(Path::new("a.png"), io);
        assert!(
            matches!(&error, ViewerError::Write { source, .. } if source.kind() == io::ErrorKind::PermissionDenied)
        );
        let other = image::ImageError::Limits(image::error::LimitError::from_kind(
            image::error::LimitErrorKind::DimensionError,
        ));
        let message = other.to_string();
        let error = ViewerError::image_write(Path::new("a.png"), other);
        let ViewerError::Write { source, .. } = &error else { panic!("{error}") };
        assert_eq!((source.kind(), source.to_string()), (io::ErrorKind::Other, message));
        assert!(source.get_ref().is_some_and(|e| e.is::<image::ImageError>()));
    }
}
