//! A geom's own contact parameters, MuJoCo's, and how a pair's map onto ODE's contact
//! (see [`GeomContact`]).

use serde::{Deserialize, Serialize};

use super::Scene;
use crate::contact::ContactSurface;
use crate::error::{Error, Result};
use crate::handle::{GeomHandle, ObjectId};

/// A geom's own contact parameters, as MuJoCo gives each geom: MJCF's `friction`,
/// `condim`, `solref`, `solimp`, `priority` and `solmix`. Two touching geoms' parameters
/// are combined as MuJoCo combines them, then mapped onto ODE's contact.
///
/// **Combined** (MuJoCo's `mj_contactParam`): the geom of higher `priority` gives all of
/// them; at equal priority, `condim` and each `friction` are the larger of the two, and
/// `solref` and `solimp` are averaged with the weights `solmix₁ / (solmix₁ + solmix₂)`
/// (0.5 when both are 0), except two direct `solref`s (negative numbers), whose
/// smaller is taken element by element. A geom without parameters of its own (ARS's
/// floors and shapes) has MuJoCo's defaults.
///
/// **Mapped onto ODE** (approximate where the two models differ):
/// - `condim` 1: no friction. 3: Coulomb friction (ODE's friction pyramid,
///   `dContactApprox1`) of coefficient `friction[0]`. 4: and torsional friction
///   (`friction[1]`, m: ODE's spinning `rhoN`). 6: and rolling friction (`friction[2]`,
///   m: ODE's `rho` and `rho2`). ODE's pyramid is MuJoCo's pyramidal cone; MuJoCo's
///   default elliptic cone is up to √2 more permissive across the pyramid's diagonals.
/// - `solref` and `solimp`: MuJoCo makes each contact a spring-damper on the
///   acceleration, `a = (1 − d)·a₀ + d·(K·d·x − B·v)` with the impedance `d` from
///   `solimp`, `K = 1 / (d_max²·τ²·ζ²)` and `B = 2 / (d_max·τ)` from `solref = (τ, ζ)`
///   (τ at least two time steps, as MuJoCo's `refsafe`), or `K = −solref[0] / d_max²`
///   and `B = −solref[1] / d_max` when direct. ODE's soft contact gives
///   `a = (1 − w)·a₀ + w·(ERP·x / h² − v / h)` with `w = h / (h + CFM·m)` for an
///   effective mass `m`. The mapping makes `w = d` and the stiffness equal:
///   `CFM = h·(1 − d) / (d·m)` and `ERP = h²·K·d`, so a resting contact sinks as deep as
///   in MuJoCo. It differs in three ways: `d` is MuJoCo's impedance at the depth
///   where such a contact rests under 9.81 m/s² (`solimp`'s curve), not at each
///   contact's own depth; ODE damps the
///   approach in one step (`v / h`, more than MuJoCo's `B·v`): it is over-damped,
///   settling into its resting depth over about `h / (ERP·d)` (0.4 s at 1 ms steps for
///   MuJoCo's default `solref`, where MuJoCo's settles within a few `τ`), and a damping ratio
///   `ζ` below 1, with which MuJoCo's contact rebounds, is given as ODE's restitution
///   `exp(−π·ζ / √(1 − ζ²))` (a linear spring-damper's over one contact, aimed higher
///   by the `1 − d` of the approach speed ODE's soft contact keeps); and `m` is
///   the two bodies' reduced mass (a static geom's
///   is infinite, and so is that of a body whose geoms have no parameters of their
///   own), where MuJoCo uses the contact's own inverse inertia along its normal.
/// - At most 4 points per pair, as MuJoCo keeps (where ODE finds more: up to 8 for a box
///   on a box, every vertex below a plane for a convex hull), the deepest and those
///   spread farthest kept (see [`ContactSurface::max_contacts`]).
/// - `margin` and `gap` are not mapped: ODE makes contacts only where geoms overlap.
///
/// The default is MuJoCo's default geom.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct GeomContact {
    /// Sliding (a coefficient), torsional (m) and rolling (m) friction: MuJoCo's
    /// `friction`, default `[1, 0.005, 0.0001]`.
    pub friction: [f64; 3],
    /// Which frictions act: 1 none, 3 sliding, 4 and torsional, 6 and rolling
    /// (MuJoCo's `condim`, default 3).
    pub condim: u8,
    /// `(time constant, damping ratio)`, or `(−stiffness, −damping)` when both are
    /// negative (MuJoCo's `solref`, default `[0.02, 1]`).
    pub solref: [f64; 2],
    /// `(d_min, d_max, width, midpoint, power)` (MuJoCo's `solimp`, default
    /// `[0.9, 0.95, 0.001, 0.5, 2]`).
    pub solimp: [f64; 5],
    /// The geom of higher priority gives the pair's parameters (default 0).
    pub priority: i32,
    /// The weight of this geom's `solref` and `solimp` against the other's (default 1).
    pub solmix: f64,
}

