"""The Markdown summary of a corpus run (`report.py` writes `results.json`, then this).

Only the standard library is needed; `DEFINITIONS` says what the tables count.
"""

from __future__ import annotations

import math
import re
from collections import Counter, defaultdict

from workers import normalise

SPEED_LIMIT = 100.0

DEFINITIONS = """\
What the tables count:
- a file *loads* when ARS's load returned; the rates are over the files the reference reads
  (MJCF: the files MuJoCo compiles; URDF: every file);
- masses are *equal* when the relative difference of the totals is at most 1e-6, *within 1 %*
  when it is at most 0.01 (MJCF: against MuJoCo's `body_mass` summed; URDF: against the masses
  the file declares in `<inertial><mass>`, summed, and against PyBullet's);
- a simulation is *finite* when no position or velocity became NaN or infinite and ARS raised
  no error while it ran; *bounded* when it reached 2 s finite and no body ever went faster than
  100 m/s (a free fall of 2 s reaches 20 m/s); *slow* when it had not reached 2 s after the
  wall-clock budget (finite up to there; a single step that outlasts the budget is stopped a
  few seconds past it); the rates are over the files whose simulation started;
- a *crash* is a worker killed by a signal, one that exited without finishing, a Rust panic
  (PyO3's `PanicException`), or one that outran its time limit (a timeout).
"""


def short(record: dict) -> str:
    """The file's path, from its package's root."""
    path = record["path"]
    root = record.get("root", "")
    inner = path[len(root) + 1 :] if root and path.startswith(root + "/") else path
    return f"{record['package']}: {inner}"


def ok(stage: dict | None) -> bool:
    return bool(stage and stage.get("ok"))


def relative(value: float | None, reference: float | None) -> float | None:
    if value is None or reference is None:
        return None
    if reference == 0.0:
        return 0.0 if value == 0.0 else math.inf
    return abs(value - reference) / abs(reference)


def reference_ok(record: dict) -> bool:
    if record["kind"] == "mjcf":
        return ok(record["mujoco"].get("mujoco"))
    return "total_mass" in record.get("declared", {})


def reference_mass(record: dict) -> float | None:
    if record["kind"] == "mjcf":
        return (record["mujoco"].get("mujoco") or {}).get("total_mass")
    return record.get("declared", {}).get("total_mass")


def pybullet_mass(record: dict) -> float | None:
    return ((record.get("pybullet") or {}).get("pybullet") or {}).get("total_mass")


def ars_mass(record: dict) -> float | None:
    return (record["ars"].get("ars_mass") or {}).get("total")


def strict_ok(record: dict) -> bool:
    return ok(record["ars"].get("ars_strict"))


def lenient_ok(record: dict) -> bool:
    return strict_ok(record) or ok(record["ars"].get("ars_skip"))


def crashes(record: dict) -> list[dict]:
    """Every crash, timeout or panic of the file's workers."""
    found = []
    for task in ("mujoco", "ars", "pybullet"):
        result = record.get(task) or {}
        if "failure" in result:
            found.append(result["failure"])
        for stage, value in result.items():
            if isinstance(value, dict) and value.get("error_class") == "PanicException":
                found.append(
                    {"task": task, "stage": stage, "kind": "panic", "error": value["error"]}
                )
    return found


def sim_state(stage: dict | None) -> str | None:
    """`finite`, `bounded` (finite and slow), `slow` (out of wall time first), or a failure."""
    if not stage:
        return None
    if not stage.get("finite"):
        return stage.get("error") or f"non-finite state at t = {stage.get('time', 0):.2f} s"
    if stage.get("out_of_time"):
        return "slow"
    speed = stage.get("max_speed")
    return "bounded" if speed is not None and speed <= SPEED_LIMIT else "finite"


