//! The two standard studies, each a set of runs with its comparison: deposition in a room
//! against Lai & Nazaroff (2000), and in a turbulent channel against Wood (1981) and
//! Papavergos & Hedley (1984). The `depo room` and `depo channel` commands print them.
//!
//! Both measure the deposition velocity after a `transient` share of the run, which lets the
//! core's concentration profile settle from the uniform injection, as deposits per area and
//! time over the mean airborne concentration (see [`crate::run`](mod@crate::run)): the
//! first tenth of a room's run, the first half of a channel's (the turbophoretic build-up of
//! inertial particles takes hundreds of wall time units).
//!
//! Where deposition is rare (every size in the room; `tau+` below 10 in the channel) they
//! count deposits by near-wall [`Excursions`] ([`Excursions::in_wall_units`], with splitting
//! factors calibrated by a pilot of a quarter of the particles): an unbiased estimate of the
//! steady deposition rate that does not wait for the Brownian sublayer to fill, and in the
//! room at 0.1 um six to eight times as efficient as plain tracking (`1 / (error^2 time)`;
//! see `docs/performance-log.md`). `excursions: false` gives plain tracking, for comparison.
//! In a furnished room ([`Scene::furnishings`]) the excursions start at the furnishings'
//! near-wall layers as at the walls' (their gap is to the nearest wall or box).

//!
//! This module holds what both studies share: their targets, rounds and excursions' budget;
//! the studies themselves are [`super::room`] and [`super::channel`].

use crate::estimation::run::Estimate;
use crate::model::error::SceneError;
use crate::model::excursions::{Excursions, Sweeps};
use crate::model::scene::{Injection, Scene};
use crate::model::settings::RunSettings;
use crate::tracking::WallTally;

/// Excursions per inward crossing in the studies: more than one, as each crossing's
/// excursions cost less than the plain tracking that found it (efficiencies in
/// docs/performance-log.md).
pub(crate) const STUDY_SAMPLING: f64 = 3.0;

/// The studies' splitting calibration: run particles per pilot particle, and rounds.
pub(crate) const PILOT: (usize, usize) = (4, 1);

/// The smallest deposition velocity (Lai & Nazaroff's, m/s) of a surface whose figure a room
/// study resolves to its `target_error`: below it the surface takes a negligible share of the
/// room's deposition.
pub const RESOLVED_FROM: f64 = 1e-7;

/// The relative standard error the default studies resolve their figures to
/// ([`RoomStudy::target_error`](super::room::RoomStudy::target_error),
/// [`ChannelStudy::target_error`](super::channel::ChannelStudy::target_error)).
pub const TARGET_ERROR: f64 = 0.05;

/// The most rounds in which a room study runs more particles towards its `target_error`.
pub(crate) const ROUNDS: usize = 3;

/// The most a round of a room study but its last multiplies the particles run.
pub(crate) const ROUND_GROWTH: usize = 4;

/// Whether estimate `e` has a deposit and a relative standard error of at most `target`:
/// what the studies run more particles until, and what `depo room` flags where not.
#[must_use]
pub fn resolved(e: &Estimate, target: f64) -> bool {
    e.events > 0 && e.error <= target * e.value
}

/// How many more particles than the first ones' errors say a study runs to reach its
/// `target_error`: a margin for the errors' own spread.
pub const TARGET_MARGIN: f64 = 1.15;

/// The share of the excursions' weight given up at their longest duration
/// ([`Run::truncated_share`](crate::Run::truncated_share)) above which a room study doubles
/// that duration, when its pilot or a size's whole run gives up more ([`lengthened`]; the
/// pilot runs again, the size starts afresh): half of [`TARGET_ERROR`], so that what giving
/// them up may miss (at most that share, had every branch given up deposited) stays within
/// half a resolved figure's error. Rooms of lower friction velocity give up more (figures in
/// docs/performance-log.md).
pub const LONGEST_SHARE: f64 = 0.025;

/// The most times a room study doubles its excursions' longest duration (from
/// [`ROOM_LONGEST_EXCURSION`] to eight times that).
pub const LONGEST_DOUBLINGS: u32 = 3;

/// The longest a room study follows an excursion at first, in wall time units (`nu / u*^2`):
/// 2400 s at `u* = 1 cm/s`.
pub const ROOM_LONGEST_EXCURSION: f64 = 16_000.0;

