//! Cause: a density of 1e10 kg/m³ in a sphere of radius 1e150 m gave a mass of
//! infinity, which was accepted: the state became NaN and every step returned `Ok`.
//! Fixed by the size range and by checking the mass and inertia that a density gives.

use ars_core::limits::MAX_SIZE;
use ars_core::*;

#[test]
fn a_density_that_overflows_the_mass_is_refused() {
    let mut world = World::new();
    let spec = MassSpec::solid(Shape::Sphere { radius: 1e150 }, Mass::Density(1e10));
    assert!(world.insert_body(BodyBuilder::new().mass(spec)).is_err());
    let spec = MassSpec::solid(Shape::Sphere { radius: MAX_SIZE }, Mass::Density(1e10));
    let err = world.insert_body(BodyBuilder::new().mass(spec)).unwrap_err();
    assert!(err.to_string().contains("from the density"), "{err}");
    let mut sim = Simulation::new().unwrap();
    assert!(sim.scene_mut().add_sphere(MAX_SIZE, [0.0, 0.0, 0.0], Mass::Density(1e10)).is_err());
    assert_eq!(world.body_count(), 0);
}
