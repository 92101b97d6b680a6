//! The API docs build for the whole workspace, as `.ci/run` builds them, with every rustdoc
//! warning an error; and the facade's page links to the crates it re-exports within its own
//! pages, so that `cargo doc -p depo --no-deps` leaves no link dangling. And the build the
//! README documents is the one `install.sh` reuses.

use std::path::Path;
use std::process::Command;

#[test]
fn workspace_docs_build_and_the_facade_links_resolve() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let out = Command::new(cargo)
        .current_dir(root)
        .env("RUSTDOCFLAGS", "-D warnings")
        .args(["doc", "--workspace", "--no-deps", "-q"])
        .output()
        .expect("run cargo doc");
    assert!(out.status.success(), "cargo doc --workspace --no-deps failed:\n{}", String::from_utf8_lossy(&out.stderr));

    // target/<profile>/deps/docs-<hash> -> target/doc
    let exe = std::env::current_exe().unwrap();
    let target = exe.ancestors().nth(3).unwrap();
    let doc = target.join("doc");
    let facade = doc.join("depo/index.html");
    let html = std::fs::read_to_string(&facade).expect("target/doc/depo/index.html");
    for module in ["wall_model", "tracker"] {
        assert!(html.contains(&format!("href=\"{module}/index.html\"")), "the facade does not link to depo::{module}");
    }
    // An intra-doc link rustdoc could not turn into a URL is left as text: `[<code>name</code>]`.
    assert!(!html.contains("[<code>"), "unresolved intra-doc link in {}", facade.display());
    // Every relative link on the page reaches a file.
    for href in html.split("href=\"").skip(1).filter_map(|s| s.split('"').next()) {
        let path = href.split('#').next().unwrap();
        if path.is_empty() || path.contains("://") || path.contains('$') {
            continue;
        }
        assert!(facade.parent().unwrap().join(path).exists(), "dangling link {href} in {}", facade.display());
    }
    assert!(doc.join("depo_wall_model/index.html").exists() && doc.join("depo_tracker/index.html").exists());
}

/// The README's one release build is the command `install.sh` runs when given no build of its
/// own: after the README's build it then has nothing to compile. (Cargo resolves features per
/// command, so any other selection, such as `-p depo-capi`, would compile the dependencies a
/// second time.)
#[test]
fn install_sh_reuses_the_readme_s_one_build() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let one_build = "cargo build --release --workspace --lib --bins --examples";
    let readme = std::fs::read_to_string(root.join("README.md")).unwrap();
    let quick_start = readme.split("## Quick start").nth(1).unwrap().split("\n## ").next().unwrap();
    assert!(quick_start.contains(one_build), "the README's quick start does not give `{one_build}`");
    // Cargo builds only the target kinds a command names: `--examples` alone leaves no
    // `target/release/depo` on a clean checkout, and `--bins` alone no `libdepo.so`.
    for kind in ["--lib", "--bins", "--examples"] {
        assert!(one_build.split_whitespace().any(|w| w == kind), "the one build must name {kind}");
    }
    let install = std::fs::read_to_string(root.join("crates/capi/install.sh")).unwrap();
    let builds: Vec<&str> = install
        .lines()
        .filter(|l| !l.trim_start().starts_with('#'))
        .filter_map(|l| l.find("cargo build").map(|at| &l[at..]))
        .collect();
    assert!(!builds.is_empty(), "install.sh builds nothing");
    for build in builds {
        assert!(
            build.trim_end_matches(')').trim_end() == one_build,
            "install.sh runs `{build}`, not the README's `{one_build}`"
        );
    }
}
