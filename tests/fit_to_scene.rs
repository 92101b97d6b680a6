//! From measured restitution to a scene: the entry `depo fit` prints for a surface is what
//! `depo room` (and `depo channel`) read, with the fitted constants to the last bit, under
//! every surface key it offers; an entry short of a constant is an error naming the key.

use std::path::{Path, PathBuf};

use serde_json::Value;

/// The synthetic series of the examples: the `li1997-sio2` curve (q = 1/2) with 2 % noise.
const DATA: &str = "examples/li1997-synthetic.csv";

mod common;
use common::{depo, ok_json, ok_text};

/// The fit of the example data (with q = 1/2, its curve's) as JSON, its entry for `surface`.
fn fit_for(surface: &str) -> Value {
    ok_json(&["fit", DATA, "--q", "0.5", "--format", "json", "--surface", surface])
}

fn entry(fit: &Value) -> &str {
    fit["scene_entry"].as_str().unwrap_or_else(|| panic!("no scene_entry: {fit}"))
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("depo-fit-to-scene-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A room as cheap as a valid run gets: one size of 10 um particles that settle onto the
/// floor within the run, plain tracking, no error target; `tail` adds the surfaces.
fn small_room(dir: &Path, tail: &str) -> PathBuf {
    let scene = dir.join("room.toml");
    std::fs::write(
        &scene,
        format!(
            "[room]\nsize = [1.0, 1.0, 1.0]\n[particles]\ndiameters = [10e-6]\ncount = 100\ntarget_error = 0.0\n\
             [run]\nduration = 30.0\nexcursions = false\n{tail}"
        ),
    )
    .unwrap();
    scene
}

#[test]
fn the_printed_entry_runs_a_room_with_the_fitted_constants() {
    let fit = fit_for("floor");
    let line = entry(&fit);
    assert!(line.starts_with("floor = { behaviour = \"law\", "), "{line}");
    assert!(!line.contains("mu"), "friction is not fitted: {line}");

    // The entry is TOML whose numbers are the fitted ones, bit for bit (and floats: `p = 1.0`).
    let table: toml::Table = toml::from_str(line).expect("the entry is TOML");
    let law = table["floor"].as_table().expect("an inline table");
    assert_eq!(law["behaviour"].as_str(), Some("law"));
    for key in ["k", "kappa", "vc", "p", "q"] {
        let printed = law[key].as_float().unwrap_or_else(|| panic!("{key} is no float in {line}"));
        let fitted = fit[key].as_f64().unwrap();
        assert_eq!(printed.to_bits(), fitted.to_bits(), "{key}: {printed} printed, {fitted} fitted");
    }
    assert_eq!(law.len(), 6, "behaviour and the five constants: {line}");

    // The table prints the same entry, with where it goes and that friction is left out.
    let table_text = ok_text(&["fit", DATA, "--q", "0.5"]);
    let lines: Vec<&str> = table_text.lines().collect();
    let at = lines.iter().position(|l| *l == format!("scene: {line}")).unwrap_or_else(|| panic!("{table_text}"));
    let notes = &lines[at + 1..(at + 3).min(lines.len())];
    assert!(notes.len() == 2 && notes.iter().all(|l| l.trim_start().starts_with('#')), "{table_text}");
    assert!(notes[0].contains("under [walls] of a room scene") && notes[1].contains("mu"), "{table_text}");

    // Pasted under [walls], the entry runs, and the floor's contacts go through the law: the
    // adhesion takes energy, as a sink's contacts never do.
    let dir = scratch("room");
    let scene = small_room(&dir, &format!("[walls]\n{line}\n"));
    let report = ok_json(&["room", scene.to_str().unwrap(), "--format", "json", "--no-plot"]);
    let tally = &report["sizes"][0]["wall_tally"];
    assert!(tally["contacts"].as_u64().unwrap() > 0, "{tally}");
    assert!(tally["energy_lost_adhesion"].as_f64().unwrap() > 0.0, "{tally}");
    std::fs::remove_dir_all(dir).ok();
}

/// An entry short of a constant is one error line naming the surface's key.
#[test]
fn an_entry_without_vc_is_rejected_naming_the_key() {
    let fit = fit_for("x0");
    let line = entry(&fit);
    let vc = format!(", vc = {:?}", fit["vc"].as_f64().unwrap());
    assert!(line.contains(&vc), "{line}");
    let dir = scratch("no-vc");
    let scene = small_room(&dir, &format!("[walls]\n{}\n", line.replace(&vc, "")));
    let out = depo(&["room", scene.to_str().unwrap(), "--no-plot"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "a law without vc ran");
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert_eq!(stderr.trim_end().lines().count(), 1, "one line: {stderr}");
    assert!(stderr.starts_with("depo: ") && stderr.contains("`walls.x0.vc` is needed"), "{stderr}");
    std::fs::remove_dir_all(dir).ok();
}

/// Every surface `--surface` offers is read where the printed note puts it: the room's walls
/// and a furnishing's faces in a room scene, the channel's walls in a channel scene.
#[test]
fn every_offered_surface_is_a_key_the_scene_reader_takes() {
    let entries = |names: &[&str]| -> String { names.iter().map(|n| format!("{}\n", entry(&fit_for(n)))).collect() };
    let dir = scratch("surfaces");
    let walls = entries(&["all", "floor", "ceiling", "x0", "x1", "y0", "y1"]);
    let faces = entries(&["all", "bottom", "top", "x0", "x1", "y0", "y1"]);
    let scene = small_room(
        &dir,
        &format!(
            "[walls]\n{walls}[[furnishings]]\nname = \"table\"\nlow = [0.3, 0.3, 0.4]\nhigh = [0.7, 0.7, 0.45]\n{faces}"
        ),
    );
    let report = ok_json(&["room", scene.to_str().unwrap(), "--format", "json", "--no-plot"]);
    assert_eq!(report["sizes"][0]["furnishings"][0]["name"], "table", "{report}");
    // An entry lands on the surface it names: with the law on the floor and the table's top
    // only (sinks elsewhere), those two alone show the law's adhesion losses in their tallies.
    let scene = small_room(
        &dir,
        &format!(
            "[walls]\n{}[[furnishings]]\nname = \"table\"\nlow = [0.3, 0.3, 0.4]\nhigh = [0.7, 0.7, 0.45]\n{}",
            entries(&["floor"]),
            entries(&["top"])
        ),
    );
    let report = ok_json(&["room", scene.to_str().unwrap(), "--format", "json", "--no-plot"]);
    let tallies = report["sizes"][0]["surface_tallies"].as_array().unwrap();
    for t in tallies {
        let (name, adhesion) = (t["surface"].as_str().unwrap(), t["energy_lost_adhesion"].as_f64().unwrap());
        let contacts = t["contacts"].as_u64().unwrap();
        if name == "floor" || name == "table.top" {
            assert!(contacts > 0 && adhesion > 0.0, "{t}");
        } else {
            assert_eq!(adhesion, 0.0, "{t}");
            assert_eq!(t["captures"], t["contacts"], "a sink captures at every contact: {t}");
        }
    }
    assert_eq!(tallies.len(), 12, "the room's six surfaces and the table's six faces");

    let channel = dir.join("channel.toml");
    std::fs::write(
        &channel,
        format!(
            "[particles]\ntau_plus = [10.0]\ncount = 50\ntarget_error = 0.0\n[run]\nduration_plus = 100.0\n\
             excursions = false\n[walls]\n{}",
            entries(&["lower", "upper"])
        ),
    )
    .unwrap();
    let report = ok_json(&["channel", channel.to_str().unwrap(), "--format", "json"]);
    assert_eq!(report["points"][0]["tau_plus"], 10.0, "{report}");
    std::fs::remove_dir_all(dir).ok();
}

/// The entry the guides and the example scene show is the one `depo fit` prints for the
/// example data, so pasting it from them gives the fitted law too.
#[test]
fn the_documented_entry_is_the_printed_one() {
    let line = entry(&fit_for("x0")).to_string();
    for doc in ["docs/commands.md", "docs/tracker.md"] {
        let text = std::fs::read_to_string(doc).unwrap();
        assert!(text.contains(&format!("scene: {line}\n")), "{doc} does not show `scene: {line}`");
    }
    let example = std::fs::read_to_string("examples/room.toml").unwrap();
    let with_mu = format!("# {}, mu = 0.3 }}\n", line.strip_suffix(" }").unwrap());
    assert!(example.contains(&with_mu), "examples/room.toml does not show {with_mu}");
}
