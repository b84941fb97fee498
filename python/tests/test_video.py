"""Video files from Python: ``sim.record_video`` and ``Program.record_video`` write
H.264 MP4 files that ffprobe (Debian's ffmpeg package, installed by ``make deps``)
reads back; bad settings are refused before anything is written."""

import json
import os
import shutil
import subprocess

import pytest

import ars
from ars.app import Program


def probe(path):
    """What ffprobe reads: codec, frames, duration (fails if ffprobe is missing)."""
    assert shutil.which("ffprobe"), "ffprobe is missing: install Debian's ffmpeg package"
    out = subprocess.run(
        [
            "ffprobe",
            "-v",
            "error",
            "-count_frames",
            "-show_entries",
            "stream=codec_name,nb_read_frames,width,height:format=duration",
            "-of",
            "json",
            str(path),
        ],
        check=True,
        capture_output=True,
        text=True,
    ).stdout
    data = json.loads(out)
    stream = data["streams"][0]
    return (
        stream["codec_name"],
        int(stream["nb_read_frames"]),
        float(data["format"]["duration"]),
        (stream["width"], stream["height"]),
    )


def falling_ball():
    sim = ars.Simulation()
    sim.add_sphere(0.2, (0.0, 2.0, 0.0), mass=1.0)
    return sim


def test_a_simulation_records_a_video_at_its_own_time(tmp_path):
    sim = falling_ball()
    path = tmp_path / "ball.mp4"
    video = sim.record_video(
        path, 1.0, fps=30, size=(160, 120), camera=(0.0, 1.0, 6.0), look_at=(0.0, 1.0, 0.0)
    )
    assert video["frames"] == 30
    assert video["duration"] == 1.0
    assert video["path"] == str(path)
    assert video["bytes"] == os.path.getsize(path)
    assert sim.time == pytest.approx(1.0)
    assert probe(path) == ("h264", 30, pytest.approx(1.0, abs=1e-3), (160, 120))
    assert os.listdir(tmp_path) == ["ball.mp4"]


@pytest.mark.parametrize(
    "kwargs, words",
    [
        ({"size": (161, 120)}, "even"),
        ({"fps": 0}, "frame rate"),
        ({"fps": -5}, "frame rate"),
        ({"fps": float("nan")}, "frame rate"),
    ],
)
def test_bad_settings_are_refused_before_anything_is_written(tmp_path, kwargs, words):
    sim = falling_ball()
    with pytest.raises(ars.InputError, match=words):
        sim.record_video(tmp_path / "bad.mp4", 1.0, **kwargs)
    assert os.listdir(tmp_path) == []
    assert sim.time == 0.0


def test_an_unwritable_path_and_an_empty_simulation_are_refused(tmp_path):
    with pytest.raises(ars.ArsError, match="does not exist"):
        falling_ball().record_video(tmp_path / "missing" / "a.mp4", 1.0, size=(64, 48))
    with pytest.raises(ars.InputError, match="no objects"):
        ars.Simulation().record_video(tmp_path / "empty.mp4", 1.0, size=(64, 48))
    assert os.listdir(tmp_path) == []


class Ball(Program):
    WINDOW_SIZE = (96, 72)

    def create_sim_objects(self):
        self.sim.add_sphere(0.3, (0.0, 2.0, 0.0), mass=1.0)


def test_a_program_starts_into_a_video(tmp_path, monkeypatch):
    monkeypatch.setenv("ARS_DURATION", "0.5")
    path = tmp_path / "program.mp4"
    Ball().start(video=str(path))
    assert probe(path) == ("h264", 15, pytest.approx(0.5, abs=1e-3), (96, 72))
    assert os.listdir(tmp_path) == ["program.mp4"]
