//! Safe wrapper over the C reference scenes.

use std::ffi::c_int;

// The C scenes are compiled into this crate by its build script; libode is linked
// through ode-sys.
use ode_sys as _;

#[repr(C)]
struct ArsCScene {
    _opaque: [u8; 0],
}

unsafe extern "C" {
    fn ars_c_falling_sphere_new() -> *mut ArsCScene;
    fn ars_c_hinge_chain_new() -> *mut ArsCScene;
    fn ars_c_drop_pile_new(count: c_int) -> *mut ArsCScene;
    fn ars_c_two_ball_laser_new() -> *mut ArsCScene;
    fn ars_c_conical_pendulum_new() -> *mut ArsCScene;
    fn ars_c_speed_profile_new() -> *mut ArsCScene;
    fn ars_c_sinusoidal_terrain_new() -> *mut ArsCScene;
    fn ars_c_scene_row(scene: *const ArsCScene, out: *mut f64);
    fn ars_c_scene_ray_distance(scene: *const ArsCScene) -> f64;
    fn ars_c_scene_time(scene: *const ArsCScene) -> f64;
    fn ars_c_drop_pile_position(i: c_int, out: *mut f64);
    fn ars_c_scene_step(scene: *mut ArsCScene, steps: c_int);
    fn ars_c_scene_body_count(scene: *const ArsCScene) -> c_int;
    fn ars_c_scene_body_state(scene: *const ArsCScene, index: c_int, out: *mut f64);
    fn ars_c_scene_free(scene: *mut ArsCScene);
}

/// One C scene, freed on drop.
pub struct CScene(*mut ArsCScene);

/// Position (3), quaternion w x y z (4), linear velocity (3), angular velocity (3).
pub type BodyState = [f64; 13];

impl CScene {
    fn wrap(make: unsafe extern "C" fn() -> *mut ArsCScene) -> Self {
        // ODE must be initialised (once per process, by ars-core) before the C code runs.
        ars_core::ensure_ode_ready();
        // SAFETY: plain constructor; the result is owned by the wrapper.
        let raw = unsafe { make() };
        assert!(!raw.is_null());
        CScene(raw)
    }
    /// The thesis' falling ball.
    pub fn falling_sphere() -> Self {
        Self::wrap(ars_c_falling_sphere_new)
    }
    /// Two hinged cylinders with a torque on the first hinge.
    pub fn hinge_chain() -> Self {
        Self::wrap(ars_c_hinge_chain_new)
    }
    /// The thesis' two balls and laser (the `TwoBallLaser` program).
    pub fn two_ball_laser() -> Self {
        Self::wrap(ars_c_two_ball_laser_new)
    }
    /// IROS example 2 (the `ConicalPendulum` program).
    pub fn conical_pendulum() -> Self {
        Self::wrap(ars_c_conical_pendulum_new)
    }
    /// IROS example 3 (the `SpeedProfile` program).
    pub fn speed_profile() -> Self {
        Self::wrap(ars_c_speed_profile_new)
    }
    /// IROS example 4 (the `SinusoidalTerrain` program).
    pub fn sinusoidal_terrain() -> Self {
        Self::wrap(ars_c_sinusoidal_terrain_new)
    }
    /// The row the last pre-step hook recorded (the programs' CSV columns).
    pub fn row(&self) -> [f64; 9] {
        let mut out = [0.0; 9];
        // SAFETY: the scene is live and `out` holds 9 reals.
        unsafe { ars_c_scene_row(self.0, out.as_mut_ptr()) };
        out
    }
    /// Closest ray hit of the last step, if any.
    pub fn ray_distance(&self) -> Option<f64> {
        // SAFETY: the scene is live.
        let d = unsafe { ars_c_scene_ray_distance(self.0) };
        (d >= 0.0).then_some(d)
    }
    /// Accumulated time, s.
    pub fn time(&self) -> f64 {
        // SAFETY: the scene is live.
        unsafe { ars_c_scene_time(self.0) }
    }
    /// `count` spheres and boxes dropped in a hash space.
    pub fn drop_pile(count: usize) -> Self {
        ars_core::ensure_ode_ready();
        // SAFETY: plain constructor (the C side caps the count at its array size).
        let raw = unsafe { ars_c_drop_pile_new(count as c_int) };
        assert!(!raw.is_null());
        CScene(raw)
    }
    /// Runs `n` steps.
    pub fn step(&mut self, n: usize) {
        // The trimesh collider shares a process-wide cache in this build of ODE: take the
        // lock the Rust worlds with meshes take, so parallel tests do not race.
        let _guard = ars_core::lock_ode_global_state();
        // SAFETY: the scene is live.
        unsafe { ars_c_scene_step(self.0, n as c_int) }
    }
    /// Number of bodies.
    pub fn body_count(&self) -> usize {
        // SAFETY: the scene is live.
        unsafe { ars_c_scene_body_count(self.0) as usize }
    }
    /// State of body `i` (creation order).
    pub fn body_state(&self, i: usize) -> BodyState {
        assert!(i < self.body_count());
        let mut out = [0.0; 13];
        // SAFETY: the scene is live, `i` is in range and `out` holds 13 reals.
        unsafe { ars_c_scene_body_state(self.0, i as c_int, out.as_mut_ptr()) };
        out
    }
}

impl Drop for CScene {
    fn drop(&mut self) {
        // SAFETY: the scene is live and freed once.
        unsafe { ars_c_scene_free(self.0) }
    }
}

/// Start position of body `i` of the drop pile (computed by the C code, so both sides
/// use the same numbers).
pub fn drop_pile_position(i: usize) -> [f64; 3] {
    let mut p = [0.0; 3];
    // SAFETY: `p` holds 3 reals; the function only computes.
    unsafe { ars_c_drop_pile_position(i as c_int, p.as_mut_ptr()) };
    p
}
