"""The viewer from Python: off-screen images (``ars.Renderer``), programs recorded with
no display, and windows on a virtual display (Xvfb) driven with xdotool."""

import json
import os
import subprocess
import sys
import textwrap
import threading
import time

import numpy as np
import pytest
from conftest import window_env, xdotool

import ars

HERE = os.path.dirname(os.path.abspath(__file__))


def ball_scene(color=(1.0, 0.0, 0.0)):
    sim = ars.Simulation(gravity=(0.0, 0.0, 0.0))
    ball = sim.add_sphere(0.5, (0.0, 0.0, 0.0), mass=1.0)
    sim.body(ball).set_color(color)
    return sim, ball


def test_a_renderer_draws_the_scene_as_the_camera_sees_it():
    sim, ball = ball_scene()
    renderer = ars.Renderer(160, 120, camera=(0.0, 0.0, 4.0), background=(0.0, 0.0, 1.0))
    image = renderer.render(sim)
    assert image.shape == (120, 160, 3) and image.dtype == np.uint8
    # The ball, in front of the camera, fills the middle: red.
    r, g, b = (int(c) for c in image[68, 72])
    assert r > 150 and g < 60 and b < 60, (r, g, b)
    # The corners show the (blue) background.
    r, g, b = (int(c) for c in image[2, 2])
    assert b > 200 and r < 60 and g < 60, (r, g, b)
    # Moved out of view, the ball is gone from the middle, which shows the background.
    sim.body(ball).set_position((10.0, 0.0, 0.0))
    moved = renderer.render(sim)
    assert tuple(moved[68, 72]) == tuple(image[2, 2])


def test_the_world_axes_are_drawn_on_request_only():
    sim = ars.Simulation(gravity=(0.0, 0.0, 0.0))  # nothing but the axes to draw
    view = {"camera": (2.0, 1.5, 3.0), "look_at": (0.3, 0.3, 0.3), "background": (1.0, 1.0, 1.0)}
    plain = ars.Renderer(120, 90, **view).render(sim)
    assert (plain == plain[0, 0]).all(), "no axes by default: only the background"
    drawn = ars.Renderer(120, 90, axes=True, **view).render(sim)
    red = (drawn[..., 0] > 150) & (drawn[..., 1] < 100) & (drawn[..., 2] < 100)
    green = (drawn[..., 1] > 100) & (drawn[..., 0] < 100) & (drawn[..., 2] < 100)
    assert red.sum() > 10 and green.sum() > 10, "X red and Y green, when asked"


