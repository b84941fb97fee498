"""Ctrl-C (SIGINT) stops every long call within 0.5 s with ``KeyboardInterrupt``:
``record_video``, ``save_replay``, ``replay``, ``record_mcap``, ``show``, ``step_many``, a vector
environment's step and a sweep (serial and on processes). Each call runs in a child
process, which is sent SIGINT once the call has started; the child then checks that
no partial file is left and that the simulation steps on."""

import json
import os
import signal
import subprocess
import sys
import textwrap
import threading
import time

import pytest
from conftest import window_env

# The longest a call may go on after SIGINT.
PROMPT = 0.5

# Common to every child: a ball on a floor, and a report of what followed the
# interrupt.
PRELUDE = """
import json, os, sys, time
import ars

def ball_on_a_floor():
    sim = ars.Simulation()
    sim.add_floor()
    sim.add_sphere(0.1, (0.0, 1.0, 0.0), mass=1.0, name="ball")
    return sim

def usable(sim):
    # Stopped between two steps, well short of the end, and it steps on.
    steps = sim.step_count
    sim.step(10)
    return {"steps": steps, "time": sim.time, "stepped_on": sim.step_count == steps + 10}
"""


def interrupt_child(tmp_path, setup, call, after="{}", env=None, wait=0.3, ready=None):
    """Runs `setup` then `call` in a child process (working in `tmp_path`), sends it
    SIGINT `wait` s after the call started (and, if given, `ready()` said it is under
    way), and returns (seconds from SIGINT to the child's KeyboardInterrupt, what
    `after` evaluated to in the child)."""
    # Under a __main__ guard: the processes backend's workers import this script.
    script = (
        PRELUDE
        + textwrap.dedent(setup)
        + textwrap.dedent(f"""
        if __name__ == "__main__":
            print("started", flush=True)
            try:
                {call}
            except KeyboardInterrupt:
                print("interrupted", flush=True)
                print(json.dumps({after}), flush=True)
                sys.exit(0)
            print("finished", flush=True)
        """)
    )
    path = tmp_path / "child.py"
    path.write_text(script)
    child = subprocess.Popen(
        [sys.executable, str(path)],
        cwd=tmp_path,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env={**(env or os.environ), "PYTHONPATH": str(tmp_path)},
    )
    # A call that ignores SIGINT is killed after a while: the test fails, not hangs.
    watchdog = threading.Timer(60.0, child.kill)
    watchdog.start()
    try:
        line = child.stdout.readline()
        assert line == "started\n", line + child.stderr.read()
        time.sleep(wait)
        while ready is not None and not ready() and child.poll() is None:
            time.sleep(0.01)
        assert child.poll() is None, "the call ended before SIGINT: " + child.stderr.read()
        sent = time.monotonic()
        child.send_signal(signal.SIGINT)
        line = child.stdout.readline()
        after = time.monotonic() - sent
        assert line == "interrupted\n", line + child.stdout.read() + child.stderr.read()
        report = json.loads(child.stdout.readline())
        assert child.wait(timeout=30) == 0, child.stderr.read()
        return after, report
    finally:
        watchdog.cancel()
        if child.poll() is None:
            child.kill()
            child.wait()
        child.stdout.close()
        child.stderr.close()


def assert_prompt(after):
    assert after <= PROMPT, f"KeyboardInterrupt came {after:.3f} s after SIGINT"


def only(tmp_path, *names):
    """The folder holds these files and no partial one (the child's script aside)."""
    left = sorted(set(os.listdir(tmp_path)) - {"child.py", "__pycache__"})
    assert left == sorted(names), left


def frames_written(folder):
    """Whether a video's hidden frames file in `folder` holds frames: the renderer
    has started (which takes half a second, more on a busy machine) and the
    recording is under way."""
    return lambda: any(
        p.name.endswith(".frames") and p.stat().st_size > 0 for p in folder.iterdir()
    )


def test_ctrl_c_stops_record_video_and_leaves_no_file(tmp_path):
    after, report = interrupt_child(
        tmp_path,
        "sim = ball_on_a_floor()\n",
        'sim.record_video("long.mp4", 3000.0, size=(64, 48))',
        "usable(sim)",
        ready=frames_written(tmp_path),
    )
    assert_prompt(after)
    only(tmp_path)
    assert report["stepped_on"] and 0 < report["steps"] < 3000 * 2500


