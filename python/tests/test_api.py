"""The Python API: construction, named access returning copies, hooks, threads, and
every failure as an exception under ars.ArsError."""

import pickle
import threading
import time

import numpy as np
import pytest

import ars


def falling_ball():
    sim = ars.Simulation()
    sim.add_floor()
    ball = sim.add_sphere(0.1, (0.0, 1.0, 0.0), mass=2.0)
    return sim, ball


def test_defaults_and_keywords():
    sim = ars.Simulation()
    assert sim.time_step == 0.0004
    assert sim.gravity == (0.0, -9.81, 0.0)
    sim = ars.Simulation(time_step=0.001, gravity=(0, 0, -9.81))
    assert (sim.time_step, sim.gravity) == (0.001, (0.0, 0.0, -9.81))
    assert sim.add_box((1, 2, 3), (0, 5, 0), density=10.0) == "box"
    assert sim.body("box").mass == pytest.approx(60.0)
    assert sim.add_sphere(0.5, name="ball") == "ball"
    assert sim.body("ball").mass == 1.0, "neither mass nor density: ODE's default body"
    assert sim.objects == ["ball", "box"]


def test_a_ball_falls_and_rests_on_the_floor():
    sim, ball = falling_ball()
    sim.run(2.0)
    assert sim.time == pytest.approx(2.0)
    assert sim.step_count == 5000
    y = sim.body(ball).position[1]
    assert abs(y - 0.1) < 1e-3


def test_attributes_are_copies_not_live_views():
    sim, ball = falling_ball()
    body = sim.body(ball)
    before = body.position
    before[1] = 42.0  # the caller owns it
    sim.step(100)
    after = body.position
    assert after[1] < 1.0 and before[1] == 42.0
    assert isinstance(after, np.ndarray) and after.flags.writeable
    assert body.rotation.shape == (3, 3)
    np.testing.assert_array_equal(body.rotation, np.eye(3))


def test_joints_by_name_read_and_act():
    sim = ars.Simulation(gravity=(0, 0, 0))
    wheel = sim.add_cylinder(0.1, 0.3, (0, 0, 0), mass=1.0)
    sim.add_rotary_joint("axle", wheel, None, None, (0, 0, 1))
    axle = sim.joint("axle")
    axle.set_speed(2.0, 50.0)
    sim.run(0.5)
    assert axle.rate == pytest.approx(2.0)
    assert axle.angle == pytest.approx(1.0, abs=0.01)
    assert sim.joints == ["axle"]


def test_a_joint_group_holds_a_body_by_three_hinges_at_a_point():
    sim = ars.Simulation()
    sim.add_box((1.0, 0.1, 0.2), (0.5, 2.0, 0.0), mass=2.0, name="arm")
    at = (0.0, 2.0, 0.0)
    names = sim.add_joint_group(
        "arm",
        None,
        [
            ("a", "hinge", at, (0, 1, 0), 0.0),
            ("b", "hinge", at, (0, 0, 1), 0.0),
            ("c", "hinge", at, (1, 0, 0), 0.0),
        ],
    )
    assert names == ["a", "b", "c"]
    sim.run(0.3)
    # The arm swings down about z ("b"), its end hanging from the point.
    assert sim.joint("b").position < -0.3
    assert abs(sim.joint("a").position) < 1e-9 and sim.joint("b").kind == "hinge"
    with pytest.raises(ars.InputError, match="perpendicular"):
        sim.add_box((0.1, 0.1, 0.1), (3.0, 1.0, 0.0), mass=1.0, name="other")
        sim.add_joint_group(
            "other", None, [("d", "hinge", at, (0, 1, 0), 0.0), ("e", "hinge", at, (0, 1, 1), 0.0)]
        )
    with pytest.raises(ars.InputError, match="slider"):
        sim.add_joint_group(
            "other", None, [("d", "ball", at, (0, 1, 0), 0.0), ("e", "hinge", at, (1, 0, 0), 0.0)]
        )


