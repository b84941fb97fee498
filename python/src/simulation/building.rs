//! `ars.Simulation`'s methods that build a scene: bodies, floors, meshes, joints,
//! their removal, rays and contact surfaces.

use crate::errors::count;
use ars_core::nalgebra::{Point3, Vector3};
use ars_core::{GroupJoint, JointType, Shape};
use pyo3::prelude::*;

use super::{Int, PySimulation, RayHit, Vec3, name_object};
use crate::errors::Checked;

/// A joint of a group from Python: name, kind, anchor, axis, reference.
type GroupJointArgs = (String, String, [f64; 3], [f64; 3], f64);

#[pymethods]
impl PySimulation {
    /// A sphere of `radius` (m) centred at `center`, of total `mass` (kg) or
    /// `density` (kg/m³) (neither: ODE's default body, 1 kg with unit inertia); returns
    /// its name.
    #[pyo3(signature = (radius, center=Checked([0.0; 3]), mass=None, density=None, *, name=None))]
    fn add_sphere(
        &self,
        py: Python<'_>,
        radius: f64,
        center: Vec3,
        mass: Option<f64>,
        density: Option<f64>,
        name: Option<String>,
    ) -> PyResult<String> {
        self.add_body(py, Shape::Sphere { radius }, center, mass, density, name)
    }

    /// A box of full edge lengths `size` (m); see `add_sphere`.
    #[pyo3(signature = (size, center=Checked([0.0; 3]), mass=None, density=None, *, name=None))]
    fn add_box(
        &self,
        py: Python<'_>,
        size: Vec3,
        center: Vec3,
        mass: Option<f64>,
        density: Option<f64>,
        name: Option<String>,
    ) -> PyResult<String> {
        self.add_body(py, Shape::Box { edges: Vector3::from(size) }, center, mass, density, name)
    }

    /// A cylinder of `length` and `radius` (m) along its local Z; see `add_sphere`.
    #[pyo3(signature = (length, radius, center=Checked([0.0; 3]), mass=None, density=None, *, name=None))]
    fn add_cylinder(
        &self,
        py: Python<'_>,
        length: f64,
        radius: f64,
        center: Vec3,
        mass: Option<f64>,
        density: Option<f64>,
        name: Option<String>,
    ) -> PyResult<String> {
        self.add_body(py, Shape::Cylinder { radius, length }, center, mass, density, name)
    }

    /// A capsule: a cylinder of `length` (without its caps) and `radius` (m) along its
    /// local Z, capped by hemispheres; see `add_sphere`.
    #[pyo3(signature = (length, radius, center=Checked([0.0; 3]), mass=None, density=None, *, name=None))]
    fn add_capsule(
        &self,
        py: Python<'_>,
        length: f64,
        radius: f64,
        center: Vec3,
        mass: Option<f64>,
        density: Option<f64>,
        name: Option<String>,
    ) -> PyResult<String> {
        self.add_body(py, Shape::Capsule { radius, length }, center, mass, density, name)
    }

    /// A cone of `height` and base `radius` (m) along its local Z, `center` its centre
    /// of mass; see `add_sphere`.
    #[pyo3(signature = (height, radius, center=Checked([0.0; 3]), mass=None, density=None, *, name=None))]
    fn add_cone(
        &self,
        py: Python<'_>,
        height: f64,
        radius: f64,
        center: Vec3,
        mass: Option<f64>,
        density: Option<f64>,
        name: Option<String>,
    ) -> PyResult<String> {
        self.add_body(py, Shape::Cone { radius, height }, center, mass, density, name)
    }

    /// A static plane `normal · x = dist` (the floor); returns its name.
    #[pyo3(signature = (normal=Checked([0.0, 1.0, 0.0]), dist=0.0, *, name=None))]
    fn add_floor(&self, py: Python<'_>, normal: Vec3, dist: f64, name: Option<String>) -> PyResult<String> {
        self.with(py, move |sim| {
            let id = sim.scene_mut().add_floor_plane(Vector3::from(normal), dist)?;
            name_object(sim, id, name)
        })
    }

