"""`ars ros` checked against an independent DDS: Eclipse Cyclone DDS's Python package.

The thesis' mobile manipulator (as `ars.gym`'s SpeedProfile builds it, with a lidar on
its chassis and a wall in front, saved as a scene file) runs under `ars ros
--lock-step`; this test, a Cyclone DDS participant with the ROS 2 wire types written out
below, reads /clock, /joint_states, /scan, /tf and /tf_static,
steps the simulation through /ars/step_simulation (simulation_interfaces, with
rmw_cyclonedds' request header), drives the vehicle with /cmd_vel, and ends the bridge
with Ctrl-C. Both sides use unicast discovery on the loopback only (no multicast), as
docs/ros2.md ("Live topics") shows.
"""

import math
import os
import random
import shutil
import signal
import subprocess
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import pytest

cyclonedds = pytest.importorskip(
    "cyclonedds",
    reason="the ROS 2 bridge test needs Eclipse Cyclone DDS (pip install cyclonedds)",
    exc_type=ImportError,
)

from cyclonedds.core import Policy, Qos
from cyclonedds.domain import DomainParticipant
from cyclonedds.idl import IdlStruct
from cyclonedds.idl.types import array, float32, float64, int32, sequence, uint8, uint32, uint64
from cyclonedds.pub import DataWriter
from cyclonedds.sub import DataReader
from cyclonedds.topic import Topic

import ars
from ars.gym.envs import SpeedProfileEnv

REPO = Path(__file__).resolve().parents[2]
# Discovery on the loopback only, unicast: no multicast needed (CI machines, containers).
CYCLONE_LOOPBACK = (
    "<CycloneDDS><Domain><General><Interfaces><NetworkInterface address='127.0.0.1'/></Interfaces>"
    "<AllowMulticast>false</AllowMulticast></General><Discovery><Peers><Peer address='127.0.0.1'/>"
    "</Peers><ParticipantIndex>auto</ParticipantIndex><MaxAutoParticipantIndex>20</MaxAutoParticipantIndex>"
    "</Discovery></Domain></CycloneDDS>"
)


@dataclass
class Time(IdlStruct, typename="builtin_interfaces::msg::dds_::Time_"):
    sec: int32
    nanosec: uint32


@dataclass
class Clock(IdlStruct, typename="rosgraph_msgs::msg::dds_::Clock_"):
    clock: Time


@dataclass
class Header(IdlStruct, typename="std_msgs::msg::dds_::Header_"):
    stamp: Time
    frame_id: str


@dataclass
class JointState(IdlStruct, typename="sensor_msgs::msg::dds_::JointState_"):
    header: Header
    name: sequence[str]
    position: sequence[float64]
    velocity: sequence[float64]
    effort: sequence[float64]


@dataclass
class Vector3(IdlStruct, typename="geometry_msgs::msg::dds_::Vector3_"):
    x: float64 = 0.0
    y: float64 = 0.0
    z: float64 = 0.0


@dataclass
class Quaternion(IdlStruct, typename="geometry_msgs::msg::dds_::Quaternion_"):
    x: float64
    y: float64
    z: float64
    w: float64


@dataclass
class Transform(IdlStruct, typename="geometry_msgs::msg::dds_::Transform_"):
    translation: Vector3
    rotation: Quaternion


@dataclass
class TransformStamped(IdlStruct, typename="geometry_msgs::msg::dds_::TransformStamped_"):
    header: Header
    child_frame_id: str
    transform: Transform


@dataclass
class TFMessage(IdlStruct, typename="tf2_msgs::msg::dds_::TFMessage_"):
    transforms: sequence[TransformStamped]


@dataclass
class LaserScan(IdlStruct, typename="sensor_msgs::msg::dds_::LaserScan_"):
    header: Header
    angle_min: float32
    angle_max: float32
    angle_increment: float32
    time_increment: float32
    scan_time: float32
    range_min: float32
    range_max: float32
    ranges: sequence[float32]
    intensities: sequence[float32]


@dataclass
class Twist(IdlStruct, typename="geometry_msgs::msg::dds_::Twist_"):
    linear: Vector3 = field(default_factory=Vector3)
    angular: Vector3 = field(default_factory=Vector3)


# simulation_interfaces' services as rmw_cyclonedds puts them on the wire: the client's
# id (the last 8 bytes of its GUID) and a sequence number, then the request.
@dataclass
class StepSimulationRequest(
    IdlStruct, typename="simulation_interfaces::srv::dds_::StepSimulation_Request_"
):
    client: array[uint8, 8]
    sequence_high: int32
    sequence_low: uint32
    steps: uint64


