"""The limits of the calls a typo would run for hours, and the smaller edges a new
user met (issue 38): a video under another format's suffix, `dir(ars)`, saving an
environment's image as PNG, the default contact friction."""

import os
import struct

import numpy as np
import pytest

import ars


def ball():
    sim = ars.Simulation()
    sim.add_floor()
    sim.add_sphere(0.1, (0.0, 1.0, 0.0), mass=1.0, name="ball")
    return sim


@pytest.mark.parametrize(
    ("record", "words"),
    [
        (lambda sim, d: sim.record_video(d / "v.mp4", 1e9, size=(64, 48)), "limit of 3600"),
        (
            lambda sim, d: sim.record_video(d / "v.mp4", 200.0, fps=1000, size=(64, 48)),
            "limit of 108000 frames",
        ),
        (lambda sim, d: sim.save_replay(d / "r.html", 1e9), "limit of 3600"),
        (lambda sim, d: sim.replay(3600.5), "limit of 3600"),
    ],
    ids=["video duration", "video frames", "save_replay", "replay"],
)
def test_a_recording_past_its_limit_is_refused_before_anything_runs(tmp_path, record, words):
    sim = ball()
    with pytest.raises(ars.InputError) as caught:
        record(sim, tmp_path)
    assert words in str(caught.value) and "allow_long=True" in str(caught.value)
    assert os.listdir(tmp_path) == [] and sim.time == 0.0


def test_allow_long_lets_a_long_replay_through():
    # 3601 s of a ball at rest, in memory: a second or two.
    sim = ars.Simulation(time_step=0.01, steps_per_frame=100)
    sim.add_sphere(0.1, (0.0, 1.0, 0.0), mass=1.0)
    sim.gravity = (0.0, 0.0, 0.0)
    replay = sim.replay(3601.0, allow_long=True, fps=0.1)
    assert replay.end == pytest.approx(3600.0)


@pytest.mark.parametrize("name", ["x.avi", "x.mkv", "x", "x.mp4.part"])
def test_a_video_path_with_another_suffix_is_refused(tmp_path, name):
    with pytest.raises(ars.InputError, match=r"suffix \.mp4"):
        ball().record_video(tmp_path / name, 0.1, size=(64, 48))
    with pytest.raises(ars.InputError, match=r"suffix \.mp4"):
        ars.VideoWriter(tmp_path / name, 64, 48)
    assert os.listdir(tmp_path) == []


def test_an_upper_case_or_m4v_suffix_is_an_mp4(tmp_path):
    for name in ("A.MP4", "b.m4v"):
        assert ball().record_video(tmp_path / name, 0.1, size=(64, 48))["frames"] == 3
    assert sorted(os.listdir(tmp_path)) == ["A.MP4", "b.m4v"]


def test_dir_ars_shows_ars_own_names():
    names = dir(ars)
    for helper in ("atexit", "importlib", "os", "TYPE_CHECKING", "_native", "_os"):
        assert helper not in names
    for public in ("Simulation", "sweep", "Image", "InputError", "__version__", "__doc__"):
        assert public in names


def test_an_image_is_saved_as_png(tmp_path):
    image = ars.Renderer(64, 48, camera=(2.0, 1.5, 2.0)).render(ball())
    image.save(tmp_path / "frame.png")
    data = (tmp_path / "frame.png").read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n" and data == image._repr_png_()
    width, height, depth, colour = struct.unpack(">IIBB", data[16:26])
    assert (width, height, depth, colour) == (64, 48, 8, 2)
    assert os.listdir(tmp_path) == ["frame.png"]
    with pytest.raises(ars.FileError) as caught:
        image.save(tmp_path / "missing" / "frame.png")
    assert caught.value.filename == str(tmp_path / "missing" / "frame.png")


def test_an_env_image_is_saved_as_png(tmp_path):
    gymnasium = pytest.importorskip("gymnasium")
    import ars.gym  # noqa: F401  (registers the environments)

    env = gymnasium.make("ars/ConicalPendulum-v0", render_mode="rgb_array")
    env.reset(seed=0)
    env.render().save(tmp_path / "pendulum.png")
    assert (tmp_path / "pendulum.png").read_bytes()[:4] == b"\x89PNG"
    env.close()


def pushed_box(coulomb):
    """A 1 kg box on the default floor pushed by 5 N for 1 s: how far it went (m)."""
    sim = ars.Simulation()
    sim.add_floor()
    sim.add_box((0.2, 0.2, 0.2), (0.0, 0.1, 0.0), mass=1.0, name="box")
    if coulomb:
        sim.set_contact_surface(mu=0.3, approx1=True)
    push = sim.add_pre_step(lambda: sim.body("box").add_force((5.0, 0.0, 0.0)))
    sim.run(1.0)
    sim.remove_hook(push)
    return float(sim.body("box").position[0])


def test_the_default_friction_is_a_force_limit_and_approx1_a_coefficient():
    # As the ArsEnv section of docs/python.md says: 5 N never moves it on the default
    # floor (mu = 500 N per contact and direction); with Coulomb's mu = 0.3 (2.9 N of
    # friction) it slides about (5 - 2.9) / 2 m in 1 s.
    assert abs(pushed_box(coulomb=False)) < 1e-3
    assert 0.5 < pushed_box(coulomb=True) < 1.5
    assert np.isfinite(pushed_box(coulomb=True))


def test_a_robot_with_nothing_to_draw_is_not_recorded(tmp_path):
    # The dynamics test arm: links with neither visuals nor collision geometry.
    arm = os.path.join(os.path.dirname(__file__), "..", "..", "tests", "data", "rnea_arm.urdf")
    sim = ars.Simulation()
    sim.add_floor()
    sim.load_urdf(arm, fixed_base=True, base_position=(0.0, 0.5, 0.0))
    with pytest.raises(ars.InputError, match="nothing to record"):
        sim.record_video(tmp_path / "arm.mp4", 0.1, size=(64, 48))
    assert os.listdir(tmp_path) == [] and sim.time == 0.0
