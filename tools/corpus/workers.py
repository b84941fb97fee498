"""The per-file work of `report.py`, each task run in its own process.

    python workers.py TASK FILE [OPTIONS_JSON]

TASK is `mujoco` (MuJoCo compiles an MJCF file, its masses, 2 s of its own simulation),
`ars-mjcf` (ARS loads it strictly and with `skip_unsupported`, its masses, 2 s of simulation),
`ars-urdf` (ARS loads a URDF, its masses, 2 s over a floor and 2 s with a fixed base) or
`pybullet` (PyBullet loads a URDF, its masses). A task prints what it finds as it goes, one JSON
object a line after the marker `@@corpus `, `{"running": STAGE}` before each stage: a crash or
a hang then still leaves what was found, and the parent knows in which stage it happened. A
simulation also prints `{"progress": {"stage": STAGE, "time": T}}` as it goes: the parent stops
one whose single step outlasts the wall-clock budget, and records how far it got.

Module level needs only the standard library (the parent imports `normalise` from here, and
PyBullet may run under another interpreter); each task imports its engine.
"""

from __future__ import annotations

import json
import math
import re
import sys
import time
import traceback
import warnings

MARKER = "@@corpus "
CHUNK = 0.1  # seconds of simulated time between finiteness checks


def emit(**fields: object) -> None:
    # On a line of its own: PyBullet prints warnings without a newline at their end.
    print("\n" + MARKER + json.dumps(fields, default=str), file=sys.stdout, flush=True)


def first_line(text: str, width: int = 4000) -> str:
    for line in str(text).splitlines():
        if line.strip():
            return line.strip()[:width]
    return ""


def describe(error: BaseException) -> str:
    """`Class: first line of the message`."""
    return f"{type(error).__name__}: {first_line(str(error))}"


_PATH = re.compile(r"(?:[A-Za-z]:)?(?:[\w.+~@-]*/)+[\w.+~@-]+")
_QUOTED = re.compile(r"\"[^\"]*\"|'[^']*'|`[^`]*`")
_AT_LINE = re.compile(r"\s*(?:at|on) line \d+(?:, column \d+)?")
_NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")


def normalise(message: str) -> str:
    """A failure message reduced to its cause: no paths, names, line numbers or numbers."""
    text = first_line(message)
    text = _QUOTED.sub("<name>", text)
    text = _PATH.sub("<file>", text)
    text = _AT_LINE.sub("", text)
    text = _NUMBER.sub("N", text)
    text = re.sub(r"\bN(?:[ ,]+N)+\b", "N…", text)
    text = re.sub(r"^(\w+: )?<file>,?\s*", r"\1", text)
    text = re.sub(r"(<file>[,;: ]*)+", "<file> ", text)
    return re.sub(r"\s+", " ", text).strip()


def finite(value: float) -> float | None:
    return value if math.isfinite(value) else None


# -- MuJoCo ---------------------------------------------------------------------------------


def task_mujoco(path: str, options: dict) -> None:
    import mujoco
    import numpy as np

    emit(running="mujoco_compile")
    start = time.perf_counter()
    try:
        model = mujoco.MjModel.from_xml_path(path)
    except Exception as error:  # noqa: BLE001 - MuJoCo's ValueError, or anything else
        emit(mujoco={"ok": False, "error": describe(error)})
        return
    masses = {}
    for i in range(1, model.nbody):
        name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_BODY, i) or f"body{i}"
        masses[name] = float(model.body_mass[i])
    emit(
        mujoco={
            "ok": True,
            "seconds": time.perf_counter() - start,
            "bodies": model.nbody - 1,
            "joints": model.njnt,
            "geoms": model.ngeom,
            "timestep": float(model.opt.timestep),
            "total_mass": float(sum(masses.values())),
            "body_masses": masses,
        }
    )
    emit(running="mujoco_sim")
    data = mujoco.MjData(model)
    start = time.perf_counter()
    steps_per_chunk = max(1, round(CHUNK / model.opt.timestep))
    ok, out_of_time = True, False
    while data.time < options["seconds"] - 1e-9:
        if time.perf_counter() - start > options["sim_wall"]:
            out_of_time = True
            break
        mujoco.mj_step(model, data, nstep=steps_per_chunk)
        if not (np.isfinite(data.qpos).all() and np.isfinite(data.qvel).all()):
            ok = False
            break
        emit(progress={"stage": "mujoco_sim", "time": float(data.time)})
    bad = int(data.warning[mujoco.mjtWarning.mjWARN_BADQACC].number)
    emit(
        mujoco_sim={
            "finite": ok,
            "out_of_time": out_of_time,
            "time": float(data.time),
            "wall": time.perf_counter() - start,
            "bad_qacc_warnings": bad,
        }
    )


