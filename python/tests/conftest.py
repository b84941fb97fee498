"""Shared test helpers: where the repository is, and the Rust examples' output."""

import csv
import pathlib
import subprocess

import pytest

REPO = pathlib.Path(__file__).resolve().parents[2]


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
