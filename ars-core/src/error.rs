//! The one error type of `ars-core`.

/// What went wrong in a call to `ars-core`. Every variant names the offending input,
/// object or handle, so that a message alone is enough to find the mistake.
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
    /// A value was outside the range the call accepts.
    #[error("{what} is out of range: {detail}")]
    OutOfRange {
        /// The argument, e.g. "joint limits".
        what: &'static str,
        /// What was wrong with it.
        detail: String,
    },
    /// A handle that was never valid in this world, or whose object has been removed.
    #[error("{kind} handle {handle} is stale: its object was removed from this world")]
    StaleHandle {
        /// "body", "geom", "joint" or "space".
        kind: &'static str,
        /// The handle, formatted.
        handle: String,
    },
    /// A handle created by another world.
    #[error("{kind} handle {handle} belongs to another world")]
    ForeignHandle {
        /// "body", "geom", "joint" or "space".
        kind: &'static str,
        /// The handle, formatted.
        handle: String,
    },
    /// A joint whose two ends are the same body.
    #[error("a {joint} joint cannot connect body {body} to itself")]
    SelfJoint {
        /// The joint kind.
        joint: &'static str,
        /// The body, formatted.
        body: String,
    },
    /// An operation that the joint kind does not have (e.g. the angle of a slider).
    #[error("{operation} is not available on a {kind} joint")]
    WrongJointKind {
        /// What was asked.
        operation: &'static str,
        /// The joint's kind.
        kind: &'static str,
    },
    /// An operation that the geom kind does not have (e.g. attaching a plane to a body).
    #[error("{operation} is not available on a {kind} geom")]
    WrongGeomKind {
        /// What was asked.
        operation: &'static str,
        /// The geom's kind.
        kind: &'static str,
    },
    /// A triangle mesh that ODE cannot take.
    #[error("invalid triangle mesh: {0}")]
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
    /// ODE refused an operation (it returned a failure code).
    #[error("ODE failed to {0}")]
    Ode(&'static str),
    /// A body whose state cannot be integrated: before a step (non-finite or too large
    /// force or torque accumulated, a state that diverged earlier and was not reset),
    /// or after a step (non-finite or runaway position, orientation or velocity). The
    /// world refuses to step until the body is reset or removed; nothing else is lost.
    #[error("body {body} diverged at t = {time} s: {detail}")]
    Diverged {
        /// The body (its name, in a simulation).
        body: String,
        /// Time at which it was found: the sum of the time steps taken by the world.
        time: f64,
        /// What was wrong with it.
        detail: String,
    },
    /// ODE reported an internal error while it stepped or collided the world, caught by
    /// the [guard](crate::guard): the world is now poisoned.
    #[error("ODE reported an internal error during {during}: {message}; the world is poisoned (drop it)")]
    OdeInternal {
        /// What ODE was doing: "step" or "collision".
        during: &'static str,
        /// ODE's message.
        message: String,
    },
    /// The world was poisoned by an earlier ODE internal error and can only be dropped.
    #[error("the world is poisoned by an earlier ODE internal error ({0}); build a new one")]
    Poisoned(String),
    /// User code (a hook or a sensor) panicked; the panic was contained and the
    /// simulation keeps its other hooks, sensors and records.
    #[error("{during} panicked: {message}")]
    Panicked {
        /// What was running, e.g. "pre-step hook 2".
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
    /// A robot description (URDF) that cannot be loaded: the file, the element and what
    /// is wrong with it.
    #[error("{file}: {element}: {problem}")]
    Urdf {
        /// The file (or `"<string>"`).
        file: String,
        /// The element, e.g. `joint "elbow"`.
        element: String,
        /// What is wrong.
        problem: String,
    },
}

fn suggestion(close: &[String]) -> String {
    if close.is_empty() { String::new() } else { format!(" (did you mean {}?)", close.join(", ")) }
}

/// `Result` with [`Error`] as its error.
pub type Result<T, E = Error> = std::result::Result<T, E>;
