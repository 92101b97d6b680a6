//! The room study: deposition onto the floor, ceiling and walls of a room (and its
//! furnishings), per particle size, beside Lai & Nazaroff (2000).
//!
//! [`study`] reads the scene and runs it once into a [`RoomResult`]: the study as run and a
//! [`Row`] per size (with a size distribution, per bin, and where its mass went,
//! [`DistributionReport`]). The renderers read that result: [`table`] (the text table),
//! [`json`] (`depo room --format json`), [`csv`] and [`figures`] (SVG figures, decay curves and
//! deposition maps).

pub mod csv;
pub mod distribution;
pub mod figures;
pub mod json;
mod resolution;
pub mod rows;
pub mod table;
#[cfg(test)]
mod tests;

use depo_tracker::distribution::DistributionStudy;
use depo_tracker::studies::RoomStudy;

pub use distribution::DistributionReport;
pub use rows::Row;

use super::{Measured, Progress};
use crate::scene_file::{self, RoomScene, SceneInput};
use crate::Error;

/// What a room study runs: its scene, and what a caller may set beside it.
#[derive(Clone, Debug)]
pub struct RoomOptions {
    /// The scene file, its text or table, or the built-in room.
    pub scene: SceneInput,
    /// The random seed, instead of the scene's `run.seed`.
    pub seed: Option<u64>,
}

impl RoomOptions {
    /// The study of `scene`, as its file says.
    pub fn new(scene: SceneInput) -> Self {
        Self { scene, seed: None }
    }
}

/// A room study's result: the study as run, a row per size, and with a size distribution
/// where its mass went. Every report renders it.
pub struct RoomResult {
    /// The study as run; with a size distribution, its diameters are the bins'.
    pub study: RoomStudy,
    /// One row per size (per bin with a size distribution), in the order run.
    pub rows: Vec<Row>,
    /// With a size distribution: where its mass went.
    pub distribution: Option<DistributionReport>,
    /// The wall-clock time the runs took, s.
    pub seconds: f64,
}

/// Reads the scene of `options` and runs its study ([`run`]).
pub fn study(options: &RoomOptions, progress: &mut dyn Progress) -> Result<RoomResult, Error> {
    let mut scene = scene_file::room_scene(&options.scene)?;
    if let Some(seed) = options.seed {
        scene.study.settings.seed = seed;
    }
    run(scene, progress)
}

/// Runs the study of a room `scene` once, telling `progress` as each size completes; an error
/// of the run names the scene file's key and line.
pub fn run(scene: RoomScene, progress: &mut dyn Progress) -> Result<RoomResult, Error> {
    let mut study: RoomStudy = scene.study;
    // A size distribution runs the study at its bins instead of the study's diameters.
    let distribution = scene.distribution.map(|distribution| DistributionStudy { study: study.clone(), distribution });
    let runs = match &distribution {
        Some(d) => d.bins().map_err(|e| Error::of_run(&e, |e| scene.source.scene_error(e)))?.0.len(),
        None => study.diameters.len(),
    };
    progress.start(runs, "sizes");
    let start = std::time::Instant::now();
    let cancel = progress.cancel();
    let mut run_all = || match &distribution {
        Some(d) => d.run(|done| progress.done(done)).map(|(points, balance)| (points, Some(balance))),
        None => study.run(|done| progress.done(done)).map(|points| (points, None)),
    };
    let outcome = match cancel {
        Some(cancel) => cancel.watch(run_all),
        None => run_all(),
    };
    progress.finish();
    let (points, balance) = outcome.map_err(|e| Error::of_run(&e, |e| scene.source.scene_error(e)))?;
    if distribution.is_some() {
        study.diameters = points.iter().map(|p| p.diameter).collect();
    }
    let furnished = !study.scene.furnishings.is_empty();
    let distribution = balance.map(|b| {
        DistributionReport::new(&b, study.scene.free_volume(), (furnished, study.scene.exchange_rate() > 0.0))
    });
    let seconds = start.elapsed().as_secs_f64();
    // Each run's density: the bins' with a size distribution (in the points' order).
    let density = |i: usize| distribution.as_ref().map_or(study.density, |d| d.bins[i].density);
    let rows: Vec<Row> =
        points.iter().enumerate().map(|(i, p)| rows::row(p, &study.scene, density(i), &study.filtration)).collect();
    Ok(RoomResult { study, rows, distribution, seconds })
}

/// A figure (a rate per hour, a ratio, a time) with its standard error: fixed-point from 0.1,
/// else in e-notation, so that a small one keeps its digits (`4.12e-3 +- 1.4e-4`, never
/// `0.004 +- 0.000`).
fn figure_cell(m: &Measured) -> String {
    if m.value.abs() >= 0.1 {
        format!("{:.3} +- {:.3}", m.value, m.error)
    } else {
        format!("{:.2e} +- {:.1e}", m.value, m.error)
    }
}

/// The rows' densities after a diameter or in a file name, where they have several: `""`
/// or `", 1500 kg/m^3"` (`sep` `", "`, `unit` `" kg/m^3"`).
fn density_label(rows: &[Row], density: f64, sep: &str, unit: &str) -> String {
    if rows.iter().any(|r| r.density != rows[0].density) {
        format!("{sep}{density}{unit}")
    } else {
        String::new()
    }
}
