//! Contact surfaces between two named objects: a wheel's grip on the floor, a gripper's
//! pads, a ball that bounces off one wall only. Every other pair touches with the
//! world's default surface ([`World::set_default_surface`](crate::World::set_default_surface)).

// Looked up for every pair of geoms whose boxes overlap, every step: a fast hash of
// the small integer handles (no input an adversary chooses reaches these keys).
use rustc_hash::{FxHashMap as HashMap, FxHashSet as HashSet};

use super::Scene;
use super::geom_contact::{GeomContact, MUJOCO_CONTACTS_PER_PAIR, reduced_mass};
use crate::contact::{CollisionHooks, ContactSurface, GeomPair};
use crate::error::{Error, Result};
use crate::handle::{GeomHandle, ObjectId, SpaceHandle};
use crate::world::{CollideStepError, CollideStepResult};

/// The surfaces chosen for pairs of objects, and which object each of their geoms
/// belongs to (only the geoms of those objects: the lookup during collision).
#[derive(Debug, Default)]
pub(crate) struct PairSurfaces {
    /// Both orders of each pair.
    by_pair: HashMap<(ObjectId, ObjectId), ContactSurface>,
    /// Pairs that never touch, both orders.
    excluded: HashSet<(ObjectId, ObjectId)>,
    owner: HashMap<GeomHandle, ObjectId>,
    /// The geoms with contact parameters of their own, each with its body's mass
    /// (infinite: static) when they were set.
    geom_contacts: HashMap<GeomHandle, (GeomContact, f64)>,
    /// The time step of the collision under way, s (the geoms' parameters depend on it).
    time_step: f64,
    /// What each pair of geoms met touches with, as worked out the first time (emptied
    /// when anything it depends on changes: a pair's surface or exclusion, a geom's
    /// parameters, the time step; and when it grows past [`MAX_VERDICTS`]): the one
    /// lookup of a step for a pair met before.
    made: HashMap<(GeomHandle, GeomHandle), Verdict>,
    /// Pairs of geoms with parameters of their own, both orders, each with the pair's
    /// reduced mass when they were set.
    pair_contacts: HashMap<(GeomHandle, GeomHandle), (GeomContact, f64)>,
    /// Those pairs, once each, in the order they were first set.
    pair_order: Vec<(GeomHandle, GeomHandle)>,
}

/// What a pair of geoms touches with.
#[derive(Clone, Copy, Debug)]
enum Verdict {
    /// Their objects never touch.
    Apart,
    /// The world's default surface (whatever it is at the time).
    Default,
    /// Their objects' own surface.
    Objects(ContactSurface),
    /// A surface made of the geoms' (or the pair's) parameters, with at most
    /// `max_contacts` points: made again when the world's default changes that.
    Geoms(ContactSurface),
}

/// The most pairs of geoms whose verdicts are kept (about 10 MB); beyond, they are
/// worked out again.
const MAX_VERDICTS: usize = 1 << 16;

impl PairSurfaces {
    pub(crate) fn is_empty(&self) -> bool {
        self.by_pair.is_empty()
            && self.excluded.is_empty()
            && self.geom_contacts.is_empty()
            && self.pair_contacts.is_empty()
    }

    /// Forgets every pair with `object` and its geoms' parameters (it is being removed).
    pub(crate) fn forget(&mut self, object: ObjectId) {
        self.by_pair.retain(|(a, b), _| *a != object && *b != object);
        self.excluded.retain(|(a, b)| *a != object && *b != object);
        let owner = &self.owner;
        self.geom_contacts.retain(|g, _| owner.get(g) != Some(&object));
        let apart = |(a, b): &(GeomHandle, GeomHandle)| owner.get(a) != Some(&object) && owner.get(b) != Some(&object);
        self.pair_contacts.retain(|pair, _| apart(pair));
        self.pair_order.retain(apart);
        self.forget_verdicts();
        self.owner.retain(|_, o| *o != object);
    }

    /// Whether `object` is in any pair or has a geom with parameters of its own (its
    /// geoms must be known).
    fn has(&self, object: ObjectId) -> bool {
        self.by_pair.keys().chain(&self.excluded).any(|(x, _)| *x == object)
            || self
                .geom_contacts
                .keys()
                .chain(self.pair_contacts.keys().map(|(g, _)| g))
                .any(|g| self.owner.get(g) == Some(&object))
    }

