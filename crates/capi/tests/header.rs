//! The checked-in `include/depo.h` must equal a fresh cbindgen generation, and carry the crate's
//! version. `DEPO_BLESS=1 cargo test -p depo-capi --test header` rewrites it.

use std::path::PathBuf;

fn generate() -> String {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let mut config = cbindgen::Config::from_file(dir.join("cbindgen.toml")).expect("cbindgen.toml");
    let version = env!("CARGO_PKG_VERSION");
    let mut parts = version.split('.');
    let mut next = || parts.next().unwrap_or("0").to_string();
    let (major, minor, patch) = (next(), next(), next());
    config.after_includes = Some(format!(
        "\n#define DEPO_VERSION \"{version}\"\n#define DEPO_VERSION_MAJOR {major}\n#define DEPO_VERSION_MINOR {minor}\n#define DEPO_VERSION_PATCH {patch}"
    ));
    let mut out = Vec::new();
    cbindgen::Builder::new()
        .with_crate(&dir)
        .with_config(config)
        .generate()
        .expect("cbindgen generation")
        .write(&mut out);
    String::from_utf8(out).expect("UTF-8 header")
}

#[test]
fn checked_in_header_is_current() {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("include/depo.h");
    let fresh = generate();
    if std::env::var_os("DEPO_BLESS").is_some() {
        std::fs::write(&path, &fresh).expect("write depo.h");
    }
    let checked_in = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        checked_in == fresh,
        "include/depo.h differs from a fresh cbindgen generation; run DEPO_BLESS=1 cargo test -p depo-capi --test header"
    );
    assert!(checked_in.contains(&format!("#define DEPO_VERSION \"{}\"", env!("CARGO_PKG_VERSION"))));
}
