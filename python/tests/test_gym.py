"""Many simulations at once (`ars.step_many`) and ARS as Gymnasium environments
(`ars.gym`): stepping many equals stepping each alone, bit for bit; bad input is
refused before anything steps; the three registered environments pass Gymnasium's
checker and replay a seeded rollout bit for bit, alone, twice, and in the vector
environment."""

import struct
import subprocess
import sys
import warnings
from importlib import resources

import numpy as np
import pytest
from conftest import window_env

import ars

gymnasium = pytest.importorskip("gymnasium")
from gymnasium.utils.env_checker import check_env

import ars.gym

IDS = ["ars/ConicalPendulum-v0", "ars/SpeedProfile-v0", "ars/Reach-v0"]


def bits(array):
    """The exact bytes of a float64 array (NaN-safe, sign-of-zero-safe equality)."""
    return np.ascontiguousarray(array, dtype=np.float64).tobytes()


# ars.gym


def test_import_ars_needs_no_gymnasium_and_ars_gym_says_how_to_get_it():
    code = (
        "import sys\n"
        "sys.modules['gymnasium'] = None\n"  # makes `import gymnasium` fail
        "import ars\n"
        "ars.Simulation().step(1)\n"
        "try:\n"
        "    import ars.gym\n"
        "except ImportError as e:\n"
        "    print('refused:', e)\n"
    )
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert "refused:" in run.stdout and "pip install ./python[gym]" in run.stdout


def test_the_module_colon_id_form_needs_no_import_of_ars_gym():
    code = (
        "import gymnasium\n"
        "env = gymnasium.make('ars.gym:ars/Reach-v0')\n"
        "print(env.reset(seed=1)[0].shape, env.spec.max_episode_steps)\n"
    )
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert run.stdout.strip() == "(18,) 200"


@pytest.mark.parametrize("env_id", IDS)
def test_each_environment_passes_gymnasiums_checker(env_id):
    env = gymnasium.make(env_id, render_mode="rgb_array")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        check_env(env.unwrapped)
    # What the checker may say: its advice on normalised action spaces and unbounded
    # observations (what the environments document), nothing else.
    advice = ("symmetric and normalized space", "infinity")
    others = [str(w.message) for w in caught if not any(a in str(w.message) for a in advice)]
    assert not others, others
    env.reset(seed=0)
    image = env.render()
    assert image.shape == (360, 480, 3) and image.dtype == np.uint8
    # The robot is in the picture: more than the floor and the sky.
    assert len(np.unique(image.reshape(-1, 3), axis=0)) > 50
    env.close()


def test_human_rendering_shows_each_step_in_the_window(display, tmp_path):
    code = (
        "import gymnasium, ars.gym\n"
        "assert 'human' in ars.gym.ArsEnv.metadata['render_modes']\n"
        "env = gymnasium.make('ars/Reach-v0', render_mode='human')\n"
        "env.reset(seed=0)\n"
        "for _ in range(2):\n"
        "    env.step(env.action_space.sample())\n"
        "print(env.unwrapped.sim.step_count, env.render())\n"
    )
    run = subprocess.run(
        [sys.executable, "-c", code],
        env=window_env(display, tmp_path),
        capture_output=True,
        text=True,
        timeout=120,
        check=False,
    )
    assert run.returncode == 0, run.stderr[-2000:]
    # Shown, not stepped: the window's frames add no steps.
    assert run.stdout.split() == ["40", "None"]


def rollout(env, actions, seed):
    """Observations, rewards and flags of a rollout of `actions` from `reset(seed)`,
    with the vector environment's autoreset: the step after an episode ends resets
    it (reward 0) and its action is not taken."""
    obs, _ = env.reset(seed=seed)
    out, done = [bits(obs)], False
    for action in actions:
        if done:
            obs, _ = env.reset()
            reward, terminated, truncated = 0.0, False, False
        else:
            obs, reward, terminated, truncated, _ = env.step(action)
        done = terminated or truncated
        out.append((bits(obs), struct.pack("<d", reward), terminated, truncated))
    return out


