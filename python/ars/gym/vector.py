"""`ArsVectorEnv`: many ARS environments stepped at once by `ars.step_many`."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import gymnasium
import numpy as np
import numpy.typing as npt
from gymnasium.vector import AutoresetMode, VectorEnv
from gymnasium.vector.utils import batch_space

import ars
from ars.gym.env import ActionError, Array, ArsEnv

# Rewards and flags, one per environment.
Batch = npt.NDArray[Any]


class ArsVectorEnv(VectorEnv[Array, Array, Batch]):
    """`N` ARS environments as one Gymnasium vector environment: each step applies
    every environment's action in Python, then steps all `N` simulations in one call of
    `ars.step_many` (native threads, one per core, the GIL released), then reads their
    observations and rewards.

    The Gymnasium 1.x API: `reset(seed=)` (an int seeds environment `i` with
    `seed + i`; a list gives each its own), `step(actions)` with actions of shape
    `(N, *single_action_space.shape)`, batched `observation_space`/`action_space`,
    infos as dicts of arrays with their `_key` masks. Autoreset is Gymnasium's default
    next-step mode: the step after an environment's episode ended resets it (its
    action is ignored, its reward 0, neither terminated nor truncated). Each
    environment steps as it would alone, bit for bit.

    `envs` are `ArsEnv`s (not wrapped: the vector environment calls them directly; any
    other environment is a `TypeError`), all with the same `frame_skip` and spaces.
    """

    # Gymnasium's own declaration: a class attribute, read through instances.
    metadata: dict[str, Any] = {  # noqa: RUF012
        "autoreset_mode": AutoresetMode.NEXT_STEP,
        "render_modes": ["rgb_array"],
    }

    def __init__(self, envs: Sequence[ArsEnv]):
        envs = list(envs)
        if not envs:
            raise ars.InputError("a vector environment needs at least one environment")
        for i, env in enumerate(envs):
            if not isinstance(env, ArsEnv):
                inner = getattr(env, "unwrapped", None)
                hint = (
                    " (a wrapped ArsEnv: pass env.unwrapped; the vector environment does not "
                    "apply wrappers)"
                    if isinstance(inner, ArsEnv)
                    else ""
                )
                raise TypeError(
                    f"ArsVectorEnv steps ars.gym.ArsEnv environments: environment {i} is a "
                    f"{type(env).__name__}{hint}"
                )
        first = envs[0]
        for i, env in enumerate(envs[1:], 1):
            if env.frame_skip != first.frame_skip:
                raise ars.InputError(
                    f"environment {i} takes {env.frame_skip} steps per step, environment 0 "
                    f"{first.frame_skip}: a vector environment steps them together"
                )
            if (
                env.observation_space != first.observation_space
                or env.action_space != first.action_space
            ):
                raise ars.InputError(f"environment {i} has other spaces than environment 0")
        self.envs = envs
        self.num_envs = len(envs)
        self.single_observation_space = first.observation_space
        self.single_action_space = first.action_space
        self.observation_space = batch_space(first.observation_space, self.num_envs)
        self.action_space = batch_space(first.action_space, self.num_envs)
        self.render_mode = first.render_mode
        self.metadata = dict(self.metadata, render_fps=first.metadata.get("render_fps"))
        self._action_shape: tuple[int, ...] = tuple(first.action_space.shape or ())
        self._autoreset = np.zeros(self.num_envs, dtype=np.bool_)

    def reset(
        self,
        *,
        seed: int | Sequence[int | None] | None = None,
        options: dict[str, Any] | None = None,
    ) -> tuple[Array, dict[str, Any]]:
        """Resets every environment: with `seed + i` for environment `i` if `seed` is
        an int, `seed[i]` if a list, unseeded if `None`."""
        if seed is None:
            seeds: list[int | None] = [None] * self.num_envs
        elif isinstance(seed, (int, np.integer)):
            seeds = [int(seed) + i for i in range(self.num_envs)]
        else:
            seeds = list(seed)
            if len(seeds) != self.num_envs:
                raise ars.InputError(f"{len(seeds)} seeds for {self.num_envs} environments")
        observations = []
        infos: dict[str, Any] = {}
        for i, (env, s) in enumerate(zip(self.envs, seeds)):
            obs, info = env.reset(seed=s, options=options)
            observations.append(obs)
            infos = self._add_info(infos, info, i)
        self._autoreset[:] = False
        return np.stack(observations), infos

    def step(self, actions: Any) -> tuple[Array, Batch, Batch, Batch, dict[str, Any]]:
        """Applies each environment's action, steps all simulations at once
        (`ars.step_many`), and returns the batched results."""
        try:
            actions = np.asarray(actions, dtype=np.float64)
        except (TypeError, ValueError) as e:
            raise ActionError(f"the actions are not an array of numbers: {e}") from None
        expected = (self.num_envs, *self._action_shape)
        if actions.shape != expected:
            raise ActionError(
                f"the actions have shape {actions.shape}; this vector environment takes {expected}"
            )
        # Every action is checked before any is applied: a bad one changes nothing.
        stepping = [i for i in range(self.num_envs) if not self._autoreset[i]]
        checked = {i: self.envs[i]._check_action(actions[i]) for i in stepping}
        for i in stepping:
            self.envs[i].apply_action(checked[i])
        ars.step_many([self.envs[i].sim for i in stepping], self.envs[0].frame_skip)
        observations = []
        rewards = np.zeros(self.num_envs, dtype=np.float64)
        terminations = np.zeros(self.num_envs, dtype=np.bool_)
        truncations = np.zeros(self.num_envs, dtype=np.bool_)
        infos: dict[str, Any] = {}
        for i, env in enumerate(self.envs):
            if self._autoreset[i]:
                obs, info = env.reset()
            else:
                obs, rewards[i], terminations[i], truncations[i], info = env._end_step(checked[i])
            observations.append(obs)
            infos = self._add_info(infos, info, i)
        self._autoreset = terminations | truncations
        return np.stack(observations), rewards, terminations, truncations, infos

    def render(self) -> tuple[Any, ...] | None:
        """Each environment's image (`render_mode="rgb_array"`), else `None`."""
        if self.render_mode != "rgb_array":
            return None
        return tuple(env.render() for env in self.envs)

    def close_extras(self, **kwargs: Any) -> None:
        """Closes every environment."""
        for env in self.envs:
            env.close()


