//! The one error type of `ars-core`.
//!
//! Every message is a sentence about what the caller gave or asked for, naming objects
//! by their names when they have one (a simulation's objects and joints); a world, which
//! has no names, says "a body" instead of showing a handle.

/// What went wrong in a call to `ars-core`. Each cause has its own variant (a value out
/// of its range, an unknown kind, a file that cannot be read, a malformed file, a
/// removed object...), so that a caller can match on it, and the message alone is
/// enough to find the mistake.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// A number that must be finite (a pose, a force, a velocity...) was NaN or infinite.
    #[error("{what} must be finite, got {value}")]
    NotFinite {
        /// The argument, e.g. "body position".
        what: &'static str,
        /// The offending value, formatted.
        value: String,
    },
    /// A size, mass, density or time step that must be strictly positive was not.
    #[error("{what} must be finite and greater than zero, got {value}")]
    NotPositive {
        /// The argument, e.g. "sphere radius".
        what: &'static str,
        /// The offending value.
        value: f64,
    },
    /// A direction (joint axis, plane normal, ray direction) was the zero vector.
    #[error("{what} must not be the zero vector")]
    ZeroVector {
        /// The argument, e.g. "hinge axis".
        what: &'static str,
    },
    /// A number outside the range the call accepts.
    #[error("{what} {detail}")]
    OutOfRange {
        /// The argument, e.g. "joint limits": the subject of the message.
        what: &'static str,
        /// The range and the value, as the rest of the sentence: "must be within
        /// [0, 1], got 2".
        detail: String,
    },
    /// A value, or a combination of values, that breaks a rule other than a range:
    /// parallel joint axes, a profile without points, an offset for a geom without a
    /// body...
    #[error("{what} {problem}")]
    Invalid {
        /// The argument, e.g. "universal joint axes": the subject of the message.
        what: &'static str,
        /// The rule it breaks, as the rest of the sentence: "must be perpendicular...".
        problem: String,
    },
    /// A kind (of sensor, of controller...) that is not one of those known.
    #[error("unknown {what} {name:?}; the known ones are {}", .known.join(", "))]
    UnknownKind {
        /// What was asked for, e.g. "sensor kind".
        what: &'static str,
        /// The name given.
        name: String,
        /// The names that are known.
        known: Vec<String>,
    },
    /// A handle whose object was removed (or that was never valid in this world).
    #[error("the {kind} was removed: its handle no longer refers to anything")]
    StaleHandle {
        /// "body", "geom", "joint", "space", "object", "sensor" or "hook".
        kind: &'static str,
    },
    /// A handle created by another world (or simulation).
    #[error("the {kind} belongs to another world or simulation")]
    ForeignHandle {
        /// "body", "geom", "joint", "space", "object", "sensor" or "hook".
        kind: &'static str,
    },
    /// A joint whose two ends are the same body.
    #[error("{} joint cannot connect {body} to itself", article(joint))]
    SelfJoint {
        /// The joint kind.
        joint: &'static str,
        /// The body: `object "arm"` in a simulation, "a body" in a world.
        body: String,
    },
    /// An operation that the joint kind does not have (e.g. the angle of a slider).
    #[error("{operation} is not available on {} joint", article(kind))]
    WrongJointKind {
        /// What was asked.
        operation: &'static str,
        /// The joint's kind.
        kind: &'static str,
    },
    /// An operation that the geom kind does not have (e.g. attaching a plane to a body).
    #[error("{operation} is not available on {} geom", article(kind))]
    WrongGeomKind {
        /// What was asked.
        operation: &'static str,
        /// The geom's kind.
        kind: &'static str,
    },
    /// An operation that needs a body (a joint, a laser mount, a velocity...), asked of
    /// a static object, which has none.
    #[error("object {object:?} is static (it has no body); {operation} needs one")]
    NoBody {
        /// What needs the body, e.g. "the first object of a joint".
        operation: &'static str,
        /// The object's name.
        object: String,
    },
    /// A triangle mesh that ODE cannot take.
    #[error("the triangle mesh is invalid: {0}")]
    InvalidMesh(String),
    /// A name that is not registered in a simulation.
    #[error("no {kind} named {name:?}{}", suggestion(.close_matches))]
    UnknownName {
        /// "object" or "joint".
        kind: &'static str,
        /// The name asked for.
        name: String,
        /// Registered names that are spelled almost the same.
        close_matches: Vec<String>,
    },
    /// A name that is already taken.
    #[error("the {kind} name {name:?} is already taken")]
    DuplicateName {
        /// "object" or "joint".
        kind: &'static str,
        /// The name.
        name: String,
    },
    /// A file that cannot be read or written (or a folder that cannot be listed).
    #[error("cannot {operation} {path:?}: {message}")]
    Io {
        /// What was tried, e.g. "read the scene file".
        operation: &'static str,
        /// The path, as given.
        path: String,
        /// The kind of failure (not found, permission denied...).
        kind: std::io::ErrorKind,
        /// The operating system's error number, when there is one.
        errno: Option<i32>,
        /// The system's description of the failure.
        message: String,
    },
    /// A file (or text) that was read but is not what it should be: a scene file that
    /// is not JSON, a URDF whose joint has no child, a key script line that does not
    /// parse...
    #[error("{file}{}: {problem}", place(&format_location(.element, *.line, *.column)))]
    Format {
        /// The format, e.g. "URDF", "scene file", "key script".
        format: &'static str,
        /// The file, or `"<string>"` for text given directly.
        file: String,
        /// The element (tag) or named part it is about, when there is one: `<geom>`,
        /// `link "gripper"`, `"state"` (empty otherwise).
        element: String,
        /// The line in the file, from 1, when it is known.
        line: Option<u32>,
        /// The column in that line, from 1, when it is known.
        column: Option<u32>,
        /// What is wrong.
        problem: String,
    },
    /// The simulation is in the middle of something that the call would disturb (hooks
    /// that reach themselves while they run).
    #[error("{0}")]
    Busy(String),
    /// ODE refused an operation (it returned a failure code).
    #[error("ODE failed to {0}")]
    Ode(&'static str),
    /// A body whose state cannot be integrated: before a step (non-finite or too large
    /// force or torque accumulated, a state that diverged earlier and was not reset),
    /// or after a step (non-finite or runaway position, orientation or velocity). The
    /// world refuses to step until the body is reset or removed; nothing else is lost.
    #[error("{body} diverged at t = {time} s: {detail}")]
    Diverged {
        /// The body: `object "ball"` in a simulation, its handle in a world (which has
        /// no names; [`diverged_body`](crate::World::diverged_body) tells it too).
        body: String,
        /// Time at which it was found: the sum of the time steps taken by the world.
        time: f64,
        /// What was wrong with it.
        detail: String,
    },
    /// ODE reported an internal error while it stepped or collided the world, caught by
    /// the [guard](crate::guard): the world is now poisoned.
    #[error(
        "ODE reported an internal error during the {during}: {message}; the simulation is poisoned (build a new one)"
    )]
    OdeInternal {
        /// What ODE was doing: "step" or "collision".
        during: &'static str,
        /// ODE's message.
        message: String,
    },
    /// The world was poisoned by an earlier ODE internal error and can only be dropped.
    #[error("the simulation is poisoned by an earlier ODE internal error ({0}); build a new one")]
    Poisoned(String),
    /// User code (a hook or a sensor) panicked; the panic was contained and the
    /// simulation keeps its other hooks, sensors and records.
    #[error("{during} panicked: {message}")]
    Panicked {
        /// What was running, e.g. "the pre-step hook of hook set 2" (the second hooks
        /// added among those that run before a step) or "the post-step hook of the program".
        during: String,
        /// The panic message.
        message: String,
    },
    /// A run was stopped on request (Ctrl-C, see [`interrupt`](crate::interrupt), or
    /// its stop condition) between two steps: the simulation is whole and can go on.
    #[error("interrupted at t = {time} s, after {steps} steps")]
    Interrupted {
        /// Simulated time when the run stopped, s.
        time: f64,
        /// Steps taken by then (since the start of the simulation).
        steps: u64,
    },
    /// An error raised by user code inside a program or hook.
    #[error("{0}")]
    User(String),
    /// A snapshot (or a scene file's state) of another scene than the simulation it is
    /// restored into: other objects, joints or sensors, or made in another order.
    #[error("the snapshot is of another scene: {detail}")]
    SnapshotMismatch {
        /// What differs.
        detail: String,
    },
    /// A snapshot written by a version of ARS whose format this one does not read.
    #[error("the snapshot is in format version {found}; this ARS reads version {supported}")]
    SnapshotVersion {
        /// The version in the snapshot.
        found: u32,
        /// The version this ARS writes and reads.
        supported: u32,
    },
    /// Bytes that are not a whole snapshot: truncated, altered, or not a snapshot at all.
    #[error("the bytes are not a whole ARS snapshot: {detail}")]
    SnapshotCorrupt {
        /// What was found wrong.
        detail: String,
    },
    /// Something a snapshot cannot hold: a joint controller or sensor of a type of your
    /// own that does not say how to save its state.
    #[error("cannot take a snapshot: {what}")]
    NotCapturable {
        /// What cannot be saved, and what to do about it.
        what: String,
    },
}

