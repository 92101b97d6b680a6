//! `depo room --format json`: the study's settings and every row, field for field.

use depo_tracker::{Flow, Geometry};
use serde::Serialize;

use super::{DistributionReport, RoomResult, Row};
use crate::Error;

/// What `depo room --format json` prints: the study's settings and its rows.
#[derive(Serialize)]
pub struct Report<'a> {
    pub size_m: [f64; 3],
    pub friction_velocity: f64,
    pub air_changes_per_hour: f64,
    pub penetration: f64,
    /// Share of the air exchange through the filtered supply.
    pub supply_share: f64,
    /// Recirculation through its filter, room volumes per hour.
    pub recirculation_per_hour: f64,
    pub particles_per_size: usize,
    /// With a target: the relative standard error each size was run to reach, and the most
    /// particles it could take.
    pub target_error: Option<f64>,
    pub max_particles_per_size: usize,
    pub duration_s: f64,
    /// The air's volume (the room's less the furnishings'), m^3.
    pub air_volume_m3: f64,
    /// All surfaces' area (walls and furnishing faces) over the air's volume, 1/m.
    pub surface_to_volume_per_m: f64,
    /// Where the steady state's continuous source enters.
    pub steady_source: String,
    pub sizes: &'a [Row],
    /// With a size distribution: where its mass went.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub distribution: Option<&'a DistributionReport>,
}

/// The report of `r` that the JSON serialises.
pub fn report(r: &RoomResult) -> Report<'_> {
    let study = &r.study;
    let rows = &r.rows;
    let Geometry::Room { size } = study.scene.geometry else { unreachable!("a room study has a room") };
    let u_star = match study.scene.flow {
        Flow::TurbulentRoom { friction_velocity, .. } => friction_velocity,
        _ => 0.0,
    };
    Report {
        size_m: size,
        friction_velocity: u_star,
        air_changes_per_hour: study.scene.exchange_rate() * 3600.0,
        penetration: study.penetration,
        supply_share: study.filtration.supply_share,
        recirculation_per_hour: study.filtration.recirculation * 3600.0,
        particles_per_size: study.count,
        target_error: study.target_error,
        max_particles_per_size: study.max_count,
        duration_s: study.settings.duration,
        air_volume_m3: study.scene.free_volume(),
        surface_to_volume_per_m: study.scene.surface_to_volume(),
        steady_source: super::rows::source_label(study),
        sizes: rows,
        distribution: r.distribution.as_ref(),
    }
}

/// The JSON of `r`, pretty-printed, as `depo room --format json` prints it.
pub fn to_json(r: &RoomResult) -> Result<String, Error> {
    Ok(serde_json::to_string_pretty(&report(r)).map_err(|e| e.to_string())?)
}
