"""Checks that this installation computes the same bits as ours.

    python -m ars.verify            # about 10 s: prints a report, exit status 1 if any differs
    python -m ars.verify --write ars-programs/golden.json   # (developers) record this machine's

Runs the golden runs of the Rust programs (the thesis programs, a URDF arm, seeded noisy
sensors: ``ars_programs::golden``) and a program written in the original ARS API, and
compares each output with the sha256 table compiled into the package: each is
"identical", or the report says where it first differs. The report names the platform
(libode, CPU, C library) and the build of ARS.
"""

from __future__ import annotations

import io
import json
import sys
import time
from typing import Any

from ars import _native

#: The golden run of this module's own program.
PYTHON_RUN = "python_original_api"
PYTHON_RUN_WHAT = (
    "an arm in the original ARS API, printing its joint rates, tip and energy every step"
)
PYTHON_RUN_DURATION = 2.0


def original_api_output(duration: float = PYTHON_RUN_DURATION) -> bytes:
    """The output of a program written in the original ARS API (``ars.app.Program``):
    a two-link arm under a waist torque and gravity, its joint rates, the position of
    its lower link and the system's energy printed (``repr``) after every step. Bytes
    of CSV.

    It prints no joint angle: ODE computes an angle with the C library's ``atan2``,
    and glibc picks one of four versions of it by CPU (FMA, FMA4, AVX, SSE2) that
    disagree in the last bit on rare arguments, so an angle is not the same bits on
    every machine although the state it is computed from is. Rates, positions and
    energy are sums and products of that state."""
    import ars.constants as cts
    from ars.app import Program, dispatcher
    from ars.model.robot import sensors
    from ars.model.simulator import signals

    out = io.StringIO()

    class Arm(Program):
        FPS = 50
        STEPS_PER_FRAME = 50

        def __init__(self) -> None:
            Program.__init__(self)
            dispatcher.connect(self.on_pre_step, signals.SIM_PRE_STEP)
            dispatcher.connect(self.on_post_step, signals.SIM_POST_STEP)

        def create_sim_objects(self) -> None:
            sim = self.sim
            base = sim.add_box((0.2, 0.2, 0.2), (0.0, 1.0, 0.0), mass=5.0)
            upper = sim.add_capsule(0.5, 0.05, (0.0, 1.35, 0.0), mass=1.0)
            lower = sim.add_capsule(0.5, 0.05, (0.0, 1.95, 0.0), mass=0.5)
            sim.add_fixed_joint("fixed", sim.get_object(base), None)
            sim.add_rotary_joint(
                "waist", sim.get_object(base), sim.get_object(upper), (0.0, 1.1, 0.0), cts.Y_AXIS
            )
            sim.add_rotary_joint(
                "elbow", sim.get_object(upper), sim.get_object(lower), (0.0, 1.65, 0.0), cts.Z_AXIS
            )
            self.energy = sensors.SystemTotalEnergy(sim)
            self.tip = sim.get_object(lower)
            out.write("time,waist rate,elbow rate,lower x,lower y,lower z,energy\n")

        def on_pre_step(self) -> None:
            # The waist turns the arm; the elbow is pushed off its balance for 0.1 s.
            self.sim.get_joint("waist").joint.add_torque(0.5)
            if self.sim.sim_time < 0.1:
                self.sim.get_joint("elbow").joint.add_torque(0.2)

        def on_post_step(self) -> None:
            sim = self.sim
            waist, elbow = sim.get_joint("waist").joint, sim.get_joint("elbow").joint
            values = (sim.sim_time, waist.angle_rate, elbow.angle_rate, *self.tip.get_position())
            out.write(",".join(repr(float(v)) for v in values))
            energy = self.energy.get_measurement().get_kwarg("total energy")
            out.write(f",{float(energy)!r}\n")

    Arm().run(duration)
    return out.getvalue().encode()


def report(table: str | None = None) -> tuple[list[str], int]:
    """Runs every golden run; returns the report's lines and how many differ.
    ``table``: JSON text of another table (the compiled-in one by default)."""
    p = _native._platform()
    first = (
        f"ARS {p['ars_version']} (commit {p['ars_commit']}) on libode {p['libode_version']} "
        f"({p['libode_configuration']}), {p['cpu']}, {p['libc']}, {p['os']}"
    )
    lines = [first]
    different = 0
    runs: list[tuple[str, float, Any]] = [
        (name, duration, lambda name=name: _native._golden_output(name))
        for name, _, duration in _native._golden_runs()
    ]
    runs.append((PYTHON_RUN, PYTHON_RUN_DURATION, original_api_output))
    for name, duration, output in runs:
        start = time.perf_counter()
        verdict = _native._golden_compare(name, output(), table)
        lines.append(
            f"  {name:<22} {duration:>5g} s simulated, {time.perf_counter() - start:5.1f} s: {verdict}"
        )
        different += verdict != "identical"
    return lines, different


def write(path: str) -> None:
    """Puts this machine's output of the Python run into the table file at ``path``
    (the Rust runs are written by ``cargo run --release --example verify -- --write``)."""
    with open(path) as f:
        text = f.read()
    text = _native._golden_with(PYTHON_RUN, PYTHON_RUN_DURATION, original_api_output(), text)
    json.loads(text)  # written only if it is a table
    with open(path, "w") as f:
        f.write(text)


def main(argv: list[str] | None = None) -> int:
    args = sys.argv[1:] if argv is None else argv
    if args[:1] == ["--write"] and len(args) == 2:
        write(args[1])
        print(f"wrote {PYTHON_RUN} into {args[1]}")
        return 0
    if args:
        print(__doc__, file=sys.stderr)
        return 2
    lines, different = report()
    print("\n".join(lines))
    if different:
        print(
            f"{different} of the golden runs differ from the table: see the README's 'The same bits everywhere'"
        )
        return 1
    print("every golden run is identical to the table")
    return 0


if __name__ == "__main__":
    sys.exit(main())