    /// A static triangle mesh (`vertices`: points; `faces`: index triples) at `center`.
    #[pyo3(signature = (vertices, faces, center=Checked([0.0; 3]), *, name=None))]
    fn add_trimesh(
        &self,
        py: Python<'_>,
        vertices: Vec<Vec3>,
        faces: Checked<Vec<[i64; 3]>>,
        center: Vec3,
        name: Option<String>,
    ) -> PyResult<String> {
        let index = |i| count::<u32>(py, "a face's vertex index", i);
        let faces =
            faces.0.into_iter().map(|[a, b, c]| Ok([index(a)?, index(b)?, index(c)?])).collect::<PyResult<Vec<_>>>()?;
        self.with(py, move |sim| {
            let shape = Shape::TriMesh { vertices: vertices.into_iter().map(Point3::from).collect(), triangles: faces };
            let [x, y, z] = center.0;
            let pose = ars_core::nalgebra::Isometry3::translation(x, y, z);
            let id = sim.scene_mut().add_static(shape, pose)?;
            name_object(sim, id, name)
        })
    }

    /// A rotary joint (hinge) named `name` between objects `obj1` and `obj2` (`None`:
    /// the world) about the world `axis` through `anchor` (default: `obj2`'s position,
    /// or `obj1`'s when joined to the world).
    #[pyo3(signature = (name, obj1, obj2, anchor=None, axis=Checked([0.0, 0.0, 1.0])))]
    fn add_rotary_joint(
        &self,
        py: Python<'_>,
        name: &str,
        obj1: &str,
        obj2: Option<&str>,
        anchor: Option<Vec3>,
        axis: Vec3,
    ) -> PyResult<String> {
        self.with(py, |sim| {
            let (a, b) = (Self::object_id(sim, obj1)?, Self::end(sim, obj2)?);
            let id = sim.scene_mut().add_hinge_joint(name, a, b, anchor.map(Point3::from), Vector3::from(axis))?;
            Ok(sim.scene().joint(id)?.name().to_string())
        })
    }

    /// A slider along the world `axis`.
    fn add_slider_joint(
        &self,
        py: Python<'_>,
        name: &str,
        obj1: &str,
        obj2: Option<&str>,
        axis: Vec3,
    ) -> PyResult<String> {
        self.with(py, |sim| {
            let (a, b) = (Self::object_id(sim, obj1)?, Self::end(sim, obj2)?);
            let id = sim.scene_mut().add_slider_joint(name, a, b, Vector3::from(axis))?;
            Ok(sim.scene().joint(id)?.name().to_string())
        })
    }

    /// A ball-and-socket joint at `anchor` (default: `obj2`'s position).
    #[pyo3(signature = (name, obj1, obj2, anchor=None))]
    fn add_ball_socket_joint(
        &self,
        py: Python<'_>,
        name: &str,
        obj1: &str,
        obj2: Option<&str>,
        anchor: Option<Vec3>,
    ) -> PyResult<String> {
        self.with(py, |sim| {
            let (a, b) = (Self::object_id(sim, obj1)?, Self::end(sim, obj2)?);
            let id = sim.scene_mut().add_ball_joint(name, a, b, anchor.map(Point3::from))?;
            Ok(sim.scene().joint(id)?.name().to_string())
        })
    }

    /// A universal joint at `anchor` with perpendicular world axes `axis1` (on `obj1`)
    /// and `axis2` (on `obj2`).
    fn add_universal_joint(
        &self,
        py: Python<'_>,
        name: &str,
        obj1: &str,
        obj2: Option<&str>,
        anchor: Vec3,
        axis1: Vec3,
        axis2: Vec3,
    ) -> PyResult<String> {
        self.with(py, |sim| {
            let (a, b) = (Self::object_id(sim, obj1)?, Self::end(sim, obj2)?);
            let id = sim.scene_mut().add_universal_joint(
                name,
                a,
                b,
                Point3::from(anchor),
                Vector3::from(axis1),
                Vector3::from(axis2),
            )?;
            Ok(sim.scene().joint(id)?.name().to_string())
        })
    }

