//! Collision geometry: shapes, attachment to bodies, poses, collision bits.

use nalgebra::{Isometry3, Point3, Rotation3, UnitQuaternion, Vector3};
use ode_sys as ffi;

use super::World;
use super::mesh_tree::{MeshTree, TreeMesh};
use crate::convert;
use crate::error::{Error, Result};
use crate::handle::{BodyHandle, GeomHandle, SpaceHandle};
use crate::init::ensure_ode_ready;
use crate::limits;
use crate::mesh_mass::Triangles;
use crate::shape::{Shape, cone_mesh};
use crate::validate;

/// The buffers ODE's trimesh data points into, freed after the geom.
struct TriMeshStorage {
    data: ffi::dTriMeshDataID,
    _vertices: Vec<f64>,
    _indices: Vec<ffi::dTriIndex>,
}

impl Drop for TriMeshStorage {
    fn drop(&mut self) {
        // SAFETY: the data was created by `dGeomTriMeshDataCreate`; its geom is
        // destroyed before this storage is dropped (see `remove_geom` and World's Drop).
        unsafe { ffi::dGeomTriMeshDataDestroy(self.data) };
    }
}

/// The arrays ODE's convex points into (it copies none of them), freed after the
/// geom: points relative to `centre`, a point inside the hull (ODE's convex colliders
/// take the geom's origin as a point inside it, and warn on stdout when a face's
/// plane does not have it behind), planes `(a, b, c, d)` with unit outward normals,
/// and polygons `[3, i0, i1, i2]`, one per triangle of area.
struct ConvexStorage {
    _planes: Vec<f64>,
    _points: Vec<f64>,
    _polygons: Vec<u32>,
}

impl ConvexStorage {
    /// The arrays of a valid hull, and its centre (its centre of volume).
    fn build(vertices: &[Point3<f64>], triangles: &[[u32; 3]]) -> (ConvexStorage, Vector3<f64>) {
        let centre =
            crate::shape::mass_properties(vertices, triangles).map_or_else(Vector3::zeros, |m| m.centre.coords);
        let points: Vec<f64> = vertices.iter().flat_map(|p| (p.coords - centre).data.0[0]).collect();
        let (mut planes, mut polygons) = (Vec::new(), Vec::new());
        for t in triangles {
            let [a, b, c] = t.map(|k| vertices[k as usize].coords - centre);
            let normal = (b - a).cross(&(c - a));
            let length = normal.norm();
            if length.is_nan() || length <= 0.0 {
                continue; // a sliver of no area has no plane; its neighbours bound the hull
            }
            let n = normal / length;
            planes.extend([n.x, n.y, n.z, n.dot(&a)]);
            polygons.extend([3, t[0], t[1], t[2]]);
        }
        (ConvexStorage { _planes: planes, _points: points, _polygons: polygons }, centre)
    }

    /// Creates the hull's geom in `space_raw`: ode-sys's hull geom (`hull.c`), which
    /// collides as ODE's convex of these arrays but whose bounding box costs O(1) per
    /// step (ODE's convex transforms every vertex for it).
    ///
    /// # Safety
    /// `space_raw` is live and ODE is ready (`ensure_ode_ready`, which registers the
    /// hull class); the geom is destroyed before `self` is dropped.
    unsafe fn create(&self, space_raw: ffi::dSpaceID) -> ffi::dGeomID {
        // SAFETY: the caller's contract; the arrays stay where they are (their heap
        // buffers do not move with `self`) and describe `planes.len() / 4` planes,
        // `points.len() / 3` points (at least one: a valid hull) and as many polygons,
        // every index in range.
        unsafe {
            ffi::odesys_hull_create(
                space_raw,
                self._planes.as_ptr(),
                (self._planes.len() / 4) as u32,
                self._points.as_ptr(),
                (self._points.len() / 3) as u32,
                self._polygons.as_ptr(),
            )
        }
    }
}

