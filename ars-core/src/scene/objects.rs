//! Objects of a simulation: bodies with their shape, static shapes and floors.

use nalgebra::{Isometry3, Matrix3, Point3, Rotation3, Vector3};

use super::Scene;
use crate::body::{BodyBuilder, BodyMut, BodyRef, Mass, MassSpec};
use crate::convert::rotation_about_axis;
use crate::error::{Error, Result};
use crate::geom::GeomBuilder;
use crate::handle::{BodyHandle, GeomHandle, ObjectId};
use crate::shape::Shape;
use crate::validate;

/// An RGB colour, each channel in [0, 1] (used by the viewer).
pub type Color = [f32; 3];

pub(crate) struct ObjectData {
    pub(crate) name: String,
    pub(crate) shape: Shape,
    pub(crate) body: Option<BodyHandle>,
    pub(crate) geom: Option<GeomHandle>,
    /// More geoms of the object (a robot link's other collision elements).
    pub(crate) extra_geoms: Vec<GeomHandle>,
    pub(crate) color: Option<Color>,
    /// What the viewer draws instead of the geoms, when not empty.
    pub(crate) visuals: Vec<Visual>,
}

/// A shape the viewer draws for an object, apart from what collides (a robot link's
/// `<visual>`): where it is relative to the object's pose, in its own colour or the
/// object's.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Visual {
    /// The shape drawn.
    pub shape: Shape,
    /// Its pose relative to the object's.
    pub offset: Isometry3<f64>,
    /// Its colour (`None`: the object's).
    pub color: Option<Color>,
}

impl Scene {
    fn register(&mut self, shape: Shape, body: Option<BodyHandle>, geom: Option<GeomHandle>) -> Result<ObjectId> {
        let base = match shape {
            Shape::Plane { .. } => "floor",
            _ => shape.kind_name(),
        };
        self.register_as(base, shape, body, geom)
    }

    /// Adds a dynamic body of `shape` centred at `center` (its centre of mass), with
    /// its mass given as a total or a density. ODE calls: create the body, set its mass
    /// and position, create the geom and attach it.
    pub fn add_body(&mut self, shape: Shape, center: impl Into<Point3<f64>>, mass: Mass) -> Result<ObjectId> {
        self.add_body_with_mass(shape.clone(), center, MassSpec::solid(shape, mass))
    }

    /// Adds a dynamic body of `shape` centred at `center`, with any mass distribution
    /// (a custom mass and inertia, say: ODE's default body is 1 kg with the identity
    /// inertia).
    pub fn add_body_with_mass(
        &mut self,
        shape: Shape,
        center: impl Into<Point3<f64>>,
        spec: MassSpec,
    ) -> Result<ObjectId> {
        let geom = GeomBuilder::new(shape.clone());
        let center = center.into();
        // Check the geom before creating the body, so that bad input leaves nothing.
        spec.to_ode()?;
        validate::point("object center", &center)?;
        let body = self.world.insert_body(BodyBuilder::new().mass(spec).position(center))?;
        match self.world.insert_geom(self.space, geom.attached_to(body)) {
            Ok(g) => self.register(shape, Some(body), Some(g)),
            Err(e) => {
                self.world.remove_body(body)?;
                Err(e)
            }
        }
    }

    /// Adds a sphere of `radius` (m) centred at `center`.
    pub fn add_sphere(&mut self, radius: f64, center: impl Into<Point3<f64>>, mass: Mass) -> Result<ObjectId> {
        self.add_body(Shape::Sphere { radius }, center, mass)
    }

    /// Adds a box with full edge lengths `edges` (m, not half-extents) centred at `center`.
    pub fn add_box(
        &mut self,
        edges: impl Into<Vector3<f64>>,
        center: impl Into<Point3<f64>>,
        mass: Mass,
    ) -> Result<ObjectId> {
        self.add_body(Shape::Box { edges: edges.into() }, center, mass)
    }

