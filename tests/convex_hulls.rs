//! Meshes that collide as their convex hulls (ODE convexes), as MuJoCo's meshes and
//! PyBullet's URDF collision meshes do: hulls of cubes and spheres, a hull resting on
//! the floor and on a box, a non-convex mesh colliding as its hull, bad input refused,
//! hulls through scene files and snapshots, and the importers' use of them.

use ars::nalgebra::{Isometry3, Point3, Vector3};
use ars::{Error, GeomBuilder, Mass, MjcfOptions, Shape, Simulation, UrdfOptions};

/// The corners of an axis-aligned box of `edges` centred on the origin.
fn box_corners(edges: [f64; 3]) -> Vec<Point3<f64>> {
    (0..8)
        .map(|i| {
            let s = |bit: i32, e: f64| if i >> bit & 1 == 1 { e / 2.0 } else { -e / 2.0 };
            Point3::new(s(0, edges[0]), s(1, edges[1]), s(2, edges[2]))
        })
        .collect()
}

/// The vertices of a UV sphere of `radius`: `rings` − 1 rings of `segments` and the poles.
fn sphere_points(radius: f64, rings: u32, segments: u32) -> Vec<Point3<f64>> {
    let mut points = vec![Point3::new(0.0, 0.0, radius), Point3::new(0.0, 0.0, -radius)];
    for i in 1..rings {
        let polar = std::f64::consts::PI * f64::from(i) / f64::from(rings);
        for j in 0..segments {
            let azimuth = std::f64::consts::TAU * f64::from(j) / f64::from(segments);
            points.push(Point3::new(
                radius * polar.sin() * azimuth.cos(),
                radius * polar.sin() * azimuth.sin(),
                radius * polar.cos(),
            ));
        }
    }
    points
}

fn hull(points: &[Point3<f64>]) -> (Vec<Point3<f64>>, Vec<[u32; 3]>) {
    match Shape::convex_hull(points).unwrap() {
        Shape::ConvexHull { vertices, triangles } => (vertices, triangles),
        other => panic!("a hull, not {other:?}"),
    }
}

#[test]
fn the_hull_of_a_cube_is_the_cube_and_of_a_sphere_mesh_every_vertex() {
    let mut points = box_corners([1.0, 2.0, 3.0]);
    points.extend([Point3::origin(), Point3::new(0.1, -0.2, 0.3)]);
    let (vertices, triangles) = hull(&points);
    assert_eq!((vertices.len(), triangles.len()), (8, 12));
    let cube = Shape::ConvexHull { vertices, triangles };
    assert!((cube.volume().unwrap() - 6.0).abs() < 1e-12, "{:?}", cube.volume());

    // Every vertex of a sphere mesh is on its hull; its volume is just under the ball's.
    let points = sphere_points(0.5, 12, 16);
    let (vertices, triangles) = hull(&points);
    assert_eq!(vertices.len(), points.len());
    assert_eq!(triangles.len(), 2 * points.len() - 4, "a closed triangulated surface of genus 0");
    let ball = 4.0 / 3.0 * std::f64::consts::PI * 0.125;
    let volume = Shape::ConvexHull { vertices, triangles }.volume().unwrap();
    assert!(volume < ball && volume > 0.93 * ball, "{volume} against {ball}");
}

/// A simulation with the floor at y = 0 (ODE's plane), time step 1 ms.
fn on_the_floor() -> Simulation {
    Simulation::builder().floor_plane(Vector3::y(), 0.0).build().unwrap()
}

/// Steps `seconds` and returns the object's final height, checking every pose finite.
fn settle(sim: &mut Simulation, name: &str, seconds: f64) -> (f64, f64) {
    let id = sim.scene().object(name).unwrap().id();
    let steps = (seconds / sim.scene().time_step()).round() as usize;
    for _ in 0..steps {
        sim.step().unwrap();
        let p = sim.scene().position(id).unwrap();
        assert!(p.coords.iter().all(|c| c.is_finite()), "{p}");
    }
    let body = sim.scene().body(id).unwrap();
    (sim.scene().position(id).unwrap().y, body.linear_velocity().norm())
}

