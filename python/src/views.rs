//! Named access: `sim.body("arm")` and `sim.joint("r1")`. Every attribute is read when
//! asked and returned as a copy (numpy arrays the caller owns), never a live view.

use ars_core::nalgebra::{Point3, Vector3};
use ars_core::{ObjectId, Simulation};
use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;

use crate::simulation::{PySimulation, Vec3};

/// A set-point: a constant, or `(time, value)` breakpoints.
#[derive(FromPyObject)]
pub(crate) enum Setpoint {
    Constant(f64),
    Points(Vec<(f64, f64)>),
}

/// An object of a simulation, by name.
#[pyclass(module = "ars", frozen)]
pub struct Body {
    sim: Py<PySimulation>,
    name: String,
}

impl Body {
    pub(crate) fn new(sim: Py<PySimulation>, name: String) -> Self {
        Body { sim, name }
    }

    fn read<R: Send>(
        &self,
        py: Python<'_>,
        f: impl FnOnce(&mut Simulation, ObjectId) -> ars_core::Result<R> + Send,
    ) -> PyResult<R> {
        let name = self.name.as_str();
        self.sim.get().with(py, |sim| {
            let id = sim.object(name)?.id();
            f(sim, id)
        })
    }
}

fn array3<'py>(py: Python<'py>, v: &Vector3<f64>) -> Bound<'py, PyArray1<f64>> {
    PyArray1::from_slice(py, v.as_slice())
}

#[pymethods]
impl Body {
    /// Its name.
    #[getter]
    fn name(&self) -> &str {
        &self.name
    }

    /// Position of its centre (of mass), m: a new array.
    #[getter]
    fn position<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let p = self.read(py, |sim, id| sim.position(id))?;
        Ok(array3(py, &p.coords))
    }

    /// Rotation matrix (body to world), 3×3: a new array.
    #[getter]
    fn rotation<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let r = self.read(py, |sim, id| sim.rotation(id))?;
        let rows: Vec<Vec<f64>> = (0..3).map(|i| (0..3).map(|j| r[(i, j)]).collect()).collect();
        Ok(PyArray2::from_vec2(py, &rows).expect("3 rows of 3"))
    }

    /// Linear velocity, m/s: a new array.
    #[getter]
    fn linear_velocity<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let v = self.read(py, |sim, id| Ok(sim.body(id)?.linear_velocity()))?;
        Ok(array3(py, &v))
    }

    /// Angular velocity, rad/s: a new array.
    #[getter]
    fn angular_velocity<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let w = self.read(py, |sim, id| Ok(sim.body(id)?.angular_velocity()))?;
        Ok(array3(py, &w))
    }

    /// Mass, kg.
    #[getter]
    fn mass(&self, py: Python<'_>) -> PyResult<f64> {
        self.read(py, |sim, id| Ok(sim.body(id)?.mass()))
    }

    /// Inertia tensor about its centre of mass in its own frame, kg·m²: a new 3×3
    /// array.
    #[getter]
    fn inertia<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let i = self.read(py, |sim, id| Ok(sim.body(id)?.inertia()))?;
        let rows: Vec<Vec<f64>> = (0..3).map(|r| (0..3).map(|c| i[(r, c)]).collect()).collect();
        Ok(PyArray2::from_vec2(py, &rows).expect("3 rows of 3"))
    }

    /// Moves it to `position` (m).
    fn set_position(&self, py: Python<'_>, position: Vec3) -> PyResult<()> {
        self.read(py, |sim, id| sim.set_position(id, Point3::from(position)))
    }

    /// Sets its linear velocity (m/s).
    fn set_linear_velocity(&self, py: Python<'_>, velocity: Vec3) -> PyResult<()> {
        self.read(py, |sim, id| sim.body_mut(id)?.set_linear_velocity(Vector3::from(velocity)))
    }

    /// Sets its angular velocity (rad/s).
    fn set_angular_velocity(&self, py: Python<'_>, velocity: Vec3) -> PyResult<()> {
        self.read(py, |sim, id| sim.body_mut(id)?.set_angular_velocity(Vector3::from(velocity)))
    }

    /// Adds a force (N, world frame) at its centre of mass for the next step.
    fn add_force(&self, py: Python<'_>, force: Vec3) -> PyResult<()> {
        self.read(py, |sim, id| sim.body_mut(id)?.add_force(Vector3::from(force)))
    }

    /// Turns it by `angle` (rad) about the world `axis`, about its centre.
    fn rotate(&self, py: Python<'_>, axis: Vec3, angle: f64) -> PyResult<()> {
        self.read(py, |sim, id| sim.rotate(id, Vector3::from(axis), angle))
    }

    /// Moves it by `offset` (m).
    fn offset_by_position(&self, py: Python<'_>, offset: Vec3) -> PyResult<()> {
        self.read(py, |sim, id| sim.offset_by_position(id, Vector3::from(offset)))
    }

    /// The colour the viewer draws it with (RGB, each in [0, 1]).
    fn set_color(&self, py: Python<'_>, color: [f32; 3]) -> PyResult<()> {
        self.read(py, |sim, id| sim.set_color(id, color))
    }

    fn __repr__(&self) -> String {
        format!("<ars.Body {:?}>", self.name)
    }
}

/// A joint of a simulation, by name.
#[pyclass(module = "ars", frozen)]
pub struct Joint {
    sim: Py<PySimulation>,
    name: String,
}

impl Joint {
    pub(crate) fn new(sim: Py<PySimulation>, name: String) -> Self {
        Joint { sim, name }
    }