    /// Gives `geom` (of `object`, whose body weighs `mass`) parameters of its own.
    pub(super) fn set_geom_contact(&mut self, geom: GeomHandle, object: ObjectId, contact: GeomContact, mass: f64) {
        self.owner.insert(geom, object);
        self.geom_contacts.insert(geom, (contact, mass));
        self.forget_verdicts();
    }

    /// Gives the pair of geoms `a` and `b` (each with its object) parameters of their
    /// own, at the pair's reduced `mass`.
    pub(super) fn set_pair_contact(
        &mut self,
        (a, object_a): (GeomHandle, ObjectId),
        (b, object_b): (GeomHandle, ObjectId),
        contact: GeomContact,
        mass: f64,
    ) {
        self.owner.insert(a, object_a);
        self.owner.insert(b, object_b);
        if !self.pair_contacts.contains_key(&(a, b)) {
            self.pair_order.push((a, b));
        }
        self.pair_contacts.insert((a, b), (contact, mass));
        self.pair_contacts.insert((b, a), (contact, mass));
        self.forget_verdicts();
    }

    /// Each pair of geoms with parameters of its own, once, in the order set.
    pub(super) fn pair_contacts(&self) -> impl Iterator<Item = (GeomHandle, GeomHandle, GeomContact)> + '_ {
        self.pair_order.iter().filter_map(|&(a, b)| self.pair_contacts.get(&(a, b)).map(|(c, _)| (a, b, *c)))
    }

    /// The object `geom` belongs to, if it has parameters of its own or is in a pair that
    /// has.
    pub(super) fn owner(&self, geom: GeomHandle) -> Option<ObjectId> {
        self.owner.get(&geom).copied()
    }

    /// Sets the time step of the collision to come (the surfaces made are forgotten
    /// when it changes).
    pub(super) fn set_time_step(&mut self, dt: f64) {
        if dt != self.time_step {
            self.time_step = dt;
            self.forget_verdicts();
        }
    }

    /// The parameters of `geom`'s own, if any.
    pub(super) fn geom_contact(&self, geom: GeomHandle) -> Option<GeomContact> {
        self.geom_contacts.get(&geom).map(|(c, _)| *c)
    }

    /// Forgets every geom's own parameters (a snapshot restores them).
    pub(crate) fn clear_geom_contacts(&mut self) {
        self.geom_contacts.clear();
        self.pair_contacts.clear();
        self.pair_order.clear();
        self.forget_verdicts();
    }

    /// The surface of two geoms of which one at least has parameters of its own: both
    /// combined (MuJoCo's defaults for one that has none), at their reduced mass.
    fn geom_surface(&self, pair: &GeomPair, most: usize) -> Option<ContactSurface> {
        let own = self.pair_contacts.get(&(pair.geom1, pair.geom2)).copied();
        let (first, second) = (self.geom_contacts.get(&pair.geom1), self.geom_contacts.get(&pair.geom2));
        if first.is_none() && second.is_none() && own.is_none() {
            return None;
        }
        let surface = match own {
            // A pair's own parameters, as they are.
            Some((contact, mass)) => contact.surface(self.time_step, mass, most),
            None => {
                let unknown = (GeomContact::default(), f64::INFINITY);
                let ((a, mass_a), (b, mass_b)) = (first.unwrap_or(&unknown), second.unwrap_or(&unknown));
                a.combined(b).surface(self.time_step, reduced_mass(*mass_a, *mass_b), most)
            }
        };
        Some(surface)
    }

    /// What `pair` touches with, worked out from the pairs, exclusions and parameters.
    fn verdict(&self, pair: &GeomPair, most: usize) -> Verdict {
        let owners = (self.owner.get(&pair.geom1), self.owner.get(&pair.geom2));
        if let (Some(a), Some(b)) = owners {
            if self.excluded.contains(&(*a, *b)) {
                return Verdict::Apart;
            }
            if let Some(surface) = self.by_pair.get(&(*a, *b)) {
                return Verdict::Objects(*surface);
            }
        }
        self.geom_surface(pair, most).map_or(Verdict::Default, Verdict::Geoms)
    }

    /// Forgets every verdict (something they depend on changed).
    fn forget_verdicts(&mut self) {
        self.made.clear();
    }
}

