"""ARS against MuJoCo, per simulated second, on the same MJCF files in one run, side by side.

    .venv/bin/python tools/corpus/speed.py --gymnasium        # Gymnasium's MuJoCo models
    .venv/bin/python tools/corpus/speed.py                    # every corpus MJCF file
    .venv/bin/python tools/corpus/speed.py --match hand --seconds 1
    .venv/bin/python tools/corpus/speed.py --match sawyer_xyz --match fetch/ --limit 5

For each file, in this one process and one after the other (nothing else of this run in
parallel): MuJoCo steps its compiled model (`mj_step`, `nstep` at a time, a native loop),
then ARS opens the file as `ars view` does (`Simulation.open`: the file's own time step,
gravity and floor) and runs it (`sim.run`, a native loop), once with ODE's exact
`dWorldStep` (ARS's default) and once with `stepper="quick"` (`dWorldQuickStep`, 20
iterations). Each engine runs the same simulated time from the file's initial state, with no
control; loading is not timed. Each is run `--repeat` times (3), and again until its
timed runs add up to `--min-wall` seconds (0.05; at most 100 runs), and the fastest run
counts, which keeps a busy machine's noise out of the figures: a small model's whole run
takes a fraction of a millisecond, where three runs leave its ratio ±30 % from one bench
to the next. A run that leaves finite numbers is timed; one that fails
(ARS's divergence check) is reported as failed and left out of the medians.

Prints one line per file and, at the end, the medians: each engine's milliseconds per
simulated second, and the median of the per-file ratios ARS / MuJoCo (exact and quick). With
`--json OUT` it also writes every measurement. The files come from the corpus manifest
(`tools/corpus/fetch.py` fetches it once into `~/.cache/ars-corpus`).
"""

from __future__ import annotations

import argparse
import json
import math
import statistics
import sys
import time
import warnings
from pathlib import Path

import fetch

GYMNASIUM_ASSETS = "gymnasium/envs/mujoco/assets/"


MAX_RUNS = 100


def runs(repeat: int, min_wall: float, walls: list[float]):
    """Yields while another timed run is due: fewer than `repeat` done, or (up to
    MAX_RUNS) fewer than `min_wall` seconds timed in all."""
    while len(walls) < repeat or (sum(walls) < min_wall and len(walls) < MAX_RUNS):
        yield


def time_mujoco(path: Path, seconds: float, repeat: int, min_wall: float) -> dict:
    import mujoco

    model = mujoco.MjModel.from_xml_path(str(path))
    data = mujoco.MjData(model)
    steps = max(1, round(seconds / model.opt.timestep))
    walls: list[float] = []
    for _ in runs(repeat, min_wall, walls):
        mujoco.mj_resetData(model, data)
        start = time.perf_counter()
        mujoco.mj_step(model, data, nstep=steps)
        walls.append(time.perf_counter() - start)
    finite = bool(all(math.isfinite(v) for v in data.qpos))
    return {
        "dt": model.opt.timestep,
        "steps": steps,
        "wall": min(walls),
        "runs": len(walls),
        "ok": finite,
    }


def time_ars(path: Path, seconds: float, stepper: str, repeat: int, min_wall: float) -> dict:
    import ars

    walls: list[float] = []
    for _ in runs(repeat, min_wall, walls):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            sim = ars.Simulation.open(str(path))
        sim.set_stepper(stepper)
        dt = sim.time_step
        steps = max(1, round(seconds / dt))
        start = time.perf_counter()
        try:
            sim.run(steps * dt)
        except ars.ArsError as error:
            return {"dt": dt, "ok": False, "error": str(error).splitlines()[0][:200]}
        walls.append(time.perf_counter() - start)
    return {"dt": dt, "steps": steps, "wall": min(walls), "runs": len(walls), "ok": True}


def per_second(run: dict) -> float | None:
    """Wall-clock milliseconds per simulated second of a run that succeeded."""
    if not run.get("ok") or "wall" not in run:
        return None
    return run["wall"] / (run["steps"] * run["dt"]) * 1000.0


def measure(path: Path, seconds: float, repeat: int, min_wall: float) -> dict:
    row: dict = {}
    for label, timer in (
        ("mujoco", lambda: time_mujoco(path, seconds, repeat, min_wall)),
        ("exact", lambda: time_ars(path, seconds, "exact", repeat, min_wall)),
        ("quick", lambda: time_ars(path, seconds, "quick", repeat, min_wall)),
    ):
        try:
            row[label] = timer()
        except Exception as error:  # noqa: BLE001 - a file one engine refuses: said, not fatal
            row[label] = {
                "ok": False,
                "error": f"{type(error).__name__}: {error}".splitlines()[0][:200],
            }
    return row


