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
//! are the delta method's over the independent particles, and the late rates' own errors
//! carried through (each rate moved by its standard error, the change it makes added in
//! quadrature, the rates taken as independent of the particles' spread): where most of the
//! steady state lies beyond the run, a figure is only as good as the rates it rests on, and
//! a rate resting on a single deposit makes it uncertain by about as much.
//!
//! ## Where the source enters
//! The release the steady state is read from is placed where the source emits
//! ([`Source`]): uniformly over the room (an indoor source spread over it, or outdoor air
//! infiltrating through the envelope, mixed in at the exchange rate), within a region of the
//! room (an indoor source there), or at a supply opening (outdoor air carried in by the
//! supply). Each particle's time near the floor ([`Record::near_floor`](crate::Record::near_floor),
//! the lowest [`NEAR_FLOOR_SHARE`] of the height) gives the steady concentration there over the
//! room's mean ([`SteadyState::near_floor`]): 1 in a room well mixed for that size, above 1
//! where particles settle faster than the room's turbulence lifts them
//! ([`NOT_WELL_MIXED`]), and where a source sits high (a supply at the ceiling) or low (a
//! source at the floor) the profiles differ.

use crate::estimation::run::{Estimate, Run};
use crate::tracking::{Fate, NEAR_FLOOR_SHARE};

/// Where a continuous source enters a room (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Source {
    /// Emitted indoors: uniformly over the box with corners `(low, high)` (m), or over the
    /// whole room where `None`. Its steady concentration is per particle emitted a second;
    /// it has no indoor/outdoor ratio.
    Indoor(Option<([f64; 3], [f64; 3])>),
    /// Outdoor air leaking in through the envelope, mixed over the whole room: particles enter
    /// at the rate the ventilation gives ([`Filtration::entering`](crate::studies::filtration::Filtration::entering),
    /// `P a` per outdoor concentration without filters), uniformly. Needs ventilation.
    Infiltration,
    /// Outdoor air brought in by the supply opening with this index in
    /// [`Scene::openings`](crate::Scene::openings), through the supply filter: the
    /// particles enter just inside the opening ([`SUPPLY_DEPTH`]) at `(1 - eta_s) Q` per
    /// outdoor concentration, `Q` the opening's flow.
    Supply(usize),
}

/// How far into the room (m) from a supply opening's face a [`Source::Supply`] places its
/// particles: where the opening's flow carries them on.
pub const SUPPLY_DEPTH: f64 = 0.01;

/// A size whose steady near-floor concentration over the room's mean
/// ([`SteadyState::near_floor`], under a source spread over the room) exceeds this is not
/// well mixed in the room: its deposition velocities over the room's mean concentration are
/// not a well-mixed room's.
pub const NOT_WELL_MIXED: f64 = 1.2;

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
    /// The steady concentration in the lowest [`NEAR_FLOOR_SHARE`] of the room's height over
    /// the room's mean, from the particles' own time in the air (the part beyond the run taken
    /// as mixed as that): `(sum L_i / V_floor) / (sum T_i / V)`, `L_i` a particle's time near the
    /// floor, `T_i` in the air, with the delta method's error.
    pub near_floor: Estimate,
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
    /// (deposition per orientation and on furnishings, exhaust), `lambda_error` their
    /// standard errors (0 for a rate known exactly, as the air exchange) and `lambda_events`
    /// the deposit events each rests on; `floor_volume` the air's volume in the lowest
    /// [`NEAR_FLOOR_SHARE`] of the height (m^3). `None` where nothing removes particles
    /// (every rate zero): the steady state is never reached.
    ///
    /// A deposition velocity's `events` are the deposit events it rests on: the release's
    /// own deposits there, and where particles were still airborne at the end, the events of
    /// the late rate that gives their future there.
    #[must_use]
    pub fn from_release(
        run: &Run,
        lambda: [f64; 5],
        lambda_error: [f64; 5],
        lambda_events: [usize; 5],
        floor_volume: f64,
    ) -> Option<Self> {
        let mut steady = Self::with_rates(run, lambda, floor_volume)?;
        let airborne = run.records.iter().any(|r| r.fate == Fate::Airborne);
        for (k, d) in steady.deposition_velocity.iter_mut().enumerate() {
            let own =
                run.records.iter().filter(|r| matches!(r.fate, Fate::Deposited(s) if fate_of(run, s) == k)).count();
            d.events = own + if airborne && lambda[k] > 0.0 { lambda_events[k] } else { 0 };
        }
        // Each rate moved by its error (down no further than 0), the change per unit error
        // squared and summed over the rates.
        let mut residence = 0.0;
        let mut velocity = [0.0; 3];
        for (j, &e) in lambda_error.iter().enumerate() {
            if !(e > 0.0 && e.is_finite()) {
                continue;
            }
            let (mut up, mut down) = (lambda, lambda);
            up[j] += e;
            down[j] = (down[j] - e).max(0.0);
            let (Some(a), Some(b)) =
                (Self::with_rates(run, up, floor_volume), Self::with_rates(run, down, floor_volume))
            else {
                continue;
            };
            let per_error = e / (up[j] - down[j]);
            residence += ((a.residence.value - b.residence.value) * per_error).powi(2);
            for (k, v) in velocity.iter_mut().enumerate() {
                *v += ((a.deposition_velocity[k].value - b.deposition_velocity[k].value) * per_error).powi(2);
            }
        }
        steady.residence.error = steady.residence.error.hypot(residence.sqrt());
        for (d, v) in steady.deposition_velocity.iter_mut().zip(velocity) {
            d.error = d.error.hypot(v.sqrt());
            if d.events > 0 {
                d.upper_bound = d.value + 2.0 * d.error;
            }
        }
        Some(steady)
    }

    /// [`SteadyState::from_release`] with the particles' errors alone, at the rates `lambda`.
    fn with_rates(run: &Run, lambda: [f64; 5], floor_volume: f64) -> Option<Self> {
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
            // the late rates give ([`SteadyState::from_release`] counts deposit events instead).
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
        let near_floor = near_floor(run, floor_volume);
        Some(Self { residence, fates, deposition_velocity, beyond_run: beyond, near_floor })
    }
}

