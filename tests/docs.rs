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

/// README.md and every page under docs/.
fn markdown_files(root: &Path) -> Vec<std::path::PathBuf> {
    let mut files = vec![root.join("README.md")];
    let mut docs: Vec<_> = std::fs::read_dir(root.join("docs"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "md"))
        .collect();
    docs.sort();
    files.extend(docs);
    files
}

/// Each fenced code block (between lines of three backticks) with its language tag, fences indented inside list items
/// included, each line with the block's indentation removed.
fn code_blocks(markdown: &str) -> Vec<(&str, Vec<&str>)> {
    let mut blocks = Vec::new();
    let mut open: Option<(&str, Vec<&str>)> = None;
    for line in markdown.lines() {
        if let Some(tag) = line.trim_start().strip_prefix("```") {
            match open.take() {
                Some(block) => blocks.push(block),
                None => open = Some((tag.trim(), Vec::new())),
            }
        } else if let Some((_, lines)) = open.as_mut() {
            lines.push(line.trim());
        }
    }
    blocks
}

/// The text outside fenced code blocks.
fn prose(markdown: &str) -> String {
    let mut inside = false;
    let mut out = String::new();
    for line in markdown.lines() {
        if line.trim_start().starts_with("```") {
            inside = !inside;
        } else if !inside {
            out.push_str(line);
            out.push('\n');
        }
    }
    out
}

/// The anchors of a page's headings, as GitHub makes them: lower case, punctuation dropped,
/// spaces as hyphens.
fn anchors(markdown: &str) -> Vec<String> {
    prose(markdown)
        .lines()
        .filter(|l| l.starts_with('#'))
        .map(|l| {
            l.trim_start_matches('#')
                .trim()
                .to_lowercase()
                .chars()
                .filter(|c| c.is_alphanumeric() || *c == '-' || *c == '_' || *c == ' ')
                .map(|c| if c == ' ' { '-' } else { c })
                .collect()
        })
        .collect()
}

/// The commands of a code block: in a shell block (`sh`) every line, in another (`text`, a
/// command with its output) the lines after a `$ ` prompt; continuation lines (`\\`) joined,
/// a trailing `# comment` dropped.
fn commands(tag: &str, block: &[&str]) -> Vec<String> {
    let shell = matches!(tag, "sh" | "bash" | "shell");
    let mut out = Vec::new();
    let mut pending: Option<String> = None;
    for &line in block {
        let line = match (line.strip_prefix("$ "), &pending) {
            (Some(command), _) => command,
            (None, Some(_)) => line,
            (None, None) if shell => line,
            (None, None) => continue,
        };
        let line = line.split(" #").next().unwrap().trim();
        let command = pending.get_or_insert_with(String::new);
        match line.strip_suffix('\\') {
            Some(head) => {
                command.push_str(head.trim_end());
                command.push(' ');
            }
            None => {
                command.push_str(line);
                let command = pending.take().unwrap();
                if !command.is_empty() {
                    out.push(command);
                }
            }
        }
    }
    out
}

/// The README is a user's quick start: short, and it opens with the two commands the project
/// promises, one that builds and runs the main job and one that runs every test.
#[test]
fn the_readme_is_a_quick_start() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let readme = std::fs::read_to_string(root.join("README.md")).unwrap();
    assert!(readme.len() < 12_000, "README.md is {} bytes: keep it under 12000, details go to docs/", readme.len());
    let quick_start = readme.split("## Quick start").nth(1).unwrap().split("\n## ").next().unwrap();
    let (tag, first) = code_blocks(quick_start).into_iter().next().expect("a code block in the quick start");
    assert_eq!(
        commands(tag, &first),
        ["cargo run --release -- room", "cargo test --workspace"],
        "the quick start's first block must be the main job and the tests"
    );
}