impl CollisionHooks for PairSurfaces {
    fn contact_surface(&mut self, pair: &GeomPair, default: &ContactSurface) -> Option<ContactSurface> {
        // A surface of geoms' parameters has at most MuJoCo's points per pair.
        let most = default.max_contacts.min(MUJOCO_CONTACTS_PER_PAIR);
        let key = (pair.geom1, pair.geom2);
        let verdict = match self.made.get(&key) {
            Some(Verdict::Geoms(surface)) if surface.max_contacts != most => None,
            Some(verdict) => Some(*verdict),
            None => None,
        };
        let verdict = verdict.unwrap_or_else(|| {
            let verdict = self.verdict(pair, most);
            if self.made.len() >= MAX_VERDICTS {
                self.forget_verdicts();
            }
            self.made.insert(key, verdict);
            verdict
        });
        match verdict {
            Verdict::Apart => None,
            Verdict::Default => Some(*default),
            Verdict::Objects(surface) | Verdict::Geoms(surface) => Some(surface),
        }
    }
}

impl Scene {
    /// Gives the contacts between objects `a` and `b` their own surface (friction,
    /// bounce, softness, most contact points), in place of the world's default surface.
    /// Setting it again replaces it; [`clear_contact_surface`](Self::clear_contact_surface)
    /// goes back to the default. A pair that includes a removed object is forgotten.
    ///
    /// ```
    /// use ars_core::{ContactSurface, Mass, Simulation};
    ///
    /// let mut sim = Simulation::builder().floor_plane(nalgebra::Vector3::y(), 0.0).build()?;
    /// let floor = sim.scene().object("floor")?.id();
    /// let puck = sim.scene_mut().add_box([0.2, 0.1, 0.2], [0.0, 0.05, 0.0], Mass::Total(1.0))?;
    /// sim.scene_mut().set_contact_surface(floor, puck, ContactSurface { mu: 0.0, bounce: None, ..Default::default() })?;
    /// sim.scene_mut().body_mut(puck)?.set_linear_velocity([1.0, 0.0, 0.0].into())?;
    /// sim.run_for(1.0)?;
    /// assert!(sim.scene().position(puck)?.x > 0.99, "no friction: it slides on");
    /// # Ok::<(), ars_core::Error>(())
    /// ```
    pub fn set_contact_surface(&mut self, a: ObjectId, b: ObjectId, surface: ContactSurface) -> Result<()> {
        surface.validate()?;
        self.own_geoms(a, b)?;
        self.pair_surfaces.by_pair.insert((a, b), surface);
        self.pair_surfaces.by_pair.insert((b, a), surface);
        self.pair_surfaces.forget_verdicts();
        Ok(())
    }

    /// The surface of the contacts between `a` and `b`: their own, or the world's
    /// default.
    pub fn contact_surface(&self, a: ObjectId, b: ObjectId) -> Result<ContactSurface> {
        self.object(a)?;
        self.object(b)?;
        Ok(self.pair_surfaces.by_pair.get(&(a, b)).copied().unwrap_or_else(|| self.world.default_surface()))
    }

    /// Gives the contacts between `a` and `b` the world's default surface again.
    pub fn clear_contact_surface(&mut self, a: ObjectId, b: ObjectId) -> Result<()> {
        self.object(a)?;
        self.object(b)?;
        self.pair_surfaces.by_pair.remove(&(a, b));
        self.pair_surfaces.by_pair.remove(&(b, a));
        self.pair_surfaces.forget_verdicts();
        self.forget_unpaired(a, b);
        Ok(())
    }

    /// Objects `a` and `b` never touch (MJCF's `<contact><exclude>`): their geoms pass
    /// through each other, whatever their collision bits and surface. Kept by scene
    /// files and snapshots; [`include_contacts`](Self::include_contacts) undoes it.
    ///
    /// ```
    /// use ars_core::{Mass, Simulation};
    ///
    /// let mut sim = Simulation::builder().floor_plane(nalgebra::Vector3::y(), 0.0).build()?;
    /// let floor = sim.scene().object("floor")?.id();
    /// let ghost = sim.scene_mut().add_sphere(0.1, [0.0, 0.5, 0.0], Mass::Total(1.0))?;
    /// sim.scene_mut().exclude_contacts(floor, ghost)?;
    /// sim.run_for(1.0)?;
    /// assert!(sim.scene().position(ghost)?.y < -1.0, "it fell through the floor");
    /// # Ok::<(), ars_core::Error>(())
    /// ```
    pub fn exclude_contacts(&mut self, a: ObjectId, b: ObjectId) -> Result<()> {
        if a == b {
            return Err(Error::Invalid {
                what: "a pair without contacts",
                problem: format!("needs two objects, and {:?} is given twice", self.object(a)?.name()),
            });
        }
        self.own_geoms(a, b)?;
        self.pair_surfaces.excluded.insert((a, b));
        self.pair_surfaces.excluded.insert((b, a));
        self.pair_surfaces.forget_verdicts();
        Ok(())
    }