def test_bad_input_is_an_input_error_and_a_value_error():
    sim = ars.Simulation()
    with pytest.raises(ars.InputError, match="radius"):
        sim.add_sphere(-1.0)
    with pytest.raises(ValueError):
        sim.add_sphere(float("nan"))
    with pytest.raises(ars.InputError, match="both mass and density"):
        sim.add_sphere(1.0, mass=1.0, density=1.0)
    ball = sim.add_sphere(0.1, (0, 1, 0), mass=1.0)
    with pytest.raises(ars.ArsError, match="itself"):
        sim.add_rotary_joint("j", ball, ball, None, (0, 0, 1))
    with pytest.raises(TypeError):
        sim.add_sphere("big")
    sim.step()  # still usable


def test_an_unknown_name_says_what_was_meant():
    sim, _ball = falling_ball()
    with pytest.raises(ars.UnknownNameError, match="did you mean sphere") as caught:
        sim.body("sphre")
    assert isinstance(caught.value, KeyError) and isinstance(caught.value, ars.ArsError)
    with pytest.raises(ars.UnknownNameError):
        sim.joint("r1")


def test_a_panic_is_an_internal_error_and_the_interpreter_lives_on():
    with pytest.raises(ars.InternalError, match="on purpose"):
        ars._native._panic_for_tests("on purpose")
    assert issubclass(ars.InternalError, Exception)
    sim, _ball = falling_ball()
    sim.step()


def test_an_exception_in_a_hook_comes_out_unchanged_and_the_simulation_goes_on():
    sim, _ball = falling_ball()

    class Stop(Exception):
        pass

    calls = []

    def hook():
        calls.append(sim.time)
        if len(calls) == 3:
            raise Stop("third step")

    hook_id = sim.add_pre_step(hook)
    with pytest.raises(Stop, match="third step"):
        sim.step(10)
    assert sim.step_count == 2, "the raising step was not taken"
    sim.remove_hook(hook_id)
    sim.step(10)
    assert sim.step_count == 12


def test_hooks_act_on_the_simulation_they_run_in():
    sim = ars.Simulation(gravity=(0, 0, 0))
    ball = sim.add_sphere(0.1, (0, 0, 0), mass=1.0)
    body = sim.body(ball)
    seen = []
    sim.add_pre_step(lambda: body.add_force((1.0, 0.0, 0.0)))
    sim.add_post_step(lambda: seen.append(body.linear_velocity[0]))
    sim.step(4)
    # 1 N on 1 kg for 4 steps of 0.4 ms.
    assert seen == pytest.approx([0.0004, 0.0008, 0.0012, 0.0016])

    def steps_inside():
        sim.step()

    sim.add_pre_step(steps_inside)
    with pytest.raises(ars.BusyError, match="cannot step the simulation it runs in"):
        sim.step()


def test_usable_from_other_threads_and_steps_without_the_gil():
    sim, ball = falling_ball()
    results = []

    def worker():
        # Long enough (50,000 steps) for the main thread to wake up during it: one
        # second of a ball (2,500 steps) could end before the main thread's first look.
        sim.run(20.0)
        results.append(sim.body(ball).position[1])

    ticks = []
    thread = threading.Thread(target=worker)
    thread.start()
    while thread.is_alive():
        ticks.append(time.perf_counter())
        time.sleep(0.0005)
    thread.join()
    assert len(results) == 1 and results[0] < 1.0
    # The main thread ran while the other stepped (the GIL was released).
    assert len(ticks) >= 2


def test_simulations_are_not_picklable_and_say_where_to_go():
    sim, _ = falling_ball()
    with pytest.raises(TypeError, match="ars.sweep"):
        pickle.dumps(sim)


def test_exceptions_pickle_as_the_same_classes():
    for cls in (
        ars.ArsError,
        ars.InputError,
        ars.UnknownKindError,
        ars.FormatError,
        ars.UnknownNameError,
        ars.SimulationError,
        ars.BusyError,
        ars.InternalError,
    ):
        again = pickle.loads(pickle.dumps(cls("message")))
        assert type(again) is cls and str(again) == "message"


