"""The thesis' conical pendulum (IROS example 2) written with the Python API steps
bit for bit as the Rust program: the float bits of every row of the Rust example's
CSV, not its text."""

import math
import struct

import ars

FPS, STEPS_PER_FRAME = 50.0, 80
FRICTION = 50e-3 * 100.0
MAX_TORQUE, SATURATION_TIME = 20.0, 1.0


def waist_torque(t):
    return MAX_TORQUE * t / SATURATION_TIME if t < SATURATION_TIME else MAX_TORQUE


def conical_pendulum():
    """The pendulum, built as the thesis' example 2 builds it; returns the simulation
    and the list its pre-step hook fills with one row per step."""
    sim = ars.Simulation(time_step=1.0 / FPS / STEPS_PER_FRAME, steps_per_frame=STEPS_PER_FRAME)
    sim.add_floor((0.0, 1.0, 0.0), -0.5)
    offset = (1.0, 0.0, 2.0)
    radius = 0.141421
    base = sim.add_box((10.0, 0.5, 10.0), (1.0, -0.25, 2.0), density=100.0)
    pole = sim.add_cylinder(1.0, radius, (0.0, 0.51, 0.0), mass=10.0)
    arm = sim.add_cylinder(1.0, radius, (0.0, 0.51, 0.1), mass=10.0)
    for link in (pole, arm):
        sim.body(link).rotate((1.0, 0.0, 0.0), math.pi / 2)
        sim.body(link).offset_by_position(offset)
    sim.add_rotary_joint("r1", base, pole, None, (0.0, 1.0, 0.0))
    sim.add_rotary_joint("r2", pole, arm, (1.0, 1.01, 2.1), (1.0, 0.0, 0.0))
    r1, r2 = sim.joint("r1"), sim.joint("r2")
    rows = []
    previous = [0.0, 0.0]

    def pre_step():
        t = sim.time
        torque = waist_torque(t)
        r1.add_torque(torque)
        r1.add_torque(-FRICTION * previous[0])
        r2.add_torque(-FRICTION * previous[1])
        previous[:] = [r1.rate, r2.rate]
        rows.append((t, sim.step_count, r1.angle, r1.rate, r2.angle, r2.rate, torque))

    sim.add_pre_step(pre_step)
    return sim, rows


def bits(x):
    return struct.pack("<d", float(x))


def test_the_python_pendulum_reproduces_the_rust_example_bit_for_bit(rust_example):
    duration = 2.0
    table = rust_example("conical_pendulum", "--duration", str(duration))
    header, expected = table[0], table[1:]
    assert header[:2] == ["time [s]", "step"]
    sim, rows = conical_pendulum()
    sim.run(duration)
    assert len(rows) == len(expected) == 8000
    for got, want in zip(rows, expected):
        assert [bits(x) for x in got] == [bits(x) for x in want], (got, want)
    # It swings out: the shoulder has left the vertical.
    assert abs(rows[-1][4]) > 0.1
