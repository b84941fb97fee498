"""The original ARS 0.5b1 programs, unedited, on this package: every demo of its
``demo_runner.py`` imports and runs headless; the IROS examples 2 and 3 print, line
for line, what the original prints on Debian's PyODE over the same libode; and every
demo the original can run there prints what it prints once two bugs of that PyODE are
fixed (see ``original_ars.BINDING_FIXES``; without them spheres given by mass weigh
what a density would, and motors have no force)."""

import json
import subprocess
import sys
import time

import original_ars
import pytest
from conftest import window_env

DEMOS = original_ars.demos()


@pytest.fixture(scope="module")
def workdir(tmp_path_factory):
    return tmp_path_factory.mktemp("original-ars")


@pytest.mark.parametrize(("module", "name"), DEMOS, ids=[f"{m}.{n}" for m, n in DEMOS])
def test_every_demo_runs_headless_unedited(module, name, workdir):
    start = time.perf_counter()
    run = original_ars.run_ours(module, name, 1.0, workdir)
    elapsed = time.perf_counter() - start
    assert run.returncode == 0, run.stderr[-3000:]
    # No handler failed (the demos log their handlers' exceptions with a traceback).
    assert "Traceback" not in run.stderr, run.stderr[-3000:]
    print(f"{module}.{name}: 1 s simulated in {elapsed:.2f} s, {run.stdout.count(chr(10))} lines")


# Every demo in ARS's window, one after the other in one interpreter (as the original's
# demo runner opens them), each for WINDOW_FRAMES frames (a number of frames, not of
# seconds: a loaded machine may take longer than a wall-time budget to draw its first).
WINDOW_FRAMES = 10
IN_WINDOWS = """
import importlib, json, sys
shown = []
for module, name in json.loads(sys.argv[1]):
    program = getattr(importlib.import_module("demos." + module), name)()
    report = program.show(frames=int(sys.argv[2]))
    shown.append([module, report["frames_drawn"], program.sim.sim_time, program.FPS, report["wall_seconds"]])
print(json.dumps(shown))
"""


def test_every_demo_shows_in_a_window_unedited(display, workdir, tmp_path):
    run = subprocess.run(
        [sys.executable, "-c", IN_WINDOWS, json.dumps(DEMOS), str(WINDOW_FRAMES)],
        cwd=original_ars.demos_only(workdir),
        env=window_env(display, tmp_path),
        capture_output=True,
        text=True,
        timeout=600,
        check=False,
    )
    assert run.returncode == 0, run.stderr[-3000:]
    assert "Traceback" not in run.stderr, run.stderr[-3000:]
    shown = json.loads(run.stdout.splitlines()[-1])
    assert [m for m, *_ in shown] == [m for m, _ in DEMOS]
    for module, frames, simulated, fps, wall in shown:
        # Each drew its first frame and its last (paced in real time, a frame drawn
        # may follow several frames of simulation, or none), and ran exactly its
        # frames of simulation (a frame is 1/FPS of simulated time).
        assert frames >= 2, (module, frames)
        assert simulated == pytest.approx(WINDOW_FRAMES / fps, rel=1e-9), (module, simulated)
        print(f"{module}: {frames} frames, {simulated:.2f} s simulated in {wall:.2f} s")


@pytest.mark.parametrize(
    ("module", "name", "seconds"),
    [
        ("IROS.example2_conical_pendulum", "Example2", 20.0),
        ("IROS.example3_speed_profile", "Example3", 15.0),
    ],
)
def test_the_iros_examples_print_what_the_original_prints(module, name, seconds, workdir):
    original = original_ars.run_original(module, name, seconds, workdir)
    assert original.returncode == 0, original.stderr[-3000:]
    ours = original_ars.run_ours(module, name, seconds, workdir)
    assert ours.returncode == 0, ours.stderr[-3000:]
    expected, got = original.stdout.splitlines(), ours.stdout.splitlines()
    assert len(expected) == len(got) > 4000 * seconds
    differing = [i for i, (a, b) in enumerate(zip(expected, got)) if a != b]
    assert not differing, (
        f"{len(differing)} lines differ, the first: {expected[differing[0]]!r} vs {got[differing[0]]!r}"
    )


# Debian's PyODE is built without trimeshes: the original cannot run example 4.
NO_TRIMESH = {
    "IROS.example4_sinusoidal_terrain",
    "IROS.example4b_sinusoidal_terrain_with_screenshot_recorder",
}


@pytest.mark.parametrize(
    ("module", "name"),
    [d for d in DEMOS if d[0] not in NO_TRIMESH],
    ids=[f"{m}.{n}" for m, n in DEMOS if m not in NO_TRIMESH],
)
def test_every_demo_prints_what_the_original_prints_on_correct_bindings(module, name, workdir):
    original = original_ars.run_original(module, name, 1.0, workdir, fixed_bindings=True)
    assert original.returncode == 0, original.stderr[-3000:]
    ours = original_ars.run_ours(module, name, 1.0, workdir)
    assert ours.returncode == 0, ours.stderr[-3000:]
    assert ours.stdout.splitlines() == original.stdout.splitlines()


def test_example_4_prints_what_the_rust_program_computes(workdir, rust_example):
    # The original cannot run it on Debian's PyODE (no trimeshes): the reference is the
    # thesis program in Rust (ars-programs' SinusoidalTerrain), every value of whose
    # CSV, printed as the demo prints it, must be the demo's line.
    seconds = 2.0
    ours = original_ars.run_ours("IROS.example4_sinusoidal_terrain", "Example4", seconds, workdir)
    assert ours.returncode == 0, ours.stderr[-3000:]
    table = rust_example("sinusoidal_terrain", "--duration", str(seconds))
    header, rows = table[0], table[1:]
    columns = [
        "time [s]",
        "x [m]",
        "y [m]",
        "z [m]",
        "q1 [rad]",
        "torque1 [N m]",
        "q2 [rad]",
        "torque2 [N m]",
    ]
    at = [header.index(c) for c in columns] + [header.index("wheel torque [N m]")]
    expected = ["\t".join(f"{float(row[i]):.7e}" for i in at) for row in rows]
    got = ours.stdout.splitlines()
    assert len(got) == len(expected) == 8000
    differing = [i for i, (a, b) in enumerate(zip(expected, got)) if a != b]
    assert not differing, (
        f"{len(differing)} lines differ, the first: {expected[differing[0]]!r} vs {got[differing[0]]!r}"
    )
