//! The scene reader's errors: one line naming the file, the line and the key.

use std::path::PathBuf;

use depo_tracker::{ParticleTally, Record, SceneError};

use super::channel::channel;
use super::room::room_scene;
use super::{line_of_key, SceneInput};

#[test]
fn a_particle_s_memory_is_counted_generously() {
    let kept = std::mem::size_of::<ParticleTally>() + std::mem::size_of::<Record>();
    assert!(kept as u64 * 3 / 2 <= super::run::PARTICLE_BYTES, "{kept} bytes a particle");
}

/// A small room's first lines, so that a bad key below them is on line 9 or later and the
/// runs that reach their checks are quick.
const ROOM: &str = "# A test room.\n\
                    [room]\n\
                    size = [2.0, 2.0, 2.0]\n\
                    [particles]\n\
                    diameters = [1e-6]\n\
                    count = 10\n\
                    target_error = 0.0\n";

/// The scene file `name` holding `text`, in the temporary directory.
fn scene_file(name: &str, text: &str) -> PathBuf {
    let path = std::env::temp_dir().join(format!("depo-scene-file-{}-{name}.toml", std::process::id()));
    std::fs::write(&path, text).unwrap();
    path
}

/// The error of a scene file `text` as the CLI gives it, reading it or else running it
/// (its scene is validated as the run starts), without the file's path it starts with.
fn error(name: &str, text: &str, kind: &str) -> String {
    let path = scene_file(name, text);
    let result = if kind == "room" {
        room_scene(&SceneInput::Path(path.clone()))
            .and_then(|s| s.study.run(|_| {}).map(drop).map_err(|e| s.source.scene_error(&e)))
    } else {
        channel(&SceneInput::Path(path.clone()))
            .and_then(|s| s.study.run(|_| {}).map(drop).map_err(|e| s.source.scene_error(&e)))
    };
    std::fs::remove_file(&path).unwrap();
    let message = result.expect_err("a bad scene");
    let name = path.display().to_string();
    message.strip_prefix(&name).unwrap_or_else(|| panic!("{message} names {name}")).to_string()
}

fn room_error(name: &str, lines: &str) -> String {
    error(name, &format!("{ROOM}{lines}"), "room")
}

#[test]
fn value_errors_name_the_line_of_their_key() {
    assert_eq!(
        room_error("air", "[air]\npressure = 101325.0\ntemperature = -5.0\n"),
        " line 10: `air.temperature` = -5 must be finite and positive"
    );
    assert_eq!(
        room_error("dt", "[run]\nduration = 10.0\n\ndt = 0.0\n"),
        " line 11: `dt` = 0 must be finite and positive"
    );
    assert_eq!(
        room_error("duration", "[run]\n\nduration = 0.0\n"),
        " line 10: `run.duration` = 0 must be finite and positive"
    );
    assert_eq!(
        room_error("scheme", "[run]\nduration = 10.0\nscheme = \"euler\"\n"),
        " line 10: `run.scheme` = \"euler\": expected \"exponential\" or \"midpoint\""
    );
    assert_eq!(
        room_error("transient", "[run]\nduration = 10.0\ntransient = 1.5\n"),
        " line 10: `run.transient` = 1.5 must be in [0, 1)"
    );
    assert_eq!(
        room_error("law", "[walls]\nceiling = { behaviour = \"sink\" }\nfloor = { behaviour = \"law\" }\n"),
        " line 10: `walls.floor.preset` (or the constants `k`, `kappa`, `vc`) is needed for a wall law"
    );
    assert_eq!(
        room_error("behaviour", "[walls.x1]\nbehaviour = \"bounce\"\n"),
        " line 9: `walls.x1.behaviour` = \"bounce\": expected \"sink\", \"reflect\" or \"law\""
    );
    assert_eq!(
        room_error("penetration", "[ventilation]\nair_changes_per_hour = 0.5\npenetration = 2.0\n"),
        " line 10: `ventilation.penetration` = 2 must be in [0, 1]"
    );
    assert_eq!(
        room_error("friction", "[flow]\ncore_rms = 0.01\n\n\nfriction_velocity = -1.0\n"),
        " line 12: `flow.friction_velocity` = -1 must be finite and positive"
    );
    // A furnishing's face: the line of its key, in the second entry.
    let furnished = "[[furnishings]]\nlow = [0.5, 0.5, 0.5]\nhigh = [0.7, 0.7, 0.7]\n\
                     [[furnishings]]\nlow = [1.0, 1.0, 1.0]\nhigh = [1.5, 1.5, 1.5]\n\
                     top = { preset = \"nope\" }\n";
    let message = room_error("face", furnished);
    assert!(message.starts_with(" line 14: `furnishings[1].top.preset`: "), "{message}");
    // A law's own constant at fault: its line, not the surface's.
    let message = room_error("p", "[walls.floor]\nk = 10.0\nkappa = 0.2\nvc = 0.07\n\np = -1.0\n");
    assert!(message.starts_with(" line 13: `walls.floor`: "), "{message}");
    let sized = "[walls.floor]\npreset = \"dunn1995-copper\"\nsize_exponent = 1.5\n\nreference_diameter = -1.0\n";
    let message = room_error("reference", sized);
    assert!(message.starts_with(" line 12: `walls.floor`: "), "{message}");
}

