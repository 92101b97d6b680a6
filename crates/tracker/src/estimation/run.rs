//! Running a scene, and what a run tells: counts and mass per wall, deposition velocities,
//! loss-rate coefficients, deposition maps.
//!
//! Particles are independent (one-way coupling), so each is tracked through the whole run in
//! one go, with its own random stream; rayon spreads fixed chunks of particles over the cores
//! and the chunks' tallies are summed in chunk order. The same seed therefore gives the same
//! run, bit for bit, on any number of threads.
//!
//! ## Deposition velocity and its error
//! `v_d = J / C`: the deposits on a set of walls per unit area and time over the averaging
//! window, divided by the mean airborne concentration over that window. Here `C` is the
//! airborne particle-seconds within the window (the exposure) over the window's length and the
//! volume: the well-mixed definition a room's or a channel's loss rate uses. With near-wall
//! [`Excursions`](crate::Excursions) the deposits are the excursions' weighted ones.
//!
//! The estimate is a ratio of two sums over the injected particles, `R = sum X_i / sum E_i`
//! (`X_i` a particle's deposits, `E_i` its exposure), and its standard error is the delta
//! method's over the independent particles, `sqrt(n / (n - 1) sum (X_i - R E_i)^2) / sum E_i`.
//! For plain tracking with rare deposits this is the familiar `v_d / sqrt(N)` for `N`
//! deposits.
//!
//! ## Stopping a run
//! A caller on another thread (a binding that sees Ctrl-C, a user interface) stops a run, or a
//! whole study, with a [`Cancel`] token it hands in through [`Cancel::watch`]: each chunk of
//! particles checks the token before it starts, and each particle every 1024 steps, so a run
//! ends within milliseconds with [`SceneError::cancelled`], however long its particles' runs.

use std::cell::RefCell;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

use rayon::prelude::*;

use crate::model::error::SceneError;
use crate::model::geometry::{in_plane_axes, Orientation, Wall};
use crate::model::scene::{Injection, Scene};
use crate::model::settings::{RunSettings, Scheme};
use crate::tracking::{track, track_excursions, track_wall_function, Fate, ParticleTally, Prepared, Record, WallTally};

/// Particles per chunk of work: fixed, so the sums do not depend on the thread count, and
/// small, so that a run's last chunks end together on every thread (a study runs a size in
/// up to three parts, each ending at a barrier).
const CHUNK: usize = 8;

pub use crate::tracking::{MAX_STEP_GRADIENT, MAX_STEP_GRADIENT_MIDPOINT};

/// A request to stop runs early, shared between the thread that runs them and the one that
/// asks: clones are the same token. [`Cancel::watch`] hands it to every run (and so every
/// study) started on the calling thread while its closure runs; [`Cancel::cancel`], from any
/// thread, then ends each of them with [`SceneError::cancelled`] at the next chunk of
/// particles, on every thread the run uses. The scene, and the functions between a study and
/// its runs, are unchanged by it.
#[derive(Clone, Debug, Default)]
pub struct Cancel(Arc<AtomicBool>);

thread_local! {
    /// The token watched by the runs this thread starts ([`Cancel::watch`]).
    static WATCHED: RefCell<Option<Cancel>> = const { RefCell::new(None) };
}

impl Cancel {
    /// A token not yet cancelled.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// Asks every run watching this token to stop; it stays cancelled.
    pub fn cancel(&self) {
        self.0.store(true, Ordering::Relaxed);
    }

    /// Whether [`Cancel::cancel`] has been called on this token or a clone.
    #[must_use]
    pub fn is_cancelled(&self) -> bool {
        self.0.load(Ordering::Relaxed)
    }

    /// Runs `f` with this token watched by every run it starts on this thread (the tracker
    /// starts a study's runs on the study's own thread, and spreads only their particles over
    /// the pool, which the token follows); the previous token, if any, is watched again after.
    pub fn watch<R>(&self, f: impl FnOnce() -> R) -> R {
        /// Puts the previous token back, even if `f` unwinds.
        struct Restore(Option<Cancel>);
        impl Drop for Restore {
            fn drop(&mut self) {
                let previous = self.0.take();
                WATCHED.with(|w| *w.borrow_mut() = previous);
            }
        }
        let _restore = Restore(WATCHED.with(|w| w.replace(Some(self.clone()))));
        f()
    }