    /// Adds a cylinder along local Z of `radius` and `length` (m) centred at `center`.
    pub fn add_cylinder(
        &mut self,
        radius: f64,
        length: f64,
        center: impl Into<Point3<f64>>,
        mass: Mass,
    ) -> Result<ObjectId> {
        self.add_body(Shape::Cylinder { radius, length }, center, mass)
    }

    /// Adds a capsule along local Z of `radius` and `length` (without the caps)
    /// centred at `center`.
    pub fn add_capsule(
        &mut self,
        radius: f64,
        length: f64,
        center: impl Into<Point3<f64>>,
        mass: Mass,
    ) -> Result<ObjectId> {
        self.add_body(Shape::Capsule { radius, length }, center, mass)
    }

    /// Adds a solid cone along local +Z of base `radius` and `height` with its centre
    /// of mass at `center`. It collides as a triangle mesh of
    /// [`CONE_SEGMENTS`](crate::CONE_SEGMENTS) facets (ODE has no cone).
    pub fn add_cone(
        &mut self,
        radius: f64,
        height: f64,
        center: impl Into<Point3<f64>>,
        mass: Mass,
    ) -> Result<ObjectId> {
        self.add_body(Shape::Cone { radius, height }, center, mass)
    }

    /// Adds a static (immovable, bodyless) shape at `pose`: it collides, but nothing
    /// moves it (a plane ignores the pose).
    pub fn add_static(&mut self, shape: Shape, pose: Isometry3<f64>) -> Result<ObjectId> {
        let geom = match shape {
            Shape::Plane { .. } => GeomBuilder::new(shape.clone()),
            _ => GeomBuilder::new(shape.clone()).pose(pose),
        };
        let g = self.world.insert_geom(self.space, geom)?;
        self.register(shape, None, Some(g))
    }

    /// Adds the infinite floor plane `normal · x = distance` (named "floor").
    pub fn add_floor_plane(&mut self, normal: Vector3<f64>, distance: f64) -> Result<ObjectId> {
        self.add_static(Shape::Plane { normal, distance }, Isometry3::identity())
    }

    /// Adds a triangle-mesh floor (terrain) translated by `center` (named "floor").
    pub fn add_trimesh_floor(
        &mut self,
        vertices: Vec<Point3<f64>>,
        triangles: Vec<[u32; 3]>,
        center: impl Into<Point3<f64>>,
    ) -> Result<ObjectId> {
        let c = center.into();
        let shape = Shape::TriMesh { vertices, triangles };
        let g = self
            .world
            .insert_geom(self.space, GeomBuilder::new(shape.clone()).pose(Isometry3::translation(c.x, c.y, c.z)))?;
        self.register_as("floor", shape, None, Some(g))
    }

