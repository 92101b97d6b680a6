//! Gives the shared library an ELF SONAME, so that programs linked against it ask for the ABI
//! they were built with (`libdepo.so.0.1` for 0.1.x) rather than for whatever `libdepo.so` is
//! found at run time. `install.sh` installs the library under that name.
//!
//! The SONAME follows Cargo's compatibility rule: versions `x.y.z` with the same `x` (for
//! `x >= 1`), or `0.y.z` with the same `y`, keep it. A release that breaks the C ABI must move
//! to a new one by its version number.

fn main() {
    let major = std::env::var("CARGO_PKG_VERSION_MAJOR").unwrap();
    let minor = std::env::var("CARGO_PKG_VERSION_MINOR").unwrap();
    let soversion = if major == "0" { format!("0.{minor}") } else { major };
    let soname = format!("libdepo.so.{soversion}");
    // For the tests (`env!("DEPO_SONAME")`); install.sh derives the same name from the version.
    println!("cargo:rustc-env=DEPO_SONAME={soname}");
    let os = std::env::var("CARGO_CFG_TARGET_OS").unwrap_or_default();
    let family = std::env::var("CARGO_CFG_TARGET_FAMILY").unwrap_or_default();
    // ELF platforms only: Mach-O has install names and Windows DLLs have neither.
    if family.split(',').any(|f| f == "unix")
        && !matches!(os.as_str(), "macos" | "ios" | "tvos" | "watchos" | "visionos")
    {
        println!("cargo:rustc-cdylib-link-arg=-Wl,-soname,{soname}");
    }
    println!("cargo:rerun-if-changed=build.rs");
}
