//! MJCF bodies weighed as MuJoCo's compiler weighs them (issue 37): meshes by their
//! `<mesh inertia>` (legacy by default) and their class's scale, meshes given by vertex
//! data, flat visual meshes as shells, `<compiler boundmass boundinertia>`, boxes placed
//! by `fromto`; and joints limited as MuJoCo limits them. The numbers are MuJoCo
//! 4.0.0's (`body_mass`, `body_ipos`, `body_inertia`) for the same files.

use ars::nalgebra::{Point3, Vector3};
use ars::{MjcfOptions, Simulation};

/// A U-shaped prism 1 deep (a 1-wide notch in a 3-square), as an OBJ file: closed and
/// wound outwards, but not star-shaped from its centre, so that MuJoCo's legacy
/// inertia weighs more than the solid.
fn u_prism_obj() -> String {
    let profile = [(0, 0), (3, 0), (3, 3), (2, 3), (2, 1), (1, 1), (1, 3), (0, 3)];
    let n = profile.len();
    let mut text = String::new();
    for z in [0, 1] {
        for (x, y) in profile {
            text += &format!("v {x} {y} {z}\n");
        }
    }
    let mut face = |a: usize, b: usize, c: usize| text += &format!("f {} {} {}\n", a + 1, b + 1, c + 1);
    for [a, b, c] in [[0, 1, 4], [0, 4, 5], [1, 2, 3], [1, 3, 4], [0, 5, 6], [0, 6, 7]] {
        face(a, c, b);
        face(a + n, b + n, c + n);
    }
    for i in 0..n {
        let j = (i + 1) % n;
        face(i, j, j + n);
        face(i, j + n, i + n);
    }
    text
}

const MODEL: &str = r#"<mujoco><compiler boundmass="0.25" boundinertia="0.01"/>
  <default><mesh scale="0.5 0.5 0.5"/><default class="exact"><mesh inertia="exact"/></default></default>
  <asset>
    <mesh name="u" file="u.obj"/><mesh name="u_exact" class="exact" file="u.obj"/>
    <mesh name="flat" file="flat.obj" inertia="shell"/>
    <mesh name="tetra" vertex="0 0 0 1 0 0 0 1 0 0 0 1"/>
  </asset>
  <worldbody>
    <body name="legacy" pos="0 0 1"><freejoint/><geom type="mesh" mesh="u" density="1000"/></body>
    <body name="exact" pos="2 0 1"><freejoint/><geom type="mesh" mesh="u_exact" density="1000"/></body>
    <body name="screen" pos="4 0 1"><freejoint/><geom type="mesh" mesh="flat" density="1000" contype="0" conaffinity="0"/></body>
    <body name="tetra" pos="6 0 1"><freejoint/><geom type="mesh" mesh="tetra" density="1000"/></body>
    <body name="light" pos="8 0 1"><freejoint/><geom type="sphere" size="0.01" density="1000"/></body>
    <body name="plank" pos="10 0 1"><freejoint/><geom type="box" fromto="0 0 0 0 0 1" size="0.1 0.3 7"/></body>
  </worldbody></mujoco>"#;

/// MuJoCo 4.0.0's mass, centre of mass (world, z up) and principal moments (smallest
/// first) of each body of [`MODEL`].
const MUJOCOS: [(&str, f64, [f64; 3], [f64; 3]); 6] = [
    (
        "legacy",
        1077.1925114547541,
        [0.75, 0.7131550687285224, 1.25],
        [209.34778528175562, 233.17981278636876, 401.0144519484223],
    ),
    (
        "exact",
        874.9999999999999,
        [2.75, 0.6785714285714287, 1.25],
        [188.2440476190476, 223.95833333333326, 375.7440476190475],
    ),
    ("screen", 250.0, [4.25, 0.25, 1.0], [5.208333333333333, 5.208333333333333, 10.416666666666666]),
    ("tetra", 20.833333333333332, [6.125, 0.125, 1.125], [0.3255208333333331, 0.3255208333333331, 0.5208333333333329]),
    ("light", 0.25, [8.0, 0.0, 1.0], [0.01, 0.01, 0.01]),
    ("plank", 40.0, [10.0, 0.0, 1.5], [0.2666666666666668, 3.4666666666666672, 3.4666666666666672]),
];

#[test]
fn bodies_weigh_what_mujoco_compiles_them_to() {
    let dir = std::env::temp_dir().join(format!("ars-mjcf-mass-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("u.obj"), u_prism_obj()).unwrap();
    // A unit square: flat, weighed as a shell (its area), in a geom that never collides.
    std::fs::write(dir.join("flat.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 4\nf 1 4 3\n").unwrap();
    let mut sim = Simulation::builder().gravity(Vector3::zeros()).build().unwrap();
    let path = dir.join("model.xml");
    let model = sim.load_mjcf_text(MODEL, path.to_str().unwrap(), &MjcfOptions::new()).unwrap();
    let close = |ours: f64, mujocos: f64| (ours - mujocos).abs() <= 1e-9 * mujocos.abs().max(1.0);
    for (name, mass, centre, moments) in MUJOCOS {
        let body = sim.scene().body(model.body(name).unwrap()).unwrap();
        assert!(close(body.mass(), mass), "{name}: mass {} vs MuJoCo's {mass}", body.mass());
        // MuJoCo's z up is ARS's y up: (x, y, z) is (x, z, −y).
        let at = body.position();
        let expected = Point3::new(centre[0], centre[2], -centre[1]);
        assert!((at - expected).norm() < 1e-9, "{name}: centre {at} vs MuJoCo's {expected}");
        let mut ours: Vec<f64> = body.inertia().symmetric_eigenvalues().iter().copied().collect();
        ours.sort_by(f64::total_cmp);
        for (ours_k, mujocos) in ours.iter().zip(moments) {
            assert!(close(*ours_k, mujocos), "{name}: moments {ours:?} vs MuJoCo's {moments:?}");
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Brax's colour_objects.xml: a class makes every joint `limited="true"`, its free
/// joints too, which MuJoCo never limits; and "auto" limits only a range that is not
/// empty (MuJoCo compiles `range="10 -10"` as unlimited).
#[test]
fn a_free_joint_is_never_limited_and_an_empty_auto_range_is_no_limit() {
    let text = r#"<mujoco><default><joint limited="true"/></default><worldbody>
        <body name="ball"><joint type="free"/><geom size="0.1"/></body>
        <body name="arm" pos="1 0 0"><joint name="free_turn" limited="auto" range="10 -10"/><geom size="0.1"/></body>
        </worldbody></mujoco>"#;
    let mut sim = Simulation::builder().build().unwrap();
    sim.load_mjcf_text(text, "limits.xml", &MjcfOptions::new()).unwrap();
    let hinge = sim.scene().joint("free_turn").unwrap().ode().unwrap();
    let lo = hinge.param(ars::JointParam::LoStop, 0).unwrap();
    assert!(lo.is_infinite() && lo < 0.0, "no lower stop: {lo}");
}
