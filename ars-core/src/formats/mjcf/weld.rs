//! Jointless bodies welded as MuJoCo welds them: a body without joints moves with its
//! parent (MuJoCo's `body_weldid`), one rigid body with it. It is merged into the body
//! it is welded to: its mass combined with that body's about their common centre, its
//! geoms at their offsets on that body's ODE body, its sites and children placed
//! through it. A chain of ODE bodies held by fixed joints would be that rigid body only
//! as nearly as the solver holds them, and not at all when one weighs grams against
//! its neighbour's kilograms (robot files write 1e-8 kg hands). Of the world body, one
//! that weighs nothing is merged into the world (its geoms static); one with mass stays
//! an ODE body of its own, kinematic (nothing moves it), its jointless descendants
//! merged into it.
//! A mocap body is never merged into the world: it is a kinematic ODE body of its own
//! (with its jointless descendants), which the user moves.

use nalgebra::Isometry3;

use super::model::{Body, Model, Welded};

use crate::formats::{combined_mass, moved_mass};

/// Merges the model's jointless bodies into the bodies they are welded to (the
/// massless ones of the world into the world); each merged body is listed in
/// `model.welded`.
pub(super) fn weld_jointless(model: &mut Model) {
    let mut top = Vec::new();
    for body in std::mem::take(&mut model.bodies) {
        into_world(body, &Isometry3::identity(), model, &mut top);
    }
    for body in &mut top {
        merge_children(body, &mut model.welded);
    }
    model.bodies = top;
}

/// A body of the world (or of a body merged into it) whose parent's frame is `parent`:
/// massless and jointless, its geoms become the world's and its children are looked at
/// in turn; any other goes to `top`.
fn into_world(mut body: Body, parent: &Isometry3<f64>, model: &mut Model, top: &mut Vec<Body>) {
    body.frame = parent * body.frame;
    // A mocap body moves (the user moves it): never merged into the world.
    if body.mocap || !(body.joints.is_empty() && body.mass.is_none()) {
        top.push(body);
        return;
    }
    for mut geom in body.geoms {
        geom.frame = body.frame * geom.frame;
        model.world_geoms.push(geom);
    }
    model.world_sites.extend(body.sites.into_iter().map(|s| s.name));
    model.welded.push(Welded { name: body.name, into: None, frame: body.frame, mass: None, principal: body.principal });
    for child in body.children {
        into_world(child, &body.frame, model, top);
    }
}

/// Merges into `body` its jointless children, then does the same in each child it
/// keeps.
fn merge_children(body: &mut Body, welded: &mut Vec<Welded>) {
    for child in std::mem::take(&mut body.children) {
        merge(body, child, &Isometry3::identity(), welded);
    }
    for child in &mut body.children {
        merge_children(child, welded);
    }
}

/// Merges `child`, whose parent's frame is `parent` in `body`'s frame, into `body` when
/// it is jointless, with its own children in turn; else makes it a child of `body`.
fn merge(body: &mut Body, mut child: Body, parent: &Isometry3<f64>, welded: &mut Vec<Welded>) {
    child.frame = parent * child.frame;
    if !child.joints.is_empty() {
        body.children.push(child);
        return;
    }
    let frame = child.frame;
    for mut geom in child.geoms {
        geom.frame = frame * geom.frame;
        body.geoms.push(geom);
    }
    for mut site in child.sites {
        site.frame = frame * site.frame;
        site.welded_from.get_or_insert_with(|| child.name.clone());
        body.sites.push(site);
    }
    if let Some(mass) = child.mass {
        body.mass = Some(combined_mass(body.mass, moved_mass(mass, &frame)));
        // The combined body's principal axes are not the ones its `<inertial>` gave.
        body.principal = None;
    }
    welded.push(Welded {
        name: child.name,
        into: Some(body.name.clone()),
        frame,
        mass: child.mass,
        principal: child.principal,
    });
    for grandchild in child.children {
        merge(body, grandchild, &frame, welded);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Matrix3, Vector3};

    /// Two unit point masses 2 m apart along x, each with a unit sphere's inertia: the
    /// centre between them, 2 kg, and 1 kg·m² each added across x by the parallel axes.
    #[test]
    fn two_masses_combine_about_their_common_centre() {
        let inertia = Matrix3::identity() * 0.4;
        let a = (1.0, Vector3::zeros(), inertia);
        let b = moved_mass((1.0, Vector3::zeros(), inertia), &Isometry3::translation(2.0, 0.0, 0.0));
        let (mass, com, total) = combined_mass(Some(a), b);
        assert_eq!((mass, com), (2.0, Vector3::new(1.0, 0.0, 0.0)));
        assert!((total - Matrix3::from_diagonal(&Vector3::new(0.8, 2.8, 2.8))).norm() < 1e-12, "{total}");
        assert_eq!(combined_mass(None, b), b);
    }
}