    /// Every object with its data, in slot order (creation order when none was removed).
    pub(crate) fn objects_in_creation_order(&self) -> impl Iterator<Item = (ObjectId, &ObjectData)> + '_ {
        self.objects.iter().map(|(h, d)| (ObjectId(h), d))
    }

    pub(crate) fn object_data(&self, id: ObjectId) -> Result<&ObjectData> {
        self.objects.get(id.0, ObjectId::KIND)
    }

    /// Every object, by name in alphabetical order.
    pub fn objects(&self) -> impl Iterator<Item = (&str, ObjectId)> + '_ {
        self.object_names.iter()
    }

    /// Renames an object; the new name must be free.
    pub fn set_name(&mut self, id: ObjectId, name: &str) -> Result<()> {
        let old = self.object_data(id)?.name.clone();
        if old == name {
            return Ok(());
        }
        self.object_names.insert(name.to_string(), id)?;
        self.object_names.remove(&old);
        self.objects.get_mut(id.0, ObjectId::KIND)?.name = name.to_string();
        Ok(())
    }

    /// Sets the colour the viewer draws an object with (channels in [0, 1]).
    pub fn set_color(&mut self, id: ObjectId, color: Color) -> Result<()> {
        valid_color(color)?;
        self.objects.get_mut(id.0, ObjectId::KIND)?.color = Some(color);
        Ok(())
    }

    /// Sets what the viewer draws for an object instead of its collision shapes (an
    /// empty list: the collision shapes again).
    pub fn set_visuals(&mut self, id: ObjectId, visuals: Vec<Visual>) -> Result<()> {
        for v in &visuals {
            v.shape.validate()?;
            if let Some(c) = v.color {
                valid_color(c)?;
            }
            crate::geom::check_isometry("visual offset", &v.offset)?;
        }
        self.objects.get_mut(id.0, ObjectId::KIND)?.visuals = visuals;
        Ok(())
    }

    fn dynamic_body(&self, id: ObjectId) -> Result<BodyHandle> {
        let data = self.object_data(id)?;
        data.body.ok_or_else(|| static_object(&data.name))
    }

    /// Read access to the body of a dynamic object (pose, velocities, mass, inertia...).
    pub fn body(&self, id: ObjectId) -> Result<BodyRef<'_>> {
        let b = self.dynamic_body(id)?;
        self.world.body(b)
    }

    /// Write access to the body of a dynamic object (velocities, forces...).
    pub fn body_mut(&mut self, id: ObjectId) -> Result<BodyMut<'_>> {
        let b = self.dynamic_body(id)?;
        self.world.body_mut(b)
    }

    /// Every dynamic object, in creation-slot order.
    pub fn bodies(&self) -> impl Iterator<Item = (ObjectId, BodyHandle)> + '_ {
        self.objects.iter().filter_map(|(h, o)| o.body.map(|b| (ObjectId(h), b)))
    }

    /// World pose of any object (static ones included; a plane's is the identity).
    pub fn pose(&self, id: ObjectId) -> Result<Isometry3<f64>> {
        let data = self.object_data(id)?;
        match (data.body, data.geom) {
            (Some(b), _) => Ok(self.world.body(b)?.pose()),
            (None, Some(g)) => Ok(self.world.geom(g)?.pose()),
            (None, None) => Ok(Isometry3::identity()),
        }
    }

    /// World position of an object.
    pub fn position(&self, id: ObjectId) -> Result<Point3<f64>> {
        let data = self.object_data(id)?;
        match data.body {
            // What `pose` would translate by, without reading the orientation.
            Some(b) => Ok(self.world.body(b)?.position()),
            None => Ok(Point3::from(self.pose(id)?.translation.vector)),
        }
    }

    /// Rotation matrix of an object (body to world).
    pub fn rotation(&self, id: ObjectId) -> Result<Rotation3<f64>> {
        let data = self.object_data(id)?;
        match data.body {
            Some(b) => Ok(self.world.body(b)?.rotation()),
            None => Ok(self.pose(id)?.rotation.to_rotation_matrix()),
        }
    }

    /// Moves an object to `position`.
    pub fn set_position(&mut self, id: ObjectId, position: impl Into<Point3<f64>>) -> Result<()> {
        let p = position.into();
        let data = self.object_data(id)?;
        match (data.body, data.geom, &data.shape) {
            (_, _, Shape::Plane { .. }) => Err(Error::WrongGeomKind { operation: "moving", kind: "plane" }),
            (Some(b), _, _) => self.world.body_mut(b)?.set_position(p),
            (None, Some(g), _) => self.world.geom_mut(g)?.set_position(p),
            (None, None, _) => Ok(()),
        }
    }

    /// Sets the rotation matrix of an object.
    pub fn set_rotation(&mut self, id: ObjectId, rotation: Rotation3<f64>) -> Result<()> {
        let data = self.object_data(id)?;
        match (data.body, data.geom, &data.shape) {
            (_, _, Shape::Plane { .. }) => Err(Error::WrongGeomKind { operation: "rotating", kind: "plane" }),
            (Some(b), _, _) => self.world.body_mut(b)?.set_rotation(rotation),
            (None, Some(g), _) => self.world.geom_mut(g)?.set_rotation(rotation),
            (None, None, _) => Ok(()),
        }
    }

    /// Sets position and orientation of an object.
    pub fn set_pose(&mut self, id: ObjectId, pose: Isometry3<f64>) -> Result<()> {
        validate::quaternion("object pose", &pose.rotation)?;
        self.set_position(id, Point3::from(pose.translation.vector))?;
        self.set_rotation(id, pose.rotation.to_rotation_matrix())
    }

    /// Rotates an object by `angle` (rad) about the world axis `axis` through its own
    /// origin: `R ← R(axis, angle) · R` (the original's `rotate`). `axis` is normalised.
    /// Rotate bodies before attaching joints to them: joints keep the relative pose
    /// they were created with.
    pub fn rotate(&mut self, id: ObjectId, axis: impl Into<Vector3<f64>>, angle: f64) -> Result<()> {
        let axis = validate::direction("rotation axis", &axis.into())?;
        let angle = validate::finite("rotation angle", angle)?;
        let unit = if (axis.norm_squared() - 1.0).abs() < 1e-15 { axis } else { axis.normalize() };
        let turn = rotation_about_axis(&unit, angle);
        let current = self.rotation(id)?;
        self.set_rotation(id, Rotation3::from_matrix_unchecked(multiply(turn.matrix(), current.matrix())))
    }

    /// Moves an object by `offset` (the original's `offset_by_position`).
    pub fn offset_by_position(&mut self, id: ObjectId, offset: impl Into<Vector3<f64>>) -> Result<()> {
        let offset = validate::vector("offset", &offset.into())?;
        let p = self.position(id)?;
        self.set_position(id, Point3::new(p.x + offset.x, p.y + offset.y, p.z + offset.z))
    }

    /// Moves an object by the position of another (the original's `offset_by_object`).
    pub fn offset_by_object(&mut self, id: ObjectId, other: ObjectId) -> Result<()> {
        let by = self.position(other)?.coords;
        self.offset_by_position(id, by)
    }

    /// Removes an object with its body and geom (its joints and the sensors reading
    /// it are the simulation's business: [`Simulation::remove_object`](crate::Simulation::remove_object)).
    /// Removes an object and its joints (the sensors are the simulation's business).
    pub(crate) fn remove_object_with_joints(&mut self, id: ObjectId) -> Result<()> {
        for joint in self.joints_of_object(id) {
            // A joint of a group went with an earlier one of its group.
            if self.joint_data(joint).is_ok() {
                self.remove_joint(joint)?;
            }
        }
        self.remove_object(id)
    }

    pub(crate) fn remove_object(&mut self, id: ObjectId) -> Result<()> {
        let data = self.objects.remove(id.0, ObjectId::KIND)?;
        self.object_names.remove(&data.name);
        self.pair_surfaces.forget(id);
        if data.body.is_none() {
            for g in data.extra_geoms {
                self.world.remove_geom(g)?;
            }
        }
        match (data.body, data.geom) {
            (Some(b), _) => self.world.remove_body(b),
            (None, Some(g)) => self.world.remove_geom(g),
            (None, None) => Ok(()),
        }
    }
}

/// `a · b` with each entry summed left to right (`a[i][0] b[0][j] + a[i][1] b[1][j] +
/// a[i][2] b[2][j]`), the order the C reference scenes use, so results are bit-identical.
pub(crate) fn multiply(a: &Matrix3<f64>, b: &Matrix3<f64>) -> Matrix3<f64> {
    Matrix3::from_fn(|i, j| a[(i, 0)] * b[(0, j)] + a[(i, 1)] * b[(1, j)] + a[(i, 2)] * b[(2, j)])
}

fn valid_color(color: Color) -> Result<()> {
    if !color.iter().all(|c| (0.0..=1.0).contains(c)) {
        return Err(Error::OutOfRange {
            what: "colour channels",
            detail: format!("must be within [0, 1], got {color:?}"),
        });
    }
    Ok(())
}

/// The error for a static object asked for its body.
pub(crate) fn static_object(name: &str) -> Error {
    Error::NoBody { operation: "a velocity, force or mass", object: name.to_string() }
}
