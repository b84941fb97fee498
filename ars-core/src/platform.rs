//! What a result was computed with: the libode build, the CPU and the C library. ARS's
//! numbers are the same bits wherever these are the same kind (see the README's
//! "The same bits everywhere"); a report of a run names them.

use std::ffi::{CStr, c_char};

use ode_sys as ffi;

unsafe extern "C" {
    /// glibc's version string (`"2.36"`); every Debian and Ubuntu has it.
    fn gnu_get_libc_version() -> *const c_char;
}

/// The platform a run computes on.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Platform {
    /// The libode version ARS was built against (pkg-config), e.g. `"0.16.2"`.
    pub libode_version: String,
    /// libode's build configuration as it reports it at run time (`dGetConfiguration`:
    /// precision, trimesh library, threading...).
    pub libode_configuration: String,
    /// The CPU's model name (from `/proc/cpuinfo`; `"unknown"` elsewhere).
    pub cpu: String,
    /// The C library: `"glibc 2.36"`.
    pub libc: String,
    /// The operating system and architecture, e.g. `"linux x86_64"`.
    pub os: String,
}

impl Platform {
    /// The platform of this process.
    pub fn current() -> Platform {
        crate::init::ensure_ode_ready();
        // SAFETY: dGetConfiguration returns a pointer to a static NUL-terminated
        // string (or null before dInitODE2, which ensure_ode_ready has called).
        let configuration = unsafe { text(ffi::dGetConfiguration()) };
        // SAFETY: gnu_get_libc_version returns a pointer to a static NUL-terminated
        // string.
        let libc = unsafe { text(gnu_get_libc_version()) };
        let cpu = std::fs::read_to_string("/proc/cpuinfo")
            .ok()
            .and_then(|info| {
                info.lines()
                    .find(|l| l.starts_with("model name"))
                    .and_then(|l| l.split_once(':'))
                    .map(|(_, name)| name.trim().to_string())
            })
            .unwrap_or_else(|| "unknown".into());
        Platform {
            libode_version: ffi::LIBODE_VERSION.to_string(),
            libode_configuration: configuration.trim().to_string(),
            cpu,
            libc: format!("glibc {libc}"),
            os: format!("{} {}", std::env::consts::OS, std::env::consts::ARCH),
        }
    }
}

impl std::fmt::Display for Platform {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "libode {} ({}), {}, {}, {}",
            self.libode_version, self.libode_configuration, self.cpu, self.libc, self.os
        )
    }
}

/// The text of a C string, or `""` for null.
///
/// # Safety
/// `p` is null or points to a NUL-terminated string that outlives the call.
unsafe fn text(p: *const c_char) -> String {
    if p.is_null() {
        return String::new();
    }
    // SAFETY: non-null and NUL-terminated, as the caller promises.
    unsafe { CStr::from_ptr(p) }.to_string_lossy().into_owned()
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_platform_names_libode_0_16_double_precision_and_glibc() {
        let p = super::Platform::current();
        assert!(p.libode_version.starts_with("0.16"), "{p}");
        assert!(p.libode_configuration.contains("ODE_double_precision"), "{p}");
        assert!(p.libc.starts_with("glibc 2."), "{p}");
    }
}
