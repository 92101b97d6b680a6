//! Decay after a release: the airborne share of the released particles over time, and the
//! loss rate fitted from it the way chamber and house experiments fit theirs.
//!
//! ## The curve
//! A run releases all its particles at `t = 0` and follows each until it deposits, is
//! exhausted by ventilation or the run ends. The airborne share at `t` is `N(t) / N(0)`, the
//! share of the released particles still in the air at `t` ([`Run::decay_curve`]), at the ends
//! of steps (where ventilation takes its particles: see [`crate::Scene::air_exchange`]), with
//! the binomial standard error `sqrt(f (1 - f) / N(0))`.
//!
//! Every tracked particle counts with weight 1, also with near-wall
//! [`Excursions`](crate::Excursions): the excursions are copies that start from the tracked
//! particles and never change them, and their weighted deposits estimate the *steady*
//! deposition rate that the study's `beta` reports. They do not enter the curve, which is what
//! a particle counter would read in the simulated room: the tracked particles leave the air by
//! their own deposits and by ventilation, as in plain tracking (a test shows the same curve,
//! particle for particle, with excursions and without). Where deposition is rare
//! (accumulation-mode particles) the curve therefore resolves `beta` far less well than the
//! excursions do; that is also the experimenters' lot, whose decay rates are least certain
//! there. And where the Brownian sublayer has not filled within the run, the two differ in
//! what they measure: the curve sees the deposition of the room as released, the excursions
//! the steady rate (see [`crate::excursions`]).
//!
//! ## The fit
//! Thatcher et al. (2002, Atmospheric Environment 36, 1811-1819) released a short burst of
//! particles into a 14.2 m^3 room and measured the size-resolved decay of the concentration
//! with an aerodynamic particle sizer; Howard-Reed, Wallace & Emmerich (2003, Atmospheric
//! Environment) did the same in an occupied townhouse. In a well-mixed room without a source,
//! `dC/dt = -(beta + a) C`, so
//!
//! `ln C(t) = ln C(t0) - (beta + a) (t - t0)`:
//!
//! the slope of `ln C` against `t` by ordinary least squares over the decay after mixing
//! gives the total loss rate `k = beta + a` ([`log_linear_fit`]), and `beta = k - a` with the
//! air-exchange rate `a` measured on its own (by a tracer gas in the experiments; the scene's
//! own here, exact).
//!
//! **Window** ([`Run::decay_fit`]): from the start of the run's averaging window
//! ([`crate::RunSettings::average_from`]; the studies' `transient`, which lets the room mix and the
//! near-wall layers form, the counterpart of the mixing period the experiments leave out, and
//! the same window the study's `beta` averages over) to the last sample time at which at least
//! [`MIN_AIRBORNE`] particles are still in the air (the counterpart of stopping before the
//! concentration nears the background: at 50 particles the count's relative error is 14 % and
//! the bias of `ln N`, about `-1 / (2 N)`, is 1 %). At least 3 sample times, or no fit.
//!
//! **Error**: the delta method over the released particles, which are independent, as for
//! every estimate the tracker reports. The slope is `b = sum_k w_k ln f_k` with
//! `w_k = (t_k - mean t) / sum_j (t_j - mean t)^2`, and `f_k = (1 / N) sum_i A_ik` with
//! `A_ik = 1` while particle `i` is in the air at `t_k`; so to first order
//! `b - E b = (1 / N) sum_i psi_i` with `psi_i = sum_k w_k (A_ik - f_k) / f_k`, and
//! `se(b) = sqrt(sum_i psi_i^2 / (N (N - 1)))`. This carries the correlation between the
//! sample times (the same particles are counted at every one), which a fit weighting each time
//! by its own standard error, as if independent, would miss. A test checks it against the
//! spread of the fitted rate over independent seeds.
//!
//! **Against the study's `beta`** ([`DecayFit::against_loss_rate`]): the run's
//! [`Run::loss_rate`] is a ratio over the same particles, `R = sum X_i / sum E_i`, whose
//! delta-method contributions are `(X_i - R E_i) / sum E` ([`Run::loss_rate_influences`]);
//! the fit's are `-psi_i / N`. A particle that deposits early lowers the curve and adds a
//! deposit to `R`, so the two are positively correlated, and the standard error of their
//! difference is the delta method's over the particles' paired contributions,
//! `delta_error(-psi_i / N - (X_i - R E_i) / sum E)` ([`delta_error`]), not the two errors
//! combined as if independent (in a ventilated room of 10 um particles that overstates it
//! 1.6 times; in a settling box 2.5 times: a test checks the paired error against the spread
//! of the difference over 400 seeds). `z` is the difference over it, left out when either
//! estimate rests on no event or has no error.

