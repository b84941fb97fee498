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

/// Repeats each actuator and sensor that names a replicated joint, body or site once
/// per copy, named with the copy's suffix, in MuJoCo's order: those that name nothing
/// replicated first, then copy by copy, in the file's order within each.
pub(super) fn replicate_references(model: &mut Model, replicas: &Replicas) {
    if replicas.is_empty() {
        return;
    }
    let actuators = std::mem::take(&mut model.actuators).into_iter().map(|a| {
        let key = (Named::Joint, a.joint.clone());
        (key, a)
    });
    model.actuators = repeated(actuators, replicas, |a, s| {
        let mut copy = a.clone();
        copy.name = format!("{}{s}", a.name);
        copy.joint = format!("{}{s}", a.joint);
        copy
    });
    let sensors = std::mem::take(&mut model.sensors).into_iter().zip(std::mem::take(&mut model.sensor_places));
    let sensors = sensors.map(|(sensor, place)| {
        let kind = match sensor.objtype.as_str() {
            "joint" => Named::Joint,
            "site" => Named::Site,
            "geom" => Named::Geom,
            _ => Named::Body,
        };
        ((kind, sensor.target.clone()), (sensor, place))
    });
    let sensors = repeated(sensors, replicas, |(sensor, place), s| {
        let mut copy = sensor.clone();
        copy.name = format!("{}{s}", sensor.name);
        copy.target = format!("{}{s}", sensor.target);
        (copy, place.clone())
    });
    (model.sensors, model.sensor_places) = sensors.into_iter().unzip();
    // Exclusions, pairs and equalities too, as MuJoCo repeats them: each name of a
    // copy that the copy replicated takes its suffix.
    let bodies = |(a, b): &(String, String)| vec![(Named::Body, a.clone()), (Named::Body, b.clone())];
    model.excluded = repeated_with(std::mem::take(&mut model.excluded), replicas, bodies, |(a, b), rename| {
        (rename(Named::Body, a), rename(Named::Body, b))
    });
    let geoms = |p: &Pair| vec![(Named::Geom, p.geom1.clone()), (Named::Geom, p.geom2.clone())];
    model.pairs = repeated_with(std::mem::take(&mut model.pairs), replicas, geoms, |p, rename| Pair {
        geom1: rename(Named::Geom, &p.geom1),
        geom2: rename(Named::Geom, &p.geom2),
        contact: p.contact,
    });
    model.equalities = repeated_with(std::mem::take(&mut model.equalities), replicas, equality_names, |e, rename| {
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
        Equality { kind, ..e.clone() }
    });
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

/// `items`, each that names a replicated element (of the names `names` gives)
/// repeated by `copy` once per copy of the first such name, where `rename` suffixes
/// each name that copy replicated; in MuJoCo's order, as [`repeated`].
fn repeated_with<T>(
    items: Vec<T>,
    replicas: &Replicas,
    names: impl Fn(&T) -> Vec<(Named, String)>,
    copy: impl Fn(&T, &Rename<'_>) -> T,
) -> Vec<T> {
    let mut kept = Vec::new();
    let mut copies = Vec::new();
    for item in items {
        let Some(made) = names(&item).into_iter().find_map(|key| replicas.get(&key)) else {
            kept.push(item);
            continue;
        };
        for (n, suffix) in made {
            let rename = |kind: Named, name: &str| match replicas.get(&(kind, name.to_string())) {
                Some(copies) if copies.iter().any(|(_, s)| s == suffix) => format!("{name}{suffix}"),
                _ => name.to_string(),
            };
            copies.push((*n, copy(&item, &rename)));
        }
    }
    copies.sort_by_key(|(n, _)| *n);
    kept.extend(copies.into_iter().map(|(_, item)| item));
    kept
}

/// `items` (each with the name it refers to), those referring to a replicated name
/// repeated by `copy` once per copy of it, in MuJoCo's order.
fn repeated<T>(
    items: impl Iterator<Item = ((Named, String), T)>,
    replicas: &Replicas,
    copy: impl Fn(&T, &str) -> T,
) -> Vec<T> {
    let mut kept = Vec::new();
    let mut copies = Vec::new();
    for (key, item) in items {
        match replicas.get(&key) {
            Some(made) => copies.extend(made.iter().map(|(n, suffix)| (*n, copy(&item, suffix)))),
            None => kept.push(item),
        }
    }
    // Stable: within a copy, the file's order.
    copies.sort_by_key(|(n, _)| *n);
    kept.extend(copies.into_iter().map(|(_, item)| item));
    kept
}
