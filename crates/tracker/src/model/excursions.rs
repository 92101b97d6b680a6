//! Near-wall excursions: a variance-reduction method for deposition rates too small for plain
//! tracking to resolve, with an estimator that is unbiased for the steady state.
//!
//! ## Why
//! In a room, a 0.1 um particle deposits at about 1e-6 m/s: a plain run of 2000 particles over
//! half an hour counted 3 to 7 deposits per surface, and none on the ceiling. What decides
//! deposition happens within millimetres of the walls, where almost none of the tracked
//! particles are; and the Brownian sublayer that limits it fills over about its thickness
//! squared over the diffusivity, which for a 1 um particle in a room is estimated at about an
//! hour, so a plain run does not even reach the steady state that deposition correlations
//! describe.
//!
//! ## How
//! The run tracks its particles plainly: they give the airborne exposure and the steady
//! stream of *inward crossings* of a near-wall layer of thickness [`Excursions::layer`] (the
//! distance from a particle's surface to the nearest wall). Each crossing within the averaging
//! window starts [`Excursions::sampling`] *excursions* on average (times the class of the
//! surface crossed's [`Excursions::class_sampling`]): copies of the particle with fresh random
//! streams, each followed until it deposits, leaves the layer again, or outlives
//! [`Excursions::max_duration`]. Their deposits, weighted one over that sampling, are what the run
//! counts; the plain particle's own deposits are not (it goes on, or ends, as plain tracking
//! would have it).
//!
//! Each excursion's outcome is an unbiased estimate of the probability that a particle
//! entering the layer in that state deposits before it leaves, so the counted deposits per
//! unit time estimate, without bias, the steady deposition rate `(entry rate) x (deposition
//! probability per entry)` (conditional Monte Carlo; the entry states are the plain run's own,
//! whatever the concentration profile near the wall). A test compares it with plain tracking
//! where plain tracking reaches the steady state and resolves it. Giving an excursion up at
//! its longest duration is the one approximation; [`Run::truncated_share`](crate::Run::truncated_share)
//! bounds what it may miss.
//!
//! Within the layer, excursions are split toward the wall ([`Splitting`]) by weight windows.
//! A branch's level is set by the gap it would have left after flying freely towards the
//! nearest wall (the distance less the stop distance of its velocity towards it), and each
//! level has a target weight. A branch that goes deeper *splits* into copies of the deeper
//! level's weight that go on independently; one that comes out two levels plays *Russian
//! roulette*, surviving with probability `w / W` at weight `W` (a single level's way out is
//! let pass, so that a branch hovering at a level's edge is not split and rouletted over and
//! over). Both keep the expected weight, so every weighted sum keeps its expectation (Kahn &
//! Harris 1951; the weight windows of Monte Carlo neutron transport, Booth & Hendricks 1984):
//! the levels and factors decide only how far the variance falls per unit of work.
//!
//! ## Sweeps caught early (channels)
//! Where inertia lets a particle coast through the viscous sublayer (`tau+` of a few), what
//! deposits it is a strong sweep: in a run at `tau+ = 3` the dozen entries into the layer with
//! the fluid's wall-ward `zeta` above 4, out of some ten thousand, carried three quarters of
//! the deposited weight, and no splitting within the layer can make the plain run meet more
//! of them. With [`Excursions::sweeps`] the excursions' region also takes in, anywhere in a
//! channel, a particle whose fluid carries it towards the nearer wall with `zeta` above
//! [`Sweeps::enter`], until `zeta` falls below [`Sweeps::leave`]; such an entry starts
//! [`Sweeps::sampling`] excursions, so each strong sweep's outcomes are sampled many times
//! over. The estimator is the same conditional Monte Carlo for any such region: every
//! deposit is preceded by an entry into it, and an excursion is followed until it leaves (the
//! layer and the sweep both behind it) or deposits. The two thresholds keep a particle whose
//! `zeta` wanders about one of them from starting excursions step after step.
//!
//! ## Coarse steps
//! Below `tau+ = 3` an excursion's branches spend most of their steps hovering within a wall
//! unit or so of the wall, for hundreds to thousands of wall time units, where the turbulence
//! has all but vanished and the particle moves little per step. With
//! [`Excursions::coarse_factor`] above 1 they take steps that many times the scene's there,
//! with the midpoint scheme ([`Scheme::Midpoint`](crate::Scheme::Midpoint), second order in
//! `dt |d sigma/dy|`, whatever the scene's own scheme), wherever a coarse step can neither
//! reach a wall nor step over the turbulence's gradients:
//!
//! - along every walled axis, `dt_coarse |d sigma/dy|` is at most
//!   [`MAX_STEP_GRADIENT`](crate::estimation::run::MAX_STEP_GRADIENT), what the scene's own step must meet;
//! - the farthest the particle can move towards a wall in the step, `tau |v| + (tau +
//!   dt_coarse) |u_f|` (its relaxation towards the fluid velocity `u_f = sigma zeta` it sees,
//!   held over the step, plus settling) and five standard deviations of its Brownian
//!   displacement, is less than its free-flight gap to the nearest wall.
//!
//! Elsewhere, and so for every contact with a wall, the branch takes the scene's step. A coarse
//! step counts as `coarse_factor` steps towards [`Excursions::max_duration`]. Coarse steps are
//! an approximation of the same dynamics, not a change of the estimator: what they cost in
//! accuracy is the step's discretisation error, measured against the midpoint scheme at the
//! scene's step (the channel study's figures, for
//! [`CHANNEL_COARSE_FACTOR`](crate::studies::channel::CHANNEL_COARSE_FACTOR), are in
//! docs/performance-log.md); the first-order scheme in coarse steps is far off and is not
//! offered. Scenes with furnishings or openings take the scene's step throughout.
//!
//! ## Sampling by class of crossing
//! [`Excursions::class_sampling`] scales the excursions per crossing by the class of the
//! surface nearest where the crossing ends ([`crossing_class`]: floor, ceiling, walls,
//! furnishings); each excursion weighs one over its own sampling, so the estimate is the
//! same in expectation, and only the spread of each class's deposits changes. A room study
//! lowers it where its figures have room to spare ([`crate::allocation`]). Each particle's
//! [`ParticleTally`](crate::ParticleTally) counts its excursions' steps and deposits by
//! class of crossing, which is what the study decides from.
//!
//! ## Estimates and their errors
//! A deposition velocity is a ratio of deposits (an injected particle's excursions' weighted
//! deposits) to exposure (its airborne time in the window), summed over the injected
//! particles, with the delta method's standard error over them: see [`crate::run`](mod@crate::run).

