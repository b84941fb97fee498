"""How fast ARS for Python is, as ratios measured in one run (issue 14):

1. ``sim.run`` of the conical pendulum built in Python (drives in native code) against
   the Rust example ``conical_pendulum`` over the same simulated time;
2. the cost of a Python pre-step hook, per step;
3. the original ARS 0.5b1 on Debian's PyODE against ours, on its IROS examples 2
   and 3 (the same printed output, checked here too);
4. a sweep of 8 pendulum runs on a local Ray with 2 CPUs against the serial sweep;
5. off-screen images from Python (``ars.Renderer``, 800×600) of the running pendulum,
   in frames per second, and the share of that time spent drawing.

Run from the repository root after ``make python`` (and ``cargo build --release
--example conical_pendulum``): ``.venv/bin/python python/bench/bench.py``.
"""

import os
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
    target = pathlib.Path(os.environ.get("CARGO_TARGET_DIR", REPO / "target"))
    binary = target / "release" / "examples" / "conical_pendulum"
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
                # The best of three (a 2-core machine is noisy), each in a new process.
                for _ in range(3):
                    start = time.perf_counter()
                    runs[who] = run(module, name, seconds, work)
                    elapsed = time.perf_counter() - start
                    runs[who + " s"] = min(elapsed, runs.get(who + " s", elapsed))
            same = runs["original"].stdout == runs["ours"].stdout
            print(
                f"3. {name}, {seconds:g} s simulated ({runs['ours'].stdout.count(chr(10))} lines, "
                f"{'the same' if same else 'DIFFERENT'} output): original on PyODE {runs['original s']:.2f} s, "
                f"ours {runs['ours s']:.2f} s, {runs['original s'] / runs['ours s']:.1f}× faster"
            )


def sweep_on_ray(seconds=20.0):
    import ray

    params = [{"torque": 5.0 * (i + 1)} for i in range(8)]

    def timed(**backend):
        start = time.perf_counter()
        results = ars.sweep(
            pendulum, params, duration=seconds, record=["r1.rate"], every=400, **backend
        )
        return results, time.perf_counter() - start

    serial, serial_s = timed()
    on_ray, ray_s = timed(backend="ray", workers=2)
    same = all(a.table.tobytes() == b.table.tobytes() for a, b in zip(serial, on_ray))
    print(
        f"4. sweep of 8 × {seconds:g} s: serial {serial_s:.2f} s, Ray on 2 CPUs {ray_s:.2f} s "
        f"(with its start and stop), ratio {ray_s / serial_s:.2f}, {'bit-identical' if same else 'DIFFERENT'}"
    )
    # On a Ray already running, whose workers have run a sweep: what a cluster user sees.
    # (Its workers import this file's module: they get this process's module path.)
    os.environ["PYTHONPATH"] = os.pathsep.join(p for p in sys.path if p and os.path.isdir(p))
    ray.init(num_cpus=2, include_dashboard=False, log_to_driver=False)
    try:
        timed(backend="ray")
        warm, warm_s = timed(backend="ray")
    finally:
        ray.shutdown()
    same = all(a.table.tobytes() == b.table.tobytes() for a, b in zip(serial, warm))
    print(
        f"4. the same on a running Ray with 2 CPUs: {warm_s:.2f} s, ratio {warm_s / serial_s:.2f}, "
        f"{'bit-identical' if same else 'DIFFERENT'}"
    )


def renderer_frames(frames=200):
    sim = pendulum()
    renderer = ars.Renderer(800, 600, camera=(3.0, 2.0, 3.0), look_at=(0.0, 1.0, 0.0))
    renderer.render(sim)  # the scene's meshes are made on the first image
    drawing = 0.0
    start = time.perf_counter()
    for _ in range(frames):
        sim.step(50)
        begin = time.perf_counter()
        renderer.render(sim)
        drawing += time.perf_counter() - begin
    total = time.perf_counter() - start
    print(
        f"5. ars.Renderer 800×600 while the pendulum runs: {frames / total:.1f} frames/s "
        f"({100 * drawing / total:.0f}% of the time drawing and copying the image to numpy)"
    )


if __name__ == "__main__":
    rust_against_python()
    hook_cost()
    original_against_ours()
    sweep_on_ray()
    renderer_frames()
