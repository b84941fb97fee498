//! `<frame>` and `<replicate>`, as MuJoCo reads them: neither is a body. A frame
//! places what it holds (and gives it its `childclass`); a replicate repeats what it
//! holds `count` times, each copy moved by its `offset` and turned by its `euler` once
//! more than the one before, every name in copy `i` suffixed with `sep` and `i`
//! (zero-padded to the digits of `count`; a nested replicate's suffix first). The
//! actuators and sensors that name a replicated joint, body or site are repeated with
//! it, as MuJoCo repeats them.

use nalgebra::{Isometry3, Translation3, Vector3};

use super::defaults::{Attrs, euler_turn, frame};
use super::model::{Equality, EqualityKind, Model, Pair, Place};
use super::problem::{Parsed, problem};
use super::read::Reader;

/// Most elements a model's `<replicate>`s may make, all copies and all nesting counted
/// (a hostile count is refused before it is made).
pub const MAX_REPLICATED: usize = 100_000;

/// An element read inside `<frame>`s and `<replicate>`s: where they put it in its body,
/// with the class and name suffix it takes there.
pub(super) struct Placed<'a, 'input> {
    pub(super) node: roxmltree::Node<'a, 'input>,
    pub(super) class: String,
    pub(super) frame: Isometry3<f64>,
    pub(super) suffix: String,
    /// The innermost replicate copy it is in (numbered in the order made; 0 outside).
    pub(super) copy: usize,
}

impl<'a, 'input> Reader<'_, 'a, 'input> {
    /// The elements of the body (or world body) `node` of class `class`, with those of
    /// its frames and replicates in their place, in the file's order.
    pub(super) fn placed_children(
        &mut self,
        node: roxmltree::Node<'a, 'input>,
        class: &str,
    ) -> Parsed<Vec<Placed<'a, 'input>>> {
        let mut out = Vec::new();
        let (suffix, copy) = (self.suffix.clone(), self.copy);
        self.place_children(node, class, &Isometry3::identity(), (&suffix, copy), false, &mut out)?;
        Ok(out)
    }

    /// `node`'s children placed at `at`; `replicated`: `node` is a `<replicate>` or in
    /// one without a body between (a joint there is refused, as MuJoCo refuses it).
    fn place_children(
        &mut self,
        node: roxmltree::Node<'a, 'input>,
        class: &str,
        at: &Isometry3<f64>,
        (suffix, copy): (&str, usize),
        replicated: bool,
        out: &mut Vec<Placed<'a, 'input>>,
    ) -> Parsed<()> {
        for child in self.tree.elements(node) {
            match child.tag_name().name() {
                "frame" => {
                    let placed = at * frame(&Attrs::new(child, self.defaults, class), &self.compiler)?;
                    let class = child.attribute("childclass").unwrap_or(class);
                    self.place_children(child, class, &placed, (suffix, copy), replicated, out)?;
                }
                "replicate" => self.replicate(child, class, at, suffix, out)?,
                "joint" | "freejoint" if replicated => {
                    return Err(problem(
                        &child,
                        "a joint cannot be a direct child of <replicate>, nor in a <frame> of one (MuJoCo refuses it \
                         too): put it in a <body> in the replicate",
                    ));
                }
                _ => {
                    if !suffix.is_empty() {
                        self.count_replicated(&child)?;
                    }
                    let class = class.to_string();
                    out.push(Placed { node: child, class, frame: *at, suffix: suffix.to_string(), copy });
                }
            }
        }
        Ok(())
    }

    /// The copies of a `<replicate>`'s elements.
    fn replicate(
        &mut self,
        node: roxmltree::Node<'a, 'input>,
        class: &str,
        at: &Isometry3<f64>,
        suffix: &str,
        out: &mut Vec<Placed<'a, 'input>>,
    ) -> Parsed<()> {
        let a = Attrs::new(node, self.defaults, class);
        let count = node.attribute("count").ok_or_else(|| problem(&node, "a <replicate> needs a count"))?;
        let count: i64 =
            count.trim().parse().map_err(|_| problem(&node, format!("count {count:?} is not a whole number")))?;
        let offset = Vector3::from(a.fixed::<3>("offset")?.unwrap_or([0.0; 3]));
        // Only `euler` turns a copy (MuJoCo reads no other orientation here).
        let turn = euler_turn(a.fixed::<3>("euler")?.unwrap_or([0.0; 3]), &self.compiler);
        let step = Isometry3::from_parts(Translation3::from(offset), turn);
        let sep = node.attribute("sep").unwrap_or("");
        let width = count.max(0).to_string().len();
        let mut copy = *at;
        for i in 0..count.max(0) {
            self.count_replicated(&node)?;
            let suffix = format!("{sep}{i:0width$}{suffix}");
            self.place_children(node, class, &copy, (&suffix, self.replicated), true, out)?;
            copy *= step;
        }
        Ok(())
    }

    /// Counts one more element or copy made by a replicate; refuses the one beyond
    /// [`MAX_REPLICATED`].
    pub(super) fn count_replicated(&mut self, node: &roxmltree::Node<'_, '_>) -> Parsed<()> {
        self.replicated += 1;
        if self.replicated > MAX_REPLICATED {
            return Err(problem(
                node,
                format!("the model's <replicate>s make more than {MAX_REPLICATED} elements and copies"),
            ));
        }
        Ok(())
    }

    /// `name` as the element being read is called: with its replicate's suffix, which
    /// is noted for the actuators and sensors that name it.
    pub(super) fn renamed(&mut self, kind: Named, name: &str) -> String {
        if self.suffix.is_empty() {
            return name.to_string();
        }
        self.replicas.entry((kind, name.to_string())).or_default().push((self.copy, self.suffix.clone()));
        format!("{name}{}", self.suffix)
    }
}

