//! The scanning range finder: geometry of its beams, mounting, planes, blind zone,
//! seeded noise, CSV.

use std::f64::consts::{FRAC_PI_2, TAU};

use ars_core::nalgebra::{Isometry3, Vector3};
use ars_core::sensors::{Lidar, Noisy};
use ars_core::{Mass, Simulation};

#[test]
fn a_lidar_in_a_square_room_sees_the_walls_where_they_are() {
    let mut sim = Simulation::builder().gravity(Vector3::zeros()).build().unwrap();
    // Walls 2 m away on every side of the origin (static boxes).
    let (along_z, along_x) = (Vector3::new(1.0, 2.0, 11.0), Vector3::new(11.0, 2.0, 1.0));
    for (x, z, edges) in [(2.5, 0.0, along_z), (-2.5, 0.0, along_z), (0.0, 2.5, along_x), (0.0, -2.5, along_x)] {
        sim.scene_mut().add_static(ars_core::Shape::Box { edges }, Isometry3::translation(x, 0.0, z)).unwrap();
    }
    let lidar = sim.add_sensor(Lidar::new(8, TAU, 10.0).unwrap()).unwrap();
    sim.step().unwrap();
    let scan = &sim.records(lidar).unwrap().last().unwrap().record;
    // Azimuths −π, −3π/4 ... 3π/4: along the axes 2 m, along the diagonals 2√2 m.
    for (i, r) in scan.ranges.iter().enumerate() {
        let expected = if i % 2 == 0 { 2.0 } else { 2.0 * 2f64.sqrt() };
        assert!((r - expected).abs() < 1e-9, "beam {i}: {r} (expected {expected})");
    }
    // Beam 6 points along azimuth π/2: towards −Z.
    let p = scan.points[6].unwrap();
    assert!((p.z + 2.0).abs() < 1e-9 && p.x.abs() < 1e-9, "{p}");
    // What a viewer draws: each beam from the sensor to its hit.
    let lines = sim.sensor_lines();
    assert_eq!(lines.len(), 8);
    assert!(lines.iter().zip(&scan.points).all(|((a, b), p)| *a == scan.origin && Some(*b) == *p));
}

#[test]
fn a_mounted_lidar_moves_with_its_object_ignores_it_and_scans_several_planes() {
    let mut sim = Simulation::builder().gravity(Vector3::zeros()).build().unwrap();
    let robot = sim.scene_mut().add_box([0.4, 0.4, 0.4], [0.0, 0.0, 0.0], Mass::Total(1.0)).unwrap();
    sim.scene_mut().add_sphere(0.5, [3.0, 0.0, 0.0], Mass::Total(1.0)).unwrap();
    sim.scene_mut().body_mut(robot).unwrap().set_linear_velocity(Vector3::new(1.0, 0.0, 0.0)).unwrap();
    let lidar = Lidar::new(3, FRAC_PI_2, 20.0).unwrap().planes(&[0.0, 0.3]).unwrap().min_range(0.1).unwrap();
    let lidar = sim.add_sensor(lidar.on(robot, Isometry3::translation(0.0, 0.0, 0.0))).unwrap();
    sim.run_for(1.0).unwrap();
    let log = sim.records(lidar).unwrap();
    let (first, last) = (&log.samples()[0].record, &log.last().unwrap().record);
    assert_eq!(first.ranges.len(), 6, "3 beams × 2 planes");
    // The middle beam of the flat plane looks along +X at the sphere: 2.5 m, then 1.5 m
    // after 1 s at 1 m/s. The robot's own box (around the sensor) is not seen.
    assert!((first.ranges[1] - (2.5 - 0.0004)).abs() < 1e-9, "{}", first.ranges[1]);
    assert!((last.ranges[1] - 1.5).abs() < 1e-6, "{}", last.ranges[1]);
    // The tilted plane's middle beam passes above the sphere's centre: longer, or a miss.
    assert!(last.ranges[4] > last.ranges[1], "{:?}", last.ranges);
    let mut csv = Vec::new();
    log.write_csv(&mut csv).unwrap();
    let header = String::from_utf8(csv).unwrap().lines().next().unwrap().to_string();
    assert_eq!(
        header,
        "time [s],step,range 0.0 [m],range 0.1 [m],range 0.2 [m],range 1.0 [m],range 1.1 [m],range 1.2 [m]"
    );
}

#[test]
fn noisy_scans_are_seeded_and_a_blind_zone_hides_near_hits() {
    let scan = |seed: u64| {
        let mut sim = Simulation::new().unwrap();
        sim.scene_mut().add_sphere(1.0, [3.0, 0.0, 0.0], Mass::Total(1.0)).unwrap();
        sim.scene_mut().add_sphere(0.1, [0.0, 0.0, -0.3], Mass::Total(1.0)).unwrap(); // 0.2 m away, along azimuth π/2
        let lidar = Lidar::new(4, TAU, 10.0).unwrap().min_range(0.5).unwrap();
        let id = sim.add_sensor(Noisy::new(lidar, 0.01, seed).unwrap()).unwrap();
        sim.step().unwrap();
        sim.records(id).unwrap().last().unwrap().record.ranges.clone()
    };
    let (a, b, c) = (scan(1), scan(1), scan(2));
    assert_eq!(a, b, "same seed, same noise");
    assert_ne!(a, c, "another seed, other noise");
    // Azimuths −π, −π/2, 0, π/2: the far sphere along 0 (2 m), the near one hidden.
    assert!((a[2] - 2.0).abs() < 0.05 && a[2] != 2.0, "noisy but close: {}", a[2]);
    assert!(a[3].is_infinite() && a[0].is_infinite() && a[1].is_infinite(), "{a:?}");
}