@dataclass
class CallResult(IdlStruct, typename="simulation_interfaces::msg::dds_::Result_"):
    result: uint8
    error_message: str


@dataclass
class StepSimulationResponse(
    IdlStruct, typename="simulation_interfaces::srv::dds_::StepSimulation_Response_"
):
    client: array[uint8, 8]
    sequence_high: int32
    sequence_low: uint32
    result: CallResult


@dataclass
class GetSimulationStateRequest(
    IdlStruct, typename="simulation_interfaces::srv::dds_::GetSimulationState_Request_"
):
    client: array[uint8, 8]
    sequence_high: int32
    sequence_low: uint32
    structure_needs_at_least_one_member: uint8


@dataclass
class SimulationState(IdlStruct, typename="simulation_interfaces::msg::dds_::SimulationState_"):
    state: uint8


@dataclass
class GetSimulationStateResponse(
    IdlStruct, typename="simulation_interfaces::srv::dds_::GetSimulationState_Response_"
):
    client: array[uint8, 8]
    sequence_high: int32
    sequence_low: uint32
    state: SimulationState
    result: CallResult


RESULT_OK = 1
STATE_PAUSED = 2


def ars_binary() -> Path:
    """The `ars` command `cargo test` built (ARS_BIN, else CARGO_TARGET_DIR's or target/'s
    debug build), built here if there is none."""
    if os.environ.get("ARS_BIN"):
        return Path(os.environ["ARS_BIN"])
    target = Path(os.environ.get("CARGO_TARGET_DIR", REPO / "target"))
    binary = target / "debug" / "ars"
    if not binary.exists():
        assert shutil.which("cargo"), "no ars binary and no cargo to build it (set ARS_BIN)"
        subprocess.run(["cargo", "build", "--bin", "ars"], cwd=REPO, check=True, timeout=3600)
    return binary


class Service:
    """A simulation_interfaces service called as rmw_cyclonedds calls it."""

    def __init__(self, dp, name, request_type, response_type):
        reliable = Qos(Policy.Reliability.Reliable(max_blocking_time=1_000_000_000))
        self.writer = DataWriter(dp, Topic(dp, f"rq/ars/{name}Request", request_type), qos=reliable)
        self.reader = DataReader(dp, Topic(dp, f"rr/ars/{name}Reply", response_type), qos=reliable)
        self.request_type = request_type
        self.client = [random.randrange(256) for _ in range(8)]
        self.sequence = 0

    def call(self, timeout, **fields):
        self.sequence += 1
        self.writer.write(self.request_type(self.client, 0, self.sequence, **fields))
        end = time.monotonic() + timeout
        while time.monotonic() < end:
            for reply in self.reader.take(N=16):
                if list(reply.client) == self.client and reply.sequence_low == self.sequence:
                    return reply
            time.sleep(0.01)
        return None


class Latest:
    """The messages of a topic, read as they come."""

    def __init__(self, dp, name, kind, qos):
        self.reader = DataReader(dp, Topic(dp, name, kind), qos=qos)
        self.seen = []

    def poll(self):
        self.seen.extend(self.reader.take(N=256))
        return self.seen

    def wait(self, predicate, timeout=10.0):
        end = time.monotonic() + timeout
        while time.monotonic() < end:
            matching = [m for m in self.poll() if predicate(m)]
            if matching:
                return matching[-1]
            time.sleep(0.01)
        raise AssertionError(f"nothing matching on {self.reader.topic.name} in {timeout} s")


def stamp(seconds_times_1e9: int) -> tuple[int, int]:
    return divmod(seconds_times_1e9, 1_000_000_000)


def chassis_at(tf: TFMessage):
    """The chassis' position in `odom` (ARS's Y-up world turned Z-up), as ARS's (x, y, z)."""
    at = next(t.transform.translation for t in tf.transforms if t.child_frame_id == "chassis")
    return [at.x, at.z, -at.y]


def scanning_manipulator():
    """The mobile manipulator with a lidar on its chassis, a wall in its view."""
    sim = SpeedProfileEnv().build()
    sim.add_box((0.2, 2.0, 6.0), (0.0, 1.0, 4.0), mass=100.0, name="wall")
    lidar = sim.add_lidar(61, math.pi, 8.0, on="chassis", position=(1.1, 0.0, 0.0), every=0.1)
    return sim, lidar