/// What a replicated name names (MuJoCo's names are per kind of element).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(super) enum Named {
    Body,
    Joint,
    Geom,
    Site,
}

/// The copies of each replicated name (which copy, its suffix), in the order read.
pub(super) type Replicas = std::collections::HashMap<(Named, String), Vec<(usize, String)>>;

/// Repeats each actuator, sensor, equality, contact exclusion and `<pair>` that names
/// a replicated element once per copy of it, in MuJoCo's order: those that name
/// nothing replicated first, then copy by copy, in the file's order within each. In a
/// copy, every name the copy replicated takes its suffix, and so does the element's
/// own name. Refused (the text) when the copies would pass [`MAX_REPLICATED`]: a few
/// lines naming an element replicated many times must not make billions.
pub(super) fn replicate_references(model: &mut Model, replicas: &Replicas) -> Result<(), String> {
    if replicas.is_empty() {
        return Ok(());
    }
    let mut budget = MAX_REPLICATED;
    let mut r = Repeater { replicas, budget: &mut budget };
    let joint = |a: &super::MjcfActuator| vec![(Named::Joint, a.joint.clone())];
    model.actuators = r.repeat(std::mem::take(&mut model.actuators), joint, |a, suffix, rename| {
        let mut copy = a.clone();
        copy.name = format!("{}{suffix}", a.name);
        copy.joint = rename(Named::Joint, &a.joint);
        copy
    })?;
    let sensors: Vec<_> =
        std::mem::take(&mut model.sensors).into_iter().zip(std::mem::take(&mut model.sensor_places)).collect();
    let target = |(sensor, _): &(super::MjcfSensor, _)| {
        let kind = match sensor.objtype.as_str() {
            "joint" => Named::Joint,
            "site" => Named::Site,
            "geom" => Named::Geom,
            _ => Named::Body,
        };
        vec![(kind, sensor.target.clone())]
    };
    let sensors = r.repeat(sensors, target, |(sensor, place), suffix, _| {
        let mut copy = sensor.clone();
        copy.name = format!("{}{suffix}", sensor.name);
        copy.target = format!("{}{suffix}", sensor.target);
        (copy, place.clone())
    })?;
    (model.sensors, model.sensor_places) = sensors.into_iter().unzip();
    let bodies = |(a, b): &(String, String)| vec![(Named::Body, a.clone()), (Named::Body, b.clone())];
    model.excluded = r.repeat(std::mem::take(&mut model.excluded), bodies, |(a, b), _, rename| {
        (rename(Named::Body, a), rename(Named::Body, b))
    })?;
    let geoms = |p: &Pair| vec![(Named::Geom, p.geom1.clone()), (Named::Geom, p.geom2.clone())];
    model.pairs = r.repeat(std::mem::take(&mut model.pairs), geoms, |p, _, rename| Pair {
        geom1: rename(Named::Geom, &p.geom1),
        geom2: rename(Named::Geom, &p.geom2),
        contact: p.contact,
    })?;
    model.equalities = r.repeat(std::mem::take(&mut model.equalities), equality_names, |e, suffix, rename| {
        let place = |p: &Place| match p {
            Place::Body(n) => Place::Body(rename(Named::Body, n)),
            Place::Site(n) => Place::Site(rename(Named::Site, n)),
        };
        let kind = match &e.kind {
            EqualityKind::Connect { first, second, anchor } => {
                EqualityKind::Connect { first: place(first), second: second.as_ref().map(place), anchor: *anchor }
            }
            EqualityKind::Weld { first, second, relpose } => {
                EqualityKind::Weld { first: place(first), second: second.as_ref().map(place), relpose: *relpose }
            }
            EqualityKind::Joint { follower, leader, polycoef } => EqualityKind::Joint {
                follower: rename(Named::Joint, follower),
                leader: leader.as_ref().map(|l| rename(Named::Joint, l)),
                polycoef: *polycoef,
            },
        };
        Equality { name: e.name.as_ref().map(|n| format!("{n}{suffix}")), kind, ..e.clone() }
    })?;
    Ok(())
}

