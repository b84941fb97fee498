"""`sim.ros(...)`, the ROS 2 bridge from Python, without a ROS 2 peer: it runs for its
duration in real time with the GIL released, refuses bad options with an
``ars.InputError`` naming them (the simulation untouched), and a Python hook's
exception comes out of it. Talking to it over DDS: test_sim_ros_dds.py; Ctrl-C:
test_interrupt_long_calls.py."""

import random
import shutil
import subprocess
import sys
import threading
import time

import pytest

import ars

# ROS domains of their own (test_ros_bridge.py takes 1 to 100, test_sim_ros_dds.py 201
# to 232).
DOMAIN = random.randrange(150, 200)


def pendulum():
    sim = ars.Simulation()
    sim.add_floor()
    bob = sim.add_sphere(0.1, (0.5, 1.0, 0.0), mass=1.0, name="bob")
    sim.add_rotary_joint("pivot", bob, None, anchor=(0.0, 1.0, 0.0), axis=(0.0, 0.0, 1.0))
    return sim


def test_a_real_time_run_ends_after_its_duration_with_the_gil_released():
    sim = pendulum()
    headless = pendulum()
    counted = []
    running = threading.Event()

    def count():
        running.set()
        while not done.is_set():
            counted.append(1)
            time.sleep(0.001)

    done = threading.Event()
    counter = threading.Thread(target=count, daemon=True)
    counter.start()
    running.wait()
    start = time.monotonic()
    summary = sim.ros(0.2, domain_id=DOMAIN)
    wall = time.monotonic() - start
    done.set()
    counter.join()
    # 0.2 s of 0.4 ms steps, paced to the wall clock.
    assert summary == {"end_time": sim.time, "steps": 500}
    assert sim.step_count == 500 and wall >= 0.2
    # Another Python thread ran meanwhile: the call released the GIL.
    assert len(counted) > 20, len(counted)
    # Given back as it ran: without commands, the headless steps.
    headless.step(500)
    assert list(sim.body("bob").position) == list(headless.body("bob").position)
    sim.step(10)
    assert sim.step_count == 510


@pytest.mark.parametrize(
    ("keywords", "named"),
    [
        ({"rate": 0.0}, "rate"),
        ({"rate": float("nan")}, "rate"),
        ({"duration": -1.0}, "duration"),
        ({"duration": float("inf")}, "duration"),
        ({"domain_id": 233}, "domain_id"),
        ({"domain_id": -1}, "domain_id"),
        ({"domain_id": 10**30}, "out of range"),
        ({"node_name": "1st"}, "node_name"),
        ({"node_name": "my-node"}, "node_name"),
        ({"node_name": ""}, "node_name"),
        ({"services": "zenoh"}, "services"),
        ({"wheel_torque": -1.0}, "wheel_torque"),
        ({"drive": ("pivot", "nowhere")}, "drive"),
        ({"drive": ("pivot",)}, "2"),
        ({"drive": ("", "pivot")}, "drive"),
    ],
)
def test_a_bad_option_is_an_input_error_naming_it_and_the_simulation_is_untouched(keywords, named):
    sim = pendulum()
    sim.step(3)
    with pytest.raises(ars.InputError, match=named) as raised:
        sim.ros(**{"duration": 0.1, "domain_id": DOMAIN, **keywords})
    assert isinstance(raised.value, ValueError)
    assert sim.step_count == 3
    sim.step(2)
    assert sim.step_count == 5


def test_a_bad_ros_domain_id_in_the_environment_is_an_input_error(monkeypatch):
    sim = pendulum()
    monkeypatch.setenv("ROS_DOMAIN_ID", "seven")
    with pytest.raises(ars.InputError, match="ROS_DOMAIN_ID"):
        sim.ros(0.1)
    monkeypatch.setenv("ROS_DOMAIN_ID", str(DOMAIN))
    assert sim.ros(0.01)["steps"] == 25


def test_a_python_hooks_exception_comes_out_and_the_simulation_is_gone():
    sim = pendulum()

    def fails():
        if sim.step_count == 10:
            raise RuntimeError("the hook's own error")

    sim.add_post_step(fails)
    with pytest.raises(RuntimeError, match="the hook's own error"):
        sim.ros(1.0, domain_id=DOMAIN)
    # The bridge dropped the simulation with its failure: said, not silently empty.
    with pytest.raises(ars.SimulationError, match="sim.ros failed"):
        sim.step()
    with pytest.raises(ars.SimulationError, match="gone"):
        _ = sim.time
    with pytest.raises(ars.SimulationError, match="gone"):
        sim.ros(0.1, domain_id=DOMAIN)


def test_a_hook_cannot_run_its_own_simulation_as_a_ros_node():
    sim = pendulum()
    refused = []

    def hook():
        try:
            sim.ros(0.1, domain_id=DOMAIN)
        except ars.BusyError as e:
            refused.append(e)

    sim.add_pre_step(hook)
    sim.step()
    assert len(refused) == 1


NO_NETWORK = """
import ars
sim = ars.Simulation()
sim.add_sphere(0.1, (0.0, 1.0, 0.0), mass=1.0)
try:
    sim.ros(0.1)
except ars.ArsError as e:
    print(type(e).__name__, e)
sim.step(3)
print(sim.step_count)
"""


def test_no_network_is_an_ars_error_and_the_simulation_is_untouched():
    # A network namespace of its own, where not even the loopback is up.
    if shutil.which("unshare") is None:
        pytest.skip("no unshare command")
    made = subprocess.run(["unshare", "-n", "true"], check=False, capture_output=True)
    if made.returncode != 0:
        pytest.skip("not allowed to make a network namespace (unshare -n)")
    run = subprocess.run(
        ["unshare", "-n", sys.executable, "-c", NO_NETWORK],
        check=False,
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert run.returncode == 0, run.stderr
    said, steps = run.stdout.splitlines()
    assert said.startswith("ArsError sim.ros: no network: no network interface is up"), said
    assert steps == "3"