def fmt(value: float | None) -> str:
    return "–" if value is None else f"{value:,.1f}"


def ratio(a: float | None, b: float | None) -> float | None:
    return None if a is None or b is None or b <= 0 else a / b


def summarise(rows: dict[str, dict]) -> list[str]:
    lines = []
    times = {k: [per_second(r[k]) for r in rows.values()] for k in ("mujoco", "exact", "quick")}
    for key in ("mujoco", "exact", "quick"):
        got = [t for t in times[key] if t is not None]
        med = statistics.median(got) if got else None
        lines.append(f"median {key:6} ms per simulated s: {fmt(med)} over {len(got)} files")
    for key in ("exact", "quick"):
        both = [ratio(per_second(r[key]), per_second(r["mujoco"])) for r in rows.values()]
        got = [x for x in both if x is not None]
        med = statistics.median(got) if got else None
        at_most_one = sum(1 for x in got if x <= 1.0)
        lines.append(
            f"median ARS {key} / MuJoCo: {'–' if med is None else f'{med:.2f}'} over {len(got)} files"
            f" ({at_most_one} at or below 1.0)"
        )
    return lines


def select(args: argparse.Namespace) -> list[tuple[str, Path]]:
    cache = fetch.cache_dir(args.cache)
    manifest = json.loads((cache / "manifest.json").read_text("utf-8"))
    entries = [e for e in manifest["files"] if e["kind"] == "mjcf"]
    if args.gymnasium:
        entries = [e for e in entries if GYMNASIUM_ASSETS in e["path"]]
    if args.match:
        # Each text's files in the manifest's order (its first --limit), one text after
        # the other, each file once.
        chosen: list[dict] = []
        for text in args.match:
            found = [e for e in entries if text in e["path"] and e not in chosen]
            chosen += found[: args.limit] if args.limit else found
        entries = chosen
    elif args.limit:
        entries = entries[: args.limit]
    return [(e["path"], cache / e["path"]) for e in entries]


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument(
        "--cache", help="corpus cache (default: $ARS_CORPUS_CACHE or ~/.cache/ars-corpus)"
    )
    parser.add_argument("--gymnasium", action="store_true", help="only Gymnasium's MuJoCo models")
    parser.add_argument(
        "--match",
        action="append",
        help="only files whose path holds this text (repeat it for several: a subset of packages)",
    )
    parser.add_argument("--limit", type=int, help="only the first N files (of each --match)")
    parser.add_argument("--seconds", type=float, default=2.0, help="simulated seconds per run")
    parser.add_argument("--repeat", type=int, default=3, help="runs per engine; the fastest counts")
    parser.add_argument(
        "--min-wall",
        type=float,
        default=0.05,
        help=f"more runs until they add up to this many seconds (at most {MAX_RUNS} runs)",
    )
    parser.add_argument("--json", help="write every measurement to this file")
    args = parser.parse_args(argv)
    files = select(args)
    if not files:
        print("no file selected (is the corpus fetched? tools/corpus/fetch.py)", file=sys.stderr)
        return 1
    rows: dict[str, dict] = {}
    print(
        f"{'MuJoCo':>9} {'exact':>9} {'quick':>9} {'ex/MJ':>6} {'qu/MJ':>6}  ms per simulated s; file"
    )
    for name, path in files:
        row = measure(path, args.seconds, args.repeat, args.min_wall)
        rows[name] = row
        mj, ex, qu = (per_second(row[k]) for k in ("mujoco", "exact", "quick"))
        r_ex, r_qu = ratio(ex, mj), ratio(qu, mj)
        cells = [
            fmt(mj),
            fmt(ex),
            fmt(qu),
            "–" if r_ex is None else f"{r_ex:.2f}",
            "–" if r_qu is None else f"{r_qu:.2f}",
        ]
        failed = "; ".join(f"{k}: {row[k]['error']}" for k in row if row[k].get("error"))
        print(
            f"{cells[0]:>9} {cells[1]:>9} {cells[2]:>9} {cells[3]:>6} {cells[4]:>6}  {name}"
            + (f"  [{failed}]" if failed else ""),
            flush=True,
        )
    print()
    for line in summarise(rows):
        print(line)
    if args.json:
        Path(args.json).write_text(json.dumps(rows, indent=1), "utf-8")
    return 0


if __name__ == "__main__":
    sys.exit(main())
