//! A small MP4 (ISO base media file) writer for one H.264 video track: what
//! [`VideoWriter`](crate::VideoWriter) puts its frames in.
//!
//! The frames' bytes go to a file of their own while recording; at the end the video
//! file is written in one go as `ftyp`, `moov` (the sample tables) and `mdat` (the
//! frames, copied), so that the index comes first ("fast start": a browser plays the
//! video while it downloads). One sample per frame, one chunk per sample, no B-frames
//! (decoding order is display order), the parameter sets (SPS, PPS) in the `avcC` box.

use std::io::{self, Read, Write};

/// The media timescale: ticks per second (90 kHz, as MPEG does).
const TIMESCALE: u64 = 90_000;

/// The sample tables of a video being written.
pub(crate) struct Mp4Track {
    width: u16,
    height: u16,
    fps: f64,
    /// Bytes of each sample (frame), in order.
    sizes: Vec<u32>,
    /// Numbers (from 1) of the samples that are key frames.
    keyframes: Vec<u32>,
    /// The first sequence and picture parameter sets met.
    sps: Option<Vec<u8>>,
    pps: Option<Vec<u8>>,
}

fn invalid(message: impl Into<String>) -> io::Error {
    io::Error::new(io::ErrorKind::InvalidData, message.into())
}

/// The NAL units of an Annex B byte stream (start-code separated).
fn nal_units(annex_b: &[u8]) -> impl Iterator<Item = &[u8]> {
    let mut starts = Vec::new();
    let mut i = 0;
    while i + 3 <= annex_b.len() {
        if annex_b[i] == 0 && annex_b[i + 1] == 0 && annex_b[i + 2] == 1 {
            starts.push(i + 3);
            i += 3;
        } else {
            i += 1;
        }
    }
    let ends: Vec<usize> = starts.iter().skip(1).map(|&s| s - 3).chain([annex_b.len()]).collect();
    starts.into_iter().zip(ends).map(move |(s, e)| {
        // A four-byte start code leaves a zero byte before the next one.
        let mut end = e;
        while end > s && annex_b[end - 1] == 0 {
            end -= 1;
        }
        &annex_b[s..end]
    })
}

impl Mp4Track {
    /// A track of `width × height` pixels at `fps` frames a second.
    pub(crate) fn new(width: u32, height: u32, fps: f64) -> io::Result<Self> {
        let (Ok(width), Ok(height)) = (u16::try_from(width), u16::try_from(height)) else {
            return Err(invalid(format!("a video of {width}×{height} pixels is too large for MP4")));
        };
        Ok(Mp4Track { width, height, fps, sizes: Vec::new(), keyframes: Vec::new(), sps: None, pps: None })
    }

    /// Frames added so far.
    pub(crate) fn frames(&self) -> usize {
        self.sizes.len()
    }

    /// Writes one encoded frame (an H.264 access unit in Annex B form) to `payload` as
    /// MP4 wants it (each NAL unit after its length), keeping the parameter sets apart.
    pub(crate) fn add_frame(&mut self, annex_b: &[u8], payload: &mut impl Write) -> io::Result<()> {
        let mut size = 0u32;
        let mut key = false;
        for nal in nal_units(annex_b).filter(|n| !n.is_empty()) {
            match nal[0] & 0x1f {
                7 => {
                    self.sps.get_or_insert_with(|| nal.to_vec());
                }
                8 => {
                    self.pps.get_or_insert_with(|| nal.to_vec());
                }
                9 => {} // access unit delimiter: not in MP4 samples
                kind => {
                    key |= kind == 5;
                    let length = u32::try_from(nal.len()).map_err(|_| invalid("a NAL unit over 4 GB"))?;
                    payload.write_all(&length.to_be_bytes())?;
                    payload.write_all(nal)?;
                    size = size.checked_add(4 + length).ok_or_else(|| invalid("a frame over 4 GB"))?;
                }
            }
        }
        if size == 0 {
            return Err(invalid(format!("the encoder gave no picture for frame {}", self.sizes.len() + 1)));
        }
        self.sizes.push(size);
        if key {
            self.keyframes.push(self.sizes.len() as u32);
        }
        Ok(())
    }

    /// The tick at which frame `k` starts: frame `k` is shown from `k / fps` seconds.
    fn tick(&self, k: usize) -> u64 {
        (k as f64 * TIMESCALE as f64 / self.fps).round() as u64
    }