impl Default for GeomContact {
    fn default() -> Self {
        GeomContact {
            friction: [1.0, 0.005, 0.0001],
            condim: 3,
            solref: [0.02, 1.0],
            solimp: [0.9, 0.95, 0.001, 0.5, 2.0],
            priority: 0,
            solmix: 1.0,
        }
    }
}

/// Most contact points MuJoCo 4.0 keeps for a pair of geoms: a box, a cylinder or a
/// convex mesh on a plane, a box or another hull, resting on a face, gives 4 (its
/// colliders return at most that many on the corpus' models); ODE's colliders return up
/// to 8 (box on box) or every vertex below a plane (a hull). The pairs of geoms with
/// contact parameters of their own keep this many, spread over what ODE finds (see
/// [`ContactSurface::max_contacts`]): fewer rows for ODE's exact step, the same
/// support.
pub(crate) const MUJOCO_CONTACTS_PER_PAIR: usize = 4;

/// Below this a mass, a weight or a time counts as 0 (MuJoCo's `mjMINVAL`).
const MIN_VALUE: f64 = 1e-15;

/// The reduced mass of two bodies, kg: `a·b / (a + b)`, or the other's when one is
/// infinite (static, or kinematic).
pub(crate) fn reduced_mass(a: f64, b: f64) -> f64 {
    match (a.is_finite(), b.is_finite()) {
        (true, true) => a * b / (a + b),
        (true, false) => a,
        _ => b,
    }
}

/// ODE's constraint force mixing that gives a constraint of effective mass `mass` kg
/// MuJoCo's impedance `d` at a time step of `h` s: `h·(1 − d) / (d·m)` (a compliance per
/// unit force); 0 against an infinite mass, which MuJoCo's impedance cannot soften.
pub(crate) fn impedance_cfm(h: f64, d: f64, mass: f64) -> f64 {
    if mass.is_finite() && mass > MIN_VALUE { h * (1.0 - d) / (d * mass) } else { 0.0 }
}

impl GeomContact {
    /// Checks every field: frictions finite and not negative, `condim` 1, 3, 4 or 6, a
    /// `solref` of two positive or two non-positive finite numbers (not both 0), a
    /// `solimp` with `0 < d_min, d_max < 1`, a positive width and power and a midpoint
    /// within [0, 1], `solmix` finite and not negative.
    pub fn validate(&self) -> Result<()> {
        let bad = |detail: String| Err(Error::OutOfRange { what: "a geom's contact parameters", detail });
        if let Some(f) = self.friction.iter().find(|f| !(f.is_finite() && **f >= 0.0)) {
            return bad(format!("friction {f} must be finite and not negative"));
        }
        if ![1, 3, 4, 6].contains(&self.condim) {
            return bad(format!("condim {} must be 1, 3, 4 or 6", self.condim));
        }
        let [a, b] = self.solref;
        let direct = a <= 0.0 && b <= 0.0 && (a, b) != (0.0, 0.0);
        if !(a.is_finite() && b.is_finite() && ((a > 0.0 && b > 0.0) || direct)) {
            return bad(format!("solref [{a}, {b}] must be two positive numbers, or two non-positive ones"));
        }
        let [d_min, d_max, width, mid, power] = self.solimp;
        let impedance = |d: f64| d > 0.0 && d < 1.0;
        let shape = width > 0.0 && width.is_finite() && (0.0..=1.0).contains(&mid) && power >= 1.0 && power.is_finite();
        if !(impedance(d_min) && impedance(d_max) && shape) {
            return bad(format!(
                "solimp {:?} must have 0 < d_min, d_max < 1, a positive width, a midpoint within [0, 1] and a power of at least 1",
                self.solimp
            ));
        }
        if !(self.solmix.is_finite() && self.solmix >= 0.0) {
            return bad(format!("solmix {} must be finite and not negative", self.solmix));
        }
        Ok(())
    }

