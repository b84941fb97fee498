"""ars.sweep: runs built where they run, results in order, the same to the bit on every
backend, and a failing run losing nothing of the others, with its exception's class."""

import numpy as np
import pytest

import ars
from ars.app import Program


class HookFailure(Exception):
    """Raised on purpose by a hook."""


def pendulum(params):
    """A ball on a hinge, pushed by a constant torque; the parameters may break it."""
    sim = ars.Simulation(gravity=(0.0, -9.81, 0.0))
    ball = sim.add_sphere(params.get("radius", 0.1), (1.0, 0.0, 0.0), mass=1.0, name="ball")
    sim.add_rotary_joint("hinge", ball, None, (0.0, 0.0, 0.0), (0.0, 0.0, 1.0))
    hinge = sim.joint("hinge")
    torque = params["torque"]
    sim.add_pre_step(lambda: hinge.add_torque(torque))
    if params.get("fail") == "hook":

        def fail():
            if sim.step_count == 100:
                raise HookFailure("on purpose at step 100")

        sim.add_pre_step(fail)
    if params.get("fail") == "panic":
        ars._native._panic_for_tests("in a worker")
    return sim


class Swing(Program):
    """The same pendulum as an original-style program; TORQUE is swept."""

    FPS = 50
    STEPS_PER_FRAME = 25
    TORQUE = 1.0

    def create_sim_objects(self):
        self.ball = self.sim.add_sphere(0.1, (1, 0, 0), mass=1.0)
        box = self.sim.add_box((0.1, 0.1, 0.1), (0, 0, 0), mass=100.0)
        self.sim.add_rotary_joint(
            "r1", self.sim.get_object(self.ball), self.sim.get_object(box), (0, 0, 0), (0, 0, 1)
        )
        self.sim.add_fixed_joint("base", self.sim.get_object(box), None)
        ars.app.dispatcher.connect(self.on_pre_step, ars.app.signals.SIM_PRE_STEP)

    def on_pre_step(self):
        self.sim.get_joint("r1").add_torque(self.TORQUE)


TORQUES = [{"torque": t} for t in (0.5, 1.0, 1.5, 2.0, -0.5, -1.0, -1.5, -2.0)]
RECORD = ["hinge.angle", "hinge.rate", "ball.position"]


def same_bits(a, b):
    return a.dtype == b.dtype and a.tobytes() == b.tobytes()


def test_a_serial_sweep_records_every_run_in_order():
    runs = ars.sweep(pendulum, TORQUES, duration=0.2, record=RECORD, every=10)
    assert len(runs) == 8 and [r.params for r in runs] == TORQUES
    t = runs[0].table
    assert t.dtype.names == ("time", "hinge.angle", "hinge.rate", "ball.position")
    assert t["ball.position"].shape == (51, 3)
    assert t["time"][0] == 0.0 and t["time"][-1] == pytest.approx(0.2)
    # More torque, more turn.
    finals = [r.table["hinge.angle"][-1] for r in runs[:4]]
    assert finals == sorted(finals)
    stacked = runs.table
    assert stacked.dtype.names[0] == "run" and len(stacked) == 8 * 51
    assert np.array_equal(stacked[stacked["run"] == 3]["hinge.rate"], runs[3].table["hinge.rate"])


def test_program_classes_are_swept_by_their_class_attributes():
    runs = ars.sweep(
        Swing, [{"TORQUE": 1.0}, {"TORQUE": 3.0}], duration=0.2, record=["r1.angle"], every=5
    )
    assert all(r.error is None for r in runs)
    a, b = (r.table["r1.angle"][-1] for r in runs)
    assert abs(b) > abs(a) > 0.0


def test_the_processes_backend_equals_serial_to_the_bit():
    serial = ars.sweep(pendulum, TORQUES, duration=0.2, record=RECORD, every=10)
    processes = ars.sweep(
        pendulum, TORQUES, duration=0.2, record=RECORD, every=10, backend="processes", workers=2
    )
    assert all(same_bits(a.table, b.table) for a, b in zip(serial, processes))


def test_a_lambda_cannot_go_to_other_processes():
    with pytest.raises(TypeError, match="importable module"):
        ars.sweep(lambda p: pendulum(p), TORQUES, duration=0.1, backend="processes")


def test_failures_are_kept_per_run_and_the_others_complete():
    params = [*TORQUES[:3], {"torque": 1.0, "radius": -1.0}, *TORQUES[3:7]]
    runs = ars.sweep(pendulum, params, duration=0.2, record=RECORD, every=10)
    assert [i for i, _ in runs.errors] == [3]
    assert isinstance(runs[3].error, ars.InputError) and "radius" in str(runs[3].error)
    assert sum(r.error is None for r in runs) == 7


