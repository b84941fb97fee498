"""ARS as Gymnasium environments (Gymnasium ≥ 1.0: ``pip install ./python[gym]``).

Importing ``ars.gym`` registers the environments ``ars/ConicalPendulum-v0``,
``ars/SpeedProfile-v0`` and ``ars/Reach-v0``; without the import,
``gymnasium.make("ars.gym:ars/ConicalPendulum-v0")`` imports it first. ``ArsEnv`` is
the base class of a user's own environment, ``make_vec`` (or ``gymnasium.make_vec``)
steps many at once. See docs/python.md, "Gymnasium".
"""

from functools import partial

try:
    import gymnasium
except ImportError as e:  # pragma: no cover - what a user without the extra sees
    raise ImportError(
        "ars.gym needs Gymnasium 1.0 or later: pip install ./python[gym] (or pip install "
        "'gymnasium>=1.0')"
    ) from e

if int(gymnasium.__version__.split(".")[0]) < 1:  # pragma: no cover
    raise ImportError(
        f"ars.gym needs Gymnasium 1.0 or later, found {gymnasium.__version__}: "
        "pip install ./python[gym]"
    )

from ars.gym.env import ActionError, ArsEnv
from ars.gym.envs import ConicalPendulumEnv, ReachEnv, SpeedProfileEnv, arm_end_effector
from ars.gym.vector import ArsVectorEnv, make_vec

__all__ = [
    "ActionError",
    "ArsEnv",
    "ArsVectorEnv",
    "ConicalPendulumEnv",
    "ReachEnv",
    "SpeedProfileEnv",
    "arm_end_effector",
    "make_vec",
]

# The registered environments: id, class, episode length (steps).
_ENVIRONMENTS = (
    ("ars/ConicalPendulum-v0", "ConicalPendulumEnv", ConicalPendulumEnv.max_episode_steps),
    ("ars/SpeedProfile-v0", "SpeedProfileEnv", SpeedProfileEnv.max_episode_steps),
    ("ars/Reach-v0", "ReachEnv", ReachEnv.max_episode_steps),
)

for _id, _class, _steps in _ENVIRONMENTS:
    if _id not in gymnasium.registry:
        gymnasium.register(
            id=_id,
            entry_point=f"ars.gym.envs:{_class}",
            vector_entry_point=partial(make_vec, _id),
            max_episode_steps=_steps,
        )
