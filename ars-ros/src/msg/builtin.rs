//! builtin_interfaces, std_msgs and rosgraph_msgs.

use serde::{Deserialize, Serialize};

/// `builtin_interfaces/msg/Time`: a time since the epoch (for ARS: since the start of
/// the simulation).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct Time {
    /// Whole seconds.
    pub sec: i32,
    /// Nanoseconds past `sec`, below 10⁹.
    pub nanosec: u32,
}

impl Time {
    /// The time `nanoseconds` after zero (saturating at `i32::MAX` seconds).
    pub fn from_nanos(nanoseconds: u64) -> Time {
        let sec = (nanoseconds / 1_000_000_000).min(i32::MAX as u64) as i32;
        Time { sec, nanosec: (nanoseconds % 1_000_000_000) as u32 }
    }

    /// The stamp of `seconds` of simulated time, to the nanosecond; 0 for a negative
    /// or non-finite time, `sec` at most `i32::MAX`.
    pub fn from_seconds(seconds: f64) -> Time {
        Time::from_nanos(nanos_of(seconds))
    }

    /// The time in nanoseconds.
    pub fn nanos(&self) -> u64 {
        self.sec.max(0) as u64 * 1_000_000_000 + u64::from(self.nanosec)
    }
}

/// Simulated time `seconds` in nanoseconds, rounded to the nearest (negative or not
/// finite: 0): what every ARS message is stamped with.
pub fn nanos_of(seconds: f64) -> u64 {
    if seconds.is_finite() && seconds > 0.0 { (seconds * 1e9).round() as u64 } else { 0 }
}

/// `std_msgs/msg/Header`: when and in which frame a message's data is.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct Header {
    /// When the data was measured.
    pub stamp: Time,
    /// The frame the data is in.
    pub frame_id: String,
}

/// `std_msgs/msg/String` (named so as not to hide Rust's `String`).
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct StringMessage {
    /// The text.
    pub data: String,
}

/// `rosgraph_msgs/msg/Clock`: the simulated time, on `/clock`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct Clock {
    /// The time now.
    pub clock: Time,
}