pub(crate) struct GeomData {
    pub(crate) raw: ffi::dGeomID,
    pub(crate) shape: Shape,
    pub(crate) body: Option<BodyHandle>,
    /// The ODE id of `body` (null when static), cached for the near callback; a body's
    /// geoms are removed before the body.
    pub(crate) body_raw: ffi::dBodyID,
    pub(crate) space: SpaceHandle,
    _mesh: Option<TriMeshStorage>,
    _convex: Option<ConvexStorage>,
    /// Where ODE's geom is in the geom's frame: a convex hull's centre (ODE's convex
    /// needs its origin inside), else zero. ODE's pose of the geom is its pose
    /// translated by this.
    pub(crate) centre: Vector3<f64>,
    /// A cone's collision mesh (vertices, triangles): what ODE collides and rays hit.
    pub(crate) cone_mesh: Option<Triangles>,
    /// The ray casts' tree of a mesh or a cone's mesh.
    pub(crate) mesh_tree: Option<MeshTree>,
    /// Its place in the world's creation order (see [`World::next_serial`]).
    pub(crate) serial: u64,
}

impl GeomData {
    /// The triangles a ray cast tests, with their tree: a mesh's, or a cone's.
    pub(crate) fn ray_mesh(&self) -> Option<TreeMesh<'_>> {
        let tree = self.mesh_tree.as_ref()?;
        match (&self.shape, &self.cone_mesh) {
            (Shape::TriMesh { vertices, triangles }, _) | (_, Some((vertices, triangles))) => {
                Some(TreeMesh { vertices, triangles, tree })
            }
            _ => None,
        }
    }
}

/// Description of a geom to insert with [`World::insert_geom`].
///
/// ODE calls happen in this order: create in the space, attach to the body, set the
/// offset from the body (or the pose of a bodyless geom), set the collision bits.
#[derive(Clone, Debug)]
#[must_use]
pub struct GeomBuilder {
    shape: Shape,
    body: Option<BodyHandle>,
    offset: Option<Isometry3<f64>>,
    pose: Option<Isometry3<f64>>,
    category_bits: Option<u64>,
    collide_bits: Option<u64>,
}

impl GeomBuilder {
    /// A geom of this shape, not attached to a body, at the origin.
    pub fn new(shape: Shape) -> Self {
        GeomBuilder { shape, body: None, offset: None, pose: None, category_bits: None, collide_bits: None }
    }
    /// A sphere.
    pub fn sphere(radius: f64) -> Self {
        Self::new(Shape::Sphere { radius })
    }
    /// A box with full edge lengths `edges` (not half-extents).
    pub fn box_edges(edges: Vector3<f64>) -> Self {
        Self::new(Shape::Box { edges })
    }
    /// A capsule along local Z.
    pub fn capsule(radius: f64, length: f64) -> Self {
        Self::new(Shape::Capsule { radius, length })
    }
    /// A cylinder along local Z.
    pub fn cylinder(radius: f64, length: f64) -> Self {
        Self::new(Shape::Cylinder { radius, length })
    }
    /// A solid cone along +Z of base `radius` and `height`, its origin at its centre of
    /// mass (it collides as a triangle mesh).
    pub fn cone(radius: f64, height: f64) -> Self {
        Self::new(Shape::Cone { radius, height })
    }
    /// An infinite plane `normal · x = distance` (never attached or moved).
    pub fn plane(normal: Vector3<f64>, distance: f64) -> Self {
        Self::new(Shape::Plane { normal, distance })
    }
    /// A ray along local +Z.
    pub fn ray(length: f64) -> Self {
        Self::new(Shape::Ray { length })
    }
    /// A triangle mesh.
    pub fn trimesh(vertices: Vec<Point3<f64>>, triangles: Vec<[u32; 3]>) -> Self {
        Self::new(Shape::TriMesh { vertices, triangles })
    }
    /// The convex hull of `points` (see [`Shape::convex_hull`], which names what is
    /// wrong with points that bound no solid).
    pub fn convex_hull(points: &[Point3<f64>]) -> Result<Self> {
        Shape::convex_hull(points).map(Self::new)
    }
    /// Attaches the geom to a body (it then moves with the body).
    pub fn attached_to(mut self, body: BodyHandle) -> Self {
        self.body = Some(body);
        self
    }
    /// Pose of the geom relative to its body (default: the body frame).
    pub fn offset(mut self, offset: Isometry3<f64>) -> Self {
        self.offset = Some(offset);
        self
    }
    /// World pose of a geom without a body.
    pub fn pose(mut self, pose: Isometry3<f64>) -> Self {
        self.pose = Some(pose);
        self
    }
    /// Category bits (which groups this geom belongs to; default all).
    pub fn category_bits(mut self, bits: u64) -> Self {
        self.category_bits = Some(bits);
        self
    }
    /// Collide bits (which groups this geom collides with; default all).
    pub fn collide_bits(mut self, bits: u64) -> Self {
        self.collide_bits = Some(bits);
        self
    }
}

