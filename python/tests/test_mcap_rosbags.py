"""`sim.record_mcap` read as `ros2 bag` reads a file, with the `rosbags` package: a reader
of rosbag2's MCAP files with its own ros2msg parser and CDR decoder (pure Python, no ROS).

The thesis' mobile manipulator with a lidar, an IMU and a depth camera is recorded; the
bare .mcap file (no metadata.yaml, as `ros2 bag info/play run.mcap` take it since
Humble) is opened, every channel's QoS is parsed as rosbag2 parses it, the message types
are built from the file's own schemas and compared with ROS 2 Jazzy's, and every message
is decoded and encoded again to the same bytes. `tools/mcap/foxglove_check.mjs` does the
same with the npm packages Foxglove reads MCAP with (not run here: no Node in CI).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

pytest.importorskip(
    "rosbags", reason="reading MCAP as ros2 bag does needs rosbags (pip install rosbags)"
)

from rosbags.highlevel import AnyReader
from rosbags.rosbag2 import Reader
from rosbags.typesys import Stores, get_typestore

from ars.gym.envs import SpeedProfileEnv

DURATION = 0.5


@pytest.fixture(scope="module")
def recording(tmp_path_factory):
    """(path, summary, IMU, depth camera) of a recording of the mobile manipulator with every
    kind of sensor the publisher takes from Python."""
    sim = SpeedProfileEnv(peak_speed=1.0).sim
    for wheel in ("w1", "w2"):
        sim.joint(wheel).set_controller("torque", 4.0)
    sim.add_box((0.2, 2.0, 6.0), (0.0, 1.0, 4.0), mass=100.0, name="wall")
    sim.add_lidar(61, math.pi, 8.0, on="chassis", position=(1.1, 0.0, 0.0), every=0.1)
    imu = sim.add_sensor("imu", "chassis", every=0.01)
    camera = sim.add_depth_camera(
        16, 12, 1.0, 0.05, 10.0, on="chassis", position=(1.0, 0.3, 0.0), every=0.1
    )
    path = tmp_path_factory.mktemp("rosbags") / "run.mcap"
    summary = sim.record_mcap(path, DURATION)
    return path, summary, imu, camera


def test_the_bare_file_opens_as_a_bag_with_its_counts(recording):
    path, summary, _, _ = recording
    with Reader(path) as bag:
        assert bag.message_count == sum(summary["messages"].values())
        counts = {topic: info.msgcount for topic, info in bag.topics.items()}
        assert counts == summary["messages"]
        assert bag.duration == round(DURATION * 1e9) + 1  # rosbags' end is one past the last
        assert {c.ext.serialization_format for c in bag.connections} == {"cdr"}
    expected = {
        "/clock",
        "/tf",
        "/tf_static",
        "/joint_states",
        "/odom",
        "/scan",
        "/imu",
        "/camera/depth/image_raw",
        "/camera/depth/camera_info",
    }
    assert {topic for topic, n in counts.items() if n} == expected


def test_the_qos_profiles_read_as_rosbag2_reads_them(recording):
    from rosbags.rosbag2.metadata import QosDurability, QosHistory, QosReliability

    with Reader(recording[0]) as bag:
        qos = {c.topic: c.ext.offered_qos_profiles for c in bag.connections}
    assert all(len(profiles) == 1 for profiles in qos.values()), qos
    profile = {topic: profiles[0] for topic, profiles in qos.items()}
    assert profile["/tf_static"].durability == QosDurability.TRANSIENT_LOCAL
    assert profile["/robot_description"].durability == QosDurability.TRANSIENT_LOCAL
    for topic in ("/scan", "/imu", "/camera/depth/image_raw", "/clock"):
        assert profile[topic].reliability == QosReliability.BEST_EFFORT, topic
    assert profile["/tf"].reliability == QosReliability.RELIABLE
    assert (profile["/tf"].history, profile["/tf"].depth) == (QosHistory.KEEP_LAST, 100)
    assert profile["/joint_states"].durability == QosDurability.VOLATILE


def test_the_schemas_define_ros2_jazzys_types(recording):
    jazzy = get_typestore(Stores.ROS2_JAZZY)
    with AnyReader([recording[0]]) as reader:
        types = reader.typestore
        assert "sensor_msgs/msg/Imu" in types.fielddefs
        for name in types.fielddefs:
            # The RIHS01 hash is of the fields' names and types, nested types included.
            assert types.hash_rihs01(name) == jazzy.hash_rihs01(name), name


def test_every_message_decodes_and_encodes_back_to_its_bytes(recording):
    path, summary, imu, camera = recording
    decoded: dict[str, list] = {}
    with AnyReader([path]) as reader:
        for connection, timestamp, data in reader.messages():
            message = reader.deserialize(data, connection.msgtype)
            again = reader.typestore.serialize_cdr(message, connection.msgtype)
            assert bytes(again) == bytes(data), (connection.topic, timestamp)
            decoded.setdefault(connection.topic, []).append((timestamp, message))
    assert {t: len(m) for t, m in decoded.items()} == {
        t: n for t, n in summary["messages"].items() if n
    }
    # The IMU's records in its ROS axes ((x, y, z) of ARS is (x, -z, y)), at their times.
    records = imu.records()
    assert len(decoded["/imu"]) == len(records) == round(DURATION / 0.01)
    for (timestamp, message), record in zip(decoded["/imu"], records):
        stamp = message.header.stamp
        assert stamp.sec * 1_000_000_000 + stamp.nanosec == timestamp == round(record["time"] * 1e9)
        assert message.header.frame_id == "imu"
        force, rate = message.linear_acceleration, message.angular_velocity
        fx, fy, fz = (record[f"f{axis} [m/s^2]"] for axis in "xyz")
        gx, gy, gz = (record[f"g{axis} [rad/s]"] for axis in "xyz")
        assert (force.x, force.y, force.z) == (fx, -fz, fy)
        assert (rate.x, rate.y, rate.z) == (gx, -gz, gy)
    # Depth images: 32FC1 rows of the camera's size, the same times as their infos.
    images, infos = decoded["/camera/depth/image_raw"], decoded["/camera/depth/camera_info"]
    assert [t for t, _ in images] == [t for t, _ in infos]
    for (_, image), (_, info) in zip(images, infos):
        assert (image.height, image.width, image.encoding) == (12, 16, "32FC1")
        assert (info.height, info.width) == (12, 16)
        assert image.step == 16 * 4 and len(image.data) == 12 * 16 * 4
        assert image.header.frame_id == info.header.frame_id == "camera_optical"
    # The pixels are the camera's records, row after row, bit for bit.
    records = camera.images()
    assert len(images) == len(records)
    for (_, image), record in zip(images, records):
        pixels = np.frombuffer(bytes(image.data), dtype="<f4").reshape(12, 16)
        np.testing.assert_array_equal(pixels, record)
    assert np.isfinite(records).any(), "the camera sees the floor or the wall"