use crate::model::error::SceneError;

/// Near-wall excursions (see the module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct Excursions {
    /// Thickness of the near-wall layer whose inward crossings start excursions: the distance
    /// from a particle's surface to the nearest wall, m.
    pub layer: f64,
    /// Excursions started per inward crossing within the averaging window, on average: below
    /// 1 a probability, above 1 several independent excursions from the same crossing (its
    /// whole part, and one more with the probability of its fraction). Each weighs
    /// `1 / sampling` (times the crossing's [`Excursions::class_sampling`] multiplier, in
    /// both).
    pub sampling: f64,
    /// [`Excursions::sampling`]'s multiplier for a crossing into the layer of each class of
    /// surface ([`crossing_class`]: the floor, the ceiling, the walls, the furnishings' faces),
    /// the surface nearest where the crossing ends: a study runs fewer excursions where its
    /// figures are resolved with room to spare (see
    /// [`RoomStudy`](crate::studies::room::RoomStudy)). Each excursion weighs one over its own
    /// sampling, so any multipliers give the same expected deposits. 1 for every class in
    /// [`Excursions::in_wall_units`].
    pub class_sampling: [f64; CROSSING_CLASSES],
    /// Longest an excursion is followed, s; beyond it, it counts as having left the layer.
    pub max_duration: f64,
    /// Splitting toward the wall within the layer.
    pub splitting: Splitting,
    /// Strong sweeps caught before they reach the layer (channels only); `None`: the layer
    /// alone.
    pub sweeps: Option<Sweeps>,
    /// The excursions' branches step this many times the scene's step where that is safe
    /// (see [Coarse steps](#coarse-steps)); 1: always the scene's step.
    pub coarse_factor: u32,
}

/// The classes of surface whose crossings [`Excursions::class_sampling`] samples apart.
pub const CROSSING_CLASSES: usize = 4;

