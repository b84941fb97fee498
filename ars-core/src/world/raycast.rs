//! Ray casts on demand, computed in Rust from each geom's shape and pose (nothing in
//! ODE is changed, so a cast needs only `&World`): what scanning sensors use. Unlike a
//! ray geom, a cast does not wait for the next collision pass.

use nalgebra::{Point3, Vector3};

use super::World;
use super::mesh_tree::{TreeMesh, box_entry};
use crate::error::Result;
use crate::handle::{BodyHandle, GeomHandle};
use crate::limits;
use crate::shape::Shape;
use crate::validate;

/// Where a cast ray first meets a geom.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CastHit {
    /// The geom hit.
    pub geom: GeomHandle,
    /// Distance from the ray's origin, m.
    pub distance: f64,
    /// The hit point, world frame.
    pub position: Point3<f64>,
}

/// A ray to cast: from `origin` along the unit `direction`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    /// Start, world frame.
    pub origin: Point3<f64>,
    /// Unit direction, world frame.
    pub direction: Vector3<f64>,
}

impl World {
    /// The first geom (of any space) the ray meets within `max_distance`, skipping the
    /// geoms of `ignore` (a sensor's own body) and ray geoms. A ray starting inside a
    /// solid hits it at distance 0.
    ///
    /// ```
    /// use ars_core::{GeomBuilder, SpaceKind, World, world::raycast::Ray};
    /// use nalgebra::{Isometry3, Point3, Vector3};
    ///
    /// let mut world = World::new();
    /// let space = world.create_space(SpaceKind::Simple)?;
    /// world.insert_geom(space, GeomBuilder::sphere(1.0).pose(Isometry3::translation(5.0, 0.0, 0.0)))?;
    /// let ray = Ray { origin: Point3::origin(), direction: Vector3::x() };
    /// let hit = world.cast_ray(ray, 100.0, None)?.unwrap();
    /// assert!((hit.distance - 4.0).abs() < 1e-12);
    /// # Ok::<(), ars_core::Error>(())
    /// ```
    pub fn cast_ray(&self, ray: Ray, max_distance: f64, ignore: Option<BodyHandle>) -> Result<Option<CastHit>> {
        Ok(self.cast_rays(&[ray], max_distance, ignore)?.pop().flatten())
    }

    /// [`cast_ray`](Self::cast_ray) for many rays at once (each geom's bounding box is
    /// read once for all of them).
    pub fn cast_rays(
        &self,
        rays: &[Ray],
        max_distance: f64,
        ignore: Option<BodyHandle>,
    ) -> Result<Vec<Option<CastHit>>> {
        self.check_usable()?;
        let max = limits::in_range("ray length", max_distance, 0.0, limits::MAX_SIZE)?;
        for r in rays {
            validate::point("ray origin", &r.origin)?;
            validate::direction("ray direction", &r.direction)?;
        }
        let targets: Vec<Target<'_>> = self
            .geoms
            .iter()
            .filter_map(|(h, data)| {
                let handle = GeomHandle(h);
                if matches!(data.shape, Shape::Ray { .. }) || (ignore.is_some() && data.body == ignore) {
                    return None;
                }
                let geom = self.geom(handle).ok()?;
                let pose = geom.pose();
                let aabb = match data.shape {
                    Shape::Plane { .. } => None,
                    _ => Some(geom.aabb()),
                };
                Some(Target { handle, shape: &data.shape, mesh: data.ray_mesh(), pose, aabb })
            })
            .collect();
        Ok(rays
            .iter()
            .map(|r| {
                let direction = r.direction.normalize();
                let mut best: Option<CastHit> = None;
                for t in &targets {
                    let reach = best.map_or(max, |b| b.distance);
                    if let Some((lo, hi)) = t.aabb
                        && box_entry(&r.origin, &direction, reach, &lo, &hi).is_none()
                    {
                        continue;
                    }
                    let Some(d) = t.distance(&r.origin, &direction, reach) else { continue };
                    if d <= reach {
                        best = Some(CastHit { geom: t.handle, distance: d, position: r.origin + direction * d });
                    }
                }
                best
            })
            .collect())
    }
}

struct Target<'w> {
    handle: GeomHandle,
    shape: &'w Shape,
    /// A mesh's or a cone's triangles, and their tree.
    mesh: Option<TreeMesh<'w>>,
    pose: nalgebra::Isometry3<f64>,
    aabb: Option<(Point3<f64>, Point3<f64>)>,
}