def test_ctrl_c_while_record_video_starts_its_renderer_returns_at_once(tmp_path):
    # SIGINT 20 ms after the call began: the renderer is still starting (half a second
    # to seconds on Mesa's software rasteriser), the simulation not yet taken.
    after, report = interrupt_child(
        tmp_path,
        "sim = ball_on_a_floor()\n",
        'sim.record_video("long.mp4", 3000.0, size=(64, 48))',
        "usable(sim)",
        wait=0.02,
    )
    assert_prompt(after)
    only(tmp_path)
    assert report["stepped_on"] and report["steps"] == 0


def test_ctrl_c_stops_a_long_record_video_allowed_with_a_python_hook(tmp_path):
    after, report = interrupt_child(
        tmp_path,
        "sim = ball_on_a_floor()\ncalls = []\nsim.add_pre_step(lambda: calls.append(1))\n",
        'sim.record_video("long.mp4", 1e9, size=(64, 48), allow_long=True)',
        "dict(usable(sim), calls=len(calls))",
        ready=frames_written(tmp_path),
    )
    assert_prompt(after)
    only(tmp_path)
    assert report["stepped_on"] and report["calls"] >= report["steps"] > 0


@pytest.mark.parametrize("call", ["save_replay", "replay"])
def test_ctrl_c_stops_a_replay_and_leaves_no_file(tmp_path, call):
    run = 'sim.save_replay("long.html", 3000.0)' if call == "save_replay" else "sim.replay(3000.0)"
    after, report = interrupt_child(tmp_path, "sim = ball_on_a_floor()\n", run, "usable(sim)")
    assert_prompt(after)
    only(tmp_path)
    assert report["stepped_on"] and 0 < report["steps"] < 3000 * 2500


def test_ctrl_c_stops_record_mcap_and_leaves_no_file(tmp_path):
    after, report = interrupt_child(
        tmp_path,
        "sim = ball_on_a_floor()\n",
        'sim.record_mcap("long.mcap", 3000.0)',
        "usable(sim)",
        ready=lambda: (tmp_path / "long.mcap").exists(),
    )
    assert_prompt(after)
    only(tmp_path)
    assert report["stepped_on"] and 0 < report["steps"] < 3000 * 2500


def test_ctrl_c_stops_step_many(tmp_path):
    after, report = interrupt_child(
        tmp_path,
        "sims = [ball_on_a_floor() for _ in range(3)]\n",
        "ars.step_many(sims, 10**12)",
        "[usable(s) for s in sims]",
    )
    assert_prompt(after)
    assert all(r["stepped_on"] and r["steps"] < 10**12 for r in report)


def test_ctrl_c_stops_step_many_while_the_calling_thread_waits_for_the_pool(tmp_path):
    # Every simulation's hook raises on the calling thread (after 20 ms, for a pool
    # thread to take a simulation meanwhile): the calling thread's share ends within a
    # second, then it waits for the pool's threads, which step on.
    if (os.cpu_count() or 1) < 2:
        pytest.skip("one core: no pool")
    setup = """
    import threading

    class StopHere(Exception):
        pass

    def on_main_only():
        if threading.current_thread() is threading.main_thread():
            time.sleep(0.02)
            raise StopHere

    sims = [ball_on_a_floor() for _ in range(40)]
    for s in sims:
        s.add_pre_step(on_main_only)
    """
    after, report = interrupt_child(
        tmp_path,
        setup,
        "ars.step_many(sims, 10**12)",
        "sorted(s.step_count for s in sims)[-1]",
        wait=1.5,
    )
    assert_prompt(after)
    assert 1 < report < 10**12, "the pool's threads stepped until Ctrl-C"