    /// Writes the whole file to `out`: `ftyp`, `moov`, then `mdat` with the `payload`
    /// bytes written by [`add_frame`](Self::add_frame).
    pub(crate) fn write_file(&self, out: &mut impl Write, payload: &mut impl Read) -> io::Result<()> {
        let (Some(sps), Some(pps)) = (&self.sps, &self.pps) else {
            return Err(invalid("no frames, or the encoder gave no parameter sets"));
        };
        if self.keyframes.first() != Some(&1) {
            return Err(invalid("the first frame is not a key frame"));
        }
        let ftyp = boxed(b"ftyp", |b| {
            b.extend_from_slice(b"isom");
            b.extend_from_slice(&0x200u32.to_be_bytes());
            for brand in [b"isom", b"iso2", b"avc1", b"mp41"] {
                b.extend_from_slice(brand);
            }
        });
        let data: u64 = self.sizes.iter().map(|&s| u64::from(s)).sum();
        // The frames' offsets depend on the size of `moov`, which depends on whether
        // they need 64 bits: measure it once with the largest offsets.
        let long = data + (1 << 20) > u64::from(u32::MAX);
        let moov_len = self.moov(sps, pps, 0, long).len() as u64;
        let mdat_header = 16u64; // size 1, "mdat", then the 64-bit size
        let first = ftyp.len() as u64 + moov_len + mdat_header;
        out.write_all(&ftyp)?;
        out.write_all(&self.moov(sps, pps, first, long))?;
        out.write_all(&1u32.to_be_bytes())?;
        out.write_all(b"mdat")?;
        out.write_all(&(mdat_header + data).to_be_bytes())?;
        let copied = io::copy(payload, out)?;
        if copied != data {
            return Err(invalid(format!("the frames' file holds {copied} bytes, {data} were written")));
        }
        Ok(())
    }

    /// The `moov` box, the frames' data starting at byte `first` of the file.
    fn moov(&self, sps: &[u8], pps: &[u8], first: u64, long: bool) -> Vec<u8> {
        let count = self.sizes.len();
        let duration = self.tick(count);
        let (w, h) = (u32::from(self.width), u32::from(self.height));
        let mvhd = full_box(b"mvhd", duration, |b| {
            times(b, duration);
            b.extend_from_slice(&0x0001_0000u32.to_be_bytes()); // rate 1.0
            b.extend_from_slice(&0x0100u16.to_be_bytes()); // volume 1.0
            b.extend_from_slice(&[0; 10]);
            matrix(b);
            b.extend_from_slice(&[0; 24]);
            b.extend_from_slice(&2u32.to_be_bytes()); // next track id
        });
        let tkhd = full_box_flags(b"tkhd", duration, 3, |b| {
            let version1 = duration > u64::from(u32::MAX);
            if version1 {
                b.extend_from_slice(&[0; 16]);
            } else {
                b.extend_from_slice(&[0; 8]);
            }
            b.extend_from_slice(&1u32.to_be_bytes()); // track id
            b.extend_from_slice(&[0; 4]);
            if version1 {
                b.extend_from_slice(&duration.to_be_bytes());
            } else {
                b.extend_from_slice(&(duration as u32).to_be_bytes());
            }
            b.extend_from_slice(&[0; 8]);
            b.extend_from_slice(&[0; 8]); // layer, alternate group, volume, reserved
            matrix(b);
            b.extend_from_slice(&(w << 16).to_be_bytes());
            b.extend_from_slice(&(h << 16).to_be_bytes());
        });
        let mdhd = full_box(b"mdhd", duration, |b| {
            times(b, duration);
            b.extend_from_slice(&0x55c4u16.to_be_bytes()); // language "und"
            b.extend_from_slice(&[0; 2]);
        });
        let hdlr = full_box(b"hdlr", 0, |b| {
            b.extend_from_slice(&[0; 4]);
            b.extend_from_slice(b"vide");
            b.extend_from_slice(&[0; 12]);
            b.extend_from_slice(b"ARS video\0");
        });
        let vmhd = full_box_flags(b"vmhd", 0, 1, |b| b.extend_from_slice(&[0; 8]));
        let dinf = boxed(b"dinf", |b| {
            b.extend(full_box(b"dref", 0, |b| {
                b.extend_from_slice(&1u32.to_be_bytes());
                b.extend(full_box_flags(b"url ", 0, 1, |_| {}));
            }))
        });
        let stbl = self.sample_table(self.sample_description(sps, pps), first, long);
        let minf = boxed(b"minf", |b| {
            for part in [vmhd, dinf, stbl] {
                b.extend(part);
            }
        });
        let mdia = boxed(b"mdia", |b| {
            for part in [mdhd, hdlr, minf] {
                b.extend(part);
            }
        });
        let trak = boxed(b"trak", |b| {
            b.extend(tkhd);
            b.extend(mdia);
        });
        boxed(b"moov", |b| {
            b.extend(mvhd);
            b.extend(trak);
        })
    }

