"""Parameter sweeps: many runs of one model, one after the other, over local processes,
or on a Ray cluster, with the same results to the bit whichever way they run.

>>> import ars
>>> def falling(params):
...     sim = ars.Simulation()
...     sim.add_floor()
...     sim.add_sphere(0.1, (0.0, params["height"], 0.0), mass=1.0, name="ball")
...     return sim
>>> runs = ars.sweep(falling, [{"height": 1.0}, {"height": 2.0}], duration=0.1,
...                  record=["ball.position"], every=50)
>>> [len(r.table) for r in runs], float(runs[1].table["ball.position"][0][1])
([6, 6], 2.0)

Only the parameters cross process boundaries: each run is built inside its worker by
``build(params)``, which returns an ``ars.Simulation`` or an original-style
``ars.app.Program``; or ``build`` is a ``Program`` subclass whose class attributes the
parameters override (``ars.sweep(Example2, [{"MAX_TORQUE": 10.0}], ...)``).
"""

from __future__ import annotations

import contextlib
import dataclasses
import hashlib
import importlib
import json
import logging
import multiprocessing
import os
import pickle
import sys
from collections.abc import Callable, Iterable, Iterator, Mapping
from concurrent.futures import ProcessPoolExecutor
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt

# What ``sweep`` runs: ``build(params)`` returning an ``ars.Simulation`` or an
# ``ars.app.Program``, or a ``Program`` subclass.
Build = Callable[[dict[str, Any]], Any] | type
# One run's samples: ``time`` then one field per recorded ``"NAME.ATTRIBUTE"``.
Table = npt.NDArray[np.void]
# What a run gives back: its table, the exception that stopped it, if any, and the
# platform it ran on (``_native._platform()``; empty if its worker died).
Outcome = tuple[Table, BaseException | None, dict[str, str]]
# What every run is given besides its parameters: duration, record, every, seed.
Args = tuple[float, list[str], int, int | None]

if TYPE_CHECKING:
    from ars._native import Body, Joint, Simulation

__all__ = ["RunResult", "SweepResults", "load_sweep", "rerun", "sweep", "table_sha256"]


def table_sha256(table: Table) -> str:
    """sha256 (hex) of a table: its fields' names, types and shapes, then its bytes."""
    digest = hashlib.sha256(repr(table.dtype.descr).encode())
    digest.update(np.ascontiguousarray(table).tobytes())
    return digest.hexdigest()


@dataclasses.dataclass
class RunResult:
    """One run: its parameters, its table (``time`` then one field per recorded
    ``"NAME.ATTRIBUTE"``; what was sampled before a failure, empty if the worker running
    it died), the exception that stopped it (``None`` if it ran to the end), and its
    ``provenance``: what ``ars.rerun`` needs to run it again anywhere and what it must
    get (``build``, ``params``, ``duration``, ``record``, ``every``, ``seed``; the
    ``ars_version``, ``ars_commit``, ``libode_version``, ``cpu`` and ``libc`` it ran
    with; ``table_sha256``)."""

    params: dict[str, Any]
    table: Table
    error: BaseException | None = None
    provenance: dict[str, Any] = dataclasses.field(default_factory=dict)


class SweepResults(list[RunResult]):
    """The runs, in the order of the parameters given."""

    @property
    def table(self) -> Table:
        """Every run's table stacked, with a first field ``run`` (its index)."""
        tables = [(i, r.table) for i, r in enumerate(self) if len(r.table)]
        if not tables:
            return np.zeros(0, dtype=[("run", "i8")])
        fields = tables[0][1].dtype.descr
        stacked = np.zeros(sum(len(t) for _, t in tables), dtype=[("run", "i8"), *fields])
        at = 0
        for i, t in tables:
            part = stacked[at : at + len(t)]
            part["run"] = i
            for name in t.dtype.names or ():
                part[name] = t[name]
            at += len(t)
        return stacked

    @property
    def errors(self) -> list[tuple[int, BaseException]]:
        """``[(index, exception), ...]`` of the runs that failed."""
        return [(i, r.error) for i, r in enumerate(self) if r.error is not None]

    def save(self, path: str | os.PathLike[str]) -> None:
        """Writes every run to a NumPy ``.npz`` file: its table (``run_0``, ``run_1``...)
        and, as JSON text in ``provenance``, each run's provenance with its error's
        message. ``ars.load_sweep(path)`` reads it back."""
        provenance = [
            dict(r.provenance, params=r.params, error=None if r.error is None else repr(r.error))
            for r in self
        ]
        tables = {f"run_{i}": r.table for i, r in enumerate(self)}
        with _file_errors("write the sweep", path):
            np.savez(path, provenance=np.array(json.dumps(provenance)), **tables)  # type: ignore[arg-type]


