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


# Where a step of an original program goes in our package, measured inside one process:
# 1. the run as it is;
# 2. the run again, timing the program's own pre-step method (its Python, with the calls
#    it makes into ours) apart from the rest (the native steps: physics, the same ODE
#    calls as the original's, and our hooks);
# 3. the run again, untimed, noting the torques it puts (apart from 2: noting costs a
#    Python call per torque, inside the pre-step method);
# 4. the floor in place: a new program whose pre-step puts those torques again (the same
#    calls in the same order: the same bits, checked on every body's final position) and
#    then runs the program's pre-step method on stand-ins of the simulation, its joints
#    and its bodies (C-level callables and plain attributes), which no implementation of
#    ours can beat. It is what ours would take if every call into it cost nothing, give
#    or take the torque calls and the hook that puts them: those are ours (about 0.3 µs
#    a step for four torques), so the floor is slightly high;
# 5. the program's pre-step method on the stand-ins in a loop of its own (its Python in
#    hot caches, without physics between).
# Printed as one line of numbers.
_BREAKDOWN = """
import importlib, itertools, os, sys, time, timeit
start = time.perf_counter()
import ars  # noqa: F401
from ars.app import dispatcher
from ars.model.simulator import signals
imported = time.perf_counter() - start
module, name, seconds = sys.argv[1], sys.argv[2], float(sys.argv[3])
cls = getattr(importlib.import_module("demos." + module), name)
stdout, sys.stdout = sys.stdout, open(os.devnull, "w")

def positions(program):
    return [o.get_position() for o in program.sim._objects.values() if hasattr(o, "body")]

def timed_run(program):
    begin = time.perf_counter()
    program.run(seconds)
    return time.perf_counter() - begin

program = cls()
run = timed_run(program)
final = positions(program)

spent = [0.0]
on_pre_step = cls.on_pre_step

def timed(self):
    begin = time.perf_counter()
    on_pre_step(self)
    spent[0] += time.perf_counter() - begin

cls.on_pre_step = timed
parts = timed_run(cls())
cls.on_pre_step = on_pre_step

torques = []
program = cls()
for joint_name, joint in program.sim._joints.items():
    def noting(torque, put=joint.add_torque, joint_name=joint_name):
        torques.append((joint_name, torque, program.sim.native.step_count))
        put(torque)
    joint.add_torque = noting
program.run(seconds)
steps = program.sim.native.step_count

# The stand-ins.
class Joint:
    angle, angle_rate = 0.1, 0.2

class SimJoint:
    __slots__ = ("joint", "add_torque")

class Body:
    __slots__ = ("get_position", "get_linear_velocity")

joint = SimJoint()
joint.joint, joint.add_torque = Joint(), [].append
body = Body()
body.get_position = body.get_linear_velocity = itertools.repeat((1.0, 2.0, 3.0)).__next__

class StandIn:
    sim_time = 0.5
    get_joint = dict.fromkeys(("r1", "r2", "w1", "w2"), joint).__getitem__
    get_object = {getattr(program, "chassis", None): body}.__getitem__

# 4: the same torques, each put by the same native call as before, step by step.
again = cls()
by_step = [[] for _ in range(steps)]
for joint_name, torque, step in torques:
    by_step[step].append((again.sim.get_joint(joint_name).add_torque, torque))
dispatcher.disconnect(again.on_pre_step, signals.SIM_PRE_STEP)
puts = iter(by_step).__next__
on_stand_ins = program.on_pre_step
program.sim = StandIn()

def pre_step():
    for put, torque in puts():
        put(torque)
    joint.add_torque = [].append
    on_stand_ins()

dispatcher.connect(pre_step, signals.SIM_PRE_STEP)
floor_run = timed_run(again)
same = bool(final) and positions(again) == final

calls = 20000
alone = min(timeit.repeat(on_stand_ins, number=calls, repeat=5)) / calls
sys.stdout = stdout
print(imported, run, parts, spent[0], steps, floor_run, int(same), alone)
"""


