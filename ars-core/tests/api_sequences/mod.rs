//! Turns bytes into a sequence of public API calls on worlds and simulations, with
//! hostile numbers (NaN, ±∞, ±0, subnormals, 1e±300, `f64::MAX`, and values at and
//! just beyond the documented limits), handles that are stale or from another world,
//! and removals in between. Every call may return `Err`; none may abort, crash, hang
//! or panic. Shared by the `cargo fuzz` target (`fuzz/fuzz_targets/api_calls.rs`) and
//! the seeded test `tests/random_api_sequences.rs`.

#![allow(dead_code)]

use ars_core::nalgebra::{Isometry3, Matrix3, Point3, Rotation3, UnitQuaternion, Vector3};
use ars_core::sensors::{
    Accelerometer, ContactSensor, Gps, HingeSensor, Imu, Inclinometer, JointForce, JointPower, JointReaction,
    JointTorque, KineticEnergy, Laser, Noisy, PotentialEnergy, SystemTotalEnergy, TotalEnergy, Velometer,
};
use ars_core::*;

/// Numbers a hostile user would try.
const HOSTILE: [f64; 40] = [
    f64::NAN,
    f64::INFINITY,
    f64::NEG_INFINITY,
    0.0,
    -0.0,
    5e-324,
    -5e-324,
    f64::MIN_POSITIVE,
    1e-300,
    1e-200,
    1e-103,
    1e-20,
    1e-10,
    1e-9,
    0.9e-9,
    1e-6,
    0.001,
    0.1,
    0.5,
    1.0,
    -1.0,
    2.0,
    3.0,
    10.0,
    -10.0,
    100.0,
    1e3,
    1e6,
    2.6e8,
    5e8,
    1e9,
    1.1e9,
    -1e9,
    1e15,
    1e17,
    1e150,
    1e300,
    -1e300,
    f64::MAX,
    f64::MIN,
];

/// Reads the fuzzer's bytes; zeros once they run out.
pub struct Bytes<'a> {
    data: &'a [u8],
    at: usize,
}

impl<'a> Bytes<'a> {
    pub fn new(data: &'a [u8]) -> Self {
        Bytes { data, at: 0 }
    }
    pub fn done(&self) -> bool {
        self.at >= self.data.len()
    }
    pub fn byte(&mut self) -> u8 {
        let b = self.data.get(self.at).copied().unwrap_or(0);
        self.at += 1;
        b
    }
    /// True once in `n` (on average).
    pub fn one_in(&mut self, n: u8) -> bool {
        self.byte().is_multiple_of(n)
    }
    fn index(&mut self, len: usize) -> usize {
        if len == 0 { 0 } else { self.byte() as usize % len }
    }
    /// Mostly ordinary values, often hostile ones, sometimes any bit pattern.
    pub fn real(&mut self) -> f64 {
        let b = self.byte();
        match b {
            0..=79 => (b as f64 - 40.0) * 0.25,
            80..=239 => HOSTILE[(b as usize - 80) % HOSTILE.len()],
            _ => {
                let mut raw = [0u8; 8];
                raw.iter_mut().for_each(|r| *r = self.byte());
                f64::from_le_bytes(raw)
            }
        }
    }
    pub fn positive(&mut self) -> f64 {
        let x = self.real();
        if self.byte() < 200 { x.abs() } else { x }
    }
    pub fn vector(&mut self) -> Vector3<f64> {
        Vector3::new(self.real(), self.real(), self.real())
    }
    pub fn point(&mut self) -> Point3<f64> {
        Point3::from(self.vector())
    }
    pub fn rotation(&mut self) -> Rotation3<f64> {
        match self.byte() % 4 {
            0 => Rotation3::identity(),
            1 => Rotation3::from_axis_angle(&Vector3::x_axis(), self.real()),
            2 => Rotation3::from_scaled_axis(self.vector()),
            _ => Rotation3::from_matrix_unchecked(Matrix3::from_fn(|_, _| self.real())),
        }
    }
    pub fn quaternion(&mut self) -> UnitQuaternion<f64> {
        match self.byte() % 3 {
            0 => UnitQuaternion::from_scaled_axis(self.vector()),
            1 => UnitQuaternion::new_unchecked(ars_core::nalgebra::Quaternion::new(
                self.real(),
                self.real(),
                self.real(),
                self.real(),
            )),
            _ => UnitQuaternion::identity(),
        }
    }
    pub fn isometry(&mut self) -> Isometry3<f64> {
        Isometry3::from_parts(self.vector().into(), self.quaternion())
    }
    pub fn amount(&mut self) -> Mass {
        if self.one_in(2) { Mass::Total(self.real()) } else { Mass::Density(self.real()) }
    }
}

