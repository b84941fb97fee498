//! CDR, the byte layout of ROS 2 messages: little-endian, each value aligned to its
//! size from the start of the body, behind the 4-byte encapsulation header
//! `00 01 00 00` (CDR_LE). Encoded with `cdr-encoding`, what RustDDS and ros2-client use.

use byteorder::LittleEndian;
use serde::Serialize;
use serde::de::DeserializeOwned;

use crate::error::{RosError, RosResult};

/// The encapsulation header of little-endian plain CDR.
pub const CDR_LE_HEADER: [u8; 4] = [0x00, 0x01, 0x00, 0x00];

/// `message` as CDR bytes, encapsulation header first: a DDS sample's payload and an
/// MCAP `cdr` message's data.
pub fn encode<T: Serialize>(message: &T) -> RosResult<Vec<u8>> {
    let mut bytes = CDR_LE_HEADER.to_vec();
    let body =
        cdr_encoding::to_vec::<T, LittleEndian>(message).map_err(|e| RosError::Encoding { detail: e.to_string() })?;
    bytes.extend_from_slice(&body);
    Ok(bytes)
}

/// The message in `bytes` (encapsulation header first, little-endian CDR only).
pub fn decode<T: DeserializeOwned>(bytes: &[u8]) -> RosResult<T> {
    let body = bytes.strip_prefix(&CDR_LE_HEADER[..]).ok_or_else(|| RosError::Encoding {
        detail: format!("expected the little-endian CDR header 00 01 00 00, got {:02x?}", &bytes[..bytes.len().min(4)]),
    })?;
    let (message, _) =
        cdr_encoding::from_bytes::<T, LittleEndian>(body).map_err(|e| RosError::Encoding { detail: e.to_string() })?;
    Ok(message)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::msg::{Clock, Header, JointState, LaserScan, StringMessage, Time, TransformStamped};

    #[test]
    fn a_clock_is_two_little_endian_words_behind_the_header() {
        let clock = Clock { clock: Time { sec: 3, nanosec: 500_000_000 } };
        let bytes = encode(&clock).unwrap();
        assert_eq!(bytes, [0, 1, 0, 0, 3, 0, 0, 0, 0x00, 0x65, 0xcd, 0x1d]);
        assert_eq!(decode::<Clock>(&bytes).unwrap(), clock);
    }

    #[test]
    fn a_string_is_its_length_with_the_nul_then_its_bytes_and_a_nul() {
        let bytes = encode(&StringMessage { data: "ab".into() }).unwrap();
        assert_eq!(bytes, [0, 1, 0, 0, 3, 0, 0, 0, b'a', b'b', 0]);
    }

    #[test]
    fn doubles_are_aligned_to_eight_bytes_from_the_start_of_the_body() {
        // Header: stamp (8 bytes), frame_id "a" (4 + 2), then child_frame_id "b" (pad 2,
        // 4 + 2), then the translation's first double at offset 24 (after 6 bytes of
        // padding), all counted from the end of the encapsulation header.
        let mut t = TransformStamped {
            header: Header { stamp: Time { sec: 1, nanosec: 2 }, frame_id: "a".into() },
            child_frame_id: "b".into(),
            ..Default::default()
        };
        t.transform.translation.x = 1.0;
        let bytes = encode(&t).unwrap();
        let body = &bytes[4..];
        assert_eq!(&body[..8], &[1, 0, 0, 0, 2, 0, 0, 0]);
        assert_eq!(&body[8..14], &[2, 0, 0, 0, b'a', 0]);
        assert_eq!(&body[14..16], &[0, 0], "padding to 4");
        assert_eq!(&body[16..22], &[2, 0, 0, 0, b'b', 0]);
        assert_eq!(&body[22..24], &[0, 0], "padding to 8");
        assert_eq!(&body[24..32], &1.0f64.to_le_bytes());
        // then y, z, and the rotation's x, y, z, w (w = 1).
        assert_eq!(body.len(), 24 + 7 * 8);
        assert_eq!(&body[24 + 6 * 8..], &1.0f64.to_le_bytes());
        assert_eq!(decode::<TransformStamped>(&bytes).unwrap(), t);
    }

    #[test]
    fn sequences_are_a_count_then_their_elements() {
        let state = JointState {
            header: Header::default(),
            name: vec!["j".into()],
            position: vec![0.5],
            velocity: vec![],
            effort: vec![],
        };
        let body = encode(&state).unwrap()[4..].to_vec();
        // stamp 8, frame_id "" (4 + 1, pad 3), names: count 1, "j" (4 + 2), pad 2,
        // positions: count 1 at 28, then 0.5 at 32 (aligned already); velocity and
        // effort: count 0 each.
        let mut expected = vec![0u8; 8];
        expected.extend([1, 0, 0, 0, 0, 0, 0, 0]);
        expected.extend([1, 0, 0, 0, 2, 0, 0, 0, b'j', 0, 0, 0]);
        expected.extend([1, 0, 0, 0]);
        expected.extend(0.5f64.to_le_bytes());
        expected.extend([0, 0, 0, 0, 0, 0, 0, 0]);
        assert_eq!(body, expected);
    }

    #[test]
    fn a_laser_scan_keeps_infinite_ranges() {
        let scan = LaserScan { ranges: vec![1.5, f32::INFINITY], range_max: 10.0, ..Default::default() };
        let bytes = encode(&scan).unwrap();
        // stamp 8 + frame_id 5 + pad 3 = 16, seven floats (28) = 44, ranges count at 44.
        let body = &bytes[4..];
        assert_eq!(&body[44..48], &[2, 0, 0, 0]);
        assert_eq!(&body[48..52], &1.5f32.to_le_bytes());
        assert_eq!(&body[52..56], &f32::INFINITY.to_le_bytes());
        assert_eq!(decode::<LaserScan>(&bytes).unwrap(), scan);
    }

    #[test]
    fn bytes_without_the_header_are_refused() {
        let err = decode::<Clock>(&[1, 2]).unwrap_err();
        assert!(err.to_string().contains("00 01 00 00"), "{err}");
    }
}
