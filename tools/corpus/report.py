"""How ARS does on the corpus `fetch.py` lists, against MuJoCo (MJCF) and PyBullet (URDF).

    python tools/corpus/fetch.py                       # once: the corpus, in the cache
    python tools/corpus/report.py                      # every file: results.json, summary.md
    python tools/corpus/report.py --package gymnasium --kind mjcf --jobs 1
    python tools/corpus/report.py --summary-only       # summary.md again from results.json

Run it with an interpreter that has `ars`, `mujoco` and `numpy` (the repository's `.venv`).
PyBullet is optional: `--pybullet-python PATH` names an interpreter that has it (its own
venv), else this interpreter is used if it has it, else the PyBullet column is left empty.

Every file is worked on by separate processes (`workers.py`), one per engine, each with a time
limit: a crash, a Rust panic or a hang is recorded with the stage it happened in and the run goes
on. For an MJCF file: MuJoCo compiles it (its masses per body, 2 s of its own simulation at the
file's time step); ARS loads it strictly and with `skip_unsupported=True` (its masses per body,
what it skipped), then `ars.Simulation.open` (what the viewer and `ars view` do: what ARS cannot
read skipped, the file's gravity applied) runs 2 s at ARS's time step. For a URDF: the masses
the file declares (its `<inertial><mass>`), PyBullet's masses, ARS's load (if it fails, again
with `ignore_visuals=True`) and masses, then 2 s over a floor with the robot's root at the
origin (what `ars view` does) and 2 s with `fixed_base=True` and no floor. `package://NAME/`
mesh paths are resolved to a folder named NAME in the file's package, given to ARS as
`packages=` (and `ROS_PACKAGE_PATH`) and to PyBullet as a search path. Each simulation is
checked for finite positions and velocities every 0.1 s and stopped after `--sim-wall` seconds of
wall-clock time (the time it reached is recorded).

Output, in `--out` (default: `report/` in the cache folder): `results.json` (every file's
findings) and `summary.md` (`summary.py` makes it). Only the standard library is needed here;
the workers need `ars`, `mujoco`, `numpy` (and `pybullet` for its column).
"""

from __future__ import annotations

import argparse
import concurrent.futures
import datetime
import json
import os
import platform
import re
import signal
import subprocess
import sys
import threading
import time
import xml.etree.ElementTree as ET
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import fetch
import summary
from workers import MARKER

_PACKAGE_URL = re.compile(r"package://([^/\"'\s<>]+)/([^\"'\s<>]+)")


def parse_output(stdout: bytes) -> dict:
    """The worker's `@@corpus` lines merged into one dict (`running`: the last stage begun)."""
    merged: dict = {}
    for line in stdout.decode("utf-8", "replace").splitlines():
        at = line.find(MARKER)
        if at >= 0:
            try:
                merged.update(json.loads(line[at + len(MARKER) :]))
            except json.JSONDecodeError:
                merged.setdefault("unreadable_lines", 0)
                merged["unreadable_lines"] += 1
    return merged


# The simulation stages of the workers, and how many wall seconds past `--sim-wall` one may
# run before its process is stopped: a simulation checks its budget between batches of steps,
# which a single step that outlasts the budget never lets it reach.
SIM_STAGES = ("mujoco_sim", "ars_sim", "ars_sim_fixed")
GRACE = 2.0


def run_task(python: str, task: str, path: Path, options: dict, timeout: float, cwd: Path) -> dict:
    """Runs one worker task; its findings, with `failure` set if it crashed or hung.

    A simulation still running `GRACE` seconds past its wall-clock budget (a step that took
    longer than the budget) is stopped and recorded as out of time (`stopped`), with the time
    it had reached: a slow simulation, as one that stopped itself at its budget, not a crash.
    A worker still running after `timeout` seconds in any other stage is a hang (a failure)."""
    command = [python, str(HERE / "workers.py"), task, str(path), json.dumps(options)]
    start = time.perf_counter()
    env = dict(os.environ, PYTHONFAULTHANDLER="1", RUST_BACKTRACE="1")
    process = subprocess.Popen(
        command, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env
    )
    stdout: list[bytes] = []
    stderr: list[bytes] = []
    stage: list = [None, start]  # the stage running, and since when

    def read_stdout() -> None:
        for line in process.stdout:  # type: ignore[union-attr]
            stdout.append(line)
            running = parse_output(line).get("running")
            if running:
                stage[:] = [running, time.perf_counter()]

    readers = [
        threading.Thread(target=read_stdout),
        threading.Thread(target=lambda: stderr.extend(process.stderr)),  # type: ignore[arg-type]
    ]
    for reader in readers:
        reader.start()
    stopped = None
    while stopped is None:
        try:
            code = process.wait(timeout=0.2)
            break
        except subprocess.TimeoutExpired:
            now = time.perf_counter()
            if now - start > timeout:
                stopped = "timeout"
            elif stage[0] in SIM_STAGES and now - stage[1] > options["sim_wall"] + GRACE:
                stopped = stage[0]
    if stopped is not None:
        process.kill()
        code = process.wait()
    for reader in readers:
        reader.join()
    found = parse_output(b"".join(stdout))
    found["wall"] = time.perf_counter() - start
    progress = found.pop("progress", None) or {}
    if stopped in SIM_STAGES:
        reached = progress.get("time", 0.0) if progress.get("stage") == stopped else 0.0
        found[stopped] = {
            "finite": True,
            "error": None,
            "out_of_time": True,
            "stopped": True,
            "time": reached,
            "wall": time.perf_counter() - stage[1],
        }
        found["done"] = True  # a simulation is the last stage of its worker
    elif stopped == "timeout" or code != 0 or not found.get("done"):
        tail = b"".join(stderr).decode("utf-8", "replace").strip().splitlines()[-12:]
        failure = {"task": task, "stage": found.get("running"), "stderr_tail": tail}
        if stopped == "timeout":
            failure["kind"] = "timeout"
        elif code < 0:
            failure["kind"] = "crash"
            failure["signal"] = (
                signal.Signals(-code).name if -code in signal.valid_signals() else -code
            )
        else:
            failure["kind"] = "exit" if code else "no end"
            failure["returncode"] = code
        found["failure"] = failure
    found.pop("done", None)
    return found


