//! Contact surfaces of pairs of objects: the pair's own surface, the default for every
//! other pair, saved in scene files and forgotten with a removed object.

use ars_core::nalgebra::Vector3;
use ars_core::*;

/// A floor and two boxes side by side on it, both sliding along +X at 1 m/s.
fn two_sliding_boxes() -> Result<(Simulation, ObjectId, ObjectId, ObjectId)> {
    let mut sim = Simulation::builder().floor_plane(Vector3::y(), 0.0).build()?;
    let floor = sim.scene().object("floor")?.id();
    let slippery = sim.scene_mut().add_box([0.2, 0.1, 0.2], [0.0, 0.05, 0.0], Mass::Total(1.0))?;
    let grippy = sim.scene_mut().add_box([0.2, 0.1, 0.2], [0.0, 0.05, 1.0], Mass::Total(1.0))?;
    for b in [slippery, grippy] {
        sim.scene_mut().body_mut(b)?.set_linear_velocity(Vector3::x())?;
    }
    Ok((sim, floor, slippery, grippy))
}

#[test]
fn a_pair_slides_on_its_own_surface_and_the_others_keep_the_default() -> Result<()> {
    let (mut sim, floor, slippery, grippy) = two_sliding_boxes()?;
    let ice = ContactSurface { mu: 0.0, bounce: None, ..Default::default() };
    sim.scene_mut().set_contact_surface(slippery, floor, ice)?;
    assert_eq!(sim.scene().contact_surface(floor, slippery)?, ice, "either order");
    assert_eq!(sim.scene().contact_surface(floor, grippy)?, ContactSurface::default());
    sim.run_for(0.5)?;
    let (x_ice, x_grip) = (sim.scene().position(slippery)?.x, sim.scene().position(grippy)?.x);
    assert!((x_ice - 0.5).abs() < 1e-3, "no friction: 0.5 m in 0.5 s, got {x_ice}");
    assert!(x_grip < 0.01, "500 N friction stops a 1 kg box at once: {x_grip}");
    assert!(sim.scene().body(grippy)?.linear_velocity().norm() < 1e-3);
    Ok(())
}

#[test]
fn clearing_a_pair_gives_it_the_default_surface_again() -> Result<()> {
    let (mut plain, ..) = two_sliding_boxes()?;
    let (mut cleared, floor, slippery, _) = two_sliding_boxes()?;
    cleared.scene_mut().set_contact_surface(slippery, floor, ContactSurface { mu: 0.0, ..Default::default() })?;
    cleared.scene_mut().clear_contact_surface(floor, slippery)?;
    assert!(cleared.scene().contact_surfaces().is_empty());
    plain.run_for(0.2)?;
    cleared.run_for(0.2)?;
    let (a, b) = (plain.scene().position(plain.scene().object("box")?.id())?, cleared.scene().position(slippery)?);
    assert_eq!(a.coords.map(f64::to_bits), b.coords.map(f64::to_bits), "the default surface again, to the bit");
    Ok(())
}

#[test]
fn a_run_with_only_default_pairs_is_bit_identical_whether_or_not_a_pair_was_ever_set() -> Result<()> {
    // Setting a pair to the default surface goes through the hooks' path: same bits.
    let (mut plain, ..) = two_sliding_boxes()?;
    let (mut hooked, floor, slippery, _) = two_sliding_boxes()?;
    hooked.scene_mut().set_contact_surface(slippery, floor, ContactSurface::default())?;
    plain.run_for(0.3)?;
    hooked.run_for(0.3)?;
    for name in ["box", "box/1"] {
        let (a, b) = (
            plain.scene().position(plain.scene().object(name)?.id())?,
            hooked.scene().position(hooked.scene().object(name)?.id())?,
        );
        assert_eq!(a.coords.map(f64::to_bits), b.coords.map(f64::to_bits), "{name}");
    }
    Ok(())
}