    /// The token the runs of this thread watch, if any.
    fn watched() -> Option<Self> {
        WATCHED.with(|w| w.borrow().clone())
    }
}

/// Tracks `injection` through `scene` on the current rayon pool, with the time step, duration,
/// seed and excursions of `settings`.
///
/// Besides [`Scene::validate`] and [`RunSettings::validate`], a turbulent scene's `dt` must keep `dt |d sigma / dy|` at or
/// below [`MAX_STEP_GRADIENT`] ([`MAX_STEP_GRADIENT_MIDPOINT`] with the midpoint scheme) over
/// the tabulated rms profiles: an error names `dt` otherwise.
pub fn run(scene: &Scene, settings: &RunSettings, injection: &Injection) -> Result<Run, SceneError> {
    let prepared = prepare(scene, settings, injection)?;
    let (records, particles, tallies) = track_range(settings, &prepared, 0..injection.count)?;
    let duration = prepared.steps as f64 * settings.dt;
    let smallest_weight = smallest_weight(settings);
    Ok(Run {
        records,
        particles,
        tallies,
        walls: prepared.surfaces,
        volume: scene.free_volume(),
        duration,
        dt: settings.dt,
        window: prepared.window,
        smallest_weight,
    })
}

/// `previous`, a run of `scene` with `settings` and the first particles of `injection`, carried on to all
/// `injection.count` of them: the particles it lacks are tracked and added. The result is
/// the run of the whole injection, particle for particle (each particle's history depends
/// on its id and the seed alone); the tallies' sums may differ from it in the last bits.
pub fn run_more(
    scene: &Scene,
    settings: &RunSettings,
    injection: &Injection,
    mut previous: Run,
) -> Result<Run, SceneError> {
    let prepared = prepare(scene, settings, injection)?;
    let done = previous.records.len();
    if done > injection.count {
        return Err(SceneError::new("count", injection.count as f64, "is fewer than the particles already run"));
    }
    let (records, particles, tallies) = track_range(settings, &prepared, done..injection.count)?;
    previous.smallest_weight = previous.smallest_weight.min(smallest_weight(settings));
    previous.records.extend(records);
    previous.particles.extend(particles);
    for (sum, x) in previous.tallies.iter_mut().zip(tallies) {
        *sum += x;
    }
    Ok(previous)
}

/// The smallest weight a deposit can carry in a run with `settings`: 1, or with excursions the
/// deepest level's weight over the largest sampling of any class of crossing.
fn smallest_weight(settings: &RunSettings) -> f64 {
    settings.excursions.as_ref().map_or(1.0, |e| {
        let most = e.class_sampling.iter().copied().fold(0.0, f64::max);
        e.splitting.weight(e.splitting.levels.len()) / (e.sampling * most)
    })
}

/// The scene and its settings validated and prepared for `injection`.
fn prepare<'a>(
    scene: &'a Scene,
    settings: &'a RunSettings,
    injection: &'a Injection,
) -> Result<Prepared<'a>, SceneError> {
    scene.validate(injection)?;
    settings.validate(scene)?;
    let mut prepared = Prepared::new(scene, settings, injection)?;
    prepared.stop = Cancel::watched().map(|c| c.0);
    let (limit, message) = if settings.scheme == Scheme::Midpoint {
        (MAX_STEP_GRADIENT_MIDPOINT, "is too long for the turbulence: dt times the steepest gradient of a velocity fluctuation's rms must be at most 0.1 with the midpoint scheme")
    } else {
        (MAX_STEP_GRADIENT, "is too long for the turbulence: dt times the steepest gradient of a velocity fluctuation's rms must be at most 0.05 (0.1 with the midpoint scheme)")
    };
    if settings.dt * prepared.field.steepest_gradient() > limit {
        return Err(SceneError::new("dt", settings.dt, message));
    }
    Ok(prepared)
}

/// What [`track_range`] gives: records, particle tallies, wall tallies.
type Tracked = (Vec<Record>, Vec<ParticleTally>, Vec<WallTally>);

