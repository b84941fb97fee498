"""Programs of our own in the original ARS style, on ``ars.app``: signals, keys,
sensors, and one program's handlers never hearing another program's simulation."""

import doctest
import math

import pytest

import ars.app
import ars.constants as cts
import ars.model.collision.base
import ars.utils.mathematical as mut
from ars.app import Program, dispatcher
from ars.model.robot import sensors
from ars.model.simulator import signals
from ars.utils.geometry import calc_rotation_matrix


def hinged_ball(sim):
    """A ball hinged (``"hinge"``) to a box fixed to the world; their names."""
    box = sim.add_box((0.2, 0.2, 0.2), (0, 2, 0), mass=1000.0)
    ball = sim.add_sphere(0.1, (1, 2, 0), mass=1.0)
    sim.add_fixed_joint("anchor", sim.get_object(box), None)
    sim.add_rotary_joint("hinge", sim.get_object(ball), sim.get_object(box), None, cts.Z_AXIS)
    return box, ball


class Pendulum(Program):
    """A ball on a massless rod hinged to a fixed box, recording its angle."""

    FPS = 50
    STEPS_PER_FRAME = 10

    def __init__(self):
        Program.__init__(self)
        self.heard = []
        dispatcher.connect(self.on_pre_step, signals.SIM_PRE_STEP)
        self.key_press_functions.add("a", self.push)
        self.key_press_functions.add("h", self.push, repeat=True)
        self.angle = sensors.RotaryJointSensor(self.sim.get_joint("hinge").joint)
        self.torques = sensors.JointTorque(self.sim.get_joint("hinge"), self.sim)

    def create_sim_objects(self):
        self.box, self.ball = hinged_ball(self.sim)

    def on_pre_step(self, sender):
        self.heard.append(sender)
        self.angle.on_change(self.sim.sim_time)

    @property
    def steps(self):
        return len(self.heard)

    def push(self):
        self.sim.get_joint("hinge").add_torque(1.0)


def test_a_program_runs_and_records_with_its_sensors():
    program = Pendulum()
    sim = program.run(0.5)
    assert sim is program.sim
    assert sim.num_frame == 25 and sim.num_iter == 250
    assert sim.sim_time == pytest.approx(0.5)
    records = program.angle.data_queue.convert_to_list()
    assert len(records) == 250
    assert records[0].get_time() == 0.0 and records[0].get_kwarg("angle") == 0.0
    # The ball falls: the hinge turns one way.
    assert records[-1].get_kwarg("angle") < -0.1
    assert str(records[0]) == " 0.000000 | angle: -0.0 | angle_rate: 0.0 |", (
        "ODE's -0.0, as printed"
    )


def test_keys_act_once_or_in_every_step_of_the_next_frame():
    program = Pendulum()
    program.on_action_selection("a")
    assert program.torques.data_queue.count() == 1
    program.on_action_selection("h")
    program.sim.on_idle()
    assert program.torques.data_queue.count() == 1 + 10, "once per step of the frame"
    program.sim.on_idle()
    assert program.torques.data_queue.count() == 11, "only in the next frame"
    program.on_action_selection("unbound")  # logged, not raised


class Listening(Pendulum):
    """Hears every sensor's records (connected with any sender), as the original's
    laser demo does, and records with a sensor of each kind of source."""

    def __init__(self):
        Pendulum.__init__(self)
        self.records = []
        dispatcher.connect(self.on_record, sensors.signals.SENSOR_POST_ON_CHANGE)
        self.gps = sensors.GPS(self.sim.get_object(self.ball))
        self.laser = sensors.Laser(self.sim.collision_space, 5.0)
        self.energy = sensors.SystemTotalEnergy(self.sim)

    def on_record(self, sender, data):
        self.records.append(sender)

    def measure(self):
        for sensor in (self.gps, self.angle, self.laser, self.energy):
            sensor.on_change(self.sim.sim_time)


def test_a_programs_handlers_hear_the_sensors_of_its_own_simulation_only():
    first = Listening()
    second = Listening()
    second.measure()
    first.measure()
    own = [first.gps, first.angle, first.laser, first.energy]
    assert first.records == own
    assert second.records == [second.gps, second.angle, second.laser, second.energy]


def test_connecting_the_same_handler_twice_calls_it_once():
    program = Pendulum()
    dispatcher.connect(program.on_pre_step, signals.SIM_PRE_STEP)
    program.run(0.02)
    assert len(program.heard) == 10


def test_a_failing_handler_is_logged_and_the_simulation_goes_on(caplog):
    class Failing(Pendulum):
        def on_pre_step(self, sender):
            raise RuntimeError("handler bug")

    program = Failing()
    program.run(0.1)
    assert program.sim.num_iter == 50
    assert "handler bug" in caplog.text


def test_the_original_helpers():
    assert doctest.testmod(ars.model.collision.base).failed == 0
    assert mut.sign(0.0) == -1.0 and mut.length3((3, 4, 12)) == 13.0
    rot = calc_rotation_matrix((0, 1, 0), mut.pi / 2)
    x = mut.rotate3(rot, (1, 0, 0))
    assert x == pytest.approx((0.0, 0.0, -1.0))
    assert cts.COLOR_RED == (0.99609375, 0.0, 0.0)
    assert issubclass(ars.app.exc.JointError, ars.ArsError)
    assert math.isclose(cts.G_VECTOR[1], -9.81)