#[test]
fn a_hull_rests_on_the_floor_and_on_a_box_at_its_height() {
    // A 0.2 × 0.1 × 0.3 box as a hull (its centre of volume at its origin), dropped
    // from 5 cm above the floor, tilted a little.
    let shape = Shape::convex_hull(&box_corners([0.2, 0.1, 0.3])).unwrap();
    let mut sim = on_the_floor();
    let id = sim.scene_mut().add_body(shape.clone(), [0.0, 0.1, 0.0], Mass::Total(1.0)).unwrap();
    sim.scene_mut().set_name(id, "hull").unwrap();
    sim.scene_mut().rotate(id, [1.0, 0.0, 1.0], 0.05).unwrap();
    let (height, speed) = settle(&mut sim, "hull", 2.0);
    assert!((height - 0.05).abs() < 1e-3, "rests at {height}, half its 0.1 m height is 0.05");
    assert!(speed < 1e-3, "still moving at {speed} m/s");
    // Several points of its face on the floor, as a box's.
    let contacts = sim.scene().world().contacts().len();
    assert!(contacts >= 3, "{contacts} contact points");

    // On a static box whose top is at y = 0.5: ODE's convex–box collider (libccd)
    // gives one point a step, which holds it at the right height, moving little.
    let mut sim = on_the_floor();
    sim.scene_mut()
        .add_static(Shape::Box { edges: Vector3::new(1.0, 0.5, 1.0) }, Isometry3::translation(0.0, 0.25, 0.0))
        .unwrap();
    let id = sim.scene_mut().add_body(shape, [0.0, 0.56, 0.0], Mass::Total(1.0)).unwrap();
    sim.scene_mut().set_name(id, "hull").unwrap();
    let start = sim.scene().position(id).unwrap();
    let (height, speed) = settle(&mut sim, "hull", 2.0);
    assert!((height - 0.55).abs() < 2e-3, "rests at {height}, not 0.55");
    assert!(speed < 0.05, "moving at {speed} m/s");
    let drift = (sim.scene().position(id).unwrap() - start).xz().norm();
    assert!(drift < 0.01, "slid {drift} m across the box");
}

/// An L-shaped prism (1 × 1 cells, a 2 × 2 square with its +x +y quarter cut out), 1 m
/// deep along z, as a triangle mesh.
fn l_prism() -> (Vec<Point3<f64>>, Vec<[u32; 3]>) {
    let outline = [(0.0, 0.0), (2.0, 0.0), (2.0, 1.0), (1.0, 1.0), (1.0, 2.0), (0.0, 2.0)];
    let mut vertices: Vec<Point3<f64>> = outline.iter().map(|&(x, y)| Point3::new(x, y, 0.0)).collect();
    vertices.extend(outline.iter().map(|&(x, y)| Point3::new(x, y, 1.0)));
    let mut triangles = vec![[0, 3, 2], [0, 2, 1], [0, 5, 4], [0, 4, 3]];
    triangles.extend([[6, 8, 9], [6, 7, 8], [6, 10, 11], [6, 9, 10]]);
    for i in 0..6u32 {
        let j = (i + 1) % 6;
        triangles.extend([[i, j, j + 6], [i, j + 6, i + 6]]);
    }
    (vertices, triangles)
}

/// The contacts of one step between a static `shape` (at the identity) and a ball of
/// radius 0.05 at `at`, with no gravity.
fn contacts_with_ball(shape: Shape, at: [f64; 3]) -> Vec<ars::ContactPoint> {
    let mut sim = Simulation::builder().gravity(Vector3::zeros()).build().unwrap();
    sim.scene_mut().add_static(shape, Isometry3::identity()).unwrap();
    sim.scene_mut().add_sphere(0.05, at, Mass::Total(0.1)).unwrap();
    sim.step().unwrap();
    sim.scene().world().contacts().to_vec()
}

#[test]
fn a_non_convex_mesh_collides_as_its_hull() {
    let (vertices, triangles) = l_prism();
    let l_mesh = Shape::TriMesh { vertices: vertices.clone(), triangles };
    assert!((l_mesh.volume().unwrap() - 3.0).abs() < 1e-12);
    let l_hull = Shape::convex_hull(&vertices).unwrap();
    assert!((l_hull.volume().unwrap() - 3.5).abs() < 1e-12, "the hull fills half the notch");
    // A ball in the notch (x, y > 1), clear of the L itself (0.4 m from its faces) but
    // inside its hull, whose slanted face x + y = 3 it overlaps by 0.2/√2 + 0.05 m.
    let at = [1.4, 1.4, 0.5];
    assert!(contacts_with_ball(l_mesh, at).is_empty(), "the triangle mesh does not reach the ball");
    let contacts = contacts_with_ball(l_hull, at);
    assert!(!contacts.is_empty(), "the hull touches the ball");
    let slant = Vector3::new(1.0, 1.0, 0.0).normalize();
    for c in &contacts {
        assert!((c.normal.dot(&slant).abs() - 1.0).abs() < 1e-6, "normal {} is not the slanted face's", c.normal);
        let depth = 0.2 / 2f64.sqrt() + 0.05;
        assert!((c.depth - depth).abs() < 1e-4, "depth {} not {depth}", c.depth);
    }
}

