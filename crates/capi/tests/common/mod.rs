//! What the tests that build and run programs against libdepo share: the repository root,
//! libdepo built in the test's own profile, and running a command that must succeed.

#![allow(dead_code)] // each test binary uses its own part

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::OnceLock;

pub fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..").canonicalize().unwrap()
}

/// Builds libdepo in the profile of this test binary and returns the directory holding it.
pub fn libdir() -> &'static Path {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        // target/<profile>/deps/<test>-<hash>
        let exe = std::env::current_exe().unwrap();
        let profile_dir = exe.parent().unwrap().parent().unwrap().to_path_buf();
        let release = profile_dir.file_name().is_some_and(|n| n == "release");
        let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
        let mut build = Command::new(cargo);
        build.current_dir(root()).args(["build", "-q", "-p", "depo-capi"]);
        if release {
            build.arg("--release");
        }
        let status = build.status().expect("cargo build -p depo-capi");
        assert!(status.success(), "building libdepo failed");
        assert!(profile_dir.join("libdepo.so").exists() && profile_dir.join("libdepo.a").exists());
        // Programs linked against libdepo.so ask for its SONAME at run time: give it that name
        // here too, as install.sh does in a prefix.
        let soname = profile_dir.join(env!("DEPO_SONAME"));
        if std::fs::read_link(&soname).is_err() {
            let _ = std::fs::remove_file(&soname);
            std::os::unix::fs::symlink("libdepo.so", &soname).expect("link the SONAME to libdepo.so");
        }
        profile_dir
    })
}

pub fn run(cmd: &mut Command) -> Output {
    let out = cmd.output().unwrap_or_else(|e| panic!("{cmd:?}: {e}"));
    assert!(
        out.status.success(),
        "{cmd:?} failed\nstdout:\n{}\nstderr:\n{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    out
}