    /// The parameters of a contact between geoms of parameters `self` and `other`, as
    /// MuJoCo combines them.
    #[must_use]
    pub fn combined(&self, other: &GeomContact) -> GeomContact {
        if self.priority != other.priority {
            return if self.priority > other.priority { *self } else { *other };
        }
        let mix = match (self.solmix < MIN_VALUE, other.solmix < MIN_VALUE) {
            (true, true) => 0.5,
            (true, false) => 0.0,
            (false, true) => 1.0,
            (false, false) => self.solmix / (self.solmix + other.solmix),
        };
        let direct = |r: &[f64; 2]| r[0] <= 0.0;
        let solref = if direct(&self.solref) && direct(&other.solref) {
            [0, 1].map(|i| self.solref[i].min(other.solref[i]))
        } else {
            [0, 1].map(|i| mix * self.solref[i] + (1.0 - mix) * other.solref[i])
        };
        GeomContact {
            friction: [0, 1, 2].map(|i| self.friction[i].max(other.friction[i])),
            condim: self.condim.max(other.condim),
            solref,
            solimp: [0, 1, 2, 3, 4].map(|i| mix * self.solimp[i] + (1.0 - mix) * other.solimp[i]),
            priority: self.priority,
            solmix: self.solmix.max(other.solmix),
        }
    }

    /// The ODE surface of a contact with these (combined) parameters, at a time step of
    /// `h` s, between bodies of reduced mass `mass` kg (infinite: against the static
    /// world), with at most `max_contacts` points.
    pub fn surface(&self, h: f64, mass: f64, max_contacts: usize) -> ContactSurface {
        let d_max = self.solimp[1];
        let (stiffness, damping) = if self.solref[0] > 0.0 {
            let time_constant = self.solref[0].max(2.0 * h);
            let ratio = self.solref[1];
            (1.0 / (d_max * d_max * time_constant * time_constant * ratio * ratio), 2.0 / (d_max * time_constant))
        } else {
            (-self.solref[0] / (d_max * d_max), -self.solref[1] / d_max)
        };
        // MuJoCo's under-damped contact rebounds; ODE's damps the approach in one step
        // and rebounds only by its restitution: that of a linear spring-damper of this
        // damping ratio over one contact.
        // ODE's soft contact keeps `1 − d` of the approach speed against the rebound it
        // aims at: it aims higher, so that `d·aim − (1 − d) = restitution`.
        let d = self.resting_impedance(stiffness);
        let ratio = damping / (2.0 * stiffness.sqrt());
        let bounce = (ratio < 1.0).then(|| {
            let restitution = (-std::f64::consts::PI * ratio / (1.0 - ratio * ratio).sqrt()).exp();
            (((restitution + 1.0 - d) / d).min(1.0), 0.0)
        });
        let erp = (h * h * stiffness * d).min(1.0);
        // ODE's CFM is a compliance per unit force: the effective mass makes it MuJoCo's
        // impedance; against the static world (an infinite mass) the contact is as hard
        // as the world's CFM.
        let cfm = impedance_cfm(h, d, mass);
        let friction = self.condim > 1;
        let rolling = match self.condim {
            4 => Some([0.0, 0.0, self.friction[1]]),
            6 => Some([self.friction[2], self.friction[2], self.friction[1]]),
            _ => None,
        };
        ContactSurface {
            mu: if friction { self.friction[0] } else { 0.0 },
            mu2: None,
            bounce,
            soft_erp: Some(erp),
            soft_cfm: Some(cfm),
            approx1: friction,
            rolling,
            max_contacts,
        }
    }

