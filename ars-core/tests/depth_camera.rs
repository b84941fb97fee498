//! The depth camera against geometry: a wall at a known distance fills the image with
//! that depth (z-distance, every pixel), a sphere's nearest point is where it should
//! be, and the `.npy` file is what NumPy reads.

use ars_core::nalgebra::{Isometry3, Vector3};
use ars_core::sensors::DepthCamera;
use ars_core::{Mass, Shape, Simulation};

#[test]
fn a_wall_at_a_known_distance_fills_the_image_with_that_depth() {
    let mut sim = Simulation::builder().gravity(Vector3::zeros()).build().unwrap();
    // A wall whose face is the plane z = -2.5, much wider than the view.
    sim.scene_mut()
        .add_static(Shape::Box { edges: Vector3::new(40.0, 40.0, 1.0) }, Isometry3::translation(0.0, 0.0, -3.0))
        .unwrap();
    let camera = sim.add_sensor(DepthCamera::new(40, 30, 1.2, 0.05, 20.0).unwrap()).unwrap();
    sim.step().unwrap();
    let image = &sim.records(camera).unwrap().last().unwrap().record;
    assert_eq!((image.width, image.height, image.pixels.len()), (40, 30, 1200));
    for (i, d) in image.pixels.iter().enumerate() {
        assert!((f64::from(*d) - 2.5).abs() < 1e-5, "pixel {i}: {d}");
    }
}

#[test]
fn a_sphere_is_seen_where_it_is_and_a_mounted_camera_moves_with_its_body() {
    let mut sim = Simulation::builder().gravity(Vector3::zeros()).build().unwrap();
    sim.scene_mut().add_sphere(0.5, [0.0, 0.0, -4.0], Mass::Total(1.0)).unwrap();
    let robot = sim.scene_mut().add_box([0.2, 0.2, 0.2], [0.0, 0.0, 0.0], Mass::Total(1.0)).unwrap();
    sim.scene_mut().body_mut(robot).unwrap().set_linear_velocity(Vector3::new(0.0, 0.0, -1.0)).unwrap();
    let camera = DepthCamera::new(41, 41, 0.8, 0.05, 10.0).unwrap().on(robot, Isometry3::identity());
    let camera = sim.add_sensor_every(camera, 0.5).unwrap();
    sim.run_for(1.0).unwrap();
    let log = sim.records(camera).unwrap();
    let (first, last) = (&log.samples()[0].record, &log.last().unwrap().record);
    // The centre pixel looks straight at the sphere's nearest point: 3.5 m, then 1 m closer.
    assert!((f64::from(first.depth(20, 20)) - 3.0).abs() < 1e-3, "{}", first.depth(20, 20));
    assert!((f64::from(last.depth(20, 20)) - 2.5).abs() < 1e-3, "{}", last.depth(20, 20));
    // The corners see nothing.
    assert!(last.depth(0, 0).is_infinite());
    let mut npy = Vec::new();
    last.write_npy(&mut npy).unwrap();
    assert_eq!(&npy[..8], b"\x93NUMPY\x01\x00");
    let header_len = u16::from_le_bytes([npy[8], npy[9]]) as usize;
    assert_eq!((10 + header_len) % 64, 0, "the data starts on a 64-byte boundary");
    let header = std::str::from_utf8(&npy[10..10 + header_len]).unwrap();
    assert!(header.contains("'descr': '<f4'") && header.contains("'shape': (41, 41)"), "{header}");
    assert_eq!(npy.len(), 10 + header_len + 41 * 41 * 4);
}