#[test]
fn points_or_faces_that_make_no_hull_are_refused_by_name() {
    let error = |points: &[Point3<f64>]| Shape::convex_hull(points).unwrap_err().to_string();
    let square: Vec<Point3<f64>> = box_corners([1.0, 1.0, 1.0]).into_iter().filter(|p| p.z > 0.0).collect();
    assert!(error(&square).contains("one plane"), "{}", error(&square));
    assert!(error(&square[..3]).contains("at least 4 points"));
    let mut nan = box_corners([1.0, 1.0, 1.0]);
    nan[2].x = f64::NAN;
    assert!(matches!(Shape::convex_hull(&nan), Err(Error::InvalidMesh(m)) if m.contains("point 2")));
    assert!(GeomBuilder::convex_hull(&[]).is_err());

    // A hull given directly is checked: the L's own triangles are not convex.
    let (vertices, triangles) = l_prism();
    let mut sim = on_the_floor();
    let not_convex = Shape::ConvexHull { vertices, triangles };
    let err = sim.scene_mut().add_static(not_convex.clone(), Isometry3::identity()).unwrap_err();
    assert!(err.to_string().contains("not convex"), "{err}");
    let err = sim.scene_mut().add_body(not_convex, [0.0, 1.0, 0.0], Mass::Total(1.0)).unwrap_err();
    assert!(err.to_string().contains("not convex"), "{err}");
    // A hull whose centre of volume is not its origin has no body mass ODE can take.
    let off = Shape::convex_hull(&box_corners([1.0, 1.0, 1.0]).iter().map(|p| p + Vector3::x()).collect::<Vec<_>>());
    let err = sim.scene_mut().add_body(off.unwrap(), [0.0, 1.0, 0.0], Mass::Total(1.0)).unwrap_err();
    assert!(err.to_string().contains("centre of volume"), "{err}");
}

#[test]
fn an_off_centre_hull_sits_where_its_vertices_say() {
    // A static hull whose vertices are 3 m along x from its origin, placed at z = 1:
    // its geom reports the pose it was given, and a ball dropped on its top lands there.
    let corners: Vec<Point3<f64>> =
        box_corners([1.0, 1.0, 1.0]).iter().map(|p| p + Vector3::new(3.0, 0.5, 0.0)).collect();
    let mut sim = on_the_floor();
    let pose = Isometry3::translation(0.0, 0.0, 1.0);
    let block = sim.scene_mut().add_static(Shape::convex_hull(&corners).unwrap(), pose).unwrap();
    assert_eq!(sim.scene().pose(block).unwrap(), pose);
    let ball = sim.scene_mut().add_sphere(0.1, [3.0, 1.5, 1.0], Mass::Total(0.1)).unwrap();
    sim.scene_mut().set_name(ball, "ball").unwrap();
    let (height, _) = settle(&mut sim, "ball", 1.0);
    assert!((height - 1.1).abs() < 2e-3, "the ball rests at {height}, on the block's top at 1 m");
    sim.scene_mut().set_position(block, [0.0, 0.0, -5.0]).unwrap();
    assert_eq!(sim.scene().pose(block).unwrap(), Isometry3::translation(0.0, 0.0, -5.0));
}