def actions_for(env_id, n, seed):
    space = gymnasium.make(env_id).action_space
    space.seed(seed)
    return [space.sample() for _ in range(n)]


@pytest.mark.parametrize("env_id", IDS)
def test_a_seeded_rollout_is_the_same_twice_and_in_the_vector_environment(env_id):
    actions = actions_for(env_id, 1000, seed=7)
    first = rollout(gymnasium.make(env_id), actions, seed=11)
    second = rollout(gymnasium.make(env_id), actions, seed=11)
    assert first == second
    # An episode ended along the way (truncation at least), and the env moved.
    assert any(t or u for *_, t, u in first[1:])
    assert len({o for o, *_ in first[1:]}) > 900

    vector = gymnasium.make_vec(env_id, num_envs=2)
    assert isinstance(vector, ars.gym.ArsVectorEnv)
    obs, _ = vector.reset(seed=[11, 11])
    rows = [[bits(obs[0])], [bits(obs[1])]]
    for action in actions:
        obs, rewards, terminated, truncated, _ = vector.step(np.stack([action, action]))
        for i in range(2):
            rows[i].append(
                (bits(obs[i]), struct.pack("<d", rewards[i]), terminated[i], truncated[i])
            )
    assert rows[0] == first
    assert rows[1] == first


@pytest.mark.parametrize("env_id", IDS)
def test_reset_restores_the_initial_state_and_steps_on_as_a_new_environment(env_id):
    used = gymnasium.make(env_id).unwrapped
    sim = used.sim
    used.reset(seed=1)
    for action in actions_for(env_id, 30, seed=2):
        used.step(action)
    assert sim.step_count > 0
    new = gymnasium.make(env_id).unwrapped
    # The same simulation, restored (not rebuilt), on as a new environment does.
    a, info_a = used.reset(seed=5)
    b, info_b = new.reset(seed=5)
    assert used.sim is sim and sim.time == 0.0 and sim.step_count == 0
    assert bits(a) == bits(b) and info_a == info_b
    for action in actions_for(env_id, 50, seed=3):
        got, want = used.step(action), new.step(action)
        assert bits(got[0]) == bits(want[0]) and got[1:] == want[1:]


def test_another_seed_draws_another_task():
    env = ars.gym.ReachEnv()
    first, _ = env.reset(seed=5)
    other, _ = env.reset(seed=6)
    assert bits(other[12:15]) != bits(first[12:15])  # another target
    assert bits(other[:12]) == bits(first[:12])  # the same arm, at rest


@pytest.mark.parametrize(
    "action, message",
    [
        ([1.0, 2.0], "shape"),
        ([[1.0]], "shape"),
        (1.0, "shape"),
        ([float("nan")], "NaN"),
        ([float("inf")], "NaN or infinite"),
        (["left"], "not an array of numbers"),
    ],
)
def test_a_bad_action_is_refused_and_the_environment_steps_on_as_if_it_never_came(action, message):
    env = ars.gym.ConicalPendulumEnv()
    reference = ars.gym.ConicalPendulumEnv()
    env.reset(seed=1)
    reference.reset(seed=1)
    env.step([5.0])
    reference.step([5.0])
    with pytest.raises(ars.gym.ActionError, match=message) as raised:
        env.step(action)
    assert isinstance(raised.value, ValueError) and isinstance(raised.value, ars.ArsError)
    assert env.sim.step_count == 80
    got = env.step([-3.0])
    want = reference.step([-3.0])
    assert bits(got[0]) == bits(want[0]) and got[1:] == want[1:]


def test_actions_beyond_the_bounds_are_clipped_to_them():
    a, b = ars.gym.ConicalPendulumEnv(), ars.gym.ConicalPendulumEnv()
    a.reset(seed=0)
    b.reset(seed=0)
    assert bits(a.step([1e6])[0]) == bits(b.step([20.0])[0])


