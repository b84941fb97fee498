//! The exact state of a simulation beyond its scene file ([`SceneState`]), and the
//! checked binary form (a header, then CBOR) in which snapshots and scene files keep it.

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::scene::joints::JointDriveState;
use crate::sensors::SensorState;
use crate::world::state::WorldState;

/// The first bytes of a snapshot.
const MAGIC: &[u8; 8] = b"ARSSNAP\0";
/// The version of the snapshot format this ARS writes and reads.
pub const SNAPSHOT_VERSION: u32 = 1;
/// Magic, version, length, checksum.
const HEADER: usize = 8 + 4 + 8 + 4;

/// The state of a simulation beyond its scene file: what makes a restored
/// simulation step to the bit as the original (see [`snapshot`](super::snapshot)).
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct SceneState {
    pub(super) world: WorldState,
    pub(super) joints: Vec<JointDriveState>,
    pub(super) sensors: Vec<SensorState>,
    /// What each hook set saved of itself ([`Hooks::save_state`](crate::Hooks::save_state)).
    pub(super) hooks: Vec<Vec<u64>>,
    pub(super) frame_count: u64,
    /// The actuated joints' names in the actuators' order (none in snapshots without
    /// actuators, or from before it was kept: joint order).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub(super) actuator_order: Vec<String>,
}

impl SceneState {
    /// Keeps the states of the sensors whose kinds pass `keep`.
    pub(crate) fn keep_sensors(&mut self, keep: impl Fn(&str) -> bool) {
        self.sensors.retain(|s| keep(&s.kind));
    }
}

/// `value` in CBOR behind the header.
pub(crate) fn encode<T: Serialize>(value: &T) -> Vec<u8> {
    let mut payload = Vec::new();
    ciborium::into_writer(value, &mut payload).expect("a snapshot serialises to memory");
    let mut out = Vec::with_capacity(HEADER + payload.len());
    out.extend_from_slice(MAGIC);
    out.extend_from_slice(&SNAPSHOT_VERSION.to_le_bytes());
    out.extend_from_slice(&(payload.len() as u64).to_le_bytes());
    out.extend_from_slice(&crc32fast::hash(&payload).to_le_bytes());
    out.extend_from_slice(&payload);
    out
}

/// What [`encode`] wrote, checked.
pub(crate) fn decode<T: for<'de> Deserialize<'de>>(bytes: &[u8]) -> Result<T> {
    let corrupt = |detail: String| Error::SnapshotCorrupt { detail };
    if bytes.len() < MAGIC.len() || &bytes[..MAGIC.len()] != MAGIC {
        return Err(corrupt("they do not start with \"ARSSNAP\\0\"".into()));
    }
    if bytes.len() < HEADER {
        return Err(corrupt(format!("they end inside the header ({} of {HEADER} bytes)", bytes.len())));
    }
    let version = u32::from_le_bytes(bytes[8..12].try_into().expect("4 bytes"));
    if version != SNAPSHOT_VERSION {
        return Err(Error::SnapshotVersion { found: version, supported: SNAPSHOT_VERSION });
    }
    let length = u64::from_le_bytes(bytes[12..20].try_into().expect("8 bytes"));
    let crc = u32::from_le_bytes(bytes[20..24].try_into().expect("4 bytes"));
    let payload = &bytes[HEADER..];
    if payload.len() as u64 != length {
        return Err(corrupt(format!("the header announces {length} bytes of content, there are {}", payload.len())));
    }
    if crc32fast::hash(payload) != crc {
        return Err(corrupt("their checksum does not match their content (altered bytes)".into()));
    }
    ciborium::from_reader(payload).map_err(|e| corrupt(format!("their content does not decode: {e}")))
}
