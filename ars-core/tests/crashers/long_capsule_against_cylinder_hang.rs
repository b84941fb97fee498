//! Cause: a capsule 1e17 m long against a cylinder made libccd's MPR penetration
//! search (`ccdMPRPenetration`) loop forever: at that scale the rounding of the
//! support points exceeds its fixed 1e-6 tolerance, so the portal never converges: a
//! hang. Fixed by the size and coordinate ranges (1e9 m); the pairs at the bounds
//! finish, checked here under a watchdog.

use std::sync::mpsc;
use std::time::Duration;

use ars_core::limits::{MAX_COORDINATE, MAX_SIZE, MIN_SIZE};
use ars_core::nalgebra::{Isometry3, Point3};
use ars_core::*;

/// Runs `f` on a thread and fails if it does not finish within a minute.
fn within_a_minute(f: impl FnOnce() + Send + 'static) {
    let (done, finished) = mpsc::channel();
    std::thread::spawn(move || {
        f();
        let _ = done.send(());
    });
    finished.recv_timeout(Duration::from_secs(60)).expect("collision did not finish within a minute (hang)");
}

#[test]
fn a_capsule_of_length_1e17_is_refused() {
    let mut world = World::new();
    let space = world.create_space(SpaceKind::Simple).unwrap();
    let err = world.insert_geom(space, GeomBuilder::capsule(1.0, 1e17)).unwrap_err();
    assert!(err.to_string().contains("capsule length"), "{err}");
}

#[test]
fn convex_pairs_at_the_bounds_finish() {
    within_a_minute(|| {
        let mut world = World::new();
        let space = world.create_space(SpaceKind::Simple).unwrap();
        let shapes = [
            (GeomBuilder::capsule(1.0, MAX_SIZE), GeomBuilder::cylinder(1.0, 1.0)),
            (GeomBuilder::cylinder(MAX_SIZE, MAX_SIZE), GeomBuilder::cylinder(MIN_SIZE, MIN_SIZE)),
            (GeomBuilder::cylinder(1.0, MAX_SIZE), GeomBuilder::capsule(MAX_SIZE, 1.0)),
            (GeomBuilder::cylinder(1.0, 1.0), GeomBuilder::cylinder(1.0, 1.0)),
        ];
        for at in [0.0, MAX_COORDINATE - 1.0] {
            for (a, b) in shapes.clone() {
                let pose = Isometry3::translation(at, at, at);
                world.insert_geom(space, a.pose(pose)).unwrap();
                let body = world.insert_body(BodyBuilder::new().position(Point3::new(at, at + 0.5, at))).unwrap();
                world.insert_geom(space, b.attached_to(body)).unwrap();
                world.collide(space).unwrap();
                world.clear_contacts();
                for g in world.geoms().collect::<Vec<_>>() {
                    world.remove_geom(g).unwrap();
                }
            }
        }
    });
}
