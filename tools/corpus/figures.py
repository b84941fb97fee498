"""The figures issue 37 is judged by, and the docs page made of them (docs/corpus.md).

    python tools/corpus/figures.py                         # the figures of CACHE/report
    python tools/corpus/figures.py --results R.json --docs docs/corpus.md

`headline` gives, per kind (MJCF, URDF), the load rates, the files that load with their exact
mass and the simulations that stay bounded for 2 s; python/tests/test_corpus.py holds them
against its floors, and `docs_page` writes them per package with what ARS still refuses or
skips and its wall time per simulated second against MuJoCo's (`make corpus-table` runs the
test and copies the page it wrote to docs/). Only the standard library is needed.
"""

from __future__ import annotations

import argparse
import json
import statistics
import sys
from collections import defaultdict
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import fetch
import summary

# Issue 37's "Done when", in % of the files the reference reads (MJCF: the files MuJoCo
# compiles; URDF: the files whose declared masses can be read, all but one ill-formed file):
# loads with exact masses, and stays bounded for 2 s.
TARGETS = {"exact_mass": 95.0, "stable": 90.0}

# The figures, with what each counts (of which files) for the tables and the test's messages.
FIGURES = {
    "strict": "loads strictly",
    "lenient": "loads (MJCF: skip_unsupported; URDF: ignore_visuals if it must)",
    "exact_mass": "loads with its exact total mass",
    "stable": "bounded for 2 s (over a floor for URDF)",
    "stable_fixed": "bounded for 2 s with a fixed base (URDF)",
}

EXACT = 1e-6  # the relative difference of total masses still called equal


def read_by_reference(records: list[dict]) -> list[dict]:
    """The files a kind's figures are over: the MJCF files MuJoCo compiles, the URDF files
    whose declared masses can be read."""
    return [r for r in records if summary.reference_ok(r)]


def exact_mass(record: dict) -> bool:
    """ARS loaded the file (leniently if it must) with the reference's total mass."""
    difference = summary.relative(summary.ars_mass(record), summary.reference_mass(record))
    return summary.lenient_ok(record) and difference is not None and difference <= EXACT


def bounded(record: dict, stage: str) -> bool:
    return summary.sim_state(record["ars"].get(stage)) == "bounded"


def slow(records: list[dict], stage: str) -> int:
    """The files whose simulation ran out of its wall-time budget."""
    return sum(summary.sim_state(r["ars"].get(stage)) == "slow" for r in records)


def figures_of(records: list[dict], kind: str) -> dict[str, tuple[int, int]]:
    """Each figure of FIGURES as (files that have it, files it is over), over the files the
    reference reads. Stability is over all of these too: a file that does not load is not
    stable (the summary's tables count it over the simulations that started)."""
    read = read_by_reference(records)
    found = {
        "strict": sum(map(summary.strict_ok, read)),
        "lenient": sum(map(summary.lenient_ok, read)),
        "exact_mass": sum(map(exact_mass, read)),
        "stable": sum(bounded(r, "ars_sim") for r in read),
    }
    if kind == "urdf":
        found["stable_fixed"] = sum(bounded(r, "ars_sim_fixed") for r in read)
    return {name: (n, len(read)) for name, n in found.items()}


def headline(results: dict) -> dict[str, dict[str, tuple[int, int]]]:
    """`{kind: {figure: (n, of)}}` for the kinds the results hold."""
    by_kind: dict[str, list[dict]] = defaultdict(list)
    for record in results["files"]:
        by_kind[record["kind"]].append(record)
    return {kind: figures_of(records, kind) for kind, records in sorted(by_kind.items())}


def percent(figure: tuple[int, int]) -> float:
    n, of = figure
    return 100.0 * n / of if of else 0.0


def crashed(results: dict) -> list[str]:
    """One line per crash, panic or timeout of any worker: file, worker, stage, kind."""
    lines = []
    for record in results["files"]:
        for c in summary.crashes(record):
            kind = f"{c['kind']} {c.get('signal', c.get('returncode', ''))}".strip()
            lines.append(f"{summary.short(record)}: {c['task']} {kind} in {c.get('stage')}")
    return lines


# -- Wall time per simulated second -----------------------------------------------------------


def per_simulated_second(stage: dict | None, seconds: float) -> float | None:
    """Wall seconds per simulated second of a run that reached `seconds` finite, else None."""
    if not stage or not stage.get("finite") or stage.get("error") or stage.get("out_of_time"):
        return None
    reached, wall = stage.get("time") or 0.0, stage.get("wall")
    if reached < seconds - 1e-6 or not wall:
        return None
    return wall / reached


