"""A ball rolls off a ramp; a hinge servo swings a paddle; a sensor records the ball.

    python hello.py

Typed throughout: ``mypy --strict`` checks it against the package's stubs
(``python/tests/test_docs.py``).
"""

import math

import numpy as np
import numpy.typing as npt

import ars


def build() -> ars.Simulation:
    """The scene: a floor, a tilted box as a ramp, a ball on it, a paddle on a hinge."""
    sim = ars.Simulation()
    sim.add_floor()
    ramp = sim.add_box((1.0, 0.05, 0.4), (0.0, 0.3, 0.0), mass=1.0, name="ramp")
    sim.body(ramp).rotate((0.0, 0.0, 1.0), -0.3)
    sim.add_fixed_joint("ramp_fixed", ramp, None)
    sim.add_sphere(0.05, (-0.4, 0.5, 0.0), mass=0.1, name="ball")
    sim.add_box((0.02, 0.2, 0.3), (1.0, 0.15, 0.0), mass=0.5, name="paddle")
    sim.add_rotary_joint("hinge", "paddle", None, (1.0, 0.25, 0.0), (0.0, 0.0, 1.0))
    # The paddle's inertia about the hinge is about 0.5·0.2²/3 = 0.0067 kg·m²: with
    # dt = 0.4 ms, kd below I/dt = 17 and kp below kd²/(4·I) keep the servo stable.
    sim.joint("hinge").set_controller("position", [(0.0, 0.0), (1.0, math.pi / 4)], kp=20.0, kd=1.0)
    return sim


def main() -> None:
    sim = build()
    gps = sim.add_sensor("gps", "ball", every=0.1)
    sim.run(1.5)
    records: npt.NDArray[np.void] = gps.records()
    print(f"{len(records)} records; the ball at {sim.body('ball').position.round(3)}")
    print(f"the paddle at {sim.joint('hinge').angle:.3f} rad (set-point {math.pi / 4:.3f})")


if __name__ == "__main__":
    main()