# -- ARS ------------------------------------------------------------------------------------


def body_masses(sim: object, names: list[str]) -> dict:
    """Each named body's mass; static objects and names ARS has no object for apart."""
    import ars

    masses, static, missing = {}, [], []
    for name in names:
        try:
            masses[name] = float(sim.body(name).mass)  # type: ignore[attr-defined]
        except ars.UnknownNameError:
            missing.append(name)
        except ars.InputError:
            static.append(name)
    return {
        "total": float(sum(masses.values())),
        "bodies": masses,
        "static": static,
        "missing": missing,
    }


def load(label: str, loader, *args, **kwargs) -> tuple[object | None, dict]:
    """Calls `loader`, emitting `{label: {ok, error, seconds}}`; returns its result."""
    emit(running=label)
    start = time.perf_counter()
    try:
        result = loader(*args, **kwargs)
    except (KeyboardInterrupt, SystemExit):
        raise
    except BaseException as error:  # noqa: BLE001 - PyO3's PanicException is one
        record = {"ok": False, "error": describe(error), "error_class": type(error).__name__}
        if type(error).__name__ == "PanicException":
            record["traceback"] = traceback.format_exc()[-2000:]
        emit(**{label: record})
        return None, record
    record = {"ok": True, "seconds": time.perf_counter() - start}
    emit(**{label: record})
    return result, record