    /// Objects `a` and `b` touch again (see [`exclude_contacts`](Self::exclude_contacts)).
    pub fn include_contacts(&mut self, a: ObjectId, b: ObjectId) -> Result<()> {
        self.object(a)?;
        self.object(b)?;
        self.pair_surfaces.excluded.remove(&(a, b));
        self.pair_surfaces.excluded.remove(&(b, a));
        self.pair_surfaces.forget_verdicts();
        self.forget_unpaired(a, b);
        Ok(())
    }

    /// Every pair of objects that never touch, once each, by the objects' names in
    /// alphabetical order.
    pub fn excluded_contacts(&self) -> Vec<(ObjectId, ObjectId)> {
        let name = |id: &ObjectId| self.object(*id).map(|o| o.name()).unwrap_or_default();
        let mut pairs: Vec<_> =
            self.pair_surfaces.excluded.iter().filter(|(a, b)| name(a) <= name(b)).copied().collect();
        pairs.sort_by(|x, y| (name(&x.0), name(&x.1)).cmp(&(name(&y.0), name(&y.1))));
        pairs
    }

    /// Records which object the geoms of `a` and `b` belong to (the collision's lookup).
    fn own_geoms(&mut self, a: ObjectId, b: ObjectId) -> Result<()> {
        let geoms = |scene: &Scene, id: ObjectId| -> Result<Vec<GeomHandle>> {
            let data = scene.objects.get(id.0, ObjectId::KIND)?;
            Ok(data.geom.iter().chain(&data.extra_geoms).copied().collect())
        };
        let (geoms_a, geoms_b) = (geoms(self, a)?, geoms(self, b)?);
        for g in geoms_a {
            self.pair_surfaces.owner.insert(g, a);
        }
        for g in geoms_b {
            self.pair_surfaces.owner.insert(g, b);
        }
        Ok(())
    }

    /// Forgets the geoms of `a` and `b` when they are in no pair any more.
    fn forget_unpaired(&mut self, a: ObjectId, b: ObjectId) {
        for object in [a, b] {
            if !self.pair_surfaces.has(object) {
                self.pair_surfaces.owner.retain(|_, o| *o != object);
            }
        }
    }

    /// Every pair of objects with a surface of its own, once each, by the objects' names
    /// in alphabetical order.
    pub fn contact_surfaces(&self) -> Vec<(ObjectId, ObjectId, ContactSurface)> {
        let name = |id: &ObjectId| self.object(*id).map(|o| o.name()).unwrap_or_default();
        let mut pairs: Vec<_> = self
            .pair_surfaces
            .by_pair
            .iter()
            .filter(|((a, b), _)| name(a) <= name(b))
            .map(|(&(a, b), s)| (a, b, *s))
            .collect();
        pairs.sort_by(|x, y| (name(&x.0), name(&x.1)).cmp(&(name(&y.0), name(&y.1))));
        pairs
    }

    /// Collides the scene's space (the pairs with a surface of their own get it, every
    /// other pair the world's default), steps the world by the scene's time step and
    /// destroys the contact joints: the error says which of the two failed (see
    /// [`World::collide_and_step`](crate::World)).
    #[inline(always)]
    pub(crate) fn collide_and_step(&mut self) -> CollideStepResult {
        if self.pair_surfaces.is_empty() {
            // The handle by reference: read where it is compared, not kept from here.
            self.world.collide_and_step(&self.space, self.time_step)
        } else {
            self.collide_with_surfaces_and_step(self.space, self.time_step.get())
        }
    }

    #[inline(never)]
    fn collide_with_surfaces_and_step(&mut self, space: SpaceHandle, dt: f64) -> CollideStepResult {
        self.pair_surfaces.set_time_step(dt);
        if let Err(e) = self.world.collide_with(space, &mut self.pair_surfaces) {
            return Err(Box::new(CollideStepError::Collide(e)));
        }
        self.world.step(dt).map_err(|e| Box::new(CollideStepError::Step(e)))?;
        self.world.clear_contacts();
        Ok(())
    }
}