/// The class of surface `id` ([`Excursions::class_sampling`]): 0 for the floor (a channel's
/// lower wall), 1 for the ceiling (its upper wall), 2 for the room's four walls, 3 for a
/// furnishing's face (see [`crate::geometry`] for the ids).
#[must_use]
pub fn crossing_class(id: usize) -> usize {
    match id {
        0 | 1 => id,
        2..=5 => 2,
        _ => FURNISHINGS_CLASS,
    }
}

/// The [`crossing_class`] of every furnishing's face.
pub const FURNISHINGS_CLASS: usize = 3;

/// Strong sweeps caught on their way to the layer, in a channel (see the module docs): a
/// particle whose fluid's normalised wall-normal fluctuation `zeta` carries it towards the
/// nearer wall faster than [`Sweeps::enter`] counts as inside the excursions' region, as one
/// within the layer does, until that `zeta` falls below [`Sweeps::leave`].
#[derive(Clone, Debug, PartialEq)]
pub struct Sweeps {
    /// Wall-ward `zeta` from which a particle is inside.
    pub enter: f64,
    /// Wall-ward `zeta` below which it is outside again (if outside the layer too).
    pub leave: f64,
    /// Excursions started per entry by a sweep, on average (as [`Excursions::sampling`] per
    /// crossing of the layer); each weighs `1 / sampling`.
    pub sampling: f64,
}

impl Excursions {
    /// Excursions in wall units of a flow with friction velocity `u*` (m/s) and kinematic
    /// viscosity `nu` (m^2/s), as the studies use them: a layer of 30 wall units (the buffer
    /// layer, where the near-wall turbulence profiles change fastest), levels halving from 15
    /// wall units down to `inner` wall units, each splitting by 2 until calibrated
    /// ([`Excursions::calibrated`]), `sampling` excursions per crossing, given up after
    /// `max_duration` wall time units (`nu / u*^2`).
    #[must_use]
    pub fn in_wall_units(friction_velocity: f64, nu: f64, inner: f64, sampling: f64, max_duration: f64) -> Self {
        let unit = nu / friction_velocity;
        Self {
            layer: 30.0 * unit,
            sampling,
            class_sampling: [1.0; CROSSING_CLASSES],
            max_duration: max_duration * unit / friction_velocity,
            splitting: Splitting::geometric(15.0 * unit, inner * unit, 2.0, 2),
            sweeps: None,
            coarse_factor: 1,
        }
    }

    /// Checks every field; the error names the first offending one.
    pub fn validate(&self) -> Result<(), SceneError> {
        if !(self.layer.is_finite() && self.layer > 0.0) {
            return Err(SceneError::new("excursions.layer", self.layer, "must be finite and positive"));
        }
        if !(self.sampling > 0.0 && self.sampling <= 1e6) {
            return Err(SceneError::new("excursions.sampling", self.sampling, "must be in (0, 1e6]"));
        }
        for &m in &self.class_sampling {
            if !(m > 0.0 && self.sampling * m <= 1e6) {
                return Err(SceneError::new(
                    "excursions.class_sampling",
                    m,
                    "must be positive, with sampling times it at most 1e6",
                ));
            }
        }
        if !(self.max_duration.is_finite() && self.max_duration > 0.0) {
            return Err(SceneError::new("excursions.max_duration", self.max_duration, "must be finite and positive"));
        }
        if self.splitting.levels.first().is_some_and(|&d| d > self.layer) {
            return Err(SceneError::new("splitting.levels", self.splitting.levels[0], "must lie within the layer"));
        }
        if let Some(s) = &self.sweeps {
            if !(s.enter.is_finite() && s.enter > 0.0) {
                return Err(SceneError::new("sweeps.enter", s.enter, "must be finite and positive"));
            }
            if !(s.leave.is_finite() && s.leave < s.enter) {
                return Err(SceneError::new("sweeps.leave", s.leave, "must be finite and below sweeps.enter"));
            }
            if !(s.sampling > 0.0 && s.sampling <= 1e6) {
                return Err(SceneError::new("sweeps.sampling", s.sampling, "must be in (0, 1e6]"));
            }
        }
        if !(1..=MAX_COARSE_FACTOR).contains(&self.coarse_factor) {
            let factor = f64::from(self.coarse_factor);
            return Err(SceneError::new("excursions.coarse_factor", factor, "must be from 1 to 64"));
        }
        self.splitting.validate()
    }
}

