//! Massless links that move: ODE needs a positive mass on every body, and URDF files
//! leave links massless between joints (human models' `*_virtual` links between the
//! hinges of a hip, a fingertip with no `<inertial>`), which PyBullet's Featherstone
//! solver accepts. Such a link is lent a small mass by the nearest link with mass
//! (above it in the tree, else below it): the lender keeps its centre of mass, and its
//! mass and inertia shrink by the same factor, so that the robot's total mass is the
//! file's exactly (but for the rounding of a sum). The mass lent is
//! [`LENT_FRACTION`] of the lender's, less when many links borrow from it (at most
//! [`LENT_AT_MOST`] of it in all); the borrower's inertia is that of a solid sphere of
//! water of that mass (if it declares none), at its own `<inertial>` origin.

use std::collections::HashMap;

use super::model::{JointType, Robot};
use crate::formats::balance::balance_inertia;
use crate::formats::inertia_tensor;

/// The share of its mass a link lends to each massless moving link that borrows from
/// it.
pub(super) const LENT_FRACTION: f64 = 1e-3;
/// The largest share of its mass a link lends in all.
pub(super) const LENT_AT_MOST: f64 = 0.05;

/// Lends mass to every massless link that moves (see the [module docs](self)), with a
/// line per loan; `None` when no link needed one. A link that finds no lender keeps no
/// mass (and is refused when built). The robot's tree is assumed checked only loosely:
/// links a joint names but the file lacks are passed over.
pub(super) fn lend_masses(robot: &Robot) -> Option<(Robot, Vec<String>)> {
    let index: HashMap<&str, usize> = robot.links.iter().enumerate().map(|(i, l)| (l.name.as_str(), i)).collect();
    // Each link's parent link and whether its joint is fixed.
    let mut parent: Vec<Option<(usize, bool)>> = vec![None; robot.links.len()];
    for joint in &robot.joints {
        if let (Some(&p), Some(&c)) = (index.get(joint.parent.link.as_str()), index.get(joint.child.link.as_str())) {
            parent[c] = Some((p, joint.joint_type == JointType::Fixed));
        }
    }
    let massless = |i: usize| robot.links[i].inertial.mass.value == 0.0;
    // A link that moves: held by a joint that is not fixed (a massless link held fixed
    // is merged into its parent's body instead; a massless root is static).
    let borrowers: Vec<usize> =
        (0..robot.links.len()).filter(|&i| massless(i) && parent[i].is_some_and(|(_, fixed)| !fixed)).collect();
    if borrowers.is_empty() {
        return None;
    }
    let loans: Vec<(usize, usize)> =
        borrowers.iter().filter_map(|&b| lender(robot, &parent, b).map(|lender| (b, lender))).collect();
    let mut lent_robot = robot.clone();
    let mut notes = Vec::new();
    for &(borrower, lender) in &loans {
        let borrowers_of_lender = loans.iter().filter(|(_, l)| *l == lender).count() as f64;
        let fraction = LENT_FRACTION.min(LENT_AT_MOST / borrowers_of_lender);
        let declared = robot.links[lender].inertial.mass.value;
        let lent = fraction * declared;
        let giver = &mut lent_robot.links[lender].inertial;
        let kept = (giver.mass.value - lent) / giver.mass.value;
        giver.mass.value -= lent;
        let i = &mut giver.inertia;
        for moment in [&mut i.ixx, &mut i.iyy, &mut i.izz, &mut i.ixy, &mut i.ixz, &mut i.iyz] {
            *moment *= kept;
        }
        let taker = &mut lent_robot.links[borrower].inertial;
        taker.mass.value = lent;
        let t = &taker.inertia;
        let declared_inertia = inertia_tensor([t.ixx, t.iyy, t.izz, t.ixy, t.ixz, t.iyz]);
        if let Some(sphere) = balance_inertia(lent, &declared_inertia).filter(|_| declared_inertia.norm() == 0.0) {
            let m = sphere.inertia;
            let t = &mut taker.inertia;
            (t.ixx, t.iyy, t.izz, t.ixy, t.ixz, t.iyz) =
                (m[(0, 0)], m[(1, 1)], m[(2, 2)], m[(0, 1)], m[(0, 2)], m[(1, 2)]);
        }
        notes.push(format!(
            "link {:?}: massless, but it moves: lent {lent:e} kg ({} % of its mass) by link {:?}, whose mass and \
             inertia shrink alike (the total mass is the file's)",
            robot.links[borrower].name,
            fraction * 100.0,
            robot.links[lender].name
        ));
    }
    Some((lent_robot, notes))
}

/// The link that lends `borrower` mass: the nearest link with mass above it, else the
/// nearest below it (breadth first); `None` when the robot has none.
fn lender(robot: &Robot, parent: &[Option<(usize, bool)>], borrower: usize) -> Option<usize> {
    let has_mass = |i: usize| robot.links[i].inertial.mass.value > 0.0;
    let mut up = parent[borrower].map(|(p, _)| p);
    let mut steps = 0;
    while let Some(p) = up {
        if has_mass(p) {
            return Some(p);
        }
        steps += 1;
        if steps > robot.links.len() {
            return None; // a loop: refused when planned
        }
        up = parent[p].map(|(q, _)| q);
    }
    let mut queue = std::collections::VecDeque::from([borrower]);
    let mut seen = vec![false; robot.links.len()];
    while let Some(link) = queue.pop_front() {
        if std::mem::replace(&mut seen[link], true) {
            continue;
        }
        if link != borrower && has_mass(link) {
            return Some(link);
        }
        queue.extend((0..robot.links.len()).filter(|&c| parent[c].is_some_and(|(p, _)| p == link)));
    }
    None
}

#[cfg(test)]
mod tests {
    use super::super::read::read;
    use super::lend_masses;

    fn robot(masses: [f64; 3]) -> super::Robot {
        let [a, b, c] = masses;
        let text = format!(
            r#"<robot name="r"><link name="a"><inertial><mass value="{a}"/></inertial></link>
            <link name="b"><inertial><mass value="{b}"/></inertial></link>
            <link name="c"><inertial><mass value="{c}"/></inertial></link>
            <joint name="ab" type="revolute"><parent link="a"/><child link="b"/></joint>
            <joint name="bc" type="revolute"><parent link="b"/><child link="c"/></joint></robot>"#
        );
        read(&text).map_err(|p| p.text).unwrap().robot
    }

    #[test]
    fn a_massless_link_borrows_from_above_else_from_below_else_stays_massless() {
        let mass = |r: &super::Robot| r.links.iter().map(|l| l.inertial.mass.value).collect::<Vec<_>>();
        let (lent, notes) = lend_masses(&robot([2.0, 0.0, 1.0])).unwrap();
        assert_eq!(mass(&lent), [2.0 - 2e-3, 2e-3, 1.0]);
        assert!(notes[0].contains("by link \"a\""), "{notes:?}");
        assert!(lent.links[1].inertial.inertia.ixx > 0.0, "a sphere's inertia");
        // A static (massless) root lends nothing: the link below does.
        let (lent, _) = lend_masses(&robot([0.0, 0.0, 1.0])).unwrap();
        assert_eq!(mass(&lent), [0.0, 1e-3, 1.0 - 1e-3]);
        // No mass anywhere: nothing to lend.
        let (lent, notes) = lend_masses(&robot([0.0, 0.0, 0.0])).unwrap();
        assert_eq!((mass(&lent), notes.len()), (vec![0.0; 3], 0));
        assert!(lend_masses(&robot([1.0, 1.0, 1.0])).is_none());
    }
}
