//! MCAP recordings: the messages of a [`Publisher`] written as `ros2 bag` writes them
//! (profile `ros2`, `ros2msg` schemas, `cdr` messages, each channel's
//! `offered_qos_profiles`), stamped with simulated time (log time = publish time = the
//! message's stamp, ns). Chunks are not compressed (no zstd or lz4: both compile C).
//! Foxglove, `ros2 bag` (with the MCAP storage plugin) and Rerun open the files.

use std::collections::BTreeMap;
use std::fs::File;
use std::io::BufWriter;
use std::path::{Path, PathBuf};

use ars_core::{Program, ProgramRunner, Simulation};

use crate::error::{RosError, RosResult};
use crate::msg;
use crate::publish::{Publisher, RosOptions};

/// What a finished recording holds.
#[derive(Clone, Debug, PartialEq)]
pub struct McapSummary {
    /// The file.
    pub path: PathBuf,
    /// Messages written, per topic, in the order of the publisher's topics.
    pub messages: Vec<(String, u64)>,
    /// Simulated time of the last message, s.
    pub end_time: f64,
}

impl McapSummary {
    /// Messages written on all topics.
    pub fn total(&self) -> u64 {
        self.messages.iter().map(|(_, n)| n).sum()
    }
}

/// Writes what a [`Publisher`] publishes into an MCAP file: call
/// [`record`](Self::record) after every step (or when
/// [`Publisher::state_due`] says so, and at the end of every frame), then
/// [`finish`](Self::finish).
pub struct McapRecorder {
    writer: mcap::Writer<BufWriter<File>>,
    publisher: Publisher,
    /// Each topic's channel id and messages written.
    channels: Vec<(u16, u64)>,
    path: PathBuf,
    end_time: f64,
}

impl std::fmt::Debug for McapRecorder {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("McapRecorder").field("path", &self.path).field("channels", &self.channels).finish()
    }
}

impl McapRecorder {
    /// Creates the file at `path` and a [`Publisher`] of `sim` (which gets its joint
    /// states sensor). A folder that does not exist is an [`ars_core::Error::Io`].
    pub fn create(path: impl AsRef<Path>, sim: &mut Simulation, options: &RosOptions) -> RosResult<McapRecorder> {
        let path = path.as_ref().to_path_buf();
        options.check()?;
        let file = File::create(&path).map_err(|e| ars_core::Error::io("create the MCAP file", &path, &e))?;
        let mut writer = mcap::WriteOptions::new()
            .compression(None)
            .profile("ros2")
            .library(concat!("ars ", env!("CARGO_PKG_VERSION")))
            .create(BufWriter::new(file))
            .map_err(|e| mcap_error(&path, e))?;
        let publisher = Publisher::attach(sim, options)?;
        let mut schemas: BTreeMap<&str, u16> = BTreeMap::new();
        let mut channels = Vec::new();
        for topic in publisher.topics() {
            let schema = match schemas.get(topic.type_name) {
                Some(id) => *id,
                None => {
                    let text = msg::schema(topic.type_name).expect("every topic's type has a schema");
                    let id = writer
                        .add_schema(topic.type_name, "ros2msg", text.as_bytes())
                        .map_err(|e| mcap_error(&path, e))?;
                    schemas.insert(topic.type_name, id);
                    id
                }
            };
            let metadata = BTreeMap::from([("offered_qos_profiles".to_string(), topic.qos.rosbag_yaml())]);
            let channel =
                writer.add_channel(schema, &topic.name, "cdr", &metadata).map_err(|e| mcap_error(&path, e))?;
            channels.push((channel, 0));
        }
        Ok(McapRecorder { writer, publisher, channels, path, end_time: 0.0 })
    }

    /// The publisher whose messages are written.
    pub fn publisher(&self) -> &Publisher {
        &self.publisher
    }

    /// Writes the messages due now (see [`Publisher::poll`]).
    pub fn record(&mut self, sim: &Simulation) -> RosResult<()> {
        for outgoing in self.publisher.poll(sim)? {
            let (channel, written) = &mut self.channels[outgoing.topic];
            let header = mcap::records::MessageHeader {
                channel_id: *channel,
                sequence: *written as u32,
                log_time: outgoing.stamp,
                publish_time: outgoing.stamp,
            };
            let data = outgoing.message.encode()?;
            self.writer.write_to_known_channel(&header, &data).map_err(|e| mcap_error(&self.path, e))?;
            *written += 1;
            self.end_time = self.end_time.max(outgoing.stamp as f64 * 1e-9);
        }
        Ok(())
    }