def test_ray_sweeps_equal_serial_to_the_bit_and_keep_each_failure():
    params = [*TORQUES[:3], {"torque": 1.0, "radius": -1.0}, *TORQUES[3:7]]
    serial = ars.sweep(pendulum, params, duration=0.2, record=RECORD, every=10)
    on_ray = ars.sweep(
        pendulum, params, duration=0.2, record=RECORD, every=10, backend="ray", workers=2
    )
    assert len(on_ray) == 8
    assert [i for i, _ in on_ray.errors] == [3]
    assert type(on_ray[3].error) is ars.InputError and "radius" in str(on_ray[3].error)
    for a, b in zip(serial, on_ray):
        if a.error is None:
            assert b.error is None and same_bits(a.table, b.table)


def test_errors_arrive_through_ray_as_their_own_classes():
    params = [
        {"torque": 1.0, "fail": "hook"},
        {"torque": 1.0, "fail": "panic"},
        {"torque": 1.0},
    ]
    runs = ars.sweep(
        pendulum, params, duration=0.2, record=["hinge.angle"], every=10, backend="ray", workers=2
    )
    hook, panic, fine = runs
    assert type(hook.error) is HookFailure and "step 100" in str(hook.error)
    assert len(hook.table) == 11, "steps 0 to 100, sampled before the failure, are kept"
    assert type(panic.error) is ars.InternalError and "in a worker" in str(panic.error)
    assert fine.error is None and len(fine.table) == 51
    unknown = ars.sweep(
        pendulum, [{"torque": 1.0}], duration=0.1, record=["hinj.angle"], backend="ray", workers=1
    )
    assert type(unknown[0].error) is ars.UnknownNameError and "hinge" in str(unknown[0].error)


def test_the_shipped_sweep_example_finds_the_thesis_cone():
    import importlib.util
    import pathlib

    path = pathlib.Path(__file__).parents[1] / "examples" / "sweep_conical_pendulum.py"
    spec = importlib.util.spec_from_file_location("sweep_conical_pendulum", path)
    example = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(example)
    runs = ars.sweep(
        example.conical_pendulum,
        [{"torque": 20.0}],
        duration=example.DURATION,
        record=["r1.rate", "r2.angle"],
        every=40,
    )
    (rate,), (angle,) = example.steady(runs)
    # The thesis' steady state at 20 N·m (ars-original.md): 3.99939 rad/s, 0.71154 rad.
    assert rate == pytest.approx(4.0, abs=1e-3)
    assert angle == pytest.approx(0.7115, abs=1e-3)


def test_a_run_of_a_sweep_is_rerun_alone_from_its_saved_provenance(tmp_path):
    # 8 runs on the processes backend; run 5 again, here, from the saved file alone.
    runs = ars.sweep(
        pendulum, TORQUES, duration=0.2, record=RECORD, every=10, backend="processes", workers=2
    )
    path = tmp_path / "sweep.npz"
    runs.save(path)
    loaded = ars.load_sweep(path)
    assert len(loaded) == 8
    fifth = loaded[5]
    assert same_bits(fifth.table, runs[5].table)
    prov = fifth.provenance
    assert prov["build"] == f"{__name__}:pendulum" and prov["params"] == TORQUES[5]
    assert (prov["duration"], prov["record"], prov["every"], prov["seed"]) == (0.2, RECORD, 10, 0)
    platform = ars._native._platform()
    for key in ("ars_version", "ars_commit", "libode_version", "cpu", "libc"):
        assert prov[key] == platform[key], key
    assert prov["table_sha256"] == ars.sweeps.table_sha256(runs[5].table)
    assert len({r.provenance["table_sha256"] for r in loaded}) == 8, "each run its own table"

    again = ars.rerun(fifth)
    assert again.provenance["table_sha256"] == prov["table_sha256"]
    assert same_bits(again.table, fifth.table)

    # A recorded hash that this machine does not compute: the re-run says so.
    recorded = prov["table_sha256"]
    fifth.provenance["table_sha256"] = "0" * 64
    with pytest.raises(ars.ReproductionError, match="not the recorded 0000"):
        ars.rerun(fifth)
    assert ars.rerun(fifth, check=False).provenance["table_sha256"] == recorded
    with pytest.raises(ars.InputError, match="cannot be re-run"):
        ars.rerun(ars.RunResult({}, fifth.table))


def test_a_failed_runs_error_is_saved_with_its_message(tmp_path):
    runs = ars.sweep(pendulum, [{"torque": 1.0, "fail": "hook"}], duration=0.1, record=RECORD)
    runs.save(tmp_path / "failed.npz")
    (loaded,) = ars.load_sweep(tmp_path / "failed.npz")
    assert isinstance(loaded.error, ars.ArsError) and "on purpose at step 100" in str(loaded.error)
