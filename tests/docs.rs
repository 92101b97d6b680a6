//! The API docs build for the whole workspace, as `.ci/run` builds them, with every rustdoc
//! warning an error; and the facade's page links to the crates it re-exports within its own
//! pages, so that `cargo doc -p depo --no-deps` leaves no link dangling.

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
