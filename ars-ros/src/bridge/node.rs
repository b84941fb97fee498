//! The bridge on the network: a ROS 2 node (RustDDS, through `ros2-client`) with a
//! writer for each of the [`Publisher`](crate::Publisher)'s topics (fed by a publishing
//! thread, the [`Outbox`]), the subscriptions and services of [`super`]'s table, and the
//! loop that feeds a [`BridgeCore`] what arrives and hands over what it makes.

use std::sync::mpsc;
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use log::warn;
use ros2_client::qos::{Durability, History, Reliability, WhenFull};
use ros2_client::{
    Context, ContextOptions, Message, MessageTypeName, Name, Node, NodeName, NodeOptions, Publisher, QosProfile,
    Server, Subscription,
};

use super::commands::CommandKind;
use super::core::BridgeCore;
use super::sim_interfaces::{
    GetSimulationStateRequest, GetSimulationStateResponse, GetSimulatorFeaturesRequest, GetSimulatorFeaturesResponse,
    ResetSimulationRequest, ResultResponse, SetSimulationStateRequest, StepSimulationRequest, service_type,
};
use super::wire::{Float64MultiArray, JointState, Twist, type_names};
use super::{BridgeError, BridgeOptions};
use crate::mcap::FrameStepper;
use crate::topics::{self, Outgoing, Topic};

/// How many batches of messages may wait for the publishing thread before the
/// simulation waits for it.
const OUTBOX_DEPTH: usize = 256;

/// How many messages of one topic are taken per turn of the loop, so that a flood
/// cannot hold it.
const TAKE_PER_TURN: usize = 64;

/// The node's endpoints.
pub(super) struct BridgeNode {
    /// Dropped first: its thread ends before the node goes.
    outbox: Outbox,
    cmd_vel: Subscription<Twist>,
    forward: Vec<(CommandKind, Subscription<Float64MultiArray>)>,
    joint_commands: Subscription<JointState>,
    get_features: Server<GetSimulatorFeaturesRequest, GetSimulatorFeaturesResponse>,
    step: Server<StepSimulationRequest, ResultResponse>,
    reset: Server<ResetSimulationRequest, ResultResponse>,
    set_state: Server<SetSimulationStateRequest, ResultResponse>,
    get_state: Server<GetSimulationStateRequest, GetSimulationStateResponse>,
    /// Dropped last (fields drop in order): the endpoints above are removed from it.
    _node: Node,
}

fn qos(reliable: bool, latched: bool, depth: usize) -> QosProfile {
    let reliability =
        if reliable { Reliability::Reliable { when_full: WhenFull::Fail } } else { Reliability::BestEffort };
    let durability = if latched { Durability::TransientLocal } else { Durability::Volatile };
    QosProfile::default().reliability(reliability).durability(durability).history(History::KeepLast { depth })
}

/// A topic's QoS as ros2-client takes it.
fn qos_of(topic: &Topic) -> QosProfile {
    qos(
        topic.qos.reliability == topics::Reliability::Reliable,
        topic.qos.durability == topics::Durability::TransientLocal,
        topic.qos.depth as usize,
    )
}

fn name(namespace: &str, base: &str) -> Result<Name, BridgeError> {
    Name::new(namespace, base).map_err(|e| BridgeError::Setup(format!("the name {namespace}/{base}: {e}")))
}

/// A full topic name (`/camera/depth/image_raw`) as a namespace and a base name.
fn topic_name(full: &str) -> Result<Name, BridgeError> {
    match full.rsplit_once('/') {
        Some(("", base)) => name("/", base),
        Some((namespace, base)) => name(namespace, base),
        None => name("/", full),
    }
}

/// A type name (`sensor_msgs/msg/JointState`) as ros2-client takes it.
fn type_name(full: &str) -> Result<MessageTypeName, BridgeError> {
    match full.split('/').collect::<Vec<_>>()[..] {
        [package, "msg", name] => Ok(MessageTypeName::new(package, name)),
        _ => Err(BridgeError::Setup(format!("the message type {full:?} is not package/msg/Name"))),
    }
}