def one_line(record: dict) -> str:
    """A progress line for a file just done."""
    ars = record["ars"]
    mark = {True: "ok", False: "FAIL"}
    parts = [f"{record['kind']} {short(record)}:"]
    if record["kind"] == "mjcf":
        parts.append(f"mujoco {mark[reference_ok(record)]}")
    elif record.get("pybullet") is not None:
        parts.append(f"pybullet {mark[ok(record['pybullet'].get('pybullet'))]}")
    parts.append(f"strict {mark[strict_ok(record)]}, lenient {mark[lenient_ok(record)]}")
    diff = relative(ars_mass(record), reference_mass(record))
    if diff is not None:
        parts.append(f"mass {'=' if diff <= 1e-6 else f'{diff:+.1e}'}")
    state = sim_state(ars.get("ars_sim"))
    if state:
        parts.append(f"sim {state[:40]}")
    parts.extend(f"{c['kind'].upper()} in {c['stage']}" for c in crashes(record))
    return " ".join(parts)


def rate(n: int, of: int) -> str:
    return f"{n}/{of} ({100.0 * n / of:.0f} %)" if of else "–"


def table(header: list[str], rows: list[list[object]]) -> list[str]:
    if not rows:
        return ["None.", ""]
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(str(c) for c in row) + " |" for row in rows]
    return lines + [""]


def mass_columns(records: list[dict], reference) -> list[str]:
    diffs = [relative(ars_mass(r), reference(r)) for r in records]
    diffs = [d for d in diffs if d is not None]
    return [
        rate(sum(d <= 1e-6 for d in diffs), len(diffs)),
        rate(sum(d <= 0.01 for d in diffs), len(diffs)),
    ]


def sim_columns(records: list[dict], stage: str) -> list[str]:
    states = [sim_state(r["ars"].get(stage)) for r in records]
    states = [s for s in states if s is not None]
    finite = sum(s in ("finite", "bounded", "slow") for s in states)
    bounded = sum(s == "bounded" for s in states)
    slow = sum(s == "slow" for s in states)
    return [rate(finite, len(states)), rate(bounded, len(states)), slow]


def package_rows(records: list[dict], kind: str) -> list[list[object]]:
    groups: dict[str, list[dict]] = defaultdict(list)
    for r in records:
        if r["kind"] == kind:
            groups[f"{r['package']} {r['version']}"].append(r)
    if len(groups) > 1:
        groups["**all**"] = [r for r in records if r["kind"] == kind]
    rows = []
    for name, group in groups.items():
        read = [r for r in group if reference_ok(r)] if kind == "mjcf" else group
        row: list[object] = [name, len(group)]
        if kind == "mjcf":
            row.append(rate(len(read), len(group)))
        else:
            has_pb = [r for r in group if r.get("pybullet") is not None]
            row.append(rate(sum(ok(r["pybullet"].get("pybullet")) for r in has_pb), len(has_pb)))
        row += [
            rate(sum(map(strict_ok, read)), len(read)),
            rate(sum(map(lenient_ok, read)), len(read)),
        ]
        row += mass_columns(read, reference_mass)
        if kind == "urdf":
            row += mass_columns(read, pybullet_mass)
        row += sim_columns(group, "ars_sim")
        if kind == "urdf":
            row += sim_columns(group, "ars_sim_fixed")
        row.append(sum(bool(crashes(r)) for r in group))
        rows.append(row)
    return rows


def cause_rows(records: list[dict], error_of, limit: int = 25) -> list[list[object]]:
    """Failure causes ranked by count, each with one example file and its message."""
    counts: Counter = Counter()
    example: dict[str, tuple[str, str]] = {}
    for r in records:
        message = error_of(r)
        if message:
            cause = normalise(message)
            counts[cause] += 1
            example.setdefault(cause, (short(r), message))
    rows = []
    for cause, n in counts.most_common(limit):
        file, message = example[cause]
        message = re.sub(r"/\S*/unpacked/[^/]+/", "", message)
        rows.append([n, f"`{cause}`", f"{file}<br>{escape(message)}"])
    rest = sum(counts.values()) - sum(r[0] for r in rows)
    if rest:
        rows.append([rest, f"({len(counts) - limit} other causes)", ""])
    return rows


