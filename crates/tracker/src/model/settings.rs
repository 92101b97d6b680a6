//! How a run is estimated, beside what is simulated: the time step and the integrator, the
//! simulated time and the averaging window, the seed of the random streams, and the near-wall
//! excursions that stand in for plain tracking where deposition is rare. A [`Scene`] says
//! what is simulated; the same scene can be run with different settings (a pilot run of
//! another seed, a coarser step, a longer window) without being copied or changed.
//!
//! Checked once, in [`RunSettings::validate`], against the scene they run.

use crate::model::error::SceneError;
use crate::model::excursions::Excursions;
use crate::model::geometry::Geometry;
use crate::model::scene::Scene;

/// How a step is integrated.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Scheme {
    /// The drag relaxation solved exactly over the step for the fluid velocity seen at its start
    /// (and the Brownian increments sampled exactly): stable for any `dt / tau`. The default.
    #[default]
    Exponential,
    /// Explicit (forward) Euler, for comparison: first order, unstable for `dt > 2 tau`.
    Euler,
    /// The exponential scheme with the turbulence taken half a step on: the fluid velocity
    /// seen over the step, and the step of its normalised fluctuation (`sigma`, `T_L` and the
    /// well-mixed drift), are read where the particle is half a step on, flying towards the
    /// fluid velocity seen at the start (a predictor), not where it starts. The default takes
    /// them at the start, which is first order in `dt` times the turbulence's gradients; this
    /// is second order there, so tracers stay well mixed and a room's `beta` holds at steps
    /// several times longer (the room study uses it; figures in docs/validation.md, "The
    /// time step"). In a room's turbulence (no mean profile, no correlated components) the
    /// predictor takes the fluctuation's scale `g sigma` where the last step read it rather
    /// than reading the profiles at the start: the predicted point moves by `O(dt^2)` (with
    /// Brownian motion, also by `O(dt^(3/2))` of zero mean), which keeps the step second
    /// order, and each step reads the turbulence's profiles once instead of twice. With a
    /// mean profile (a channel's) each step reads them twice. Particles go one at a time (the
    /// tracker's lanes do not have it).
    Midpoint,
}

/// How a run of a [`Scene`] is estimated: time stepping, duration, averaging window, seed and
/// near-wall excursions.
#[derive(Clone, Debug, PartialEq)]
pub struct RunSettings {
    /// The integrator.
    pub scheme: Scheme,
    /// Time step, s.
    pub dt: f64,
    /// Simulated time, s (rounded up to whole steps).
    pub duration: f64,
    /// Seed of the per-particle random streams.
    pub seed: u64,
    /// Start of the averaging window of the run's deposition velocities and loss rates, s (the
    /// window ends with the run): what comes before lets the near-wall layers form.
    pub average_from: f64,
    /// Near-wall excursions, for deposition rates too small to resolve by plain tracking;
    /// `None` (the default) counts the tracked particles' own deposits.
    pub excursions: Option<Excursions>,
}

impl RunSettings {
    /// Steps of `dt` (s) for `duration` (s): the exponential scheme, seed 1, averaging from the
    /// start, no excursions.
    #[must_use]
    pub fn new(dt: f64, duration: f64) -> Self {
        Self { scheme: Scheme::Exponential, dt, duration, seed: 1, average_from: 0.0, excursions: None }
    }

    /// Number of steps the run takes.
    #[must_use]
    pub fn steps(&self) -> usize {
        ((self.duration / self.dt) - 1e-9).ceil().max(0.0) as usize
    }

    /// Checks the settings, and that `scene` can be run with them; the error names the first
    /// offending field as a scene file names it.
    pub fn validate(&self, scene: &Scene) -> Result<(), SceneError> {
        if !(self.dt.is_finite() && self.dt > 0.0) {
            return Err(SceneError::new("dt", self.dt, "must be finite and positive"));
        }
        if !(self.duration.is_finite() && self.duration >= 0.0) {
            return Err(SceneError::new("duration", self.duration, "must be finite and not negative"));
        }
        if !(self.average_from.is_finite()
            && self.average_from >= 0.0
            && self.average_from < self.duration.max(f64::MIN_POSITIVE))
        {
            return Err(SceneError::new(
                "average_from",
                self.average_from,
                "must be finite, not negative and before the end of the run",
            ));
        }
        if let Some(excursions) = &self.excursions {
            excursions.validate()?;
            if excursions.sweeps.is_some() && !matches!(scene.geometry, Geometry::Channel { .. }) {
                return Err(SceneError::new("sweeps", 0.0, "are for a channel only"));
            }
            if scene.wall_function.is_some() {
                return Err(SceneError::new(
                    "wall_function",
                    1.0,
                    "counts deposits itself: near-wall excursions must be off",
                ));
            }
        }
        Ok(())
    }
}