def test_rendering_prints_nothing_on_stderr_without_xdg_runtime_dir():
    # Under Xvfb or in CI: Mesa's Vulkan layer made libwayland print four lines per
    # renderer; the package turns the layer off at import (NODEVICE_SELECT).
    env = {
        k: v
        for k, v in os.environ.items()
        if k not in ("XDG_RUNTIME_DIR", "WAYLAND_DISPLAY", "NODEVICE_SELECT")
    }
    script = "import ars\nars.Renderer(32, 24).render(ars.Simulation())\n"
    run = subprocess.run(
        [sys.executable, "-c", script],
        check=False,
        env=env,
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert run.returncode == 0, run.stderr
    assert run.stderr == "", run.stderr


def test_renderers_can_be_made_again_and_again_and_save_png(tmp_path):
    sim, _ = ball_scene()
    for i in range(3):
        path = tmp_path / f"ball{i}.png"
        ars.Renderer(64, 48, camera=(0.0, 0.0, 4.0)).save(sim, path)
        assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_a_renderer_collected_at_exit_does_not_crash_the_interpreter():
    # The renderer's thread ended (and Mesa with it) while the interpreter exited: a
    # double free in about one run in 25. Now the renderer waits for its thread.
    script = textwrap.dedent(
        """
        import ars
        sim = ars.Simulation()
        sim.add_sphere(0.5, (0.0, 1.0, 0.0), mass=1.0)
        renderer = ars.Renderer(64, 48)
        renderer.render(sim)
        """
    )
    for _ in range(40):
        run = subprocess.run(
            [sys.executable, "-c", script], check=False, capture_output=True, text=True, timeout=60
        )
        assert run.returncode == 0, run.stderr[-2000:]


@pytest.mark.parametrize(
    ("kwargs", "words"),
    [
        ({"width": 0}, "between 1 and 8192"),
        ({"quality": "best"}, '"auto", "fast" or "fine"'),
        ({"camera": (0.0, 0.0, 0.0)}, "cannot look at the point it is at"),
        ({"camera": (float("nan"), 0.0, 1.0)}, "finite"),
        ({"background": (2.0, 0.0, 0.0)}, "[0, 1]"),
    ],
)
def test_bad_view_settings_are_input_errors(kwargs, words):
    with pytest.raises(ars.InputError, match=None) as caught:
        ars.Renderer(**kwargs)
    assert words in str(caught.value)


def test_a_hook_cannot_render_its_own_simulation_and_the_simulation_goes_on():
    sim, _ = ball_scene()
    renderer = ars.Renderer(32, 24)
    hook = sim.add_pre_step(lambda: renderer.render(sim))
    with pytest.raises(ars.BusyError, match="render between steps"):
        sim.step()
    sim.remove_hook(hook)
    sim.step(3)
    assert sim.step_count == 3
    assert renderer.render(sim).shape == (24, 32, 3)


def test_show_without_a_display_is_a_no_display_error(monkeypatch):
    monkeypatch.delenv("DISPLAY", raising=False)
    monkeypatch.delenv("WAYLAND_DISPLAY", raising=False)
    sim, _ = ball_scene()
    assert not ars.has_display()
    with pytest.raises(ars.NoDisplayError, match="no display"):
        sim.show(1.0)


@pytest.mark.parametrize(
    ("kwargs", "words"),
    [
        ({"duration": -1.0}, "duration -1 s must be positive"),
        ({"frames": -1}, "frames -1 must be 0 or more"),
    ],
)
def test_a_window_for_a_negative_time_or_number_of_frames_is_an_input_error(kwargs, words):
    sim, _ = ball_scene()
    with pytest.raises(ars.InputError) as caught:
        sim.show(**kwargs)
    assert words in str(caught.value)


def test_a_window_from_another_thread_is_an_input_error(monkeypatch):
    monkeypatch.setenv("DISPLAY", ":12345")  # never reached: refused before
    sim, _ = ball_scene()
    caught = []

    def show():
        try:
            sim.show(1.0)
        except ars.InputError as e:
            caught.append(str(e))

    thread = threading.Thread(target=show)
    thread.start()
    thread.join()
    assert caught and "main thread only" in caught[0]


# A program in the original's style: a ball on an arm hinged about the vertical (gravity
# does not turn it), turned by 'up' while it is held, and counting presses of 'a'.
WHEEL = textwrap.dedent(
    """
    import json, sys
    import ars.constants as cts
    from ars.app import Program, gp

    class Wheel(Program):
        FPS = 50
        STEPS_PER_FRAME = 10
        WINDOW_SIZE = (480, 360)
        CAMERA_POSITION = (3, 3, 3)

        def __init__(self):
            self.presses = 0
            Program.__init__(self)
            self.key_press_functions.add("up", self.turn, repeat=True)
            self.key_press_functions.add("a", self.press)

        def create_sim_objects(self):
            box = self.sim.add_box((0.2, 0.2, 0.2), (0, 1, 0), mass=1000.0)
            ball = self.sim.add_sphere(0.1, (1, 1, 0), mass=1.0)
            self.sim.get_object(ball).actor.set_color(cts.COLOR_YELLOW)
            self.sim.add_fixed_joint("anchor", self.sim.get_object(box), None)
            self.sim.add_rotary_joint(
                "hinge", self.sim.get_object(ball), self.sim.get_object(box), None, cts.Y_AXIS
            )

        def turn(self):
            self.sim.get_joint("hinge").add_torque(2.0)

        def press(self):
            self.presses += 1

        def reset_simulation(self):
            self.rate_before_reset = self.sim.get_joint("hinge").joint.angle_rate
            Program.reset_simulation(self)
    """
)


def run_python(code, env, timeout=120):
    return subprocess.run(
        [sys.executable, "-c", code],
        env=env,
        capture_output=True,
        text=True,
        timeout=timeout,
        check=False,
    )


def test_a_program_with_no_display_records_frames_off_screen(tmp_path):
    env = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY")}
    env.update(ARS_DURATION="0.2", TMPDIR=str(tmp_path))
    code = WHEEL + "Wheel().start()\n"
    run = run_python(code, env)
    assert run.returncode == 0, run.stderr[-3000:]
    folder = tmp_path / "ars-frames-autonomous_robot_simulator"
    assert f"frames into {folder}" in run.stderr
    # 0.2 s = 10 frames: the first image before any step, then one every 5 frames.
    assert sorted(p.name for p in folder.iterdir()) == [
        "frame_00001.png",
        "frame_00002.png",
        "frame_00003.png",
    ]


def test_the_screenshot_recorder_of_a_recorded_program_writes_its_images(tmp_path):
    code = WHEEL + textwrap.dedent(
        f"""
        import os
        os.chdir({str(tmp_path)!r})
        wheel = Wheel()
        wheel.create_screenshot_recorder("shot", periodically=True)
        written = wheel.record("frames", 0.1, every=1)
        print(json.dumps(written))
        """
    )
    run = run_python(code, dict(os.environ))
    assert run.returncode == 0, run.stderr[-3000:]
    assert len(json.loads(run.stdout)) == 6
    # One screenshot per frame (period 1/FPS), named as the original names them.
    assert sorted(p.name for p in tmp_path.glob("shot*.png")) == sorted(
        f"shot{i}.png" for i in range(1, 6)
    )


def run_in_window(code, display, tmp_path, drive):
    """Runs ``code``, which opens the Wheel's window, in another interpreter; calls
    ``drive()`` once the window is up and focused, waits for the program to end, and
    returns the JSON it printed last."""
    window = subprocess.Popen(
        [sys.executable, "-c", code],
        env=window_env(display, tmp_path),
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    try:
        found = xdotool(display, "search", "--sync", "--onlyvisible", "--name", "Autonomous")
        assert found.returncode == 0, found.stderr
        # Keys go to the focused window (with --window, xdotool also sends each event
        # to the window itself, and it arrives twice).
        xdotool(display, "windowfocus", "--sync", found.stdout.split()[0])
        drive()
        out, err = window.communicate(timeout=30)
    finally:
        window.kill()
    assert window.returncode == 0, err[-3000:]
    return json.loads(out.splitlines()[-1])


def test_start_opens_a_window_that_takes_the_programs_keys_and_escape_closes(display, tmp_path):
    code = WHEEL + textwrap.dedent(
        """
        import time
        wheel = Wheel()
        first = wheel.sim
        started = time.perf_counter()
        wheel.start()  # until the window is closed
        wall = time.perf_counter() - started
        joint = wheel.sim.get_joint("hinge").joint
        print(json.dumps({"wall": wall, "time": wheel.sim.sim_time, "rate": joint.angle_rate,
                          "rate_before_reset": wheel.rate_before_reset,
                          "rebuilt": wheel.sim is not first, "presses": wheel.presses}))
        """
    )

    def drive():
        time.sleep(1.0)
        xdotool(display, "key", "a")
        xdotool(display, "keydown", "Up")
        time.sleep(1.5)
        xdotool(display, "keyup", "Up")
        time.sleep(0.5)
        xdotool(display, "key", "r")  # the original's reset: the program rebuilt
        time.sleep(1.0)
        xdotool(display, "key", "Escape")

    result = run_in_window(code, display, tmp_path, drive)
    assert result["presses"] == 1
    # Held for 1.5 s at 2 N·m: the arm turned (it is still, untouched).
    assert result["rate_before_reset"] > 0.5, result
    # `r` rebuilt the program in the same window: a new simulation, from rest, which
    # ran about a second (in real time) until Escape closed the window.
    assert result["rebuilt"] and result["rate"] == 0.0, result
    assert 0.5 < result["time"] < result["wall"] - 2.0, result


@pytest.mark.parametrize("key", ["q", "shift+e"])
def test_e_and_q_close_a_programs_window_as_in_the_original(display, tmp_path, key):
    code = WHEEL + textwrap.dedent(
        """
        wheel = Wheel()
        wheel.key_press_functions.add("q", wheel.press)
        wheel.start()  # until the window is closed
        print(json.dumps({"presses": wheel.presses}))
        """
    )

    def drive():
        time.sleep(0.5)
        xdotool(display, "key", key)

    result = run_in_window(code, display, tmp_path, drive)
    # The program's own action for q ran before the window closed; e has none.
    assert result["presses"] == (1 if key == "q" else 0), result


def test_a_simulation_window_runs_in_real_time_and_a_hooks_exception_comes_out(display, tmp_path):
    code = textwrap.dedent(
        """
        import json
        import ars

        sim = ars.Simulation()
        sim.add_floor()
        sim.add_sphere(0.2, (0, 2, 0), mass=1.0)

        def fail():
            if sim.step_count == 5000:  # 2 s
                raise ZeroDivisionError("from the hook")

        hook = sim.add_pre_step(fail)
        started = time.perf_counter()
        try:
            sim.show(30.0, title="falling ball", size=(320, 240))
            raised = None
        except ZeroDivisionError as e:
            raised = str(e)
        wall = time.perf_counter() - started
        stopped_at = sim.step_count
        sim.remove_hook(hook)
        sim.step(10)
        second = sim.show(frames=10)
        third = ars.Simulation().show(frames=3, title="another")
        print(json.dumps({"raised": raised, "wall": wall, "stopped_at": stopped_at,
                          "steps": sim.step_count, "second": second, "third": third}))
        """
    ).replace("import json", "import json, time")
    run = run_python(code, window_env(display, tmp_path))
    assert run.returncode == 0, run.stderr[-3000:]
    result = json.loads(run.stdout.splitlines()[-1])
    # The hook's own exception came out of show(), unchanged, when the simulation
    # reached 2 s: paced to the wall clock, about 2 s after the window opened.
    assert result["raised"] == "from the hook"
    assert result["stopped_at"] == 5000
    assert 1.5 < result["wall"] < 10.0, result
    # The simulation goes on (the step whose hook raised was not taken), in another
    # window, and another simulation in a third: window after window in one
    # interpreter, which then exits cleanly (the return code above).
    assert result["second"]["frames_drawn"] >= 2 and result["third"]["frames_drawn"] >= 2, result
    # 10 frames of 50 steps each (the default 20 ms frame of 0.4 ms steps).
    assert result["steps"] == 5000 + 10 + 10 * 50, result
