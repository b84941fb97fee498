//! Compiles the reference scenes of `tests/c/*.c` (plain C against the system libode)
//! into a static library that the tests and benchmarks of the root crate call through
//! `extern "C"`, to hold the Rust port against native ODE.

fn main() {
    println!("cargo:rerun-if-changed=tests/c");
    let ode = pkg_config::Config::new().range_version("0.16".."0.17").probe("ode").unwrap_or_else(|err| {
        panic!("\n\nars: could not find ODE 0.16 with pkg-config ({err});\ninstall it with: sudo apt-get install libode-dev pkg-config libclang-dev\n\n")
    });
    let mut sources: Vec<_> = std::fs::read_dir("tests/c")
        .expect("tests/c exists")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "c"))
        .collect();
    sources.sort();
    let mut build = cc::Build::new();
    build
        .files(&sources)
        .include("tests/c")
        .includes(&ode.include_paths)
        // Same floating-point operations as the Rust code: no fused multiply-add.
        .flag_if_supported("-ffp-contract=off")
        .opt_level(2)
        .warnings(true);
    build.compile("ars_c_scenes");
}