/// One world and what it handed out (removed objects' handles stay, to be reused).
struct WorldState {
    world: World,
    spaces: Vec<SpaceHandle>,
    bodies: Vec<BodyHandle>,
    geoms: Vec<GeomHandle>,
    joints: Vec<JointHandle>,
}

struct SimState {
    sim: Simulation,
    objects: Vec<ObjectId>,
    joints: Vec<JointId>,
    gps: Vec<SensorId<Gps>>,
}

/// Everything a sequence acts on.
pub struct Harness {
    worlds: Vec<WorldState>,
    sims: Vec<SimState>,
    /// Whether hooks may panic (not under libFuzzer, whose panic hook aborts).
    panicking_hooks: bool,
}

fn pick<T: Copy>(items: &[T], input: &mut Bytes<'_>) -> Option<T> {
    if items.is_empty() { None } else { Some(items[input.index(items.len())]) }
}

impl Harness {
    /// Runs calls until the bytes run out (at most `max_calls`). With
    /// `panicking_hooks`, some hooks panic (the simulation must contain it).
    pub fn run(input: &[u8], max_calls: usize, panicking_hooks: bool) {
        let mut input = Bytes::new(input);
        let mut harness = Harness { worlds: Vec::new(), sims: Vec::new(), panicking_hooks };
        for _ in 0..max_calls {
            if input.done() {
                break;
            }
            harness.call(&mut input);
        }
    }

    fn shape(input: &mut Bytes<'_>) -> Shape {
        match input.byte() % 7 {
            0 => Shape::Sphere { radius: input.positive() },
            1 => Shape::Box { edges: input.vector() },
            2 => Shape::Capsule { radius: input.positive(), length: input.positive() },
            3 => Shape::Cylinder { radius: input.positive(), length: input.positive() },
            4 => Shape::Plane { normal: input.vector(), distance: input.real() },
            5 => Shape::Ray { length: input.positive() },
            _ => {
                let n = 1 + input.byte() as usize % 5;
                let vertices = (0..n + 2).map(|_| input.point()).collect();
                let triangles = (0..n)
                    .map(|_| [input.byte() as u32 % 8, input.byte() as u32 % 8, input.byte() as u32 % 8])
                    .collect();
                Shape::TriMesh { vertices, triangles }
            }
        }
    }

    fn mass(input: &mut Bytes<'_>) -> MassSpec {
        match input.byte() % 5 {
            0 => MassSpec::solid(Shape::Sphere { radius: input.positive() }, input.amount()),
            1 => MassSpec::solid(Shape::Box { edges: input.vector() }, input.amount()),
            2 => MassSpec::solid(Shape::Capsule { radius: input.positive(), length: input.positive() }, input.amount()),
            3 => {
                MassSpec::solid(Shape::Cylinder { radius: input.positive(), length: input.positive() }, input.amount())
            }
            _ => MassSpec::Custom {
                mass: input.positive(),
                inertia: Matrix3::from_fn(|r, c| if r == c { input.positive() } else { input.real() * 0.1 }),
            },
        }
    }

    /// One call (or a short burst of steps).
    fn call(&mut self, input: &mut Bytes<'_>) {
        let op = input.byte();
        if op < 150 || self.sims.is_empty() && op >= 230 {
            self.world_call(op, input);
        } else {
            self.sim_call(op, input);
        }
    }

