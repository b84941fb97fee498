"""`ArsEnv`: a Gymnasium environment around one `ars.Simulation`."""

from __future__ import annotations

import functools
import inspect
from collections.abc import Callable
from typing import Any, cast

import gymnasium
import numpy as np
import numpy.typing as npt

import ars

Array = npt.NDArray[np.float64]


class ActionError(ars.InputError):
    """An action an environment cannot take: of the wrong shape or type, or not finite.
    Also an `ars.InputError` and a `ValueError`. Nothing was applied or stepped: the
    environment can be stepped on with a good action."""


class ArsEnv(gymnasium.Env[Array, Array]):
    """A Gymnasium environment on one ARS simulation, for a user's own task.

    A subclass gives the scene and the task; `ArsEnv` does the rest (seeding, resets,
    the step loop, action checks, truncation, rendering):

    - `build(self) -> ars.Simulation`: makes the scene, once, when the environment
      is made; every reset restores the exact snapshot taken then (a Python hook's
      own variables are not in it: reset them in `randomize`);
    - `observe(self) -> numpy array`: the observation, in `observation_space`;
    - `reward(self, obs, action) -> float`: the reward of the step that led to `obs`;
    - `apply_action(self, action)`: puts the (checked) action on the simulation
      before the steps. By default each component is the torque (or force) of the
      joint of the same index in `actuators`, held through the step (a native
      `"torque"` controller);
    - `terminated(self, obs) -> bool` (default `False`): whether the episode ended
      in a terminal state;
    - `randomize(self, rng)`: the seeded part of an episode (a target, a start
      offset...), called by `reset` after the scene is restored, with the
      environment's `np_random`; by default nothing;
    - `info(self) -> dict` (default empty): the `info` of `reset` and `step`.

    and declares `observation_space` and `action_space` (`gymnasium.spaces.Box`),
    `frame_skip` (simulation steps per environment step), `max_episode_steps` (the
    step at which an episode is truncated; `None`: never) and, for rendering,
    `camera`, `look_at`, `follow` and `render_size` (see `ars.Renderer`).

    `step(action)` checks the action (an `ActionError`, a `ValueError`, for a wrong
    shape or a NaN or infinite component, before anything is applied), clips it to
    the action space's bounds, applies it, steps the simulation `frame_skip` steps and
    returns `(obs, reward, terminated, truncated, info)`. `render_mode="rgb_array"`
    draws off screen (`ars.Renderer`); `"human"` shows the state in ARS's window after
    every `reset` and `step` (and `render()`), one frame each: the window opens and
    closes each time (a display is needed).
    """

    # Gymnasium's class attribute. "human" where there is a display when `ars.gym` is
    # imported (without one, the window cannot open).
    metadata: dict[str, Any] = {  # noqa: RUF012
        "render_modes": ["rgb_array", "human"] if ars.has_display() else ["rgb_array"],
        "render_fps": 50,
    }

    #: Simulation steps per environment step.
    frame_skip: int = 1
    #: The step at which an episode is truncated (`None`: never).
    max_episode_steps: int | None = None
    #: The joints `apply_action` drives, one per action component.
    actuators: tuple[str, ...] = ()
    #: The renderer's camera position, the point it looks at, the object it follows.
    camera: tuple[float, float, float] = (10.0, 8.0, 10.0)
    look_at: tuple[float, float, float] = (0.0, 0.0, 0.0)
    follow: str | None = None
    #: The rendered image's (width, height), pixels.
    render_size: tuple[int, int] = (480, 360)

    def __init_subclass__(cls, **kwargs: Any) -> None:
        """Makes a subclass's own `__init__` forgiving (see `_forgiving_init`)."""
        super().__init_subclass__(**kwargs)
        init = cls.__dict__.get("__init__")
        if init is not None and not getattr(init, "_ars_forgiving", False):
            cls.__init__ = _forgiving_init(init)  # type: ignore[method-assign]

    def __init__(self, render_mode: str | None = None, max_episode_steps: int | None = None):
        # What the environment was made with (`gymnasium.make`, `make_vec`), kept by a
        # subclass's `__init__` wrapper: a subclass that does not pass `render_mode` or
        # `max_episode_steps` on to this `__init__` still gets them.
        requested = self.__dict__.pop("_ars_requested", {})
        if render_mode is None:
            render_mode = requested.get("render_mode", self.__dict__.get("render_mode"))
        if max_episode_steps is None:
            max_episode_steps = requested.get("max_episode_steps")
        if render_mode == "human" and not ars.has_display():
            raise ars.InputError('render_mode="human" needs a display: use "rgb_array"')
        if render_mode not in (None, "rgb_array", "human"):
            raise ars.InputError(f'render_mode {render_mode!r} is not None, "rgb_array" or "human"')
        self.render_mode = render_mode
        if max_episode_steps is not None:
            self.max_episode_steps = int(max_episode_steps)
        if int(self.frame_skip) < 1:
            raise ars.InputError(f"frame_skip must be 1 or more, got {self.frame_skip}")
        #: The simulation the environment steps (the same object for the
        #: environment's life: resets restore its state).
        self.sim: ars.Simulation = self.build()
        self._initial_state: bytes = self.sim.snapshot()
        self._elapsed = 0
        self._renderer: ars.Renderer | None = None

    # What a subclass gives.

    def build(self) -> ars.Simulation:
        """The scene: a new simulation, ready to step."""
        raise NotImplementedError(f"{type(self).__name__} must define build(self)")

    def observe(self) -> Array:
        """The observation now."""
        raise NotImplementedError(f"{type(self).__name__} must define observe(self)")

    def reward(self, obs: Array, action: Array) -> float:
        """The reward for the step that took `action` and led to `obs`."""
        raise NotImplementedError(f"{type(self).__name__} must define reward(self, obs, action)")

    def apply_action(self, action: Array) -> None:
        """Puts `action` on the simulation: by default, component `i` is the torque
        (force) of joint `actuators[i]`, held through the step."""
        if action.ndim != 1 or len(self.actuators) != action.shape[0]:
            raise NotImplementedError(
                f"{type(self).__name__} must define apply_action(self, action) or name one joint per "
                "action component in `actuators`"
            )
        for name, value in zip(self.actuators, action):
            self.sim.joint(name).set_controller("torque", float(value))

    def terminated(self, obs: Array) -> bool:
        """Whether the episode has ended in a terminal state (default: never)."""
        return False

    def randomize(self, rng: np.random.Generator) -> None:
        """The seeded part of an episode, drawn from `rng` (default: none)."""

    def info(self) -> dict[str, Any]:
        """The `info` of `reset` and `step` (default: empty)."""
        return {}

    # The Gymnasium API.

    def reset(
        self, *, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[Array, dict[str, Any]]:
        """Restores the scene's initial state (the snapshot taken after `build`: the
        same bits as a new environment), then calls `randomize` with the
        environment's random generator (seeded by `seed` if given)."""
        super().reset(seed=seed, options=options)
        self._restore_initial_state()
        self._elapsed = 0
        self.randomize(self.np_random)
        if self.render_mode == "human":
            self.render()
        return self.observe(), self.info()

    def step(self, action: Any) -> tuple[Array, float, bool, bool, dict[str, Any]]:
        """Takes `action` for `frame_skip` simulation steps."""
        checked = self._begin_step(action)
        self.sim.step(self.frame_skip)
        result = self._end_step(checked)
        if self.render_mode == "human":
            self.render()
        return result

    def render(self) -> npt.NDArray[np.uint8] | None:
        """`rgb_array`: the image now (height × width × 3, `uint8`); `human`: shows
        the state now in ARS's window (needs a display); no render mode: `None`."""
        if self.render_mode == "rgb_array":
            if self._renderer is None:
                width, height = self.render_size
                self._renderer = ars.Renderer(
                    width, height, camera=self.camera, look_at=self.look_at, follow=self.follow
                )
            return self._renderer.render(self.sim)
        if self.render_mode == "human":
            self.sim.show(
                frames=0,
                title=type(self).__name__,
                size=self.render_size,
                camera=self.camera,
                look_at=self.look_at,
                follow=self.follow,
            )
        return None

    def close(self) -> None:
        """Lets the renderer go."""
        self._renderer = None

    # The step in two halves, for the vector environment (which steps many
    # simulations at once between them).

    def _check_action(self, action: Any) -> Array:
        """`action` as a float64 array within the action space's bounds, or an
        `ActionError` naming what is wrong."""
        space = self.action_space
        if not isinstance(space, gymnasium.spaces.Box):
            raise TypeError(f"ArsEnv needs a Box action space, {type(self).__name__} has {space}")
        try:
            array = np.asarray(action, dtype=np.float64)
        except (TypeError, ValueError) as e:
            raise ActionError(f"the action {action!r} is not an array of numbers: {e}") from None
        if array.shape != space.shape:
            raise ActionError(
                f"the action has shape {array.shape}; {type(self).__name__} takes shape {space.shape}"
            )
        if not np.isfinite(array).all():
            raise ActionError(f"the action {array} has a NaN or infinite component")
        return np.clip(array, space.low, space.high)

    def _begin_step(self, action: Any) -> Array:
        """Checks and applies `action`; the simulation is then stepped by the caller."""
        checked = self._check_action(action)
        self.apply_action(checked)
        return checked

    def _end_step(self, action: Array) -> tuple[Array, float, bool, bool, dict[str, Any]]:
        """What the step that took `action` came to, once the simulation has stepped."""
        self._elapsed += 1
        obs = self.observe()
        reward = float(self.reward(obs, action))
        terminated = bool(self.terminated(obs))
        truncated = self.max_episode_steps is not None and self._elapsed >= self.max_episode_steps
        return obs, reward, terminated, truncated, self.info()

    def _restore_initial_state(self) -> None:
        """Puts the scene back as `build` made it: restores the exact snapshot taken
        then (bodies, joints, controllers, sensors, clock; records cleared)."""
        self.sim.restore(self._initial_state)


#: The keywords `gymnasium.make` and `make_vec` pass to an environment's constructor.
CONSTRUCTOR_KEYWORDS = ("render_mode", "max_episode_steps")


def _forgiving_init(init: Callable[..., None]) -> Callable[..., None]:
    """A subclass's `__init__`, forgiving about `ArsEnv.__init__`'s keywords
    (`render_mode`, `max_episode_steps`): those it does not take are not passed to it,
    and those given reach `ArsEnv.__init__` even when it calls `super().__init__()`
    without them. So `gymnasium.make(id, render_mode="rgb_array")` renders, and
    `make_vec` makes any registered `ArsEnv`, whichever way the subclass was written."""
    parameters = inspect.signature(init).parameters
    takes_any = any(p.kind is inspect.Parameter.VAR_KEYWORD for p in parameters.values())
    taken = {k for k in CONSTRUCTOR_KEYWORDS if takes_any or k in parameters}

    @functools.wraps(init)
    def forgiving(self: ArsEnv, *args: Any, **kwargs: Any) -> None:
        given = {k: kwargs[k] for k in CONSTRUCTOR_KEYWORDS if k in kwargs}
        # The outermost subclass's wrapper runs first: it alone records them.
        self.__dict__.setdefault("_ars_requested", given)
        for k in given.keys() - taken:
            del kwargs[k]
        init(self, *args, **kwargs)
        if "_ars_requested" in self.__dict__ and "sim" not in self.__dict__:
            raise TypeError(
                f"{type(self).__name__}.__init__ did not call super().__init__(): call it at "
                "the end of __init__, after setting the spaces and your own attributes"
            )

    forgiving._ars_forgiving = True  # type: ignore[attr-defined]
    return forgiving


def float_box(low: npt.ArrayLike, high: npt.ArrayLike) -> gymnasium.spaces.Space[Array]:
    """A float64 `gymnasium.spaces.Box` with these bounds."""
    box = gymnasium.spaces.Box(
        low=np.asarray(low, dtype=np.float64),
        high=np.asarray(high, dtype=np.float64),
        dtype=np.float64,
    )
    return cast("gymnasium.spaces.Space[Array]", box)