/// The largest [`Excursions::coarse_factor`].
pub const MAX_COARSE_FACTOR: u32 = 64;

/// Splitting toward the walls within the near-wall layer (see the module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct Splitting {
    /// Distances from the particle's surface to the nearest wall at which the levels start, m,
    /// strictly decreasing: level `k` (from 1) is within `levels[k - 1]`.
    pub levels: Vec<f64>,
    /// Copies a branch splits into on entering each level (at least 1), one per level.
    pub factors: Vec<u32>,
}

/// Most levels a splitting may have.
pub const MAX_LEVELS: usize = 32;

/// The deepest level's weight may not fall below this (a bound on the number of branches an
/// excursion can have).
const SMALLEST_WEIGHT: f64 = 1e-12;

impl Splitting {
    /// Levels at `outer`, `outer / ratio`, `outer / ratio^2`, ... down to `inner` (m), each
    /// splitting by `factor`.
    #[must_use]
    pub fn geometric(outer: f64, inner: f64, ratio: f64, factor: u32) -> Self {
        let mut levels = Vec::new();
        let mut d = outer;
        while d >= inner * (1.0 - 1e-9) && levels.len() < MAX_LEVELS && ratio > 1.0 {
            levels.push(d);
            d /= ratio;
        }
        let factors = vec![factor; levels.len()];
        Self { levels, factors }
    }

    /// Checks the levels and the factors; the error names the field.
    pub fn validate(&self) -> Result<(), SceneError> {
        if self.levels.len() > MAX_LEVELS {
            return Err(SceneError::new("splitting.levels", self.levels.len() as f64, "must be at most 32"));
        }
        if self.factors.len() != self.levels.len() {
            return Err(SceneError::new(
                "splitting.factors",
                self.factors.len() as f64,
                "must give one factor per level",
            ));
        }
        if let Some(&f) = self.factors.iter().find(|&&f| f < 1) {
            return Err(SceneError::new("splitting.factors", f64::from(f), "must be at least 1"));
        }
        for (i, &d) in self.levels.iter().enumerate() {
            if !(d.is_finite() && d > 0.0) {
                return Err(SceneError::new("splitting.levels", d, "must be finite and positive"));
            }
            if i > 0 && d >= self.levels[i - 1] {
                return Err(SceneError::new("splitting.levels", d, "must decrease strictly"));
            }
        }
        if self.weight(self.levels.len()) < SMALLEST_WEIGHT {
            return Err(SceneError::new(
                "splitting.factors",
                self.weight(self.levels.len()),
                "multiply to too much: the deepest weight would fall below 1e-12",
            ));
        }
        Ok(())
    }

    /// The level of a particle whose surface is `distance` (m) from the nearest wall.
    #[inline]
    #[must_use]
    pub fn level(&self, distance: f64) -> usize {
        // Few levels, most particles at level 0: a linear scan that usually stops at once.
        self.levels.iter().take_while(|&&d| distance < d).count()
    }

    /// The target weight of `level`: one over the product of the factors of the levels up to
    /// it.
    #[inline]
    #[must_use]
    pub fn weight(&self, level: usize) -> f64 {
        1.0 / self.factors[..level].iter().map(|&f| f64::from(f)).product::<f64>()
    }