#[test]
fn channel_errors_name_the_line_of_their_key() {
    let head = "[channel]\nre_tau = 150.0\n[particles]\ntau_plus = [1.0]\ncount = 10\n";
    let message = error("lower", &format!("{head}[walls]\nlower = {{ preset = \"nope\" }}\n"), "channel");
    assert!(message.starts_with(" line 7: `walls.lower.preset`: "), "{message}");
    // Room walls in a channel: the first of them in the file.
    let foreign = format!("{head}[walls]\nx0 = {{ behaviour = \"sink\" }}\nceiling = {{ behaviour = \"sink\" }}\n");
    let message = error("foreign", &foreign, "channel");
    assert!(message.starts_with(" line 7: `walls`: a room has"), "{message}");
    assert_eq!(
        error("seconds", &format!("{head}[run]\nduration_plus = 10.0\ndt = 0.1\n"), "channel"),
        " line 8: a channel takes `run.dt_plus` and `run.duration_plus` in wall units"
    );
    assert_eq!(
        error("tau_plus", "[channel]\nre_tau = 150.0\n[particles]\ntau_plus = []\ncount = 10\n", "channel"),
        " line 4: `particles.tau_plus` is empty"
    );
    assert_eq!(
        error("duration_plus", &format!("{head}[run]\nduration_plus = 0.0\n"), "channel"),
        " line 7: `run.duration_plus` = 0 must be finite and positive"
    );
    let message = error("dt_plus", &format!("{head}[run]\nduration_plus = 10.0\ndt_plus = -0.1\n"), "channel");
    assert!(message.starts_with(" line 8: `dt` = -") && message.ends_with(" must be finite and positive"), "{message}");
}

/// Errors of what the file gives as a whole, or through other keys, name the keys it wrote.
#[test]
fn errors_name_the_keys_the_file_wrote() {
    let filled = "[[furnishings]]\nlow = [0.001, 0.001, 0.001]\nhigh = [1.999, 1.999, 1.999]\n";
    let message = room_error("filled", filled);
    assert!(message.starts_with(" line 8: `[[furnishings]]` take up 99.7"), "{message}");
    assert!(!message.contains("particles.region"), "{message}");
    let shallow = "[channel]\nre_tau = 0.5\n[particles]\ntau_plus = [100.0]\ncount = 10\n";
    let message = error("shallow", shallow, "channel");
    assert!(
        message.starts_with(" line 2: `channel.re_tau` = 0.5: the channel, 2 Re_tau wall units high, must be"),
        "{message}"
    );
    assert!(message.contains("its largest particle, 73.6924 um across (`particles.tau_plus`)"), "{message}");
    let heavy = "[channel]\nre_tau = 150.0\n[particles]\ntau_plus = [30000.0]\ncount = 10\n";
    let message = error("heavy", heavy, "channel");
    assert!(message.starts_with(" line 4: `particles.tau_plus`: a particle of "), "{message}");
    assert!(message.contains(" um must be at most 1 mm"), "{message}");
}

/// A key the file leaves out is the default's: no line (none in the file is the key's).
#[test]
fn a_default_value_s_error_has_no_line() {
    let path = scene_file("default", &format!("{ROOM}[run]\nduration = 10.0\n"));
    let scene = room_scene(&SceneInput::Path(path.clone())).unwrap();
    std::fs::remove_file(&path).unwrap();
    let e = SceneError { field: "flow.core_time".into(), value: 0.0, requirement: "must be finite and positive" };
    assert_eq!(
        scene.source.scene_error(&e),
        format!("{}: `flow.core_time` = 0 must be finite and positive", path.display())
    );
    let e = SceneError { field: "duration".into(), ..e };
    assert!(scene.source.scene_error(&e).contains(" line 9: `duration` = 0"), "{e}");
    let built_in = room_scene(&SceneInput::BuiltIn).unwrap().source;
    assert_eq!(built_in.scene_error(&e), "the built-in room: `duration` = 0 must be finite and positive");
}

