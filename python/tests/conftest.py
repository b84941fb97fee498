"""Shared test helpers: where the repository is, the Rust examples' output, a file of
the corpus of robot files, and a virtual display for the window tests."""

import csv
import os
import pathlib
import shutil
import subprocess
import sys

import pytest

REPO = pathlib.Path(__file__).resolve().parents[2]


def corpus_file(relative):
    """A file of the corpus `tools/corpus/fetch.py` fetches (`test_corpus.py` fetches it
    first in a whole run), by its path under the cache's `unpacked/`; `None` where it
    is not there."""
    sys.path.insert(0, str(REPO / "tools" / "corpus"))
    import fetch  # tools/corpus, on the path just above

    path = fetch.cache_dir() / "unpacked" / relative
    return path if path.exists() else None


def run_rust_example(name, *args, tmp_path):
    """Runs `cargo run --example NAME -- ARGS --csv FILE` and returns the CSV rows
    (header first) as read back: Rust writes every float in its shortest round-trip
    form, so parsing gives back the exact bits."""
    out = tmp_path / f"{name}.csv"
    subprocess.run(
        ["cargo", "run", "--quiet", "--example", name, "--", *args, "--csv", str(out)],
        cwd=REPO,
        check=True,
        stdout=subprocess.DEVNULL,
    )
    with open(out, newline="") as f:
        return list(csv.reader(f))


@pytest.fixture
def rust_example(tmp_path):
    return lambda name, *args: run_rust_example(name, *args, tmp_path=tmp_path)


@pytest.fixture(scope="session")
def display():
    """A virtual display (Xvfb) for the window tests. Without Xvfb and xdotool they
    fail (``make deps`` installs both), unless ``ARS_SKIP_WINDOW_TEST=1`` says to skip
    them on purpose, as the Rust window tests do."""
    if shutil.which("Xvfb") is None or shutil.which("xdotool") is None:
        if os.environ.get("ARS_SKIP_WINDOW_TEST") == "1":
            pytest.skip("no Xvfb or xdotool, and ARS_SKIP_WINDOW_TEST=1")
        pytest.fail("the window tests need Xvfb and xdotool: make deps (or ARS_SKIP_WINDOW_TEST=1)")
    read, write = os.pipe()
    server = subprocess.Popen(
        ["Xvfb", "-displayfd", str(write), "-screen", "0", "1280x1024x24", "-nolisten", "tcp"],
        pass_fds=(write,),
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
    )
    os.close(write)
    with os.fdopen(read) as f:
        number = f.readline().strip()
    yield f":{number}"
    server.terminate()
    server.wait()


def window_env(display, tmp_path):
    env = dict(os.environ)
    env.pop("WAYLAND_DISPLAY", None)
    env.update(DISPLAY=display, XDG_RUNTIME_DIR=str(tmp_path))
    return env


def xdotool(display, *args):
    return subprocess.run(
        ["xdotool", *args],
        env={**os.environ, "DISPLAY": display},
        capture_output=True,
        text=True,
        timeout=30,
        check=False,
    )