use crate::estimation::run::{binomial_error, delta_error, Estimate, Run};
use crate::tracking::{Fate, Record};

/// Intervals of a study's decay curve: 41 sample times from the release to the end of the run.
pub const DECAY_INTERVALS: usize = 40;

/// The fewest particles in the air at a sample time that the fit takes (see the module docs).
pub const MIN_AIRBORNE: usize = 50;

/// The airborne share of the released particles over time (see the module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct DecayCurve {
    /// Sample times from the release, s, at ends of steps.
    pub times: Vec<f64>,
    /// Airborne share `N(t) / N(0)` at each.
    pub airborne: Vec<f64>,
    /// Its binomial standard error, `sqrt(f (1 - f) / N(0))`.
    pub errors: Vec<f64>,
    /// Particles in the air at each.
    pub counts: Vec<usize>,
    /// Particles released, `N(0)`.
    pub released: usize,
    /// The sample times as step numbers: a particle counts at `steps[k]` while it is in the
    /// air at that step's end.
    pub steps: Vec<u64>,
}

/// `ln y = intercept - rate t`, fitted by least squares.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LogLinear {
    /// The decay rate `-d ln y / dt`, 1/s.
    pub rate: f64,
    /// `ln y` at `t = 0`.
    pub intercept: f64,
}

/// The ordinary least-squares line through `(t_k, ln y_k)`: `rate = -sum_k w_k ln y_k` with
/// `w_k = (t_k - mean t) / sum_j (t_j - mean t)^2`, and `intercept = mean ln y + rate mean t`
/// (the decay fit of Thatcher et al. 2002 and of chamber studies; see the module docs).
/// `None` with fewer than two distinct times, a length mismatch, or a `y` that is not finite
/// and positive.
#[must_use]
pub fn log_linear_fit(times: &[f64], values: &[f64]) -> Option<LogLinear> {
    if times.len() != values.len() || values.iter().any(|&y| !(y.is_finite() && y > 0.0)) {
        return None;
    }
    let weights = slope_weights(times)?;
    let logs: Vec<f64> = values.iter().map(|y| y.ln()).collect();
    let slope: f64 = weights.iter().zip(&logs).map(|(w, l)| w * l).sum();
    let n = times.len() as f64;
    let (mean_t, mean_l) = (times.iter().sum::<f64>() / n, logs.iter().sum::<f64>() / n);
    Some(LogLinear { rate: -slope, intercept: mean_l - slope * mean_t })
}

/// The least-squares slope's weights `w_k = (t_k - mean t) / sum_j (t_j - mean t)^2`; `None`
/// with fewer than two distinct times.
fn slope_weights(times: &[f64]) -> Option<Vec<f64>> {
    let n = times.len() as f64;
    let mean = times.iter().sum::<f64>() / n;
    let sxx: f64 = times.iter().map(|t| (t - mean).powi(2)).sum();
    (times.len() >= 2 && sxx.is_finite() && sxx > 0.0).then(|| times.iter().map(|t| (t - mean) / sxx).collect())
}

/// The decay rate fitted to a [`DecayCurve`] (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DecayFit {
    /// The total loss rate `k = beta + a`, 1/s, with the delta method's standard error; its
    /// events are the particles that left the air within the window.
    pub total: Estimate,
    /// `beta = k - a`, 1/s, the same error; its events are the deposits within the window.
    pub beta: Estimate,
    /// `ln (N / N(0))` of the fitted line at `t = 0`.
    pub intercept: f64,
    /// The first and last sample times fitted, s.
    pub window: [f64; 2],
    /// Sample times fitted.
    pub points: usize,
    /// The fitted `beta` against the run's own [`Run::loss_rate`] (a study's `beta`), the
    /// error of the difference paired over the particles.
    pub against_loss_rate: Comparison,
}