def breakdown(module, name, seconds, work):
    """The breakdown's line, and what the run's own calls into ours cost in all (s)."""
    out = subprocess.run(
        [sys.executable, "-c", _BREAKDOWN, module, name, str(seconds)],
        cwd=original_ars.demos_only(work),
        env=dict(os.environ, PYTHONPATH=str(original_ars.demos_only(work))),
        capture_output=True,
        text=True,
        check=True,
    )
    imported, run, parts, program, steps, floor, same, alone = map(float, out.stdout.split())
    per = 1e6 / steps
    line = (
        f"   in one process: importing ars {imported:.2f} s; the run {run:.3f} s; timed in parts: "
        f"the program's on_pre_step {program * per:.1f} µs/step (its Python and the calls it "
        f"makes into ours), the native steps {(parts - program) * per:.1f} µs/step (physics, "
        f"the same ODE calls as the original's, and our hooks); the floor in place, the same "
        f"physics with the program's Python on stand-ins: {floor:.3f} s "
        f"({'the same bits' if same else 'DIFFERENT BITS'}), so calls into ours cost "
        f"{(run - floor) * per:.1f} µs/step; the program's Python alone: {alone * 1e6:.1f} µs/step"
    )
    return line, run - floor


def interpreters():
    """``(ours, the original's)``: the interpreter each runs on, its path and version. Ours
    is this one (a virtual environment's is its base's), the original's Debian's, which
    has PyODE."""
    probe = "import os, sys; print(os.path.realpath(sys.executable), sys.version.split()[0])"
    original = subprocess.run(
        [original_ars.ORIGINAL_PYTHON, "-c", probe], capture_output=True, text=True, check=True
    ).stdout.split()
    ours = [os.path.realpath(getattr(sys, "_base_executable", sys.executable))]
    return " ".join(ours + [sys.version.split()[0]]), " ".join(original)


def original_against_ours():
    # On one interpreter: another build of the same Python version (pyenv's, say: no
    # profile-guided optimisation, libpython a shared library) ran our example 3 8%
    # slower than Debian's. Make the virtual environment from Debian's python3, as
    # `make python` does on a fresh Debian machine.
    ours, original = interpreters()
    if ours != original:
        print(
            f"3. NOT LIKE FOR LIKE: ours runs on {ours}, the original on {original}; "
            f"make .venv with {original_ars.ORIGINAL_PYTHON} -m venv"
        )
    # As a user runs them: Python's default output buffering (PYTHONUNBUFFERED, set in
    # some shells, makes every print two system calls in both, about 0.4 s here).
    env = {k: v for k, v in os.environ.items() if k != "PYTHONUNBUFFERED"}
    with tempfile.TemporaryDirectory() as work:
        for module, name, seconds in [
            ("IROS.example2_conical_pendulum", "Example2", 20.0),
            ("IROS.example3_speed_profile", "Example3", 15.0),
        ]:
            runs, times = {}, {}
            for who, run in [
                ("original", original_ars.run_original),
                ("ours", original_ars.run_ours),
            ]:
                run(module, name, 0.02, work, env=env)  # warm the caches (imports, sdist)
            # Three runs each, interleaved, each in a new process; the medians.
            for _ in range(3):
                for who, run in [
                    ("original", original_ars.run_original),
                    ("ours", original_ars.run_ours),
                ]:
                    start = time.perf_counter()
                    runs[who] = run(module, name, seconds, work, env=env)
                    times.setdefault(who, []).append(time.perf_counter() - start)
            original, ours = (sorted(times[w])[1] for w in ("original", "ours"))
            same = runs["original"].stdout == runs["ours"].stdout
            print(
                f"3. {name}, {seconds:g} s simulated ({runs['ours'].stdout.count(chr(10))} lines, "
                f"{'the same' if same else 'DIFFERENT'} output): original on PyODE {original:.2f} s, "
                f"ours {ours:.2f} s, original/ours {original / ours:.2f} (medians of three)"
            )
            line, calls = breakdown(module, name, seconds, work)
            print(line)
            print(
                f"   with every call into ours free (ours less {calls:.3f} s): original/ours "
                f"{original / (ours - calls):.2f}, the most any implementation of ours could reach"
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
