//! The broad-phase spaces: the grid is the default of a new simulation, every
//! kind and axis order finds the pairs the simple space finds, and scenes in them
//! behave as they should (a ball rests on the floor, two balls bounce apart).

use std::collections::BTreeSet;

use ars_core::nalgebra::{Point3, Vector3};
use ars_core::*;

/// Every space kind: simple, hash, the grid, and sweep and prune in each axis order.
fn all_kinds() -> Vec<SpaceKind> {
    let orders = [AxisOrder::Xyz, AxisOrder::Xzy, AxisOrder::Yxz, AxisOrder::Yzx, AxisOrder::Zxy, AxisOrder::Zyx];
    let mut kinds = vec![SpaceKind::Simple, SpaceKind::HASH, SpaceKind::Grid];
    kinds.extend(orders.map(|axes| SpaceKind::SweepAndPrune { axes }));
    kinds
}

#[test]
fn a_new_simulation_has_a_grid_and_a_program_the_simple_space() {
    assert_eq!(DEFAULT_SPACE, SpaceKind::Grid);
    let sim = Simulation::new().unwrap();
    assert_eq!(sim.scene().space_kind(), DEFAULT_SPACE);
    assert_eq!(sim.scene().world().space_kind(sim.scene().space()).unwrap(), DEFAULT_SPACE);
    assert_eq!(Simulation::builder().build().unwrap().scene().space_kind(), DEFAULT_SPACE);
    assert_eq!(Simulation::builder().space(SpaceKind::Simple).build().unwrap().scene().space_kind(), SpaceKind::Simple);

    struct Plain;
    impl Hooks for Plain {}
    impl Program for Plain {
        fn create_sim_objects(&mut self, _: &mut Simulation) -> Result<()> {
            Ok(())
        }
    }
    assert_eq!(Plain.create_simulation().unwrap().scene().space_kind(), SpaceKind::Simple);
}

#[test]
fn axis_orders_name_their_axes_first_to_last() {
    assert_eq!(AxisOrder::Xzy.axes(), [0, 2, 1]);
    assert_eq!(AxisOrder::Zyx.axes(), [2, 1, 0]);
    let orders = [AxisOrder::Xyz, AxisOrder::Xzy, AxisOrder::Yxz, AxisOrder::Yzx, AxisOrder::Zxy, AxisOrder::Zyx];
    let distinct: BTreeSet<[u8; 3]> = orders.iter().map(|o| o.axes()).collect();
    assert_eq!(distinct.len(), 6);
    for o in orders {
        let mut axes = o.axes();
        axes.sort_unstable();
        assert_eq!(axes, [0, 1, 2], "{o:?}");
    }
}

/// The unordered geom pairs in contact after one collision of 400 spheres of random
/// radii in a 4 m cube (about a few hundred touching pairs), on a floor through the
/// cube's lower part.
fn touching_pairs(kind: SpaceKind) -> BTreeSet<(u32, u32)> {
    let mut world = World::new();
    let space = world.create_space(kind).unwrap();
    let floor = world.insert_geom(space, GeomBuilder::plane(Vector3::y(), 0.3)).unwrap();
    let mut seed = 0x2545_f491_4f6c_dd1d_u64;
    let mut next = || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut index = std::collections::HashMap::new();
    index.insert(floor, u32::MAX);
    for i in 0..400 {
        let p = Point3::new(4.0 * next() - 2.0, 4.0 * next(), 4.0 * next() - 2.0);
        let r = 0.05 + 0.2 * next();
        let b = world.insert_body(BodyBuilder::new().position(p).mass(MassSpec::sphere_total(1.0, r))).unwrap();
        let g = world.insert_geom(space, GeomBuilder::sphere(r).attached_to(b)).unwrap();
        index.insert(g, i);
    }
    world.collide(space).unwrap();
    let pairs = world
        .contacts()
        .iter()
        .map(|c| {
            let (a, b) = (index[&c.pair.geom1], index[&c.pair.geom2]);
            (a.min(b), a.max(b))
        })
        .collect();
    world.clear_contacts();
    pairs
}

#[test]
fn every_space_finds_the_pairs_the_simple_space_finds() {
    let simple = touching_pairs(SpaceKind::Simple);
    let with_floor = simple.iter().filter(|(_, b)| *b == u32::MAX).count();
    assert!(simple.len() > 100 && with_floor > 10, "{} pairs, {with_floor} on the floor", simple.len());
    for kind in all_kinds() {
        assert_eq!(touching_pairs(kind), simple, "{kind:?}");
    }
}

#[test]
fn a_ball_dropped_on_the_floor_bounces_and_rests_on_it_in_every_space() {
    for kind in all_kinds() {
        let mut sim = Simulation::builder().space(kind).floor_plane(Vector3::y(), 0.0).build().unwrap();
        let ball = sim.scene_mut().add_sphere(0.5, [1.0, 1.0, 1.0], Mass::Total(1.0)).unwrap();
        let (mut lowest, mut rose) = (f64::INFINITY, false);
        for _ in 0..2500 {
            sim.step().unwrap();
            let b = sim.scene().body(ball).unwrap();
            lowest = lowest.min(b.position().y);
            rose |= b.linear_velocity().y > 0.5;
        }
        let b = sim.scene().body(ball).unwrap();
        assert!(rose, "{kind:?}: the ball bounced");
        assert!(lowest > 0.49, "{kind:?}: the ball sank to {lowest}");
        assert!((b.position().y - 0.5).abs() < 1e-3, "{kind:?}: rests at {}", b.position().y);
        assert!(b.linear_velocity().norm() < 1e-3, "{kind:?}: at rest");
    }
}