    /// Writes the file's index and summary and closes it.
    pub fn finish(mut self) -> RosResult<McapSummary> {
        self.writer.finish().map_err(|e| mcap_error(&self.path, e))?;
        let messages =
            self.publisher.topics().iter().zip(&self.channels).map(|(t, (_, n))| (t.name.clone(), *n)).collect();
        Ok(McapSummary { path: self.path, messages, end_time: self.end_time })
    }
}

fn mcap_error(path: &Path, e: mcap::McapError) -> RosError {
    RosError::Mcap { file: path.display().to_string(), detail: e.to_string() }
}

/// What steps a simulation in frames, showing it after each step: a bare
/// [`Simulation`] (its own hooks) or a [`ProgramRunner`] (its program's hooks too).
pub trait FrameStepper {
    /// The simulation.
    fn simulation(&self) -> &Simulation;
    /// The simulation, mutably (the recorder adds its joint states sensor).
    fn simulation_mut(&mut self) -> &mut Simulation;
    /// One step.
    fn step(&mut self) -> ars_core::Result<()>;
    /// One frame, showing the simulation to `after_step` after each step.
    fn step_frame_observed(
        &mut self,
        after_step: &mut dyn FnMut(&Simulation) -> ars_core::Result<()>,
    ) -> ars_core::Result<()>;
}

impl FrameStepper for Simulation {
    fn simulation(&self) -> &Simulation {
        self
    }
    fn simulation_mut(&mut self) -> &mut Simulation {
        self
    }
    fn step(&mut self) -> ars_core::Result<()> {
        Simulation::step(self)
    }
    fn step_frame_observed(
        &mut self,
        after_step: &mut dyn FnMut(&Simulation) -> ars_core::Result<()>,
    ) -> ars_core::Result<()> {
        Simulation::step_frame_observed(self, after_step)
    }
}

impl<P: Program> FrameStepper for ProgramRunner<'_, P> {
    fn simulation(&self) -> &Simulation {
        ProgramRunner::simulation(self)
    }
    fn simulation_mut(&mut self) -> &mut Simulation {
        ProgramRunner::simulation_mut(self)
    }
    fn step(&mut self) -> ars_core::Result<()> {
        ProgramRunner::step(self)
    }
    fn step_frame_observed(
        &mut self,
        after_step: &mut dyn FnMut(&Simulation) -> ars_core::Result<()>,
    ) -> ars_core::Result<()> {
        ProgramRunner::step_frame_observed(self, after_step)
    }
}

/// Runs `sim` for `duration` simulated seconds (whole steps, in frames) and records it
/// into an MCAP file at `path`, asking `stop` before each frame. Stopped, the file is
/// finished with what was recorded until then and the error is
/// [`ars_core::Error::Interrupted`]; on any other error the file is left unfinished.
/// `sim` is a [`Simulation`] or a [`ProgramRunner`] ([`FrameStepper`]).
pub fn record_mcap(
    sim: &mut impl FrameStepper,
    path: impl AsRef<Path>,
    duration: f64,
    options: &RosOptions,
    mut stop: impl FnMut() -> bool,
) -> RosResult<McapSummary> {
    let mut steps = sim.simulation().scene().steps_in(duration)?;
    let mut recorder = McapRecorder::create(path, sim.simulation_mut(), options)?;
    recorder.record(sim.simulation())?;
    let per_frame = u64::from(sim.simulation().scene().steps_per_frame());
    while steps > 0 {
        if stop() {
            recorder.finish()?;
            let scene = sim.simulation().scene();
            return Err(ars_core::Error::Interrupted { time: scene.time(), steps: scene.step_count() }.into());
        }
        let mut failed = None;
        if steps >= per_frame {
            sim.step_frame_observed(&mut |sim| {
                if failed.is_none() && recorder.publisher.state_due(sim) {
                    failed = recorder.record(sim).err();
                }
                Ok(())
            })?;
            if failed.is_none() {
                failed = recorder.record(sim.simulation()).err();
            }
            steps -= per_frame;
        } else {
            sim.step()?;
            failed = recorder.record(sim.simulation()).err();
            steps -= 1;
        }
        if let Some(e) = failed {
            return Err(e);
        }
    }
    recorder.finish()
}