def test_scenes_save_and_load():
    sim, ball = falling_ball()
    sim.step(10)
    loaded = ars.Simulation.load_scene(sim.save_scene())
    np.testing.assert_array_equal(loaded.body(ball).position, sim.body(ball).position)
    sim.step(100)
    loaded.step(100)
    np.testing.assert_array_equal(loaded.body(ball).position, sim.body(ball).position)


def test_a_thread_reads_while_another_steps_with_python_hooks():
    sim, ball = falling_ball()
    body = sim.body(ball)
    sim.add_pre_step(lambda: body.add_force((0.0, 1.0, 0.0)))
    reads = []
    done = threading.Event()

    def reader():
        while not done.is_set():
            reads.append(sim.time)

    thread = threading.Thread(target=reader)
    thread.start()
    sim.run(0.5)
    done.set()
    thread.join(timeout=10)
    assert not thread.is_alive()
    assert reads == sorted(reads) and reads


def test_other_threads_run_while_a_simulation_with_a_python_hook_steps():
    # With a Python hook at every step, the stepping thread keeps the GIL between
    # steps; the interpreter still hands it over while the hook's Python runs.
    sim, _ = falling_ball()
    steps = []
    sim.add_pre_step(lambda: steps.append(None))
    seen = []
    thread = threading.Thread(target=lambda: sim.run(20.0))  # 50,000 steps
    thread.start()
    while thread.is_alive():
        seen.append(len(steps))
    thread.join()
    assert len(steps) == 50_000
    assert any(0 < n < 50_000 for n in seen), "the main thread ran during the run"


def test_the_package_docs_examples_run():
    import doctest

    import ars.sweeps

    assert doctest.testmod(ars).failed == 0
    assert doctest.testmod(ars.sweeps).failed == 0


def test_urdf_robots_load_with_their_names(tmp_path):
    import pathlib

    data = pathlib.Path(__file__).parents[2] / "tests" / "data"
    sim = ars.Simulation()
    robot = sim.load_urdf(data / "gripper.urdf", fixed_base=True, base_position=(0, 1, 0))
    assert robot["name"] == "gripper"
    assert robot["joints"] == ["left_finger_joint", "right_finger_joint"]
    assert robot["base_joint"] == "gripper/base"
    sim.joint("left_finger_joint").set_speed(0.05, 10.0)
    sim.run(0.2)
    left, right = sim.joint("left_finger_joint").position, sim.joint("right_finger_joint").position
    assert left > 0.005 and abs(left - right) < 1e-6, "the right finger mimics the left"
    text = (data / "gripper.urdf").read_text()
    bad = tmp_path / "bad.urdf"
    bad.write_text(text.replace('<child link="left_finger"/>', '<child link="nowhere"/>'))
    with pytest.raises(ars.FormatError, match='link "nowhere"') as caught:
        ars.Simulation().load_urdf(bad)
    assert caught.value.filename == str(bad) and isinstance(caught.value, ars.InputError)


def test_sensors_record_as_numpy_tables_and_csv(tmp_path):
    sim, ball = falling_ball()
    gps = sim.add_sensor("gps", ball)
    energy = sim.add_sensor("total_energy", ball, every=0.01)
    sim.run(0.1)
    table = gps.records()
    assert table.dtype.names == ("time", "step", "x [m]", "y [m]", "z [m]")
    assert len(table) == len(gps) == 250 and table["step"][0] == 1
    assert table["time"][0] == pytest.approx(0.0004)
    assert table["y [m]"][-1] < table["y [m]"][0] < 1.0
    assert len(energy) == 10
    gps.to_csv(tmp_path / "gps.csv")
    lines = (tmp_path / "gps.csv").read_text().splitlines()
    assert lines[0] == "time [s],step,x [m],y [m],z [m]" and len(lines) == 251
    assert float(lines[-1].split(",")[3]) == table["y [m]"][-1], "the CSV holds the exact values"
    with pytest.raises(
        ars.UnknownKindError, match='unknown sensor kind "sonar"; the known ones are gps, '
    ):
        sim.add_sensor("sonar", ball)
    with pytest.raises(ars.UnknownNameError):
        sim.add_sensor("gps", "nothing")