fn setup<T, E: std::fmt::Debug>(what: &str, made: Result<T, E>) -> Result<T, BridgeError> {
    made.map_err(|e| BridgeError::Setup(format!("{what}: {e:?}")))
}

impl BridgeNode {
    /// The node `options.node_name` on `options.domain_id`, with a writer for each of
    /// `published` and every subscription and service.
    pub(super) fn new(options: &BridgeOptions, published: &[Topic]) -> Result<BridgeNode, BridgeError> {
        let context = Context::with_options(ContextOptions::new().domain_id(options.domain_id))
            .map_err(|e| BridgeError::Network(format!("starting DDS on domain {}: {e:?}", options.domain_id)))?;
        let node_name = NodeName::new("/", &options.node_name)
            .map_err(|e| BridgeError::Setup(format!("the node name {:?}: {e}", options.node_name)))?;
        let mut node = setup("the node", context.new_node(node_name, NodeOptions::new()))?;
        let mut writers = Vec::with_capacity(published.len());
        for topic in published {
            let made = node.create_topic(&topic_name(&topic.name)?, type_name(topic.type_name)?, &qos_of(topic));
            let dds_topic = setup(&topic.name, made)?;
            writers.push((topic.name.clone(), setup(&topic.name, node.create_publisher(&dds_topic, None))?));
        }
        let topic = |n: &str, t: MessageTypeName, q: &QosProfile| setup(n, node.create_topic(&name("/", n)?, t, q));
        // Best effort subscriptions take from reliable and best effort publishers alike.
        let commands = qos(false, false, 10);
        let cmd_vel_topic = topic("cmd_vel", type_names::twist(), &commands)?;
        let joint_commands_topic = topic("joint_commands", type_names::joint_state(), &commands)?;
        let mut forward = Vec::new();
        for kind in CommandKind::ALL {
            let t = setup(
                kind.controller(),
                node.create_topic(
                    &name(&format!("/{}", kind.controller()), "commands")?,
                    type_names::float64_multi_array(),
                    &commands,
                ),
            )?;
            forward.push((kind, setup(kind.controller(), node.create_subscription(&t, None))?));
        }
        let mapping = options.services.mapping();
        let services = format!("/{}", options.node_name);
        let service_qos = qos(true, false, 10);
        macro_rules! server {
            ($base:literal, $type:literal) => {
                setup(
                    $base,
                    node.create_server(
                        mapping,
                        &name(&services, $base)?,
                        &service_type($type),
                        service_qos.clone(),
                        service_qos.clone(),
                    ),
                )?
            };
        }
        Ok(BridgeNode {
            cmd_vel: setup("/cmd_vel", node.create_subscription(&cmd_vel_topic, None))?,
            joint_commands: setup("/joint_commands", node.create_subscription(&joint_commands_topic, None))?,
            forward,
            get_features: server!("get_simulator_features", "GetSimulatorFeatures"),
            step: server!("step_simulation", "StepSimulation"),
            reset: server!("reset_simulation", "ResetSimulation"),
            set_state: server!("set_simulation_state", "SetSimulationState"),
            get_state: server!("get_simulation_state", "GetSimulationState"),
            outbox: Outbox::start(writers)?,
            _node: node,
        })
    }

    /// Hands over what is due since the last call.
    pub(super) fn send_due<S: FrameStepper>(&self, core: &mut BridgeCore<S>) -> Result<(), BridgeError> {
        self.outbox.send(core.poll()?);
        Ok(())
    }

    /// Takes what arrived on the subscriptions and gives it to `core`; what it refuses
    /// is logged.
    pub(super) fn take_commands<S: FrameStepper>(&self, core: &mut BridgeCore<S>) {
        take_each("/cmd_vel", &self.cmd_vel, |m| core.take_twist(m));
        take_each("/joint_commands", &self.joint_commands, |m| core.take_named(&m));
        for (kind, subscription) in &self.forward {
            take_each(kind.controller(), subscription, |m| core.take_forward(*kind, &m));
        }
    }