/// The longer duration (wall units) to follow excursions for, after a run that followed them
/// for `duration` gave up the share `truncated` of their weight: twice as long where that
/// share is above [`LONGEST_SHARE`] and twice as long is at most `most`; `None` otherwise.
#[must_use]
pub fn lengthened(duration: f64, truncated: f64, most: f64) -> Option<f64> {
    // `most` is a power of two times the first duration; the tolerance takes the rounding of
    // a duration read back from seconds.
    (truncated > LONGEST_SHARE && 2.0 * duration <= most * (1.0 + 1e-9)).then_some(2.0 * duration)
}

/// `settings` with the studies' excursions for `scene`, calibrated by a pilot of `pilot` particles of
/// `injection` with factors up to `max`; `inner` and the durations in wall units; `sweeps`
/// and `coarse_factor` as [`Excursions`] has them. The excursions are given up after
/// `first` and, while the pilot gives up more than [`LONGEST_SHARE`] of the weight, twice as
/// long and the pilot runs again, up to `most` ([`lengthened`]; `most = first` keeps the
/// first). Also the duration taken, and the pilots' wall-clock time, s.
#[allow(clippy::too_many_arguments)]
pub(crate) fn with_excursions(
    scene: &Scene,
    mut settings: RunSettings,
    injection: &Injection,
    pilot: usize,
    inner: f64,
    (first, most): (f64, f64),
    max: u32,
    sweeps: Option<Sweeps>,
    coarse_factor: u32,
) -> Result<(RunSettings, f64, f64), SceneError> {
    let start = std::time::Instant::now();
    let u_star = scene.flow.friction_velocity().unwrap_or(0.0);
    let mut duration = first;
    if u_star > 0.0 {
        let nu = scene.air.kinematic_viscosity();
        // With sweeps, one excursion per crossing of the layer: the sweeps carry the deposits.
        let sampling = if sweeps.is_some() { 1.0 } else { STUDY_SAMPLING };
        let (_, rounds) = PILOT;
        loop {
            let excursions = Excursions {
                sweeps: sweeps.clone(),
                coarse_factor,
                ..Excursions::in_wall_units(u_star, nu, inner, sampling, duration)
            };
            let (calibrated, truncated) =
                excursions.calibrated(scene, &settings, injection, pilot.max(1), rounds, max)?;
            settings.excursions = Some(calibrated);
            match lengthened(duration, truncated, most) {
                Some(longer) => duration = longer,
                None => break,
            }
        }
    }
    Ok((settings, duration, start.elapsed().as_secs_f64()))
}

/// The particles an estimate from `n` of them needs for a relative standard error of
/// `target`, as its error falls with `1 / sqrt(n)`, times [`TARGET_MARGIN`]; `usize::MAX`
/// with no deposit to go by. What a room study runs more particles by, and what `depo room`
/// tells of a figure left above its target at `max_count`.
#[must_use]
pub fn particles_for(e: &Estimate, n: usize, target: f64) -> usize {
    if e.events == 0 || e.value <= 0.0 {
        return usize::MAX;
    }
    (n as f64 * (e.error / e.value / target).powi(2) * TARGET_MARGIN).ceil() as usize
}

/// The particles a room study's top-up round runs in all, from the `have` it has run and the
/// `needed` that [`particles_for`] asks of them: [`TARGET_MARGIN`] on the particles it adds,
/// not on all of them. The margin is for the spread of errors not yet seen: from the first
/// particles, whose errors rest on few deposits, on all; once most of the particles have run,
/// the pooled figures' spread is what they showed, and only the added particles' is unknown
/// (docs/performance-log.md, "The pilot a quarter of the first particles, and a top-up's
/// margin on what it adds"). At least one more.
#[must_use]
pub fn topped_up(have: usize, needed: usize) -> usize {
    let bare = needed as f64 / TARGET_MARGIN;
    let more = ((bare - have as f64) * TARGET_MARGIN).ceil().max(1.0);
    (have + more as usize).min(needed.max(have + 1))
}

/// A room study's error in its own terms: its particles' sizes are the list `particles.diameters`.
pub(crate) fn for_diameters(mut e: SceneError) -> SceneError {
    if e.field == "particles.diameter" {
        e.field = "particles.diameters".into();
    }
    e
}