/// Dotted keys in tables, inline tables, headers and arrays of tables.
#[test]
fn keys_are_found_by_their_spans() {
    let text = "title = 1\n\
                [walls]\n\
                floor = { preset = \"a\",\n  mu = 0.3 }\n\
                [walls.x0]\n\
                k = 1.0\n\
                [[furnishings]]\n\
                low = [1, 2, 3]\n\
                [[furnishings]]\n\
                top.preset = \"b\"\n";
    let root = toml::de::DeTable::parse(text).unwrap();
    let line = |key: &str| line_of_key(text, root.get_ref(), key);
    assert_eq!(line("title"), Some(1));
    assert_eq!(line("walls"), Some(2));
    assert_eq!(line("walls.floor"), Some(3));
    assert_eq!(line("walls.floor.mu"), Some(4));
    assert_eq!(line("walls.x0"), Some(5));
    assert_eq!(line("walls.x0.k"), Some(6));
    assert_eq!(line("furnishings[0]"), Some(7));
    assert_eq!(line("furnishings[0].low"), Some(8));
    assert_eq!(line("furnishings[1].top.preset"), Some(10));
    for absent in ["run.dt", "walls.x1", "walls.floor.k", "furnishings[2]", "title.x", "walls[0]", "furnishings.low"] {
        assert_eq!(line(absent), None, "{absent}");
    }
}

/// A scene given as text or as a parsed table (a binding's dictionary) reads as its file does,
/// with the same one-line errors under the name given for it.
#[test]
fn a_scene_from_text_or_a_table_reads_as_its_file() {
    let text = "[particles]\ntarget_error = -0.1\n";
    let message = "`particles.target_error` = -0.1 must be finite and not negative";
    let dir = PathBuf::from(".");
    let from_text = SceneInput::Text { text: text.to_string(), name: "scene".into(), dir: dir.clone() };
    assert_eq!(room_scene(&from_text).err(), Some(format!("scene line 2: {message}")));
    let table: toml::Table = toml::from_str(text).unwrap();
    let from_table = SceneInput::Table { table, name: "scene".into(), dir: dir.clone() };
    // A table has no lines: its errors name the key alone, the reader's and the TOML's.
    assert_eq!(room_scene(&from_table).err(), Some(format!("scene: {message}")));
    let wrong_type = "[room]\nsize = [4.0, 3.0, 2.5]\n[run]\nseed = 1\nduration = \"long\"\n";
    let table =
        SceneInput::Table { table: toml::from_str(wrong_type).unwrap(), name: "scene".into(), dir: dir.clone() };
    let error = room_scene(&table).err().unwrap();
    assert!(error.starts_with("scene: `run.duration`: invalid type: string"), "{error}");
    let unknown = "[walls]\nfloor = { behaviour = \"law\", preset = \"li1997-sio2\", kk = 1.0 }\n";
    let table = SceneInput::Table { table: toml::from_str(unknown).unwrap(), name: "scene".into(), dir: dir.clone() };
    let error = room_scene(&table).err().unwrap();
    assert!(error.starts_with("scene: `walls.floor.kk`: unknown field `kk`"), "{error}");
    let furnished = "[[furnishings]]\nname = \"a\"\nlow = [0.0, 0.0, 0.0]\nhigh = [1.0, 1.0, 1.0]\n\
                     [[furnishings]]\nname = \"b\"\nlow = [0.0, 0.0]\nhigh = [1.0, 1.0, 1.0]\n";
    let table = SceneInput::Table { table: toml::from_str(furnished).unwrap(), name: "scene".into(), dir: dir.clone() };
    let error = room_scene(&table).err().unwrap();
    assert!(error.starts_with("scene: `furnishings[1].low`: invalid length 2"), "{error}");
    let path = scene_file("text", ROOM);
    let from_file = room_scene(&SceneInput::Path(path.clone())).unwrap();
    std::fs::remove_file(&path).unwrap();
    let table: toml::Table = toml::from_str(ROOM).unwrap();
    let from_table = room_scene(&SceneInput::Table { table, name: "scene".into(), dir }).unwrap();
    assert!(from_table.study == from_file.study, "the table's study differs from the file's");
}

/// Two openings for the small test room: a supply in the ceiling (`openings[0]`) and an
/// exhaust on the `x1` wall (`openings[1]`), 8 lines.
const OPENINGS: &str = "[[openings]]\nkind = \"supply\"\nwall = \"ceiling\"\ncenter = [1.0, 1.0]\nsize = [0.2, 0.2]\n\
                        flow_m3_per_hour = 10.0\n[[openings]]\nkind = \"exhaust\"\nwall = \"x1\"\ncenter = [1.0, 0.3]\n\
                        size = [0.2, 0.2]\nflow_m3_per_hour = 10.0\n";

