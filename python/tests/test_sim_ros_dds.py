"""`sim.ros(...)` checked against an independent DDS, Eclipse Cyclone DDS's Python
package, as test_ros_bridge.py checks `ars ros`: the thesis' mobile manipulator runs
under `sim.ros(..., lock_step=True)` in a Python thread (the call releases the GIL)
while this test, a Cyclone DDS participant in the same process, steps it through
/ars/step_simulation and reads /clock and /joint_states, which equal the same steps run
headless; the simulation given back is the headless one to the bit. A real-time
`sim.ros` with no duration ends on SetSimulationState's QUITTING, and a URDF robot's
text is /robot_description. Both sides use unicast discovery on the loopback only."""

import random
import threading
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip(
    "cyclonedds",
    reason="the ROS 2 bridge test needs Eclipse Cyclone DDS (pip install cyclonedds)",
    exc_type=ImportError,
)
pytest.importorskip("gymnasium", reason="the mobile manipulator is built by ars.gym")

from cyclonedds.core import Policy, Qos
from cyclonedds.domain import DomainParticipant
from cyclonedds.idl import IdlStruct
from cyclonedds.idl.types import array, int32, uint8, uint32
from test_ros_bridge import (
    CYCLONE_LOOPBACK,
    RESULT_OK,
    STATE_PAUSED,
    CallResult,
    Clock,
    GetSimulationStateRequest,
    GetSimulationStateResponse,
    JointState,
    Latest,
    Service,
    SimulationState,
    StepSimulationRequest,
    StepSimulationResponse,
)

import ars
from ars.gym.envs import SpeedProfileEnv

STATE_PLAYING = 1
STATE_QUITTING = 3


@dataclass
class SetSimulationStateRequest(
    IdlStruct, typename="simulation_interfaces::srv::dds_::SetSimulationState_Request_"
):
    client: array[uint8, 8]
    sequence_high: int32
    sequence_low: uint32
    state: SimulationState


@dataclass
class SetSimulationStateResponse(
    IdlStruct, typename="simulation_interfaces::srv::dds_::SetSimulationState_Response_"
):
    client: array[uint8, 8]
    sequence_high: int32
    sequence_low: uint32
    result: CallResult


class InThread:
    """`sim.ros(**options)` on a Python thread of its own: what it returned or raised."""

    def __init__(self, sim, **options):
        self.returned = self.raised = None

        def run():
            try:
                self.returned = sim.ros(**options)
            except BaseException as e:  # noqa: BLE001  (handed to the test)
                self.raised = e

        self.thread = threading.Thread(target=run, daemon=True)
        self.thread.start()

    def result(self, timeout):
        self.thread.join(timeout)
        assert not self.thread.is_alive(), f"sim.ros still running after {timeout} s"
        if self.raised is not None:
            raise self.raised
        return self.returned


def whole_state(sim):
    """Every moving object's pose and velocities, the four joints' positions and rates."""
    kept = ("position", "rotation", "linear_velocity", "angular_velocity")
    moving = [n for n in sim.objects if n != "floor"]
    bodies = {n: [np.asarray(getattr(sim.body(n), a)).tolist() for a in kept] for n in moving}
    joints = {n: (sim.joint(n).position, sim.joint(n).rate) for n in ("r1", "r2", "w1", "w2")}
    return bodies, joints


def answered(get_state, bridge):
    """The bridge's state once it answers (discovery), asking for 30 s."""
    for _ in range(60):
        assert bridge.thread.is_alive(), f"sim.ros ended: {bridge.raised!r}"
        state = get_state.call(0.5, structure_needs_at_least_one_member=0)
        if state is not None:
            return state
    raise AssertionError("no answer from /ars/get_simulation_state in 30 s")


@pytest.fixture
def domain(monkeypatch):
    """A ROS domain of the test's own, with Cyclone DDS on the loopback only."""
    monkeypatch.setenv("CYCLONEDDS_URI", CYCLONE_LOOPBACK)
    return random.randrange(201, 233)


