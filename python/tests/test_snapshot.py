"""Exact snapshots from Python: restored in the same simulation, in a fresh one built by
the same code, from the bytes alone and in another process, every later step is the
same to the bit; bad snapshots raise their own classes and change nothing."""

import math
import pickle
import subprocess
import sys

import numpy as np
import pytest

import ars


def build():
    """A floor, a ball, a servoed paddle on a hinge and a noisy-free GPS."""
    sim = ars.Simulation()
    sim.add_floor()
    sim.add_sphere(0.05, (-0.2, 0.5, 0.0), mass=0.1, name="ball")
    sim.add_box((0.02, 0.2, 0.3), (0.3, 0.15, 0.0), mass=0.5, name="paddle")
    sim.add_rotary_joint("hinge", "paddle", None, (0.3, 0.25, 0.0), (0.0, 0.0, 1.0))
    setpoint = [(0.0, 0.0), (1.0, math.pi / 4)]
    sim.joint("hinge").set_controller("position", setpoint, kp=20.0, kd=1.0)
    sim.add_sensor("gps", "ball", every=0.01)
    return sim


def state_bits(sim):
    """Every object's position and velocity, as bytes."""
    parts = []
    for name in ("ball", "paddle"):
        body = sim.body(name)
        parts += [body.position, body.linear_velocity, body.angular_velocity]
    return np.concatenate(parts).tobytes()


def test_restores_are_exact_in_place_in_a_fresh_simulation_and_from_bytes():
    sim = build()
    sim.step(1234)
    state = sim.snapshot()
    assert isinstance(state, bytes)
    sim.step(2000)
    expected = state_bits(sim)
    for target in (sim, build()):
        target.restore(state)
        assert target.step_count == 1234
        target.step(2000)
        assert state_bits(target) == expected
    copy = ars.Simulation.from_snapshot(pickle.loads(pickle.dumps(state)))
    copy.step(2000)
    assert state_bits(copy) == expected


def test_a_snapshot_restores_in_another_process(tmp_path):
    sim = build()
    sim.step(777)
    path = tmp_path / "state.bin"
    path.write_bytes(sim.snapshot())
    sim.step(1000)
    script = (
        "import sys, ars\n"
        "sim = ars.Simulation.from_snapshot(open(sys.argv[1], 'rb').read())\n"
        "sim.step(1000)\n"
        "b = sim.body('ball')\n"
        "sys.stdout.buffer.write(b.position.tobytes() + b.linear_velocity.tobytes())\n"
    )
    out = subprocess.run([sys.executable, "-c", script, str(path)], capture_output=True, check=True)
    ball = sim.body("ball")
    assert out.stdout == ball.position.tobytes() + ball.linear_velocity.tobytes()


def test_bad_snapshots_raise_their_own_classes_and_change_nothing():
    sim = build()
    sim.step(100)
    state = sim.snapshot()
    before = state_bits(sim)
    other = ars.Simulation()
    other.add_sphere(0.1, (0.0, 1.0, 0.0), mass=1.0, name="lonely")
    with pytest.raises(ars.SnapshotMismatchError):
        sim.restore(other.snapshot())
    with pytest.raises(ars.SnapshotCorruptError):
        sim.restore(state[:-5])
    with pytest.raises(ValueError):
        sim.restore(b"not a snapshot")
    altered = bytearray(state)
    altered[8] = 42
    with pytest.raises(ars.SnapshotVersionError):
        sim.restore(bytes(altered))
    assert issubclass(ars.SnapshotMismatchError, ars.SnapshotError)
    assert state_bits(sim) == before
    sim.step()
