//! Compiles the reference scenes of `c/*.c` (plain C against the system libode) into a
//! static library. ODE's headers are where `ode-sys` found them (its one pkg-config
//! probe, passed on as `DEP_ODE_INCLUDE`).

fn main() {
    println!("cargo:rerun-if-changed=c");
    let includes = std::env::var_os("DEP_ODE_INCLUDE").expect("ode-sys passes on ODE's include paths");
    let mut sources: Vec<_> = std::fs::read_dir("c")
        .expect("c/ exists")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "c"))
        .collect();
    sources.sort();
    cc::Build::new()
        .files(&sources)
        .include("c")
        .includes(std::env::split_paths(&includes))
        // Same floating-point operations as the Rust code: no fused multiply-add.
        .flag_if_supported("-ffp-contract=off")
        .opt_level(2)
        .warnings(true)
        .compile("ars_c_scenes");
}