    /// Several joints between `obj1` and `obj2` (or the world) as one joint group, as
    /// MuJoCo moves a body with several joints: `joints` lists `(name, kind, anchor,
    /// axis, reference)`, `kind` `"hinge"` or `"slider"`, slides first (world frame,
    /// where the objects are now, where each joint reads its `reference`). Hinges
    /// through one point about perpendicular axes; slides along perpendicular axes, of
    /// an object joined to the world, with at most one hinge about their plane's normal.
    /// Returns the joints' names, in order.
    fn add_joint_group(
        &self,
        py: Python<'_>,
        obj1: &str,
        obj2: Option<&str>,
        joints: Checked<Vec<GroupJointArgs>>,
    ) -> PyResult<Vec<String>> {
        self.with(py, |sim| {
            let (a, b) = (Self::object_id(sim, obj1)?, Self::end(sim, obj2)?);
            let joints = joints
                .0
                .into_iter()
                .map(|(name, kind, anchor, axis, reference)| {
                    let kind = match kind.as_str() {
                        "hinge" => JointType::Hinge,
                        "slider" => JointType::Slider,
                        other => {
                            return Err(ars_core::Error::Invalid {
                                what: "a joint group",
                                problem: format!("holds \"hinge\" and \"slider\" joints, not {other:?}"),
                            });
                        }
                    };
                    Ok(GroupJoint { name, kind, anchor: Point3::from(anchor), axis: Vector3::from(axis), reference })
                })
                .collect::<ars_core::Result<Vec<_>>>()?;
            let ids = sim.scene_mut().add_joint_group(a, b, &joints)?;
            ids.into_iter().map(|id| Ok(sim.scene().joint(id)?.name().to_string())).collect()
        })
    }

    /// A fixed joint: locks `obj1`'s pose relative to `obj2` (or the world) as it is.
    fn add_fixed_joint(&self, py: Python<'_>, name: &str, obj1: &str, obj2: Option<&str>) -> PyResult<String> {
        self.with(py, |sim| {
            let (a, b) = (Self::object_id(sim, obj1)?, Self::end(sim, obj2)?);
            let id = sim.scene_mut().add_fixed_joint(name, a, b)?;
            Ok(sim.scene().joint(id)?.name().to_string())
        })
    }

    /// The first thing a ray from `origin` along `direction` meets within `length`
    /// (m): `(distance, point)`, or `None`.
    fn cast_ray(&self, py: Python<'_>, origin: Vec3, direction: Vec3, length: f64) -> PyResult<Option<RayHit>> {
        self.with(py, move |sim| {
            let direction = Vector3::from(direction);
            let norm = direction.norm();
            let direction = if norm > 0.0 { direction / norm } else { direction };
            let ray = ars_core::world::raycast::Ray { origin: Point3::from(origin), direction };
            let hit = sim.scene().world().cast_ray(ray, length, None)?;
            Ok(hit.map(|h| (h.distance, (h.position.x, h.position.y, h.position.z))))
        })
    }

    /// A piston: slides along and turns about the world `axis` through `anchor`.
    #[pyo3(signature = (name, obj1, obj2, anchor, axis))]
    fn add_piston_joint(
        &self,
        py: Python<'_>,
        name: &str,
        obj1: &str,
        obj2: Option<&str>,
        anchor: Vec3,
        axis: Vec3,
    ) -> PyResult<String> {
        self.with(py, |sim| {
            let (a, b) = (Self::object_id(sim, obj1)?, Self::end(sim, obj2)?);
            let id = sim.scene_mut().add_piston_joint(name, a, b, Point3::from(anchor), Vector3::from(axis))?;
            Ok(sim.scene().joint(id)?.name().to_string())
        })
    }

    /// Removes the object `name` with its body and geoms; the joints attached to it go
    /// too, and the sensors reading it stop sampling (`Sensor.detached`). Its name can
    /// be used again.
    fn remove_object(&self, py: Python<'_>, name: &str) -> PyResult<()> {
        self.with(py, |sim| {
            let id = Self::object_id(sim, name)?;
            sim.remove_object(id)
        })
    }

    /// Removes the joint `name`; the sensors reading it stop sampling.
    fn remove_joint(&self, py: Python<'_>, name: &str) -> PyResult<()> {
        self.with(py, |sim| {
            let id = sim.scene().joint(name)?.id();
            sim.remove_joint(id)
        })
    }

