"""Errors people can act on: one class per cause, importable as ``ars.X`` and picklable,
and messages that are sentences naming objects, never internal handles."""

import errno
import os
import pickle

import pytest

import ars


def readable(error):
    """The message of `error`, checked for what a person cannot act on."""
    message = str(error)
    assert "#" not in message and "WorldId" not in message and "v0@" not in message, message
    assert "out of range" not in message, message
    return message


def test_every_class_is_importable_from_ars_and_is_the_python_class_it_should_be():
    assert issubclass(ars.InputError, ValueError)
    assert issubclass(ars.UnknownKindError, ars.InputError)
    assert issubclass(ars.FormatError, ars.InputError)
    assert issubclass(ars.UnknownNameError, KeyError)
    assert issubclass(ars.FileError, OSError)
    assert issubclass(ars.BusyError, RuntimeError)
    assert issubclass(ars.NoDisplayError, RuntimeError)
    assert issubclass(ars.RendererError, RuntimeError)
    for cls in (
        ars.SimulationError,
        ars.InternalError,
        ars.FileError,
        ars.BusyError,
        ars.FormatError,
        ars.NoDisplayError,
        ars.RendererError,
    ):
        assert issubclass(cls, ars.ArsError) and cls.__module__ == "ars"
    assert not issubclass(ars.SimulationError, ars.InternalError)


def test_file_and_format_errors_pickle_with_their_details():
    error = ars.FileError(errno.ENOENT, 'cannot write the CSV file "/x/y.csv": gone', "/x/y.csv")
    again = pickle.loads(pickle.dumps(error))
    assert type(again) is ars.FileError
    assert (again.errno, again.filename, str(again)) == (errno.ENOENT, "/x/y.csv", str(error))
    assert again.msg == str(error)

    sim = ars.Simulation()
    with pytest.raises(ars.FormatError) as caught:
        sim.load_scene("{")
    again = pickle.loads(pickle.dumps(caught.value))
    assert type(again) is ars.FormatError and str(again) == str(caught.value)
    assert (again.filename, again.position) == (caught.value.filename, caught.value.position)
    assert (again.element, again.line) == (caught.value.element, caught.value.line)


def test_a_missing_csv_folder_is_an_os_error_with_the_path(tmp_path):
    sim = ars.Simulation()
    ball = sim.add_sphere(0.1, (0.0, 1.0, 0.0), mass=1.0)
    gps = sim.add_sensor("gps", ball)
    sim.step(3)
    path = tmp_path / "no such folder" / "gps.csv"
    with pytest.raises(OSError) as caught:
        gps.to_csv(path)
    error = caught.value
    assert type(error) is ars.FileError
    assert error.errno == errno.ENOENT and error.filename == str(path)
    assert readable(error).startswith(
        f"cannot write the CSV file {str(path)!r}: ".replace("'", '"')
    )


def test_a_malformed_scene_is_a_format_error_with_its_position():
    with pytest.raises(ars.FormatError) as caught:
        ars.Simulation.load_scene('{\n  "format": 3,\n')
    error = caught.value
    assert error.filename == "<string>" and error.position.startswith("line 2, column ")
    assert (error.element, error.line) == ("", 2)
    assert readable(error).startswith("<string>, line 2, column ")


def test_a_bad_mjcf_element_is_named_with_its_line(tmp_path):
    path = tmp_path / "bad.xml"
    path.write_text('<mujoco>\n<worldbody>\n<body><geom size="-1"/></body>\n</worldbody></mujoco>')
    with pytest.raises(ars.FormatError) as caught:
        ars.Simulation().load_mjcf(path)
    error = caught.value
    assert (error.filename, error.element, error.line) == (str(path), "<geom>", 3)
    assert "must be positive" in str(error)


