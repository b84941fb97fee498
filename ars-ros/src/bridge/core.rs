//! The bridge without the network: a simulation, its state (playing or paused), the
//! commands it was given, the Simulation Interfaces calls, and the [`Publisher`] that
//! turns it into messages. The node (module `node`) feeds it what arrives and sends
//! what it makes; the tests drive it directly.

use ars_core::{JointId, Simulation, Snapshot};

use super::commands::{CheckResult, CommandGains, CommandKind, DiffDrive, HeldCommands};
use super::sim_interfaces::{
    CallResult, GetSimulationStateResponse, GetSimulatorFeaturesResponse, ResetSimulationRequest, ResultResponse,
    SimulationState, SimulatorFeatures,
};
use super::wire::{Float64MultiArray, JointState, Twist};
use crate::mcap::FrameStepper;
use crate::publish::{Publisher, RosOptions};
use crate::topics::{Outgoing, Topic};

/// The most steps one `StepSimulation` call may ask for (about 11 simulated hours at
/// ARS's 0.4 ms step); a larger request fails rather than hold the bridge.
pub const MAX_STEPS_PER_CALL: u64 = 100_000_000;

/// A simulation run by the bridge: a [`Simulation`], or a program's
/// ([`ProgramRunner`](ars_core::ProgramRunner)), stepped with its hooks.
pub struct BridgeCore<S: FrameStepper = Simulation> {
    stepper: S,
    initial: Snapshot,
    publisher: Publisher,
    /// The joints of `/joint_states`, in its order (the forward controllers').
    joints: Vec<(String, JointId)>,
    drive: Option<DiffDrive>,
    gains: CommandGains,
    held: HeldCommands,
    /// A `/cmd_vel` not yet put on the wheels.
    pending_twist: Option<Twist>,
    /// When the wheels were last commanded (simulated time), for the timeout.
    last_twist_at: Option<f64>,
    /// How long the wheels keep a `/cmd_vel` without a new one, simulated s.
    pub twist_timeout: f64,
    state: u8,
    commands_since_step: u32,
}

impl<S: FrameStepper> BridgeCore<S> {
    /// The bridge of `stepper`'s simulation, published as `ros` says, playing or
    /// (`paused`) waiting to be stepped, with `drive` (if any) for `/cmd_vel`. Its
    /// chassis is published as a vehicle (`/odom`) if `ros` does not already list it.
    pub fn new(
        mut stepper: S,
        ros: &RosOptions,
        drive: Option<DiffDrive>,
        gains: CommandGains,
        paused: bool,
    ) -> crate::RosResult<Self> {
        let mut ros = ros.clone();
        if let Some(chassis) = drive.as_ref().map(|d| d.chassis)
            && !ros.vehicles.contains(&chassis)
        {
            ros.vehicles.push(chassis);
        }
        let publisher = Publisher::attach(stepper.simulation_mut(), &ros)?;
        let sim = stepper.simulation();
        let joints = sim.sensor(publisher.joint_states_sensor())?.named_joints();
        // After the publisher's sensor: a reset restores a simulation with it.
        let initial = sim.snapshot()?;
        let state = if paused { SimulationState::PAUSED } else { SimulationState::PLAYING };
        Ok(BridgeCore {
            stepper,
            initial,
            publisher,
            joints,
            drive,
            gains,
            held: HeldCommands::default(),
            pending_twist: None,
            last_twist_at: None,
            twist_timeout: 0.5,
            state,
            commands_since_step: 0,
        })
    }

    /// The simulation.
    pub fn sim(&self) -> &Simulation {
        self.stepper.simulation()
    }

    /// The simulation (or program) given back.
    pub fn into_stepper(self) -> S {
        self.stepper
    }

    /// The joints of `/joint_states`, in its order: the forward command controllers'.
    pub fn joints(&self) -> &[(String, JointId)] {
        &self.joints
    }

    /// The topics published, in the order [`Outgoing::topic`] indexes them.
    pub fn topics(&self) -> &[Topic] {
        self.publisher.topics()
    }

    /// The publisher.
    pub fn publisher(&self) -> &Publisher {
        &self.publisher
    }

    /// Whether the state (`/clock`, `/tf`...) is due at this step.
    pub fn state_due(&self) -> bool {
        self.publisher.state_due(self.stepper.simulation())
    }

    /// The messages due since the last call (see [`Publisher::poll`]).
    pub fn poll(&mut self) -> crate::RosResult<Vec<Outgoing>> {
        self.publisher.poll(self.stepper.simulation())
    }

    /// The messages due, and the state now (see [`Publisher::poll_with_state_now`]):
    /// what is sent at the end of a `StepSimulation` call.
    pub fn poll_with_state_now(&mut self) -> crate::RosResult<Vec<Outgoing>> {
        self.publisher.poll_with_state_now(self.stepper.simulation())
    }

    /// The drive `/cmd_vel` turns, if any.
    pub fn drive(&self) -> Option<&DiffDrive> {
        self.drive.as_ref()
    }

    /// Whether the simulation plays (in real time) rather than waits to be stepped.
    pub fn is_playing(&self) -> bool {
        self.state == SimulationState::PLAYING
    }

    /// Whether `SetSimulationState` asked the bridge to quit.
    pub fn is_quitting(&self) -> bool {
        self.state == SimulationState::QUITTING
    }

    /// A `/cmd_vel`: kept for the next step (the last one before a step wins).
    pub fn take_twist(&mut self, twist: Twist) -> CheckResult {
        if self.drive.is_none() {
            return Err("/cmd_vel: the scene has no differential drive (see --drive); ignored".into());
        }
        DiffDrive::check(&twist)?;
        self.pending_twist = Some(twist);
        self.faster_than_steps("/cmd_vel")
    }

