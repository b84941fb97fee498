//! The videos' H.264 encoder: Cisco's OpenH264, compiled from its bundled source by
//! the `openh264` crate (feature `video`, on by default). Without the feature,
//! starting an encoder is [`ViewerError::NotBuilt`] and nothing else changes.

use crate::error::{Result, ViewerError};

/// An H.264 encoder (Baseline profile, no rate control) for frames of one size.
#[cfg(feature = "video")]
pub(crate) struct H264 {
    encoder: openh264::encoder::Encoder,
    size: (usize, usize),
}

/// No encoder in this build: [`H264::new`] says so, and no value exists.
#[cfg(not(feature = "video"))]
pub(crate) enum H264 {}

#[cfg(feature = "video")]
impl H264 {
    /// An encoder of `width × height` frames at `fps` frames a second.
    pub(crate) fn new(width: u32, height: u32, fps: f64) -> Result<Self> {
        use openh264::encoder::{
            Encoder, EncoderConfig, FrameRate, IntraFramePeriod, Profile, QpRange, RateControlMode, UsageType,
            VuiConfig,
        };
        let config = EncoderConfig::new()
            .profile(Profile::Baseline)
            .usage_type(UsageType::CameraVideoRealTime)
            // No rate control: the quantiser range holds the quality (about 37 dB
            // PSNR on the thesis scenes), whatever the size of the file.
            .rate_control_mode(RateControlMode::Off)
            .qp(QpRange::new(10, 30))
            .max_frame_rate(FrameRate::from_hz(fps as f32))
            .skip_frames(false)
            .num_threads(1)
            // A key frame every two seconds, to seek.
            .intra_frame_period(IntraFramePeriod::from_num_frames((2.0 * fps).ceil().max(1.0) as u32))
            .vui(VuiConfig::bt601());
        let encoder = Encoder::with_api_config(openh264::OpenH264API::from_source(), config)
            .map_err(|e| ViewerError::Encoder(format!("could not start the H.264 encoder: {e}")))?;
        Ok(H264 { encoder, size: (width as usize, height as usize) })
    }

    /// Encodes frame number `index` (from 1, for the error message), given as planar
    /// YUV 4:2:0 in `yuv`; returns the encoded bytes and `yuv`'s storage for the next
    /// frame.
    pub(crate) fn encode(&mut self, yuv: Vec<u8>, index: u64) -> Result<(Vec<u8>, Vec<u8>)> {
        use openh264::formats::{YUVBuffer, YUVSource};
        let buffer = YUVBuffer::from_vec(yuv, self.size.0, self.size.1);
        let encoded = self
            .encoder
            .encode(&buffer)
            .map_err(|e| ViewerError::Encoder(format!("H.264 encoding failed at frame {index}: {e}")))?;
        let bytes = encoded.to_vec();
        let mut storage = Vec::with_capacity(buffer.y().len() + buffer.u().len() + buffer.v().len());
        storage.extend_from_slice(buffer.y());
        storage.extend_from_slice(buffer.u());
        storage.extend_from_slice(buffer.v());
        Ok((bytes, storage))
    }
}

#[cfg(not(feature = "video"))]
impl H264 {
    /// Always [`ViewerError::NotBuilt`]: this build has no encoder.
    pub(crate) fn new(_width: u32, _height: u32, _fps: f64) -> Result<Self> {
        Err(ViewerError::NotBuilt { feature: "video", what: "an MP4 video" })
    }

    /// Never called: no encoder exists in this build.
    pub(crate) fn encode(&mut self, _yuv: Vec<u8>, _index: u64) -> Result<(Vec<u8>, Vec<u8>)> {
        match *self {}
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[cfg(not(feature = "video"))]
    #[test]
    fn a_video_in_a_build_without_the_encoder_is_not_built_and_leaves_no_file() {
        let dir = std::env::temp_dir().join(format!("ars-no-video-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let error = crate::VideoWriter::create(dir.join("v.mp4"), 64, 48, 25.0).err().unwrap();
        assert!(matches!(error, ViewerError::NotBuilt { feature: "video", .. }), "{error:?}");
        assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 0, "partial files left");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[cfg(feature = "video")]
    #[test]
    fn a_grey_frame_encodes_to_some_bytes_and_gives_its_storage_back() {
        let mut encoder = H264::new(64, 48, 25.0).unwrap();
        let (bytes, storage) = encoder.encode(vec![128; 64 * 48 * 3 / 2], 1).unwrap();
        assert!(!bytes.is_empty());
        assert_eq!(storage.len(), 64 * 48 * 3 / 2);
    }
}