    /// Factors that keep the expected number of branches about the same at every level, from
    /// a pilot run's weighted arrivals per level (`arrivals[k]` into level `k + 1`, from
    /// [`ParticleTally::arrivals`](crate::ParticleTally::arrivals)) and its number of
    /// excursions: `f_k = A_{k-1} / A_k`, rounded and clamped to `1..=max`. A level the pilot
    /// reached fewer than `20` times takes the factor of the level above it.
    #[must_use]
    pub fn calibrated(&self, excursions: f64, arrivals: &[f64], branches: &[u64], max: u32) -> Self {
        let mut factors = Vec::with_capacity(self.levels.len());
        let mut above = excursions;
        let mut last = 2;
        for k in 0..self.levels.len() {
            let (a, n) = (arrivals.get(k).copied().unwrap_or(0.0), branches.get(k).copied().unwrap_or(0));
            let f = if n >= 20 && a > 0.0 { (above / a).round().clamp(1.0, f64::from(max)) as u32 } else { last };
            factors.push(f);
            last = f;
            above = a;
        }
        Self { levels: self.levels.clone(), factors }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::scene::{Injection, Scene};
    use crate::model::settings::RunSettings;

    #[test]
    fn levels_count_the_distances_passed() {
        let s = Splitting { levels: vec![0.1, 0.01, 0.001], factors: vec![3; 3] };
        assert_eq!(s.level(1.0), 0);
        assert_eq!(s.level(0.1), 0);
        assert_eq!(s.level(0.05), 1);
        assert_eq!(s.level(0.005), 2);
        assert_eq!(s.level(0.0), 3);
        assert_eq!(s.weight(2), 1.0 / 9.0);
        assert!(s.validate().is_ok());
    }

    #[test]
    fn calibrated_factors_follow_the_pilot_arrivals() {
        let s = Splitting::geometric(1.0, 0.1, 2.0, 2);
        // 1000 excursions; arrivals at each level (weighted) fall by 4, 2, then 10; the last
        // level saw too few branches and takes the factor above it.
        let c = s.calibrated(1000.0, &[250.0, 125.0, 12.5, 1.0], &[250, 250, 100, 5], 8);
        assert_eq!(c.factors, vec![4, 2, 8, 8]);
        assert_eq!(c.levels, s.levels);
    }

    #[test]
    fn geometric_levels_reach_the_inner_distance() {
        let s = Splitting::geometric(0.1, 1e-4, 10.0, 2);
        assert_eq!(s.levels.len(), 4);
        assert!((s.levels[3] - 1e-4).abs() < 1e-15);
    }

    #[test]
    fn bad_sweeps_name_the_field_and_need_a_channel() {
        let with = |enter, leave, sampling| Excursions {
            sweeps: Some(Sweeps { enter, leave, sampling }),
            ..Excursions::in_wall_units(0.3, 1.5e-5, 0.2, 1.0, 1e4)
        };
        assert!(with(3.0, 2.0, 10.0).validate().is_ok());
        assert_eq!(with(f64::NAN, 2.0, 10.0).validate().unwrap_err().field, "sweeps.enter");
        assert_eq!(with(3.0, 3.0, 10.0).validate().unwrap_err().field, "sweeps.leave");
        assert_eq!(with(3.0, 2.0, 0.0).validate().unwrap_err().field, "sweeps.sampling");
        let room = Scene::new(crate::Geometry::Room { size: [4.0, 3.0, 2.5] });
        let settings = RunSettings { excursions: Some(with(3.0, 2.0, 10.0)), ..RunSettings::new(0.1, 60.0) };
        let injection = Injection::new(1, crate::SizeDistribution::Monodisperse { diameter: 1e-6 }, 1000.0);
        assert!(room.validate(&injection).is_ok());
        assert_eq!(settings.validate(&room).unwrap_err().field, "sweeps");
        let channel = Scene::new(crate::Geometry::Channel { length: 0.1, width: 0.1, height: 0.01 });
        let settings = RunSettings { excursions: Some(with(3.0, 2.0, 10.0)), ..RunSettings::new(1e-4, 1.0) };
        assert!(channel.validate(&injection).is_ok() && settings.validate(&channel).is_ok());
    }

    #[test]
    fn bad_splitting_names_the_field() {
        let bad = |levels: Vec<f64>, factor| {
            let factors = vec![factor; levels.len()];
            Splitting { levels, factors }.validate().unwrap_err().field
        };
        assert_eq!(bad(vec![0.1], 0), "splitting.factors");
        assert_eq!(bad(vec![0.1, 0.2], 2), "splitting.levels");
        assert_eq!(bad(vec![0.1, f64::NAN], 2), "splitting.levels");
        assert_eq!(bad((0..50).map(|k| 0.5f64.powi(k)).collect(), 2), "splitting.levels");
        assert_eq!(bad((0..30).map(|k| 0.5f64.powi(k)).collect(), 4), "splitting.factors");
        let s = Splitting { levels: vec![0.1], factors: vec![] };
        assert_eq!(s.validate().unwrap_err().field, "splitting.factors");
    }
}
