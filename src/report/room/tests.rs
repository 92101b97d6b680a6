//! The room study's rules of resolution and its table's cells.

use depo_tracker::studies;

use super::figures::significant;
use super::resolution::{particles_to_resolve, two_figures_up, unresolved};
use super::table::model_cell;
use super::*;

/// Resolved: events, and where the model asks it, an error and a given-up share within 5 %.
/// `depo room --help` states the excursions' longest duration and its doublings in words.
#[test]
fn the_help_s_excursion_numbers_are_the_study_s() {
    assert_eq!(studies::ROOM_LONGEST_EXCURSION, 16000.0);
    assert_eq!(studies::LONGEST_SHARE, 0.025);
    assert_eq!(1 << studies::LONGEST_DOUBLINGS, 8);
}

#[test]
fn a_vanishing_model_velocity_reads_as_a_bound() {
    assert_eq!(model_cell(1.97e-138), "< 1e-30");
    assert_eq!(model_cell(0.0), "< 1e-30");
    assert_eq!(model_cell(1.78e-5), "1.78e-5");
}

#[test]
fn significant_digits_drop_trailing_zeros() {
    assert_eq!(significant(12.2828, 3), "12.3");
    assert_eq!(significant(0.011719, 3), "0.0117");
    assert_eq!(significant(10.0, 3), "10");
    assert_eq!(significant(0.3, 3), "0.3");
    assert_eq!(significant(1234.6, 3), "1235");
}

#[test]
fn a_figure_is_unresolved_by_its_error_or_by_what_its_excursions_gave_up() {
    let m = |error: f64, events| Measured { value: 1e-6, error, events, upper_bound: None };
    assert!(!unresolved(&m(4e-8, 100), 1e-6, 0.01));
    assert!(unresolved(&m(6e-8, 100), 1e-6, 0.01));
    assert!(unresolved(&m(4e-8, 100), 1e-6, 0.06));
    assert!(unresolved(&m(0.0, 0), 1e-9, 0.0));
    // Below the model's 1e-7 m/s neither the error nor the given-up share is asked.
    assert!(!unresolved(&m(6e-7, 100), 1e-8, 0.06));
}

/// 8000 particles left the walls at 10 % and the ceiling at 7.4 %: four times the
/// particles halve the walls' error, so 32000, with the study's margin of 1.15 36800,
/// resolve both; the ceiling alone 8000 x 1.48^2 x 1.15 = 20151.7. A figure within 5 %,
/// one without an event and one the model does not ask to resolve set nothing.
#[test]
fn the_particles_to_resolve_a_figure_grow_with_its_error_squared() {
    let m = |error: f64, events| Measured { value: 1e-6, error, events, upper_bound: None };
    let (walls, ceiling, floor) = (m(1e-7, 900), m(7.4e-8, 300), m(4e-8, 5000));
    assert_eq!(particles_to_resolve(8000, [(&floor, 1e-6), (&ceiling, 1e-6), (&walls, 1e-6)]), Some(36800));
    assert_eq!(particles_to_resolve(8000, [(&floor, 1e-6), (&ceiling, 1e-6), (&walls, 1e-8)]), Some(20152));
    assert_eq!(
        [two_figures_up(20152), two_figures_up(36800), two_figures_up(99), two_figures_up(101)],
        [21000, 37000, 99, 110]
    );
    let none = m(0.0, 0);
    assert_eq!(particles_to_resolve(8000, [(&floor, 1e-6), (&none, 1e-6), (&walls, 1e-8)]), None);
}

/// Counts what a study tells its progress.
#[derive(Default)]
struct Counted {
    started: Vec<(usize, String)>,
    done: Vec<usize>,
    finished: usize,
}

impl crate::report::Progress for Counted {
    fn start(&mut self, total: usize, what: &str) {
        self.started.push((total, what.to_string()));
    }
    fn done(&mut self, done: usize) {
        self.done.push(done);
    }
    fn finish(&mut self) {
        self.finished += 1;
    }
}

/// The study of a scene given as a table (a binding's dictionary) renders the JSON its file
/// does; a seed given beside the scene takes the place of its `run.seed`; progress is told
/// each size as it completes.
#[test]
fn a_study_s_json_is_the_same_from_its_file_or_its_table() {
    use crate::scene_file::SceneInput;
    let text = "[room]\nsize = [1.0, 1.0, 1.0]\n[particles]\ndiameters = [3e-6, 10e-6]\ncount = 20\n\
                target_error = 0.0\n[run]\nduration = 20.0\n";
    let path = std::env::temp_dir().join(format!("depo-report-room-{}.toml", std::process::id()));
    std::fs::write(&path, text).unwrap();
    let mut progress = Counted::default();
    let from_file = study(&RoomOptions::new(SceneInput::Path(path.clone())), &mut progress);
    std::fs::remove_file(&path).unwrap();
    let from_file = json::to_json(&from_file.unwrap()).unwrap();
    assert_eq!(progress.started, [(2, "sizes".to_string())]);
    assert_eq!((progress.done, progress.finished), (vec![1, 2], 1));
    let table = || SceneInput::Table { table: toml::from_str(text).unwrap(), name: "scene".into(), dir: ".".into() };
    let from_table = study(&RoomOptions::new(table()), &mut crate::report::Silent).unwrap();
    assert_eq!(json::to_json(&from_table).unwrap(), from_file);
    let seeded = RoomOptions { seed: Some(7), ..RoomOptions::new(table()) };
    let reseeded = json::to_json(&study(&seeded, &mut crate::report::Silent).unwrap()).unwrap();
    assert_ne!(reseeded, from_file);
}

