//! The studies' outputs, byte for byte, against outputs stored in `tests/golden/`: the built-in
//! room and channel and every shipped scene in `examples/`, each cut to a few hundred particles
//! and a shorter run so that all of them take seconds, with their seeds fixed. A change that is
//! meant to keep results (a restructuring, a faster loop) must leave every byte of them; one that
//! is meant to change them writes the files anew with `DEPO_BLESS=1 cargo test --test golden`,
//! and its commit says why the numbers moved.
//!
//! The JSON of a study carries no timings, so it is compared whole; so is the room's CSV.

use std::path::{Path, PathBuf};

mod common;
use common::depo;

/// Where the stored outputs live.
fn golden_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/golden")
}

/// `base` (a shipped scene, or none for the built-in one) with its particle counts and run
/// length cut by `cuts` (`section.key = value`), written where the test can run it.
fn cut_scene(name: &str, base: Option<&str>, cuts: &[(&str, &str, toml::Value)]) -> PathBuf {
    let mut table: toml::Table = match base {
        Some(file) => {
            let text = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join(file)).unwrap();
            text.parse().unwrap_or_else(|e| panic!("{file}: {e}"))
        }
        None => toml::Table::new(),
    };
    for (section, key, value) in cuts {
        let section = table.entry(*section).or_insert_with(|| toml::Value::Table(toml::Table::new()));
        section.as_table_mut().unwrap().insert((*key).to_string(), value.clone());
    }
    let path = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("golden-{name}.toml"));
    std::fs::write(&path, toml::to_string(&table).unwrap()).unwrap();
    path
}

/// Compares `output` with the stored file `name`, or stores it under `DEPO_BLESS=1`.
fn same_as_stored(name: &str, output: &str) {
    let stored = golden_dir().join(name);
    if std::env::var_os("DEPO_BLESS").is_some_and(|v| v == "1") {
        std::fs::create_dir_all(golden_dir()).unwrap();
        std::fs::write(&stored, output).unwrap();
        return;
    }
    let expected = std::fs::read_to_string(&stored)
        .unwrap_or_else(|e| panic!("{}: {e} (DEPO_BLESS=1 writes it)", stored.display()));
    if let Some((i, (now, was))) = output.lines().zip(expected.lines()).enumerate().find(|(_, (a, b))| a != b) {
        panic!("{name} changed at line {}:\n  now:    {now}\n  stored: {was}", i + 1);
    }
    assert_eq!(output.lines().count(), expected.lines().count(), "{name}: another number of lines");
    assert_eq!(output, expected, "{name}: line endings or the final newline changed");
}

/// `depo ARGS...`, which must succeed; its standard output.
fn stdout_of(args: &[&str]) -> String {
    let out = depo(args);
    assert!(out.status.success(), "depo {args:?} failed: {}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8(out.stdout).unwrap()
}

fn room_cuts() -> Vec<(&'static str, &'static str, toml::Value)> {
    vec![
        ("particles", "count", toml::Value::Integer(150)),
        ("particles", "max_count", toml::Value::Integer(150)),
        ("particles", "target_error", toml::Value::Float(0.0)),
        ("run", "duration", toml::Value::Float(600.0)),
        ("run", "seed", toml::Value::Integer(11)),
    ]
}

fn room_case(name: &str, base: Option<&str>) {
    let scene = cut_scene(name, base, &room_cuts());
    let scene = scene.to_str().unwrap();
    same_as_stored(&format!("{name}.json"), &stdout_of(&["room", "--format", "json", "--no-plot", scene]));
}

#[test]
fn built_in_room() {
    let scene = cut_scene("room", None, &room_cuts());
    let scene = scene.to_str().unwrap();
    same_as_stored("room.json", &stdout_of(&["room", "--format", "json", "--no-plot", scene]));
    same_as_stored("room.csv", &stdout_of(&["room", "--format", "csv", "--no-plot", scene]));
}

#[test]
fn shipped_rooms() {
    for (name, file) in [
        ("example-room", "examples/room.toml"),
        ("example-room-pm", "examples/room-pm.toml"),
        ("example-lai2005-chamber", "examples/lai2005-chamber.toml"),
        ("example-thatcher2002-bare-fast", "examples/thatcher2002-bare-fast.toml"),
        ("example-thatcher2002-bare-slow", "examples/thatcher2002-bare-slow.toml"),
        ("example-thatcher2002-furnished-fast", "examples/thatcher2002-furnished-fast.toml"),
        ("example-thatcher2002-furnished-slow", "examples/thatcher2002-furnished-slow.toml"),
    ] {
        room_case(name, Some(file));
    }
}

fn channel_case(name: &str, base: Option<&str>) {
    let cuts = [
        ("particles", "count", toml::Value::Integer(300)),
        ("particles", "excursion_count", toml::Value::Integer(100)),
        ("particles", "target_error", toml::Value::Float(0.0)),
        ("run", "duration_plus", toml::Value::Float(800.0)),
        ("run", "seed", toml::Value::Integer(11)),
    ];
    let scene = cut_scene(name, base, &cuts);
    let scene = scene.to_str().unwrap();
    same_as_stored(&format!("{name}.json"), &stdout_of(&["channel", "--format", "json", "--near-wall", "all", scene]));
}

#[test]
fn built_in_channel() {
    channel_case("channel", None);
}

#[test]
fn shipped_channel() {
    channel_case("example-channel", Some("examples/channel.toml"));
}