    /// The `stsd` box: the one H.264 sample entry, with the stream's SPS and PPS.
    fn sample_description(&self, sps: &[u8], pps: &[u8]) -> Vec<u8> {
        let avc1 = boxed(b"avc1", |b| {
            b.extend_from_slice(&[0; 6]);
            b.extend_from_slice(&1u16.to_be_bytes()); // data reference index
            b.extend_from_slice(&[0; 16]);
            b.extend_from_slice(&self.width.to_be_bytes());
            b.extend_from_slice(&self.height.to_be_bytes());
            b.extend_from_slice(&0x0048_0000u32.to_be_bytes()); // 72 dpi
            b.extend_from_slice(&0x0048_0000u32.to_be_bytes());
            b.extend_from_slice(&[0; 4]);
            b.extend_from_slice(&1u16.to_be_bytes()); // one frame a sample
            let mut name = [0u8; 32];
            let label = b"ARS H.264";
            name[0] = label.len() as u8;
            name[1..=label.len()].copy_from_slice(label);
            b.extend_from_slice(&name);
            b.extend_from_slice(&0x0018u16.to_be_bytes()); // colour, no alpha
            b.extend_from_slice(&(-1i16).to_be_bytes());
            b.extend(boxed(b"avcC", |b| {
                b.push(1);
                b.extend_from_slice(&sps[1..4.min(sps.len())]);
                b.resize(b.len() + 4usize.saturating_sub(sps.len()), 0);
                b.push(0xff); // four-byte NAL lengths
                b.push(0xe1); // one SPS
                b.extend_from_slice(&(sps.len() as u16).to_be_bytes());
                b.extend_from_slice(sps);
                b.push(1); // one PPS
                b.extend_from_slice(&(pps.len() as u16).to_be_bytes());
                b.extend_from_slice(pps);
            }));
        });
        full_box(b"stsd", 0, |b| {
            b.extend_from_slice(&1u32.to_be_bytes());
            b.extend(avc1);
        })
    }

    /// The `stbl` box: the sample description `stsd`, the frames' durations, key
    /// frames, sizes and offsets (from byte `first` of the file; 64-bit when `long`).
    fn sample_table(&self, stsd: Vec<u8>, first: u64, long: bool) -> Vec<u8> {
        let count = self.sizes.len();
        // Frame k lasts from tick(k) to tick(k + 1): runs of equal lengths.
        let mut runs: Vec<(u32, u32)> = Vec::new();
        for k in 0..count {
            let delta = (self.tick(k + 1) - self.tick(k)) as u32;
            match runs.last_mut() {
                Some((n, d)) if *d == delta => *n += 1,
                _ => runs.push((1, delta)),
            }
        }
        let stts = full_box(b"stts", 0, |b| {
            b.extend_from_slice(&(runs.len() as u32).to_be_bytes());
            for (n, d) in &runs {
                b.extend_from_slice(&n.to_be_bytes());
                b.extend_from_slice(&d.to_be_bytes());
            }
        });
        let stss = full_box(b"stss", 0, |b| {
            b.extend_from_slice(&(self.keyframes.len() as u32).to_be_bytes());
            for k in &self.keyframes {
                b.extend_from_slice(&k.to_be_bytes());
            }
        });
        let stsc = full_box(b"stsc", 0, |b| {
            b.extend_from_slice(&1u32.to_be_bytes());
            for v in [1u32, 1, 1] {
                b.extend_from_slice(&v.to_be_bytes()); // every chunk: one sample
            }
        });
        let stsz = full_box(b"stsz", 0, |b| {
            b.extend_from_slice(&0u32.to_be_bytes());
            b.extend_from_slice(&(count as u32).to_be_bytes());
            for s in &self.sizes {
                b.extend_from_slice(&s.to_be_bytes());
            }
        });
        let offsets = full_box(if long { b"co64" } else { b"stco" }, 0, |b| {
            b.extend_from_slice(&(count as u32).to_be_bytes());
            let mut at = first;
            for s in &self.sizes {
                if long {
                    b.extend_from_slice(&at.to_be_bytes());
                } else {
                    b.extend_from_slice(&(at as u32).to_be_bytes());
                }
                at += u64::from(*s);
            }
        });
        boxed(b"stbl", |b| {
            for part in [stsd, stts, stss, stsc, stsz, offsets] {
                b.extend(part);
            }
        })
    }
}