/// Tracks particles `ids` in chunks of [`CHUNK`] ids (fixed, whatever the thread count):
/// their records and tallies in id order, and their wall tallies summed in chunk order. A
/// chunk does not start once the watched [`Cancel`] is cancelled, and the particles in hand
/// stop (`Prepared::stop`): the range then ends with [`SceneError::cancelled`].
fn track_range(
    settings: &RunSettings,
    prepared: &Prepared<'_>,
    ids: std::ops::Range<usize>,
) -> Result<Tracked, SceneError> {
    let wall_count = prepared.surfaces.len();
    let window = prepared.window;
    let first = ids.start;
    let cancel = Cancel::watched();
    let stopped = || cancel.as_ref().is_some_and(Cancel::is_cancelled);
    if stopped() {
        return Err(SceneError::cancelled());
    }
    let chunks: Option<Vec<Tracked>> = (first / CHUNK..ids.end.div_ceil(CHUNK))
        .into_par_iter()
        .map(|c| {
            if stopped() {
                return None;
            }
            let mut tally = vec![WallTally::default(); wall_count];
            let ids = (c * CHUNK).max(first)..((c + 1) * CHUNK).min(ids.end);
            let (records, particles) = match &settings.excursions {
                Some(excursions) => track_excursions(prepared, excursions, ids, &mut tally),
                None if prepared.wall_function.is_some() => track_wall_function(prepared, ids, &mut tally),
                None => {
                    let records = track(prepared, ids, &mut tally);
                    let particles = records.iter().map(|r| ParticleTally::of(r, window)).collect();
                    (records, particles)
                }
            };
            Some((records, particles, tally))
        })
        .collect();
    // Cancelled while chunks ran: their particles stopped short of the run's end.
    let chunks = chunks.filter(|_| !stopped()).ok_or_else(SceneError::cancelled)?;
    let mut records = Vec::with_capacity(ids.len());
    let mut particles = Vec::with_capacity(ids.len());
    let mut tallies = vec![WallTally::default(); wall_count];
    for (r, p, t) in chunks {
        records.extend(r);
        particles.extend(p);
        for (sum, x) in tallies.iter_mut().zip(t) {
            *sum += x;
        }
    }
    Ok((records, particles, tallies))
}

/// A value with its standard error.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Estimate {
    /// The value.
    pub value: f64,
    /// Its standard error (one standard deviation of the estimate over the run's randomness).
    pub error: f64,
    /// The number of deposit events it rests on.
    pub events: usize,
    /// With no event, a 95 % upper bound on the value: what three events of the smallest
    /// weight a deposit can have would give (the rule of three for a Poisson count); the value
    /// itself plus two standard errors otherwise.
    pub upper_bound: f64,
}

impl Estimate {
    /// The ratio `sum x_i / sum e_i` over independent samples `(x_i, e_i)` times `scale`, with
    /// the delta method's standard error; `events` deposits, `unit` the smallest weight one
    /// can carry.
    fn ratio(samples: impl Iterator<Item = (f64, f64)> + Clone, scale: f64, events: usize, unit: f64) -> Self {
        let (mut n, mut sx, mut se) = (0usize, 0.0, 0.0);
        for (x, e) in samples.clone() {
            n += 1;
            sx += x;
            se += e;
        }
        if se.is_nan() || se <= 0.0 || n < 2 {
            return Self { value: 0.0, error: 0.0, events, upper_bound: f64::INFINITY };
        }
        let r = sx / se;
        let spread: f64 = samples.map(|(x, e)| (x - r * e).powi(2)).sum();
        let error = (spread * n as f64 / (n - 1) as f64).sqrt() / se;
        let upper_bound = if events == 0 { 3.0 * unit / se } else { r + 2.0 * error };
        Self { value: r * scale, error: error * scale, events, upper_bound: upper_bound * scale }
    }
}

/// The delta method's standard error of an estimate from its independent samples' first-order
/// contributions `c_i` to its deviation (each sample's influence, summing to zero):
/// `sqrt(n / (n - 1) sum c_i^2)`; 0 with fewer than two samples. [`Run::loss_rate`]'s error is
/// this of [`Run::loss_rate_influences`], the decay fit's of its slope's influences (see
/// [`crate::decay`]).
#[must_use]
pub fn delta_error(contributions: &[f64]) -> f64 {
    let n = contributions.len();
    if n < 2 {
        return 0.0;
    }
    let sum: f64 = contributions.iter().map(|c| c * c).sum();
    (sum * n as f64 / (n - 1) as f64).sqrt()
}

