//! The bridge without the network: a simulation, its state (playing or paused), the
//! commands it was given and the Simulation Interfaces calls. The node (module `node`)
//! feeds it what arrives and publishes what it makes; the tests drive it directly.

use ars_core::{Simulation, Snapshot};

use super::commands::{CheckResult, CommandGains, CommandKind, DiffDrive, HeldCommands};
use super::frames::SceneFrames;
use super::sim_interfaces::{
    CallResult, GetSimulationStateResponse, GetSimulatorFeaturesResponse, ResetSimulationRequest, ResultResponse,
    SimulationState, SimulatorFeatures,
};
use super::wire::{Clock, Float64MultiArray, JointState, Time, Twist};

/// The most steps one `StepSimulation` call may ask for (about 11 simulated hours at
/// ARS's 0.4 ms step); a larger request fails rather than hold the bridge.
pub const MAX_STEPS_PER_CALL: u64 = 100_000_000;

/// A simulation run by the bridge.
pub struct BridgeCore {
    sim: Simulation,
    initial: Snapshot,
    /// The joints and frames published.
    pub frames: SceneFrames,
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

impl BridgeCore {
    /// The bridge of `sim`, playing or (`paused`) waiting to be stepped, with `drive`
    /// (if any) for `/cmd_vel`.
    pub fn new(sim: Simulation, drive: Option<DiffDrive>, gains: CommandGains, paused: bool) -> ars_core::Result<Self> {
        let initial = sim.snapshot()?;
        let frames = SceneFrames::of(sim.scene())?;
        let state = if paused { SimulationState::PAUSED } else { SimulationState::PLAYING };
        Ok(BridgeCore {
            sim,
            initial,
            frames,
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
        &self.sim
    }

    /// The simulation, given back.
    pub fn into_simulation(self) -> Simulation {
        self.sim
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
        self.held.forward(kind, &self.frames.joints, message)?;
        self.faster_than_steps(kind.controller())
    }

    /// A named command on `/joint_commands`.
    pub fn take_named(&mut self, message: &JointState) -> CheckResult {
        self.held.named(&self.frames.joints, message)?;
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
        let time = self.sim.scene().time();
        if let (Some(drive), Some(twist)) = (&self.drive, self.pending_twist.take()) {
            match drive.drive(&mut self.sim, &twist) {
                Ok(()) => self.last_twist_at = Some(time),
                Err(e) => warnings.push(format!("/cmd_vel not applied: {e}")),
            }
        } else if let (Some(drive), Some(at)) = (&self.drive, self.last_twist_at)
            && time - at > self.twist_timeout
        {
            // No /cmd_vel for a while: stop, as diff_drive_controller does.
            if let Err(e) = drive.drive(&mut self.sim, &Twist::default()) {
                warnings.push(format!("stopping the wheels: {e}"));
            }
            self.last_twist_at = None;
        }
        if !self.held.is_empty() {
            warnings.extend(self.held.apply(&mut self.sim, self.gains));
        }
        self.commands_since_step = 0;
        self.sim.step()?;
        Ok(warnings)
    }

    /// `/clock` now.
    pub fn clock(&self) -> Clock {
        Clock { clock: Time::from_seconds(self.sim.scene().time()) }
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
        let result = match self.sim.restore(&self.initial) {
            Ok(()) => {
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
