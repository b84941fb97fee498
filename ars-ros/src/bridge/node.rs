//! The bridge on the network: a ROS 2 node (RustDDS, through `ros2-client`) with the
//! publishers, subscriptions and services of [`super`]'s table, and the loop that
//! feeds a [`BridgeCore`] what arrives and publishes what it makes.

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
use super::wire::{Clock, Float64MultiArray, JointState, StringMessage, TfMessage, Twist, type_names};
use super::{BridgeError, BridgeOptions};

/// How many messages of one topic are taken per turn of the loop, so that a flood
/// cannot hold it.
const TAKE_PER_TURN: usize = 64;

/// The node's endpoints.
pub(super) struct BridgeNode {
    clock: Publisher<Clock>,
    joint_states: Publisher<JointState>,
    tf: Publisher<TfMessage>,
    tf_static: Publisher<TfMessage>,
    robot_description: Publisher<StringMessage>,
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

fn name(namespace: &str, base: &str) -> Result<Name, BridgeError> {
    Name::new(namespace, base).map_err(|e| BridgeError::Setup(format!("the name {namespace}/{base}: {e}")))
}

fn setup<T, E: std::fmt::Debug>(what: &str, made: Result<T, E>) -> Result<T, BridgeError> {
    made.map_err(|e| BridgeError::Setup(format!("{what}: {e:?}")))
}

impl BridgeNode {
    /// The node `options.node_name` on `options.domain_id`, with every endpoint.
    pub(super) fn new(options: &BridgeOptions) -> Result<BridgeNode, BridgeError> {
        let context = Context::with_options(ContextOptions::new().domain_id(options.domain_id))
            .map_err(|e| BridgeError::Network(format!("starting DDS on domain {}: {e:?}", options.domain_id)))?;
        let node_name = NodeName::new("/", &options.node_name)
            .map_err(|e| BridgeError::Setup(format!("the node name {:?}: {e}", options.node_name)))?;
        let mut node = setup("the node", context.new_node(node_name, NodeOptions::new()))?;
        let topic = |n: &str, t: MessageTypeName, q: &QosProfile| setup(n, node.create_topic(&name("/", n)?, t, q));
        // /clock as rclcpp's ClockQoS; the rest reliable (as joint_state_publisher and
        // tf2's broadcasters); /tf_static and /robot_description latched.
        let state = qos(true, false, 10);
        let latched = qos(true, true, 1);
        // Best effort subscriptions take from reliable and best effort publishers alike.
        let commands = qos(false, false, 10);
        let clock_topic = topic("clock", type_names::clock(), &qos(false, false, 1))?;
        let joint_states_topic = topic("joint_states", type_names::joint_state(), &state)?;
        let tf_topic = topic("tf", type_names::tf(), &qos(true, false, 100))?;
        let tf_static_topic = topic("tf_static", type_names::tf(), &latched)?;
        let description_topic = topic("robot_description", type_names::string(), &latched)?;
        let cmd_vel_topic = topic("cmd_vel", type_names::twist(), &commands)?;
        let joint_commands_topic = topic("joint_commands", type_names::joint_state(), &commands)?;
        let mut forward_topics = Vec::new();
        for kind in CommandKind::ALL {
            let t = setup(
                kind.controller(),
                node.create_topic(
                    &name(&format!("/{}", kind.controller()), "commands")?,
                    type_names::float64_multi_array(),
                    &commands,
                ),
            )?;
            forward_topics.push((kind, t));
        }
        let mut forward = Vec::new();
        for (kind, t) in &forward_topics {
            forward.push((*kind, setup(kind.controller(), node.create_subscription(t, None))?));
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
            clock: setup("/clock", node.create_publisher(&clock_topic, None))?,
            joint_states: setup("/joint_states", node.create_publisher(&joint_states_topic, None))?,
            tf: setup("/tf", node.create_publisher(&tf_topic, None))?,
            tf_static: setup("/tf_static", node.create_publisher(&tf_static_topic, None))?,
            robot_description: setup("/robot_description", node.create_publisher(&description_topic, None))?,
            cmd_vel: setup("/cmd_vel", node.create_subscription(&cmd_vel_topic, None))?,
            joint_commands: setup("/joint_commands", node.create_subscription(&joint_commands_topic, None))?,
            forward,
            get_features: server!("get_simulator_features", "GetSimulatorFeatures"),
            step: server!("step_simulation", "StepSimulation"),
            reset: server!("reset_simulation", "ResetSimulation"),
            set_state: server!("set_simulation_state", "SetSimulationState"),
            get_state: server!("get_simulation_state", "GetSimulationState"),
            _node: node,
        })
    }