pub(crate) fn total(tallies: &[WallTally]) -> WallTally {
    let mut sum = WallTally::default();
    for t in tallies {
        sum += *t;
    }
    sum
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::estimation::run::run;
    use crate::model::scene::SizeDistribution;
    use crate::studies::room::*;

    #[test]
    fn excursions_are_followed_twice_as_long_while_too_much_is_given_up_and_at_most_the_most() {
        let first = ROOM_LONGEST_EXCURSION;
        assert_eq!(lengthened(first, 0.03, 8.0 * first), Some(2.0 * first));
        assert_eq!(lengthened(first, LONGEST_SHARE, 8.0 * first), None);
        assert_eq!(lengthened(4.0 * first, 0.5, 8.0 * first), Some(8.0 * first));
        assert_eq!(lengthened(8.0 * first, 0.5, 8.0 * first), None);
        // A duration read back from seconds, a little above four times the first.
        assert_eq!(lengthened(4.0 * first * (1.0 + 1e-12), 0.5, 8.0 * first), Some(8.0 * first * (1.0 + 1e-12)));
        // `most = first`: never.
        assert_eq!(lengthened(first, 0.5, first), None);
    }

    #[test]
    fn a_top_up_keeps_its_margin_on_the_particles_it_adds() {
        // 4000 run, 5% needs 5000 of them (5750 with the margin on all): 4000 + 1150.
        assert_eq!(topped_up(4000, 5750), 5150);
        // A figure just above its target still gets at least one more particle.
        assert_eq!(topped_up(4000, 4600), 4001);
        assert_eq!(topped_up(4000, 4000), 4001);
    }

    #[test]
    fn the_particles_a_target_needs_follow_one_over_the_square_root_of_their_number() {
        // 10 % from 1000 particles: a quarter of the error takes four times the particles,
        // 4600 with the margin; no deposit gives nothing to go by.
        let e = Estimate { value: 2.0, error: 0.2, events: 50, upper_bound: 2.4 };
        assert_eq!(particles_for(&e, 1000, 0.05), 4600);
        assert_eq!(particles_for(&e, 1000, 0.2), 288);
        let none = Estimate { value: 0.0, error: 0.0, events: 0, upper_bound: 1.0 };
        assert_eq!(particles_for(&none, 1000, 0.05), usize::MAX);
    }

    /// A room study's excursions are followed twice as long while their pilot gives up more
    /// than `LONGEST_SHARE` of the weight, at most `LONGEST_DOUBLINGS` times. Given up after 20
    /// wall time units (3 s at u* = 1 cm/s: most excursions are still in the layer), 0.3 um
    /// particles are followed eight times as long, and then still give up more than 2.5 %;
    /// after 16000, once. Without `lengthen` (the channel's) the duration stays.
    #[test]
    fn a_room_s_excursions_are_followed_longer_while_the_pilot_gives_up_too_much() {
        let RoomStudy { scene, mut settings, .. } = RoomStudy::default();
        settings.duration = 300.0;
        settings.average_from = 30.0;
        let injection = Injection::new(100, SizeDistribution::Monodisperse { diameter: 0.3e-6 }, 1000.0);
        let unit = scene.air.kinematic_viscosity() / 1e-4; // nu / u*^2, s
        let longest = |base: f64, lengthen: bool| {
            let most = if lengthen { 8.0 * base } else { base };
            let (settings, ..) =
                with_excursions(&scene, settings.clone(), &injection, 100, 0.05, (base, most), 16, None, 1).unwrap();
            let max_duration = settings.excursions.as_ref().unwrap().max_duration;
            let share =
                run(&scene, &RunSettings { seed: 7, ..settings.clone() }, &injection).unwrap().truncated_share();
            (max_duration / unit, share)
        };
        let (short, share) = longest(20.0, true);
        assert!((short - 160.0).abs() < 1e-9 && share > LONGEST_SHARE, "{short} {share}");
        let (kept, _) = longest(20.0, false);
        assert!((kept - 20.0).abs() < 1e-9, "{kept}");
        let (long, share) = longest(ROOM_LONGEST_EXCURSION, true);
        assert!((long - ROOM_LONGEST_EXCURSION).abs() < 1e-6 && share < LONGEST_SHARE, "{long} {share}");
    }
}