def test_unknown_kinds_list_the_known_ones():
    sim = ars.Simulation()
    ball = sim.add_sphere(0.1, (0.0, 1.0, 0.0), mass=1.0)
    with pytest.raises(ars.UnknownKindError) as caught:
        sim.add_sensor("sonar", ball)
    assert readable(caught.value).startswith(
        'unknown sensor kind "sonar"; the known ones are gps, velometer, '
    )

    sim.add_rotary_joint("hinge", ball, None, anchor=(0.0, 2.0, 0.0))
    with pytest.raises(ars.UnknownKindError) as caught:
        sim.joint("hinge").set_controller("pid", 1.0)
    assert (
        readable(caught.value)
        == 'unknown controller kind "pid"; the known ones are torque, position, velocity, '
        "dc_motor"
    )
    with pytest.raises(ars.UnknownKindError, match='unknown joint parameter "stiffness"'):
        sim.joint("hinge").set_param("stiffness", 1.0)
    with pytest.raises(ars.InputError) as caught:
        sim.joint("hinge").set_controller("position")
    assert readable(caught.value) == "a controller needs a setpoint"


def test_a_static_object_has_no_body_and_the_message_names_it():
    sim = ars.Simulation()
    floor = sim.add_floor()
    ball = sim.add_sphere(0.1, (0.0, 1.0, 0.0), mass=1.0)
    with pytest.raises(ars.InputError) as caught:
        sim.body(floor).linear_velocity  # noqa: B018 (the read raises)
    assert readable(caught.value).startswith('object "floor" is static (it has no body); ')
    with pytest.raises(ars.InputError) as caught:
        sim.add_fixed_joint("j", floor, ball)
    assert (
        readable(caught.value)
        == 'object "floor" is static (it has no body); the first object of a joint needs one'
    )


def test_messages_read_as_sentences():
    sim = ars.Simulation()
    with pytest.raises(ars.InputError) as caught:
        sim.add_box((1e12, 1.0, 1.0), mass=1.0)
    assert readable(caught.value).startswith("box edges must be within [")
    ball = sim.add_sphere(0.1, mass=1.0, name="ball")
    with pytest.raises(ars.InputError) as caught:
        sim.add_fixed_joint("self", ball, ball)
    assert readable(caught.value) == 'a fixed joint cannot connect object "ball" to itself'


@pytest.mark.parametrize(
    ("call", "words"),
    [
        (lambda sim: sim.step(-1), "the number of steps must be 0 or more, got -1"),
        (lambda sim: sim.set_seed(-1), "the seed must be 0 or more, got -1"),
        (lambda sim: sim.set_seed(2**40), "the seed is too large, got 1099511627776"),
        (
            lambda sim: ars.Simulation(steps_per_frame=-2),
            "steps_per_frame must be 0 or more, got -2",
        ),
        (
            lambda sim: sim.add_trimesh([(0, 0, 0), (1, 0, 0), (0, 1, 0)], [(0, 1, -2)]),
            "must be 0 or more, got -2",
        ),
        (lambda sim: ars.Renderer(-640, 480), "the image size -640×480 must be between 1 and 8192"),
        (lambda sim: sim.show(frames=-1), "frames -1 must be 0 or more"),
    ],
)
def test_negative_counts_are_input_errors_not_overflow_errors(call, words):
    sim = ars.Simulation()
    with pytest.raises(ars.InputError) as caught:
        call(sim)
    assert not isinstance(caught.value, OverflowError)
    assert words in readable(caught.value)


def test_a_removed_hook_is_an_unknown_name_the_second_time():
    sim = ars.Simulation()
    hook = sim.add_pre_step(lambda: None)
    sim.remove_hook(hook)
    for again in (hook, -1):
        with pytest.raises(ars.UnknownNameError) as caught:
            sim.remove_hook(again)
        assert (
            readable(caught.value)
            == f"no hook {again} in this simulation (removed, or never added)"
        )


def test_a_hook_stepping_its_own_simulation_is_busy():
    sim = ars.Simulation()
    sim.add_pre_step(lambda: sim.step())
    with pytest.raises(ars.BusyError, match="a hook cannot step the simulation it runs in"):
        sim.step()


def test_a_diverged_body_is_named_and_the_same_class_comes_every_time():
    sim = ars.Simulation(gravity=(0.0, 0.0, 0.0))
    ball = sim.add_sphere(0.1, mass=1.0, name="ball")
    body = sim.body(ball)
    caught = []
    for _ in range(1000):
        body.add_force((1e9, 0.0, 0.0))
        try:
            sim.step()
        except ars.ArsError as e:
            caught.append(e)
            break
    assert caught, "the body diverged"
    with pytest.raises(ars.ArsError) as again:
        sim.step()
    assert type(caught[0]) is ars.SimulationError and type(again.value) is ars.SimulationError
    assert readable(caught[0]).startswith('object "ball" diverged at t = ')