    /// MuJoCo's impedance at a penetration of `depth` m: `solimp`'s curve from `d_min`
    /// at the surface to `d_max` at `width` deep, through `midpoint` with `power`.
    pub fn impedance(&self, depth: f64) -> f64 {
        let [d_min, d_max, width, mid, power] = self.solimp;
        let x = (depth / width).clamp(0.0, 1.0);
        let mid = mid.clamp(1e-4, 1.0 - 1e-4);
        let y = if power == 1.0 {
            x
        } else if x <= mid {
            x.powf(power) / mid.powf(power - 1.0)
        } else {
            1.0 - (1.0 - x).powf(power) / (1.0 - mid).powf(power - 1.0)
        };
        d_min + y * (d_max - d_min)
    }

    /// The impedance where a contact of stiffness `stiffness` (MuJoCo's `K`, per unit
    /// mass) rests under a gravity of `RESTING_GRAVITY`: the depth `x` where
    /// `(1 − d(x))·g = d(x)²·K·x`, found by bisection.
    fn resting_impedance(&self, stiffness: f64) -> f64 {
        let excess = |x: f64| {
            let d = self.impedance(x);
            d * d * stiffness * x - (1.0 - d) * RESTING_GRAVITY
        };
        let (mut low, mut high) = (0.0, self.solimp[2]);
        while excess(high) < 0.0 && high < 1e3 {
            high *= 2.0;
        }
        for _ in 0..60 {
            let middle = 0.5 * (low + high);
            if excess(middle) < 0.0 {
                low = middle;
            } else {
                high = middle;
            }
        }
        self.impedance(high)
    }
}

/// A geom named by its object and its index there (0: the object's first geom), as
/// [`Scene::set_geom_contact`] takes it.
pub type GeomOf = (ObjectId, usize);

/// The gravity under which the mapping makes a contact rest as deep as MuJoCo's, m/s²
/// (see [`GeomContact`]).
const RESTING_GRAVITY: f64 = 9.81;

impl Scene {
    /// Gives a geom of `object` contact parameters of its own (`geom` 0: its first geom,
    /// then its other geoms in order), combined with those of each geom it touches
    /// (see [`GeomContact`]). A pair of objects with a surface of their own
    /// ([`set_contact_surface`](Self::set_contact_surface)) keeps it. The effective mass
    /// is the object's mass now: set the parameters again after changing it.
    pub fn set_geom_contact(&mut self, object: ObjectId, geom: usize, contact: GeomContact) -> Result<()> {
        contact.validate()?;
        let handle = self.geom_of(object, geom)?;
        let mass = match self.object(object)?.body_handle() {
            Some(body) => self.world.body(body)?.mass(),
            None => f64::INFINITY,
        };
        self.pair_surfaces.set_geom_contact(handle, object, contact, mass);
        Ok(())
    }

    /// A geom's own contact parameters (see [`set_geom_contact`](Self::set_geom_contact)),
    /// if it has them.
    pub fn geom_contact(&self, object: ObjectId, geom: usize) -> Result<Option<GeomContact>> {
        let handle = self.geom_of(object, geom)?;
        Ok(self.pair_surfaces.geom_contact(handle))
    }

    /// Every geom with contact parameters of its own: its object, its index in the
    /// object (as [`set_geom_contact`](Self::set_geom_contact) takes it) and its
    /// parameters, in the objects' creation order.
    pub fn geom_contacts(&self) -> Vec<(ObjectId, usize, GeomContact)> {
        let mut all = Vec::new();
        for (_, id) in self.objects() {
            let Ok(data) = self.objects.get(id.0, ObjectId::KIND) else { continue };
            for (k, g) in data.geom.iter().chain(&data.extra_geoms).enumerate() {
                if let Some(c) = self.pair_surfaces.geom_contact(*g) {
                    all.push((id, k, c));
                }
            }
        }
        all
    }