/// Every relative link of the README and the docs reaches a file, and a link to a heading of
/// a page reaches a heading of that page.
#[test]
fn links_in_the_readme_and_docs_resolve() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut bad = Vec::new();
    for file in markdown_files(root) {
        let text = std::fs::read_to_string(&file).unwrap();
        for link in prose(&text).split("](").skip(1).filter_map(|s| s.split(')').next()) {
            if link.contains("://") || link.contains(' ') {
                continue;
            }
            let (path, anchor) = link.split_once('#').unwrap_or((link, ""));
            let target = if path.is_empty() { file.clone() } else { file.parent().unwrap().join(path) };
            if !target.exists() {
                bad.push(format!("{}: {link}: no such file", file.display()));
            } else if !anchor.is_empty() && target.extension().is_some_and(|e| e == "md") {
                let page = std::fs::read_to_string(&target).unwrap();
                if !anchors(&page).iter().any(|a| a == anchor) {
                    bad.push(format!("{}: {link}: no such heading", file.display()));
                }
            }
        }
    }
    assert!(bad.is_empty(), "links that lead nowhere:\n{}", bad.join("\n"));
}

/// Every `depo ...` command in a code block of the README and the docs runs as shown and exits
/// 0, from a scratch directory (files they name under the repository are found there). The
/// studies (`room`, `channel`) take a minute each and are not run; `bench` runs with a small
/// batch. The README shows an example of every subcommand.
#[test]
fn the_depo_commands_the_readme_and_docs_show_run() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let scratch = std::env::temp_dir().join(format!("depo-docs-{}", std::process::id()));
    std::fs::create_dir_all(&scratch).unwrap();
    let mut bad = Vec::new();
    let mut shown_in_readme = Vec::new();
    for file in markdown_files(root) {
        let text = std::fs::read_to_string(&file).unwrap();
        for command in code_blocks(&text).iter().flat_map(|(tag, lines)| commands(tag, lines)) {
            let Some(args) = command.strip_prefix("depo ").or_else(|| command.strip_prefix("target/release/depo "))
            else {
                continue;
            };
            assert!(
                !args.contains(['"', '\'', '$', '|', '>', '<', ';', '&']),
                "{}: `{command}`: this test runs plain arguments only",
                file.display()
            );
            let mut args: Vec<String> = args.split_whitespace().map(String::from).collect();
            if file.ends_with("README.md") {
                shown_in_readme.push(args[0].clone());
            }
            // Paths into the repository, as given from its root; the input files must be there.
            for arg in args.iter_mut() {
                if root.join(arg.as_str()).is_file() {
                    *arg = root.join(arg.as_str()).display().to_string();
                } else if arg.ends_with(".toml") || arg.ends_with(".csv") {
                    bad.push(format!("{}: `{command}`: no file {arg}", file.display()));
                }
            }
            match args[0].as_str() {
                "room" | "channel" => continue,
                "bench" if args.iter().any(|a| a == "--integrators" || a == "--studies") => continue,
                "bench" => args.extend(["--n", "100000", "--reps", "1"].map(String::from)),
                _ => {}
            }
            let out = Command::new(env!("CARGO_BIN_EXE_depo")).current_dir(&scratch).args(&args).output().unwrap();
            if !out.status.success() {
                bad.push(format!("{}: `{command}`: {}", file.display(), String::from_utf8_lossy(&out.stderr).trim()));
            }
        }
    }
    std::fs::remove_dir_all(&scratch).ok();
    assert!(bad.is_empty(), "documented commands that fail:\n{}", bad.join("\n"));

    let help = Command::new(env!("CARGO_BIN_EXE_depo")).arg("--help").output().unwrap();
    let help = String::from_utf8(help.stdout).unwrap();
    let subcommands = help.split("Commands:").nth(1).unwrap().split("\n\n").next().unwrap();
    for name in subcommands.lines().filter_map(|l| l.split_whitespace().next()).filter(|&n| n != "help") {
        assert!(shown_in_readme.iter().any(|s| s == name), "the README shows no `depo {name}` command");
    }
}