    /// Answers the service calls that arrived; a `StepSimulation` steps `core`
    /// (publishing as it goes, then the state it ended in) before its answer.
    pub(super) fn serve<S: FrameStepper>(&self, core: &mut BridgeCore<S>) -> Result<(), BridgeError> {
        answer_each("get_simulator_features", &self.get_features, |_| core.features());
        answer_each("get_simulation_state", &self.get_state, |_| core.get_state());
        answer_each("set_simulation_state", &self.set_state, |r| core.set_state(r.state.state));
        let mut failure = None;
        answer_each("reset_simulation", &self.reset, |r| {
            let answer = core.reset(r.scope);
            if let Err(e) = self.send_due(core) {
                failure = Some(e);
            }
            answer
        });
        answer_each("step_simulation", &self.step, |r| {
            if let Err(result) = core.check_step_request(r.steps) {
                return ResultResponse { result };
            }
            // Commands sent before the call count from its first step.
            self.take_commands(core);
            let result = match self.step_call(core, r.steps) {
                Ok(()) => super::sim_interfaces::CallResult::ok(),
                Err(e) => {
                    let answer = super::sim_interfaces::CallResult::failed(
                        super::sim_interfaces::CallResult::OPERATION_FAILED,
                        e.to_string(),
                    );
                    failure = Some(e);
                    answer
                }
            };
            ResultResponse { result }
        });
        failure.map_or(Ok(()), Err)
    }

    /// A `StepSimulation` of `n` steps: then the state it ended in, sent before the
    /// call is answered.
    fn step_call<S: FrameStepper>(&self, core: &mut BridgeCore<S>, n: u64) -> Result<(), BridgeError> {
        for _ in 0..n {
            if ars_core::interrupt::requested() {
                return Err(BridgeError::Interrupted);
            }
            self.step(core)?;
        }
        self.outbox.send(core.poll_with_state_now()?);
        self.outbox.flush();
        Ok(())
    }

    /// One step, handing over the state (and the sensors' samples) when it is due.
    fn step<S: FrameStepper>(&self, core: &mut BridgeCore<S>) -> Result<(), BridgeError> {
        for warning in core.step()? {
            warn!("{warning}");
        }
        if core.state_due() {
            self.send_due(core)?;
        }
        Ok(())
    }
}

/// The publishing thread: it owns the topics' writers and publishes what it is handed,
/// in order, so that DDS's writers do not hold the steps.
struct Outbox {
    sender: Option<mpsc::SyncSender<Outbound>>,
    thread: Option<JoinHandle<()>>,
}

enum Outbound {
    Messages(Vec<Outgoing>),
    /// Answered once everything handed over before it is published.
    Flush(mpsc::SyncSender<()>),
}

impl Outbox {
    /// The thread, with a writer per topic (in the order [`Outgoing::topic`] indexes).
    fn start(writers: Vec<(String, Publisher<topics::Message>)>) -> Result<Outbox, BridgeError> {
        let (sender, receiver) = mpsc::sync_channel::<Outbound>(OUTBOX_DEPTH);
        let thread = std::thread::Builder::new()
            .name("ars-ros publisher".into())
            .spawn(move || {
                for outbound in receiver {
                    match outbound {
                        Outbound::Messages(messages) => {
                            for Outgoing { topic, message, .. } in messages {
                                let (name, writer) = &writers[topic];
                                if let Err(e) = writer.publish(message) {
                                    warn!("{name}: not published: {e:?}");
                                }
                            }
                        }
                        Outbound::Flush(done) => {
                            let _ = done.send(());
                        }
                    }
                }
            })
            .map_err(|e| BridgeError::Setup(format!("starting the publishing thread: {e}")))?;
        Ok(Outbox { sender: Some(sender), thread: Some(thread) })
    }

