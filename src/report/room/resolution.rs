//! When a room study's figure is resolved, and how many particles would resolve it: the rules
//! the rows flag and the table's notes state.

use depo_tracker::studies;

use crate::report::Measured;

/// A surface's figure is resolved when its relative standard error is at most this (the
/// study's target)...
pub(super) const RESOLVED_ERROR: f64 = studies::TARGET_ERROR;
/// ...where Lai & Nazaroff give at least this deposition velocity (m/s); below it the
/// relative error is not asked of a figure (a few events over a whole run).
pub(super) const RESOLVABLE: f64 = studies::RESOLVED_FROM;

/// Whether a surface's deposition velocity `measured` is unresolved beside the model's `model`
/// (m/s), its run's excursions having given up the share `given_up` of their weight at their
/// longest duration: no deposit event; or, where the model gives at least [`RESOLVABLE`], a
/// relative standard error above [`RESOLVED_ERROR`] ([`too_uncertain`]), or a given-up share
/// above it (what giving them up may have missed, at most that share, could then exceed a
/// resolved figure's error).
pub(super) fn unresolved(measured: &Measured, model: f64, given_up: f64) -> bool {
    measured.events == 0 || too_uncertain(measured, model) || (model >= RESOLVABLE && given_up > RESOLVED_ERROR)
}

/// Whether `measured`, with deposit events, has a relative standard error above
/// [`RESOLVED_ERROR`] where the model `model` (m/s) asks it ([`RESOLVABLE`]).
pub(super) fn too_uncertain(measured: &Measured, model: f64) -> bool {
    model >= RESOLVABLE && measured.events > 0 && !studies::resolved(&measured.estimate(), RESOLVED_ERROR)
}

/// The particles that would bring the `figures` (each a measured deposition velocity beside
/// Lai & Nazaroff's) that are [`too_uncertain`] within [`RESOLVED_ERROR`], from a run of
/// `particles`: as the study itself would run more ([`studies::particles_for`]). `None` where
/// no figure is so (more particles cannot be told how far a figure without a deposit event is
/// from resolved, nor lower a share given up).
pub(super) fn particles_to_resolve(particles: usize, figures: [(&Measured, f64); 3]) -> Option<usize> {
    figures
        .into_iter()
        .filter(|(m, model)| too_uncertain(m, *model))
        .map(|(m, _)| studies::particles_for(&m.estimate(), particles, RESOLVED_ERROR))
        .max()
}

/// `n` rounded up to two significant figures (12618 to 13000): what an estimate of a count
/// can claim.
pub(super) fn two_figures_up(n: usize) -> usize {
    let mut unit = 1;
    while n / unit >= 100 {
        unit *= 10;
    }
    n.div_ceil(unit) * unit
}