#: The most environments `make_vec` makes without `allow_many=True`: each holds a
#: simulation (and its snapshot), and more than a few per core only wait their turn.
MAX_NUM_ENVS = 1024


def make_vec(
    id: str, num_envs: int = 1, *, allow_many: bool = False, **kwargs: Any
) -> ArsVectorEnv:
    """`num_envs` copies of the registered ARS environment `id` (e.g.
    `"ars/ConicalPendulum-v0"`, or any registered `ArsEnv` subclass, made with
    `kwargs`) as one `ArsVectorEnv`, stepped together by `ars.step_many`. Also what
    `gymnasium.make_vec(id, num_envs)` gives for the `ars/` environments. More than
    `MAX_NUM_ENVS` (1024) environments need `allow_many=True`."""
    if isinstance(num_envs, bool) or not isinstance(num_envs, (int, np.integer)) or num_envs < 1:
        raise ars.InputError(f"num_envs must be 1 or more, got {num_envs!r}")
    if num_envs > MAX_NUM_ENVS and not allow_many:
        raise ars.InputError(
            f"num_envs={num_envs} is more than the limit of {MAX_NUM_ENVS} environments (each "
            "holds a simulation; on a few cores more only wait their turn): pass "
            "allow_many=True to make them"
        )
    spec = gymnasium.spec(id)
    if spec.entry_point is None:
        raise ars.InputError(f"{id} has no entry point")
    kwargs = {**spec.kwargs, **kwargs}
    if "max_episode_steps" not in kwargs and spec.max_episode_steps is not None:
        kwargs["max_episode_steps"] = spec.max_episode_steps
    creator: Any = spec.entry_point
    if isinstance(creator, str):
        creator = gymnasium.envs.registration.load_env_creator(creator)
    envs = [creator(**kwargs) for _ in range(int(num_envs))]
    vector = ArsVectorEnv(envs)
    vector.spec = spec
    return vector