/// The steady near-floor concentration over the room's mean under a source that emits as
/// `run`'s release was placed ([`SteadyState::near_floor`]), from the particles' own time in
/// the air; `floor_volume` as [`SteadyState::from_release`] takes it. NaN without time in the
/// air, and with fewer than two particles.
#[must_use]
pub fn near_floor(run: &Run, floor_volume: f64) -> Estimate {
    let n = run.records.len() as f64;
    let (low, all): (f64, f64) = run.records.iter().fold((0.0, 0.0), |(l, t), r| (l + r.near_floor, t + r.time));
    let events = run.records.iter().filter(|r| r.near_floor > 0.0).count();
    if !(all > 0.0 && floor_volume > 0.0) || n < 2.0 {
        return Estimate { value: f64::NAN, error: f64::NAN, events, upper_bound: f64::NAN };
    }
    let r = low / all;
    let spread: f64 = run.records.iter().map(|x| (x.near_floor - r * x.time).powi(2)).sum::<f64>() / (n - 1.0);
    let scale = run.volume / floor_volume;
    let error = (spread * n).sqrt() / all * scale;
    Estimate { value: r * scale, error, events, upper_bound: r * scale + 2.0 * error }
}

/// The air's volume (m^3) in the lowest [`NEAR_FLOOR_SHARE`] of a room `size` (m) with
/// `furnishings`.
#[must_use]
pub fn near_floor_volume(size: [f64; 3], furnishings: &[crate::model::furnishing::Furnishing]) -> f64 {
    let high = [size[0], size[1], NEAR_FLOOR_SHARE * size[2]];
    high.iter().product::<f64>() - furnishings.iter().map(|f| f.shared_volume([0.0; 3], high)).sum::<f64>()
}

impl Source {
    /// The release to read the steady state from: `injection` placed where the source
    /// enters in a room of `size` (m) with `openings`; `None` for a source spread over the
    /// whole room (the study's own release). An error names `source.region` or
    /// `source.opening`.
    pub fn injection(
        &self,
        injection: crate::model::scene::Injection,
        size: [f64; 3],
        openings: &[crate::model::openings::Opening],
    ) -> Result<Option<crate::model::scene::Injection>, crate::model::error::SceneError> {
        use crate::model::error::SceneError;
        match *self {
            Source::Indoor(None) | Source::Infiltration => Ok(None),
            Source::Indoor(Some((low, high))) => {
                for a in 0..3 {
                    if !(low[a].is_finite()
                        && high[a].is_finite()
                        && 0.0 <= low[a]
                        && low[a] < high[a]
                        && high[a] <= size[a])
                    {
                        return Err(SceneError::new(
                            "source.region",
                            if low[a] < high[a] { high[a] } else { low[a] },
                            "must be a box inside the room, its low corner below its high one on every axis",
                        ));
                    }
                }
                Ok(Some(injection.within(low, high)))
            }
            Source::Supply(k) => {
                let Some(o) = openings.get(k).filter(|o| o.kind == crate::model::openings::OpeningKind::Supply) else {
                    return Err(SceneError::new("source.opening", k as f64, "must be the index of a supply opening"));
                };
                let (axis, upper) = crate::model::openings::wall_axis(o.wall);
                let axes = crate::model::geometry::in_plane_axes(axis);
                let bounds = o.bounds();
                let (mut low, mut high) = ([0.0; 3], [0.0; 3]);
                for i in 0..2 {
                    (low[axes[i]], high[axes[i]]) = (bounds[i][0], bounds[i][1]);
                }
                let depth = SUPPLY_DEPTH.min(0.5 * size[axis]);
                (low[axis], high[axis]) = if upper { (size[axis] - depth, size[axis]) } else { (0.0, depth) };
                Ok(Some(injection.within(low, high)))
            }
        }
    }
}