/// Stops the study through its token when the first size is done.
struct StopAfterOne(depo_tracker::Cancel);

impl crate::report::Progress for StopAfterOne {
    fn cancel(&self) -> Option<depo_tracker::Cancel> {
        Some(self.0.clone())
    }
    fn done(&mut self, _done: usize) {
        self.0.cancel();
    }
}

/// A study whose caller cancels its token after the first size ends with `Error::Cancelled`
/// before the next size's run, not with a result nor a scene's error.
#[test]
fn a_cancelled_study_ends_with_the_cancelled_error() {
    use crate::scene_file::SceneInput;
    let text = "[room]\nsize = [1.0, 1.0, 1.0]\n[particles]\ndiameters = [3e-6, 10e-6]\ncount = 20\n\
                target_error = 0.0\n[run]\nduration = 20.0\n";
    let table = SceneInput::Table { table: toml::from_str(text).unwrap(), name: "scene".into(), dir: ".".into() };
    let mut progress = StopAfterOne(depo_tracker::Cancel::new());
    let outcome = study(&RoomOptions::new(table), &mut progress);
    assert_eq!(outcome.err(), Some(Error::Cancelled));
    assert_eq!(Error::Cancelled.to_string(), "the study was cancelled");
}

/// A size the room does not mix well is said so beside its figure, in every report: the
/// table's `near floor` cell is marked `~` with a legend line, the JSON's `well_mixed` is
/// false and the CSV's `well_mixed` column says so; for a size it mixes (0.3 um) none of it.
/// The figure of the steady state names it in its title.
#[test]
fn a_size_the_room_does_not_mix_well_is_flagged_in_every_report() {
    let text = "[particles]\ndiameters = [0.3e-6, 50e-6]\ncount = 300\ntarget_error = 0.0\n\
                [run]\nexcursions = false\nduration = 600.0\n";
    let input = SceneInput::Text { text: text.into(), name: "scene".into(), dir: ".".into() };
    let result = study(&RoomOptions::new(input), &mut crate::report::Silent).unwrap();
    let [fine, coarse] = &result.rows[..] else { panic!("two sizes") };
    assert_eq!((fine.well_mixed, coarse.well_mixed), (Some(true), Some(false)));
    let near = coarse.near_floor_over_mean.unwrap();
    assert!(near.value > 1.2 + 3.0 * near.error, "{}", near.value);

    let table = table::table(&result);
    let line = |d: &str| table.lines().find(|l| l.trim_start().starts_with(d)).unwrap().to_string();
    assert!(line("50.000").contains(&format!("{:.2} ~", near.value)), "{}", line("50.000"));
    assert!(!line("0.300").contains(" ~ "), "{}", line("0.300"));
    assert!(table.contains("~ not well mixed (near floor above 1.2)"), "{table}");

    let json: serde_json::Value = serde_json::from_str(&json::to_json(&result).unwrap()).unwrap();
    assert_eq!(json["sizes"][0]["well_mixed"], serde_json::json!(true));
    assert_eq!(json["sizes"][1]["well_mixed"], serde_json::json!(false));
    assert_eq!(json["sizes"][1]["near_floor_over_mean"]["value"].as_f64(), Some(near.value));

    let csv = csv::to_csv(&result).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let column = header.iter().position(|h| *h == "well_mixed").expect("a well_mixed column");
    let cells: Vec<String> = lines.map(|l| l.split(',').nth(column).unwrap().to_string()).collect();
    assert_eq!(cells, ["true", "false"]);

    let dir = std::env::temp_dir().join(format!("depo-not-mixed-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    figures::figures(&dir, &result, &mut |_| {}).unwrap();
    let svg = std::fs::read_to_string(dir.join("room-steady.svg")).unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    assert!(svg.contains("not well mixed at 50 um"), "the steady figure's title");
}

/// A figure that does not exist is an empty CSV cell, never `NaN`: 50 um particles all settle
/// within a minute, before the decay fit has three sample times, so their fitted `beta` is
/// absent (and ventilated, the indoor/outdoor columns are there and filled).
#[test]
fn the_csv_leaves_an_absent_figure_empty_not_nan() {
    let text = "[particles]\ndiameters = [50e-6]\ncount = 100\ntarget_error = 0.0\n\
                [ventilation]\nair_changes_per_hour = 1.0\n[run]\nexcursions = false\nduration = 600.0\n";
    let input = SceneInput::Text { text: text.into(), name: "scene".into(), dir: ".".into() };
    let result = study(&RoomOptions::new(input), &mut crate::report::Silent).unwrap();
    assert!(result.rows[0].decay_fit.is_none(), "no fit for particles gone within a minute");
    let csv = csv::to_csv(&result).unwrap();
    assert!(!csv.contains("NaN"), "{csv}");
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let row: Vec<&str> = lines.next().unwrap().split(',').collect();
    let cell = |name: &str| row[header.iter().position(|h| *h == name).unwrap()];
    assert_eq!((cell("beta_fitted_per_hour"), cell("beta_fitted_error")), ("", ""));
    assert!(cell("indoor_outdoor").parse::<f64>().is_ok_and(|v| v > 0.0 && v < 1.0));
}
