//! Cause: a capsule of radius f64::MAX next to a cone (a triangle mesh) overflowed
//! ODE's capsule–trimesh collider, which then asserted: SIGABRT. Fixed by the size
//! range (`limits::MAX_SIZE` = 1e9 m); at that bound the pair collides normally.

use ars_core::limits::MAX_SIZE;
use ars_core::*;

#[test]
fn a_capsule_of_radius_max_is_refused_and_one_at_the_bound_collides() {
    let mut sim = Simulation::builder().build().unwrap();
    let err = sim.scene_mut().add_capsule(f64::MAX, 1.0, [0.0, 0.0, 0.0], Mass::Total(1.0)).unwrap_err();
    assert!(err.to_string().contains("capsule"), "{err}");
    let err = sim.scene_mut().add_capsule(1.0, f64::MAX, [0.0, 0.0, 0.0], Mass::Total(1.0)).unwrap_err();
    assert!(err.to_string().contains("capsule"), "{err}");

    sim.scene_mut().add_cone(0.5, 1.0, [0.0, 0.0, 0.0], Mass::Total(1.0)).unwrap();
    sim.scene_mut().add_capsule(MAX_SIZE, 1.0, [0.0, 0.0, 0.0], Mass::Total(1e9)).unwrap();
    for _ in 0..5 {
        let _ = sim.step();
    }
}
