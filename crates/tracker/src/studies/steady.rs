//! The steady state under a continuous source, from a release.
//!
//! Particles do not interact, so a source emitting `S` particles a second, each placed and
//! started as a release's particles are (uniformly over the room: an indoor source, or
//! outdoor air infiltrating through the envelope and mixed in), holds at steady state the
//! superposition of releases of every age: the airborne number is `S E[T]`, with `T` the time
//! an emitted particle stays in the air, and a surface receives `S P(s)`, with `P(s)` the
//! share of the emitted particles that end there (Little's law). Both are read off one
//! release followed from `t = 0`, whatever the room's mixing: a size that settles before a
//! release study's averaging window opens gets its steady answer all the same.
//!
//! The steady deposition velocity onto a surface of area `A` is then the flux over the mean
//! concentration, `v_d = S P(s) / A / (S E[T] / V) = P(s) V / (A E[T])`, and with outdoor air
//! entering at `Q = P a + ...` particles per second per outdoor concentration (see
//! [`Filtration::entering`](crate::studies::filtration::Filtration::entering)) the indoor/outdoor
//! ratio is `Q E[T]`.
//!
//! A particle still airborne at the run's end has its future taken from the room's late
//! rates (the study's window estimates: loss rate `beta` and air exchange `a`): it stays
//! `1 / (beta + a)` longer on average and ends on a surface `s` with probability
//! `lambda_s / (beta + a)`, `lambda_s = v_d,s A_s / V`; that part is reported
//! ([`SteadyState::beyond_run`]), the rest is the particles' own history. The standard errors
//! are the delta method's over the independent particles.

use crate::estimation::run::{Estimate, Run};
use crate::tracking::Fate;

/// The steady state under a continuous source of one size (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SteadyState {
    /// Mean time an emitted particle stays in the air, `E[T]`, s: the steady airborne number
    /// per particle emitted a second.
    pub residence: Estimate,
    /// The share of the source that ends on the floor, the ceiling, the walls, the
    /// furnishings, and exhausted.
    pub fates: [f64; 5],
    /// The steady deposition velocity onto the floor, ceiling and walls, m/s.
    pub deposition_velocity: [Estimate; 3],
    /// The share of `residence` that comes from beyond the run's end (the late rates').
    pub beyond_run: f64,
}

/// Which of the five fates of [`SteadyState::fates`] surface `s` is: 0-2 by orientation for
/// the room's walls (`surfaces_facing` gives them), 3 for a furnishing's face.
fn fate_of(run: &Run, s: usize) -> usize {
    let w = &run.walls[s];
    if w.furnishing.is_some() {
        return 3;
    }
    match w.orientation() {
        crate::model::geometry::Orientation::Floor => 0,
        crate::model::geometry::Orientation::Ceiling => 1,
        crate::model::geometry::Orientation::Wall => 2,
    }
}

impl SteadyState {
    /// From `run`, a release followed from `t = 0` for `duration` (s), with its late rates:
    /// `lambda` the rate (1/s) at which an airborne particle ends in each of the five fates
    /// (deposition per orientation and on furnishings, exhaust). `None` where nothing removes
    /// particles (every rate zero): the steady state is never reached.
    #[must_use]
    pub fn from_release(run: &Run, lambda: [f64; 5]) -> Option<Self> {
        let total: f64 = lambda.iter().sum();
        if !(total > 0.0 && total.is_finite()) || run.records.is_empty() {
            return None;
        }
        let n = run.records.len() as f64;
        // Per particle: its time in the air, and the share of it that ends in each fate.
        let samples: Vec<(f64, [f64; 5], bool)> = run
            .records
            .iter()
            .map(|r| {
                let mut ends = [0.0; 5];
                match r.fate {
                    Fate::Airborne => {
                        for (e, l) in ends.iter_mut().zip(lambda) {
                            *e = l / total;
                        }
                        (r.time + 1.0 / total, ends, true)
                    }
                    Fate::Deposited(s) => {
                        ends[fate_of(run, s)] = 1.0;
                        (r.time, ends, false)
                    }
                    Fate::Exhausted => {
                        ends[4] = 1.0;
                        (r.time, ends, false)
                    }
                    Fate::Escaped => (r.time, ends, false),
                }
            })
            .collect();
        let mean_t = samples.iter().map(|s| s.0).sum::<f64>() / n;
        let spread: f64 = samples.iter().map(|s| (s.0 - mean_t).powi(2)).sum::<f64>() / (n - 1.0).max(1.0);
        let beyond = samples.iter().filter(|s| s.2).count() as f64 / total / n / mean_t;
        let residence = Estimate {
            value: mean_t,
            error: (spread / n).sqrt(),
            events: samples.iter().filter(|s| !s.2).count(),
            upper_bound: f64::NAN,
        };
        let fates: [f64; 5] = std::array::from_fn(|k| samples.iter().map(|s| s.1[k]).sum::<f64>() / n);
        let orientations = [
            crate::model::geometry::Orientation::Floor,
            crate::model::geometry::Orientation::Ceiling,
            crate::model::geometry::Orientation::Wall,
        ];
        let deposition_velocity = std::array::from_fn(|k| {
            let area: f64 = run.walls_facing(orientations[k]).iter().map(|&w| run.walls[w].area).sum();
            // The particles it rests on: those deposited there, and those whose future there
            // the late rates give.
            let events = samples.iter().filter(|s| s.1[k] > 0.0).count();
            // The ratio sum D / sum T, by the delta method over the particles.
            let r = fates[k] / mean_t;
            let spread: f64 = samples.iter().map(|s| (s.1[k] - r * s.0).powi(2)).sum::<f64>() / (n - 1.0).max(1.0);
            let scale = if area > 0.0 { run.volume / area } else { 0.0 };
            Estimate {
                value: r * scale,
                error: (spread / n).sqrt() / mean_t * scale,
                events,
                upper_bound: if events == 0 {
                    3.0 / (n * mean_t) * scale
                } else {
                    (r + 2.0 * (spread / n).sqrt() / mean_t) * scale
                },
            }
        });
        Some(Self { residence, fates, deposition_velocity, beyond_run: beyond })
    }
}