class Counting(Program):
    """Counts its steps in a pre-step handler that takes nothing (what the original's
    programs connect: the one the simulation calls without sending the signal)."""

    FPS = 50
    STEPS_PER_FRAME = 10

    def __init__(self):
        Program.__init__(self)
        self.steps = 0
        dispatcher.connect(self.on_pre_step, signals.SIM_PRE_STEP)

    def create_sim_objects(self):
        self.box, self.ball = hinged_ball(self.sim)

    def on_pre_step(self):
        self.steps += 1


def test_handlers_connected_or_gone_during_a_run_are_heard_from_the_next_step():
    program = Counting()
    after = []

    def on_post_step():
        after.append(program.sim.num_iter)

    class Late:
        def __init__(self):
            self.steps = 0

        def on_pre_step(self):
            self.steps += 1

    late = [Late()]  # (a list, so that the test can let it go)

    def connect_late():
        if program.steps == 20:
            dispatcher.connect(late[0].on_pre_step, signals.SIM_PRE_STEP)
            dispatcher.connect(on_post_step, signals.SIM_POST_STEP)

    dispatcher.connect(connect_late, signals.SIM_PRE_STEP)
    program.run(0.1)  # 50 steps
    assert program.steps == 50 and program.sim.num_iter == 50
    # Connected in the 20th step: heard from the 21st; the post-step handler from the
    # 20th step's end.
    assert late[0].steps == 30
    assert after == list(range(20, 51))
    dispatcher.disconnect(on_post_step, signals.SIM_POST_STEP)
    late.clear()  # gone: no longer called, and nothing fails
    program.run(0.1)
    assert program.steps == 100 and program.sim.num_iter == 100 and len(after) == 31
    dispatcher.disconnect(connect_late, signals.SIM_PRE_STEP)


# A handler that takes the sender is sent the signal; one that takes nothing is called
# by the step's hook directly: both hear their own program's simulation only.
@pytest.mark.parametrize(
    "program_class", [Pendulum, Counting], ids=["taking the sender", "taking nothing"]
)
def test_a_programs_handlers_hear_its_own_simulation_only(program_class):
    first = program_class()
    first.run(0.1)
    second = program_class()
    second.run(0.1)
    first.run(0.1)
    assert (first.steps, second.steps) == (100, 50)
    if program_class is Pendulum:
        assert all(s is second.sim for s in second.heard)
        assert all(s is first.sim for s in first.heard)


class Pushing(Counting):
    """Puts a torque on its hinge at every step, as the IROS programs do."""

    TORQUE = 0.5

    def on_pre_step(self):
        Counting.on_pre_step(self)
        self.sim.get_joint("hinge").add_torque(self.TORQUE)


def test_torques_act_the_same_heard_or_not_and_a_bad_one_is_logged(caplog):
    from ars.model.robot import signals as joint_signals

    quiet = Pushing()
    quiet.run(0.2)
    heard = []

    def on_torque(torque):
        heard.append(torque)

    listened = Pushing()
    dispatcher.connect(on_torque, joint_signals.JOINT_PRE_ADD_TORQUE)
    listened.run(0.2)
    dispatcher.disconnect(on_torque, joint_signals.JOINT_PRE_ADD_TORQUE)
    assert heard == [0.5] * 100
    angle = [p.sim.get_joint("hinge").joint.angle for p in (quiet, listened)]
    assert angle[0] == angle[1] and angle[0] != 0.0

    class Failing(Pushing):
        TORQUE = math.nan

    failing = Failing()
    failing.run(0.02)
    assert failing.steps == 10 and "Exception when adding torque to joint 'hinge'" in caplog.text
    with pytest.raises(ars.app.exc.JointError):
        failing.sim.get_joint("hinge").joint.add_torque(math.nan)


def test_importing_ars_leaves_numpy_and_typing_until_they_are_needed():
    import subprocess
    import sys

    code = (
        "import sys, ars, ars.app, ars.utils.mathematical\n"
        "assert 'numpy' not in sys.modules, 'numpy imported early'\n"
        "assert 'typing' not in sys.modules, 'typing imported early'\n"
        "assert ars.sweep.__name__ == 'sweep' and 'numpy' in sys.modules\n"
    )
    subprocess.run([sys.executable, "-c", code], check=True)


def test_a_handler_gone_during_a_send_is_not_called():
    called = []

    class Handler:
        def __init__(self, name):
            self.name = name

        def on_signal(self):
            called.append(self.name)
            handlers.pop("second", None)  # the second handler goes away

    handlers = {"first": Handler("first"), "second": Handler("second")}
    for handler in handlers.values():
        dispatcher.connect(handler.on_signal, "a test signal")
    del handler  # (the loop's variable would keep the second alive)
    dispatcher.send("a test signal")
    assert called == ["first"]
    dispatcher.send("a test signal")
    assert called == ["first", "first"]


def test_a_step_finds_its_handlers_once_not_at_every_step(monkeypatch):
    from ars import dispatch

    found = []
    direct_calls = dispatch._direct_calls

    def counted(signal, sender):
        found.append(signal)
        return direct_calls(signal, sender)

    monkeypatch.setattr(dispatch, "_direct_calls", counted)
    # Handlers that take the sender are sent the signal, those that take nothing are
    # called directly: either way the step finds out which once.
    for program_class in (Pendulum, Counting):
        program = program_class()
        found.clear()
        program.run(0.1)
        assert program.steps == 50 and found == [signals.SIM_PRE_STEP]
