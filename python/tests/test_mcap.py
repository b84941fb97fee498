"""`sim.record_mcap`: the thesis' mobile manipulator recorded as ROS 2 messages, read
back with the `mcap` and `mcap-ros2-support` packages (independent readers of MCAP and
CDR), equal to ARS's own sensor records of the same run."""

from __future__ import annotations

import math

import numpy as np
import pytest
from mcap.reader import make_reader
from mcap_ros2.decoder import DecoderFactory

import ars
from ars.gym.envs import SpeedProfileEnv

JOINTS = ["r1", "r2", "w1", "w2"]  # /joint_states' order: the names, alphabetical


def mobile_manipulator() -> ars.Simulation:
    """The thesis' mobile manipulator (IROS example 3), both wheels driven forward."""
    sim = SpeedProfileEnv(peak_speed=1.0).sim
    for wheel in ("w1", "w2"):
        sim.joint(wheel).set_controller("torque", 4.0)
    return sim


class Decoded:
    """A message as read back: its channel, log and publish times, and the decoded message."""

    def __init__(self, channel, message, ros_msg):
        self.channel, self.ros_msg = channel, ros_msg
        self.log_time_ns, self.publish_time_ns = message.log_time, message.publish_time


def by_topic(path):
    """Every message of the file, decoded by mcap-ros2-support, by topic."""
    messages: dict[str, list] = {}
    with open(path, "rb") as f:
        reader = make_reader(f, decoder_factories=[DecoderFactory()])
        for _, channel, message, ros_msg in reader.iter_decoded_messages():
            messages.setdefault(channel.topic, []).append(Decoded(channel, message, ros_msg))
    return messages


def test_a_recording_reads_back_equal_to_the_sensor_records(tmp_path):
    sim = mobile_manipulator()
    # A wall some 2.5 m ahead of the chassis' front, where its lidar sees it.
    sim.add_box((0.2, 2.0, 6.0), (0.0, 1.0, 4.0), mass=100.0, name="wall")
    positions = sim.add_sensor("joint_positions", JOINTS, every=0.02)
    lidar = sim.add_lidar(61, math.pi, 8.0, on="chassis", position=(1.1, 0.0, 0.0), every=0.1)
    summary = sim.record_mcap(tmp_path / "run.mcap", 1.0)
    assert summary["path"] == str(tmp_path / "run.mcap")
    assert summary["messages"]["/clock"] == 51  # t = 0, 0.02 ... 1.0
    messages = by_topic(tmp_path / "run.mcap")
    assert {topic: len(m) for topic, m in messages.items()} == {
        topic: n for topic, n in summary["messages"].items() if n
    }
    # Joint states: the joint_positions sensor's records, bit for bit, at its times.
    records = positions.records()
    states = messages["/joint_states"]
    assert len(states) == len(records) == 50
    for message, record in zip(states, records):
        assert message.log_time_ns == message.publish_time_ns == round(record["time"] * 1e9)
        state = message.ros_msg
        assert list(state.name) == JOINTS
        assert list(state.position) == [record[field] for field in records.dtype.names[2:]]
        stamp = state.header.stamp
        assert stamp.sec * 1_000_000_000 + stamp.nanosec == message.log_time_ns
    # Scans: the lidar's ranges, as float32.
    ranges = lidar.ranges()
    scans = messages["/scan"]
    assert len(scans) == len(ranges) == 10
    for message, row in zip(scans, ranges):
        assert message.ros_msg.header.frame_id == "laser"
        np.testing.assert_array_equal(
            np.array(message.ros_msg.ranges, dtype=np.float32), row.astype(np.float32)
        )
    assert np.isfinite(ranges).any(), "the lidar sees the wall"
    # The vehicle drove forward: its odometry is the chassis in Z-up map, (x, −z, y).
    odometry = messages["/odom"]
    first, last = odometry[0].ros_msg.pose.pose.position, odometry[-1].ros_msg.pose.pose.position
    x, y, z = sim.body("chassis").position
    assert (last.x, last.y, last.z) == (x, -z, y)
    assert last.x > first.x + 0.05, (first, last)
    assert odometry[-1].ros_msg.child_frame_id == "chassis"
    # The frames: the chassis in odom, the arm along its joints from the chassis, the
    # laser on the chassis.
    tf = messages["/tf"][-1].ros_msg.transforms
    assert {(t.header.frame_id, t.child_frame_id) for t in tf} >= {
        ("odom", "chassis"),
        ("chassis", "link1"),
        ("link1", "link2"),
    }
    static = messages["/tf_static"][0].ros_msg.transforms
    assert {(t.header.frame_id, t.child_frame_id) for t in static} >= {
        ("map", "odom"),
        ("chassis", "laser"),
    }


def test_the_file_is_written_as_ros2_bag_writes_it(tmp_path):
    sim = mobile_manipulator()
    sim.record_mcap(tmp_path / "run.mcap", 0.1, state_rate=100.0)
    with open(tmp_path / "run.mcap", "rb") as f:
        reader = make_reader(f)
        assert reader.get_header().profile == "ros2"
        summary = reader.get_summary()
    channels = {c.topic: c for c in summary.channels.values()}
    schemas = {c.topic: summary.schemas[c.schema_id] for c in summary.channels.values()}
    assert schemas["/joint_states"].name == "sensor_msgs/msg/JointState"
    assert schemas["/tf_static"].encoding == "ros2msg"
    assert all(c.message_encoding == "cdr" for c in channels.values())
    assert "durability: 1" in channels["/tf_static"].metadata["offered_qos_profiles"]
    assert "reliability: 2" in channels["/clock"].metadata["offered_qos_profiles"]
    assert summary.statistics.channel_message_counts[channels["/clock"].id] == 11  # 100 a second


def test_a_folder_that_does_not_exist_is_a_file_error_and_leaves_no_file(tmp_path):
    sim = mobile_manipulator()
    with pytest.raises(ars.FileError):
        sim.record_mcap(tmp_path / "missing" / "run.mcap", 0.1)
    assert not (tmp_path / "missing").exists()
    with pytest.raises(ars.InputError, match="allow_long"):
        sim.record_mcap(tmp_path / "long.mcap", 4000.0)
    with pytest.raises(ars.InputError, match="ROS state rate"):
        sim.record_mcap(tmp_path / "rate.mcap", 0.1, state_rate=0.0)
    assert not (tmp_path / "rate.mcap").exists()
