//! The plain collision: for worlds without rays, collision hooks or contact feedback,
//! ODE's pairs go to a near callback in C (ode-sys's `guard.c`) and a `Simulation`
//! collides and steps in one guarded call. It must do exactly what the Rust near
//! callback does: these tests run the same scenes through both (contact feedback on
//! takes the Rust one; it only records forces) and compare every bit.

use ars_core::nalgebra::Vector3;
use ars_core::*;

/// Spheres, boxes, capsules and cylinders dropped in a heap on the floor of a hash
/// space: many pairs, several contact points per pair, jointed pairs skipped.
fn heap(feedback: bool) -> Simulation {
    let mut sim = Simulation::builder().space(SpaceKind::HASH).floor_plane(Vector3::y(), 0.0).build().unwrap();
    for i in 0..24 {
        let p = [0.22 * f64::from(i % 4), 0.16 + 0.28 * f64::from(i / 4), 0.05 * f64::from(i % 3)];
        match i % 4 {
            0 => sim.scene_mut().add_sphere(0.15, p, Mass::Total(1.0)).unwrap(),
            1 => sim.scene_mut().add_box([0.25, 0.2, 0.3], p, Mass::Total(1.0)).unwrap(),
            2 => sim.scene_mut().add_capsule(0.08, 0.3, p, Mass::Total(1.0)).unwrap(),
            _ => sim.scene_mut().add_cylinder(0.1, 0.25, p, Mass::Total(1.0)).unwrap(),
        };
    }
    sim.scene_mut().world_mut().set_contact_feedback(feedback);
    sim
}

fn states(sim: &Simulation) -> Vec<[u64; 13]> {
    sim.scene()
        .bodies()
        .map(|(_, h)| {
            let b = sim.scene().world().body(h).unwrap();
            let (p, q, v, w) = (b.position(), b.quaternion(), b.linear_velocity(), b.angular_velocity());
            [p.x, p.y, p.z, q.w, q.i, q.j, q.k, v.x, v.y, v.z, w.x, w.y, w.z].map(f64::to_bits)
        })
        .collect()
}

/// A contact point without its force (only the Rust path measures it), its handles
/// without their world.
fn geometry(c: &ContactPoint) -> (String, [u64; 7]) {
    let (p, n) = (c.position, c.normal);
    let pair = format!("{:?}", c.pair);
    let pair = pair.split("@w").map(|part| part.trim_start_matches(|c: char| c.is_ascii_digit())).collect();
    (pair, [p.x, p.y, p.z, n.x, n.y, n.z, c.depth].map(f64::to_bits))
}

#[test]
fn the_plain_collision_steps_and_records_bit_for_bit_as_the_rust_callback() {
    let (mut plain, mut rust) = (heap(false), heap(true));
    let mut touching = 0;
    for step in 0..600 {
        plain.step().unwrap();
        rust.step().unwrap();
        assert_eq!(states(&plain), states(&rust), "step {step}");
        let a: Vec<_> = plain.scene().world().contacts().iter().map(geometry).collect();
        let b: Vec<_> = rust.scene().world().contacts().iter().map(geometry).collect();
        assert_eq!(a, b, "step {step}");
        touching = touching.max(a.len());
    }
    assert!(touching > 10, "the heap touches at many points ({touching})");
}

#[test]
fn the_world_layer_collides_bit_for_bit_on_both_paths() {
    let (mut plain, mut rust) = (heap(false), heap(true));
    for step in 0..200 {
        for sim in [&mut plain, &mut rust] {
            let space = sim.scene().space();
            let world = sim.scene_mut().world_mut();
            world.collide(space).unwrap();
            world.step(0.0004).unwrap();
            world.clear_contacts();
        }
        assert_eq!(states(&plain), states(&rust), "step {step}");
    }
}

#[test]
fn contact_points_keep_their_geoms_after_the_geom_is_removed() {
    // The plain collision makes its points when they are first read: a geom removed
    // before that must still be named by them, as on the Rust path.
    let mut sim = heap(false);
    sim.step_n(1000).unwrap();
    let touching = sim.scene().world().contacts()[0].pair.geom1;
    let space = sim.scene().space();
    let world = sim.scene_mut().world_mut();
    world.collide(space).unwrap();
    world.remove_geom(touching).unwrap();
    let points = world.contacts().iter().filter(|c| c.pair.geom1 == touching || c.pair.geom2 == touching).count();
    assert!(points > 0, "the removed geom's points are listed");
    world.clear_contacts();
}

#[test]
fn more_contact_points_than_the_exact_stepper_takes_is_still_refused() {
    let mut sim = heap(false);
    sim.step_n(1500).unwrap();
    assert!(sim.scene().world().contacts().len() > 3);
    sim.scene_mut().world_mut().set_exact_step_contact_limit(3);
    let e = sim.step().unwrap_err();
    assert!(e.to_string().contains("island"), "{e}");
}