    /// A forward command controller's command.
    pub fn take_forward(&mut self, kind: CommandKind, message: &Float64MultiArray) -> CheckResult {
        self.held.forward(kind, &self.joints, message)?;
        self.faster_than_steps(kind.controller())
    }

    /// A named command on `/joint_commands`.
    pub fn take_named(&mut self, message: &JointState) -> CheckResult {
        self.held.named(&self.joints, message)?;
        self.faster_than_steps("/joint_commands")
    }

    /// Commands counted between steps: past the first, the earlier ones were replaced
    /// before any step used them, which is said (once per step).
    fn faster_than_steps(&mut self, what: &str) -> CheckResult {
        self.commands_since_step += 1;
        if self.commands_since_step == 2 {
            return Err(format!(
                "{what}: commands arrive faster than the simulation steps; only the last before a step is used"
            ));
        }
        Ok(())
    }

    /// One step: the commands on the joints and wheels, then the simulation's step.
    /// Returns the warnings of commands that could not be applied.
    pub fn step(&mut self) -> ars_core::Result<Vec<String>> {
        let mut warnings = Vec::new();
        let time = self.sim().scene().time();
        let sim = self.stepper.simulation_mut();
        if let (Some(drive), Some(twist)) = (&self.drive, self.pending_twist.take()) {
            match drive.drive(sim, &twist) {
                Ok(()) => self.last_twist_at = Some(time),
                Err(e) => warnings.push(format!("/cmd_vel not applied: {e}")),
            }
        } else if let (Some(drive), Some(at)) = (&self.drive, self.last_twist_at)
            && time - at > self.twist_timeout
        {
            // No /cmd_vel for a while: stop, as diff_drive_controller does.
            if let Err(e) = drive.drive(sim, &Twist::default()) {
                warnings.push(format!("stopping the wheels: {e}"));
            }
            self.last_twist_at = None;
        }
        if !self.held.is_empty() {
            warnings.extend(self.held.apply(sim, self.gains));
        }
        self.commands_since_step = 0;
        self.stepper.step()?;
        Ok(warnings)
    }

    /// `GetSimulatorFeatures`.
    pub fn features(&self) -> GetSimulatorFeaturesResponse {
        use SimulatorFeatures as F;
        GetSimulatorFeaturesResponse {
            features: SimulatorFeatures {
                features: vec![
                    F::SIMULATION_RESET,
                    F::SIMULATION_STATE_GETTING,
                    F::SIMULATION_STATE_SETTING,
                    F::SIMULATION_STATE_PAUSE,
                    F::STEP_SIMULATION_SINGLE,
                    F::STEP_SIMULATION_MULTIPLE,
                ],
                spawn_formats: Vec::new(),
                custom_info: format!(
                    "ARS {}: resets restore the start (scopes DEFAULT, ALL, or TIME and STATE together)",
                    env!("CARGO_PKG_VERSION")
                ),
            },
        }
    }

    /// Checks a `StepSimulation` of `steps`: `Ok` if it may go ahead.
    pub fn check_step_request(&self, steps: u64) -> Result<(), CallResult> {
        if self.state != SimulationState::PAUSED && self.state != SimulationState::STOPPED {
            return Err(CallResult::failed(
                CallResult::OPERATION_FAILED,
                "the simulation is playing: pause it (SetSimulationState) to step it",
            ));
        }
        if steps > MAX_STEPS_PER_CALL {
            return Err(CallResult::failed(
                CallResult::OPERATION_FAILED,
                format!("{steps} steps in one call: at most {MAX_STEPS_PER_CALL}"),
            ));
        }
        Ok(())
    }

    /// `ResetSimulation`: back to the start (time, poses, velocities), commands dropped.
    pub fn reset(&mut self, scope: u8) -> ResultResponse {
        use ResetSimulationRequest as R;
        let both = R::SCOPE_TIME | R::SCOPE_STATE;
        if scope != R::SCOPE_DEFAULT && scope != R::SCOPE_ALL && scope & both != both {
            return ResultResponse {
                result: CallResult::failed(
                    CallResult::FEATURE_UNSUPPORTED,
                    format!("reset scope {scope}: ARS resets time and state together (DEFAULT, ALL, or TIME|STATE)"),
                ),
            };
        }
        let result = match self.stepper.simulation_mut().restore(&self.initial) {
            Ok(()) => {
                self.publisher.restart(self.stepper.simulation());
                self.held.clear();
                self.pending_twist = None;
                self.last_twist_at = None;
                CallResult::ok()
            }
            Err(e) => CallResult::failed(CallResult::OPERATION_FAILED, format!("restoring the start: {e}")),
        };
        ResultResponse { result }
    }

    /// `SetSimulationState`: play, pause, stop (pause and reset) or quit.
    pub fn set_state(&mut self, wanted: u8) -> ResultResponse {
        use SimulationState as S;
        let result = match wanted {
            w if w == self.state => CallResult::failed(CallResult::ALREADY_IN_TARGET_STATE, "already in that state"),
            S::PLAYING | S::PAUSED | S::QUITTING => {
                self.state = wanted;
                CallResult::ok()
            }
            S::STOPPED => {
                let reset = self.reset(ResetSimulationRequest::SCOPE_ALL);
                if reset.result.result == CallResult::OK {
                    self.state = S::STOPPED;
                }
                reset.result
            }
            other => CallResult::failed(
                CallResult::INCORRECT_TRANSITION,
                format!("state {other}: ARS plays, pauses, stops (0-3) and quits, and has no world to load"),
            ),
        };
        ResultResponse { result }
    }

    /// `GetSimulationState`.
    pub fn get_state(&self) -> GetSimulationStateResponse {
        GetSimulationStateResponse { state: SimulationState { state: self.state }, result: CallResult::ok() }
    }
}
