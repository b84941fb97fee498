"""How fast ARS for Python is, as ratios measured in one run (issue 14):

1. ``sim.run`` of the conical pendulum built in Python (drives in native code) against
   the Rust example ``conical_pendulum`` over the same simulated time;
2. the cost of a Python pre-step hook, per step;
3. the original ARS 0.5b1 on Debian's PyODE against ours, on its IROS examples 2
   and 3 (the same printed output, checked here too);
4. a sweep of 8 pendulum runs on a local Ray with 2 CPUs against the serial sweep.

Run from the repository root after ``make python`` (and ``cargo build --release
--example conical_pendulum``): ``.venv/bin/python python/bench/bench.py``.
"""

import pathlib
import subprocess
import sys
import tempfile
import time

import ars

REPO = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO / "python" / "tests"))
sys.path.insert(0, str(REPO / "python" / "examples"))
import original_ars
from sweep_conical_pendulum import conical_pendulum


def best_of(n, fn):
    times = []
    for _ in range(n):
        start = time.perf_counter()
        fn()
        times.append(time.perf_counter() - start)
    return min(times)


def pendulum(params=None):
    """The thesis' conical pendulum with its drives in native code (the sweep example's)."""
    return conical_pendulum(params or {"torque": 20.0})


def rust_against_python(seconds=60.0):
    binary = REPO / "target" / "release" / "examples" / "conical_pendulum"
    if not binary.is_file():
        subprocess.run(
            ["cargo", "build", "--release", "--quiet", "--example", "conical_pendulum"],
            cwd=REPO,
            check=True,
        )
    rust = best_of(
        3,
        lambda: subprocess.run(
            [binary, "--duration", str(seconds)], check=True, capture_output=True
        ),
    )
    python = best_of(3, lambda: pendulum().run(seconds))
    print(
        f"1. conical pendulum, {seconds:g} s simulated: Rust example {rust:.3f} s, Python sim.run {python:.3f} s, "
        f"ratio {python / rust:.3f}"
    )


def hook_cost(steps=200_000):
    def scene():
        sim = ars.Simulation()
        sim.add_floor()
        sim.add_sphere(0.1, (0.0, 0.1, 0.0), mass=1.0)
        return sim

    plain = best_of(3, lambda: scene().step(steps))

    def hooked():
        sim = scene()
        sim.add_pre_step(lambda: None)
        sim.step(steps)

    with_hook = best_of(3, hooked)
    print(
        f"2. a Python pre-step hook: {(with_hook - plain) / steps * 1e6:.2f} µs per step "
        f"({plain / steps * 1e6:.2f} µs per step without)"
    )


def original_against_ours():
    with tempfile.TemporaryDirectory() as work:
        for module, name, seconds in [
            ("IROS.example2_conical_pendulum", "Example2", 20.0),
            ("IROS.example3_speed_profile", "Example3", 15.0),
        ]:
            runs = {}
            for who, run in [
                ("original", original_ars.run_original),
                ("ours", original_ars.run_ours),
            ]:
                run(module, name, 0.02, work)  # warm the caches (imports, sdist)
                start = time.perf_counter()
                runs[who] = run(module, name, seconds, work)
                runs[who + " s"] = time.perf_counter() - start
            same = runs["original"].stdout == runs["ours"].stdout
            print(
                f"3. {name}, {seconds:g} s simulated ({runs['ours'].stdout.count(chr(10))} lines, "
                f"{'the same' if same else 'DIFFERENT'} output): original on PyODE {runs['original s']:.2f} s, "
                f"ours {runs['ours s']:.2f} s, {runs['original s'] / runs['ours s']:.1f}× faster"
            )


def sweep_on_ray(seconds=20.0):
    params = [{"torque": 5.0 * (i + 1)} for i in range(8)]
    start = time.perf_counter()
    serial = ars.sweep(pendulum, params, duration=seconds, record=["r1.rate"], every=400)
    serial_s = time.perf_counter() - start
    start = time.perf_counter()
    on_ray = ars.sweep(
        pendulum, params, duration=seconds, record=["r1.rate"], every=400, backend="ray", workers=2
    )
    ray_s = time.perf_counter() - start
    same = all(a.table.tobytes() == b.table.tobytes() for a, b in zip(serial, on_ray))
    print(
        f"4. sweep of 8 × {seconds:g} s: serial {serial_s:.2f} s, Ray on 2 CPUs {ray_s:.2f} s "
        f"(with its start and stop), ratio {ray_s / serial_s:.2f}, {'bit-identical' if same else 'DIFFERENT'}"
    )


if __name__ == "__main__":
    rust_against_python()
    hook_cost()
    original_against_ours()
    sweep_on_ray()
