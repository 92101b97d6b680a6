//! Run time against statistical error of the studies' variance reduction, beside the plain
//! tracking it replaces.
//!
//! A study's figure is only as good as its error bar, so what a user waits for is the time to
//! a given relative standard error, not a rate of particle-steps. For each case below the same
//! study (same scene, same particle) is run twice in one sitting: once with plain tracking,
//! which counts each deposited particle, and once with the method the default study uses (the
//! near-wall excursions of [`crate::excursions`], with the channel's coarse steps or sweeps
//! where the study takes them). Each run's time to a target error follows from its own error,
//! which falls as `1 / sqrt(n)` with the particles run: `t (error / target)^2`, less the
//! excursions' pilot calibration, a cost fixed per run that is added back unscaled. Machines
//! swing by up to 2x between runs; the ratio of the two times, taken in the same run, far
//! less.
//!
//! Plain tracking of a rare deposition leaves a handful of deposits or none, and then its own
//! error says little. Its deposits are then taken as what they are, a Poisson count: at the
//! reduced run's value each plainly tracked particle deposits with the probability that value
//! implies (one deposit is worth `value / events` of the figure, or a third of the 95 % upper
//! bound with none; [`Estimate::upper_bound`]), so the plain run's relative error would be
//! `1 / sqrt(expected deposits)`. Such a time is marked as projected.
//!
//! The cases are those where the studies' figures are hardest to resolve: the room's `beta`
//! in the accumulation mode (0.1 um) and at 1 um, and the channel's `V+` in the
//! diffusion-impaction regime (`tau+` 0.3 and 3).

use std::time::Instant;

use crate::estimation::run::Estimate;
use crate::model::error::SceneError;
use crate::studies::channel::ChannelStudy;
use crate::studies::room::RoomStudy;

/// Below this many deposit events a run's own standard error is too rough to extrapolate
/// from: a plain run's time is then projected from the reduced run's value, and a reduced
/// run gives none.
pub const MIN_EVENTS: usize = 10;

/// The cases [`compare_methods`] runs.
pub const CASES: usize = 4;

/// One method's run of one case.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MethodRun {
    /// The figure's estimate.
    pub estimate: Estimate,
    /// Particles run.
    pub particles: usize,
    /// Wall-clock time of the run, s.
    pub seconds: f64,
    /// The part of `seconds` fixed per run whatever the particles (the excursions' pilot
    /// calibration), s.
    pub fixed_seconds: f64,
}

impl MethodRun {
    /// The relative standard error, `None` without an event.
    pub fn relative_error(&self) -> Option<f64> {
        (self.estimate.events > 0 && self.estimate.value > 0.0).then(|| self.estimate.error / self.estimate.value)
    }
}

/// The time a run needs for a relative standard error, s.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TimeTo {
    /// Seconds.
    pub seconds: f64,
    /// Whether the error behind it was projected from the other method's value (too few
    /// deposit events of its own; see the module's doc).
    pub projected: bool,
}

/// One case run both ways.
#[derive(Clone, Debug, PartialEq)]
pub struct Case {
    /// What is run, e.g. `room, 0.1 um`.
    pub name: String,
    /// The figure compared, e.g. `beta (1/s)`.
    pub figure: &'static str,
    /// Plain tracking.
    pub plain: MethodRun,
    /// The default study's variance reduction.
    pub reduced: MethodRun,
    /// What the reduced run used, e.g. `excursions+sweeps`.
    pub method: &'static str,
}

impl Case {
    /// The time each of plain tracking and the reduced method needs for the relative standard
    /// error `target`: each run's fixed part plus the rest times `(relative error / target)^2`.
    /// Each error is the run's own from [`MIN_EVENTS`] deposit events on. Below that the plain
    /// run's is projected from the reduced run's value (the module's doc), and the reduced run
    /// gives no time (`None`), nor does a plain run with nothing to project from.
    pub fn time_to(&self, target: f64) -> [Option<TimeTo>; 2] {
        let scale = |run: &MethodRun, error: f64| {
            run.fixed_seconds + (run.seconds - run.fixed_seconds) * (error / target).powi(2)
        };
        let own = |run: &MethodRun| {
            (run.estimate.events >= MIN_EVENTS)
                .then(|| run.relative_error())
                .flatten()
                .map(|e| TimeTo { seconds: scale(run, e), projected: false })
        };
        let reduced = own(&self.reduced);
        let plain = own(&self.plain).or_else(|| {
            let per_event = match self.plain.estimate.events {
                0 => self.plain.estimate.upper_bound / 3.0,
                n => self.plain.estimate.value / n as f64,
            };
            let expected = self.reduced.estimate.value / per_event;
            (expected > 0.0 && expected.is_finite())
                .then(|| TimeTo { seconds: scale(&self.plain, 1.0 / expected.sqrt()), projected: true })
        });
        [plain, reduced]
    }