/// `[source]` reads where the steady state's source enters, and its errors name the key the
/// file wrote, at its line: a name it does not know, infiltration without ventilation, a supply
/// without a supply opening or at an exhaust, a region outside the room or for another entry.
#[test]
fn the_source_s_entry_is_read_and_its_errors_name_the_key_written() {
    use depo_tracker::steady::Source;
    let read = |name: &str, lines: &str| {
        let path = scene_file(name, &format!("{ROOM}{lines}"));
        let scene = room_scene(&SceneInput::Path(path.clone()));
        std::fs::remove_file(&path).unwrap();
        scene.map(|s| s.study.source)
    };
    assert_eq!(read("src-none", "").unwrap(), None);
    assert_eq!(
        read("src-supply", &format!("{OPENINGS}[source]\nenters = \"supply\"\n")).unwrap(),
        Some(Source::Supply(0))
    );
    assert_eq!(
        read("src-region", "[source]\nenters = \"indoor\"\nregion = [[0.0, 0.0, 0.0], [2.0, 2.0, 0.2]]\n").unwrap(),
        Some(Source::Indoor(Some(([0.0; 3], [2.0, 2.0, 0.2]))))
    );
    assert_eq!(
        read("src-infiltration", "[ventilation]\nair_changes_per_hour = 1.0\n[source]\nenters = \"infiltration\"\n")
            .unwrap(),
        Some(Source::Infiltration)
    );
    assert_eq!(
        room_error("src-name", "[source]\nenters = \"window\"\n"),
        " line 9: `source.enters` = \"window\": expected \"indoor\" or \"infiltration\" or \"supply\""
    );
    assert_eq!(
        room_error("src-closed", "[source]\nenters = \"infiltration\"\n"),
        " line 9: `source.enters` = \"infiltration\" needs ventilation: `ventilation.air_changes_per_hour` or \
         `[[openings]]`"
    );
    assert_eq!(
        room_error("src-no-supply", "[source]\nenters = \"supply\"\n"),
        " line 9: `source.enters` = \"supply\" needs a supply opening in `[[openings]]`"
    );
    assert_eq!(
        room_error("src-exhaust", &format!("{OPENINGS}[source]\nenters = \"supply\"\nopening = 1\n")),
        " line 22: `source.opening` = 1 is not a supply opening: `openings[1]` is an exhaust"
    );
    assert_eq!(
        room_error("src-outside", "[source]\nenters = \"indoor\"\nregion = [[0.0, 0.0, 0.0], [3.0, 1.0, 1.0]]\n"),
        " line 10: `source.region` = [[0, 0, 0], [3, 1, 1]] must be a box inside the room (2 x 2 x 2 m), its first \
         corner below its second on every axis"
    );
    assert_eq!(
        room_error(
            "src-region-supply",
            &format!("{OPENINGS}[source]\nenters = \"supply\"\nregion = [[0.0, 0.0, 0.0], [1.0, 1.0, 1.0]]\n")
        ),
        " line 22: `source.region` places an indoor source: not with `source.enters` = \"supply\""
    );
    assert_eq!(
        room_error("src-bare-region", "[source]\nregion = [[0.0, 0.0, 0.0], [1.0, 1.0, 1.0]]\n"),
        " line 9: `source.region` needs `source.enters` = \"indoor\""
    );
}

/// A room's wall function takes Lai & Nazaroff's correlation, and on its vertical walls the
/// one `run.vertical_correlation` names; the key is refused without a wall function.
#[test]
fn the_vertical_walls_take_their_own_correlation() {
    use depo_tracker::{Correlation, WallFunction};
    let text = format!("{ROOM}[run]\nnear_wall = \"wall-function\"\nvertical_correlation = \"hussein\"\n");
    let path = scene_file("vertical", &text);
    let scene = room_scene(&SceneInput::Path(path.clone())).map(|s| s.study.scene.wall_function);
    std::fs::remove_file(&path).unwrap();
    let expected = WallFunction { vertical: Some(Correlation::Hussein), ..WallFunction::new(Correlation::LaiNazaroff) };
    assert_eq!(scene, Ok(Some(expected)));
    assert_eq!(
        room_error("unset", "[run]\nduration = 10.0\nvertical_correlation = \"hussein\"\n"),
        " line 10: `run.vertical_correlation` is for a wall function: set `run.near_wall = \"wall-function\"`"
    );
    let message = room_error("name", "[run]\nnear_wall = \"wall-function\"\nvertical_correlation = \"zhao-wu\"\n");
    assert!(
        message.ends_with("expected \"wood\" or \"papavergos-hedley\" or \"lai-nazaroff\" or \"hussein\""),
        "{message}"
    );
}