/// The binomial standard error `sqrt(f (1 - f) / n)` of a share `f` of `n` independent
/// particles (0 with none).
#[must_use]
pub fn binomial_error(f: f64, n: usize) -> f64 {
    if n == 0 {
        0.0
    } else {
        (f * (1.0 - f) / n as f64).sqrt()
    }
}

/// Where the injected particles are at the end: the mass balance of a run.
#[derive(Clone, Debug, PartialEq)]
pub struct Balance {
    /// Injected particles.
    pub injected: usize,
    /// Still airborne.
    pub airborne: usize,
    /// Deposited, per surface (walls, then furnishing faces; see [`Run::walls`]).
    pub deposited: Vec<usize>,
    /// Escaped.
    pub escaped: usize,
    /// Exhausted by ventilation.
    pub exhausted: usize,
    /// Injected mass, kg.
    pub injected_mass: f64,
    /// Airborne mass, kg.
    pub airborne_mass: f64,
    /// Deposited mass per surface, kg.
    pub deposited_mass: Vec<f64>,
    /// Escaped mass, kg.
    pub escaped_mass: f64,
    /// Exhausted mass, kg.
    pub exhausted_mass: f64,
}

/// The outcome of a run.
#[derive(Clone, Debug, PartialEq)]
pub struct Run {
    /// One record per particle, in injection order.
    pub records: Vec<Record>,
    /// What each injected particle contributed to the window's statistics, in injection order.
    pub particles: Vec<ParticleTally>,
    /// Impact statistics per surface.
    pub tallies: Vec<WallTally>,
    /// The surfaces in id order: the walls, then the furnishings' faces
    /// ([`Scene::surfaces`]).
    pub walls: Vec<Wall>,
    /// The air's volume (the domain's less the furnishings'), m^3.
    pub volume: f64,
    /// Simulated time, s.
    pub duration: f64,
    /// Time step, s.
    pub dt: f64,
    /// The averaging window, s.
    pub window: [f64; 2],
    /// The smallest weight a deposit can carry (1 without excursions).
    pub smallest_weight: f64,
}

impl Run {
    /// Particle-steps tracked (the unit of tracking cost).
    #[must_use]
    pub fn particle_steps(&self) -> u64 {
        self.records.iter().map(|r| r.steps).sum()
    }

    /// Steps the run took.
    #[must_use]
    pub fn steps(&self) -> u64 {
        (self.duration / self.dt).round() as u64
    }

    /// Counts and masses: airborne + deposited (per surface, walls and furnishing faces) +
    /// escaped + exhausted = injected, exactly.
    #[must_use]
    pub fn balance(&self) -> Balance {
        let mut b = Balance {
            injected: self.records.len(),
            airborne: 0,
            deposited: vec![0; self.walls.len()],
            escaped: 0,
            exhausted: 0,
            injected_mass: 0.0,
            airborne_mass: 0.0,
            deposited_mass: vec![0.0; self.walls.len()],
            escaped_mass: 0.0,
            exhausted_mass: 0.0,
        };
        for r in &self.records {
            b.injected_mass += r.mass;
            match r.fate {
                Fate::Airborne => {
                    b.airborne += 1;
                    b.airborne_mass += r.mass;
                }
                Fate::Deposited(w) => {
                    b.deposited[w] += 1;
                    b.deposited_mass[w] += r.mass;
                }
                Fate::Escaped => {
                    b.escaped += 1;
                    b.escaped_mass += r.mass;
                }
                Fate::Exhausted => {
                    b.exhausted += 1;
                    b.exhausted_mass += r.mass;
                }
            }
        }
        b
    }

    /// Deposition velocity onto `walls` over the averaging window (m/s; see the module docs).
    #[must_use]
    pub fn deposition_velocity(&self, walls: &[usize]) -> Estimate {
        let area: f64 = walls.iter().map(|&w| self.walls[w].area).sum();
        let events = self.particles.iter().map(|p| walls.iter().map(|&w| p.events_on(w) as usize).sum::<usize>()).sum();
        let samples =
            self.particles.iter().map(|p| (walls.iter().map(|&w| p.deposited_on(w)).sum::<f64>(), p.exposure));
        let scale = if area > 0.0 { self.volume / area } else { 0.0 };
        Estimate::ratio(samples, scale, events, self.smallest_weight)
    }