/// A box: its size, its kind, then what `body` writes.
fn boxed(kind: &[u8; 4], body: impl FnOnce(&mut Vec<u8>)) -> Vec<u8> {
    let mut b = vec![0, 0, 0, 0];
    b.extend_from_slice(kind);
    body(&mut b);
    let size = b.len() as u32;
    b[..4].copy_from_slice(&size.to_be_bytes());
    b
}

/// A full box with no flags, of version 1 if `duration` needs 64 bits.
fn full_box(kind: &[u8; 4], duration: u64, body: impl FnOnce(&mut Vec<u8>)) -> Vec<u8> {
    full_box_flags(kind, duration, 0, body)
}

/// A full box with `flags`, of version 1 if `duration` needs 64 bits.
fn full_box_flags(kind: &[u8; 4], duration: u64, flags: u32, body: impl FnOnce(&mut Vec<u8>)) -> Vec<u8> {
    boxed(kind, |b| {
        let version = u32::from(duration > u64::from(u32::MAX));
        b.extend_from_slice(&((version << 24) | flags).to_be_bytes());
        body(b);
    })
}

/// Creation and modification times (zero), the timescale and the duration, 32 or 64
/// bits as the box's version says.
fn times(b: &mut Vec<u8>, duration: u64) {
    if duration > u64::from(u32::MAX) {
        b.extend_from_slice(&[0; 16]);
        b.extend_from_slice(&(TIMESCALE as u32).to_be_bytes());
        b.extend_from_slice(&duration.to_be_bytes());
    } else {
        b.extend_from_slice(&[0; 8]);
        b.extend_from_slice(&(TIMESCALE as u32).to_be_bytes());
        b.extend_from_slice(&(duration as u32).to_be_bytes());
    }
}

/// The identity transformation matrix.
fn matrix(b: &mut Vec<u8>) {
    for v in [0x0001_0000u32, 0, 0, 0, 0x0001_0000, 0, 0, 0, 0x4000_0000] {
        b.extend_from_slice(&v.to_be_bytes());
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An access unit: SPS, PPS and an IDR slice (or a P slice), four-byte start codes.
    fn access_unit(key: bool) -> Vec<u8> {
        let mut v = Vec::new();
        if key {
            v.extend_from_slice(&[0, 0, 0, 1, 0x67, 66, 0xc0, 30, 0xaa]);
            v.extend_from_slice(&[0, 0, 0, 1, 0x68, 0xce, 0x3c, 0x80]);
            v.extend_from_slice(&[0, 0, 0, 1, 0x65, 1, 2, 3]);
        } else {
            v.extend_from_slice(&[0, 0, 1, 0x41, 9, 8]);
        }
        v
    }

    #[test]
    fn nal_units_are_split_at_three_and_four_byte_start_codes() {
        let au = access_unit(true);
        let units: Vec<&[u8]> = nal_units(&au).collect();
        assert_eq!(units, [&[0x67, 66, 0xc0, 30, 0xaa][..], &[0x68, 0xce, 0x3c, 0x80], &[0x65, 1, 2, 3]]);
    }

    #[test]
    fn frames_are_length_prefixed_and_the_file_starts_with_its_index() {
        let mut track = Mp4Track::new(64, 48, 30.0).unwrap();
        let mut payload = Vec::new();
        track.add_frame(&access_unit(true), &mut payload).unwrap();
        track.add_frame(&access_unit(false), &mut payload).unwrap();
        assert_eq!(payload, [0, 0, 0, 4, 0x65, 1, 2, 3, 0, 0, 0, 3, 0x41, 9, 8]);
        assert_eq!(track.keyframes, [1]);
        let mut file = Vec::new();
        track.write_file(&mut file, &mut payload.as_slice()).unwrap();
        assert_eq!(&file[4..8], b"ftyp");
        let ftyp = u32::from_be_bytes(file[0..4].try_into().unwrap()) as usize;
        let moov = u32::from_be_bytes(file[ftyp..ftyp + 4].try_into().unwrap()) as usize;
        assert_eq!(&file[ftyp + 4..ftyp + 8], b"moov");
        assert_eq!(&file[ftyp + moov + 4..ftyp + moov + 8], b"mdat");
        assert!(file.ends_with(&payload));
        // 2 frames at 30 frames/s: 3000 ticks each.
        assert_eq!(track.tick(2), 6000);
    }

    #[test]
    fn a_video_without_frames_is_refused() {
        let track = Mp4Track::new(64, 48, 30.0).unwrap();
        assert!(track.write_file(&mut Vec::new(), &mut [].as_slice()).is_err());
    }
}
