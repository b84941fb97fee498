"""Programs in the original ARS style (``from ars.app import Program``): subclass
:class:`Program`, build the scene in ``create_sim_objects``, connect handlers to the
simulation's signals, and run it.

``Program()`` builds the simulation (``create_simulation`` calls
``create_sim_objects``). ``start()`` is the original's entry point: it opens ARS's
viewer on the program where there is a display, until the window is closed (the
program's keys act as in the original; ``r`` rebuilds it, ``e`` and ``q`` close the
window); with no display it records
``ARS_DURATION`` seconds (default 10) off screen, a PNG every 5 frames, into a folder
it names on stderr. ``run(duration)`` runs it headless for ``duration`` seconds of
simulated time, frame by frame, and returns the simulation; ``show(duration)`` opens the
window for ``duration`` wall seconds; ``record(folder, duration)`` records off screen.

Module names, as the original: ``Program``, ``ActionMap``, ``Simulation``,
``dispatcher``, ``signals``, ``gp`` (graphics), ``exc`` (exceptions), ``logger``.
"""

import contextlib
import logging
import math
import os
import sys
import weakref

from ars import _native
from ars import dispatch as dispatcher
from ars import exceptions as exc
from ars import graphics as gp
from ars.model.simulator import Simulation, signals

__all__ = ["ActionMap", "Program", "Simulation", "dispatcher", "exc", "gp", "logger", "signals"]

logger = logging.getLogger("ars.app")


class ActionMap:
    """Keys and what they do: ``add(key, function, repeat=False)``; a repeated key acts
    in every step of the next frame, the others once, at once."""

    def __init__(self):
        self._actions = {}

    def add(self, key, value, repeat=False):
        self._actions[key] = (value, repeat)

    def has_key(self, key):
        return key in self._actions

    def get(self, key, default=None):
        return self._actions.get(key, default)

    def get_function(self, key):
        return self._actions[key][0]

    def call(self, key):
        try:
            self._actions[key][0]()
        except Exception:
            logger.exception("Exception when calling the action of key %r", key)

    def is_repeat(self, key):
        return self._actions[key][1]

    def __str__(self):
        return ", ".join(f"{k}{' (held)' if r else ''}" for k, (_, r) in self._actions.items())