    /// Publishes what never changes: `/tf_static` and `/robot_description` (if any).
    pub(super) fn publish_latched(&self, core: &BridgeCore, description: Option<&str>) -> Result<(), BridgeError> {
        let tf_static = core.frames.tf_static(core.sim().scene())?;
        sent("/tf_static", self.tf_static.publish(tf_static));
        if let Some(text) = description {
            sent("/robot_description", self.robot_description.publish(StringMessage { data: text.to_string() }));
        }
        Ok(())
    }

    /// Publishes `/clock`, `/joint_states` and `/tf` now.
    pub(super) fn publish_state(&self, core: &BridgeCore) -> Result<(), BridgeError> {
        let scene = core.sim().scene();
        sent("/clock", self.clock.publish(core.clock()));
        sent("/joint_states", self.joint_states.publish(core.frames.joint_states(scene)?));
        sent("/tf", self.tf.publish(core.frames.tf(scene)?));
        Ok(())
    }

    /// Takes what arrived on the subscriptions and gives it to `core`; what it refuses
    /// is logged.
    pub(super) fn take_commands(&self, core: &mut BridgeCore) {
        take_each("/cmd_vel", &self.cmd_vel, |m| core.take_twist(m));
        take_each("/joint_commands", &self.joint_commands, |m| core.take_named(&m));
        for (kind, subscription) in &self.forward {
            take_each(kind.controller(), subscription, |m| core.take_forward(*kind, &m));
        }
    }

    /// Answers the service calls that arrived; a `StepSimulation` steps `core`
    /// (publishing as it goes) before its answer.
    pub(super) fn serve(&self, core: &mut BridgeCore, stepper: &mut Stepper) -> Result<(), BridgeError> {
        answer_each("get_simulator_features", &self.get_features, |_| core.features());
        answer_each("get_simulation_state", &self.get_state, |_| core.get_state());
        answer_each("set_simulation_state", &self.set_state, |r| core.set_state(r.state.state));
        answer_each("reset_simulation", &self.reset, |r| {
            let answer = core.reset(r.scope);
            stepper.restart();
            answer
        });
        let mut failure = None;
        answer_each("step_simulation", &self.step, |r| {
            if let Err(result) = core.check_step_request(r.steps) {
                return ResultResponse { result };
            }
            // Commands sent before the call count from its first step.
            self.take_commands(core);
            let result = match stepper.step(self, core, r.steps) {
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
}

/// Steps a core and publishes at the rate asked, counted in simulated time.
pub(super) struct Stepper {
    /// Steps between two publications.
    period_steps: u64,
    /// The step count of the last publication.
    published_at: Option<u64>,
}

impl Stepper {
    /// Publishes `rate` times per simulated second of `core`'s steps.
    pub(super) fn new(core: &BridgeCore, rate: f64) -> Stepper {
        let dt = core.sim().scene().time_step();
        let period_steps = ((1.0 / (rate * dt)).round() as u64).max(1);
        Stepper { period_steps, published_at: None }
    }

    /// Takes `n` steps, publishing on the way at the rate and after the last.
    pub(super) fn step(&mut self, node: &BridgeNode, core: &mut BridgeCore, n: u64) -> Result<(), BridgeError> {
        for _ in 0..n {
            if ars_core::interrupt::requested() {
                return Err(BridgeError::Interrupted);
            }
            self.step_quietly(node, core)?;
        }
        self.publish(node, core)
    }

    /// Publishes the state unless it already was at this step.
    pub(super) fn publish(&mut self, node: &BridgeNode, core: &BridgeCore) -> Result<(), BridgeError> {
        let count = core.sim().scene().step_count();
        if self.published_at != Some(count) {
            node.publish_state(core)?;
            self.published_at = Some(count);
        }
        Ok(())
    }

    /// After a reset: the next state is published whatever its step count.
    pub(super) fn restart(&mut self) {
        self.published_at = None;
    }
}

/// The loop: real time while playing, waiting for calls while paused, until Ctrl-C, a
/// `SetSimulationState` to quit, or `options.duration` simulated seconds.
pub(super) fn run_loop(node: &BridgeNode, core: &mut BridgeCore, options: &BridgeOptions) -> Result<(), BridgeError> {
    let mut stepper = Stepper::new(core, options.rate);
    stepper.publish(node, core)?;
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
        node.serve(core, &mut stepper)?;
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
            stepper.step_quietly(node, core)?;
        }
    }
}

impl Stepper {
    /// One step, publishing if a publication is due, not after it otherwise.
    fn step_quietly(&mut self, node: &BridgeNode, core: &mut BridgeCore) -> Result<(), BridgeError> {
        for warning in core.step()? {
            warn!("{warning}");
        }
        if core.sim().scene().step_count().is_multiple_of(self.period_steps) {
            self.publish(node, core)?;
        }
        Ok(())
    }
}

fn sent<E: std::fmt::Debug>(topic: &str, result: Result<(), E>) {
    if let Err(e) = result {
        warn!("{topic}: not published: {e:?}");
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