impl Target<'_> {
    /// Distance along the unit `dir` to the shape, if the ray meets it (a mesh's only
    /// within `reach`).
    fn distance(&self, origin: &Point3<f64>, dir: &Vector3<f64>, reach: f64) -> Option<f64> {
        if let Shape::Plane { normal, distance } = self.shape {
            let n = normal.normalize();
            let above = n.dot(&origin.coords) - distance;
            if above <= 0.0 {
                return Some(0.0);
            }
            let towards = n.dot(dir);
            return (towards < 0.0).then(|| -above / towards);
        }
        // The ray in the shape's frame.
        let inv = self.pose.inverse();
        let o = inv * origin;
        let d = inv * dir;
        match self.shape {
            Shape::Sphere { radius } => sphere(&o.coords, &d, *radius),
            Shape::Box { edges } => slab(&o, &d, &(edges / 2.0)),
            Shape::Cylinder { radius, length } => cylinder(&o, &d, *radius, length / 2.0),
            Shape::Capsule { radius, length } => {
                let h = length / 2.0;
                let caps = [h, -h].map(|z| sphere(&(o.coords - Vector3::new(0.0, 0.0, z)), &d, *radius));
                let side = cylinder_side(&o, &d, *radius, h);
                [side, caps[0], caps[1]].into_iter().flatten().reduce(f64::min)
            }
            Shape::TriMesh { .. } | Shape::Cone { .. } => self.mesh.and_then(|mesh| mesh.nearest(&o, &d, reach)),
            Shape::ConvexHull { vertices, triangles } => convex(&o, &d, vertices, triangles),
            Shape::Plane { .. } | Shape::Ray { .. } => None,
        }
    }
}

/// Where the ray from `o` along the unit `d` enters the solid a convex hull bounds (0
/// from inside): the last entry through the faces' planes, if before the first exit.
fn convex(o: &Point3<f64>, d: &Vector3<f64>, vertices: &[Point3<f64>], triangles: &[[u32; 3]]) -> Option<f64> {
    let (mut enter, mut exit) = (0.0f64, f64::INFINITY);
    for t in triangles {
        let [a, b, c] = t.map(|k| vertices[k as usize]);
        let n = (b - a).cross(&(c - a));
        if n.norm_squared().is_nan() || n.norm_squared() <= 0.0 {
            continue;
        }
        // The ray is inside this face's half-space where n·(o + t d − a) ≤ 0.
        let (height, towards) = (n.dot(&(o - a)), n.dot(d));
        if towards == 0.0 {
            if height > 0.0 {
                return None; // parallel, outside
            }
        } else if towards < 0.0 {
            enter = enter.max(-height / towards);
        } else {
            exit = exit.min(-height / towards);
        }
        if enter > exit {
            return None;
        }
    }
    Some(enter)
}

fn sphere(o: &Vector3<f64>, d: &Vector3<f64>, r: f64) -> Option<f64> {
    let c = o.norm_squared() - r * r;
    if c <= 0.0 {
        return Some(0.0);
    }
    let b = o.dot(d);
    let disc = b * b - c;
    (b < 0.0 && disc >= 0.0).then(|| -b - disc.sqrt())
}

/// A box of half-extents `h` about the origin.
fn slab(o: &Point3<f64>, d: &Vector3<f64>, h: &Vector3<f64>) -> Option<f64> {
    let (mut t0, mut t1) = (f64::NEG_INFINITY, f64::INFINITY);
    for i in 0..3 {
        if d[i].abs() < 1e-300 {
            if o[i].abs() > h[i] {
                return None;
            }
            continue;
        }
        let (a, b) = ((-h[i] - o[i]) / d[i], (h[i] - o[i]) / d[i]);
        t0 = t0.max(a.min(b));
        t1 = t1.min(a.max(b));
    }
    (t0 <= t1 && t1 >= 0.0).then_some(t0.max(0.0))
}

/// The round side of a cylinder of radius `r` along Z with |z| ≤ `h` (no caps).
fn cylinder_side(o: &Point3<f64>, d: &Vector3<f64>, r: f64, h: f64) -> Option<f64> {
    let a = d.x * d.x + d.y * d.y;
    let c = o.x * o.x + o.y * o.y - r * r;
    if c <= 0.0 && o.z.abs() <= h {
        return Some(0.0);
    }
    if a < 1e-300 {
        return None;
    }
    let b = o.x * d.x + o.y * d.y;
    let disc = b * b - a * c;
    if disc < 0.0 {
        return None;
    }
    let t = (-b - disc.sqrt()) / a;
    (t >= 0.0 && (o.z + t * d.z).abs() <= h).then_some(t)
}

/// A solid cylinder of radius `r` along Z, |z| ≤ `h`.
fn cylinder(o: &Point3<f64>, d: &Vector3<f64>, r: f64, h: f64) -> Option<f64> {
    let side = cylinder_side(o, d, r, h);
    let caps = [h, -h].map(|z| {
        if d.z.abs() < 1e-300 {
            return None;
        }
        let t = (z - o.z) / d.z;
        let (x, y) = (o.x + t * d.x, o.y + t * d.y);
        (t >= 0.0 && x * x + y * y <= r * r).then_some(t)
    });
    [side, caps[0], caps[1]].into_iter().flatten().reduce(f64::min)
}