    /// With a wall function ([`crate::wall_function`]): the mean airborne concentration within
    /// the walls' layers, of `layer_volume` (m^3) in all, over the mean concentration in the
    /// whole volume, over the averaging window, with its standard error: 1 where the layers
    /// hold the concentration the correlation is defined against.
    #[must_use]
    pub fn layer_concentration(&self, layer_volume: f64) -> Estimate {
        let samples = self.particles.iter().map(|p| (p.layer_exposure, p.exposure));
        let events = self.particles.iter().filter(|p| p.layer_exposure > 0.0).count();
        Estimate::ratio(samples, self.volume / layer_volume, events, self.dt)
    }

    /// With [`Excursions`](crate::Excursions): the weight of excursion branches given up at
    /// their longest duration, over the weight that deposited (zero otherwise). A bound on
    /// the share of deposits that giving them up may have missed.
    #[must_use]
    pub fn truncated_share(&self) -> f64 {
        let truncated: f64 = self.particles.iter().map(|p| p.truncated).sum();
        let deposited: f64 = self.particles.iter().map(ParticleTally::deposited_total).sum();
        if truncated > 0.0 {
            truncated / deposited
        } else {
            0.0
        }
    }

    /// Loss-rate coefficient `beta = sum(v_d A) / V` over the averaging window, 1/s: the
    /// first-order rate at which deposition removes airborne particles.
    #[must_use]
    pub fn loss_rate(&self) -> Estimate {
        let all: Vec<usize> = (0..self.walls.len()).collect();
        let v = self.deposition_velocity(&all);
        let area: f64 = self.walls.iter().map(|w| w.area).sum();
        let k = area / self.volume;
        Estimate { value: v.value * k, error: v.error * k, events: v.events, upper_bound: v.upper_bound * k }
    }

    /// Each injected particle's first-order contribution to [`Run::loss_rate`] (1/s), in
    /// injection order: with `beta = R = sum X_i / sum E_i` (`X_i` the particle's deposits
    /// within the averaging window, `E_i` its exposure there), the delta method's
    /// `(X_i - R E_i) / sum E`. They sum to zero, and the loss rate's error is their
    /// [`delta_error`]. Other estimates from the same particles (the decay fit's `beta`) are
    /// correlated with the loss rate through them: the error of a difference is the
    /// [`delta_error`] of the differences of the contributions. `None` without exposure.
    #[must_use]
    pub fn loss_rate_influences(&self) -> Option<Vec<f64>> {
        // Every surface's, the furnishings' faces' too, as the loss rate counts them.
        let deposits = ParticleTally::deposited_total;
        let exposure: f64 = self.particles.iter().map(|p| p.exposure).sum();
        if exposure.is_nan() || exposure <= 0.0 {
            return None;
        }
        let r = self.particles.iter().map(deposits).sum::<f64>() / exposure;
        Some(self.particles.iter().map(|p| (deposits(p) - r * p.exposure) / exposure).collect())
    }

    /// The room's own walls of one orientation (not the furnishings' faces: see
    /// [`Run::surfaces_facing`]).
    #[must_use]
    pub fn walls_facing(&self, orientation: Orientation) -> Vec<usize> {
        self.walls.iter().filter(|w| w.furnishing.is_none() && w.orientation() == orientation).map(|w| w.id).collect()
    }

    /// Every surface of one orientation, walls and furnishing faces (a table's top faces up
    /// like the floor).
    #[must_use]
    pub fn surfaces_facing(&self, orientation: Orientation) -> Vec<usize> {
        self.walls.iter().filter(|w| w.orientation() == orientation).map(|w| w.id).collect()
    }

    /// The faces of furnishing `k`, in face order.
    #[must_use]
    pub fn furnishing_faces(&self, k: usize) -> Vec<usize> {
        self.walls.iter().filter(|w| w.furnishing == Some(k)).map(|w| w.id).collect()
    }

