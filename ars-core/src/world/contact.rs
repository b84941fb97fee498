//! Contacts: the surface of a pair, the hooks that choose it, and the contact points
//! and ray hits of the last collision pass (made by [`World::collide`]).

use nalgebra::{Point3, Vector3};
use ode_sys as ffi;

use super::World;
use crate::convert;
use crate::error::{Error, Result};
use crate::handle::{BodyHandle, GeomHandle};
use crate::validate;

/// Most contact points ODE generates for one pair of geoms (PyODE's fixed limit,
/// which the original ARS inherited).
pub const MAX_CONTACTS_LIMIT: usize = 150;

/// Surface parameters of the contacts between two geoms (ODE's `dSurfaceParameters`).
///
/// The default is the ARS surface: restitution only (bounce 0.2 above 0 m/s), friction
/// force limit 500 N per contact point and direction (ODE's box friction, not Coulomb),
/// no soft ERP/CFM, up to 150 contact points per pair.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ContactSurface {
    /// Friction limit: the largest friction force per contact point and tangent
    /// direction, N (with `approx1` set it is a Coulomb coefficient instead).
    /// `f64::INFINITY` never slips.
    pub mu: f64,
    /// A different limit for the second tangent direction.
    pub mu2: Option<f64>,
    /// Restitution `(bounce, bounce_vel)`: coefficient in [0, 1] and the smallest
    /// approaching speed (m/s) that bounces.
    pub bounce: Option<(f64, f64)>,
    /// Contact-normal ERP (else the world's).
    pub soft_erp: Option<f64>,
    /// Contact-normal CFM (else the world's).
    pub soft_cfm: Option<f64>,
    /// Friction pyramid approximation: friction limits proportional to the normal force
    /// (Coulomb-like, `mu` is then a coefficient).
    pub approx1: bool,
    /// Rolling friction `[rho, rho2, rhoN]` (ODE's `dContactRolling`): torque limits
    /// against rolling about the two friction directions and spinning about the normal,
    /// N·m (with `approx1` proportional to the normal force: lengths, m). `None`: none.
    #[serde(default)]
    pub rolling: Option<[f64; 3]>,
    /// Most contact points generated per pair (1 to [`MAX_CONTACTS_LIMIT`]). The world's
    /// default surface keeps the collider's first points (ODE's order, as the original
    /// ARS); a surface chosen by [`CollisionHooks`] keeps, when the collider finds more,
    /// the deepest and those spread farthest from it and each other (a footprint's
    /// corners, not the first vertices of a hull's list).
    pub max_contacts: usize,
}

impl Default for ContactSurface {
    fn default() -> Self {
        ContactSurface {
            mu: 500.0,
            mu2: None,
            bounce: Some((0.2, 0.0)),
            soft_erp: None,
            soft_cfm: None,
            approx1: false,
            rolling: None,
            max_contacts: MAX_CONTACTS_LIMIT,
        }
    }
}

impl ContactSurface {
    /// Checks every field.
    pub fn validate(&self) -> Result<()> {
        if self.mu.is_nan() || self.mu < 0.0 {
            return Err(Error::OutOfRange { what: "contact mu", detail: format!("must be ≥ 0, got {}", self.mu) });
        }
        if let Some(mu2) = self.mu2
            && (mu2.is_nan() || mu2 < 0.0)
        {
            return Err(Error::OutOfRange { what: "contact mu2", detail: format!("must be ≥ 0, got {mu2}") });
        }
        if let Some((b, v)) = self.bounce {
            if !(0.0..=1.0).contains(&b) {
                return Err(Error::OutOfRange {
                    what: "contact bounce",
                    detail: format!("must be within [0, 1], got {b}"),
                });
            }
            validate::non_negative("contact bounce velocity", v)?;
        }
        if let Some(e) = self.soft_erp
            && !(0.0..=1.0).contains(&e)
        {
            return Err(Error::OutOfRange {
                what: "contact soft ERP",
                detail: format!("must be within [0, 1], got {e}"),
            });
        }
        if let Some(c) = self.soft_cfm {
            validate::non_negative("contact soft CFM", c)?;
        }
        for rho in self.rolling.iter().flatten() {
            validate::non_negative("contact rolling friction", *rho)?;
        }
        if self.max_contacts == 0 || self.max_contacts > MAX_CONTACTS_LIMIT {
            return Err(Error::OutOfRange {
                what: "max contacts",
                detail: format!("must be 1 to {MAX_CONTACTS_LIMIT}, got {}", self.max_contacts),
            });
        }
        Ok(())
    }

