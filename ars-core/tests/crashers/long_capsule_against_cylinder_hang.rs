//! Cause: a capsule 1e17 m long against a cylinder made libccd's MPR penetration
//! search (`ccdMPRPenetration`) loop forever: at that scale the rounding of the
//! support points exceeds its fixed 1e-6 tolerance, so the portal never converges: a
//! hang. What makes it loop is the ratio of the pair's largest to smallest dimension
//! (measured: none up to 1e8 in 100,000 random pairs, hangs from about 6e9). Fixed
//! by the size range (1e9 m) and by refusing, when two such shapes meet, a pair
//! beyond `limits::MAX_CONVEX_PAIR_RATIO` (an `Err`, before libccd is called); pairs
//! at the bounds finish, checked here under a watchdog.

use std::sync::mpsc;
use std::time::Duration;

use ars_core::limits::{MAX_CONVEX_PAIR_RATIO, MAX_COORDINATE, MAX_SIZE, MIN_SIZE};
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
fn convex_pairs_at_the_bounds_finish_and_beyond_the_ratio_are_refused() {
    within_a_minute(|| {
        let mut world = World::new();
        let space = world.create_space(SpaceKind::Simple).unwrap();
        let r = MAX_CONVEX_PAIR_RATIO;
        // (static geom, moving geom, accepted)
        let cases = [
            (GeomBuilder::capsule(10.0, 10.0 * r), GeomBuilder::cylinder(10.0, 10.0), true),
            (GeomBuilder::cylinder(MAX_SIZE, MAX_SIZE), GeomBuilder::cylinder(MAX_SIZE / r, MAX_SIZE / r), true),
            (GeomBuilder::cylinder(MIN_SIZE * r, MIN_SIZE), GeomBuilder::capsule(MIN_SIZE, MIN_SIZE), true),
            (GeomBuilder::cylinder(1.0, 1.0), GeomBuilder::cylinder(1.0, 1.0), true),
            (GeomBuilder::capsule(1.0, MAX_SIZE), GeomBuilder::cylinder(1.0, 1.0), false),
            (GeomBuilder::cylinder(MAX_SIZE, MAX_SIZE), GeomBuilder::cylinder(MIN_SIZE, MIN_SIZE), false),
        ];
        for at in [0.0, MAX_COORDINATE - 1.0] {
            for (a, b, accepted) in cases.clone() {
                let pose = Isometry3::translation(at, at, at);
                world.insert_geom(space, a.pose(pose)).unwrap();
                let body = world.insert_body(BodyBuilder::new().position(Point3::new(at, at - 0.5, at))).unwrap();
                world.insert_geom(space, b.attached_to(body)).unwrap();
                let collided = world.collide(space);
                assert_eq!(collided.is_ok(), accepted, "{collided:?}");
                if let Err(e) = collided {
                    assert!(e.to_string().contains("differ by a factor"), "{e}");
                    assert!(world.contacts().is_empty() || !world.is_poisoned());
                }
                world.clear_contacts();
                world.remove_body(body).unwrap();
                for g in world.geoms().collect::<Vec<_>>() {
                    world.remove_geom(g).unwrap();
                }
            }
        }
    });
}