/// Read access to a geom, from [`World::geom`].
#[derive(Clone, Copy)]
pub struct GeomRef<'w> {
    handle: GeomHandle,
    data: &'w GeomData,
}

/// Write access to a geom, from [`World::geom_mut`].
pub struct GeomMut<'w> {
    handle: GeomHandle,
    raw: ffi::dGeomID,
    placeable: bool,
    /// Where ODE's geom is in the geom's frame (see [`GeomData::centre`]).
    centre: Vector3<f64>,
    kind: &'static str,
    is_ray: bool,
    /// The ODE body it is attached to (null: none).
    body_raw: ffi::dBodyID,
    world: &'w mut World,
}

/// The placement a builder asks for fits its geom: an offset needs a body, a pose no
/// body, and a plane takes neither.
fn check_placement(body: bool, offset: bool, pose: bool, placeable: bool) -> Result<()> {
    if offset && !body {
        return Err(Error::Invalid {
            what: "a geom offset",
            problem: "needs a body; use `pose` for a geom without one".into(),
        });
    }
    if pose && body {
        return Err(Error::Invalid {
            what: "a geom pose",
            problem: "cannot be given to an attached geom, which follows its body; use `offset` instead".into(),
        });
    }
    if pose && !placeable {
        return Err(Error::WrongGeomKind { operation: "setting a pose", kind: "plane" });
    }
    Ok(())
}

impl TriMeshStorage {
    /// ODE's data of a triangle mesh, with the buffers it points into.
    fn build(vertices: &[Point3<f64>], triangles: &[[u32; 3]]) -> TriMeshStorage {
        let flat_v: Vec<f64> = vertices.iter().flat_map(|p| [p.x, p.y, p.z]).collect();
        let mut flat_i: Vec<ffi::dTriIndex> = triangles.iter().flatten().copied().collect();
        if triangles.len() == 1 {
            // OPCODE's tree of a one-triangle mesh is a lone leaf, and its
            // trimesh–trimesh collider reads a child that leaf does not have
            // (SIGSEGV when two such meshes overlap). Give ODE the triangle twice:
            // a two-leaf tree, the same surface.
            flat_i.extend_from_within(..);
        }
        // SAFETY: the buffers are kept alive in `TriMeshStorage` for as long as the
        // data exists; counts and strides describe them exactly (checked above:
        // every index is in range, counts fit in an int).
        let data = unsafe {
            let data = ffi::dGeomTriMeshDataCreate();
            ffi::dGeomTriMeshDataBuildDouble(
                data,
                flat_v.as_ptr().cast(),
                (3 * size_of::<f64>()) as i32,
                vertices.len() as i32,
                flat_i.as_ptr().cast(),
                flat_i.len() as i32,
                (3 * size_of::<ffi::dTriIndex>()) as i32,
            );
            // The convex–trimesh collider reads the angles between the faces (it
            // asserts without them); no other collider does. ODE's preprocessing
            // asserts that a mesh has at most three vertices per triangle.
            if vertices.len() <= flat_i.len() {
                let face_angles = 1u32 << ffi::dTRIDATAPREPROCESS_BUILD_FACE_ANGLES;
                ffi::dGeomTriMeshDataPreprocess2(data, face_angles, std::ptr::null());
            }
            data
        };
        TriMeshStorage { data, _vertices: flat_v, _indices: flat_i }
    }
}

