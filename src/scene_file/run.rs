//! `[run]`: the time step and length, the seed, the physics switched on, the drag law, the
//! scheme and the near-wall model; and the checks of counts and lengths a run needs.

use depo_tracker::{Correlation, Drag, Geometry, NearWall, RunSettings, Scene, Scheme, WallFunction};
use serde::Deserialize;

use super::{named, set, Error, SceneSource};
use crate::text::check_memory;

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub(super) struct RunFile {
    pub(super) dt: Option<f64>,
    pub(super) duration: Option<f64>,
    pub(super) dt_plus: Option<f64>,
    pub(super) duration_plus: Option<f64>,
    pub(super) seed: Option<u64>,
    pub(super) brownian: Option<bool>,
    pub(super) gravity: Option<f64>,
    pub(super) lift: Option<bool>,
    pub(super) transient: Option<f64>,
    /// "stokes" or "schiller-naumann".
    pub(super) drag: Option<String>,
    /// "gaussian", "intermittent" (channels) or "wall-function".
    pub(super) near_wall: Option<String>,
    /// The wall function's correlation: "wood", "papavergos-hedley", "lai-nazaroff" or
    /// "hussein".
    pub(super) correlation: Option<String>,
    /// The wall function's correlation on vertical surfaces, if not `correlation`.
    pub(super) vertical_correlation: Option<String>,
    /// The wall function's layer in wall units.
    pub(super) layer_plus: Option<f64>,
    /// "exponential" or "midpoint".
    pub(super) scheme: Option<String>,
    pub(super) excursions: Option<bool>,
}

/// The run's named choices where the file makes them: the drag law, the step (the studies offer
/// the exponential scheme and its midpoint form; Euler is for the integrator benchmark), the
/// near-wall model and what it steps.
pub(super) fn apply_run_choices(
    src: &SceneSource,
    (scene, settings): (&mut Scene, &mut RunSettings),
    run: &RunFile,
) -> Result<(), Error> {
    let drag = [("stokes", Drag::Stokes), ("schiller-naumann", Drag::SchillerNaumann)];
    set(&mut scene.drag, named(src, "run.drag", run.drag.as_deref(), &drag)?);
    let schemes = [("exponential", Scheme::Exponential), ("midpoint", Scheme::Midpoint)];
    set(&mut settings.scheme, named(src, "run.scheme", run.scheme.as_deref(), &schemes)?);
    let models = [
        ("gaussian", Some(NearWall::Gaussian)),
        ("intermittent", Some(NearWall::Intermittent)),
        ("wall-function", None),
    ];
    match named(src, "run.near_wall", run.near_wall.as_deref(), &models)? {
        Some(Some(model)) => scene.near_wall = model,
        // The wall function's transport is the Gaussian model's.
        Some(None) => {
            scene.near_wall = NearWall::Gaussian;
            let correlation = if matches!(scene.geometry, Geometry::Channel { .. }) {
                Correlation::Wood
            } else {
                Correlation::LaiNazaroff
            };
            scene.wall_function = Some(WallFunction::new(correlation));
        }
        None => {}
    }
    let correlation = named(src, "run.correlation", run.correlation.as_deref(), &Correlation::NAMED)?;
    let vertical = named(src, "run.vertical_correlation", run.vertical_correlation.as_deref(), &Correlation::NAMED)?;
    if let Some(wf) = &mut scene.wall_function {
        set(&mut wf.correlation, correlation);
        if vertical.is_some() {
            wf.vertical = vertical;
        }
        set(&mut wf.layer_plus, run.layer_plus);
    } else if let Some(key) = [
        (correlation.is_some(), "run.correlation"),
        (vertical.is_some(), "run.vertical_correlation"),
        (run.layer_plus.is_some(), "run.layer_plus"),
    ]
    .into_iter()
    .find_map(|(given, key)| given.then_some(key))
    {
        return Err(src.at(&[key], format!("`{key}` is for a wall function: set `run.near_wall = \"wall-function\"`")));
    }
    Ok(())
}

pub(super) fn gravity(g: f64) -> [f64; 3] {
    [0.0, 0.0, -g]
}

/// A run's length `key`, if the file sets it: a run of no time measures nothing (its rates
/// would be bounds of `inf`).
pub(super) fn check_duration(src: &SceneSource, key: &str, value: Option<f64>) -> Result<(), Error> {
    match value {
        Some(d) if !(d.is_finite() && d > 0.0) => {
            Err(src.at(&[key], format!("`{key}` = {d} must be finite and positive")))
        }
        _ => Ok(()),
    }
}

/// `particles.target_error`, if the file sets it: 0 turns the target off.
pub(super) fn set_target_error(
    src: &SceneSource,
    target_error: &mut Option<f64>,
    value: Option<f64>,
) -> Result<(), Error> {
    if let Some(target) = value {
        if !(target.is_finite() && target >= 0.0) {
            let key = "particles.target_error";
            return Err(src.at(&[key], format!("`{key}` = {target} must be finite and not negative")));
        }
        *target_error = (target > 0.0).then_some(target);
    }
    Ok(())
}

/// A particle count whose particles would not fit in memory is one line, not an abort: the
/// count's `key`, at the line of the first of `lines` the file gives.
pub(super) fn check_count(src: &SceneSource, key: &str, lines: &[&str], count: usize) -> Result<(), Error> {
    check_memory(&src.at(lines, format!("`{key}` = {count}")), count as u64, PARTICLE_BYTES)
}

/// What a particle of a run keeps in memory, generously: its record and tally (about 900
/// bytes with the excursions' counts by level and by class of crossing, and 24 bytes per
/// deposit event for the maps), and a share of the study's results.
pub(super) const PARTICLE_BYTES: u64 = 1536;

pub(super) fn check_transient(src: &SceneSource, transient: f64) -> Result<(), Error> {
    if (0.0..1.0).contains(&transient) {
        Ok(())
    } else {
        Err(src.at(&["run.transient"], format!("`run.transient` = {transient} must be in [0, 1)")))
    }
}