    /// Gives the pair of geoms `a` and `b` (each its object and its index there, as
    /// [`set_geom_contact`](Self::set_geom_contact) takes it) contact parameters of
    /// their own: used as they are in place of the two geoms' combined, as MuJoCo's
    /// `<contact><pair>` gives its own. The effective mass is the two objects'
    /// reduced mass now. Setting it again replaces it.
    pub fn set_geom_pair_contact(&mut self, a: GeomOf, b: GeomOf, contact: GeomContact) -> Result<()> {
        contact.validate()?;
        let (first, second) = (self.geom_of(a.0, a.1)?, self.geom_of(b.0, b.1)?);
        if first == second {
            return Err(Error::Invalid {
                what: "a pair of geoms",
                problem: "a geom cannot make a pair with itself".into(),
            });
        }
        let mass = |scene: &Self, object: ObjectId| -> Result<f64> {
            Ok(match scene.object(object)?.body_handle() {
                Some(body) => scene.world.body(body)?.mass(),
                None => f64::INFINITY,
            })
        };
        let mass = reduced_mass(mass(self, a.0)?, mass(self, b.0)?);
        self.pair_surfaces.set_pair_contact((first, a.0), (second, b.0), contact, mass);
        Ok(())
    }

    /// Every pair of geoms with contact parameters of its own (see
    /// [`set_geom_pair_contact`](Self::set_geom_pair_contact)): each geom as its object
    /// and index, in the order the pairs were set.
    pub fn geom_pair_contacts(&self) -> Vec<(GeomOf, GeomOf, GeomContact)> {
        self.pair_surfaces
            .pair_contacts()
            .filter_map(|(a, b, contact)| Some((self.geom_place(a)?, self.geom_place(b)?, contact)))
            .collect()
    }

    /// The object and index (as [`set_geom_contact`](Self::set_geom_contact) takes
    /// them) of a geom that has contact parameters of its own or is in a pair that has.
    pub(crate) fn geom_place(&self, geom: GeomHandle) -> Option<GeomOf> {
        let object = self.pair_surfaces.owner(geom)?;
        let data = self.objects.get(object.0, ObjectId::KIND).ok()?;
        let k = data.geom.iter().chain(&data.extra_geoms).position(|g| *g == geom)?;
        Some((object, k))
    }

    /// Forgets every geom's own parameters (a snapshot restores its own).
    pub(crate) fn clear_geom_contacts(&mut self) {
        self.pair_surfaces.clear_geom_contacts();
    }