/// One estimate against another from the same particles: their difference and its standard
/// error by the delta method over the particles, each particle's contributions to the two
/// taken together. Both rest on the same particles, so they are correlated and the error of
/// the difference is not the two errors combined as if independent (it is 0.63 of that in a
/// ventilated room at 10 um, 0.41 in a ventilated box of settling particles; see the module
/// docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Comparison {
    /// The first estimate less the second.
    pub difference: f64,
    /// Its standard error, paired over the particles.
    pub error: f64,
    /// `difference / error`; `None` when either estimate rests on no event (its value is then
    /// no measurement to compare) or has no error (nothing left the air in the fit's window).
    pub z: Option<f64>,
}

/// The step after which a particle is no longer in the air (`u64::MAX` while airborne at the
/// end): it leaves within the step its record counts last, at its end when exhausted.
fn leaves_after(fate: Fate, steps: u64) -> u64 {
    if fate == Fate::Airborne {
        u64::MAX
    } else {
        steps
    }
}

/// Each particle's influence on the least-squares slope of `ln f_k` against `t_k`,
/// `psi_i = sum_k w_k (A_ik - f_k) / f_k` with `A_ik = 1` while particle `i` (leaving the air
/// after step `leaves[i]`) is in the air at step `steps[k]`, and `f_k` the airborne share
/// there: to first order the slope deviates by `(1 / N) sum_i psi_i` (see the module docs).
#[must_use]
pub fn slope_influences(leaves: &[u64], steps: &[u64], weights: &[f64], shares: &[f64]) -> Vec<f64> {
    leaves
        .iter()
        .map(|&leaves| {
            weights
                .iter()
                .zip(shares)
                .zip(steps)
                .map(|((w, f), &n)| w * (f64::from(u8::from(leaves > n)) - f) / f)
                .sum()
        })
        .collect()
}

impl Run {
    /// The airborne share at `intervals + 1` times evenly spread (to whole steps) from the
    /// release to the end of the run (see the [module docs](crate::decay)).
    #[must_use]
    pub fn decay_curve(&self, intervals: usize) -> DecayCurve {
        let steps = self.steps();
        let intervals = intervals.max(1);
        let sample_steps: Vec<u64> =
            (0..=intervals).map(|k| (k as u64 * steps + intervals as u64 / 2) / intervals as u64).collect();
        let released = self.records.len();
        let counts = self.airborne_at(&sample_steps);
        let n = released.max(1) as f64;
        let airborne: Vec<f64> = counts.iter().map(|&c| c as f64 / n).collect();
        DecayCurve {
            times: sample_steps.iter().map(|&s| s as f64 * self.dt).collect(),
            errors: airborne.iter().map(|&f| binomial_error(f, released)).collect(),
            steps: sample_steps,
            airborne,
            counts,
            released,
        }
    }

    /// The tracked particles in the air at the end of each of `steps`.
    fn airborne_at(&self, steps: &[u64]) -> Vec<usize> {
        let mut counts = vec![0usize; steps.len()];
        for r in &self.records {
            let leaves = leaves_after(r.fate, r.steps);
            for (c, &n) in counts.iter_mut().zip(steps) {
                *c += usize::from(leaves > n);
            }
        }
        counts
    }

    /// The loss rate fitted to `curve` (this run's, from [`Run::decay_curve`]) over the sample
    /// times from the averaging window's start on while at least [`MIN_AIRBORNE`] particles
    /// are in the air, with the delta method's standard error over the particles, and `beta`
    /// with the air-exchange rate `air_exchange` (1/s) taken off (see the
    /// [module docs](crate::decay)); compared with the run's [`Run::loss_rate`]. `None` with
    /// fewer than 3 such times.
    ///
    /// # Panics
    /// If `curve` is not this run's: its release or its counts at the fitted times differ from
    /// what this run's particles give.
    #[must_use]
    pub fn decay_fit(&self, curve: &DecayCurve, air_exchange: f64) -> Option<DecayFit> {
        self.decay_fit_from(curve, air_exchange, self.window[0])
    }