def test_the_vector_environment_refuses_bad_actions_before_any_environment_steps():
    vector = ars.gym.make_vec("ars/ConicalPendulum-v0", num_envs=3)
    vector.reset(seed=0)
    counts = [env.sim.step_count for env in vector.envs]
    with pytest.raises(ars.gym.ActionError, match="shape"):
        vector.step(np.zeros((2, 1)))
    with pytest.raises(ars.gym.ActionError, match="NaN"):
        vector.step(np.array([[1.0], [float("nan")], [2.0]]))
    with pytest.raises(ars.gym.ActionError, match="not an array of numbers"):
        vector.step([["a"], [1.0], [2.0]])
    assert [env.sim.step_count for env in vector.envs] == counts
    vector.step(np.ones((3, 1)))
    assert [env.sim.step_count for env in vector.envs] == [80, 80, 80]


def test_a_vector_environment_of_non_ars_environments_is_refused():
    with pytest.raises(TypeError, match="environment 0 is a TimeLimit .*pass env.unwrapped"):
        ars.gym.ArsVectorEnv([gymnasium.make("ars/Reach-v0")])
    with pytest.raises(TypeError, match="environment 1 is a str"):
        ars.gym.ArsVectorEnv([ars.gym.ReachEnv(), "CartPole-v1"])
    with pytest.raises(ars.InputError, match="steps per step"):
        ars.gym.ArsVectorEnv([ars.gym.ReachEnv(), ars.gym.ConicalPendulumEnv()])
    with pytest.raises(ars.InputError, match="num_envs"):
        ars.gym.make_vec("ars/Reach-v0", num_envs=0)


def test_the_vector_environment_resets_an_ended_episode_on_the_next_step():
    vector = ars.gym.make_vec("ars/Reach-v0", num_envs=2, max_episode_steps=3)
    vector.reset(seed=1)
    for _ in range(2):
        vector.step(np.zeros((2, 3)))
    _, rewards, terminated, truncated, _ = vector.step(np.zeros((2, 3)))
    assert truncated.all() and not terminated.any()
    _, rewards, terminated, truncated, _ = vector.step(np.ones((2, 3)))
    assert (rewards == 0.0).all() and not truncated.any()
    assert [env.sim.step_count for env in vector.envs] == [0, 0]


def test_the_pendulum_swings_out_with_the_waist_torque():
    env = ars.gym.ConicalPendulumEnv()
    obs, _ = env.reset(seed=0)
    assert 0.1 <= obs[5] <= 0.6 and obs[3] == 0.0
    rewards = []
    for _ in range(250):
        obs, reward, *_ = env.step([20.0])
        rewards.append(reward)
    # 5 s of the largest torque: the waist near its 4 rad/s, the arm far out.
    assert 3.5 < obs[2] < 4.0 and obs[3] > 0.6
    assert rewards[-1] == pytest.approx(-((obs[3] - obs[5]) ** 2) - 1e-3)


def test_the_thesis_controller_tracks_the_speed_profile():
    env = ars.gym.SpeedProfileEnv(peak_speed=1.0)
    obs, _ = env.reset(seed=0)
    errors = []
    for _ in range(400):  # 8 s: up the ramp and onto the plateau
        torque = 10.0 * (obs[1] - obs[0])
        obs, _reward, terminated, *_ = env.step([torque, torque])
        assert not terminated
        if obs[3] > 6.0:
            errors.append(obs[0] - obs[1])
    assert obs[1] == 1.0 and obs[2] == pytest.approx(1.0)
    assert abs(np.mean(errors)) < 0.05


