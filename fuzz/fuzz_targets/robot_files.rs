//! Bytes → an MJCF or a URDF file's text, read and inserted into a simulation (a floor
//! under it), then stepped. The first byte chooses the reader and its options; the rest
//! is the text. Any abort, crash, hang or panic is a bug; an `Err` is the answer a bad
//! file must get. Seeds: `fuzz/seeds/robot_files/` (small valid files of both kinds).
#![no_main]

use ars_core::{MjcfOptions, Simulation, UrdfOptions};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Some((&choice, rest)) = data.split_first() else { return };
    let Ok(text) = std::str::from_utf8(rest) else { return };
    let Ok(mut sim) = Simulation::builder().floor_plane(ars_core::nalgebra::Vector3::y(), 0.0).build() else {
        return;
    };
    let loaded = if choice & 1 == 0 {
        let options = MjcfOptions::new().skip_unsupported(choice & 2 != 0);
        sim.load_mjcf_text(text, "fuzz.xml", &options).is_ok()
    } else {
        let options = UrdfOptions::new().fixed_base(choice & 2 != 0).ignore_visuals(choice & 4 != 0);
        sim.load_urdf_text(text, "fuzz.urdf", &options).is_ok()
    };
    if loaded {
        // A model that loads must also step without harm (an error is fine: diverged).
        let _ = sim.step_n(20);
    }
});
