"""A hand-written policy for ``ars/ConicalPendulum-v0``: the waist torque that holds the
target cone angle, from the steady state of the conical pendulum, against random
torques, over one seeded episode each, alone and in a vector environment of four.

    python gym_pendulum.py      (needs Gymnasium: pip install ./python[gym])

Typed throughout: ``mypy --strict`` checks it (``python/tests/test_docs.py``).
"""

import numpy as np
import numpy.typing as npt

import ars.gym

Array = npt.NDArray[np.float64]


def policy(obs: Array) -> Array:
    """Spin the waist at the rate whose cone is the target: faster while the arm is
    inside the target cone, slower outside (the torque bounded by the action space)."""
    waist_rate, cone, target = obs[2], obs[3], obs[5]
    wanted_rate = 3.0 + 3.0 * (target - cone)
    torque = 5.0 * wanted_rate + 40.0 * (wanted_rate - waist_rate)
    action: Array = np.clip(np.array([torque]), -20.0, 20.0)
    return action


def episode(env: ars.gym.ConicalPendulumEnv, seed: int, random: bool) -> float:
    """The return of one seeded episode, with the policy or with random torques."""
    obs, _ = env.reset(seed=seed)
    env.action_space.seed(seed)
    total, done = 0.0, False
    while not done:
        action = env.action_space.sample() if random else policy(obs)
        obs, reward, terminated, truncated, _ = env.step(action)
        total += reward
        done = terminated or truncated
    return total


def main() -> None:
    env = ars.gym.ConicalPendulumEnv()
    for seed in (1, 2):
        print(
            f"seed {seed}: policy {episode(env, seed, False):.2f}, random {episode(env, seed, True):.2f}"
        )
    envs = ars.gym.make_vec("ars/ConicalPendulum-v0", num_envs=4)
    obs, _ = envs.reset(seed=10)
    for _ in range(250):
        obs, _, _, _, _ = envs.step(np.stack([policy(o) for o in obs]))
    print("after 5 s, cone angles", obs[:, 3].round(3), "targets", obs[:, 5].round(3))


if __name__ == "__main__":
    main()