@contextlib.contextmanager
def _file_errors(what: str, path: str | os.PathLike[str]) -> Iterator[None]:
    """An ``OSError`` inside, as an ``ars.FileError`` naming ``what`` and ``path``."""
    try:
        yield
    except OSError as e:
        from ars import FileError

        if isinstance(e, FileError):
            raise
        shown = os.fspath(path)
        raise FileError(e.errno, f"cannot {what} {shown!r}: {e.strerror or e}", shown) from e


def load_sweep(path: str | os.PathLike[str]) -> SweepResults:
    """The runs saved by ``SweepResults.save``: tables and provenance (an error comes
    back as an ``ars.ArsError`` holding the message it had)."""
    from ars import ArsError

    with _file_errors("read the sweep", path), np.load(path, allow_pickle=False) as data:
        provenance = json.loads(str(data["provenance"]))
        runs = SweepResults()
        for i, prov in enumerate(provenance):
            message = prov.pop("error")
            error = None if message is None else ArsError(message)
            runs.append(RunResult(dict(prov["params"]), data[f"run_{i}"], error, prov))
    return runs


def _build_name(build: Build) -> str:
    return f"{build.__module__}:{build.__qualname__}"


def _import_build(name: str) -> Build:
    module, _, qualname = name.partition(":")
    target: Any = importlib.import_module(module)
    for part in qualname.split("."):
        target = getattr(target, part)
    return target  # type: ignore[no-any-return]


def _provenance(
    build: Build, params: dict[str, Any], args: Args, outcome: Outcome
) -> dict[str, Any]:
    duration, record, every, seed = args
    table, _, platform = outcome
    return {
        "build": _build_name(build),
        "params": params,
        "duration": duration,
        "record": record,
        "every": every,
        "seed": seed,
        **{
            k: platform.get(k, "unknown")
            for k in ("ars_version", "ars_commit", "libode_version", "cpu", "libc")
        },
        "table_sha256": table_sha256(table),
    }


def rerun(result: RunResult, check: bool = True) -> RunResult:
    """Runs one run of a sweep again, here, from its provenance alone (``build`` is
    imported by name: it must be importable here), and returns the new result. With
    ``check`` (the default), a table whose sha256 differs from the one recorded raises
    ``ars.ReproductionError`` naming both runs' platforms."""
    prov = result.provenance
    try:
        build = _import_build(prov["build"])
        args: Args = (prov["duration"], list(prov["record"]), prov["every"], prov["seed"])
    except (KeyError, ImportError, AttributeError) as e:
        from ars import InputError

        raise InputError(
            f"this result cannot be re-run: its provenance lacks or cannot import {e}"
        ) from e
    params = dict(prov["params"])
    outcome = run_one(build, params, *args)
    again = RunResult(params, outcome[0], outcome[1], _provenance(build, params, args, outcome))
    if check and again.provenance["table_sha256"] != prov.get("table_sha256"):
        from ars import ReproductionError

        where = ", ".join(
            f"{k} {prov.get(k)!r} -> {again.provenance[k]!r}"
            for k in ("ars_commit", "libode_version", "cpu", "libc")
        )
        raise ReproductionError(
            f"the re-run of {prov['build']} with {params} gave a table with sha256 "
            f"{again.provenance['table_sha256']}, not the recorded {prov.get('table_sha256')} ({where})"
        )
    return again


def _build(build: Any, params: dict[str, Any]) -> Any:
    from ars.app import Program

    if isinstance(build, type) and issubclass(build, Program):
        return type(build.__name__, (build,), dict(params))()
    return build(params)


def _native_of(target: Any) -> tuple[Simulation, Callable[[float], Any]]:
    from ars import _native
    from ars.app import Program
    from ars.model.simulator import Simulation as OriginalSimulation

    if isinstance(target, _native.Simulation):
        return target, lambda duration: target.run(duration)
    if isinstance(target, Program):
        program: Any = target
        return program.sim.native, program.run
    if isinstance(target, OriginalSimulation):
        original: Any = target

        def frames(duration: float) -> None:
            for _ in range(round(duration * original._FPS)):
                original.on_idle()

        return original.native, frames
    raise TypeError(
        f"build must return an ars.Simulation or an ars.app.Program, got {type(target).__name__}"
    )