def test_ctrl_c_stops_a_vector_environment_step(tmp_path):
    pytest.importorskip("gymnasium")
    setup = """
    import numpy as np
    import ars.gym
    from ars.gym.env import float_box

    class Long(ars.gym.ArsEnv):
        frame_skip, actuators = 10**12, ("hinge",)

        def __init__(self, **kwargs):
            self.action_space = float_box([-1.0], [1.0])
            self.observation_space = float_box([-np.inf], [np.inf])
            super().__init__(**kwargs)

        def build(self):
            sim = ars.Simulation()
            sim.add_sphere(0.05, (0.5, 1.0, 0.0), mass=1.0, name="bob")
            sim.add_rotary_joint("hinge", "bob", None, (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))
            return sim

        def observe(self):
            return np.array([self.sim.joint("hinge").angle])

        def reward(self, obs, action):
            return 0.0

    envs = ars.gym.ArsVectorEnv([Long(), Long()])
    envs.reset(seed=0)
    """
    after, report = interrupt_child(
        tmp_path, setup, "envs.step(np.zeros((2, 1)))", "[usable(e.sim) for e in envs.envs]"
    )
    assert_prompt(after)
    assert all(r["stepped_on"] for r in report)


@pytest.mark.parametrize("backend", ["serial", "processes", "ray"])
def test_ctrl_c_stops_a_sweep(tmp_path, backend):
    if backend == "ray":
        pytest.importorskip("ray")
    # Each run leaves a mark when it starts: SIGINT goes once one has (the workers
    # start first: processes are spawned, Ray starts a local cluster in seconds).
    (tmp_path / "started").mkdir()
    (tmp_path / "sweepmodel.py").write_text(
        textwrap.dedent(f"""
        import os
        import ars

        def falling(params):
            open(os.path.join({str(tmp_path / "started")!r}, str(params["height"])), "w").close()
            sim = ars.Simulation()
            sim.add_floor()
            sim.add_sphere(0.1, (0.0, params["height"], 0.0), mass=1.0, name="ball")
            return sim
        """)
    )
    setup = """
    import multiprocessing
    from sweepmodel import falling

    def ray_cpus_freed():
        # Whether every CPU of the local cluster is free again (the tasks ended),
        # within 5 s.
        import ray
        for _ in range(100):
            if ray.available_resources().get("CPU") == ray.cluster_resources().get("CPU"):
                return True
            time.sleep(0.05)
        return False
    """
    call = (
        f"ars.sweep(falling, [{{'height': 1.0}}, {{'height': 2.0}}], duration=1e6, "
        f"backend={backend!r}, workers=2, progress=False)"
    )
    # Ray's workers are not child processes of this one: after Ctrl-C, the cluster's
    # CPUs must all be free again (the tasks cancelled).
    after = "len(multiprocessing.active_children())" if backend != "ray" else "ray_cpus_freed()"
    after, report = interrupt_child(
        tmp_path, setup, call, after, wait=0.1, ready=lambda: any((tmp_path / "started").iterdir())
    )
    assert_prompt(after)
    if backend == "ray":
        assert report is True, "Ray's tasks were left running"
    else:
        assert report == 0, "worker processes were left running"
    only(tmp_path, "sweepmodel.py", "started")


def test_ctrl_c_closes_the_window_of_show(tmp_path, display):
    after, report = interrupt_child(
        tmp_path,
        "sim = ball_on_a_floor()\n",
        "sim.show(size=(160, 120))",
        "usable(sim)",
        env=window_env(display, tmp_path),
        wait=2.0,
    )
    assert_prompt(after)
    assert report["stepped_on"]


@pytest.mark.parametrize("lock_step", [False, True], ids=["real_time", "lock_step"])
def test_ctrl_c_stops_the_ros_bridge_and_gives_the_simulation_back(tmp_path, lock_step):
    # Real time: ready once it steps (a hook leaves a file at the first step). Lock step
    # waits for StepSimulation calls that never come: ready once its node is up.
    setup = """
    sim = ball_on_a_floor()
    sim.add_post_step(lambda: sim.step_count == 1 and open("stepping", "w").close())
    """
    domain = 100 + os.getpid() % 100
    after, report = interrupt_child(
        tmp_path,
        setup,
        f"sim.ros(lock_step={lock_step}, domain_id={domain})",
        "usable(sim)",
        wait=1.5 if lock_step else 0.0,
        ready=None if lock_step else (lambda: (tmp_path / "stepping").exists()),
    )
    assert_prompt(after)
    assert report["stepped_on"]
    if lock_step:
        assert report["steps"] == 0, "paused: nothing stepped it"
    else:
        assert 0 < report["steps"] < 60 * 2500, "real time: some steps, no more than a minute's"