def timings(record: dict, seconds: float) -> tuple[float, float] | None:
    """ARS's and MuJoCo's wall seconds per simulated second on an MJCF file both ran for
    `seconds` at the same time step, else None."""
    ars = record["ars"].get("ars_sim")
    mujoco = record["mujoco"].get("mujoco_sim")
    step = (record["mujoco"].get("mujoco") or {}).get("timestep")
    if not ars or step is None or abs(ars.get("dt", 0.0) - step) > 1e-12 * step:
        return None
    ours, theirs = per_simulated_second(ars, seconds), per_simulated_second(mujoco, seconds)
    return None if ours is None or theirs is None else (ours, theirs)


def milliseconds(values: list[float]) -> str:
    """The median of `values` (seconds) in milliseconds, to 3 digits."""
    if not values:
        return "–"
    median = 1000.0 * statistics.median(values)
    return f"{median:.3g}" if median < 1000.0 else f"{median:,.0f}"


# -- The docs page ----------------------------------------------------------------------------


def rate(figure: tuple[int, int]) -> str:
    return summary.rate(*figure)


def grouped(records: list[dict]) -> dict[str, list[dict]]:
    """The records by package (in the corpus's order), then `**all**`."""
    groups: dict[str, list[dict]] = defaultdict(list)
    for r in records:
        groups[f"{r['package']} {r['version']}"].append(r)
    if len(groups) > 1:
        groups["**all**"] = list(records)
    return groups


def mjcf_rows(records: list[dict], seconds: float) -> list[list[object]]:
    rows = []
    for name, group in grouped(records).items():
        f = figures_of(group, "mjcf")
        pairs = [t for t in (timings(r, seconds) for r in read_by_reference(group)) if t]
        ratios = [ours / theirs for ours, theirs in pairs if theirs > 0]
        rows.append(
            [
                name,
                len(group),
                summary.rate(len(read_by_reference(group)), len(group)),
                rate(f["strict"]),
                rate(f["lenient"]),
                rate(f["exact_mass"]),
                rate(f["stable"]),
                slow(read_by_reference(group), "ars_sim"),
                len(pairs),
                milliseconds([p[0] for p in pairs]),
                milliseconds([p[1] for p in pairs]),
                f"{statistics.median(ratios):.3g}" if ratios else "–",
            ]
        )
    return rows


def urdf_rows(records: list[dict], seconds: float) -> list[list[object]]:
    rows = []
    for name, group in grouped(records).items():
        f = figures_of(group, "urdf")
        walls = [per_simulated_second(r["ars"].get("ars_sim"), seconds) for r in group]
        walls = [w for w in walls if w is not None]
        rows.append(
            [
                name,
                len(group),
                rate(f["strict"]),
                rate(f["lenient"]),
                rate(f["exact_mass"]),
                rate(f["stable"]),
                slow(group, "ars_sim"),
                rate(f["stable_fixed"]),
                slow(group, "ars_sim_fixed"),
                len(walls),
                milliseconds(walls),
            ]
        )
    return rows


def headline_rows(figures: dict[str, dict[str, tuple[int, int]]]) -> list[list[object]]:
    rows = []
    for name, what in FIGURES.items():
        target = TARGETS.get(name.removesuffix("_fixed"))
        cells = [rate(figures[k][name]) if name in figures.get(k, {}) else "–" for k in figures]
        rows.append([what, *cells, f"{target:g} %" if target else ""])
    return rows


def definitions(seconds: float) -> list[str]:
    """What the page's words count."""
    return [
        "What the figures count (`tools/corpus/summary.py` defines the words):",
        "",
        "- every figure is over the files the reference reads: the MJCF files MuJoCo compiles,",
        "  the URDF files whose declared masses Python's XML parser reads (all but one);",
        "- *strict*: ARS's load returned with its defaults; *skip_unsupported* (MJCF) or",
        "  *ignore_visuals* (URDF): it returned with what ARS cannot read skipped, or with the",
        "  visuals left out (a broken visual mesh);",
        "- *exact mass*: the file loads (at least leniently) and ARS's total mass is MuJoCo's",
        "  compiled `body_mass` summed (MJCF) or the masses the file declares (URDF), to a",
        f"  relative {EXACT:g};",
        "- *2 s stable*: `ars.Simulation.open` (MJCF; what `ars view` does) or the robot over",
        f"  a floor (URDF) ran {seconds:g} s finite within the wall-time budget, no body faster",
        f"  than {summary.SPEED_LIMIT:g} m/s; a file that does not load is not stable; *slow*: of",
        "  these, the simulations that had not reached the end when their budget ran out;",
        "- *ms per simulated s*: wall-clock milliseconds per simulated second, the median over",
        "  the files both engines ran for the whole run at the file's own time step (MuJoCo:",
        "  `mj_step` with its compiled model; each engine's state checked every 0.1 s of",
        "  simulated time); *ARS / MuJoCo* is the median of the per-file ratios.",
        "",
    ]