def _reader(sim: Simulation, entry: str) -> Callable[[], Any]:
    name, sep, attribute = entry.rpartition(".")
    if not sep or not name or not attribute:
        from ars import InputError

        raise InputError(f"record entries are 'NAME.ATTRIBUTE' (\"r1.angle\"), got {entry!r}")
    from ars import UnknownNameError

    view: Body | Joint
    try:
        view = sim.body(name)
    except UnknownNameError:
        view = sim.joint(name)
    getattr(view, attribute)  # fails now, with the attribute's name, if it has none
    return lambda: getattr(view, attribute)


def _table(record: list[str], rows: list[list[Any]]) -> Table:
    if not rows:
        return np.zeros(0, dtype=[("time", "f8")] + [(r, "f8") for r in record])
    fields: list[Any] = [("time", "f8")]
    for name, value in zip(record, rows[0][1:]):
        shape = np.shape(value)
        fields.append((name, "f8", shape) if shape else (name, "f8"))
    table = np.zeros(len(rows), dtype=fields)
    for i, row in enumerate(rows):
        table[i] = tuple(row)
    return table


def _portable(error: BaseException) -> BaseException:
    """The error itself if it survives pickling, else an ``ars.ArsError`` saying what
    it was."""
    try:
        pickle.loads(pickle.dumps(error))
        return error
    except Exception:  # noqa: BLE001  (whatever stops pickling, say what it was instead)
        from ars import ArsError

        return ArsError(f"{type(error).__module__}.{type(error).__qualname__}: {error}")


def run_one(
    build: Build,
    params: dict[str, Any],
    duration: float,
    record: list[str],
    every: int,
    seed: int | None,
) -> Outcome:
    """One run, where it runs (a worker): returns ``(table, error, platform)``."""
    from ars import _native

    platform: dict[str, str] = dict(_native._platform())
    rows: list[list[Any]] = []
    try:
        target = _build(build, params)
        sim, advance = _native_of(target)
        if seed is not None:
            sim.set_seed(seed)
        readers = [_reader(sim, entry) for entry in record]

        def sample() -> None:
            rows.append([sim.time] + [read() for read in readers])

        def maybe_sample() -> None:
            if sim.step_count % every == 0:
                sample()

        sample()
        sim.add_post_step(maybe_sample)
        advance(duration)
        return _table(record, rows), None, platform
    except Exception as e:  # noqa: BLE001  (a failing run is a result, not a crash)
        return _table(record, rows), _portable(e), platform


class _Progress:
    def __init__(self, total: int, show: bool) -> None:
        self.total, self.done, self.show = total, 0, show

    def step(self) -> None:
        self.done += 1
        if self.show:
            filled = 30 * self.done // max(self.total, 1)
            sys.stderr.write(
                f"\rars.sweep [{'#' * filled}{' ' * (30 - filled)}] {self.done}/{self.total}"
            )
            if self.done == self.total:
                sys.stderr.write("\n")
            sys.stderr.flush()


def sweep(
    build: Build,
    params: Iterable[Mapping[str, Any]],
    duration: float,
    record: Iterable[str] = (),
    every: int = 1,
    backend: str = "serial",
    seed: int | None = 0,
    workers: int | None = None,
    address: str | None = None,
    progress: bool | None = None,
) -> SweepResults:
    """Runs ``build(p)`` for ``duration`` seconds for every ``p`` in ``params``,
    sampling ``time`` and each ``"NAME.ATTRIBUTE"`` of ``record`` (named access:
    ``"r1.angle"``, ``"pole.position"``) at the start and every ``every`` steps.

    ``backend``: ``"serial"`` (here), ``"processes"`` (``workers`` local processes;
    ``build`` must be importable, and a script needs an ``if __name__ ==
    "__main__":`` guard), or ``"ray"`` (the cluster at ``address`` or ``RAY_ADDRESS``
    if given, else a quiet local one of ``workers`` CPUs, started and shut down here).
    ``seed`` seeds each run's world (``None``: leave it). ``progress``: a progress bar on
    stderr (default: when it is a terminal).

    Returns a :class:`SweepResults`: one :class:`RunResult` per parameter set, in
    order; a run that fails has its ``error`` and the others run on.
    """
    sets = [dict(p) for p in params]
    fields = list(record)
    repeated = sorted({f for f in fields if fields.count(f) > 1})
    if repeated:
        from ars import InputError

        raise InputError(f"record names {repeated} more than once: name each entry once")
    if not isinstance(every, int) or every < 1:
        from ars import InputError

        raise InputError(f"every must be a whole number of steps ≥ 1, got {every!r}")
    show = sys.stderr.isatty() if progress is None else progress
    bar = _Progress(len(sets), show)
    args = (duration, fields, every, seed)
    if backend == "serial":
        outcomes: list[Outcome] = []
        for p in sets:
            outcomes.append(run_one(build, p, *args))
            bar.step()
    elif backend == "processes":
        outcomes = _on_processes(build, sets, args, workers, bar)
    elif backend == "ray":
        outcomes = _on_ray(build, sets, args, workers, address, bar)
    else:
        from ars import InputError

        raise InputError(f"backend must be 'serial', 'processes' or 'ray', got {backend!r}")
    return SweepResults(
        RunResult(p, o[0], o[1], _provenance(build, p, args, o)) for p, o in zip(sets, outcomes)
    )


