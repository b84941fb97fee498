"""`ArsEnv`'s constructor contract: `render_mode` and `max_episode_steps` reach the
environment however a subclass writes its `__init__` (passing them on, taking none,
taking one and forgetting to pass it), so that `gymnasium.make(id,
render_mode="rgb_array")` renders and `make_vec` makes any registered `ArsEnv`; and
the limit on `make_vec`'s `num_envs`."""

import itertools
import math

import numpy as np
import pytest

gymnasium = pytest.importorskip("gymnasium")

import ars
import ars.gym
from ars.gym import ArsEnv
from ars.gym.env import float_box

_ids = itertools.count()


class Pendulum(ArsEnv):
    """The docs' `Swing`, without an `__init__`: the scene and the task."""

    frame_skip, max_episode_steps, actuators = 20, 200, ("hinge",)
    action_space = float_box([-2.0], [2.0])
    observation_space = float_box([-1, -1, -np.inf], [1, 1, np.inf])
    render_size = (64, 48)

    def build(self):
        sim = ars.Simulation(time_step=0.001)
        sim.add_sphere(0.05, (0.5, 1.0, 0.0), mass=1.0, name="bob")
        sim.add_rotary_joint("hinge", "bob", None, (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))
        return sim

    def observe(self):
        q = self.sim.joint("hinge")
        return np.array([math.cos(q.angle), math.sin(q.angle), q.rate])

    def reward(self, obs, action):
        return -abs(math.atan2(obs[1], obs[0]))


class PassesThemOn(Pendulum):
    """As the docs write it now: keywords passed on to `ArsEnv.__init__`."""

    def __init__(self, **kwargs):
        self.goal = 0.0
        super().__init__(**kwargs)


class TakesNone(Pendulum):
    """As the docs wrote it before: an `__init__` without parameters."""

    def __init__(self):
        self.goal = 0.0
        super().__init__()


class ForgetsToPassThem(Pendulum):
    """Takes `render_mode`, keeps it, and calls `super().__init__()` without it."""

    def __init__(self, render_mode=None, max_episode_steps=None):
        self.render_mode = render_mode
        super().__init__()


class Grandchild(TakesNone):
    """A subclass of a subclass, with an `__init__` of its own."""

    def __init__(self, scale=1.0):
        self.scale = scale
        super().__init__()


def register(cls, max_episode_steps=7):
    env_id = f"test/Contract{next(_ids)}-v0"
    gymnasium.register(id=env_id, entry_point=cls, max_episode_steps=max_episode_steps)
    return env_id


CLASSES = [PassesThemOn, TakesNone, ForgetsToPassThem, Grandchild]


@pytest.mark.parametrize("cls", CLASSES, ids=lambda c: c.__name__)
def test_gymnasium_make_renders_whatever_the_subclass_init(cls):
    env = gymnasium.make(register(cls), render_mode="rgb_array")
    assert env.unwrapped.render_mode == "rgb_array"
    env.reset(seed=0)
    image = env.render()
    assert isinstance(image, np.ndarray) and image.shape == (48, 64, 3)
    env.close()


@pytest.mark.parametrize("cls", CLASSES, ids=lambda c: c.__name__)
def test_the_registered_episode_length_reaches_the_environment(cls):
    # Gymnasium applies it with its TimeLimit wrapper; make_vec passes it on (below).
    env = gymnasium.make(register(cls, max_episode_steps=3))
    env.reset(seed=0)
    truncated = [env.step([0.0])[3] for _ in range(3)]
    assert truncated == [False, False, True]


@pytest.mark.parametrize("cls", CLASSES, ids=lambda c: c.__name__)
def test_make_vec_makes_any_registered_ars_env(cls):
    env_id = register(cls, max_episode_steps=5)
    envs = ars.gym.make_vec(env_id, num_envs=2, render_mode="rgb_array")
    obs, _ = envs.reset(seed=1)
    assert obs.shape == (2, 3)
    assert all(e.max_episode_steps == 5 for e in envs.envs)
    obs, rewards, _, truncated, _ = envs.step(np.zeros((2, 1)))
    assert rewards.shape == (2,) and not truncated.any()
    assert all(image.shape == (48, 64, 3) for image in envs.render())
    envs.close()
    # Gymnasium's own vector environment makes them too.
    sync = gymnasium.make_vec(env_id, num_envs=2, vectorization_mode="sync")
    assert sync.reset(seed=1)[0].shape == (2, 3)
    sync.close()


def test_an_init_argument_of_its_own_is_still_taken():
    env = Grandchild(scale=2.0, render_mode="rgb_array")
    assert env.scale == 2.0 and env.render_mode == "rgb_array"
    with pytest.raises(TypeError, match="scale"):
        Grandchild(2.0, scale=3.0)


def test_a_bad_render_mode_is_still_refused():
    with pytest.raises(ars.InputError, match="render_mode"):
        TakesNone(render_mode="video")


def test_an_init_that_does_not_call_super_names_the_fix():
    class NoSuper(Pendulum):
        def __init__(self):
            self.goal = 0.0

    with pytest.raises(TypeError, match=r"super\(\).__init__\(\)"):
        NoSuper()


def test_make_vec_refuses_more_than_its_limit_unless_asked():
    with pytest.raises(ars.InputError) as caught:
        ars.gym.make_vec("ars/ConicalPendulum-v0", num_envs=10**6)
    message = str(caught.value)
    assert "1024" in message and "allow_many=True" in message
    assert ars.gym.vector.MAX_NUM_ENVS == 1024