def start_bridge(tmp_path, monkeypatch, *mode):
    """`ars ros` on the scanning manipulator in `mode`, on a domain of its own."""
    monkeypatch.setenv("CYCLONEDDS_URI", CYCLONE_LOOPBACK)
    scene = tmp_path / "mobile_manipulator.json"
    scanning_manipulator()[0].save_scene_to(scene)
    domain = random.randrange(1, 101)
    log = (tmp_path / "ars-ros.log").open("w")
    process = subprocess.Popen(
        [str(ars_binary()), "ros", str(scene), *mode, "--domain-id", str(domain)]
        + ["--services", "cyclonedds", "--rate", "50"],
        stdout=log,
        stderr=subprocess.STDOUT,
        text=True,
    )
    return scene, domain, process, tmp_path / "ars-ros.log"


@pytest.fixture
def bridge(tmp_path, monkeypatch):
    """`ars ros --lock-step` on the mobile manipulator."""
    started = start_bridge(tmp_path, monkeypatch, "--lock-step")
    yield started
    if started[2].poll() is None:
        started[2].kill()
        started[2].wait()


def test_ars_ros_talks_to_cyclone_dds(bridge):
    scene, domain, process, log = bridge
    dp = DomainParticipant(domain)
    best_effort = Qos(Policy.Reliability.BestEffort, Policy.History.KeepLast(100))
    reliable = Qos(
        Policy.Reliability.Reliable(max_blocking_time=1_000_000_000), Policy.History.KeepLast(100)
    )
    latched = Qos(
        Policy.Reliability.Reliable(max_blocking_time=1_000_000_000),
        Policy.Durability.TransientLocal,
        Policy.History.KeepLast(1),
    )
    clock = Latest(dp, "rt/clock", Clock, best_effort)
    joint_states = Latest(dp, "rt/joint_states", JointState, reliable)
    tf = Latest(dp, "rt/tf", TFMessage, reliable)
    tf_static = Latest(dp, "rt/tf_static", TFMessage, latched)
    scan = Latest(dp, "rt/scan", LaserScan, best_effort)
    cmd_vel = DataWriter(dp, Topic(dp, "rt/cmd_vel", Twist), qos=reliable)
    step = Service(dp, "step_simulation", StepSimulationRequest, StepSimulationResponse)
    get_state = Service(
        dp, "get_simulation_state", GetSimulationStateRequest, GetSimulationStateResponse
    )

    # Discovery: ask for the state until the bridge answers (asking twice changes nothing).
    state = None
    for _ in range(60):
        assert process.poll() is None, log.read_text()
        state = get_state.call(0.5, structure_needs_at_least_one_member=0)
        if state is not None:
            break
    assert state is not None, (
        "no answer from /ars/get_simulation_state in 30 s:\n" + log.read_text()
    )
    assert (state.state.state, state.result.result) == (STATE_PAUSED, RESULT_OK)
    # Latched: the vehicle's odometry frame in the world's, the lidar on the chassis.
    static = tf_static.wait(lambda m: len(m.transforms) > 0)
    edges = {(t.header.frame_id, t.child_frame_id) for t in static.transforms}
    assert {("map", "odom"), ("chassis", "laser")} <= edges, edges

    # Lock step: one second of 0.25 ms steps, the same bits as the same run headless.
    reply = step.call(60.0, steps=4000)
    assert reply is not None and reply.result.result == RESULT_OK, reply
    states = joint_states.wait(lambda m: (m.header.stamp.sec, m.header.stamp.nanosec) == (1, 0))
    poses = tf.wait(
        lambda m: (m.transforms[0].header.stamp.sec, m.transforms[0].header.stamp.nanosec) == (1, 0)
    )
    headless = ars.Simulation.load_scene_from(scene)
    headless.step(4000)
    assert list(states.name) == ["r1", "r2", "w1", "w2"]
    assert list(states.position) == [headless.joint(n).position for n in states.name]
    at = chassis_at(poses)
    assert at == list(headless.body("chassis").position)
    # /scan: the lidar's records of the same run (every 0.1 s), as float32. Best
    # effort: some may be lost in a burst, none is different.
    same_run, lidar = scanning_manipulator()
    same_run.step(4000)
    records = lidar.records()
    seen = {}
    for message in scan.poll():
        seen[message.header.stamp.sec * 1_000_000_000 + message.header.stamp.nanosec] = message
    assert seen, "no /scan received"
    for time_ns, message in seen.items():
        row = next(k for k, r in enumerate(records) if round(r["time"] * 1e9) == time_ns)
        assert message.header.frame_id == "laser"
        np.testing.assert_array_equal(
            np.array(message.ranges, dtype=np.float32), lidar.ranges()[row].astype(np.float32)
        )
    assert any(np.isfinite(m.ranges).any() for m in seen.values()), "the lidar sees the wall"
    # /clock at --rate 50: every 0.02 s of simulated time, in order, up to 1 s. Best
    # effort, as rclcpp's /clock: a burst of 50 in a fraction of a second loses some.
    stamps = [m.clock.sec * 1_000_000_000 + m.clock.nanosec for m in clock.poll()]
    assert stamps and stamps == sorted(stamps) and stamps[-1] <= 1_000_000_000, stamps
    assert all(s % 20_000_000 == 0 for s in stamps), stamps

    # /cmd_vel at 10 Hz of simulated time: the vehicle drives forward (ARS's +X).
    start = at[0]
    for _ in range(20):
        cmd_vel.write(Twist(linear=Vector3(x=0.5)))
        time.sleep(0.05)  # delivered before the step that follows
        reply = step.call(60.0, steps=400)
        assert reply is not None and reply.result.result == RESULT_OK, reply
    poses = tf.wait(lambda m: m.transforms[0].header.stamp.sec == 3)
    moved = chassis_at(poses)[0] - start
    assert moved > 0.3, f"the chassis moved {moved} m in 2 s at 0.5 m/s"

    # Ctrl-C ends the bridge cleanly.
    process.send_signal(signal.SIGINT)
    assert process.wait(timeout=20) == 0, log.read_text()
    output = log.read_text()
    assert "interrupted (Ctrl-C)" in output and "ran to t = 3 s" in output, output