/// The triangles a mesh or a cone collides with: ODE's data, the tree ARS's own
/// queries use, and a cone's mesh (kept for drawing); all `None` for other shapes.
fn triangle_mesh_parts(shape: &Shape) -> (Option<TriMeshStorage>, Option<MeshTree>, Option<Triangles>) {
    let mut mesh = None;
    let mut mesh_tree = None;
    let cone = match &shape {
        Shape::Cone { radius, height } => Some(cone_mesh(*radius, *height)),
        _ => None,
    };
    let triangle_mesh = match (&shape, &cone) {
        (Shape::TriMesh { vertices, triangles }, _) => Some((vertices, triangles)),
        (_, Some((vertices, triangles))) => Some((vertices, triangles)),
        _ => None,
    };
    if let Some((vertices, triangles)) = triangle_mesh {
        mesh_tree = Some(MeshTree::new(vertices, triangles));
        mesh = Some(TriMeshStorage::build(vertices, triangles));
    }
    (mesh, mesh_tree, cone)
}

/// Creates the ODE geom of `shape` in `space_raw`; a triangle mesh or cone takes
/// `mesh`'s data.
///
/// # Safety
/// `space_raw` is live, `shape` is valid, and `mesh` holds the data of a mesh or cone.
unsafe fn create_ode_geom(
    space_raw: ffi::dSpaceID,
    shape: &Shape,
    mesh: Option<&TriMeshStorage>,
    convex: Option<&ConvexStorage>,
) -> ffi::dGeomID {
    // SAFETY: the caller's contract.
    unsafe {
        match &shape {
            Shape::Sphere { radius } => ffi::dCreateSphere(space_raw, *radius),
            Shape::Box { edges: e } => ffi::dCreateBox(space_raw, e.x, e.y, e.z),
            Shape::Capsule { radius, length } => ffi::dCreateCapsule(space_raw, *radius, *length),
            Shape::Cylinder { radius, length } => ffi::dCreateCylinder(space_raw, *radius, *length),
            Shape::Plane { normal, distance } => ffi::dCreatePlane(space_raw, normal.x, normal.y, normal.z, *distance),
            Shape::Ray { length } => ffi::dCreateRay(space_raw, *length),
            Shape::TriMesh { .. } | Shape::Cone { .. } => {
                let data = mesh.map_or(std::ptr::null_mut(), |m| m.data);
                ffi::dCreateTriMesh(space_raw, data, None, None, None)
            }
            Shape::ConvexHull { .. } => match convex {
                Some(c) => c.create(space_raw),
                None => unreachable!("a convex hull's arrays are built before its geom"),
            },
        }
    }
}

/// Keeps a geom that touches nothing (its category and collide bits both 0, as
/// MuJoCo's visual geoms) out of its ODE space, and any other geom in it. No pair of
/// such a geom passes ODE's bits test, so the others' pairs are the same, in the same
/// order; but ODE brings every moved geom of a space up to date before it collides
/// it, and a visual mesh's box costs a pass over its every vertex. ARS keeps the geom
/// as its space's ([`GeomRef::space`]): ray casts, drawing and snapshots see it.
///
/// # Safety
/// `raw` is a live geom made in `space`, which is live, and no collision of that space
/// is under way.
pub(super) unsafe fn keep_in_space(raw: ffi::dGeomID, space: ffi::dSpaceID) {
    // SAFETY: the caller's contract; a geom is only ever in the space it was made
    // in, or in none (checked before each call, as ODE asserts it).
    unsafe {
        let silent = ffi::dGeomGetCategoryBits(raw) == 0 && ffi::dGeomGetCollideBits(raw) == 0;
        let current = ffi::dGeomGetSpace(raw);
        if silent && current == space {
            ffi::dSpaceRemove(space, raw);
        } else if !silent && current.is_null() {
            ffi::dSpaceAdd(space, raw);
        }
    }
}