    /// For a release that leaves the air before the averaging window opens (or too soon for
    /// [`Run::decay_fit`]'s three sample times): its decay fitted from the release, `t = 0`,
    /// on a curve of `intervals + 1` sample times from the release to the last step at which
    /// at least [`MIN_AIRBORNE`] particles are in the air (the same rule as the window's fit,
    /// on a time scale the release has), as [`Run::decay_fit`] fits it otherwise. The curve
    /// and its fit; `None` with fewer than [`MIN_AIRBORNE`] particles or 3 distinct sample
    /// steps. Where the particles settle out of a room that does not mix them, `N(t)` falls
    /// more nearly linearly than exponentially: the fitted rate then characterises how fast
    /// the release went, not a first-order loss rate.
    #[must_use]
    pub fn release_decay(&self, intervals: usize, air_exchange: f64) -> Option<(DecayCurve, DecayFit)> {
        let released = self.records.len();
        if released < MIN_AIRBORNE {
            return None;
        }
        let mut leaves: Vec<u64> = self.records.iter().map(|r| leaves_after(r.fate, r.steps)).collect();
        leaves.sort_unstable();
        // At step n, #{leaves > n} are airborne: at least MIN_AIRBORNE up to one step before
        // the MIN_AIRBORNE-th last departure.
        let last = leaves[released - MIN_AIRBORNE].saturating_sub(1).min(self.steps());
        let intervals = intervals.max(1) as u64;
        let mut steps: Vec<u64> = (0..=intervals).map(|k| (k * last + intervals / 2) / intervals).collect();
        steps.dedup();
        if steps.len() < 3 {
            return None;
        }
        let counts = self.airborne_at(&steps);
        let airborne: Vec<f64> = counts.iter().map(|&c| c as f64 / released as f64).collect();
        let curve = DecayCurve {
            times: steps.iter().map(|&s| s as f64 * self.dt).collect(),
            errors: airborne.iter().map(|&f| binomial_error(f, released)).collect(),
            steps,
            airborne,
            counts,
            released,
        };
        let fit = self.decay_fit_from(&curve, air_exchange, 0.0)?;
        Some((curve, fit))
    }

    /// [`Run::decay_fit`] over the sample times from `from` (s) on.
    fn decay_fit_from(&self, curve: &DecayCurve, air_exchange: f64, from: f64) -> Option<DecayFit> {
        assert!(
            curve.released == self.records.len() && curve.steps.iter().all(|&n| n <= self.steps()),
            "the decay curve is not this run's"
        );
        let from = from * (1.0 - 1e-12);
        let mut chosen: Vec<usize> = Vec::new();
        for (k, (&t, &c)) in curve.times.iter().zip(&curve.counts).enumerate() {
            if t >= from {
                if c < MIN_AIRBORNE {
                    break;
                }
                chosen.push(k);
            }
        }
        if chosen.len() < 3 {
            return None;
        }
        let times: Vec<f64> = chosen.iter().map(|&k| curve.times[k]).collect();
        let steps: Vec<u64> = chosen.iter().map(|&k| curve.steps[k]).collect();
        let counts: Vec<usize> = chosen.iter().map(|&k| curve.counts[k]).collect();
        assert_eq!(self.airborne_at(&steps), counts, "the decay curve is not this run's");
        let shares: Vec<f64> = chosen.iter().map(|&k| curve.airborne[k]).collect();
        let fit = log_linear_fit(&times, &shares)?;
        let weights = slope_weights(&times)?;
        let leaves: Vec<u64> = self.records.iter().map(|r| leaves_after(r.fate, r.steps)).collect();
        let n = self.records.len() as f64;
        // The rate is minus the slope: particle i moves it by -psi_i / N.
        let influences: Vec<f64> =
            slope_influences(&leaves, &steps, &weights, &shares).iter().map(|psi| -psi / n).collect();
        let error = delta_error(&influences);
        let (first, last) = (steps[0], steps[steps.len() - 1]);
        let within = |r: &&Record| {
            let leaves = leaves_after(r.fate, r.steps);
            leaves > first && leaves <= last
        };
        let left = self.records.iter().filter(within).count();
        let deposited = self.records.iter().filter(within).filter(|r| matches!(r.fate, Fate::Deposited(_))).count();
        // With no departure (or no deposit) at all, the rate three would give over the
        // window's airborne particle-seconds (the rule of three, as for deposits), else two
        // standard errors above.
        let exposure: f64 =
            times.windows(2).zip(counts.windows(2)).map(|(t, c)| (t[1] - t[0]) * (c[0] + c[1]) as f64 / 2.0).sum();
        let bound = |value: f64, events: usize| if events == 0 { 3.0 / exposure } else { value + 2.0 * error };
        let total = Estimate { value: fit.rate, error, events: left, upper_bound: bound(fit.rate, left) };
        let beta_value = fit.rate - air_exchange;
        let beta = Estimate { value: beta_value, error, events: deposited, upper_bound: bound(beta_value, deposited) };
        Some(DecayFit {
            total,
            beta,
            intercept: fit.intercept,
            window: [times[0], times[times.len() - 1]],
            points: times.len(),
            against_loss_rate: self.against_loss_rate(&beta, &influences),
        })
    }

