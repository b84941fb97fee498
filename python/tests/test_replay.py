"""Browser replays from Python (``sim.save_replay``, ``sim.replay``, ``ars.Replay``) and
what a notebook shows: replays inline, ``Renderer`` images as pictures; the example
notebook ``python/examples/replay.ipynb`` runs headless."""

import math
import os
import struct
import zlib

import numpy as np
import pytest

import ars

HERE = os.path.dirname(os.path.abspath(__file__))
NOTEBOOK = os.path.join(HERE, "..", "examples", "replay.ipynb")


def pendulum():
    sim = ars.Simulation()
    sim.add_floor()
    bob = sim.add_sphere(0.1, (0.5, 1.0, 0.0), mass=1.0, name="bob")
    sim.add_rotary_joint("pivot", bob, None, anchor=(0.0, 1.0, 0.0), axis=(0.0, 0.0, 1.0))
    sim.add_sensor("gps", bob)
    return sim


def test_save_replay_writes_one_page_and_runs_the_simulation(tmp_path):
    sim = pendulum()
    path = tmp_path / "pendulum.html"
    replay = sim.save_replay(
        path, 2.0, fps=25, plots=["Gps 1: y"], camera=(0, 1, 3), look_at=(0, 0.8, 0)
    )
    assert isinstance(replay, ars.Replay)
    assert math.isclose(sim.time, 2.0)
    # One sample at the start, then 25 a second.
    assert replay.frames == 51 and replay.start == 0.0 and math.isclose(replay.end, 2.0)
    page = path.read_text(encoding="utf-8")
    assert page == replay.html and replay.path == str(path)
    assert page.startswith("<!DOCTYPE html>") and 'id="ars-data"' in page
    assert "http://" not in page and "https://" not in page
    assert repr(replay) == f"<ars.Replay 51 frames, t = 0 to 2 s, {str(path)!r}>"
    assert os.listdir(tmp_path) == ["pendulum.html"]


def test_a_replay_in_memory_shows_inline_in_a_notebook(tmp_path):
    sim = pendulum()
    replay = sim.replay(1.0)
    # The simulation's frame rate: 50 frames a second.
    assert replay.frames == 51 and replay.path is None
    shown = replay._repr_html_()
    assert shown.startswith("<iframe srcdoc=") and "&lt;!DOCTYPE html&gt;" in shown
    assert 'sandbox="allow-scripts"' in shown
    replay.save(tmp_path / "later.html")
    assert (tmp_path / "later.html").read_text(encoding="utf-8") == replay.html


@pytest.mark.parametrize("fps", [0.0, -1.0, float("nan")])
def test_a_frame_rate_that_is_not_positive_is_refused_and_nothing_is_written(tmp_path, fps):
    sim = pendulum()
    with pytest.raises(ars.InputError, match="frame rate must be positive"):
        sim.save_replay(tmp_path / "x.html", 1.0, fps=fps)
    assert os.listdir(tmp_path) == [] and sim.time == 0.0


def test_bad_replays_are_said_and_leave_no_file(tmp_path):
    sim = pendulum()
    with pytest.raises(ars.FileError, match="missing"):
        sim.save_replay(tmp_path / "missing" / "x.html", 1.0)
    with pytest.raises(
        ars.InputError,
        match=r'no sensor column "Gps 1: w" to plot; the columns are: Gps 1: x \[m\]',
    ):
        sim.save_replay(tmp_path / "x.html", 1.0, plots=["Gps 1: w"])
    with pytest.raises(ars.InputError, match="nothing to replay: the simulation has no objects"):
        ars.Simulation().save_replay(tmp_path / "x.html", 1.0)
    with pytest.raises(ars.InputError, match="duration must be positive"):
        sim.save_replay(tmp_path / "x.html", -1.0)
    with pytest.raises(ars.InputError, match="image size"):
        sim.save_replay(tmp_path / "x.html", 1.0, size=(0, 10))
    assert os.listdir(tmp_path) == [] and sim.time == 0.0


def png_pixels(data):
    """The pixels of an 8-bit RGB PNG with unfiltered rows (what ``ars.Image`` writes)."""
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    at, chunks = 8, {}
    while at < len(data):
        (length,) = struct.unpack(">I", data[at : at + 4])
        kind, body = data[at + 4 : at + 8], data[at + 8 : at + 8 + length]
        assert struct.unpack(">I", data[at + 8 + length : at + 12 + length])[0] == zlib.crc32(
            kind + body
        )
        chunks[kind] = chunks.get(kind, b"") + body
        at += 12 + length
    width, height, depth, colour = struct.unpack(">IIBB", chunks[b"IHDR"][:10])
    assert (depth, colour) == (8, 2)
    rows = np.frombuffer(zlib.decompress(chunks[b"IDAT"]), np.uint8).reshape(height, 1 + 3 * width)
    assert not rows[:, 0].any()
    return rows[:, 1:].reshape(height, width, 3)


def test_renderer_images_are_arrays_that_a_notebook_shows_as_pictures():
    sim = pendulum()
    image = ars.Renderer(64, 48, camera=(0, 1, 3), look_at=(0, 0.8, 0)).render(sim)
    assert isinstance(image, ars.Image) and isinstance(image, np.ndarray)
    assert image.shape == (48, 64, 3) and image.dtype == np.uint8
    assert np.array_equal(png_pixels(image._repr_png_()), image)
    # What numpy computes from it is a plain array, shown as numbers.
    assert type(image.astype(np.int32) - 1) is np.ndarray
    assert type(image.mean()) is np.float64
    assert image[:, :, 0]._repr_png_() is not None
    assert image.astype(np.float32).view(ars.Image)._repr_png_() is None


def test_the_example_notebook_runs_headless():
    nbclient = pytest.importorskip("nbclient")
    nbformat = pytest.importorskip("nbformat")
    notebook = nbformat.read(NOTEBOOK, as_version=4)
    assert all(not cell.get("outputs") for cell in notebook.cells if cell.cell_type == "code")
    nbclient.NotebookClient(notebook, timeout=300, kernel_name="python3").execute()
    shown = [o for cell in notebook.cells if cell.cell_type == "code" for o in cell.outputs]
    kinds = {kind for output in shown for kind in output.get("data", {})}
    # The replay inline (HTML) and a rendered image (PNG).
    assert {"text/html", "image/png"} <= kinds, kinds