    pub(super) fn to_ode(self) -> ffi::dSurfaceParameters {
        let mut s = ffi::dSurfaceParameters { mu: self.mu, ..Default::default() };
        let mut mode = 0;
        if let Some(mu2) = self.mu2 {
            mode |= ffi::dContactMu2;
            s.mu2 = mu2;
        }
        if let Some((b, v)) = self.bounce {
            mode |= ffi::dContactBounce;
            s.bounce = b;
            s.bounce_vel = v;
        }
        if let Some(e) = self.soft_erp {
            mode |= ffi::dContactSoftERP;
            s.soft_erp = e;
        }
        if let Some(c) = self.soft_cfm {
            mode |= ffi::dContactSoftCFM;
            s.soft_cfm = c;
        }
        if self.approx1 {
            mode |= ffi::dContactApprox1;
        }
        if let Some([rho, rho2, rho_n]) = self.rolling {
            mode |= ffi::dContactRolling;
            (s.rho, s.rho2, s.rhoN) = (rho, rho2, rho_n);
        }
        s.mode = mode as i32;
        s
    }
}

/// A pair of geoms that may touch, as passed to [`CollisionHooks::contact_surface`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct GeomPair {
    /// First geom (as ODE reports the pair).
    pub geom1: GeomHandle,
    /// Second geom.
    pub geom2: GeomHandle,
    /// Body of the first geom (`None`: static).
    pub body1: Option<BodyHandle>,
    /// Body of the second geom.
    pub body2: Option<BodyHandle>,
}

/// User decisions during collision. The default methods give the world's default
/// surface to every pair.
pub trait CollisionHooks {
    /// `true` when every pair gets the default surface, so that
    /// [`contact_surface`](Self::contact_surface) need not be asked (a fast path for
    /// [`DefaultHooks`]). Leave it `false` in your own hooks.
    fn always_default(&self) -> bool {
        false
    }

    /// Surface of the contacts of `pair`, or `None` for no contact at all.
    fn contact_surface(&mut self, pair: &GeomPair, default: &ContactSurface) -> Option<ContactSurface> {
        let _ = pair;
        Some(*default)
    }
}

/// The default hooks: every pair touches with the world's default surface.
#[derive(Clone, Copy, Debug, Default)]
pub struct DefaultHooks;

impl CollisionHooks for DefaultHooks {
    fn always_default(&self) -> bool {
        true
    }
}

/// A contact point created by the last [`World::collide`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactPoint {
    /// The pair.
    pub pair: GeomPair,
    /// Position, world frame, m.
    pub position: Point3<f64>,
    /// Normal, pointing into geom 1.
    pub normal: Vector3<f64>,
    /// Penetration depth, m.
    pub depth: f64,
    /// Force of the contact on geom 1 (on geom 2: its opposite), world frame, N, over
    /// the step just taken: zero until a step, and unless asked with
    /// [`World::set_contact_feedback`] (a [`ContactForces`](crate::sensors::ContactForces)
    /// sensor asks for it).
    pub force: Vector3<f64>,
}

/// A ray hit found by the last [`World::collide`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RayHit {
    /// The ray.
    pub ray: GeomHandle,
    /// The geom it hit.
    pub other: GeomHandle,
    /// Hit point, world frame, m.
    pub position: Point3<f64>,
    /// Surface normal at the hit point.
    pub normal: Vector3<f64>,
    /// Distance from the ray origin to the hit point, m.
    pub distance: f64,
}