    /// `estimate` (with its per-particle `influences`) against [`Run::loss_rate`], paired over
    /// the particles.
    fn against_loss_rate(&self, estimate: &Estimate, influences: &[f64]) -> Comparison {
        let study = self.loss_rate();
        let difference = estimate.value - study.value;
        let paired: Option<Vec<f64>> = self
            .loss_rate_influences()
            .map(|theirs| influences.iter().zip(&theirs).map(|(mine, theirs)| mine - theirs).collect());
        let error = paired.map_or(estimate.error, |c| delta_error(&c));
        let resolved = estimate.events > 0 && study.events > 0 && estimate.error > 0.0 && study.error > 0.0;
        Comparison { difference, error, z: (resolved && error > 0.0).then(|| difference / error) }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_exact_exponential_gives_its_rate_exactly() {
        let times = [0.0f64, 60.0, 120.0, 300.0, 600.0];
        let values: Vec<f64> = times.iter().map(|t| 0.8 * (-2.5e-4 * t).exp()).collect();
        let fit = log_linear_fit(&times, &values).unwrap();
        assert!((fit.rate - 2.5e-4).abs() < 1e-15, "{fit:?}");
        assert!((fit.intercept - 0.8f64.ln()).abs() < 1e-12, "{fit:?}");
    }

    /// By hand: `ln y = 0, -1, -3` at `t = 0, 1, 2`; mean t 1, mean ln y -4/3; the slope is
    /// `((-1)(4/3) + 0 + (1)(-5/3)) / 2 = -3/2`, the intercept `-4/3 + 3/2 = 1/6`.
    #[test]
    fn the_fit_is_least_squares_in_ln_y() {
        let e = std::f64::consts::E;
        let fit = log_linear_fit(&[0.0, 1.0, 2.0], &[1.0, 1.0 / e, 1.0 / e.powi(3)]).unwrap();
        assert!((fit.rate - 1.5).abs() < 1e-14, "{fit:?}");
        assert!((fit.intercept - 1.0 / 6.0).abs() < 1e-14, "{fit:?}");
    }

    #[test]
    fn a_fit_needs_two_times_and_positive_values() {
        assert!(log_linear_fit(&[1.0], &[0.5]).is_none());
        assert!(log_linear_fit(&[1.0, 1.0], &[0.5, 0.4]).is_none());
        assert!(log_linear_fit(&[0.0, 1.0], &[0.5, 0.0]).is_none());
        assert!(log_linear_fit(&[0.0, 1.0], &[0.5]).is_none());
    }
}
