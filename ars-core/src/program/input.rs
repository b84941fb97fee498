//! Input for programs: keys, key events, key scripts that replay them, and the
//! actions keys are bound to.

use std::collections::BTreeMap;
use std::fmt;
use std::sync::Arc;

use crate::error::Result;
use crate::simulation::Simulation;

/// A key of the keyboard, as the viewer reports it and as programs bind them.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[non_exhaustive]
pub enum Key {
    /// A character key, lower case (`'a'`, `'z'`, `'r'`...).
    Char(char),
    /// Arrow up.
    Up,
    /// Arrow down.
    Down,
    /// Arrow left.
    Left,
    /// Arrow right.
    Right,
    /// Space bar.
    Space,
}

impl fmt::Display for Key {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Key::Char(c) => write!(f, "{c}"),
            Key::Up => write!(f, "up"),
            Key::Down => write!(f, "down"),
            Key::Left => write!(f, "left"),
            Key::Right => write!(f, "right"),
            Key::Space => write!(f, "space"),
        }
    }
}

impl Key {
    /// A key from its name: `up`, `down`, `left`, `right`, `space`, or one character.
    pub fn from_name(name: &str) -> Option<Key> {
        match name {
            "up" => Some(Key::Up),
            "down" => Some(Key::Down),
            "left" => Some(Key::Left),
            "right" => Some(Key::Right),
            "space" => Some(Key::Space),
            _ => {
                let mut chars = name.chars();
                match (chars.next(), chars.next()) {
                    (Some(c), None) => Some(Key::Char(c.to_ascii_lowercase())),
                    _ => None,
                }
            }
        }
    }
}

/// A key going down or up at a moment of simulated time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct KeyEvent {
    /// Simulated time, s.
    pub time: f64,
    /// The key.
    pub key: Key,
    /// `true` when the key goes down.
    pub down: bool,
}

/// Timed key events that drive a program without a keyboard (headless runs, tests).
///
/// The text form has one event per line, `TIME down|up KEY`, with `#` comments:
/// ```
/// use ars_core::{Key, KeyScript};
/// let script = KeyScript::parse("# drive, then turn\n0.5 down up\n2.0 down left\n4 up left\n4 up up\n")?;
/// assert_eq!(script.events().len(), 4);
/// assert_eq!(script.events()[1].key, Key::Left);
/// # Ok::<(), ars_core::Error>(())
/// ```
#[derive(Clone, Debug, Default, PartialEq)]
pub struct KeyScript {
    events: Vec<KeyEvent>,
}

impl KeyScript {
    /// A script of these events (sorted by time; equal times keep their order).
    pub fn new(mut events: Vec<KeyEvent>) -> Result<Self> {
        if let Some(e) = events.iter().find(|e| !e.time.is_finite() || e.time < 0.0) {
            return Err(crate::Error::OutOfRange {
                what: "a key event time",
                detail: format!("must be finite and at least 0 s, got {} s", e.time),
            });
        }
        events.sort_by(|a, b| a.time.total_cmp(&b.time));
        Ok(KeyScript { events })
    }

    /// Parses the text form (see the type's docs).
    pub fn parse(text: &str) -> Result<Self> {
        let mut events = Vec::new();
        for (n, line) in text.lines().enumerate() {
            let line = line.split('#').next().unwrap_or("").trim();
            if line.is_empty() {
                continue;
            }
            let bad = |why: &str| crate::Error::Format {
                format: "key script",
                file: "<key script>".into(),
                element: String::new(),
                line: u32::try_from(n + 1).ok(),
                column: None,
                problem: format!("{why}: {line:?} (expected `TIME down|up KEY`)"),
            };
            let parts: Vec<&str> = line.split_whitespace().collect();
            let [time, action, key] = parts[..] else { return Err(bad("three fields needed")) };
            let time: f64 = time.parse().map_err(|_| bad("bad time"))?;
            let down = match action {
                "down" => true,
                "up" => false,
                _ => return Err(bad("the action is `down` or `up`")),
            };
            let key = Key::from_name(key).ok_or_else(|| bad("unknown key"))?;
            events.push(KeyEvent { time, key, down });
        }
        Self::new(events)
    }

    /// The events, by time.
    pub fn events(&self) -> &[KeyEvent] {
        &self.events
    }
}

/// When a bound action runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Repeat {
    /// Once when the key goes down, between steps (a torque added then acts for one
    /// step, as in the original).
    Once,
    /// In every step while the key is held, after the pre-step hooks.
    WhileHeld,
}

/// What a key does to a program and its simulation.
pub type Action<P> = Arc<dyn Fn(&mut P, &mut Simulation) -> Result<()> + Send + Sync>;

/// Keys bound to actions of a program `P`.
pub struct ActionMap<P> {
    actions: BTreeMap<Key, (Action<P>, Repeat)>,
}

impl<P> Default for ActionMap<P> {
    fn default() -> Self {
        ActionMap { actions: BTreeMap::new() }
    }
}

impl<P> fmt::Debug for ActionMap<P> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_map().entries(self.actions.iter().map(|(k, (_, r))| (k, r))).finish()
    }
}

impl<P> ActionMap<P> {
    /// No bindings.
    pub fn new() -> Self {
        ActionMap::default()
    }
    /// Binds `key` (replacing an earlier binding).
    #[must_use]
    pub fn add(
        mut self,
        key: Key,
        action: impl Fn(&mut P, &mut Simulation) -> Result<()> + Send + Sync + 'static,
        repeat: Repeat,
    ) -> Self {
        self.actions.insert(key, (Arc::new(action), repeat));
        self
    }
    /// The action bound to `key`.
    pub fn get(&self, key: Key) -> Option<(Action<P>, Repeat)> {
        self.actions.get(&key).map(|(a, r)| (Arc::clone(a), *r))
    }
    /// The bound keys.
    pub fn keys(&self) -> impl Iterator<Item = Key> + '_ {
        self.actions.keys().copied()
    }
}