def escape(text: str, width: int = 300) -> str:
    text = text if len(text) <= width else text[: width - 1] + "…"
    return text.replace("|", "\\|").replace("<", "&lt;").replace(">", "&gt;")


def stage_error(stage: str):
    """The error of an ARS stage, or a crash in it: for `cause_rows`."""

    def error_of(record: dict) -> str | None:
        ars = record["ars"]
        value = ars.get(stage)
        if value is None:
            failure = ars.get("failure")
            if failure and failure.get("stage") == stage:
                return f"{failure['kind']} {failure.get('signal', '')} in {stage}".strip()
            return None
        return None if value.get("ok") else value.get("error")

    return error_of


def skipped_rows(records: list[dict], limit: int = 20) -> list[list[object]]:
    files: Counter = Counter()
    items: Counter = Counter()
    example: dict[str, str] = {}
    for r in records:
        seen = set()
        for item in r["ars"].get("ars_skipped") or []:
            cause = skipped_cause(item)
            items[cause] += 1
            seen.add(cause)
            example.setdefault(cause, short(r))
        files.update(seen)
    return [[files[c], items[c], f"`{c}`", example[c]] for c, _ in files.most_common(limit)]


def skipped_cause(item: str) -> str:
    """A skipped item's kind: its element and what was skipped, attribute lists collapsed."""
    cause = normalise(item)
    head, _, tail = cause.partition(": ")
    if " not used" in tail:
        tail = "… not used" + tail.split(" not used", 1)[1]
    return f"{head}: {tail}" if tail else head


def mass_rows(records: list[dict], reference=reference_mass, limit: int = 30) -> list[list[object]]:
    """The files whose ARS total mass is not the reference's, the worst first."""
    rows = []
    for r in records:
        diff = relative(ars_mass(r), reference(r))
        if diff is None or diff <= 1e-6:
            continue
        masses = r["ars"].get("ars_mass") or {}
        row = [diff, short(r), f"{reference(r):.6g}", f"{ars_mass(r):.6g}"]
        rows.append(row + [body_detail(r, masses)] if reference is reference_mass else row)
    rows.sort(key=lambda row: -row[0])
    return [[f"{row[0]:.2e}", *row[1:]] for row in rows[:limit]]


def body_detail(record: dict, masses: dict) -> str:
    """Which bodies differ (MJCF: from MuJoCo's, by name) and which ARS has no body for."""
    parts = []
    if record["kind"] == "mjcf":
        reference = (record["mujoco"].get("mujoco") or {}).get("body_masses") or {}
        ours = masses.get("bodies") or {}
        differ = [
            n for n in ours if n in reference and (relative(ours[n], reference[n]) or 0) > 1e-6
        ]
        absent = [n for n in reference if n not in ours and reference[n] > 0]
        if differ:
            parts.append(f"{len(differ)} bodies differ (e.g. {differ[0]})")
        if absent:
            parts.append(f"{len(absent)} massive bodies not among ARS's (e.g. {absent[0]})")
    for key in ("static", "missing"):
        if masses.get(key):
            parts.append(f"{len(masses[key])} {key}")
    return escape("; ".join(parts))


def stability_rows(records: list[dict], stage: str, limit: int = 40) -> list[list[object]]:
    rows = []
    for r in records:
        value = r["ars"].get(stage)
        state = sim_state(value)
        if state in (None, "bounded", "slow"):
            continue
        speed = value.get("max_speed")
        if r["kind"] == "mjcf":
            mujoco = (r.get("mujoco") or {}).get("mujoco_sim")
            reference = (
                "–" if mujoco is None else ("finite" if mujoco.get("finite") else "NOT finite")
            )
        else:
            other = "ars_sim_fixed" if stage == "ars_sim" else "ars_sim"
            reference = sim_state(r["ars"].get(other)) or "–"
        what = f"faster than {SPEED_LIMIT:g} m/s" if state == "finite" else escape(state)
        rows.append(
            [
                short(r),
                what,
                f"{value.get('time', 0):.2f}",
                f"{speed:.3g}" if speed else "",
                reference,
            ]
        )
    return rows[:limit]