def _check_portable(build: Build, backend: str) -> None:
    try:
        pickle.dumps(build)
    except Exception as e:
        raise TypeError(
            f"the {backend} backend sends build to other processes by name: define it at the top "
            f"level of an importable module (not a lambda or a local function) ({e})"
        ) from e


def _on_processes(
    build: Build, params: list[dict[str, Any]], args: Args, workers: int | None, bar: _Progress
) -> list[Outcome]:
    _check_portable(build, "processes")
    context = multiprocessing.get_context("spawn")
    pool = ProcessPoolExecutor(max_workers=workers or os.cpu_count(), mp_context=context)
    try:
        futures = [pool.submit(run_one, build, p, *args) for p in params]
        outcomes: list[Outcome] = []
        for f in futures:
            try:
                outcomes.append(f.result())
            except Exception as e:  # noqa: BLE001  (the worker died: that run's result)
                outcomes.append((_table(args[1], []), e, {}))
            bar.step()
    except BaseException:
        # Ctrl-C (or any other way out): the runs not finished are dropped and their
        # workers ended now, rather than waited for.
        _stop_workers(pool)
        raise
    pool.shutdown()
    return outcomes


def _stop_workers(pool: ProcessPoolExecutor) -> None:
    """Cancels the runs not started and ends the pool's worker processes at once
    (rather than waiting for the runs they are in)."""
    terminate = getattr(pool, "terminate_workers", None)  # Python 3.14
    if terminate is not None:
        terminate()
        return
    # Before Python 3.14: the processes, as the pool keeps them until its shutdown.
    processes = list((getattr(pool, "_processes", None) or {}).values())
    for process in processes:
        process.terminate()
    pool.shutdown(wait=True, cancel_futures=True)
    for process in processes:
        process.join(timeout=5)


def _on_ray(
    build: Build,
    params: list[dict[str, Any]],
    args: Args,
    workers: int | None,
    address: str | None,
    bar: _Progress,
) -> list[Outcome]:
    try:
        import ray  # type: ignore[import-not-found, unused-ignore]
    except ImportError as e:
        raise ImportError("the ray backend needs Ray: pip install ray") from e
    started = False
    if not ray.is_initialized():
        address = address or os.environ.get("RAY_ADDRESS")
        if address:
            ray.init(address=address, log_to_driver=False, logging_level=logging.ERROR)
        else:
            os.environ.setdefault("RAY_USAGE_STATS_ENABLED", "0")
            os.environ.setdefault("RAY_ENABLE_WINDOWS_OR_OSX_CLUSTER", "0")
            # Workers import what this process imports: give them its module path.
            path = os.pathsep.join(p for p in sys.path if p and os.path.isdir(p))
            previous = os.environ.get("PYTHONPATH")
            os.environ["PYTHONPATH"] = path
            try:
                ray.init(
                    num_cpus=workers or os.cpu_count(),
                    include_dashboard=False,
                    log_to_driver=False,
                    logging_level=logging.ERROR,
                )
            finally:
                if previous is None:
                    del os.environ["PYTHONPATH"]
                else:
                    os.environ["PYTHONPATH"] = previous
        started = True
    try:
        remote = ray.remote(num_cpus=1)(run_one)
        refs = [remote.remote(build, p, *args) for p in params]
        outcomes: list[Outcome] = []
        try:
            for ref in refs:
                # Waited for in short slices: Python sees Ctrl-C between two (a bare
                # ray.get let it through half a second late).
                while not ray.wait([ref], timeout=0.05)[0]:
                    pass
                try:
                    outcomes.append(ray.get(ref))
                except Exception as e:  # noqa: BLE001  (the worker died: that run's result)
                    outcomes.append((_table(args[1], []), e, {}))
                bar.step()
        except KeyboardInterrupt:
            # Ctrl-C: the runs not finished are cancelled (their tasks killed). The
            # local cluster is left for Python's exit (or ray.shutdown()) to end: its
            # shutdown takes over a second, and Ctrl-C must return at once.
            for ref in refs:
                ray.cancel(ref, force=True)
            started = False
            raise
        return outcomes
    finally:
        if started:
            ray.shutdown()