def package_dirs(path: Path, root: Path, index: dict[Path, dict[str, list[Path]]]) -> dict:
    """`package://NAME/` names in a URDF mapped to a folder named NAME under `root` (the
    file's package) that holds what the file asks for in it."""
    try:
        text = path.read_text("utf-8", "replace")
    except OSError:
        return {}
    wanted: dict[str, list[str]] = {}
    for name, rest in _PACKAGE_URL.findall(text):
        wanted.setdefault(name, []).append(rest)
    if not wanted:
        return {}
    if root not in index:
        folders: dict[str, list[Path]] = {}
        for folder in sorted(p for p in root.rglob("*") if p.is_dir()):
            folders.setdefault(folder.name, []).append(folder)
        index[root] = folders
    found = {}
    for name, rests in wanted.items():
        candidates = index[root].get(name, [])
        best = max(candidates, key=lambda c: sum((c / r).exists() for r in rests), default=None)
        if best is not None and any((best / r).exists() for r in rests):
            found[name] = str(best)
    return found


def declared_urdf(path: Path) -> dict:
    """The masses a URDF file declares, link by link (`<inertial><mass value>`)."""
    try:
        root = ET.parse(path).getroot()
    except (ET.ParseError, OSError) as error:
        return {"error": f"{type(error).__name__}: {error}"}
    masses = {}
    for index, link in enumerate(root.findall("link")):
        mass = link.find("inertial/mass")
        try:
            value = float(mass.get("value", "0")) if mass is not None else 0.0
        except ValueError:
            return {"error": f"link {link.get('name')}: mass {mass.get('value')!r}"}  # type: ignore[union-attr]
        masses[link.get("name") or f"link{index}"] = value
    text = path.read_text("utf-8", "replace")
    return {"total_mass": sum(masses.values()), "links": masses, "xacro": "xacro:" in text}


class Runner:
    """Works on the files, `jobs` at a time, and keeps the results in file order."""

    def __init__(self, args: argparse.Namespace, cache: Path, out: Path) -> None:
        self.args, self.cache, self.out = args, cache, out
        self.work = out / "work"  # the workers' folder (MuJoCo may write MUJOCO_LOG.TXT there)
        self.work.mkdir(parents=True, exist_ok=True)
        self.options = {"seconds": args.seconds, "sim_wall": args.sim_wall}
        self.index: dict[Path, dict[str, list[Path]]] = {}
        self.lock = threading.Lock()
        self.finished = 0

    def one(self, entry: dict, total: int) -> dict:
        path = self.cache / entry["path"]
        record = dict(entry)
        timeout = self.args.timeout
        if entry["kind"] == "mjcf":
            record["mujoco"] = run_task(
                sys.executable, "mujoco", path, self.options, timeout, self.work
            )
            record["ars"] = run_task(
                sys.executable, "ars-mjcf", path, self.options, timeout, self.work
            )
        else:
            with self.lock:
                packages = package_dirs(path, self.cache / entry["root"], self.index)
            options = dict(self.options, packages=packages)
            record["declared"] = dict(declared_urdf(path), packages=packages)
            if self.args.pybullet_python:
                record["pybullet"] = run_task(
                    self.args.pybullet_python, "pybullet", path, options, timeout, self.work
                )
            ars = run_task(sys.executable, "ars-urdf", path, options, timeout, self.work)
            if (ars.get("ars_sim") or {}).get("stopped"):  # the fixed base's run, on its own
                lenient = (ars.get("ars_mass") or {}).get("from") == "ignore_visuals"
                again = dict(options, after="ars_sim", ignore_visuals=lenient)
                more = run_task(sys.executable, "ars-urdf", path, again, timeout, self.work)
                ars["wall"] += more.pop("wall")
                ars.update(more)
            record["ars"] = ars
        with self.lock:
            self.finished += 1
            print(
                f"[{self.finished}/{total}] {summary.one_line(record)}", file=sys.stderr, flush=True
            )
        return record

    def run(self, entries: list[dict]) -> list[dict]:
        with concurrent.futures.ThreadPoolExecutor(max_workers=self.args.jobs) as pool:
            return list(pool.map(lambda e: self.one(e, len(entries)), entries))