@dataclass
class ShortTwist(IdlStruct, typename="geometry_msgs::msg::dds_::Twist_"):
    """A malformed /cmd_vel: the right type name, one number where six are due."""

    x: float64


def test_ars_ros_ignores_bad_messages_with_a_warning(bridge):
    scene, domain, process, log = bridge
    dp = DomainParticipant(domain)
    reliable = Qos(Policy.Reliability.Reliable(max_blocking_time=1_000_000_000))
    malformed = DataWriter(dp, Topic(dp, "rt/cmd_vel", ShortTwist), qos=reliable)
    cmd_vel = DataWriter(dp, Topic(dp, "rt/cmd_vel", Twist), qos=reliable)
    step = Service(dp, "step_simulation", StepSimulationRequest, StepSimulationResponse)
    get_state = Service(
        dp, "get_simulation_state", GetSimulationStateRequest, GetSimulationStateResponse
    )
    for _ in range(60):
        if get_state.call(0.5, structure_needs_at_least_one_member=0) is not None:
            break
    malformed.write(ShortTwist(0.5))
    cmd_vel.write(Twist(linear=Vector3(x=float("nan"))))
    time.sleep(0.2)
    reply = step.call(60.0, steps=400)
    assert reply is not None and reply.result.result == RESULT_OK, log.read_text()
    # Nothing was applied: the run is the headless one.
    tf = Latest(dp, "rt/tf", TFMessage, reliable)
    time.sleep(0.5)
    reply = step.call(60.0, steps=400)
    assert reply is not None and reply.result.result == RESULT_OK
    poses = tf.wait(lambda m: m.transforms[0].header.stamp.nanosec == 200_000_000)
    headless = ars.Simulation.load_scene_from(scene)
    headless.step(800)
    assert chassis_at(poses) == list(headless.body("chassis").position)
    process.send_signal(signal.SIGINT)
    assert process.wait(timeout=20) == 0
    output = log.read_text()
    assert "/cmd_vel: a message that does not read as its type" in output, output
    assert "/cmd_vel: linear.x = NaN, angular.z = 0: not finite; ignored" in output, output


def test_ars_ros_in_real_time_never_runs_ahead_of_the_wall_clock(tmp_path, monkeypatch):
    _, domain, process, log = start_bridge(tmp_path, monkeypatch)
    try:
        dp = DomainParticipant(domain)
        clock = Latest(dp, "rt/clock", Clock, Qos(Policy.Reliability.BestEffort))
        first = clock.wait(lambda m: True, timeout=30.0)
        start = time.monotonic()
        time.sleep(2.0)
        last = clock.poll()[-1]
        wall = time.monotonic() - start
        simulated = (last.clock.sec - first.clock.sec) + (
            last.clock.nanosec - first.clock.nanosec
        ) / 1e9
        # Paced: never ahead of the wall clock (a loaded machine may fall behind it).
        assert 0.1 * wall < simulated <= wall + 0.1, (simulated, wall)
        process.send_signal(signal.SIGINT)
        assert process.wait(timeout=20) == 0, log.read_text()
    finally:
        if process.poll() is None:
            process.kill()
            process.wait()
