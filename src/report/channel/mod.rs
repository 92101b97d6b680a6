//! The channel study: `V+` against `tau+` in a turbulent channel, beside Wood (1981) and
//! Papavergos & Hedley (1984).
//!
//! [`study`] reads the scene and runs it once, or twice with [`NearWallChoice::All`] (the
//! near-wall layer resolved, then a wall function), into a [`ChannelResult`]; [`table`],
//! [`json`], [`csv`] and [`figures`] render each run or the whole. [`peer`] holds
//! Code_Saturne's own results, which the table and the figure set beside depo's.

pub mod csv;
pub mod figures;
pub mod json;
pub mod peer;
pub mod table;

use depo_tracker::correlations::band_factor;
use depo_tracker::studies::ChannelStudy;
use depo_tracker::{Correlation, Geometry, WallFunction};
use serde::Serialize;

use super::{Measured, Progress, Tally};
use crate::scene_file::{self, ChannelScene, SceneInput, SceneSource};
use crate::Error;

/// How deposition at the walls is modelled, where the caller chooses.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NearWallChoice {
    /// The near-wall layer tracked to the wall.
    Resolved,
    /// A particle within the wall function's layer deposits at the rate of Wood's correlation.
    WallFunction,
    /// Both, one run each.
    All,
}

/// What a channel study runs: its scene, and what a caller may set beside it.
#[derive(Clone, Debug)]
pub struct ChannelOptions {
    /// The scene file, its text or table, or the built-in channel.
    pub scene: SceneInput,
    /// The `tau+` values to run instead of the scene's.
    pub tau_plus: Option<Vec<f64>>,
    /// The near-wall model instead of the scene's `run.near_wall`.
    pub near_wall: Option<NearWallChoice>,
    /// The random seed, instead of the scene's `run.seed`.
    pub seed: Option<u64>,
}

impl ChannelOptions {
    /// The study of `scene`, as its file says.
    pub fn new(scene: SceneInput) -> Self {
        Self { scene, tau_plus: None, near_wall: None, seed: None }
    }
}

/// One `tau+`'s figures beside the correlations, as the JSON gives them.
#[derive(Serialize)]
pub struct Row {
    pub tau_plus: f64,
    pub diameter_um: f64,
    pub schmidt: f64,
    pub v_plus: Measured,
    pub wood: f64,
    pub papavergos_hedley: f64,
    pub ratio_to_wood: f64,
    /// `V+` against the band between Wood and Papavergos & Hedley: 1 within it, else the
    /// factor to its nearer edge (`correlations::band_factor`); null with no deposit.
    pub band_factor: Option<f64>,
    pub particle_steps: u64,
    /// Particles run at this `tau+`.
    pub particles: usize,
    /// "excursions", "excursions+sweeps" (strong sweeps caught before the layer too),
    /// "plain", or "wall-function" (deposition from the layer's correlation).
    pub method: &'static str,
    /// With a wall function: the concentration in its layers over the mean, `C_w / C` (`V+`
    /// is proportional to it; 1 where the layers hold the bulk concentration).
    pub layer_concentration: Option<Measured>,
    /// With excursions: the share of their weight given up at their longest duration.
    pub excursions_truncated: Option<f64>,
    /// Beside a target error: no deposit event, or a relative standard error above the target
    /// (which `max_factor` times the first particles would not reach).
    pub unresolved: bool,
    pub wall_tally: Tally,
}

/// One run of a channel study: its name in the figure, the study as run, its rows.
pub struct ChannelRun {
    /// `depo, resolved` or `depo, wall function`.
    pub name: &'static str,
    pub study: ChannelStudy,
    pub rows: Vec<Row>,
    /// The friction velocity, m/s, and the channel's `Re_tau`.
    pub friction_velocity: f64,
    pub re_tau: f64,
    /// The wall-clock time the run took, s.
    pub seconds: f64,
}

/// A channel study's result: a run, or with [`NearWallChoice::All`] two.
pub struct ChannelResult {
    pub runs: Vec<ChannelRun>,
    /// Whether both near-wall models ran (the table and figure then add Code_Saturne's).
    pub all: bool,
}

