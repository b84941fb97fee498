//! Contact surfaces of pairs of objects: the pair's own surface, the default for every
//! other pair, saved in scene files and forgotten with a removed object.

use ars_core::nalgebra::Vector3;
use ars_core::*;

/// A floor and two boxes side by side on it, both sliding along +X at 1 m/s.
fn two_sliding_boxes() -> Result<(Simulation, ObjectId, ObjectId, ObjectId)> {
    let mut sim = Simulation::builder().floor_plane(Vector3::y(), 0.0).build()?;
    let floor = sim.object("floor")?.id();
    let slippery = sim.add_box([0.2, 0.1, 0.2], [0.0, 0.05, 0.0], Mass::Total(1.0))?;
    let grippy = sim.add_box([0.2, 0.1, 0.2], [0.0, 0.05, 1.0], Mass::Total(1.0))?;
    for b in [slippery, grippy] {
        sim.body_mut(b)?.set_linear_velocity(Vector3::x())?;
    }
    Ok((sim, floor, slippery, grippy))
}

#[test]
fn a_pair_slides_on_its_own_surface_and_the_others_keep_the_default() -> Result<()> {
    let (mut sim, floor, slippery, grippy) = two_sliding_boxes()?;
    let ice = ContactSurface { mu: 0.0, bounce: None, ..Default::default() };
    sim.set_contact_surface(slippery, floor, ice)?;
    assert_eq!(sim.contact_surface(floor, slippery)?, ice, "either order");
    assert_eq!(sim.contact_surface(floor, grippy)?, ContactSurface::default());
    sim.run_for(0.5)?;
    let (x_ice, x_grip) = (sim.position(slippery)?.x, sim.position(grippy)?.x);
    assert!((x_ice - 0.5).abs() < 1e-3, "no friction: 0.5 m in 0.5 s, got {x_ice}");
    assert!(x_grip < 0.01, "500 N friction stops a 1 kg box at once: {x_grip}");
    assert!(sim.body(grippy)?.linear_velocity().norm() < 1e-3);
    Ok(())
}

#[test]
fn clearing_a_pair_gives_it_the_default_surface_again() -> Result<()> {
    let (mut plain, ..) = two_sliding_boxes()?;
    let (mut cleared, floor, slippery, _) = two_sliding_boxes()?;
    cleared.set_contact_surface(slippery, floor, ContactSurface { mu: 0.0, ..Default::default() })?;
    cleared.clear_contact_surface(floor, slippery)?;
    assert!(cleared.contact_surfaces().is_empty());
    plain.run_for(0.2)?;
    cleared.run_for(0.2)?;
    let (a, b) = (plain.position(plain.object("box")?.id())?, cleared.position(slippery)?);
    assert_eq!(a.coords.map(f64::to_bits), b.coords.map(f64::to_bits), "the default surface again, to the bit");
    Ok(())
}

#[test]
fn a_run_with_only_default_pairs_is_bit_identical_whether_or_not_a_pair_was_ever_set() -> Result<()> {
    // Setting a pair to the default surface goes through the hooks' path: same bits.
    let (mut plain, ..) = two_sliding_boxes()?;
    let (mut hooked, floor, slippery, _) = two_sliding_boxes()?;
    hooked.set_contact_surface(slippery, floor, ContactSurface::default())?;
    plain.run_for(0.3)?;
    hooked.run_for(0.3)?;
    for name in ["box", "box/1"] {
        let (a, b) = (plain.position(plain.object(name)?.id())?, hooked.position(hooked.object(name)?.id())?);
        assert_eq!(a.coords.map(f64::to_bits), b.coords.map(f64::to_bits), "{name}");
    }
    Ok(())
}

#[test]
fn pair_surfaces_are_saved_in_scene_files_and_checked() -> Result<()> {
    let (mut sim, floor, slippery, grippy) = two_sliding_boxes()?;
    let ice = ContactSurface { mu: 0.0, bounce: None, max_contacts: 4, ..Default::default() };
    sim.set_contact_surface(floor, slippery, ice)?;
    let mut loaded = Simulation::load_scene(&sim.save_scene()?)?;
    let (f, s, g) = (
        loaded.object("floor")?.id(),
        loaded.object(sim.object(slippery)?.name())?.id(),
        loaded.object(sim.object(grippy)?.name())?.id(),
    );
    assert_eq!(loaded.contact_surface(s, f)?, ice);
    assert_eq!(loaded.contact_surface(g, f)?, ContactSurface::default());
    sim.run_for(0.2)?;
    loaded.run_for(0.2)?;
    assert_eq!(sim.position(slippery)?.x.to_bits(), loaded.position(s)?.x.to_bits());

    let bad = ContactSurface { mu: -1.0, ..Default::default() };
    assert!(sim.set_contact_surface(floor, grippy, bad).is_err());
    assert_eq!(sim.contact_surface(floor, grippy)?, ContactSurface::default(), "a refused surface changes nothing");
    Ok(())
}

#[test]
fn a_removed_object_takes_its_pair_surfaces_with_it() -> Result<()> {
    let (mut sim, floor, slippery, grippy) = two_sliding_boxes()?;
    sim.set_contact_surface(floor, slippery, ContactSurface { mu: 0.0, ..Default::default() })?;
    sim.remove_object(slippery)?;
    assert!(sim.contact_surfaces().is_empty());
    assert!(sim.contact_surface(floor, slippery).is_err(), "a removed object has no surface");
    sim.run_for(0.1)?;
    assert!(sim.position(grippy)?.x < 0.01);
    Ok(())
}