    fn world_call(&mut self, op: u8, input: &mut Bytes<'_>) {
        if self.worlds.is_empty() || op.is_multiple_of(50) && self.worlds.len() < 3 {
            let mut world = World::new();
            let space = world.create_space(SpaceKind::Simple).unwrap();
            self.worlds.push(WorldState { world, spaces: vec![space], bodies: vec![], geoms: vec![], joints: vec![] });
            return;
        }
        let wi = input.index(self.worlds.len());
        // Handles of another world, now and then.
        let other = input.index(self.worlds.len());
        let (bodies_from, geoms_from, joints_from, spaces_from) = {
            let o = &self.worlds[other];
            (o.bodies.clone(), o.geoms.clone(), o.joints.clone(), o.spaces.clone())
        };
        let w = &mut self.worlds[wi];
        let body = pick(&bodies_from, input);
        let body2 = pick(&bodies_from, input);
        let geom = pick(&geoms_from, input);
        let joint = pick(&joints_from, input);
        let space = pick(&spaces_from, input);
        match op % 25 {
            0 => {
                let mut b = BodyBuilder::new();
                if input.one_in(2) {
                    b = b.mass(Self::mass(input));
                }
                if input.one_in(2) {
                    b = b.position(input.point()).rotation(input.rotation());
                }
                if input.one_in(3) {
                    b = b.linear_velocity(input.vector()).angular_velocity(input.vector());
                }
                if input.one_in(5) {
                    b = BodyBuilder::kinematic().position(input.point());
                }
                if let Ok(h) = w.world.insert_body(b) {
                    w.bodies.push(h);
                }
            }
            1 | 2 => {
                let Some(space) = space else { return };
                let mut g = GeomBuilder::new(Self::shape(input));
                match (input.byte() % 3, body) {
                    (0, Some(b)) => {
                        g = g.attached_to(b);
                        if input.one_in(2) {
                            g = g.offset(input.isometry());
                        }
                    }
                    (1, _) => g = g.pose(input.isometry()),
                    _ => {}
                }
                if input.one_in(4) {
                    g = g.category_bits(u64::from(input.byte())).collide_bits(u64::from(input.byte()));
                }
                if let Ok(h) = w.world.insert_geom(space, g) {
                    w.geoms.push(h);
                }
            }
            3 => {
                let kind = match input.byte() % 9 {
                    0 => JointKind::Fixed,
                    1 => JointKind::Hinge { anchor: input.point(), axis: input.vector() },
                    2 => JointKind::Slider { axis: input.vector() },
                    3 => JointKind::Universal { anchor: input.point(), axis1: input.vector(), axis2: input.vector() },
                    4 => JointKind::Ball { anchor: input.point() },
                    5 => JointKind::Hinge2 { anchor: input.point(), axis1: input.vector(), axis2: input.vector() },
                    6 => JointKind::Piston { anchor: input.point(), axis: input.vector() },
                    7 => JointKind::AngularMotor { axes: vec![(AxisFrame::World, input.vector())] },
                    _ => JointKind::LinearMotor {
                        axes: vec![(AxisFrame::Body1, input.vector()), (AxisFrame::Body2, input.vector())],
                    },
                };
                let Some(b1) = body else { return };
                let mut j = JointBuilder::new(kind);
                j = match body2 {
                    Some(b2) if !input.one_in(3) => j.between(b1, b2),
                    _ => j.to_world(b1),
                };
                if input.one_in(2) {
                    j = j.limits(input.real(), input.real());
                }
                if input.one_in(2) {
                    j = j.motor(input.real(), input.real()).feedback();
                }
                if let Ok(h) = w.world.insert_joint(j) {
                    w.joints.push(h);
                }
            }
            4 => {
                let _ = body.map(|b| w.world.remove_body(b));
            }
            5 => {
                let _ = geom.map(|g| w.world.remove_geom(g));
            }
            6 => {
                let _ = joint.map(|j| w.world.remove_joint(j));
            }
            7 => {
                let Some(b) = body else { return };
                let Ok(mut bm) = w.world.body_mut(b) else { return };
                let _ = match input.byte() % 8 {
                    0 => bm.set_position(input.point()),
                    1 => bm.set_rotation(input.rotation()),
                    2 => bm.set_quaternion(input.quaternion()),
                    3 => bm.set_pose(input.isometry()),
                    4 => bm.set_linear_velocity(input.vector()),
                    5 => bm.set_angular_velocity(input.vector()),
                    6 => bm.set_mass(Self::mass(input)),
                    _ => {
                        bm.set_kinematic(input.one_in(2));
                        bm.set_enabled(!input.one_in(4));
                        bm.set_gravity_enabled(!input.one_in(4));
                        Ok(())
                    }
                };
            }
            8 | 9 => {
                let Some(b) = body else { return };
                let Ok(mut bm) = w.world.body_mut(b) else { return };
                let repeat = 1 + input.byte() % 4;
                for _ in 0..repeat {
                    let _ = match input.byte() % 7 {
                        0 => bm.add_force(input.vector()),
                        1 => bm.add_torque(input.vector()),
                        2 => bm.add_relative_force(input.vector()),
                        3 => bm.add_relative_torque(input.vector()),
                        4 => bm.add_force_at_point(input.vector(), input.point()),
                        5 => bm.add_relative_force_at_relative_point(input.vector(), input.point()),
                        _ => {
                            bm.clear_forces();
                            Ok(())
                        }
                    };
                }
            }
            10 => {
                let Some(j) = joint else { return };
                let Ok(mut jm) = w.world.joint_mut(j) else { return };
                let axis = input.byte() as usize % 4;
                let _ = match input.byte() % 7 {
                    0 => jm.set_limits(axis, input.real(), input.real()),
                    1 => jm.set_motor(axis, input.real(), input.real()),
                    2 => jm.add_torque(input.real()),
                    3 => jm.add_torques(input.real(), input.real()),
                    4 => jm.add_force(input.real()),
                    5 => {
                        let params = [
                            JointParam::LoStop,
                            JointParam::HiStop,
                            JointParam::Velocity,
                            JointParam::MaxForce,
                            JointParam::FudgeFactor,
                            JointParam::Bounce,
                            JointParam::Cfm,
                            JointParam::StopErp,
                            JointParam::StopCfm,
                        ];
                        jm.set_param(params[input.index(params.len())], axis, input.real())
                    }
                    _ => {
                        jm.enable_feedback();
                        Ok(())
                    }
                };
            }
            11..=15 => {
                // Steps: the usual collide / step / clear loop.
                let Some(space) = space else { return };
                let dt = if input.one_in(4) { input.real() } else { 0.0004 };
                let steps = 1 + input.byte() as usize % 20;
                for _ in 0..steps {
                    let collided = w.world.collide(space);
                    let stepped = w.world.step(dt);
                    w.world.clear_contacts();
                    if collided.is_err() || stepped.is_err() {
                        break;
                    }
                }
            }
            16 => {
                let _ = match input.byte() % 5 {
                    0 => w.world.set_gravity(input.vector()),
                    1 => w.world.set_erp(input.real()),
                    2 => w.world.set_cfm(input.real()),
                    3 => w.world.set_stepper(Stepper::Quick { iterations: u32::from(input.byte()) }),
                    _ => w.world.set_stepper(Stepper::Exact),
                };
                w.world.set_random_seed(u32::from(input.byte()));
            }
            17 => {
                let kind = match input.byte() % 3 {
                    0 => SpaceKind::Simple,
                    1 => SpaceKind::Hash {
                        min_level: i32::from(input.byte() as i8),
                        max_level: i32::from(input.byte() as i8),
                    },
                    _ => sweep_and_prune(input.byte()),
                };
                if let Ok(s) = w.world.create_space(kind) {
                    w.spaces.push(s);
                }
            }
            18 => {
                let Some(g) = geom else { return };
                let Ok(mut gm) = w.world.geom_mut(g) else { return };
                // Bits of 0 often: a geom with neither category nor collide bits
                // leaves ODE's space, and comes back with bits again.
                let bits = |input: &mut Bytes<'_>| if input.one_in(2) { 0 } else { u64::from(input.byte()) };
                let _ = match input.byte() % 7 {
                    0 => gm.set_position(input.point()),
                    1 => gm.set_rotation(input.rotation()),
                    2 => gm.set_pose(input.isometry()),
                    3 => gm.set_ray_length(input.real()),
                    4 => {
                        gm.set_enabled(input.one_in(2));
                        Ok(())
                    }
                    5 => {
                        gm.set_category_bits(bits(input));
                        Ok(())
                    }
                    _ => {
                        gm.set_collide_bits(bits(input));
                        Ok(())
                    }
                };
            }
            19 => {
                let surface = ContactSurface {
                    mu: input.real(),
                    mu2: (input.one_in(2)).then(|| input.real()),
                    bounce: (input.one_in(2)).then(|| (input.real(), input.real())),
                    soft_erp: (input.one_in(3)).then(|| input.real()),
                    soft_cfm: (input.one_in(3)).then(|| input.real()),
                    approx1: input.one_in(2),
                    rolling: (input.one_in(3)).then(|| [input.real(), input.real(), input.real()]),
                    max_contacts: input.byte() as usize,
                };
                let _ = w.world.set_default_surface(surface);
            }
            20 => {
                // Reads of everything, including stale and foreign handles.
                if let Some(Ok(b)) = body.map(|b| w.world.body(b)) {
                    let _ = (b.pose(), b.linear_velocity(), b.angular_velocity(), b.inertia_world(), b.force());
                    let _ = b.point_velocity(Point3::new(1.0, 2.0, 3.0));
                }
                if let Some(Ok(g)) = geom.map(|g| w.world.geom(g)) {
                    let _ = (g.pose(), g.aabb(), g.ray(), g.shape().kind_name());
                }
                if let Some(Ok(j)) = joint.map(|j| w.world.joint(j)) {
                    let _ = (j.angle(), j.angle_rate(), j.angle2(), j.position(), j.anchor(), j.axis(), j.feedback());
                    let _ = j.param(JointParam::HiStop, input.byte() as usize % 4);
                }
                let _ = (w.world.contacts().len(), w.world.ray_hits().len(), w.world.diverged_body());
            }
            21 => {
                // Drop a world (a poisoned one included) and start a new one.
                self.worlds.swap_remove(wi);
            }
            _ => {
                // Reset a diverged body, as a user would.
                if let Some(b) = w.world.diverged_body()
                    && let Ok(mut bm) = w.world.body_mut(b)
                {
                    let _ = bm.set_position(Point3::origin());
                    let _ = bm.set_linear_velocity(Vector3::zeros());
                    let _ = bm.set_angular_velocity(Vector3::zeros());
                    bm.clear_forces();
                }
            }
        }
    }