impl World {
    /// Creates a geom in `space`.
    pub fn insert_geom(&mut self, space: SpaceHandle, builder: GeomBuilder) -> Result<GeomHandle> {
        self.check_usable()?;
        ensure_ode_ready();
        let space_raw = self.space_data(space)?.raw;
        let shape = builder.shape;
        shape.validate()?;
        let placeable = !matches!(shape, Shape::Plane { .. });
        let body_raw = match builder.body {
            Some(b) => {
                if !placeable {
                    return Err(Error::WrongGeomKind { operation: "attaching to a body", kind: "plane" });
                }
                Some(self.body_raw(b)?)
            }
            None => None,
        };
        check_placement(builder.body.is_some(), builder.offset.is_some(), builder.pose.is_some(), placeable)?;
        let offset = builder.offset.map(|o| check_isometry("geom offset", &o)).transpose()?;
        let pose = builder.pose.map(|p| check_isometry("geom pose", &p)).transpose()?;

        let (mesh, mesh_tree, cone) = triangle_mesh_parts(&shape);
        let (convex, centre) = match &shape {
            Shape::ConvexHull { vertices, triangles } => {
                let (storage, centre) = ConvexStorage::build(vertices, triangles);
                (Some(storage), centre)
            }
            _ => (None, Vector3::zeros()),
        };
        // SAFETY: the space is live and every size was checked positive and finite; a
        // trimesh's data and a hull's arrays were built above, kept with the geom.
        let raw = unsafe { create_ode_geom(space_raw, &shape, mesh.as_ref(), convex.as_ref()) };
        if raw.is_null() {
            return Err(Error::Ode("create the geom (ODE gave none)"));
        }
        if mesh.is_some() {
            self.trimesh_count += 1;
        }
        if matches!(shape, Shape::Ray { .. }) {
            self.ray_geoms += 1;
        }
        self.convex_sizes.note(&shape);
        self.refresh_gate();
        let serial = self.next_serial();
        let handle = GeomHandle(self.geoms.insert(GeomData {
            serial,
            raw,
            shape,
            body: builder.body,
            body_raw: body_raw.unwrap_or(std::ptr::null_mut()),
            space,
            _mesh: mesh,
            _convex: convex,
            centre,
            cone_mesh: cone,
            mesh_tree,
        }));
        // SAFETY: the geom was just created; the data is the slot index, never dereferenced.
        unsafe { ffi::dGeomSetData(raw, handle.0.index as usize as *mut _) };
        let mut g = self.geom_mut(handle)?;
        if let Some(b) = body_raw {
            // SAFETY: geom and body are live and belong to this world; the geom is placeable.
            unsafe { ffi::dGeomSetBody(g.raw, b) };
        }
        place_new_geom(&mut g, offset, pose, centre, body_raw.is_some())?;
        if let Some(bits) = builder.category_bits {
            g.set_category_bits(bits);
        }
        if let Some(bits) = builder.collide_bits {
            g.set_collide_bits(bits);
        }
        Ok(handle)
    }

    /// Removes a geom.
    pub fn remove_geom(&mut self, geom: GeomHandle) -> Result<()> {
        self.check_usable()?;
        // The last pass's contact points are made from its records while the geoms
        // they name are alive (the records hold ODE ids, read through ODE).
        self.contacts();
        let data = self.geoms.remove(geom.0, GeomHandle::KIND)?;
        if matches!(data.shape, Shape::TriMesh { .. } | Shape::Cone { .. }) {
            self.trimesh_count -= 1;
        }
        if matches!(data.shape, Shape::Ray { .. }) {
            self.ray_geoms -= 1;
        }
        self.refresh_gate();
        // SAFETY: the geom was created by this world and is destroyed once; its
        // trimesh storage (if any) is dropped after it.
        unsafe { ffi::dGeomDestroy(data.raw) };
        drop(data);
        Ok(())
    }