    /// How many times faster the reduced method reaches the relative error `target` than plain
    /// tracking ([`Case::time_to`]).
    pub fn speedup(&self, target: f64) -> Option<f64> {
        match self.time_to(target) {
            [Some(plain), Some(reduced)] => Some(plain.seconds / reduced.seconds),
            _ => None,
        }
    }
}

/// The cases run both ways, on the current rayon pool; `scale` multiplies the particles each
/// run takes (1: the studies' first particles, 1000 per room size, 4000 plain and 1000 with
/// excursions per `tau+`), with at least 4 per run. `progress` is told after each case.
pub fn compare_methods(scale: f64, mut progress: impl FnMut(usize)) -> Result<Vec<Case>, SceneError> {
    let count = |n: usize| ((n as f64 * scale).round() as usize).max(4);
    let mut cases = Vec::new();
    for microns in [0.1, 1.0] {
        let diameter = microns * 1e-6;
        let room = |excursions: bool| RoomStudy {
            diameters: vec![diameter],
            count: count(1000),
            target_error: None,
            excursions,
            ..RoomStudy::default()
        };
        let beta = |study: RoomStudy| {
            timed(|| {
                let point = study.run(|_| {})?.remove(0);
                Ok((point.beta, point.particles, point.calibration_seconds))
            })
        };
        let (plain, reduced) = (beta(room(false))?, beta(room(true))?);
        let name = format!("room, {microns} um");
        cases.push(Case { name, figure: "beta (1/s)", plain, reduced, method: "excursions" });
        progress(cases.len());
    }
    for tau_plus in [0.3, 3.0] {
        let channel = |excursions_below: f64| ChannelStudy {
            tau_plus: vec![tau_plus],
            count: count(4000),
            excursion_count: count(1000),
            excursions_below,
            target_error: None,
            ..ChannelStudy::default()
        };
        let mut sweeps = false;
        let mut v_plus = |study: ChannelStudy| {
            timed(|| {
                let point = study.run(|_| {})?.remove(0);
                sweeps = point.sweeps;
                Ok((point.v_plus, point.particles, point.calibration_seconds))
            })
        };
        let plain = v_plus(channel(0.0))?;
        let reduced = v_plus(channel(ChannelStudy::default().excursions_below))?;
        // The study's excursions take coarse steps where they do not catch sweeps.
        let method = if sweeps { "excursions+sweeps" } else { "excursions, coarse steps" };
        cases.push(Case { name: format!("channel, tau+ = {tau_plus}"), figure: "V+", plain, reduced, method });
        progress(cases.len());
    }
    Ok(cases)
}

