//! The upper limits of the calls where a typo (milliseconds for seconds, an extra
//! zero) would run for hours: a recording's duration and a video's frames. Each is
//! refused with the limit in the message unless the call is given `allow_long=True`.

/// The longest recording (`record_video`, `save_replay`, `replay`), seconds of
/// simulated time, without `allow_long=True`: an hour.
pub(crate) const MAX_RECORDING_SECONDS: f64 = 3600.0;

/// The most frames a video has without `allow_long=True`: an hour at 30 frames a
/// second (each frame is drawn, some 10 to 50 ms in software).
pub(crate) const MAX_VIDEO_FRAMES: u64 = 108_000;

/// Checks a recording of `duration` seconds (and `frames` frames, for a video)
/// against the limits, unless `allow_long`; the message names the limit and the way
/// past it.
pub(crate) fn check_recording(duration: f64, frames: Option<u64>, allow_long: bool) -> Result<(), String> {
    if allow_long {
        return Ok(());
    }
    if duration > MAX_RECORDING_SECONDS {
        return Err(format!(
            "a recording of {duration} s is longer than the limit of {MAX_RECORDING_SECONDS} s of simulated \
             time (a typo for milliseconds?): pass allow_long=True to record it"
        ));
    }
    match frames {
        Some(n) if n > MAX_VIDEO_FRAMES => Err(format!(
            "a video of {n} frames has more than the limit of {MAX_VIDEO_FRAMES} frames: lower the frame rate, \
             or pass allow_long=True to record it"
        )),
        _ => Ok(()),
    }
}