def poisoned():
    """A simulation that ODE cannot step: two fixed joints on one pair of bodies with a
    CFM of 0 make its matrix singular (see the Rust crasher
    `redundant_fixed_joints_with_zero_cfm`); the first error stops the stepping."""
    sim = ars.Simulation(cfm=0.0)
    a = sim.add_box((0.2, 0.2, 0.2), (0.0, 1.0, 0.0), mass=1.0)
    b = sim.add_box((0.2, 0.2, 0.2), (1.0, 1.0, 0.0), mass=1.0)
    sim.add_fixed_joint("one", a, b)
    sim.add_fixed_joint("two", a, b)
    sim.add_fixed_joint("world", a, None)
    for _ in range(1000):
        try:
            sim.step()
        except ars.ArsError as e:
            return sim, e
    pytest.skip("ODE stepped the singular system without an error on this machine")


def test_a_simulation_that_cannot_go_on_raises_the_same_class_every_time():
    sim, first = poisoned()
    assert type(first) is ars.SimulationError, repr(first)
    for _ in range(2):
        with pytest.raises(ars.ArsError) as later:
            sim.step()
        assert type(later.value) is ars.SimulationError, repr(later.value)
        readable(later.value)


def ball():
    """A simulation with something to show."""
    sim = ars.Simulation()
    sim.add_sphere(0.2, (0.0, 2.0, 0.0), mass=1.0, name="ball")
    return sim


def test_the_viewer_classes_pickle_as_the_same_classes():
    for cls in (ars.NoDisplayError, ars.RendererError):
        again = pickle.loads(pickle.dumps(cls("message")))
        assert type(again) is cls and str(again) == "message"
        assert not issubclass(cls, ars.InputError)


def test_a_window_with_no_display_is_a_no_display_error(monkeypatch):
    monkeypatch.delenv("DISPLAY", raising=False)
    monkeypatch.delenv("WAYLAND_DISPLAY", raising=False)
    assert not ars.has_display()
    with pytest.raises(ars.NoDisplayError) as caught:
        ball().show(1.0)
    error = caught.value
    assert isinstance(error, RuntimeError) and isinstance(error, ars.ArsError)
    assert not isinstance(error, ars.InputError)
    assert readable(error) == "no display: DISPLAY and WAYLAND_DISPLAY are unset"


def test_a_video_into_a_missing_folder_is_a_file_error_with_the_path(tmp_path):
    sim = ball()
    path = tmp_path / "no such folder" / "ball.mp4"
    with pytest.raises(OSError) as caught:
        sim.record_video(path, 1.0, size=(64, 48))
    error = caught.value
    assert type(error) is ars.FileError
    assert error.errno == errno.ENOENT and error.filename == str(path)
    assert readable(error) == f"could not write {path}: the folder {path.parent} does not exist"
    assert os.listdir(tmp_path) == [] and sim.time == 0.0


def test_a_replay_into_a_missing_folder_is_a_file_error_with_the_path(tmp_path):
    sim = ball()
    path = tmp_path / "no such folder" / "ball.html"
    with pytest.raises(OSError) as caught:
        sim.save_replay(path, 0.1)
    error = caught.value
    assert type(error) is ars.FileError
    assert error.errno == errno.ENOENT and error.filename == str(path)
    assert readable(error).startswith(f"cannot write the replay {str(path)!r}: ".replace("'", '"'))
    assert os.listdir(tmp_path) == []


@pytest.mark.parametrize(
    ("kwargs", "words"),
    [
        ({"size": (65, 48)}, "a video's width and height must be even"),
        ({"fps": 0.0, "size": (64, 48)}, "a video's frame rate must be a number of frames"),
    ],
)
def test_a_bad_video_setting_is_an_input_error(tmp_path, kwargs, words):
    with pytest.raises(ars.InputError) as caught:
        ball().record_video(tmp_path / "ball.mp4", 1.0, **kwargs)
    assert readable(caught.value).startswith(words)
    assert os.listdir(tmp_path) == []