    /// Read access to a geom.
    pub fn geom(&self, geom: GeomHandle) -> Result<GeomRef<'_>> {
        let data = self.geoms.get(geom.0, GeomHandle::KIND)?;
        Ok(GeomRef { handle: geom, data })
    }

    /// Write access to a geom.
    pub fn geom_mut(&mut self, geom: GeomHandle) -> Result<GeomMut<'_>> {
        self.check_usable()?;
        let data = self.geoms.get(geom.0, GeomHandle::KIND)?;
        Ok(GeomMut {
            handle: geom,
            raw: data.raw,
            placeable: !matches!(data.shape, Shape::Plane { .. }),
            centre: data.centre,
            kind: data.shape.kind_name(),
            is_ray: matches!(data.shape, Shape::Ray { .. }),
            body_raw: data.body_raw,
            world: self,
        })
    }

    /// Every geom of the world, in slot order.
    pub fn geoms(&self) -> impl Iterator<Item = GeomHandle> + '_ {
        self.geoms.iter().map(|(h, _)| GeomHandle(h))
    }

    pub(crate) fn geoms_of_body(&self, body: BodyHandle) -> Vec<GeomHandle> {
        self.geoms.iter().filter(|(_, g)| g.body == Some(body)).map(|(h, _)| GeomHandle(h)).collect()
    }
}

pub(crate) fn check_isometry(what: &'static str, iso: &Isometry3<f64>) -> Result<Isometry3<f64>> {
    limits::vector_within(what, &iso.translation.vector, limits::MAX_COORDINATE, "m")?;
    validate::quaternion(what, &iso.rotation)?;
    Ok(*iso)
}

impl GeomRef<'_> {
    /// The handle of this geom.
    pub fn handle(&self) -> GeomHandle {
        self.handle
    }
    /// Its shape.
    pub fn shape(&self) -> &Shape {
        &self.data.shape
    }
    /// The body it is attached to.
    pub fn body(&self) -> Option<BodyHandle> {
        self.data.body
    }
    /// The space it is in.
    pub fn space(&self) -> SpaceHandle {
        self.data.space
    }
    /// World pose (for a plane: the identity; planes are not placeable).
    pub fn pose(&self) -> Isometry3<f64> {
        if matches!(self.data.shape, Shape::Plane { .. }) {
            return Isometry3::identity();
        }
        let mut q = [0.0; 4];
        // SAFETY: the geom is live and placeable; ODE returns 3 reals and fills 4.
        let (p, q) = unsafe {
            let p = std::slice::from_raw_parts(ffi::dGeomGetPosition(self.data.raw), 3);
            ffi::dGeomGetQuaternion(self.data.raw, q.as_mut_ptr());
            (convert::point_from_ode(p), convert::quaternion_from_ode(&q))
        };
        let centre = self.data.centre;
        if centre == Vector3::zeros() {
            return Isometry3::from_parts(p.coords.into(), q);
        }
        Isometry3::from_parts((p.coords - q * centre).into(), q)
    }
    /// For a ray: its world origin and unit direction.
    pub fn ray(&self) -> Option<(Point3<f64>, Vector3<f64>)> {
        if !matches!(self.data.shape, Shape::Ray { .. }) {
            return None;
        }
        let (mut start, mut dir) = ([0.0; 4], [0.0; 4]);
        // SAFETY: the geom is a live ray; both arrays hold a dVector3.
        unsafe { ffi::dGeomRayGet(self.data.raw, start.as_mut_ptr(), dir.as_mut_ptr()) };
        Some((convert::point_from_ode(&start), convert::vector_from_ode(&dir)))
    }
    /// Axis-aligned bounding box `(min, max)` in world coordinates: ODE's broad phase
    /// box. For a convex hull it holds the hull but is not always the tightest (the
    /// hull's own box turned with it, clipped to a sphere: O(1) per step).
    pub fn aabb(&self) -> (Point3<f64>, Point3<f64>) {
        let mut a = [0.0; 6];
        // SAFETY: the geom is live; `a` holds 6 reals.
        unsafe { ffi::dGeomGetAABB(self.data.raw, a.as_mut_ptr()) };
        (Point3::new(a[0], a[2], a[4]), Point3::new(a[1], a[3], a[5]))
    }
}