def pybullet_python(given: str | None, disabled: bool) -> str | None:
    """The interpreter to run PyBullet with: `given`, else this one if it has PyBullet."""
    if disabled:
        return None
    candidate = given or sys.executable
    check = [candidate, "-c", "import pybullet"]
    ok = subprocess.run(check, check=False, capture_output=True, timeout=120).returncode == 0
    if not ok and given:
        raise SystemExit(f"{given} cannot import pybullet")
    return candidate if ok else None


def versions(pybullet: str | None) -> dict:
    """The versions of the engines compared, each read in its own interpreter."""
    probe = "import importlib.metadata as m, sys; print(m.version(sys.argv[1]))"
    found = {
        "python": platform.python_version(),
        "platform": platform.platform(),
        "cpus": os.cpu_count(),
        "commit": commit(),
    }
    for name, python in (
        ("ars", sys.executable),
        ("mujoco", sys.executable),
        ("pybullet", pybullet),
    ):
        if python is None:
            found[name] = None
            continue
        done = subprocess.run(
            [python, "-c", probe, name], check=False, capture_output=True, text=True
        )
        found[name] = done.stdout.strip() or None
    return found


def commit() -> str | None:
    """The repository's commit (`+` if its work tree has changes), as `git describe` says it:
    what the installed `ars` was built from when it was built from this work tree."""
    done = subprocess.run(
        ["git", "-C", str(HERE), "describe", "--always", "--dirty=+", "--abbrev=12"],
        check=False,
        capture_output=True,
        text=True,
    )
    return done.stdout.strip() or None


def select(manifest: dict, args: argparse.Namespace) -> list[dict]:
    entries = manifest["files"]
    if args.package:
        entries = [e for e in entries if e["package"] in args.package]
    if args.kind:
        entries = [e for e in entries if e["kind"] == args.kind]
    if args.match:
        entries = [e for e in entries if args.match in e["path"]]
    return entries[: args.limit] if args.limit else entries


def parse_args(argv: list[str] | None) -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument(
        "--cache", help="cache folder (default: $ARS_CORPUS_CACHE or ~/.cache/ars-corpus)"
    )
    parser.add_argument("--out", help="output folder (default: CACHE/report)")
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 1, help="files at once")
    parser.add_argument("--timeout", type=float, default=300.0, help="seconds per worker process")
    parser.add_argument("--seconds", type=float, default=2.0, help="simulated seconds per run")
    parser.add_argument("--sim-wall", type=float, default=30.0, help="wall seconds per simulation")
    parser.add_argument("--package", action="append", help="only this package (repeatable)")
    parser.add_argument("--kind", choices=("mjcf", "urdf"), help="only MJCF or only URDF files")
    parser.add_argument("--match", help="only files whose path holds this text")
    parser.add_argument("--limit", type=int, help="only the first N files")
    parser.add_argument("--pybullet-python", help="an interpreter that can import pybullet")
    parser.add_argument("--no-pybullet", action="store_true", help="leave PyBullet out")
    parser.add_argument("--summary-only", action="store_true", help="remake summary.md only")
    return parser.parse_args(argv)


def main(argv: list[str] | None = None) -> int:
    args = parse_args(argv)
    cache = fetch.cache_dir(args.cache)
    out = Path(args.out).resolve() if args.out else cache / "report"
    out.mkdir(parents=True, exist_ok=True)
    if args.summary_only:
        results = json.loads((out / "results.json").read_text())
        (out / "summary.md").write_text(summary.markdown(results))
        print(out / "summary.md")
        return 0
    manifest_path = cache / "manifest.json"
    if not manifest_path.exists():
        raise SystemExit(f"no {manifest_path}: run tools/corpus/fetch.py first")
    manifest = json.loads(manifest_path.read_text())
    entries = select(manifest, args)
    args.pybullet_python = pybullet_python(args.pybullet_python, args.no_pybullet)
    started = datetime.datetime.now(datetime.timezone.utc)
    start = time.perf_counter()
    files = Runner(args, cache, out).run(entries)
    meta = {
        "started": started.isoformat(timespec="seconds"),
        "wall_seconds": time.perf_counter() - start,
        "jobs": args.jobs,
        "options": {k: v for k, v in vars(args).items() if k != "summary_only"},
        "versions": versions(args.pybullet_python),
        "cache": str(cache),
        "packages": manifest["packages"],
    }
    results = {"meta": meta, "files": files}
    (out / "results.json").write_text(json.dumps(results, indent=1, default=str) + "\n")
    (out / "summary.md").write_text(summary.markdown(results))
    print(f"{len(files)} files in {meta['wall_seconds']:.0f} s: {out / 'summary.md'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
