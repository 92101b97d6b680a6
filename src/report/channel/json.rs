//! `depo channel --format json`: a run's settings and every row, field for field.

use serde::Serialize;

use super::{ChannelRun, Row};
use crate::Error;

/// What `depo channel --format json` prints for a run: its settings and its rows.
#[derive(Serialize)]
pub struct Report<'a> {
    pub friction_velocity: f64,
    pub re_tau: f64,
    pub particles_per_point: usize,
    /// Particles per point where excursions count the deposits (`tau+` below
    /// `excursions_below_tau_plus`).
    pub excursion_particles_per_point: usize,
    pub excursions_below_tau_plus: f64,
    /// The relative standard error each `V+` is run to, where its first particles times
    /// `max_factor` reach it.
    pub target_error: Option<f64>,
    pub max_factor: f64,
    pub duration_plus: f64,
    pub points: &'a [Row],
}

/// The report of `run` that the JSON serialises.
pub fn report(run: &ChannelRun) -> Report<'_> {
    let study = &run.study;
    let (u_star, re_tau) = (run.friction_velocity, run.re_tau);
    let nu = study.scene.air.kinematic_viscosity();
    Report {
        friction_velocity: u_star,
        re_tau,
        particles_per_point: study.count,
        excursion_particles_per_point: study.excursion_count,
        excursions_below_tau_plus: study.excursions_below,
        target_error: study.target_error,
        max_factor: study.max_factor,
        duration_plus: study.settings.duration * u_star * u_star / nu,
        points: &run.rows,
    }
}

/// The JSON of `run`, pretty-printed, as `depo channel --format json` prints it.
pub fn to_json(run: &ChannelRun) -> Result<String, Error> {
    Ok(serde_json::to_string_pretty(&report(run)).map_err(|e| e.to_string())?)
}