#[test]
fn hulls_come_back_from_scene_files_and_snapshots() {
    let mut sim = on_the_floor();
    let shape = Shape::convex_hull(&sphere_points(0.2, 6, 8)).unwrap();
    let id = sim.scene_mut().add_body(shape.clone(), [0.0, 0.5, 0.0], Mass::Density(500.0)).unwrap();
    sim.scene_mut().set_name(id, "hull").unwrap();
    for _ in 0..50 {
        sim.step().unwrap();
    }
    let loaded = Simulation::load_scene(&sim.save_scene().unwrap()).unwrap();
    assert_eq!(loaded.scene().object("hull").unwrap().shape(), &shape);
    let snapshot = ars::Snapshot::from_bytes(&sim.snapshot().unwrap().to_bytes()).unwrap();
    let mut restored = Simulation::from_snapshot(&snapshot).unwrap();
    assert_eq!(restored.scene().object("hull").unwrap().shape(), &shape);
    for _ in 0..3000 {
        sim.step().unwrap();
        restored.step().unwrap();
    }
    let at = |s: &Simulation| s.scene().position(s.scene().object("hull").unwrap().id()).unwrap();
    assert_eq!(at(&sim), at(&restored), "the restored hull steps bit for bit");
    assert!((at(&sim).y - 0.2).abs() < 0.01, "rests on the floor at {}", at(&sim).y);
}

/// A unit cube as an OBJ file (corners at 0 and 1), its faces wound outwards or in.
fn cube_obj(inwards: bool) -> String {
    let mut text = String::new();
    for p in box_corners([1.0, 1.0, 1.0]) {
        text += &format!("v {} {} {}\n", p.x + 0.5, p.y + 0.5, p.z + 0.5);
    }
    let faces = [[1, 3, 4, 2], [5, 6, 8, 7], [1, 2, 6, 5], [3, 7, 8, 4], [1, 5, 7, 3], [2, 4, 8, 6]];
    for f in faces {
        let f = if inwards { [f[3], f[2], f[1], f[0]] } else { f };
        text += &format!("f {} {} {}\nf {} {} {}\n", f[0], f[1], f[2], f[0], f[2], f[3]);
    }
    text
}

#[test]
fn mjcf_meshes_collide_as_hulls_and_are_drawn_as_meshes() {
    let dir = std::env::temp_dir().join(format!("ars-convex-hulls-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("cube.obj"), cube_obj(false)).unwrap();
    std::fs::write(dir.join("inwards.obj"), cube_obj(true)).unwrap();
    let model = r#"<mujoco><asset><mesh name="cube" file="cube.obj"/><mesh name="inwards" file="inwards.obj"/></asset>
        <worldbody><geom type="plane" size="5 5 0.1"/>
          <body name="block" pos="0 0 0.2"><freejoint/><geom type="mesh" mesh="cube" density="1000"/></body>
          <body name="inside_out" pos="3 0 0.2"><freejoint/><geom type="mesh" mesh="inwards" density="1000"/></body>
        </worldbody></mujoco>"#;
    let mut sim = Simulation::builder().build().unwrap();
    let made = sim.load_mjcf_text(model, dir.join("model.xml").to_str().unwrap(), &MjcfOptions::new()).unwrap();
    let block = sim.scene().object("block").unwrap();
    assert!(matches!(block.shape(), Shape::ConvexHull { .. }), "{:?}", block.shape());
    assert!(matches!(block.visuals()[0].shape, Shape::TriMesh { .. }), "drawn as the mesh");
    let block = block.id();
    let mass = sim.scene().body(block).unwrap().mass();
    assert!((mass - 1000.0).abs() < 1e-9, "{mass}");
    // The cube wound inwards weighs as MuJoCo's (default, legacy) inertia weighs it,
    // each triangle's pyramid taken positive: 1 m³ of 1000 kg/m³, nothing skipped.
    assert!(made.skipped.is_empty(), "{:?}", made.skipped);
    let inside_out = sim.scene().object("inside_out").unwrap().id();
    assert!((sim.scene().body(inside_out).unwrap().mass() - 1000.0).abs() < 1e-9);
    // Resting on the floor: the block's centre 0.5 m up (MuJoCo z is ARS's y).
    for _ in 0..5000 {
        sim.step().unwrap();
    }
    let y = sim.scene().position(block).unwrap().y;
    assert!((y - 0.5).abs() < 2e-3, "{y}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn urdf_collision_meshes_collide_as_hulls_unless_asked_for_triangles() {
    const ARM: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/ars_test_robot/three_link_arm.urdf");
    let shape_of = |options: UrdfOptions| {
        let mut sim = on_the_floor();
        sim.load_urdf(ARM, &options.fixed_base(true)).unwrap();
        sim.scene().object("gripper").unwrap().shape().clone()
    };
    assert!(matches!(shape_of(UrdfOptions::new()), Shape::ConvexHull { vertices, .. } if vertices.len() == 8));
    assert!(matches!(shape_of(UrdfOptions::new().triangle_mesh_collisions(true)), Shape::TriMesh { .. }));
}