def docs_page(results: dict) -> str:
    meta = results.get("meta", {})
    options = meta.get("options", {})
    seconds = float(options.get("seconds") or 2.0)
    v = meta.get("versions", {})
    files = results["files"]
    mjcf = [r for r in files if r["kind"] == "mjcf"]
    urdf = [r for r in files if r["kind"] == "urdf"]
    figures = headline(results)
    out = [
        "# ARS on robot files from the wild",
        "",
        "<!-- Written by tools/corpus/figures.py: edit that, not this page. -->",
        "",
        "Regenerate this page with `make corpus-table`: it runs `python/tests/test_corpus.py`,",
        "the test `make test` (and so CI) runs, which fetches the corpus once (about 650 MB, into",
        "`~/.cache/ars-corpus`), reports on every file and holds the figures below to its floors,",
        "then copies the page the test wrote. From a report already made:",
        "`.venv/bin/python tools/corpus/figures.py --results RESULTS.json --docs docs/corpus.md`.",
        "",
        (
            f"The corpus is {len(files)} files ({len(mjcf)} MJCF, {len(urdf)} URDF) of"
            f" {len(meta.get('packages', []))} PyPI packages pinned in `tools/corpus/fetch.py`"
            " (issue 37; `tools/corpus/README.md`). This run: "
            f"{str(meta.get('started', '?'))[:10]}, repository at {v.get('commit', '?')},"
            f" ars {v.get('ars')}, mujoco {v.get('mujoco')}, Python {v.get('python')};"
            f" {seconds:g} simulated s per run, at most {options.get('sim_wall'):g} s of wall"
            f" time each, {meta.get('jobs')} files at a time on {v.get('cpus', '?')} CPUs."
        ),
        "",
        *definitions(seconds),
        "## Issue 37's targets",
        "",
    ]
    out += summary.table(
        ["files that", *(k.upper() for k in figures), "target"], headline_rows(figures)
    )
    if mjcf:
        out += ["## MJCF, against MuJoCo", ""]
        head = ["package", "files", "MuJoCo compiles", "ARS strict", "skip_unsupported"]
        head += ["exact mass", "2 s stable", "slow", "both ran", "ARS ms per sim s"]
        head += ["MuJoCo ms per sim s"]
        out += summary.table([*head, "ARS / MuJoCo"], mjcf_rows(mjcf, seconds))
        read = read_by_reference(mjcf)
        out += ["### Why ARS still refuses a file with skip_unsupported", ""]
        out += summary.table(
            ["files", "cause", "example"],
            summary.cause_rows(read, summary.stage_error("ars_skip"), 15),
        )
        out += ["### What skip_unsupported still skips", ""]
        out += ["Each item is named in the `skipped` list `load_mjcf` returns, with a warning.", ""]
        out += summary.table(["files", "items", "what", "example"], summary.skipped_rows(read))
    if urdf:
        out += ["## URDF, against the masses the file declares", ""]
        head = ["package", "files", "ARS loads", "ignore_visuals", "exact mass"]
        head += ["2 s stable over a floor", "slow", "with a fixed base", "slow", "ran"]
        head += ["ARS ms per sim s"]
        out += summary.table(head, urdf_rows(urdf, seconds))
        out += ["### Why ARS still refuses a URDF file with ignore_visuals", ""]
        out += summary.table(
            ["files", "cause", "example"],
            summary.cause_rows(urdf, summary.stage_error("ars_skip"), 15),
        )
    return "\n".join(out) + "\n"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--results", help="a report's results.json (default: CACHE/report's)")
    parser.add_argument("--docs", help="write the docs page here (e.g. docs/corpus.md)")
    args = parser.parse_args(argv)
    path = Path(args.results) if args.results else fetch.cache_dir() / "report" / "results.json"
    results = json.loads(path.read_text())
    for kind, found in headline(results).items():
        for name, figure in found.items():
            print(f"{kind} {name}: {rate(figure)}")
    print(f"crashes: {len(crashed(results))}")
    if args.docs:
        Path(args.docs).write_text(docs_page(results))
        print(f"written: {args.docs}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