def crash_rows(records: list[dict]) -> list[list[object]]:
    rows = []
    for r in records:
        for c in crashes(r):
            detail = c.get("error") or " / ".join((c.get("stderr_tail") or [])[-3:])
            kind = f"{c['kind']} {c.get('signal', c.get('returncode', ''))}".strip()
            rows.append([short(r), c["task"], c.get("stage"), kind, escape(detail or "", 400)])
    return rows


def slow_rows(records: list[dict], limit: int = 15) -> list[list[object]]:
    rows = []
    for r in records:
        for stage in ("ars_sim", "ars_sim_fixed"):
            value = r["ars"].get(stage) or {}
            # A simulation stopped in its first step reached t = 0: the slowest of all.
            if not value.get("wall") or value.get("time") is None or value.get("error"):
                continue
            factor = value["time"] / value["wall"]
            bodies = value.get("bodies", "–")
            rows.append([factor, short(r), stage, bodies, value["time"], value["wall"]])
    rows.sort(key=lambda row: row[0])
    return [
        [f"{f:.3f}", *rest[:3], f"{rest[3]:.2f}", f"{rest[4]:.1f}"] for f, *rest in rows[:limit]
    ]


def header(meta: dict, files: list[dict]) -> list[str]:
    v = meta.get("versions", {})
    kinds = Counter(f["kind"] for f in files)
    o = meta.get("options", {})
    lines = [
        "# ARS on robot files from the wild",
        "",
        (
            f"Run of {meta.get('started')}: {len(files)} files ({kinds['mjcf']} MJCF, {kinds['urdf']} URDF)"
            f" in {meta.get('wall_seconds', 0) / 60:.1f} min with {meta.get('jobs')} jobs;"
            f" ars {v.get('ars')}, mujoco {v.get('mujoco')}, pybullet {v.get('pybullet')},"
            f" Python {v.get('python')}. Simulations: {o.get('seconds')} s each, at most"
            f" {o.get('sim_wall')} s of wall-clock time; {o.get('timeout')} s per worker process."
        ),
        "",
        "| package | version | archive | MJCF | URDF | what |",
        "|---|---|---|---|---|---|",
    ]
    present = {f["package"] for f in files}
    for p in meta.get("packages", []):
        if p["name"] not in present:
            continue
        counts = p.get("counts", {})
        row = [
            p["name"],
            p["version"],
            f"`{p['file']}`",
            counts.get("mjcf", 0),
            counts.get("urdf", 0),
        ]
        lines.append("| " + " | ".join(str(c) for c in [*row, p.get("note", "")]) + " |")
    return lines + [""]