/// `run` (the figure, the particles run and the run's fixed part in seconds) timed by the
/// wall clock.
fn timed(run: impl FnOnce() -> Result<(Estimate, usize, f64), SceneError>) -> Result<MethodRun, SceneError> {
    let start = Instant::now();
    let (estimate, particles, fixed_seconds) = run()?;
    Ok(MethodRun { estimate, particles, seconds: start.elapsed().as_secs_f64(), fixed_seconds })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn estimate(value: f64, error: f64, events: usize, upper_bound: f64) -> Estimate {
        Estimate { value, error, events, upper_bound }
    }

    fn case(plain: Estimate, reduced: Estimate) -> Case {
        Case {
            name: "by hand".into(),
            figure: "V+",
            plain: MethodRun { estimate: plain, particles: 4000, seconds: 1.0, fixed_seconds: 0.0 },
            reduced: MethodRun { estimate: reduced, particles: 1000, seconds: 10.0, fixed_seconds: 0.0 },
            method: "excursions",
        }
    }

    #[test]
    fn times_to_an_error_scale_each_run_by_its_squared_error() {
        // Plain: 10 % in 1 s needs 4 s for 5 %. Reduced: 2.5 % in 10 s needs 2.5 s. With 100
        // plain events neither is projected.
        let c = case(estimate(1e-4, 1e-5, 100, 1.2e-4), estimate(1e-4, 2.5e-6, 5000, 1.05e-4));
        let [plain, reduced] = c.time_to(0.05);
        let (plain, reduced) = (plain.unwrap(), reduced.unwrap());
        assert!(!plain.projected && (plain.seconds - 4.0).abs() < 1e-9, "{plain:?}");
        assert!(!reduced.projected && (reduced.seconds - 2.5).abs() < 1e-9, "{reduced:?}");
        assert!((c.speedup(0.05).unwrap() - 1.6).abs() < 1e-9);
    }

    #[test]
    fn a_fixed_cost_is_not_scaled_with_the_particles() {
        // The reduced run's 10 s include a 2 s pilot: 2 + 8 (2.5 / 5)^2 = 4 s for 5 %.
        let mut c = case(estimate(1e-4, 1e-5, 100, 1.2e-4), estimate(1e-4, 2.5e-6, 5000, 1.05e-4));
        c.reduced.fixed_seconds = 2.0;
        let reduced = c.time_to(0.05)[1].unwrap();
        assert!((reduced.seconds - 4.0).abs() < 1e-9, "{reduced:?}");
    }

    #[test]
    fn runs_of_fewer_than_ten_deposits_are_not_extrapolated_from_their_own_error() {
        // Ten plain deposits, 2e-5 +- 6.3e-6 (31.6 %): its own error, 1 s (0.316 / 0.05)^2 = 40 s.
        let reduced = estimate(2e-5, 1e-6, 800, 2.2e-5);
        let plain = c_plain(estimate(2e-5, 2e-5 / 10f64.sqrt(), 10, 3.3e-5), reduced);
        assert!(!plain.projected && (plain.seconds - 40.0).abs() < 1e-9, "{plain:?}");
        // Nine: projected at the reduced value, one deposit worth 2e-5 / 9, so 9 expected, 44.4 s.
        let plain = c_plain(estimate(2e-5, 1e-5, 9, 4e-5), reduced);
        assert!(plain.projected && (plain.seconds - 400.0 / 9.0).abs() < 1e-9, "{plain:?}");
        // A reduced run of nine deposits gives no time, so no speed-up.
        let c = case(estimate(2e-5, 2e-5 / 10f64.sqrt(), 10, 3.3e-5), estimate(2e-5, 6e-6, 9, 3.2e-5));
        assert_eq!(c.time_to(0.05)[1], None);
        assert_eq!(c.speedup(0.05), None);
    }

    fn c_plain(plain: Estimate, reduced: Estimate) -> TimeTo {
        case(plain, reduced).time_to(0.05)[0].unwrap()
    }

    #[test]
    fn a_plain_run_without_deposits_is_projected_from_the_reduced_value() {
        // No plain deposit: one would be worth a third of the 3e-6 bound, 1e-6. At the reduced
        // run's 5e-6 the plain run would expect 5 deposits, a relative error of 1/sqrt(5), so
        // 1 s * (0.4472 / 0.05)^2 = 80 s for 5 %. The reduced run: 5 % in 10 s, 10 s.
        let c = case(estimate(0.0, 0.0, 0, 3e-6), estimate(5e-6, 2.5e-7, 3000, 5.5e-6));
        let [plain, reduced] = c.time_to(0.05);
        let plain = plain.unwrap();
        assert!(plain.projected && (plain.seconds - 80.0).abs() < 1e-9, "{plain:?}");
        let reduced = reduced.unwrap();
        assert!(!reduced.projected && (reduced.seconds - 10.0).abs() < 1e-9, "{reduced:?}");
        assert!((c.speedup(0.05).unwrap() - 8.0).abs() < 1e-9);
        // With two plain deposits (each worth 1.5e-6 of a 3e-6 value) the projection uses the
        // reduced value too: 5e-6 / 1.5e-6 = 3.33 expected, 1 s * 400 / 3.33 = 120 s.
        let c = case(estimate(3e-6, 2.1e-6, 2, 7.2e-6), estimate(5e-6, 2.5e-7, 3000, 5.5e-6));
        let plain = c.time_to(0.05)[0].unwrap();
        assert!(plain.projected && (plain.seconds - 120.0).abs() < 1e-9, "{plain:?}");
    }

    #[test]
    fn a_reduced_run_without_deposits_gives_no_time() {
        let c = case(estimate(0.0, 0.0, 0, 3e-6), estimate(0.0, 0.0, 0, 1e-7));
        assert_eq!(c.time_to(0.05), [None, None]);
        assert_eq!(c.speedup(0.05), None);
    }

    #[test]
    fn every_case_runs_both_ways() {
        // A handful of particles per run: what is checked is the plumbing (each case's two
        // runs are the study's figure for the same particle, plainly tracked and with
        // excursions, timed), not the figures. At this scale the room runs 4 particles either
        // way, the channel 16 plainly and 4 with excursions; only excursions have a pilot.
        let cases = compare_methods(0.004, |_| {}).unwrap();
        assert_eq!(cases.len(), CASES);
        for c in &cases {
            assert!(c.plain.seconds > 0.0 && c.reduced.seconds > c.reduced.fixed_seconds, "{c:?}");
            assert!(c.plain.fixed_seconds == 0.0 && c.reduced.fixed_seconds > 0.0, "{c:?}");
        }
        let particles: Vec<_> = cases.iter().map(|c| (c.plain.particles, c.reduced.particles)).collect();
        assert_eq!(particles, [(4, 4), (4, 4), (16, 4), (16, 4)]);
        assert_eq!(cases[2].method, "excursions, coarse steps");
        assert_eq!(cases[3].method, "excursions+sweeps");
    }
}
