"""Sweep the conical pendulum's driving torque and plot where it settles.

For each saturation torque of the waist (the thesis' 20 N·m among them), the pendulum
runs 20 s; the steady waist rate and cone angle (the shoulder's angle from hanging) are
the means over the last second. The plot goes to ``conical_pendulum_sweep.png``.

    python sweep_conical_pendulum.py [serial|processes|ray] [OUTPUT.png]

Needs matplotlib (``pip install matplotlib``) for the plot; the numbers are printed
either way. On a Ray cluster, set ``RAY_ADDRESS`` (or start one: ``ray start --head``
here, ``ray start --address=HEAD:6379`` on the other machines) and run with ``ray``.
"""

import math
import sys
from typing import Any

import numpy as np

import ars

TORQUES = [5.0, 10.0, 15.0, 20.0, 25.0, 30.0, 35.0, 40.0]
DURATION = 20.0


def conical_pendulum(params: dict[str, Any]) -> ars.Simulation:
    """IROS example 2 with the waist torque ramping to ``params["torque"]`` in 1 s and
    viscous friction 5 N·m·s/rad on both joints, all driven in native code."""
    sim = ars.Simulation(time_step=1.0 / 50 / 80, steps_per_frame=80)
    sim.add_floor((0.0, 1.0, 0.0), -0.5)
    base = sim.add_box((10.0, 0.5, 10.0), (1.0, -0.25, 2.0), density=100.0)
    pole = sim.add_cylinder(1.0, 0.141421, (0.0, 0.51, 0.0), mass=10.0)
    arm = sim.add_cylinder(1.0, 0.141421, (0.0, 0.51, 0.1), mass=10.0)
    for link in (pole, arm):
        sim.body(link).rotate((1.0, 0.0, 0.0), math.pi / 2)
        sim.body(link).offset_by_position((1.0, 0.0, 2.0))
    sim.add_rotary_joint("r1", base, pole, None, (0.0, 1.0, 0.0))
    sim.add_rotary_joint("r2", pole, arm, (1.0, 1.01, 2.1), (1.0, 0.0, 0.0))
    sim.joint("r1").set_controller("torque", [(0.0, 0.0), (1.0, params["torque"])])
    sim.joint("r1").set_viscous_friction(5.0)
    sim.joint("r2").set_viscous_friction(5.0)
    return sim


def steady(runs: ars.SweepResults) -> tuple[list[float], list[float]]:
    """The means over the last second: waist rate (rad/s) and cone angle (rad)."""
    rates: list[float] = []
    angles: list[float] = []
    for run in runs:
        last = run.table[run.table["time"] > DURATION - 1.0]
        rates.append(float(np.mean(last["r1.rate"])))
        angles.append(float(np.mean(np.abs(last["r2.angle"]))))
    return rates, angles


def main() -> None:
    backend = sys.argv[1] if len(sys.argv) > 1 else "serial"
    output = sys.argv[2] if len(sys.argv) > 2 else "conical_pendulum_sweep.png"
    runs = ars.sweep(
        conical_pendulum,
        [{"torque": t} for t in TORQUES],
        duration=DURATION,
        record=["r1.rate", "r2.angle"],
        every=40,
        backend=backend,
    )
    for i, error in runs.errors:
        print(f"run {i} failed: {error!r}")
    rates, angles = steady(runs)
    print("torque [N m]  waist rate [rad/s]  cone angle [rad]")
    for t, w, q in zip(TORQUES, rates, angles):
        print(f"{t:12.1f}  {w:18.5f}  {q:16.5f}")
    try:
        import matplotlib  # type: ignore[import-not-found, unused-ignore]

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt  # type: ignore[import-not-found, unused-ignore]
    except ImportError:
        print("matplotlib is not installed: no plot (pip install matplotlib)")
        return
    fig, left = plt.subplots(figsize=(7, 4.5))
    left.plot(TORQUES, rates, "o-", color="tab:blue")
    left.set_xlabel("waist torque [N m]")
    left.set_ylabel("steady waist rate [rad/s]", color="tab:blue")
    right = left.twinx()
    right.plot(TORQUES, angles, "s--", color="tab:red")
    right.set_ylabel("steady cone angle [rad]", color="tab:red")
    left.set_title("Conical pendulum: where it settles, by driving torque")
    fig.tight_layout()
    fig.savefig(output, dpi=120)
    print(f"wrote {output}")


if __name__ == "__main__":
    main()