def markdown(results: dict) -> str:
    files = results["files"]
    mjcf = [f for f in files if f["kind"] == "mjcf"]
    urdf = [f for f in files if f["kind"] == "urdf"]
    mjcf_read = [f for f in mjcf if reference_ok(f)]
    out = header(results.get("meta", {}), files)
    out += [DEFINITIONS]
    if mjcf:
        out += ["## MJCF: ARS against MuJoCo", ""]
        head = ["package", "files", "MuJoCo compiles", "ARS strict", "ARS skip_unsupported"]
        head += ["mass = MuJoCo", "mass ±1 %", "2 s finite", "2 s bounded", "slow", "crashes"]
        out += table(head, package_rows(mjcf, "mjcf"))
        extra = [f for f in mjcf if not reference_ok(f) and lenient_ok(f)]
        out += [f"ARS loads {len(extra)} of the files MuJoCo refuses:", ""]
        out += [f"- {short(r)} (MuJoCo: {escape(r['mujoco']['mujoco']['error'])})" for r in extra]
        out += [""]
        out += ["### Why ARS refuses an MJCF file MuJoCo compiles (strict)", ""]
        out += table(
            ["files", "cause", "example"], cause_rows(mjcf_read, stage_error("ars_strict"))
        )
        out += ["### ... and with skip_unsupported", ""]
        out += table(["files", "cause", "example"], cause_rows(mjcf_read, stage_error("ars_skip")))
        out += ["### What skip_unsupported skipped", ""]
        out += table(["files", "items", "what", "example"], skipped_rows(mjcf_read))
        out += ["### Why MuJoCo refuses a file (not counted above)", ""]
        refused = lambda r: (
            None if reference_ok(r) else (r["mujoco"].get("mujoco") or {}).get("error")
        )
        out += table(["files", "cause", "example"], cause_rows(mjcf, refused, 10))
        out += ["### Masses that differ from MuJoCo's (relative difference > 1e-6)", ""]
        out += table(["rel. diff", "file", "MuJoCo kg", "ARS kg", "bodies"], mass_rows(mjcf_read))
        out += ["### Simulations that were not bounded (2 s, `ars.Simulation.open`)", ""]
        out += table(
            ["file", "what", "t reached s", "max speed m/s", "MuJoCo 2 s"],
            stability_rows(mjcf, "ars_sim"),
        )
    if urdf:
        out += urdf_sections(urdf)
    records = mjcf + urdf
    out += ["## Crashes, panics and timeouts", ""]
    out += table(["file", "worker", "stage", "kind", "detail"], crash_rows(records)) or [
        "None.",
        "",
    ]
    out += ["## Slowest simulations (simulated s per wall s)", ""]
    out += table(
        ["sim/wall", "file", "stage", "bodies", "t reached s", "wall s"], slow_rows(records)
    )
    return "\n".join(out) + "\n"


def urdf_sections(urdf: list[dict]) -> list[str]:
    out = ["## URDF: ARS against the file's declared masses and PyBullet", ""]
    head = ["package", "files", "PyBullet loads", "ARS loads", "ARS (ignore_visuals)"]
    head += ["mass = declared", "±1 %", "mass = PyBullet", "±1 %", "floor: finite", "bounded"]
    head += ["slow", "fixed base: finite", "bounded", "slow", "crashes"]
    out += table(head, package_rows(urdf, "urdf"))
    out += ["### Why ARS refuses a URDF file", ""]
    out += table(["files", "cause", "example"], cause_rows(urdf, stage_error("ars_strict")))
    out += ["### ... and with ignore_visuals", ""]
    out += table(["files", "cause", "example"], cause_rows(urdf, stage_error("ars_skip")))
    pybullet_errors = lambda r: ((r.get("pybullet") or {}).get("pybullet") or {}).get("error")
    out += ["### Why PyBullet refuses a URDF file", ""]
    out += table(["files", "cause", "example"], cause_rows(urdf, pybullet_errors, 10))
    out += ["### Masses that differ from the declared ones (relative difference > 1e-6)", ""]
    out += table(["rel. diff", "file", "declared kg", "ARS kg", "links"], mass_rows(urdf))
    out += ["### Masses that differ from PyBullet's (relative difference > 1e-6)", ""]
    out += [
        "PyBullet gives a link without `<inertial>` 1 kg; the file and ARS give it none.",
        "",
    ]
    out += table(["rel. diff", "file", "PyBullet kg", "ARS kg"], mass_rows(urdf, pybullet_mass))
    for stage, what in (("ars_sim", "over a floor"), ("ars_sim_fixed", "with a fixed base")):
        out += [f"### Simulations {what} that were not bounded", ""]
        out += table(
            ["file", "what", "t reached s", "max speed m/s", "the other run"],
            stability_rows(urdf, stage),
        )
    return out