class Program:
    """A simulation program: override ``create_sim_objects`` (and the class constants)."""

    WINDOW_TITLE = "Autonomous Robot Simulator"
    WINDOW_POSITION = (0, 0)
    WINDOW_SIZE = (1024, 768)
    WINDOW_ZOOM = 1.0
    CAMERA_POSITION = (10, 8, 10)
    BACKGROUND_COLOR = (1, 1, 1)
    FPS = 50
    STEPS_PER_FRAME = 50
    FLOOR_BOX_SIZE = (10, 0.01, 10)

    def __init__(self):
        self.do_create_window = True
        self.key_press_functions = None
        self.sim = None
        self._screenshot_recorder = None
        self.set_key_2_action_mapping()
        self.gAdapter = gp.Engine(
            self.WINDOW_TITLE,
            self.WINDOW_POSITION,
            self.WINDOW_SIZE,
            zoom=self.WINDOW_ZOOM,
            background_color=self.BACKGROUND_COLOR,
            cam_position=self.CAMERA_POSITION,
        )
        self.create_simulation()
        self._own_simulation()

    def _own_simulation(self):
        """Tells the simulation it is this program's, so that the program's handlers
        hear it alone (see ``ars.dispatch``). Done when it is made and whenever the
        program runs it, not on every attribute set: a program sets its own
        attributes every step."""
        sim = self.__dict__.get("sim")
        if isinstance(sim, Simulation) and (sim._program is None or sim._program() is not self):
            sim._program = weakref.ref(self)
            sim._signals_changed()

    # -- building -------------------------------------------------------------------

    def create_simulation(self, add_axes=True, add_floor=True):
        """Builds the simulation: world, axes, floor, then ``create_sim_objects``."""
        self.sim = Simulation(self.FPS, self.STEPS_PER_FRAME)
        self.sim.graph_adapter = gp
        self.sim.add_basic_simulation_objects()
        if add_axes:
            self.sim.add_axes()
        if add_floor:
            self.sim.add_floor(
                normal=(0, 1, 0), box_size=self.FLOOR_BOX_SIZE, color=(0.7, 0.7, 0.7)
            )
        self.create_sim_objects()
        self.gAdapter.add_objects_list(self.sim.actors.values())
        self.sim.update_actors()

    def create_sim_objects(self):
        """Adds the program's objects and joints to ``self.sim``: override it."""

    def set_key_2_action_mapping(self):
        self.key_press_functions = ActionMap()
        self.key_press_functions.add("r", self.reset_simulation)

    # -- running --------------------------------------------------------------------

    def run(self, duration):
        """Runs headless for ``duration`` seconds of simulated time (whole frames of
        ``1/FPS`` s) and returns the simulation."""
        frames = max(0, math.ceil(duration * self.FPS - 1e-9))
        self._own_simulation()
        for _ in range(frames):
            self.sim.on_idle()
        return self.sim

    def start(self, video=None):
        """Opens the viewer on the program until its window is closed; with no display,
        records ``ARS_DURATION`` seconds (default 10) off screen instead. With
        ``video="out.mp4"``, records those seconds off screen into that MP4 video
        (see ``record_video``), display or not."""
        self.do_create_window = False
        if video is not None:
            duration = float(os.environ.get("ARS_DURATION", "10"))
            made = self.record_video(video, duration)
            print(
                f"ars: wrote {made['path']}: {made['frames']} frames, {made['duration']:g} s",
                file=sys.stderr,
            )
            return
        if _native.has_display():
            self.show()
            return
        duration = float(os.environ.get("ARS_DURATION", "10"))
        stem = "".join(c if c.isalnum() else "_" for c in self.WINDOW_TITLE.lower())
        import tempfile  # here: most programs never record without a display

        folder = os.path.join(tempfile.gettempdir(), f"ars-frames-{stem}")
        print(
            f"ars: no display (DISPLAY and WAYLAND_DISPLAY are unset): recording {duration:g} s "
            f"of {type(self).__name__} off screen, frames into {folder} (set ARS_DURATION to change)",
            file=sys.stderr,
        )
        written = self.record(folder, duration)
        print(f"ars: wrote {len(written)} frames into {folder}", file=sys.stderr)

    def _view(self):
        """The viewer's settings: the window's title, size, colour and camera (the
        original's zoom brings the camera nearer the origin)."""
        zoom = self.WINDOW_ZOOM if self.WINDOW_ZOOM and self.WINDOW_ZOOM > 0 else 1.0
        return {
            "size": tuple(int(v) for v in self.WINDOW_SIZE),
            "camera": tuple(float(c) / zoom for c in self.CAMERA_POSITION),
            "look_at": (0.0, 0.0, 0.0),
            "background": tuple(float(c) for c in self.BACKGROUND_COLOR),
        }

    def show(self, duration=None, frames=None):
        """Opens the viewer's window on the program (needs a display) until it is
        closed, for ``duration`` seconds of wall time, or until it has run ``frames``
        frames (the last one drawn); returns what the run measured (frames, seconds,
        real-time factor)."""
        with self._viewed() as driver:
            return _native.show_program(
                driver, duration=duration, frames=frames, title=self.WINDOW_TITLE, **self._view()
            )

    def record(self, folder, duration, every=5):
        """Runs ``duration`` seconds of simulated time off screen, writing
        ``frame_00001.png`` (before any step), then one image every ``every`` frames,
        into ``folder``; returns the paths written."""
        if every < 1:
            raise exc.ArsError(f"every must be at least one frame, got {every}")
        os.makedirs(folder, exist_ok=True)
        written = []
        with self._viewed() as driver:

            def write():
                path = os.path.join(folder, f"frame_{len(written) + 1:05d}.png")
                driver.snapshot(path)
                written.append(path)

            write()
            for frame in range(1, max(0, math.ceil(duration * self.FPS - 1e-9)) + 1):
                driver.frame()
                if frame % every == 0:
                    write()
        return written

    def record_video(self, path, duration, fps=30):
        """Runs ``duration`` seconds of simulated time off screen into an H.264 MP4
        video at ``path`` (the window's size and camera); returns a dict of what it
        holds. The program's frames run in Python, so frame k is the picture at the
        first frame start at or after k/fps simulated seconds (at most one frame of
        ``1/FPS`` late; ``Simulation.record_video`` takes it at the step)."""
        view = self._view()
        width, height = view.pop("size")
        writer = _native.VideoWriter(path, width, height, fps, **view)
        count = max(1, math.ceil(duration * fps - 1e-9))
        try:
            with self._viewed() as driver:
                start = self.sim.sim_time
                taken = 0
                frames = max(0, math.ceil(duration * self.FPS - 1e-9))
                for frame in range(frames + 1):
                    now = self.sim.sim_time - start
                    while taken < count and now >= taken / fps - 1e-9:
                        writer.add(driver.native())
                        taken += 1
                    if frame < frames:
                        driver.frame()
            return writer.finish()
        finally:
            writer.close()

    @contextlib.contextmanager
    def _viewed(self):
        """The viewer's driver of this program; while it is in use, the screenshot
        recorder writes through it."""
        self._own_simulation()
        driver = _ViewerDriver(self)
        self.gAdapter.snapshot = driver.snapshot
        try:
            yield driver
        finally:
            self.do_create_window = False
            if self.gAdapter is not None:
                self.gAdapter.snapshot = None

    def finalize(self):
        if self.gAdapter is not None:
            self.gAdapter.finalize_window()
        self.do_create_window = False
        self.key_press_functions = None
        self.sim = None
        self._screenshot_recorder = None
        self.gAdapter = None

    def reset_simulation(self):
        """Builds the simulation anew (the handlers stay connected)."""
        logger.info("reset simulation")
        self.do_create_window = True
        self.gAdapter.reset()
        self.create_simulation()
        self._own_simulation()

    def on_action_selection(self, key):
        """What a key press does: a held key's action runs in every step of the next
        frame, the others' at once."""
        logger.info("key: %s", key)
        try:
            if self.key_press_functions.has_key(key):
                if self.key_press_functions.is_repeat(key):
                    self.sim.all_frame_steps_callbacks.append(
                        self.key_press_functions.get_function(key)
                    )
                else:
                    self.key_press_functions.call(key)
            else:
                logger.info("unregistered key: %s", key)
        except Exception:
            logger.exception("Exception when handling key %r", key)

    def on_pre_step(self):
        raise NotImplementedError

    def on_pre_frame(self):
        raise NotImplementedError

    # -- screenshots ----------------------------------------------------------------

    def create_screenshot_recorder(self, base_filename, periodically=False):
        self._screenshot_recorder = gp.ScreenshotRecorder(base_filename, self.gAdapter)
        if periodically:
            self._screenshot_recorder.period = 1.0 / self.FPS
        dispatcher.connect(self.record_frame, signals.SIM_PRE_FRAME)

    def record_frame(self):
        if self._screenshot_recorder is None:
            raise exc.ArsError("Screenshot recorder is not initialized")
        try:
            if self._screenshot_recorder.period is None:
                self._screenshot_recorder.write(self.sim.num_frame)
            else:
                self._screenshot_recorder.write(self.sim.num_frame, self.sim.sim_time)
        except Exception as e:
            raise exc.ArsError("Could not record frame") from e


