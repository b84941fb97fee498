//! Finds the system ODE with pkg-config, insists on 0.16.x in double precision,
//! generates the bindings with bindgen and compiles the guard shim `src/guard.c`.
//! Every failure ends the build with one message that says which Debian packages to
//! install.

use std::env;
use std::path::PathBuf;

const INSTALL_HINT: &str = "install them with: sudo apt-get install libode-dev pkg-config libclang-dev";

fn fail(what: &str) -> ! {
    panic!(
        "\n\node-sys: {what}\node-sys: ARS needs ODE 0.16 (double precision), pkg-config and libclang; {INSTALL_HINT}\n\n"
    );
}

fn main() {
    println!("cargo:rerun-if-changed=wrapper.h");
    println!("cargo:rerun-if-changed=src/guard.c");
    println!("cargo:rerun-if-changed=src/guard.h");
    println!("cargo:rerun-if-changed=src/hull.c");
    println!("cargo:rerun-if-changed=src/hull.h");
    println!("cargo:rerun-if-changed=src/simple_space.c");
    println!("cargo:rerun-if-changed=src/simple_space.h");
    println!("cargo:rerun-if-env-changed=PKG_CONFIG_PATH");
    println!("cargo:rerun-if-env-changed=LIBCLANG_PATH");

    let ode = match pkg_config::Config::new().range_version("0.16".."0.17").probe("ode") {
        Ok(lib) => lib,
        Err(err) => fail(&format!("could not find ODE 0.16.x with pkg-config ({err})")),
    };
    match pkg_config::get_variable("ode", "precision") {
        Ok(p) if p == "dDOUBLE" => {}
        Ok(p) => fail(&format!("the installed ODE is built with precision `{p}`, ARS needs `dDOUBLE`")),
        Err(err) => fail(&format!("could not read ODE's precision from pkg-config ({err})")),
    }

    // The version built against, for reports of what a result was computed with.
    println!("cargo:rustc-env=ODESYS_LIBODE_VERSION={}", ode.version);

    // For the build scripts of crates that compile C against ODE (DEP_ODE_INCLUDE).
    let includes = env::join_paths(&ode.include_paths).expect("include paths without separators");
    println!("cargo:include={}", includes.to_string_lossy());

    let mut builder = bindgen::Builder::default()
        .header("wrapper.h")
        .allowlist_function("d[A-Z].*")
        .allowlist_type("d[A-Z].*")
        .allowlist_var("d[A-Z].*")
        .allowlist_function("odesys_.*")
        .allowlist_type("odesys_.*")
        .allowlist_var("ODESYS_.*")
        .derive_default(true)
        .derive_debug(true)
        .layout_tests(false)
        .generate_comments(false)
        .parse_callbacks(Box::new(bindgen::CargoCallbacks::new()));
    for dir in &ode.include_paths {
        builder = builder.clang_arg(format!("-I{}", dir.display()));
    }
    // bindgen panics when libclang cannot be loaded; turn that into the readable message.
    let generated = std::panic::catch_unwind(std::panic::AssertUnwindSafe(move || builder.generate()));
    let bindings = match generated {
        Ok(Ok(b)) => b,
        Ok(Err(err)) => fail(&format!("bindgen could not parse ODE's headers ({err})")),
        Err(_) => fail("bindgen could not load libclang"),
    };
    let out = PathBuf::from(env::var("OUT_DIR").expect("cargo sets OUT_DIR"));
    bindings.write_to_file(out.join("bindings.rs")).expect("writing the generated bindings into OUT_DIR");

    // The guard that turns ODE's internal errors into return codes (src/guard.c).
    cc::Build::new()
        .file("src/guard.c")
        .file("src/hull.c")
        .file("src/simple_space.c")
        .includes(&ode.include_paths)
        .flag_if_supported("-std=c11")
        .warnings(true)
        .compile("odesys_guard");
}