impl GeomMut<'_> {
    /// The handle of this geom.
    pub fn handle(&self) -> GeomHandle {
        self.handle
    }

    fn check_movable(&self, operation: &'static str) -> Result<()> {
        if !self.placeable {
            return Err(Error::WrongGeomKind { operation, kind: self.kind });
        }
        if !self.body_raw.is_null() {
            return Err(Error::Invalid {
                what: "a geom pose",
                problem: "cannot be set on an attached geom, which follows its body; move the body instead".into(),
            });
        }
        Ok(())
    }

    /// ODE's position of the geom (its centre, for a hull).
    fn ode_position(&self) -> Vector3<f64> {
        // SAFETY: the geom is live and placeable; ODE returns 3 reals.
        unsafe { convert::point_from_ode(std::slice::from_raw_parts(ffi::dGeomGetPosition(self.raw), 3)).coords }
    }

    /// The geom's rotation, for placing a hull's centre (the identity for the other
    /// shapes, whose centre is their origin: it turns nothing there).
    fn rotation(&self) -> Rotation3<f64> {
        if self.centre == Vector3::zeros() {
            return Rotation3::identity();
        }
        let mut q = [0.0; 4];
        // SAFETY: the geom is live and placeable; ODE fills 4 reals.
        unsafe { ffi::dGeomGetQuaternion(self.raw, q.as_mut_ptr()) };
        convert::quaternion_from_ode(&q).to_rotation_matrix()
    }

    /// Sets the world position of a geom without a body.
    pub fn set_position(&mut self, p: Point3<f64>) -> Result<()> {
        self.check_movable("setting a position")?;
        let p = limits::point("geom position", &p)?;
        let p = p + self.rotation() * self.centre;
        // SAFETY: the geom is live and placeable.
        unsafe { ffi::dGeomSetPosition(self.raw, p.x, p.y, p.z) };
        self.note_reach();
        Ok(())
    }

    /// Sets the world orientation of a geom without a body.
    pub fn set_rotation(&mut self, r: Rotation3<f64>) -> Result<()> {
        self.check_movable("setting a rotation")?;
        let r = validate::rotation("geom rotation", &r)?;
        // A hull turns about its own origin, not about ODE's (its centre).
        let origin = (self.centre != Vector3::zeros()).then(|| self.ode_position() - self.rotation() * self.centre);
        let m = convert::rotation_to_ode(&r);
        // SAFETY: the geom is live and placeable; `m` is a dMatrix3.
        unsafe { ffi::dGeomSetRotation(self.raw, m.as_ptr()) };
        if let Some(origin) = origin {
            let p = origin + r * self.centre;
            // SAFETY: the geom is live and placeable.
            unsafe { ffi::dGeomSetPosition(self.raw, p.x, p.y, p.z) };
        }
        self.note_reach();
        Ok(())
    }

    /// Sets the world pose of a geom without a body.
    pub fn set_pose(&mut self, pose: Isometry3<f64>) -> Result<()> {
        self.check_movable("setting a pose")?;
        let pose = check_isometry("geom pose", &pose)?;
        let q: UnitQuaternion<f64> = pose.rotation;
        let p = pose.translation.vector + q * self.centre;
        let q = convert::quaternion_to_ode(&q);
        // SAFETY: the geom is live and placeable; `q` is a dQuaternion.
        unsafe {
            ffi::dGeomSetPosition(self.raw, p.x, p.y, p.z);
            ffi::dGeomSetQuaternion(self.raw, q.as_ptr());
        }
        self.note_reach();
        Ok(())
    }

    /// For a ray: sets its length.
    pub fn set_ray_length(&mut self, length: f64) -> Result<()> {
        if !self.is_ray {
            return Err(Error::WrongGeomKind { operation: "setting a ray length", kind: self.kind });
        }
        let l = limits::size("ray length", length)?;
        // SAFETY: the geom is a live ray.
        unsafe { ffi::dGeomRaySetLength(self.raw, l) };
        self.note_reach();
        Ok(())
    }

    /// Notes how far the geom reaches from its body's origin (from the world's origin
    /// without a body), for the hash spaces' cheap bound (`World::note_geom_reach`):
    /// the farthest corner of its AABB, a distance, so the bound holds however the
    /// body turns.
    fn note_reach(&mut self) {
        if !self.placeable {
            return;
        }
        let (mut a, mut origin) = ([0.0; 6], [0.0; 3]);
        // SAFETY: the geom is live and placeable; `a` holds 6 reals; its body, if any,
        // is live and ODE returns 3 reals for its position.
        unsafe {
            ffi::dGeomGetAABB(self.raw, a.as_mut_ptr());
            if !self.body_raw.is_null() {
                origin.copy_from_slice(std::slice::from_raw_parts(ffi::dBodyGetPosition(self.body_raw), 3));
            }
        }
        let corner = |i: usize| (a[2 * i] - origin[i]).abs().max((a[2 * i + 1] - origin[i]).abs());
        self.world.note_geom_reach((0..3).map(|i| corner(i).powi(2)).sum::<f64>().sqrt());
    }

    /// Sets the category bits. A geom whose category and collide bits are both 0
    /// touches nothing, and ODE never brings its box up to date for a collision.
    pub fn set_category_bits(&mut self, bits: u64) {
        // SAFETY: the geom is live.
        unsafe { ffi::dGeomSetCategoryBits(self.raw, bits) };
        self.keep_in_space();
    }

    /// Sets the collide bits (see [`set_category_bits`](Self::set_category_bits)).
    pub fn set_collide_bits(&mut self, bits: u64) {
        // SAFETY: the geom is live.
        unsafe { ffi::dGeomSetCollideBits(self.raw, bits) };
        self.keep_in_space();
    }

    fn keep_in_space(&mut self) {
        let Ok(data) = self.world.geoms.get(self.handle.0, GeomHandle::KIND) else { return };
        let Ok(space) = self.world.space_data(data.space) else { return };
        // SAFETY: the geom and its space are live.
        unsafe { keep_in_space(self.raw, space.raw) };
    }

    /// Enables or disables collision for this geom.
    pub fn set_enabled(&mut self, enabled: bool) {
        // SAFETY: the geom is live.
        unsafe { if enabled { ffi::dGeomEnable(self.raw) } else { ffi::dGeomDisable(self.raw) } }
    }
}