/// The names an equality refers to.
fn equality_names(e: &Equality) -> Vec<(Named, String)> {
    let place = |p: &Place| match p {
        Place::Body(n) => (Named::Body, n.clone()),
        Place::Site(n) => (Named::Site, n.clone()),
    };
    match &e.kind {
        EqualityKind::Connect { first, second, .. } | EqualityKind::Weld { first, second, .. } => {
            std::iter::once(first).chain(second.as_ref()).map(place).collect()
        }
        EqualityKind::Joint { follower, leader, .. } => {
            std::iter::once(follower).chain(leader.as_ref()).map(|j| (Named::Joint, j.clone())).collect()
        }
    }
}

/// A renaming: a name of a kind as the copy under way calls it.
type Rename<'r> = dyn Fn(Named, &str) -> String + 'r;

/// Repeats the elements that name replicated ones, within a budget of copies.
struct Repeater<'r> {
    replicas: &'r Replicas,
    budget: &'r mut usize,
}

impl Repeater<'_> {
    /// `items`, each that names a replicated element (of the names `names` gives)
    /// repeated by `copy` (given the copy's suffix and its renaming) once per copy of
    /// the first such name.
    fn repeat<T>(
        &mut self,
        items: Vec<T>,
        names: impl Fn(&T) -> Vec<(Named, String)>,
        copy: impl Fn(&T, &str, &Rename<'_>) -> T,
    ) -> Result<Vec<T>, String> {
        let replicas = self.replicas;
        let mut kept = Vec::new();
        let mut copies = Vec::new();
        for item in items {
            let Some(made) = names(&item).into_iter().find_map(|key| replicas.get(&key)) else {
                kept.push(item);
                continue;
            };
            *self.budget = self.budget.checked_sub(made.len()).ok_or_else(|| {
                format!(
                    "the model's <replicate>s repeat the actuators, sensors, equalities, exclusions and pairs that \
                     name what they replicate into more than {MAX_REPLICATED} elements"
                )
            })?;
            for (n, suffix) in made {
                let rename = |kind: Named, name: &str| match replicas.get(&(kind, name.to_string())) {
                    Some(copies) if copies.iter().any(|(_, s)| s == suffix) => format!("{name}{suffix}"),
                    _ => name.to_string(),
                };
                copies.push((*n, copy(&item, suffix, &rename)));
            }
        }
        // Stable: within a copy, the file's order.
        copies.sort_by_key(|(n, _)| *n);
        kept.extend(copies.into_iter().map(|(_, item)| item));
        Ok(kept)
    }
}
