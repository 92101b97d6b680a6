//! `[ventilation]`: the air exchange, the outdoor particles' penetration, and the supply and
//! recirculation filters.

use depo_tracker::filtration::FilterEfficiency;
use depo_tracker::studies::RoomStudy;
use serde::Deserialize;

use super::{Error, SceneSource};

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub(super) struct VentilationFile {
    pub(super) air_changes_per_hour: Option<f64>,
    pub(super) penetration: Option<f64>,
    pub(super) supply_share: Option<f64>,
    pub(super) supply_filter: Option<EfficiencyFile>,
    pub(super) recirculation_per_hour: Option<f64>,
    pub(super) recirculation_filter: Option<EfficiencyFile>,
}

/// A filter's efficiency in a scene: one number for every size, or `[diameter m, efficiency]`
/// pairs.
#[derive(Deserialize)]
#[serde(untagged)]
pub(super) enum EfficiencyFile {
    One(f64),
    Curve(Vec<[f64; 2]>),
}

/// The filter of `ventilation.{key}` as [`FilterEfficiency`], or an error naming the file, the
/// key and its line.
pub(super) fn filter_efficiency(
    src: &SceneSource,
    key: &str,
    file: &EfficiencyFile,
) -> Result<FilterEfficiency, Error> {
    let curve = match file {
        EfficiencyFile::One(eta) => FilterEfficiency::constant(*eta),
        EfficiencyFile::Curve(points) => FilterEfficiency::new(points.iter().map(|&[d, eta]| (d, eta)).collect()),
    };
    let key = format!("ventilation.{key}");
    curve.map_err(|e| src.at(&[&key], format!("`{key}`: {} = {} {}", e.field, e.value, e.requirement)))
}

/// The ventilation `ventilation` gives `study`: its exchange rate (none beside openings, whose
/// exhaust sets it), penetration and filters; an error names the key and its line.
pub(super) fn apply_ventilation(
    src: &SceneSource,
    study: &mut RoomStudy,
    ventilation: &VentilationFile,
) -> Result<(), Error> {
    // An error at the line of `ventilation.{key}`.
    let at = |key: &str, message: String| src.at(&[&format!("ventilation.{key}")], message);
    if let Some(ach) = ventilation.air_changes_per_hour {
        if !(ach.is_finite() && ach >= 0.0) {
            return Err(at(
                "air_changes_per_hour",
                format!("`ventilation.air_changes_per_hour` = {ach} must be finite and not negative"),
            ));
        }
        if ach > 0.0 && !study.scene.openings.is_empty() {
            return Err(at(
                "air_changes_per_hour",
                format!(
                    "`ventilation.air_changes_per_hour` = {ach} must be 0 with `[[openings]]`: their exhaust flow sets it"
                ),
            ));
        }
        study.scene.air_exchange = ach / 3600.0;
    }
    if let Some(p) = ventilation.penetration {
        if !(0.0..=1.0).contains(&p) {
            return Err(at("penetration", format!("`ventilation.penetration` = {p} must be in [0, 1]")));
        }
        study.penetration = p;
    }
    if let Some(share) = ventilation.supply_share {
        if !(0.0..=1.0).contains(&share) {
            return Err(at("supply_share", format!("`ventilation.supply_share` = {share} must be in [0, 1]")));
        }
        study.filtration.supply_share = share;
    }
    if let Some(filter) = &ventilation.supply_filter {
        study.filtration.supply_filter = filter_efficiency(src, "supply_filter", filter)?;
    }
    if let Some(rate) = ventilation.recirculation_per_hour {
        if !(rate.is_finite() && rate >= 0.0) {
            return Err(at(
                "recirculation_per_hour",
                format!("`ventilation.recirculation_per_hour` = {rate} must be finite and not negative"),
            ));
        }
        if rate > 0.0 && !study.scene.openings.is_empty() {
            return Err(at(
                "recirculation_per_hour",
                format!(
                    "`ventilation.recirculation_per_hour` = {rate} must be 0 with `[[openings]]` (not modelled beside them)"
                ),
            ));
        }
        study.filtration.recirculation = rate / 3600.0;
    }
    if let Some(filter) = &ventilation.recirculation_filter {
        study.filtration.recirculation_filter = filter_efficiency(src, "recirculation_filter", filter)?;
    }
    Ok(())
}
