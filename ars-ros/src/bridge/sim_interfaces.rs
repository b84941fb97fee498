//! The ROS 2 Simulation Interfaces (`simulation_interfaces`, version 2.1.0) that fit
//! ARS, as their `.msg` and `.srv` files define them: the field names, order and
//! constants are theirs. An empty request gets the one `uint8` member ROS 2's IDL gives
//! an empty structure (`structure_needs_at_least_one_member`).

use ros2_client::{Message, ServiceTypeName};
use serde::{Deserialize, Serialize};

/// `simulation_interfaces/Result`: how a call went.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct CallResult {
    /// One of the `RESULT_*` constants.
    pub result: u8,
    /// Why, when it failed.
    pub error_message: String,
}

impl CallResult {
    /// `RESULT_FEATURE_UNSUPPORTED`.
    pub const FEATURE_UNSUPPORTED: u8 = 0;
    /// `RESULT_OK`.
    pub const OK: u8 = 1;
    /// `RESULT_NOT_FOUND`.
    pub const NOT_FOUND: u8 = 2;
    /// `RESULT_INCORRECT_STATE`.
    pub const INCORRECT_STATE: u8 = 3;
    /// `RESULT_OPERATION_FAILED`.
    pub const OPERATION_FAILED: u8 = 4;
    /// `SetSimulationState`'s `ALREADY_IN_TARGET_STATE`.
    pub const ALREADY_IN_TARGET_STATE: u8 = 101;
    /// `SetSimulationState`'s `INCORRECT_TRANSITION`.
    pub const INCORRECT_TRANSITION: u8 = 103;

    /// Success.
    pub fn ok() -> CallResult {
        CallResult { result: Self::OK, error_message: String::new() }
    }

    /// A failure of kind `result`, saying why.
    pub fn failed(result: u8, why: impl Into<String>) -> CallResult {
        CallResult { result, error_message: why.into() }
    }
}

/// `simulation_interfaces/SimulationState`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct SimulationState {
    /// One of the `STATE_*` constants.
    pub state: u8,
}

impl SimulationState {
    /// `STATE_STOPPED`: paused and reset.
    pub const STOPPED: u8 = 0;
    /// `STATE_PLAYING`.
    pub const PLAYING: u8 = 1;
    /// `STATE_PAUSED`.
    pub const PAUSED: u8 = 2;
    /// `STATE_QUITTING`: the bridge ends.
    pub const QUITTING: u8 = 3;
}

/// `simulation_interfaces/SimulatorFeatures`.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct SimulatorFeatures {
    /// The supported features (the constants below).
    pub features: Vec<u16>,
    /// Formats SpawnEntity takes (none: ARS does not spawn).
    pub spawn_formats: Vec<String>,
    /// Free text for the caller.
    pub custom_info: String,
}

impl SimulatorFeatures {
    /// `SIMULATION_RESET`.
    pub const SIMULATION_RESET: u16 = 20;
    /// `SIMULATION_RESET_TIME`.
    pub const SIMULATION_RESET_TIME: u16 = 21;
    /// `SIMULATION_RESET_STATE`.
    pub const SIMULATION_RESET_STATE: u16 = 22;
    /// `SIMULATION_STATE_GETTING`.
    pub const SIMULATION_STATE_GETTING: u16 = 24;
    /// `SIMULATION_STATE_SETTING`.
    pub const SIMULATION_STATE_SETTING: u16 = 25;
    /// `SIMULATION_STATE_PAUSE`.
    pub const SIMULATION_STATE_PAUSE: u16 = 26;
    /// `STEP_SIMULATION_SINGLE`.
    pub const STEP_SIMULATION_SINGLE: u16 = 31;
    /// `STEP_SIMULATION_MULTIPLE`.
    pub const STEP_SIMULATION_MULTIPLE: u16 = 32;
}

/// `GetSimulatorFeatures` request (empty).
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct GetSimulatorFeaturesRequest {
    /// ROS 2's placeholder member of an empty structure.
    pub structure_needs_at_least_one_member: u8,
}

/// `GetSimulatorFeatures` response.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct GetSimulatorFeaturesResponse {
    /// What ARS supports.
    pub features: SimulatorFeatures,
}

/// `StepSimulation` request: step this many times (the simulation must be paused).
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct StepSimulationRequest {
    /// Steps of the simulation's time step.
    pub steps: u64,
}

/// `StepSimulation`, `ResetSimulation` and `SetSimulationState` responses: a result.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct ResultResponse {
    /// How it went.
    pub result: CallResult,
}

/// `ResetSimulation` request.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct ResetSimulationRequest {
    /// `SCOPE_*` flags: what to reset.
    pub scope: u8,
}

impl ResetSimulationRequest {
    /// `SCOPE_DEFAULT` (the same as `SCOPE_ALL`).
    pub const SCOPE_DEFAULT: u8 = 0;
    /// `SCOPE_TIME`.
    pub const SCOPE_TIME: u8 = 1;
    /// `SCOPE_STATE`.
    pub const SCOPE_STATE: u8 = 2;
    /// `SCOPE_ALL`.
    pub const SCOPE_ALL: u8 = 255;
}

/// `SetSimulationState` request.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct SetSimulationStateRequest {
    /// The state wanted.
    pub state: SimulationState,
}

/// `GetSimulationState` request (empty).
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct GetSimulationStateRequest {
    /// ROS 2's placeholder member of an empty structure.
    pub structure_needs_at_least_one_member: u8,
}

/// `GetSimulationState` response.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct GetSimulationStateResponse {
    /// The current state.
    pub state: SimulationState,
    /// How the call went.
    pub result: CallResult,
}

impl Message for GetSimulatorFeaturesRequest {}
impl Message for GetSimulatorFeaturesResponse {}
impl Message for StepSimulationRequest {}
impl Message for ResultResponse {}
impl Message for ResetSimulationRequest {}
impl Message for SetSimulationStateRequest {}
impl Message for GetSimulationStateRequest {}
impl Message for GetSimulationStateResponse {}

/// The type name of the service `simulation_interfaces/srv/NAME`.
pub fn service_type(name: &str) -> ServiceTypeName {
    ServiceTypeName::new("simulation_interfaces", name)
}