    fn act<R: Send>(
        &self,
        py: Python<'_>,
        f: impl FnOnce(&mut Simulation, ars_core::JointId) -> ars_core::Result<R> + Send,
    ) -> PyResult<R> {
        let name = self.name.as_str();
        self.sim.get().with(py, |sim| {
            let id = sim.joint(name)?.id();
            f(sim, id)
        })
    }
}

#[pymethods]
impl Joint {
    /// Its name.
    #[getter]
    fn name(&self) -> &str {
        &self.name
    }

    /// Angle (rad) of a rotary joint, or position (m) of a slider: its first degree of
    /// freedom.
    #[getter]
    fn angle(&self, py: Python<'_>) -> PyResult<f64> {
        self.act(py, |sim, id| Ok(sim.joint_state(id)?.position))
    }

    /// Same as `angle` (the word for sliders).
    #[getter]
    fn position(&self, py: Python<'_>) -> PyResult<f64> {
        self.angle(py)
    }

    /// Rate of `angle`, rad/s (or m/s).
    #[getter]
    fn rate(&self, py: Python<'_>) -> PyResult<f64> {
        self.act(py, |sim, id| sim.joint_rate(id))
    }

    /// Adds a torque (N·m) about a rotary joint's axis for the next step.
    fn add_torque(&self, py: Python<'_>, torque: f64) -> PyResult<()> {
        self.act(py, |sim, id| sim.joint_mut(id)?.add_torque(torque))
    }

    /// Adds a force (N) along a slider's axis for the next step.
    fn add_force(&self, py: Python<'_>, force: f64) -> PyResult<()> {
        self.act(py, |sim, id| sim.joint_mut(id)?.add_force(force))
    }

    /// Drives the joint at `speed` (rad/s or m/s) with at most `max_force` (N·m or N);
    /// `max_force = 0` turns the motor off.
    fn set_speed(&self, py: Python<'_>, speed: f64, max_force: f64) -> PyResult<()> {
        self.act(py, |sim, id| sim.joint_mut(id)?.set_speed(speed, max_force))
    }

    /// Sets one of ODE's parameters of its first axis, by name: `"lo_stop"`,
    /// `"hi_stop"`, `"velocity"`, `"max_force"`, `"fudge_factor"`, `"bounce"`, `"cfm"`,
    /// `"stop_erp"`, `"stop_cfm"`.
    fn set_param(&self, py: Python<'_>, name: &str, value: f64) -> PyResult<()> {
        use ars_core::JointParam as P;
        let param = match name {
            "lo_stop" => P::LoStop,
            "hi_stop" => P::HiStop,
            "velocity" => P::Velocity,
            "max_force" => P::MaxForce,
            "fudge_factor" => P::FudgeFactor,
            "bounce" => P::Bounce,
            "cfm" => P::Cfm,
            "stop_erp" => P::StopErp,
            "stop_cfm" => P::StopCfm,
            other => {
                return Err(crate::errors::raise(py, "InputError", format!("no joint parameter {other:?}")));
            }
        };
        self.act(py, |sim, id| sim.joint_mut(id)?.set_param(param, value))
    }

    /// Viscous friction: `-coefficient · rate` every step (N·m·s/rad or N·s/m; 0: off).
    fn set_viscous_friction(&self, py: Python<'_>, coefficient: f64) -> PyResult<()> {
        self.act(py, |sim, id| sim.joint_mut(id)?.set_viscous_friction(coefficient))
    }

    /// Drives the joint in native code every step: `kind` is `"torque"` (the torque
    /// follows `setpoint`), `"position"` (a PD servo to `setpoint` with gains `kp`,
    /// `kd`) or `"velocity"` (a P servo to `setpoint` with gain `kp`). `setpoint` is a
    /// number or `(time, value)` breakpoints, linear between them. `None` removes it.
    #[pyo3(signature = (kind, setpoint=None, kp=0.0, kd=0.0))]
    fn set_controller(
        &self,
        py: Python<'_>,
        kind: Option<&str>,
        setpoint: Option<Setpoint>,
        kp: f64,
        kd: f64,
    ) -> PyResult<()> {
        use ars_core::{PositionServo, Profile, TorqueMotor, VelocityServo};
        let profile = |s: Option<Setpoint>| -> ars_core::Result<Profile> {
            match s {
                None => Err(ars_core::Error::OutOfRange { what: "controller", detail: "needs a setpoint".into() }),
                Some(Setpoint::Constant(v)) => Profile::constant(v),
                Some(Setpoint::Points(p)) => Profile::new(p),
            }
        };
        let kind = kind.map(str::to_string);
        self.act(py, move |sim, id| {
            let mut joint = sim.joint_mut(id)?;
            match kind.as_deref() {
                None => {
                    joint.clear_controller();
                    Ok(())
                }
                Some("torque") => joint.set_controller(TorqueMotor { torque: profile(setpoint)? }),
                Some("position") => joint.set_controller(PositionServo::pd(profile(setpoint)?, kp, kd)),
                Some("velocity") => joint.set_controller(VelocityServo { setpoint: profile(setpoint)?, gain: kp }),
                Some(other) => Err(ars_core::Error::OutOfRange {
                    what: "controller",
                    detail: format!("kind {other:?}: \"torque\", \"position\" or \"velocity\""),
                }),
            }
        })
    }

    /// Stops (limits) of its first degree of freedom (±inf: none).
    fn set_limits(&self, py: Python<'_>, low: f64, high: f64) -> PyResult<()> {
        self.act(py, |sim, id| sim.joint_mut(id)?.set_limits(low, high))
    }

    fn __repr__(&self) -> String {
        format!("<ars.Joint {:?}>", self.name)
    }
}