def test_the_reach_target_is_where_the_arm_would_be_at_the_drawn_angles():
    # The forward kinematics the targets are drawn with agree with ARS's URDF arm.
    for q in [(0.0, 0.0, 0.0), (0.4, -0.7, 1.1), (-2.5, 1.0, -0.6)]:
        sim = ars.Simulation()
        env = ars.gym.ReachEnv()
        path = resources.files("ars.gym") / "reach_arm.urdf"
        sim.load_urdf(str(path), fixed_base=True, initial_positions=dict(zip(env.actuators, q)))
        assert [sim.joint(j).angle for j in env.actuators] == pytest.approx(q, abs=1e-12)
        assert ars.gym.arm_end_effector(q) == pytest.approx(sim.body("fore").position, abs=1e-9)


def test_the_reach_kinematics_are_read_from_the_urdf_by_its_links(tmp_path):
    # An arm moved in a copy of reach_arm.urdf, with its joints listed in reverse: the
    # kinematics parsed from the copy follow it and agree with ARS loading the copy.
    from ars.gym.envs import _end_effector, _parse_arm

    text = (resources.files("ars.gym") / "reach_arm.urdf").read_text(encoding="utf-8")
    joints = ars.gym.ReachEnv.actuators
    shipped = _parse_arm(text, joints)
    for old, new in [
        ('xyz="0 0 0.3" rpy="0 0 0.4"', 'xyz="0.05 -0.02 0.25" rpy="0.1 0 0.4"'),  # j2
        ('<axis xyz="0 0.6 0.8"/>', '<axis xyz="0.6 0 0.8"/>'),  # j3
        ('xyz="0.15 0 0.02" rpy="0 0.5 0"', 'xyz="0.12 0.01 0.03" rpy="0 0.5 0"'),  # fore's mass
    ]:
        assert text.count(old) == 1
        text = text.replace(old, new)
    first, last = text.index("<joint "), text.rindex("</joint>") + len("</joint>")
    blocks = [b + "</joint>" for b in text[first:last].split("</joint>")[:-1]]
    text = text[:first] + "".join(reversed(blocks)) + text[last:]
    moved = _parse_arm(text, joints)
    assert [j.name for j in moved[0]] == list(joints)
    path = tmp_path / "moved_arm.urdf"
    path.write_text(text, encoding="utf-8")
    for q in [(0.0, 0.0, 0.0), (0.4, -0.7, 1.1), (-2.5, 1.0, -0.6)]:
        sim = ars.Simulation()
        sim.load_urdf(str(path), fixed_base=True, initial_positions=dict(zip(joints, q)))
        effector = _end_effector(moved, q, (0.0, 0.0, 0.0))
        assert effector == pytest.approx(sim.body("fore").position, abs=1e-9)
        assert bits(ars.gym.arm_end_effector(q)) == bits(_end_effector(shipped, q, (0, 0, 0)))
        assert np.linalg.norm(effector - ars.gym.arm_end_effector(q)) > 1e-3


def test_a_reach_urdf_without_a_joint_or_link_of_the_arm_is_refused_by_name():
    from ars.gym.envs import _parse_arm

    text = (resources.files("ars.gym") / "reach_arm.urdf").read_text(encoding="utf-8")
    joints = ars.gym.ReachEnv.actuators
    j2 = text[text.index('<joint name="j2"') : text.index("</joint>", text.index('"j2"')) + 8]
    with pytest.raises(ValueError, match=r"from the link 'upper' to 'fore' are \[j3"):
        _parse_arm(text.replace(j2, ""), joints)
    with pytest.raises(ValueError, match="no link 'fore'"):
        _parse_arm(text.replace('<link name="fore">', '<link name="forearm">'), joints)
    with pytest.raises(ValueError, match="parent link 'turret' of the joint 'j2' is missing"):
        _parse_arm(text.replace('<link name="turret">', '<link name="tower">'), joints)


def test_a_subclass_that_leaves_out_a_part_is_told_which():
    class Empty(ars.gym.ArsEnv):
        def build(self):
            return ars.Simulation()

    env = Empty()
    with pytest.raises(NotImplementedError, match="observe"):
        env.reset()
