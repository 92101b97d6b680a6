//! `[air]`: the air's temperature, pressure, density and viscosity.

use depo_tracker::Scene;
use serde::Deserialize;

use super::set;

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub(super) struct AirFile {
    pub(super) temperature: Option<f64>,
    pub(super) pressure: Option<f64>,
    pub(super) density: Option<f64>,
    pub(super) viscosity: Option<f64>,
}

pub(super) fn apply_air(scene: &mut Scene, air: &AirFile) {
    set(&mut scene.air.temperature, air.temperature);
    set(&mut scene.air.pressure, air.pressure);
    set(&mut scene.air.density, air.density);
    set(&mut scene.air.viscosity, air.viscosity);
}