    /// All surfaces' area over the air's volume, 1/m: the room's walls and the furnishings'
    /// faces over the room's volume less the furnishings'.
    #[must_use]
    pub fn surface_to_volume(&self) -> f64 {
        self.walls.iter().map(|w| w.area).sum::<f64>() / self.volume
    }

    /// Deposition map of one wall: the tracked particles' deposits over the whole run on a
    /// `bins[0] x bins[1]` grid over its two in-plane axes (in the order x, y, z without the
    /// wall's own axis), row-major, spanning `[0, size]` (for a furnishing's face, pass the
    /// box's extent with [`Run::deposition_map_within`]).
    #[must_use]
    pub fn deposition_map(&self, wall: usize, size: [f64; 3], bins: [usize; 2]) -> Vec<u32> {
        self.deposition_map_within(wall, [0.0; 3], size, bins)
    }

    /// [`Run::deposition_map`] over the box `[low, high]` (m).
    #[must_use]
    pub fn deposition_map_within(&self, wall: usize, low: [f64; 3], high: [f64; 3], bins: [usize; 2]) -> Vec<u32> {
        let size: [f64; 3] = std::array::from_fn(|a| high[a] - low[a]);
        let axis = self.walls[wall].axis;
        let [a, b] = in_plane_axes(axis);
        let mut map = vec![0u32; bins[0] * bins[1]];
        for r in self.records.iter().filter(|r| r.fate == Fate::Deposited(wall)) {
            let i = (((r.position[a] - low[a]) / size[a] * bins[0] as f64).max(0.0) as usize).min(bins[0] - 1);
            let j = (((r.position[b] - low[b]) / size[b] * bins[1] as f64).max(0.0) as usize).min(bins[1] - 1);
            map[i * bins[1] + j] += 1;
        }
        map
    }
}

#[cfg(test)]
mod tests {
    use std::time::{Duration, Instant};

    use super::*;
    use crate::model::geometry::Geometry;
    use crate::model::scene::SizeDistribution;

    /// Brownian 0.1 um particles in still air in a 1 m box for 1000 s of 10 ms steps: about
    /// 1e5 steps each, far more than a second's work for `count` of them.
    fn long_run(count: usize) -> (Scene, RunSettings, Injection) {
        let mut scene = Scene::new(Geometry::Room { size: [1.0, 1.0, 1.0] });
        scene.brownian = true;
        (
            scene,
            RunSettings::new(0.01, 1000.0),
            Injection::new(count, SizeDistribution::Monodisperse { diameter: 0.1e-6 }, 1000.0),
        )
    }

    /// A run cancelled from another thread ends within a second with the cancelled error, where
    /// it would take minutes; the token is no longer watched after `watch` returns.
    #[test]
    fn a_cancelled_run_returns_quickly() {
        let (scene, settings, injection) = long_run(1_000_000);
        let cancel = Cancel::new();
        let start = Instant::now();
        let result = std::thread::scope(|s| {
            s.spawn(|| {
                std::thread::sleep(Duration::from_millis(200));
                cancel.cancel();
            });
            cancel.watch(|| run(&scene, &settings, &injection))
        });
        let took = start.elapsed();
        let error = result.expect_err("the run was cancelled");
        assert!(error.is_cancelled(), "{error}");
        assert_eq!(error.to_string(), "the run was cancelled");
        assert!(took < Duration::from_secs(2), "the cancelled run took {took:?}");
        // Without the token watched, a (short) run goes through.
        let (scene, settings, injection) = long_run(4);
        assert_eq!(run(&scene, &settings, &injection).map(|r| r.records.len()), Ok(4));
    }

    /// A token cancelled before the run stops it before any particle; one not cancelled
    /// changes nothing, to the bit.
    #[test]
    fn a_watched_token_changes_nothing_until_cancelled() {
        let (scene, mut settings, injection) = long_run(16);
        settings.duration = 1.0;
        let cancelled = Cancel::new();
        cancelled.cancel();
        assert!(cancelled.watch(|| run(&scene, &settings, &injection)).is_err_and(|e| e.is_cancelled()));
        let watched = Cancel::new().watch(|| run(&scene, &settings, &injection)).unwrap();
        assert_eq!(watched, run(&scene, &settings, &injection).unwrap());
    }
}
