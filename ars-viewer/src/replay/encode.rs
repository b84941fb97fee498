//! The replay's data as the page carries it: a JSON header and its arrays, deflated
//! and written in base64.

use std::io::Write;

use flate2::Compression;
use flate2::write::ZlibEncoder;
use serde_json::{Value, json};

/// The arrays of a replay, one after the other, little-endian, each starting 4-byte
/// aligned.
#[derive(Default)]
pub(super) struct Blob {
    bytes: Vec<u8>,
}

impl Blob {
    /// Appends `values`; returns where they are, as the player reads it: the offset in
    /// bytes from the start of the arrays and the count.
    pub(super) fn f32s(&mut self, values: &[f32]) -> Value {
        let offset = self.bytes.len();
        self.bytes.extend(values.iter().flat_map(|v| v.to_le_bytes()));
        json!({ "type": "f32", "offset": offset, "count": values.len() })
    }

    /// As [`f32s`](Self::f32s), for indices.
    pub(super) fn u32s(&mut self, values: &[u32]) -> Value {
        let offset = self.bytes.len();
        self.bytes.extend(values.iter().flat_map(|v| v.to_le_bytes()));
        json!({ "type": "u32", "offset": offset, "count": values.len() })
    }

    /// As [`f32s`](Self::f32s), for small indices (padded to the next 4 bytes).
    pub(super) fn u16s(&mut self, values: &[u16]) -> Value {
        let offset = self.bytes.len();
        self.bytes.extend(values.iter().flat_map(|v| v.to_le_bytes()));
        self.pad();
        json!({ "type": "u16", "offset": offset, "count": values.len() })
    }

    /// As [`f32s`](Self::f32s), for bytes (padded to the next 4 bytes): unit normals
    /// as WebGL's normalized `BYTE`s, say.
    pub(super) fn i8s(&mut self, values: &[i8]) -> Value {
        let offset = self.bytes.len();
        self.bytes.extend(values.iter().flat_map(|v| v.to_le_bytes()));
        self.pad();
        json!({ "type": "i8", "offset": offset, "count": values.len() })
    }

    /// Zeros up to the next multiple of 4 bytes, where the next array starts.
    fn pad(&mut self) {
        self.bytes.resize(self.bytes.len().next_multiple_of(4), 0);
    }
}

/// The header and the arrays as one zlib (`deflate` to the browser's
/// `DecompressionStream`) block in base64: the header's length in bytes (`u32`), the
/// header (JSON, padded with spaces to a multiple of 4 bytes), the arrays.
pub(super) fn pack(header: &Value, blob: &Blob) -> String {
    let mut json = header.to_string().into_bytes();
    json.resize(json.len().next_multiple_of(4), b' ');
    let mut raw = Vec::with_capacity(4 + json.len() + blob.bytes.len());
    raw.extend((json.len() as u32).to_le_bytes());
    raw.extend(&json);
    raw.extend(&blob.bytes);
    let mut encoder = ZlibEncoder::new(Vec::new(), Compression::best());
    // Writing into a Vec cannot fail.
    let _ = encoder.write_all(&raw);
    base64(&encoder.finish().unwrap_or_default())
}

/// Standard base64, padded.
pub(super) fn base64(bytes: &[u8]) -> String {
    const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let b = [chunk[0], *chunk.get(1).unwrap_or(&0), *chunk.get(2).unwrap_or(&0)];
        let n = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for (i, shift) in [18, 12, 6, 0].into_iter().enumerate() {
            if i <= chunk.len() {
                out.push(ALPHABET[(n >> shift) as usize & 63] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

/// `text` safe inside HTML.
pub(super) fn html_escape(text: &str) -> String {
    text.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;")
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;

    #[test]
    fn base64_matches_the_standard_alphabet_and_padding() {
        assert_eq!(base64(b""), "");
        assert_eq!(base64(b"f"), "Zg==");
        assert_eq!(base64(b"fo"), "Zm8=");
        assert_eq!(base64(b"foo"), "Zm9v");
        assert_eq!(base64(b"foobar"), "Zm9vYmFy");
        assert_eq!(base64(&[0xfb, 0xff]), "+/8=");
    }

    /// A packed block back: its header and its arrays.
    pub(crate) fn unpack(packed: &str) -> (Value, Vec<u8>) {
        use std::io::Read;
        // Back from base64 by the standard alphabet.
        let alphabet = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
        let sextets: Vec<u32> = packed
            .bytes()
            .filter(|c| *c != b'=')
            .map(|c| alphabet.iter().position(|a| *a == c).unwrap() as u32)
            .collect();
        let mut deflated = Vec::new();
        for group in sextets.chunks(4) {
            let n = group.iter().enumerate().fold(0u32, |n, (i, s)| n | (s << (18 - 6 * i)));
            deflated.extend(&n.to_be_bytes()[1..group.len()]);
        }
        let mut raw = Vec::new();
        flate2::read::ZlibDecoder::new(&deflated[..]).read_to_end(&mut raw).unwrap();
        let length = u32::from_le_bytes(raw[..4].try_into().unwrap()) as usize;
        assert_eq!(length % 4, 0);
        let header: Value = serde_json::from_slice(&raw[4..4 + length]).unwrap();
        (header, raw[4 + length..].to_vec())
    }

    #[test]
    fn a_packed_block_inflates_to_the_header_and_the_arrays() {
        let mut blob = Blob::default();
        let at = blob.f32s(&[1.5, -2.0]);
        let (header, arrays) = unpack(&pack(&json!({ "a": at }), &blob));
        assert_eq!(header["a"]["offset"], 0);
        assert_eq!(header["a"]["count"], 2);
        assert_eq!(f32::from_le_bytes(arrays[4..8].try_into().unwrap()), -2.0);
    }

    #[test]
    fn short_arrays_are_padded_so_that_the_next_starts_4_byte_aligned() {
        let mut blob = Blob::default();
        let (bytes, small, after) = (blob.i8s(&[-127, 0, 127]), blob.u16s(&[1, 2, 65535]), blob.f32s(&[0.5]));
        assert_eq!([&bytes["offset"], &small["offset"], &after["offset"]], [0, 4, 12]);
        assert_eq!([&bytes["type"], &small["type"]], ["i8", "u16"]);
        assert_eq!(blob.bytes, [0x81, 0, 0x7f, 0, 1, 0, 2, 0, 0xff, 0xff, 0, 0, 0, 0, 0, 0x3f]);
    }
}