    /// Hands `messages` to the thread (waiting only if it is [`OUTBOX_DEPTH`] batches
    /// behind).
    fn send(&self, messages: Vec<Outgoing>) {
        if messages.is_empty() {
            return;
        }
        if let Some(sender) = &self.sender
            && sender.send(Outbound::Messages(messages)).is_err()
        {
            warn!("the publishing thread has stopped: messages not published");
        }
    }

    /// Waits until everything handed over is published.
    fn flush(&self) {
        let (done, wait) = mpsc::sync_channel(1);
        if let Some(sender) = &self.sender
            && sender.send(Outbound::Flush(done)).is_ok()
        {
            let _ = wait.recv();
        }
    }
}

impl Drop for Outbox {
    /// Publishes what is left, then ends the thread.
    fn drop(&mut self) {
        self.sender = None;
        if let Some(thread) = self.thread.take()
            && thread.join().is_err()
        {
            warn!("the publishing thread panicked");
        }
    }
}

/// The loop: real time while playing, waiting for calls while paused, until Ctrl-C, a
/// `SetSimulationState` to quit, or `options.duration` simulated seconds.
pub(super) fn run_loop<S: FrameStepper>(
    node: &BridgeNode,
    core: &mut BridgeCore<S>,
    options: &BridgeOptions,
) -> Result<(), BridgeError> {
    node.send_due(core)?;
    let dt = core.sim().scene().time_step();
    // Real time: the wall clock instant at which the simulation was at `paced_from`.
    let mut pace: Option<(Instant, f64)> = None;
    let end = options.duration.map(|d| core.sim().scene().time() + d);
    loop {
        if ars_core::interrupt::requested() {
            return Err(BridgeError::Interrupted);
        }
        if core.is_quitting() || end.is_some_and(|end| core.sim().scene().time() >= end - dt / 2.0) {
            return Ok(());
        }
        node.take_commands(core);
        node.serve(core)?;
        if !core.is_playing() {
            pace = None;
            std::thread::sleep(Duration::from_millis(1));
            continue;
        }
        let time = core.sim().scene().time();
        let (start, from) = *pace.get_or_insert((Instant::now(), time));
        let due = from + start.elapsed().as_secs_f64();
        let behind = ((due - time) / dt).floor().max(0.0);
        // More than a second behind: the machine cannot keep real time; go on from now.
        if behind * dt > 1.0 {
            warn!("the simulation runs slower than real time; {:.3} s of simulated time skipped pacing", behind * dt);
            pace = Some((Instant::now(), time));
            continue;
        }
        let mut steps = behind as u64;
        if let Some(end) = end {
            steps = steps.min(((end - time) / dt).round().max(0.0) as u64);
        }
        if steps == 0 {
            std::thread::sleep(Duration::from_micros(500));
            continue;
        }
        for _ in 0..steps {
            node.step(core)?;
        }
        // The sensors' samples of these steps.
        node.send_due(core)?;
    }
}

fn take_each<M: Message + 'static>(topic: &str, from: &Subscription<M>, mut take: impl FnMut(M) -> Result<(), String>) {
    for _ in 0..TAKE_PER_TURN {
        match from.take() {
            Ok(Some((message, _))) => {
                if let Err(why) = take(message) {
                    warn!("{why}");
                }
            }
            Ok(None) => return,
            Err(e) => warn!("{topic}: a message that does not read as its type ({e}); ignored"),
        }
    }
}

fn answer_each<Q: Message + Clone + 'static, A: Message + 'static>(
    service: &str,
    server: &Server<Q, A>,
    mut answer: impl FnMut(Q) -> A,
) {
    for _ in 0..TAKE_PER_TURN {
        match server.receive_request() {
            Ok(Some((id, request))) => {
                if let Err(e) = server.send_response(id, answer(request)) {
                    warn!("{service}: the answer was not sent: {e:?}");
                }
            }
            Ok(None) => return,
            Err(e) => warn!("{service}: a request that does not read as its type ({e}); ignored"),
        }
    }
}
