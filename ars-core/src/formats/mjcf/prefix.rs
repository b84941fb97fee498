//! [`MjcfOptions::prefix`](super::MjcfOptions::prefix): every name of a read model prefixed, as MuJoCo's `attach`
//! prefixes an attached model's, so that two copies of a model (two robots of one file)
//! share a simulation: bodies, joints, geoms, sites, actuators, sensors, and every
//! reference to them (exclusions, pairs, equalities, what a sensor reads). The world
//! body (`world`) stays the world.

use super::model::{Body, EqualityKind, Model, Place};

/// Prefixes every name of `model` with `prefix`.
pub(super) fn prefix_names(model: &mut Model, prefix: &str) {
    let p = |name: &mut String| {
        if name != "world" {
            name.insert_str(0, prefix);
        }
    };
    for g in &mut model.world_geoms {
        g.name.as_mut().map(p);
    }
    for body in &mut model.bodies {
        prefix_body(body, &p);
    }
    for a in &mut model.actuators {
        p(&mut a.name);
        p(&mut a.joint);
        a.actuator.rename(a.name.clone());
    }
    let pairs = model.pairs.iter_mut().map(|q| (&mut q.geom1, &mut q.geom2));
    for (a, b) in model.excluded.iter_mut().map(|(a, b)| (a, b)).chain(pairs) {
        p(a);
        p(b);
    }
    for s in &mut model.sensors {
        p(&mut s.name);
        p(&mut s.target);
    }
    model.world_sites.iter_mut().for_each(p);
    for w in &mut model.welded {
        p(&mut w.name);
        w.into.as_mut().map(p);
    }
    for e in &mut model.equalities {
        e.name.as_mut().map(p);
        match &mut e.kind {
            EqualityKind::Connect { first, second, .. } | EqualityKind::Weld { first, second, .. } => {
                for place in std::iter::once(first).chain(second.as_mut()) {
                    match place {
                        Place::Body(name) | Place::Site(name) => p(name),
                    }
                }
            }
            EqualityKind::Joint { follower, leader, .. } => {
                p(follower);
                leader.as_mut().map(p);
            }
        }
    }
}

fn prefix_body(body: &mut Body, p: &dyn Fn(&mut String)) {
    p(&mut body.name);
    for g in &mut body.geoms {
        g.name.as_mut().map(p);
    }
    for j in &mut body.joints {
        p(&mut j.name);
    }
    for s in &mut body.sites {
        p(&mut s.name);
        s.welded_from.as_mut().map(p);
    }
    for child in &mut body.children {
        prefix_body(child, p);
    }
}