def simulate(label: str, sim: object, options: dict) -> None:
    """Runs `sim` for `options["seconds"]`, checking that every body stays finite, for at most
    `options["sim_wall"]` seconds of wall-clock time; emits `label`.

    Steps go in batches of 1 to 0.1 s worth, each batch sized to take about 0.1 to 1 s of wall
    time, so that a slow model is stopped close to its budget (a single step that outlasts it is
    stopped by the parent, `report.run_task`)."""
    import ars
    import numpy as np

    emit(running=label)
    bodies = []
    for name in sim.objects:  # type: ignore[attr-defined]
        try:
            body = sim.body(name)  # type: ignore[attr-defined]
            body.mass  # noqa: B018 - raises for static objects
            bodies.append(body)
        except ars.ArsError:
            continue
    start = time.perf_counter()
    record: dict = {"finite": True, "error": None, "out_of_time": False}
    max_speed = 0.0
    dt = float(sim.time_step)  # type: ignore[attr-defined]
    total = round(options["seconds"] / dt)
    most = max(1, round(CHUNK / dt))
    batch = 1
    while sim.step_count < total:  # type: ignore[attr-defined]
        if time.perf_counter() - start > options["sim_wall"]:
            record["out_of_time"] = True
            break
        began = time.perf_counter()
        try:
            sim.step(min(batch, total - sim.step_count))  # type: ignore[attr-defined]
        except (KeyboardInterrupt, SystemExit):
            raise
        except BaseException as error:  # noqa: BLE001 - a panic too: a finding
            record.update(finite=False, error=describe(error), error_class=type(error).__name__)
            break
        took = time.perf_counter() - began
        batch = min(most, batch * 2) if took < 0.1 else max(1, batch // 2) if took > 1 else batch
        state = [b.position for b in bodies] + [b.linear_velocity for b in bodies]
        if state and not np.isfinite(np.array(state)).all():
            record["finite"] = False
            break
        speeds = [float(np.linalg.norm(b.linear_velocity)) for b in bodies]
        max_speed = max([max_speed, *speeds])
        emit(progress={"stage": label, "time": float(sim.time)})  # type: ignore[attr-defined]
    record.update(
        time=float(sim.time),  # type: ignore[attr-defined]
        steps=int(sim.step_count),  # type: ignore[attr-defined]
        dt=dt,
        bodies=len(bodies),
        max_speed=finite(max_speed),
        wall=time.perf_counter() - start,
    )
    emit(**{label: record})


def task_ars_mjcf(path: str, options: dict) -> None:
    import ars

    warnings.simplefilter("ignore")
    strict_sim = ars.Simulation()
    strict, _ = load("ars_strict", strict_sim.load_mjcf, path)
    skip_sim = ars.Simulation()
    skip, _ = load("ars_skip", skip_sim.load_mjcf, path, skip_unsupported=True)
    if skip is not None:
        skipped = [first_line(s) for s in skip["skipped"]]  # type: ignore[index]
        emit(ars_skipped=skipped)
    model, sim, source = (
        (strict, strict_sim, "strict") if strict is not None else (skip, skip_sim, "skip")
    )
    if model is None:
        return
    masses = body_masses(sim, list(model["bodies"]))  # type: ignore[index]
    emit(ars_mass={"from": source, **masses})
    opened, _ = load("ars_open", ars.Simulation.open, path)
    if opened is not None:
        simulate("ars_sim", opened, options)


def task_ars_urdf(path: str, options: dict) -> None:
    """Loads, weighs, simulates over a floor, then with a fixed base; with `options["after"]`
    set to `"ars_sim"` (the parent stopped that simulation), only the last, with
    `options["ignore_visuals"]` as the first run found it needed."""
    import os

    import ars

    warnings.simplefilter("ignore")
    packages = options.get("packages") or {}
    if packages:  # for the simulations below, as a user's ROS_PACKAGE_PATH would
        parents = sorted({os.path.dirname(d) for d in packages.values()})
        os.environ["ROS_PACKAGE_PATH"] = os.pathsep.join(parents)
    kwargs = {"packages": packages}
    if options.get("after") == "ars_sim":
        if options.get("ignore_visuals"):
            kwargs["ignore_visuals"] = True
        simulate_fixed(path, kwargs, options)
        return
    strict_sim = ars.Simulation()
    robot, _ = load("ars_strict", strict_sim.load_urdf, path, **kwargs)
    sim, source = strict_sim, "strict"
    if robot is None:
        skip_sim = ars.Simulation()
        robot, _ = load("ars_skip", skip_sim.load_urdf, path, ignore_visuals=True, **kwargs)
        sim, source = skip_sim, "ignore_visuals"
        kwargs["ignore_visuals"] = True
    if robot is None:
        return
    emit(ars_mass={"from": source, **body_masses(sim, list(robot["links"]))})  # type: ignore[index]
    floor_sim = ars.Simulation()
    floor_sim.add_floor()
    floored, _ = load("ars_open", floor_sim.load_urdf, path, **kwargs)
    if floored is not None:
        simulate("ars_sim", floor_sim, options)
    simulate_fixed(path, kwargs, options)


def simulate_fixed(path: str, kwargs: dict, options: dict) -> None:
    import ars

    fixed_sim = ars.Simulation()
    fixed, _ = load("ars_open_fixed", fixed_sim.load_urdf, path, fixed_base=True, **kwargs)
    if fixed is not None:
        simulate("ars_sim_fixed", fixed_sim, options)


# -- PyBullet -------------------------------------------------------------------------------


def task_pybullet(path: str, options: dict) -> None:
    import os

    emit(running="pybullet_import")
    import pybullet as p

    client = p.connect(p.DIRECT)
    for directory in sorted({os.path.dirname(d) for d in (options.get("packages") or {}).values()}):
        p.setAdditionalSearchPath(directory, physicsClientId=client)
    emit(running="pybullet_load")
    start = time.perf_counter()
    try:
        body = p.loadURDF(path, physicsClientId=client)
    except Exception as error:  # noqa: BLE001 - pybullet.error, or anything else
        emit(pybullet={"ok": False, "error": describe(error)})
        return
    masses = {p.getBodyInfo(body, physicsClientId=client)[0].decode(): 0.0}
    base = next(iter(masses))
    masses[base] = float(p.getDynamicsInfo(body, -1, physicsClientId=client)[0])
    for j in range(p.getNumJoints(body, physicsClientId=client)):
        link = p.getJointInfo(body, j, physicsClientId=client)[12].decode()
        masses[link] = float(p.getDynamicsInfo(body, j, physicsClientId=client)[0])
    emit(
        pybullet={
            "ok": True,
            "seconds": time.perf_counter() - start,
            "total_mass": float(sum(masses.values())),
            "link_masses": masses,
        }
    )


TASKS = {
    "mujoco": task_mujoco,
    "ars-mjcf": task_ars_mjcf,
    "ars-urdf": task_ars_urdf,
    "pybullet": task_pybullet,
}


def main(argv: list[str]) -> int:
    task, path = argv[0], argv[1]
    options = json.loads(argv[2]) if len(argv) > 2 else {}
    options.setdefault("seconds", 2.0)
    options.setdefault("sim_wall", 30.0)
    TASKS[task](path, options)
    emit(done=True)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