# The keys that close the window, as VTK's interactor closed the original's.
_QUIT_KEYS = ("e", "q")


class _ViewerDriver:
    """What the viewer calls to run a program: its frames, its reset, its keys. A key
    held down whose action repeats acts in every step while it is held; a one-shot key
    acts at every press (and the system's auto-repeat), as in the original."""

    def __init__(self, program):
        self.program = program
        self.held = set()
        self._renderer = None

    def native(self):
        self.program.sim._sync_colors()
        return self.program.sim.native

    def frame(self):
        keys = self.program.key_press_functions
        for key in sorted(self.held):
            if keys is not None and keys.has_key(key) and keys.is_repeat(key):
                self.program.on_action_selection(key)
        self.program.sim.on_idle()

    def step(self):
        self.program.sim.native.step(1)

    def reset(self):
        self.held.clear()
        self.program.on_action_selection("r")

    def key(self, name, down):
        """Acts for a key going down or up; true when the window should close: ``e``
        and ``q`` quit, as VTK's keys did in the original (after the program's own
        action for them, if it has one)."""
        keys = self.program.key_press_functions
        repeats = keys is not None and keys.has_key(name) and keys.is_repeat(name)
        if not down:
            self.held.discard(name)
            return False
        if name in self.held and repeats:
            return False  # auto-repeat of a held key: frame() acts for it
        self.held.add(name)
        self.program.on_action_selection(name)
        return name in _QUIT_KEYS

    def snapshot(self, path):
        """Writes the simulation as it is now to a PNG (the screenshot recorder's)."""
        if self._renderer is None:
            view = self.program._view()
            width, height = view.pop("size")
            self._renderer = _native.Renderer(width, height, **view)
        self._renderer.save(self.native(), path)