    /// The `k`-th geom of `object` (0: its first).
    fn geom_of(&self, object: ObjectId, k: usize) -> Result<GeomHandle> {
        let data = self.objects.get(object.0, ObjectId::KIND)?;
        data.geom.iter().chain(&data.extra_geoms).nth(k).copied().ok_or_else(|| Error::Invalid {
            what: "a geom of an object",
            problem: format!(
                "{:?} has {} geoms, and geom {k} was asked",
                data.name,
                data.geom.iter().chain(&data.extra_geoms).count()
            ),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// MuJoCo's rules: priority decides outright; at equal priority the larger
    /// frictions and condim, and solref/solimp weighted by solmix.
    #[test]
    fn parameters_combine_as_mujoco_combines_them() {
        let a = GeomContact {
            friction: [0.5, 0.01, 0.0],
            condim: 4,
            solref: [0.02, 1.0],
            solmix: 3.0,
            ..Default::default()
        };
        let b = GeomContact {
            friction: [0.8, 0.0, 0.001],
            condim: 3,
            solref: [0.06, 0.5],
            solmix: 1.0,
            ..Default::default()
        };
        let c = a.combined(&b);
        assert_eq!((c.friction, c.condim), ([0.8, 0.01, 0.001], 4));
        assert!((c.solref[0] - (0.75 * 0.02 + 0.25 * 0.06)).abs() < 1e-15);
        assert!((c.solref[1] - (0.75 * 1.0 + 0.25 * 0.5)).abs() < 1e-15);
        let boss = GeomContact { priority: 1, ..b };
        assert_eq!(a.combined(&boss), boss);
        assert_eq!(boss.combined(&a), boss);
        // Two direct solrefs: the smaller of each.
        let (x, y) = (GeomContact { solref: [-100.0, -5.0], ..a }, GeomContact { solref: [-50.0, -8.0], ..b });
        assert_eq!(x.combined(&y).solref, [-100.0, -8.0]);
        // Weights of 0 count as equal ones.
        let (p, q) = (GeomContact { solmix: 0.0, ..a }, GeomContact { solmix: 0.0, ..b });
        assert!((p.combined(&q).solref[0] - 0.04).abs() < 1e-15);
    }

    /// A resting contact sinks as deep as MuJoCo's spring-damper with its impedance
    /// at that depth: `(1 − d)·g = d·K·d·x` there, and ODE's `(1 − w)·g = w·ERP·x / h²`.
    #[test]
    fn the_mapping_keeps_mujoco_s_resting_depth() {
        // MuJoCo's default, and Gymnasium's half-cheetah's (an impedance of 0 at the
        // surface, 0.8 at 1 cm).
        for contact in
            [GeomContact::default(), GeomContact { solimp: [1e-4, 0.8, 0.01, 0.5, 2.0], ..Default::default() }]
        {
            let (h, m, g) = (0.002, 2.0, RESTING_GRAVITY);
            let s = contact.surface(h, m, 4);
            let (erp, cfm) = (s.soft_erp.unwrap(), s.soft_cfm.unwrap());
            let w = h / (h + cfm * m);
            let ode = (1.0 - w) * g * h * h / (w * erp);
            let k = 1.0 / (contact.solimp[1].powi(2) * 0.02f64.powi(2));
            let d = contact.impedance(ode);
            assert!((w - d).abs() < 1e-9, "{w} {d}");
            let mujoco = (1.0 - d) * g / (d * k * d);
            assert!((ode - mujoco).abs() < 1e-9 * mujoco, "{ode} {mujoco}");
        }
        let contact = GeomContact::default();
        let (h, m) = (0.002, 2.0);
        let s = contact.surface(h, m, 4);
        // Frictions by condim.
        assert_eq!((s.mu, s.approx1, s.rolling), (1.0, true, None));
        let spin = GeomContact { condim: 4, ..contact }.surface(h, m, 4);
        assert_eq!(spin.rolling, Some([0.0, 0.0, 0.005]));
        let frictionless = GeomContact { condim: 1, ..contact }.surface(h, m, 4);
        assert_eq!((frictionless.mu, frictionless.approx1), (0.0, false));
        // A time constant below two steps is raised to two (MuJoCo's refsafe).
        let quick = GeomContact { solref: [0.001, 1.0], ..contact };
        assert_eq!(quick.surface(h, m, 4), GeomContact { solref: [2.0 * h, 1.0], ..contact }.surface(h, m, 4));
    }

    #[test]
    fn bad_parameters_are_refused() {
        let ok = GeomContact::default();
        assert!(ok.validate().is_ok());
        for bad in [
            GeomContact { friction: [-1.0, 0.0, 0.0], ..ok },
            GeomContact { friction: [f64::NAN, 0.0, 0.0], ..ok },
            GeomContact { condim: 2, ..ok },
            GeomContact { solref: [0.02, -1.0], ..ok },
            GeomContact { solref: [0.0, 0.0], ..ok },
            GeomContact { solimp: [0.0, 0.95, 0.001, 0.5, 2.0], ..ok },
            GeomContact { solimp: [0.9, 1.0, 0.001, 0.5, 2.0], ..ok },
            GeomContact { solimp: [0.9, 0.95, 0.0, 0.5, 2.0], ..ok },
            GeomContact { solmix: f64::INFINITY, ..ok },
        ] {
            assert!(bad.validate().is_err(), "{bad:?}");
        }
    }
}