impl World {
    /// The surface given to every pair unless hooks decide otherwise.
    pub fn default_surface(&self) -> ContactSurface {
        self.collision.default_surface
    }

    /// Sets the default contact surface.
    pub fn set_default_surface(&mut self, surface: ContactSurface) -> Result<()> {
        surface.validate()?;
        self.collision.default_surface = surface;
        self.collision.plain.set_surface(&surface);
        Ok(())
    }

    /// Destroys the contact joints created by the last collisions.
    #[inline]
    pub fn clear_contacts(&mut self) {
        // SAFETY: the group is live; its joints are contact joints owned by it alone.
        unsafe { ffi::dJointGroupEmpty(self.contact_group) };
    }

    /// Whether ODE reports the force of every contact point (in
    /// [`ContactPoint::force`], after each step). Off by default: it costs a little at
    /// every contact.
    pub fn set_contact_feedback(&mut self, on: bool) {
        self.collision.feedback.on = on;
        self.refresh_gate();
    }

    /// Whether contact forces are reported (see [`World::set_contact_feedback`]).
    pub fn contact_feedback(&self) -> bool {
        self.collision.feedback.on
    }

    /// The contact points created by the last collision pass.
    pub fn contacts(&self) -> &[ContactPoint] {
        self.collision.points.get_or_init(|| {
            let mut points = self.collision.spare_points.take();
            points_from_records(&self.geoms, self.collision.plain.records(), &mut points);
            points
        })
    }

    /// The ray hits found by the last collision pass, in the order ODE reported them.
    pub fn ray_hits(&self) -> &[RayHit] {
        &self.collision.ray_hits
    }

    /// The closest hit of `ray` in the last collision pass, if any.
    pub fn closest_ray_hit(&self, ray: GeomHandle) -> Option<RayHit> {
        self.collision
            .ray_hits
            .iter()
            .filter(|h| h.ray == ray)
            .min_by(|a, b| a.distance.total_cmp(&b.distance))
            .copied()
    }
}

/// The contact points of a plain collision's records, appended to `points`; the
/// handles are looked up once per pair.
fn points_from_records(
    geoms: &crate::handle::Arena<super::geom::GeomData>,
    records: &[ffi::odesys_contact_record],
    points: &mut Vec<ContactPoint>,
) {
    let mut last: Option<(ffi::dGeomID, ffi::dGeomID, GeomPair)> = None;
    for r in records {
        let pair = match last {
            Some((o1, o2, pair)) if o1 == r.o1 && o2 == r.o2 => pair,
            _ => match (geom_slot_in(geoms, r.o1), geom_slot_in(geoms, r.o2)) {
                (Some((g1, d1)), Some((g2, d2))) => {
                    let pair = GeomPair { geom1: g1, geom2: g2, body1: d1.body, body2: d2.body };
                    last = Some((r.o1, r.o2, pair));
                    pair
                }
                _ => {
                    log::error!("collision reported a geom that this world does not own; contact not recorded");
                    continue;
                }
            },
        };
        points.push(ContactPoint {
            pair,
            position: convert::point_from_ode(&r.geom.pos),
            normal: convert::vector_from_ode(&r.geom.normal),
            depth: r.geom.depth,
            force: Vector3::zeros(),
        });
    }
}

/// The handle and data of a geom that ODE reports, in `geoms` (see
/// [`World::geom_slot`]).
#[inline]
pub(super) fn geom_slot_in(
    geoms: &crate::handle::Arena<super::geom::GeomData>,
    raw: ffi::dGeomID,
) -> Option<(GeomHandle, &super::geom::GeomData)> {
    // SAFETY: ODE hands the callback live geoms of the collided space; their user
    // data is the arena index set at creation.
    let index = unsafe { ffi::dGeomGetData(raw) } as usize as u32;
    let (h, data) = geoms.get_by_index(index)?;
    if data.raw != raw {
        return None;
    }
    Some((GeomHandle(h), data))
}