    /// Sets the contact surface: of every pair of objects (`between=None`, the world's
    /// default), or of the contacts between the two objects `between=("a", "b")` only.
    /// The fields not given take the ARS defaults (not their current values):
    /// `mu=500` (N per contact point and direction, ODE's box friction; with
    /// `approx1=True` a Coulomb coefficient; `math.inf`: never slips), `mu2` (another
    /// limit for the second direction), `bounce=0.2` above `bounce_velocity=0` m/s,
    /// `soft_erp`/`soft_cfm` (soft contacts; else the world's), `max_contacts=150`
    /// points per pair.
    #[pyo3(signature = (between=None, *, mu=500.0, mu2=None, bounce=0.2, bounce_velocity=0.0, soft_erp=None,
                        soft_cfm=None, approx1=false, max_contacts=Checked(150)))]
    fn set_contact_surface(
        &self,
        py: Python<'_>,
        between: Option<Checked<(String, String)>>,
        mu: f64,
        mu2: Option<f64>,
        bounce: f64,
        bounce_velocity: f64,
        soft_erp: Option<f64>,
        soft_cfm: Option<f64>,
        approx1: bool,
        max_contacts: Int,
    ) -> PyResult<()> {
        let max_contacts: usize = count(py, "max_contacts", max_contacts)?;
        let surface = ars_core::ContactSurface {
            mu,
            mu2,
            bounce: Some((bounce, bounce_velocity)),
            soft_erp,
            soft_cfm,
            approx1,
            rolling: None,
            max_contacts,
        };
        self.with(py, move |sim| match between {
            None => sim.scene_mut().world_mut().set_default_surface(surface),
            Some(Checked((a, b))) => {
                let (a, b) = (Self::object_id(sim, &a)?, Self::object_id(sim, &b)?);
                sim.scene_mut().set_contact_surface(a, b, surface)
            }
        })
    }

    /// The contact surface of every pair (`between=None`) or of the pair `between`, as
    /// a dict of the keywords of `set_contact_surface`.
    #[pyo3(signature = (between=None))]
    fn contact_surface<'py>(
        &self,
        py: Python<'py>,
        between: Option<Checked<(String, String)>>,
    ) -> PyResult<Bound<'py, pyo3::types::PyDict>> {
        let s = self.with(py, move |sim| match between {
            None => Ok(sim.scene().world().default_surface()),
            Some(Checked((a, b))) => {
                let (a, b) = (Self::object_id(sim, &a)?, Self::object_id(sim, &b)?);
                sim.scene().contact_surface(a, b)
            }
        })?;
        let dict = pyo3::types::PyDict::new(py);
        let (bounce, bounce_velocity) = s.bounce.unwrap_or((0.0, 0.0));
        dict.set_item("mu", s.mu)?;
        dict.set_item("mu2", s.mu2)?;
        dict.set_item("bounce", bounce)?;
        dict.set_item("bounce_velocity", bounce_velocity)?;
        dict.set_item("soft_erp", s.soft_erp)?;
        dict.set_item("soft_cfm", s.soft_cfm)?;
        dict.set_item("approx1", s.approx1)?;
        dict.set_item("max_contacts", s.max_contacts)?;
        Ok(dict)
    }

    /// Gives the contacts between objects `a` and `b` the default surface again.
    fn clear_contact_surface(&self, py: Python<'_>, a: &str, b: &str) -> PyResult<()> {
        self.with(py, |sim| {
            let (a, b) = (Self::object_id(sim, a)?, Self::object_id(sim, b)?);
            sim.scene_mut().clear_contact_surface(a, b)
        })
    }

    /// Objects `a` and `b` never touch (MJCF's `<contact><exclude>`).
    fn exclude_contacts(&self, py: Python<'_>, a: &str, b: &str) -> PyResult<()> {
        self.with(py, |sim| {
            let (a, b) = (Self::object_id(sim, a)?, Self::object_id(sim, b)?);
            sim.scene_mut().exclude_contacts(a, b)
        })
    }

    /// Objects `a` and `b` touch again.
    fn include_contacts(&self, py: Python<'_>, a: &str, b: &str) -> PyResult<()> {
        self.with(py, |sim| {
            let (a, b) = (Self::object_id(sim, a)?, Self::object_id(sim, b)?);
            sim.scene_mut().include_contacts(a, b)
        })
    }

    /// The pairs of objects that never touch, by name.
    fn excluded_contacts(&self, py: Python<'_>) -> PyResult<Vec<(String, String)>> {
        self.with(py, |sim| {
            let name = |id| sim.scene().object(id).map(|o| o.name().to_string());
            sim.scene().excluded_contacts().into_iter().map(|(a, b)| Ok((name(a)?, name(b)?))).collect()
        })
    }
}
