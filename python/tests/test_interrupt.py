"""Ctrl-C (SIGINT) stops a long ``sim.run``/``sim.step`` promptly with
``KeyboardInterrupt``, between two steps, and the simulation steps on."""

import os
import signal
import threading
import time

import pytest

import ars


def ball_on_a_floor():
    sim = ars.Simulation()
    sim.add_floor()
    sim.add_sphere(0.1, (0.0, 1.0, 0.0), mass=1.0)
    return sim


def interrupted_after(seconds, run):
    """Sends SIGINT to this process after ``seconds``; returns how long ``run`` went on
    after it before ``KeyboardInterrupt`` came out of it."""
    sent = []

    def send():
        sent.append(time.perf_counter())
        os.kill(os.getpid(), signal.SIGINT)

    timer = threading.Timer(seconds, send)
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            run()
        return time.perf_counter() - sent[0]
    finally:
        timer.cancel()


@pytest.mark.parametrize("with_hook", [False, True], ids=["no hooks", "a Python hook"])
@pytest.mark.parametrize("call", ["run", "step"])
def test_ctrl_c_stops_a_long_run_and_the_simulation_goes_on(call, with_hook):
    sim = ball_on_a_floor()
    calls = []
    if with_hook:
        sim.add_pre_step(lambda: calls.append(None))
    long_run = (lambda: sim.run(1e6)) if call == "run" else (lambda: sim.step(10**12))
    after = interrupted_after(0.3, long_run)
    assert after <= 0.5, f"KeyboardInterrupt came {after:.3f} s after SIGINT"
    # Stopped between two steps, well short of the end, and it steps on.
    steps = sim.step_count
    assert 0 < steps < 10**9
    assert sim.time == pytest.approx(steps * sim.time_step)
    if with_hook:
        # The hook ran before every step taken (and maybe one step that the
        # interrupted hook did not let happen).
        assert len(calls) in (steps, steps + 1)
    sim.step(10)
    assert sim.step_count == steps + 10
    sim.run(0.1)
    assert sim.step_count == steps + 10 + 250
    assert abs(sim.body("sphere").position[1] - 0.1) < 1e-3