/// Sets a new geom's offset from its body (`attached`) or its pose, each moved by a
/// hull's `centre`: ODE's geom of a hull sits at the hull's centre.
fn place_new_geom(
    g: &mut GeomMut<'_>,
    offset: Option<Isometry3<f64>>,
    pose: Option<Isometry3<f64>>,
    centre: Vector3<f64>,
    attached: bool,
) -> Result<()> {
    let offset = match offset {
        Some(o) if centre != Vector3::zeros() => Some(o * nalgebra::Translation3::from(centre)),
        None if centre != Vector3::zeros() && attached => {
            Some(Isometry3::from_parts(nalgebra::Translation3::from(centre), UnitQuaternion::identity()))
        }
        other => other,
    };
    let pose = match pose {
        None if centre != Vector3::zeros() && !attached => Some(Isometry3::identity()),
        other => other,
    };
    if let Some(o) = offset {
        let p = o.translation.vector;
        let q = convert::quaternion_to_ode(&o.rotation);
        // SAFETY: the geom is live, and attached to a body: an offset is given only with
        // one (`check_placement`), and made for a hull only when `attached`.
        unsafe {
            ffi::dGeomSetOffsetPosition(g.raw, p.x, p.y, p.z);
            ffi::dGeomSetOffsetQuaternion(g.raw, q.as_ptr());
        }
    }
    if let Some(p) = pose {
        g.set_pose(p)?;
    }
    g.note_reach();
    Ok(())
}

#[cfg(test)]
#[path = "hull_geom_tests.rs"]
mod hull_geom_tests;