    fn sim_call(&mut self, op: u8, input: &mut Bytes<'_>) {
        if self.sims.is_empty() || op.is_multiple_of(40) && self.sims.len() < 2 {
            let mut b = Simulation::builder();
            if input.one_in(2) {
                b = b.floor_plane(Vector3::y(), 0.0);
            }
            if input.one_in(4) {
                b = b.time_step(input.real()).gravity(input.vector()).erp(input.real()).cfm(input.real());
            }
            if input.one_in(4) {
                b = b.space(SpaceKind::Hash {
                    min_level: i32::from(input.byte() as i8),
                    max_level: i32::from(input.byte() as i8),
                });
            } else if input.one_in(4) {
                b = b.space(SpaceKind::Simple);
            } else if input.one_in(2) {
                b = b.space(sweep_and_prune(input.byte()));
            }
            if input.one_in(4) {
                b = b.stepper(Stepper::Quick { iterations: 1 + u32::from(input.byte()) }).seed(7);
            }
            if let Ok(sim) = b.build() {
                self.sims.push(SimState { sim, objects: vec![], joints: vec![], gps: vec![] });
            }
            return;
        }
        let si = input.index(self.sims.len());
        let other = input.index(self.sims.len());
        let (objects_from, joints_from) = (self.sims[other].objects.clone(), self.sims[other].joints.clone());
        let s = &mut self.sims[si];
        let object = pick(&objects_from, input);
        let object2 = pick(&objects_from, input);
        let joint = pick(&joints_from, input);
        match op % 16 {
            0 | 1 => {
                let c = input.point();
                let m = input.amount();
                let r = match input.byte() % 6 {
                    0 => s.sim.scene_mut().add_sphere(input.real(), c, m),
                    1 => s.sim.scene_mut().add_box(input.vector(), c, m),
                    2 => s.sim.scene_mut().add_cylinder(input.real(), input.real(), c, m),
                    3 => s.sim.scene_mut().add_capsule(input.real(), input.real(), c, m),
                    4 => s.sim.scene_mut().add_cone(input.real(), input.real(), c, m),
                    _ => s.sim.scene_mut().add_static(Shape::Box { edges: input.vector() }, input.isometry()),
                };
                if let Ok(id) = r {
                    s.objects.push(id);
                }
            }
            2 => {
                let v = vec![input.point(), input.point(), input.point(), input.point()];
                let n = 1 + input.byte() as usize % 2;
                let faces = (0..n).map(|i| [0, 1 + i as u32, 2 + i as u32]).collect();
                if let Ok(id) = s.sim.scene_mut().add_trimesh_floor(v, faces, input.point()) {
                    s.objects.push(id);
                }
            }
            3 => {
                let Some(o1) = object else { return };
                let end = match object2 {
                    Some(o2) if !input.one_in(3) => JointEnd::Object(o2),
                    _ => JointEnd::World,
                };
                let name = if input.one_in(2) { "" } else { "j" };
                if input.one_in(4) {
                    // A joint group: mostly perpendicular axes (what it takes), sometimes any.
                    let axes = [Vector3::x(), Vector3::y(), Vector3::z()];
                    let (n, anchor, turn) = (2 + input.index(4), input.point(), input.index(3));
                    let joints: Vec<GroupJoint> = (0..n)
                        .map(|k| GroupJoint {
                            name: if input.one_in(2) { String::new() } else { format!("g{k}") },
                            kind: if input.one_in(2) { JointType::Slider } else { JointType::Hinge },
                            anchor,
                            axis: if input.one_in(5) { input.vector() } else { axes[(k + turn) % 3] },
                            reference: if input.one_in(3) { input.real() } else { 0.0 },
                        })
                        .collect();
                    if let Ok(ids) = s.sim.scene_mut().add_joint_group(o1, end, &joints) {
                        s.joints.extend(ids);
                    }
                    return;
                }
                let r = match input.byte() % 6 {
                    0 => s.sim.scene_mut().add_fixed_joint(name, o1, end),
                    1 => s.sim.scene_mut().add_hinge_joint(name, o1, end, Some(input.point()), input.vector()),
                    2 => s.sim.scene_mut().add_slider_joint(name, o1, end, input.vector()),
                    3 => s.sim.scene_mut().add_universal_joint(
                        name,
                        o1,
                        end,
                        input.point(),
                        input.vector(),
                        input.vector(),
                    ),
                    4 => s.sim.scene_mut().add_ball_joint(name, o1, end, None),
                    _ => s.sim.scene_mut().add_piston_joint(name, o1, end, input.point(), input.vector()),
                };
                if let Ok(id) = r {
                    s.joints.push(id);
                }
            }
            4 => {
                let Some(j) = joint else { return };
                let leader = if s.joints.is_empty() { None } else { Some(s.joints[input.index(s.joints.len())]) };
                let Ok(mut jm) = s.sim.scene_mut().joint_mut(j) else { return };
                let _ = match input.byte() % 12 {
                    0 => jm.add_torque(input.real()),
                    1 => jm.add_force(input.real()),
                    2 => jm.set_speed(input.real(), input.real()),
                    3 => jm.set_limits(input.real(), input.real()),
                    4 => jm.set_viscous_friction(input.real()),
                    5 => jm.set_dry_friction(input.real()),
                    6 => jm.set_actuator_limits(ActuatorLimits { effort: input.real(), velocity: input.real() }),
                    7 => match leader {
                        Some(l) => jm.set_mimic(l, input.real(), input.real()),
                        None => jm.clear_mimic(),
                    },
                    8 => jm.clear_mimic(),
                    9 => jm.set_armature(input.real()),
                    10 => jm.set_damping(input.real()),
                    _ => {
                        let (target, kp, kd) = (input.real(), input.real(), input.real());
                        Profile::new(vec![(0.0, target)]).and_then(|p| jm.set_controller(PositionServo::pd(p, kp, kd)))
                    }
                };
            }
            5 => {
                let _ = object.map(|o| s.sim.remove_object(o));
            }
            6 => {
                let _ = joint.map(|j| s.sim.remove_joint(j));
            }
            7 => {
                let Some(o) = object else { return };
                let r: Result<()> = match input.byte() % 14 {
                    0 => s.sim.add_sensor(Gps::new(o)).map(|id| s.gps.push(id)),
                    1 => s.sim.add_sensor(Velometer::new(o)).map(drop),
                    2 => s.sim.add_sensor_every(Accelerometer::new(o), input.real()).map(drop),
                    3 => s.sim.add_sensor(Inclinometer::new(o)).map(drop),
                    4 => s.sim.add_sensor(Imu::new(o)).map(drop),
                    5 => s.sim.add_sensor(ContactSensor::new(o)).map(drop),
                    6 => s.sim.add_sensor(KineticEnergy::new(o)).map(drop),
                    7 => s.sim.add_sensor(PotentialEnergy::new(o)).map(drop),
                    8 => s.sim.add_sensor(TotalEnergy::new(o)).map(drop),
                    9 => s.sim.add_sensor(SystemTotalEnergy::new()).map(drop),
                    10 => s.sim.add_sensor(Laser::new(input.real()).mounted_on(o, input.isometry())).map(drop),
                    11 => s.sim.add_sensor(Laser::new(input.real()).at(input.point(), input.rotation())).map(drop),
                    12 => Noisy::new(Gps::new(o), input.real(), 3).and_then(|n| s.sim.add_sensor(n)).map(drop),
                    _ => match joint {
                        Some(j) => match input.byte() % 5 {
                            0 => s.sim.add_sensor(HingeSensor::new(j)).map(drop),
                            1 => s.sim.add_sensor(JointTorque::new(j)).map(drop),
                            2 => s.sim.add_sensor(JointForce::new(j)).map(drop),
                            3 => s.sim.add_sensor(JointPower::new(j)).map(drop),
                            _ => s.sim.add_sensor(JointReaction::new(j)).map(drop),
                        },
                        None => Ok(()),
                    },
                };
                let _ = r;
            }
            8 => {
                if let Some(g) = pick(&s.gps, input) {
                    let _ = match input.byte() % 3 {
                        0 => s.sim.remove_sensor(g).map(drop),
                        1 => s.sim.records(g).map(|log| {
                            let mut out = Vec::new();
                            let _ = log.write_csv(&mut out);
                        }),
                        _ => s.sim.clear_records(g),
                    };
                }
            }
            9..=11 => {
                let _ = match input.byte() % 4 {
                    0 => s.sim.step(),
                    1 => s.sim.step_n(u64::from(input.byte() % 30)),
                    2 => s.sim.step_frame(),
                    // At most 100 steps: a tiny time step makes a long duration a
                    // legitimately long run, not a hang.
                    _ => s.sim.run_for(input.real().min(100.0 * s.sim.scene().time_step())),
                };
            }
            12 => {
                let _ = s.sim.scene_mut().set_time_step(input.real());
            }
            13 => {
                let Some(o) = object else { return };
                let _ = match input.byte() % 7 {
                    0 => s.sim.scene_mut().set_position(o, input.point()),
                    1 => s.sim.scene_mut().set_rotation(o, input.rotation()),
                    2 => s.sim.scene_mut().rotate(o, input.vector(), input.real()),
                    3 => s.sim.scene_mut().offset_by_position(o, input.vector()),
                    4 => s.sim.scene_mut().body_mut(o).and_then(|mut b| b.add_force(input.vector())),
                    5 => s.sim.scene_mut().body_mut(o).and_then(|mut b| b.set_linear_velocity(input.vector())),
                    // A pair of geoms' own contact (possibly of another world, or the same
                    // geom twice), with hostile parameters.
                    _ => {
                        let other = object2.unwrap_or(o);
                        let contact = GeomContact {
                            friction: [input.real(), input.real(), input.real()],
                            condim: input.byte() % 8,
                            solref: [input.real(), input.real()],
                            solimp: [input.real(), input.real(), input.real(), input.real(), input.real()],
                            priority: i32::from(input.byte()),
                            solmix: input.real(),
                        };
                        let (k1, k2) = (usize::from(input.byte() % 3), usize::from(input.byte() % 3));
                        s.sim.scene_mut().set_geom_pair_contact((o, k1), (other, k2), contact)
                    }
                };
            }
            14 => {
                // A hook that sometimes fails or panics.
                let mode = input.byte() % if self.panicking_hooks { 3 } else { 2 };
                let mut calls = 0u32;
                let _ = s.sim.add_hooks(PreStep(move |_| {
                    calls += 1;
                    match (mode, calls % 7) {
                        (1, 0) => Err(Error::User("hook error".into())),
                        (2, 0) => panic!("hook panic"),
                        _ => Ok(()),
                    }
                }));
            }
            _ => {
                let _ = (s.sim.scene().time(), s.sim.scene().objects().count(), s.sim.scene().world().body_count());
                if let Some(o) = object {
                    let _ = (
                        s.sim.scene().pose(o),
                        s.sim.scene().object(o).map(|v| v.name().len()),
                        s.sim.scene().body(o).map(|b| b.position()),
                    );
                }
                if let Some(j) = joint {
                    let _ = (s.sim.scene().joint_state(j), s.sim.scene().joint(j).map(|v| v.efforts()));
                }
            }
        }
    }
}

/// A sweep-and-prune space in one of the six axis orders, or (one time in seven) the
/// grid.
fn sweep_and_prune(byte: u8) -> SpaceKind {
    let orders = [AxisOrder::Xyz, AxisOrder::Xzy, AxisOrder::Yxz, AxisOrder::Yzx, AxisOrder::Zxy, AxisOrder::Zyx];
    match usize::from(byte) % 7 {
        6 => SpaceKind::Grid,
        k => SpaceKind::SweepAndPrune { axes: orders[k] },
    }
}