impl Error {
    /// The [`Error::Io`] for `error`, met while trying to `operation` (e.g. "read the
    /// scene file") on `path`.
    pub fn io(operation: &'static str, path: &std::path::Path, error: &std::io::Error) -> Error {
        Error::Io {
            operation,
            path: path.display().to_string(),
            kind: error.kind(),
            errno: error.raw_os_error(),
            message: error.to_string(),
        }
    }
}

fn suggestion(close: &[String]) -> String {
    if close.is_empty() { String::new() } else { format!(" (did you mean {}?)", close.join(", ")) }
}

/// Where in a file a [`Error::Format`] is, as its message says it: `<geom> at line 12`,
/// `line 3, column 7`, `line 3`, `link "gripper"`, or empty for the whole file.
pub fn format_location(element: &str, line: Option<u32>, column: Option<u32>) -> String {
    match (element.is_empty(), line, column) {
        (false, Some(l), _) => format!("{element} at line {l}"),
        (false, None, _) => element.to_string(),
        (true, Some(l), Some(c)) => format!("line {l}, column {c}"),
        (true, Some(l), None) => format!("line {l}"),
        (true, None, _) => String::new(),
    }
}

fn place(location: &str) -> String {
    if location.is_empty() { String::new() } else { format!(", {location}") }
}

/// `word` with its indefinite article: "a hinge", "an angular motor".
pub(crate) fn article(word: &str) -> String {
    let lower = word.to_ascii_lowercase();
    // "a universal", "an unknown".
    let an = lower.starts_with(['a', 'e', 'i', 'o']) || (lower.starts_with("un") && !lower.starts_with("uni"));
    format!("{} {word}", if an { "an" } else { "a" })
}

/// `Result` with [`Error`] as its error.
pub type Result<T, E = Error> = std::result::Result<T, E>;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn articles_follow_the_sound_of_the_word() {
        let wrong = |kind| Error::WrongJointKind { operation: "reading an angle", kind }.to_string();
        assert_eq!(wrong("angular motor"), "reading an angle is not available on an angular motor joint");
        assert_eq!(wrong("slider"), "reading an angle is not available on a slider joint");
        assert_eq!(wrong("universal"), "reading an angle is not available on a universal joint");
    }
}