/// Two 1 kg balls 1 m apart along `axis`, approaching at 1 m/s each, without gravity:
/// their velocities along the axis after 0.5 s.
fn head_on(kind: SpaceKind, axis: Vector3<f64>) -> (f64, f64) {
    let mut sim = Simulation::builder().space(kind).gravity(Vector3::zeros()).build().unwrap();
    let centre = Point3::new(0.3, 0.7, -0.2);
    let a = sim.scene_mut().add_sphere(0.25, centre - 0.5 * axis, Mass::Total(1.0)).unwrap();
    let b = sim.scene_mut().add_sphere(0.25, centre + 0.5 * axis, Mass::Total(1.0)).unwrap();
    sim.scene_mut().body_mut(a).unwrap().set_linear_velocity(axis).unwrap();
    sim.scene_mut().body_mut(b).unwrap().set_linear_velocity(-axis).unwrap();
    sim.run_for(0.5).unwrap();
    let (va, vb) = (sim.scene().body(a).unwrap().linear_velocity(), sim.scene().body(b).unwrap().linear_velocity());
    assert!((va - axis * va.dot(&axis)).norm() < 1e-9, "{kind:?}: no sideways motion");
    (va.dot(&axis), vb.dot(&axis))
}

#[test]
fn two_balls_meet_head_on_and_bounce_apart_in_every_space_along_every_axis() {
    for axis in [Vector3::x(), Vector3::y(), Vector3::z()] {
        let (sa, sb) = head_on(SpaceKind::Simple, axis);
        // Restitution 0.2 (the ARS surface): 2 m/s closing, about 0.4 m/s apart.
        assert!(sa < 0.0 && sb > 0.0, "simple along {axis:?}: {sa}, {sb} apart");
        assert!((sa + sb).abs() < 1e-9, "momentum kept: {sa} + {sb}");
        assert!((0.35..0.5).contains(&(sb - sa)), "simple along {axis:?}: {} m/s apart", sb - sa);
        for kind in all_kinds() {
            let (a, b) = head_on(kind, axis);
            assert!((a - sa).abs() < 1e-9 && (b - sb).abs() < 1e-9, "{kind:?} along {axis:?}: {a}, {b}");
        }
    }
}

#[test]
fn a_geom_without_collision_bits_touches_nothing_and_stays_its_space_s() -> Result<()> {
    // ODE never brings such a geom's box up to date for a collision (it is kept out of
    // ODE's space): it must still be cast at, saved and restored, and touch again once
    // it has bits.
    // In every kind of space (the grid and ODE's).
    for kind in all_kinds() {
        let mut sim = Simulation::builder().space(kind).floor_plane(Vector3::y(), 0.0).build()?;
        let crate_ = sim.scene_mut().add_box([0.2, 0.1, 0.2], [0.0, 0.05, 0.0], Mass::Total(1.0))?;
        let geom = sim.scene().object(crate_)?.geoms().next().expect("a box has a geom");
        let set_bits = |sim: &mut Simulation, bits: u64| -> Result<()> {
            let mut g = sim.scene_mut().world_mut().geom_mut(geom)?;
            g.set_category_bits(bits);
            g.set_collide_bits(bits);
            Ok(())
        };
        set_bits(&mut sim, 0)?;
        assert_eq!(sim.scene().world().geom(geom)?.space(), sim.scene().space(), "still its space's");
        let silent = sim.snapshot()?;
        let down = world::raycast::Ray { origin: Point3::new(0.0, 1.0, 0.0), direction: -Vector3::y() };
        let hit = sim.scene().world().cast_ray(down, 2.0, None)?.expect("the ray meets the crate");
        assert_eq!(hit.geom, geom, "a cast sees a geom without bits");
        sim.run_for(0.5)?;
        assert!(sim.scene().position(crate_)?.y < -0.5, "{kind:?}: no bits: it falls through the floor");

        sim.restore(&silent)?;
        set_bits(&mut sim, u64::MAX)?;
        let touching = sim.snapshot()?;
        sim.run_for(0.5)?;
        let resting = sim.scene().position(crate_)?.y;
        assert!((resting - 0.05).abs() < 1e-3, "{kind:?}: bits again: it rests on the floor, at {resting}");

        // A snapshot puts the bits back, and the geom in or out of the collision with them.
        set_bits(&mut sim, 0)?;
        sim.restore(&touching)?;
        sim.run_for(0.5)?;
        assert_eq!(sim.scene().position(crate_)?.y, resting, "restored with bits: the same run, to the bit");
        sim.restore(&silent)?;
        sim.run_for(0.5)?;
        assert!(sim.scene().position(crate_)?.y < -0.5, "{kind:?}: restored without bits: it falls through again");
    }
    Ok(())
}