/// Reads the scene of `options` and runs its study ([`run`]).
pub fn study(options: &ChannelOptions, progress: &mut dyn Progress) -> Result<ChannelResult, Error> {
    run(scene_file::channel_scene(&options.scene)?, options, progress)
}

/// Runs the study of a channel `scene` with the `tau+` values, near-wall model and seed of
/// `options` (its scene unused), telling `progress` as each `tau+` completes.
pub fn run(scene: ChannelScene, options: &ChannelOptions, progress: &mut dyn Progress) -> Result<ChannelResult, Error> {
    let ChannelScene { mut study, source } = scene;
    if let Some(seed) = options.seed {
        study.settings.seed = seed;
    }
    if let Some(list) = &options.tau_plus {
        if list.is_empty() {
            return Err("--tau-plus: give at least one value".into());
        }
        if let Some(bad) = list.iter().find(|t| !(t.is_finite() && **t > 0.0)) {
            return Err(format!("--tau-plus: {bad} is not a positive number").into());
        }
        study.tau_plus.clone_from(list);
    }
    let with_wall_function = |mut study: ChannelStudy| {
        study.scene.wall_function = Some(study.scene.wall_function.unwrap_or(WallFunction::new(Correlation::Wood)));
        study
    };
    let resolved = |mut study: ChannelStudy| {
        study.scene.wall_function = None;
        study
    };
    let studies = match options.near_wall {
        None => vec![study],
        Some(NearWallChoice::Resolved) => vec![resolved(study)],
        Some(NearWallChoice::WallFunction) => vec![with_wall_function(study)],
        Some(NearWallChoice::All) => vec![resolved(study.clone()), with_wall_function(study)],
    };
    let mut runs = Vec::new();
    for study in studies {
        runs.push(run_one(study, &source, progress)?);
    }
    Ok(ChannelResult { runs, all: options.near_wall == Some(NearWallChoice::All) })
}

/// Runs one channel study into its rows.
fn run_one(study: ChannelStudy, source: &SceneSource, progress: &mut dyn Progress) -> Result<ChannelRun, Error> {
    progress.start(study.tau_plus.len(), "tau+");
    let start = std::time::Instant::now();
    let cancel = progress.cancel();
    let mut run_all = || study.run(|done| progress.done(done));
    let points = match cancel {
        Some(cancel) => cancel.watch(run_all),
        None => run_all(),
    };
    progress.finish();
    let points = points.map_err(|e| Error::of_run(&e, |e| source.scene_error(e)))?;
    let seconds = start.elapsed().as_secs_f64();
    let u_star = study.scene.flow.friction_velocity().unwrap_or(0.0);
    let nu = study.scene.air.kinematic_viscosity();
    let Geometry::Channel { height, .. } = study.scene.geometry else { unreachable!("a channel study has a channel") };
    let re_tau = 0.5 * height * u_star / nu;
    let rows: Vec<Row> = points
        .iter()
        .map(|p| Row {
            tau_plus: p.tau_plus,
            diameter_um: p.diameter * 1e6,
            schmidt: p.schmidt,
            v_plus: p.v_plus.into(),
            wood: p.wood,
            papavergos_hedley: p.papavergos_hedley,
            ratio_to_wood: p.v_plus.value / p.wood,
            band_factor: (p.v_plus.events > 0).then(|| band_factor(p.v_plus.value, p.wood, p.papavergos_hedley)),
            particle_steps: p.particle_steps,
            particles: p.particles,
            method: match (p.excursions, p.sweeps, p.layer_concentration) {
                (Some(_), true, _) => "excursions+sweeps",
                (Some(_), false, _) => "excursions",
                (None, _, Some(_)) => "wall-function",
                (None, _, None) => "plain",
            },
            layer_concentration: p.layer_concentration.map(Into::into),
            excursions_truncated: p.excursions,
            unresolved: study.target_error.is_some_and(|t| p.v_plus.events == 0 || p.v_plus.error > t * p.v_plus.value),
            wall_tally: p.tally.into(),
        })
        .collect();
    let name = if study.scene.wall_function.is_some() { "depo, wall function" } else { "depo, resolved" };
    Ok(ChannelRun { name, study, rows, friction_velocity: u_star, re_tau, seconds })
}