#[test]
fn pair_surfaces_are_saved_in_scene_files_and_checked() -> Result<()> {
    let (mut sim, floor, slippery, grippy) = two_sliding_boxes()?;
    let ice = ContactSurface { mu: 0.0, bounce: None, max_contacts: 4, ..Default::default() };
    sim.scene_mut().set_contact_surface(floor, slippery, ice)?;
    let mut loaded = Simulation::load_scene(&sim.save_scene()?)?;
    let (f, s, g) = (
        loaded.scene().object("floor")?.id(),
        loaded.scene().object(sim.scene().object(slippery)?.name())?.id(),
        loaded.scene().object(sim.scene().object(grippy)?.name())?.id(),
    );
    assert_eq!(loaded.scene().contact_surface(s, f)?, ice);
    assert_eq!(loaded.scene().contact_surface(g, f)?, ContactSurface::default());
    sim.run_for(0.2)?;
    loaded.run_for(0.2)?;
    assert_eq!(sim.scene().position(slippery)?.x.to_bits(), loaded.scene().position(s)?.x.to_bits());

    let bad = ContactSurface { mu: -1.0, ..Default::default() };
    assert!(sim.scene_mut().set_contact_surface(floor, grippy, bad).is_err());
    assert_eq!(
        sim.scene().contact_surface(floor, grippy)?,
        ContactSurface::default(),
        "a refused surface changes nothing"
    );
    Ok(())
}

#[test]
fn a_removed_object_takes_its_pair_surfaces_with_it() -> Result<()> {
    let (mut sim, floor, slippery, grippy) = two_sliding_boxes()?;
    sim.scene_mut().set_contact_surface(floor, slippery, ContactSurface { mu: 0.0, ..Default::default() })?;
    sim.remove_object(slippery)?;
    assert!(sim.scene().contact_surfaces().is_empty());
    assert!(sim.scene().contact_surface(floor, slippery).is_err(), "a removed object has no surface");
    sim.run_for(0.1)?;
    assert!(sim.scene().position(grippy)?.x < 0.01);
    Ok(())
}

#[test]
fn a_surface_changed_between_steps_holds_from_the_next_step() -> Result<()> {
    // The collision keeps what each pair of geoms touches with from one step to the
    // next: every change of a pair's surface or exclusion must reach it.
    let (mut sim, floor, slippery, grippy) = two_sliding_boxes()?;
    let ice = ContactSurface { mu: 0.0, bounce: None, ..Default::default() };
    // How far the slippery box goes in 0.1 s, pushed at 1 m/s.
    let slide = |sim: &mut Simulation| -> Result<f64> {
        sim.scene_mut().body_mut(slippery)?.set_linear_velocity(Vector3::x())?;
        let start = sim.scene().position(slippery)?.x;
        sim.run_for(0.1)?;
        Ok(sim.scene().position(slippery)?.x - start)
    };
    sim.scene_mut().set_contact_surface(slippery, floor, ice)?;
    let on_ice = slide(&mut sim)?;
    assert!((on_ice - 0.1).abs() < 1e-3, "slides on ice: {on_ice}");
    sim.scene_mut().set_contact_surface(slippery, floor, ContactSurface::default())?;
    let held = slide(&mut sim)?;
    assert!(held < 0.01, "the default surface holds it: {held}");
    sim.scene_mut().set_contact_surface(slippery, floor, ice)?;
    let again = slide(&mut sim)?;
    assert!((again - 0.1).abs() < 1e-2, "on ice again: {again}");
    sim.scene_mut().clear_contact_surface(floor, slippery)?;
    let cleared = slide(&mut sim)?;
    assert!(cleared < 0.01, "cleared: the default again: {cleared}");
    sim.scene_mut().exclude_contacts(floor, grippy)?;
    sim.run_for(0.5)?;
    assert!(sim.scene().position(grippy)?.y < -0.5, "excluded: it falls through the floor");
    let height = sim.scene().position(slippery)?.y;
    assert!((height - 0.05).abs() < 1e-2, "the other box stays on the floor: {height}");
    sim.scene_mut().include_contacts(floor, grippy)?;
    sim.scene_mut().set_contact_surface(slippery, floor, ice)?;
    let last = slide(&mut sim)?;
    assert!((last - 0.1).abs() < 1e-2, "a surface set after an exclusion holds: {last}");
    Ok(())
}
