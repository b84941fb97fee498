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
        self.box = self.sim.add_box((0.2, 0.2, 0.2), (0, 2, 0), mass=1000.0)
        self.ball = self.sim.add_sphere(0.1, (1, 2, 0), mass=1.0)
        self.sim.add_fixed_joint("anchor", self.sim.get_object(self.box), None)
        self.sim.add_rotary_joint(
            "hinge", self.sim.get_object(self.ball), self.sim.get_object(self.box), None, cts.Z_AXIS
        )

    def on_pre_step(self, sender):
        self.heard.append(sender)
        self.angle.on_change(self.sim.sim_time)

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


def test_a_programs_handlers_hear_its_own_simulation_only():
    first = Pendulum()
    first.run(0.1)
    second = Pendulum()
    second.run(0.1)
    first.run(0.1)
    assert len(second.heard) == 50 and all(s is second.sim for s in second.heard)
    assert len(first.heard) == 100 and all(s is first.sim for s in first.heard)


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