def test_sim_ros_in_lock_step_gives_the_headless_bits_over_dds(domain):
    sim = SpeedProfileEnv().build()
    bridge = InThread(
        sim, duration=1.0, lock_step=True, rate=50, domain_id=domain, services="cyclonedds"
    )
    dp = DomainParticipant(domain)
    best_effort = Qos(Policy.Reliability.BestEffort, Policy.History.KeepLast(100))
    reliable = Qos(
        Policy.Reliability.Reliable(max_blocking_time=1_000_000_000), Policy.History.KeepLast(100)
    )
    clock = Latest(dp, "rt/clock", Clock, best_effort)
    joint_states = Latest(dp, "rt/joint_states", JointState, reliable)
    step = Service(dp, "step_simulation", StepSimulationRequest, StepSimulationResponse)
    get_state = Service(
        dp, "get_simulation_state", GetSimulationStateRequest, GetSimulationStateResponse
    )
    state = answered(get_state, bridge)
    assert (state.state.state, state.result.result) == (STATE_PAUSED, RESULT_OK)

    # One second of 0.25 ms steps in two calls; the bridge ends at its duration.
    def stamped(sec, nanosec):
        return lambda m: (m.header.stamp.sec, m.header.stamp.nanosec) == (sec, nanosec)

    reply = step.call(60.0, steps=1000)
    assert reply is not None and reply.result.result == RESULT_OK, reply
    after_first = joint_states.wait(stamped(0, 250_000_000))
    reply = step.call(60.0, steps=3000)
    assert reply is not None and reply.result.result == RESULT_OK, reply
    last = joint_states.wait(stamped(1, 0))
    summary = bridge.result(timeout=30)
    headless = SpeedProfileEnv().build()
    headless.step(4000)
    assert summary == {"end_time": headless.time, "steps": 4000}

    assert list(last.name) == ["r1", "r2", "w1", "w2"]
    assert list(last.position) == [headless.joint(n).position for n in last.name]
    assert list(last.velocity) == [headless.joint(n).rate for n in last.name]
    first = SpeedProfileEnv().build()
    first.step(1000)
    assert list(after_first.position) == [first.joint(n).position for n in after_first.name]
    # /clock at rate 50: every 0.02 s of simulated time and at the end of each call
    # (0.25 s), in order, up to 1 s (best effort: a burst may lose some).
    stamps = [m.clock.sec * 1_000_000_000 + m.clock.nanosec for m in clock.poll()]
    assert stamps and stamps == sorted(stamps) and stamps[-1] <= 1_000_000_000, stamps
    assert all(s % 20_000_000 == 0 or s == 250_000_000 for s in stamps), stamps
    # The simulation given back is the headless run's, to the bit (it also holds the
    # bridge's joint states sensor), and steps on.
    assert whole_state(sim) == whole_state(headless)
    sim.step(10)
    assert sim.step_count == 4010


def test_sim_ros_in_real_time_ends_when_asked_to_quit(domain):
    sim = SpeedProfileEnv().build()
    bridge = InThread(sim, domain_id=domain, services="cyclonedds")
    dp = DomainParticipant(domain)
    get_state = Service(
        dp, "get_simulation_state", GetSimulationStateRequest, GetSimulationStateResponse
    )
    set_state = Service(
        dp, "set_simulation_state", SetSimulationStateRequest, SetSimulationStateResponse
    )
    state = answered(get_state, bridge)
    assert state.state.state == STATE_PLAYING
    reply = set_state.call(10.0, state=SimulationState(STATE_QUITTING))
    assert reply is not None and reply.result.result == RESULT_OK, reply
    summary = bridge.result(timeout=30)
    assert summary["steps"] == sim.step_count > 0
    assert summary["end_time"] == sim.time


@dataclass
class String(IdlStruct, typename="std_msgs::msg::dds_::String_"):
    data: str


def test_sim_ros_publishes_the_urdf_robots_description(domain):
    urdf = Path(__file__).resolve().parents[2] / "tests" / "data" / "rnea_arm.urdf"
    sim = ars.Simulation()
    sim.load_urdf(str(urdf), fixed_base=True)
    bridge = InThread(sim, lock_step=True, domain_id=domain, services="cyclonedds")
    dp = DomainParticipant(domain)
    latched = Qos(
        Policy.Reliability.Reliable(max_blocking_time=1_000_000_000),
        Policy.Durability.TransientLocal,
        Policy.History.KeepLast(1),
    )
    description = Latest(dp, "rt/robot_description", String, latched)
    get_state = Service(
        dp, "get_simulation_state", GetSimulationStateRequest, GetSimulationStateResponse
    )
    set_state = Service(
        dp, "set_simulation_state", SetSimulationStateRequest, SetSimulationStateResponse
    )
    answered(get_state, bridge)
    assert description.wait(lambda m: True).data == urdf.read_text()
    reply = set_state.call(10.0, state=SimulationState(STATE_QUITTING))
    assert reply is not None and reply.result.result == RESULT_OK, reply
    assert bridge.result(timeout=30) == {"end_time": 0.0, "steps": 0}
