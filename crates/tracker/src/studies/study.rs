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

use crate::estimation::allocation::{self, Figure};
use crate::estimation::decay::{DecayCurve, DecayFit, DECAY_INTERVALS};
use crate::estimation::run::{run, run_more, Balance, Estimate, Run};
use crate::model::air::Air;
use crate::model::error::SceneError;
use crate::model::excursions::{crossing_class, Excursions, Sweeps, CROSSING_CLASSES};
use crate::model::flow::Flow;
use crate::model::geometry::{Geometry, Orientation};
use crate::model::scene::{Injection, Scene, Scheme, SizeDistribution};
use crate::physics::correlations::{diameter_for_tau_plus, papavergos_hedley, schmidt, wood, LaiNazaroff};
use crate::studies::filtration::Filtration;
use crate::studies::steady::SteadyState;
use crate::tracking::WallTally;

/// A room study: one run per diameter in `scene` (a room with a turbulent-room flow).
#[derive(Clone, Debug, PartialEq)]
pub struct RoomStudy {
    /// The room, its air, flow, walls and time stepping.
    pub scene: Scene,
    /// Particle diameters, m.
    pub diameters: Vec<f64>,
    /// Particles per diameter: all of them without `target_error`, the first ones with it.
    pub count: usize,
    /// The relative standard error to resolve each size's figures to: `beta`, and the
    /// deposition velocity onto each surface where Lai & Nazaroff's model gives at least
    /// [`RESOLVED_FROM`] (the figures a room study is read for). When the first `count`
    /// particles leave one of them less resolved, more are run (and pooled with them), in up
    /// to three rounds, until every figure is within the target or `max_count` particles have
    /// run: each round as many as the least resolved figure's error, falling as
    /// `1 / sqrt(n)`, says it needs, with a margin of [`TARGET_MARGIN`] (in the first, on all
    /// of them, and a few more where that lets the excursions be cut elsewhere; in the second,
    /// on the particles it adds, [`topped_up`]; in the last, again on all), but at most four
    /// times the particles run in all but the last. With excursions, those particles start
    /// fewer excursions per crossing where the figures they resolve have room to spare, as
    /// the first particles show ([`crate::allocation`]). `None`: `count` particles, whatever
    /// the errors.
    pub target_error: Option<f64>,
    /// The most particles per diameter with `target_error`.
    pub max_count: usize,
    /// Particle density, kg/m^3.
    pub density: f64,
    /// Share of the run left out of the averages, in `[0, 1)`.
    pub transient: f64,
    /// Count deposits by near-wall excursions (the default) rather than plain tracking.
    pub excursions: bool,
    /// Penetration factor `P` of outdoor particles through the building envelope, in `[0, 1]`
    /// (1 by default): with ventilation ([`Scene::exchange_rate`]) it sets the steady
    /// indoor/outdoor ratio [`RoomPoint::indoor_outdoor`].
    pub penetration: f64,
    /// A filtered supply and recirculation ([`crate::filtration`]): the recirculation filter
    /// adds its removal `eta_r(d) a_r` to each size's exhaust, and the indoor/outdoor ratio
    /// takes both filters. The default has neither.
    pub filtration: Filtration,
}

/// Excursions per inward crossing in the studies: more than one, as each crossing's
/// excursions cost less than the plain tracking that found it (room, 0.1 um: efficiency
/// 21 with one, 32 with three).
const STUDY_SAMPLING: f64 = 3.0;

/// The studies' splitting calibration: run particles per pilot particle, and rounds.
const PILOT: (usize, usize) = (4, 1);

/// The longest a channel study follows an excursion, in wall time units (`nu / u*^2`). Below
/// `tau+ = 3` particles hover in the viscous sublayer, where the turbulence has all but
/// vanished and Brownian motion at `Sc ~ 1e6` crosses the last wall unit slowly: given up
/// after 1e4 wall time units, the weight left hovering was 3-4 times the weight deposited and
/// `V+` came out half of what it is (`tau+ = 0.3`, 500 particles: 0.070 of Wood with 1e4,
/// 0.134 with 3e4 and 0.132 with 1e5, where the share given up fell to 6 % and then below
/// 0.5 %). After 1e5 none is left to give up, so the estimate has no truncation bias left to
/// speak of; the printed share given up says so for each run.
pub const CHANNEL_LONGEST_EXCURSION: f64 = 1e5;

/// The innermost splitting level of a channel study's excursions, in wall units (from the
/// particle's surface): levels halve from 15 wall units down to 0.23. Below `tau+ = 3` the
/// branches spend about 95 % of their steps within one wall unit of the wall, hovering for
/// hundreds to thousands of wall time units, so each split below a few tenths of a wall unit
/// multiplies the costliest branches. Measured at 1000 particles per `tau+` (single runs,
/// efficiency `1 / (relative error^2 time)`), three more levels down to 0.03 wall units gave
/// 21, 14 and 24 at `tau+` 0.1, 0.3 and 1, and stopping at 0.23 gave 30, 28 and 31 with the
/// same `V+` within the errors; stopping one level further out (0.47) gave 22, 20 and 25.
pub const CHANNEL_INNERMOST_LEVEL: f64 = 0.2;

/// The channel study catches strong sweeps on their way to the near-wall layer
/// ([`Excursions::sweeps`]) from this `tau+` on: where a strong sweep's wall-ward speed (a
/// few `u*`) times the particle's relaxation time carries it across the sublayer's few wall
/// units. At `tau+` 0.1-1, where Brownian motion and the turbulence within the sublayer carry
/// the particles the last part of the way, sweeps took 2-2.5 times the run time for errors
/// 3-25 % smaller, so they stay off there.
pub const CHANNEL_SWEEPS_FROM: f64 = 3.0;

/// The sweeps the channel study catches: the fluid's wall-ward `zeta` above 3 (0.13 % of the
/// time in a Gaussian) until it falls below 2, ten excursions per such entry, and then one
/// per crossing of the layer (not the three the studies start elsewhere). Measured at
/// `tau+ = 3`, 1000 particles (efficiency `1 / (relative error^2 time)`): without sweeps the
/// relative error was 19-40 % in 8-9 s (three seeds; efficiency 0.7-3.6); with these,
/// 11-16 % in 2.8-4.4 s (five seeds; 13-24); with three excursions per crossing and thirty
/// per sweep, 7-10 % in 8-12 s (about the same efficiency, at three times the cost). With
/// those, thresholds of 2.5 or 3.5, and sweeps counted only within 45, 60 or 100 wall units
/// of the wall, did no better. The table is in docs/performance-log.md.
pub const CHANNEL_SWEEPS: Sweeps = Sweeps { enter: 3.0, leave: 2.0, sampling: 10.0 };

/// The coarse steps of a channel study's excursions below [`CHANNEL_SWEEPS_FROM`]
/// ([`Excursions::coarse_factor`]): four times the study's step (0.8 wall time units), with
/// the midpoint scheme, wherever they cannot reach a wall (the wall-normal rms' steepest slope,
/// about 0.04 `u*` per wall unit, times 0.8 is below the gradient limit, so that limit does not
/// bind here). Measured at `tau+` 0.1, 0.3 and 1, 1000 particles, three seeds, against the
/// same excursions stepped with the midpoint scheme at the study's step wherever clear of a
/// wall (ratios of `V+` pooled over the nine runs, and run time against the study's step
/// throughout): factor 2 gave 1.00 +- 0.03 in 1.0 times the time; 4 gave 1.03 +- 0.03 in 0.59;
/// 8 gave 1.11 +- 0.04 in 0.39. The study's step throughout, with the default scheme, gave
/// 1.08 +- 0.04: its first-order error in the sublayer, which the midpoint scheme takes out.
/// Coarse steps of 4 with the default scheme gave 1.4 times the study's step's `V+` at
/// `tau+ = 0.3`. From `tau+ = 3`, where sweeps carry the particles to the wall rather than
/// hovering, they are off: 1.4 times faster there, but over five seeds no more efficient.
pub const CHANNEL_COARSE_FACTOR: u32 = 4;

/// The smallest deposition velocity (Lai & Nazaroff's, m/s) of a surface whose figure a room
/// study resolves to its `target_error`: below it the surface takes a negligible share of the
/// room's deposition.
pub const RESOLVED_FROM: f64 = 1e-7;

/// The relative standard error the default studies resolve their figures to
/// ([`RoomStudy::target_error`], [`ChannelStudy::target_error`]).
pub const TARGET_ERROR: f64 = 0.05;

/// The most rounds in which a room study runs more particles towards its `target_error`.
const ROUNDS: usize = 3;

/// The most a round of a room study but its last multiplies the particles run.
const ROUND_GROWTH: usize = 4;

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
/// half a resolved figure's error. The default room gives up 0.3-1.3 % at 0.1-1 um; the
/// measured rooms of Thatcher et al. (2002), at their lower friction velocities, up to 17 %
/// at 0.5 um.
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

/// `scene` with the studies' excursions, calibrated by a pilot of `pilot` particles of
/// `injection` with factors up to `max`; `inner` and the durations in wall units; `sweeps`
/// and `coarse_factor` as [`Excursions`] has them. The excursions are given up after
/// `first` and, while the pilot gives up more than [`LONGEST_SHARE`] of the weight, twice as
/// long and the pilot runs again, up to `most` ([`lengthened`]; `most = first` keeps the
/// first). Also the duration taken, and the pilots' wall-clock time, s.
#[allow(clippy::too_many_arguments)]
fn with_excursions(
    mut scene: Scene,
    injection: &Injection,
    pilot: usize,
    inner: f64,
    (first, most): (f64, f64),
    max: u32,
    sweeps: Option<Sweeps>,
    coarse_factor: u32,
) -> Result<(Scene, f64, f64), SceneError> {
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
            let (calibrated, truncated) = excursions.calibrated(&scene, injection, pilot.max(1), rounds, max)?;
            scene.excursions = Some(calibrated);
            match lengthened(duration, truncated, most) {
                Some(longer) => duration = longer,
                None => break,
            }
        }
    }
    Ok((scene, duration, start.elapsed().as_secs_f64()))
}

impl Default for RoomStudy {
    /// A 4 m x 3 m x 2.5 m room, `u* = 1 cm/s` with a well-mixed core ([`Flow::indoor_room`]),
    /// Brownian motion, perfectly absorbing surfaces (as Lai & Nazaroff assume), 0.01-10 um
    /// unit-density particles, 1800 s of 0.1 s steps of the midpoint scheme, averages from
    /// 180 s on. The midpoint scheme ([`Scheme::Midpoint`]) at 0.1 s gives `beta` within the
    /// errors of the default scheme at 0.01 s, where the default scheme at 0.05 s (this
    /// study's step before) was 9-14 % high at 0.01-0.3 um, in about the same run time.
    fn default() -> Self {
        let mut scene = Scene::new(Geometry::Room { size: [4.0, 3.0, 2.5] }, 0.1, 1800.0);
        scene.flow = Flow::indoor_room();
        scene.brownian = true;
        scene.scheme = Scheme::Midpoint;
        Self {
            scene,
            diameters: vec![0.01e-6, 0.03e-6, 0.1e-6, 0.3e-6, 1e-6, 3e-6, 10e-6],
            count: 1000,
            target_error: Some(TARGET_ERROR),
            max_count: 8000,
            density: 1000.0,
            transient: 0.1,
            excursions: true,
            penetration: 1.0,
            filtration: Filtration::default(),
        }
    }
}

/// One size of a room study.
#[derive(Clone, Debug, PartialEq)]
pub struct RoomPoint {
    /// Diameter, m.
    pub diameter: f64,
    /// Deposition velocity onto the floor, m/s.
    pub floor: Estimate,
    /// Onto the ceiling, m/s.
    pub ceiling: Estimate,
    /// Onto the vertical walls (all four together), m/s.
    pub walls: Estimate,
    /// Onto each vertical wall, in id order (`x0`, `x1`, `y0`, `y1`; see [`crate::geometry`]),
    /// m/s: the walls can differ in material, and with openings in the flow that reaches them.
    pub each_wall: [Estimate; 4],
    /// Loss-rate coefficient, 1/s.
    pub beta: Estimate,
    /// Lai & Nazaroff's model for the same particle and friction velocity.
    pub model: LaiNazaroff,
    /// The model's loss-rate coefficient for this room, 1/s.
    pub model_beta: f64,
    /// Particle-steps the run took (of the tracked particles; excursions not included).
    pub particle_steps: u64,
    /// Particles run (more than [`RoomStudy::count`] where its `target_error` needed them).
    pub particles: usize,
    /// Whether deposits were counted by near-wall excursions, and if so the share of their
    /// weight given up at their longest duration ([`Run::truncated_share`](crate::Run::truncated_share)).
    pub excursions: Option<f64>,
    /// With excursions, their longest duration ([`Excursions::max_duration`]), s:
    /// [`ROOM_LONGEST_EXCURSION`], doubled while the pilot or the whole run gave up more
    /// than [`LONGEST_SHARE`] of the weight ([`lengthened`]).
    pub longest_excursion: Option<f64>,
    /// With excursions, the multipliers of their sampling per class of crossing (floor,
    /// ceiling, walls, furnishings; [`Excursions::class_sampling`]) that the particles after
    /// the first ran with: 1 where the study cut none, or ran no more particles.
    pub class_sampling: Option<[f64; CROSSING_CLASSES]>,
    /// Wall-clock time of the excursions' pilot calibration, and of the runs of this size
    /// given up for a longer duration, s (0 without excursions): a cost fixed per run, which
    /// does not grow with the particles run.
    pub calibration_seconds: f64,
    /// With ventilation (air-exchange rate `a > 0`), the steady indoor/outdoor concentration
    /// ratio of outdoor particles, `C_in / C_out = P a / (a + beta)` (the well-mixed room's
    /// mass balance with penetration `P`; with filters [`Filtration::indoor_outdoor`]), its
    /// error carried from `beta`'s.
    pub indoor_outdoor: Option<Estimate>,
    /// The recirculation filter's removal rate `eta_r(d) a_r` at this size, 1/s (0 without
    /// one), which the run's exhaust included.
    pub filter_removal: f64,
    /// The wall-law tallies summed over all surfaces.
    pub tally: WallTally,
    /// Each surface's own tally (contacts, rebounds, captures, resting, energy by
    /// mechanism), in id order as [`RoomPoint::maps`]: what each material did.
    pub tallies: Vec<WallTally>,
    /// Deposition maps, one per surface in id order (floor, ceiling, x0, x1, y0, y1, then the
    /// furnishings' faces), each on a [`MAP_BINS`] grid over the surface's two in-plane axes in
    /// the order x, y, z (rows, columns): the floor's over x and y, the `x0`/`x1` walls' over
    /// y and z; a furnishing face's over the box's extent.
    pub maps: Vec<Vec<u32>>,
    /// Deposited count and mass (kg) of the tracked particles over the whole run onto the
    /// room's floor, ceiling and vertical walls (the furnishings' faces are in `furnishings`):
    /// with those and `balance`'s exhausted and airborne, the whole release, exactly.
    pub deposited: [(usize, f64); 3],
    /// Deposited count and mass (kg) of the tracked particles over the whole run onto each
    /// vertical wall (`x0`, `x1`, `y0`, `y1`): together `deposited`'s walls.
    pub wall_deposited: [(usize, f64); 4],
    /// Each furnishing's deposition figures, in the order of [`Scene::furnishings`].
    pub furnishings: Vec<FurnishingPoint>,
    /// All surfaces' area over the air's volume, 1/m ([`Scene::surface_to_volume`]).
    pub surface_to_volume: f64,
    /// The airborne share of the release over the run ([`DECAY_INTERVALS`] intervals; see
    /// [`crate::decay`]).
    pub decay: DecayCurve,
    /// The loss rate fitted to it as decay experiments fit theirs, and `beta` from it with
    /// the air-exchange rate taken off; `None` when fewer than 3 sample times qualify.
    pub decay_fit: Option<DecayFit>,
    /// Where the tracked particles are at the end of the run (with ventilation, the exhausted
    /// ones too): the mass balance a size distribution's is summed from.
    pub balance: Balance,
    /// The start of this size's averaging window, s: the study's, or 0 where every particle
    /// had left the air before it opened (fast-settling sizes), whose figures are then over
    /// the release from its start: what became of it, not a well-mixed room's steady rates.
    pub averaged_from: f64,
    /// When half and when nine tenths of the released particles had deposited, s; `None`
    /// where the run ended first.
    pub deposited_by: [Option<f64>; 2],
    /// The steady state under a continuous source of this size ([`crate::steady`]); `None`
    /// where nothing removes the particles.
    pub steady: Option<SteadyState>,
    /// With ventilation, the steady indoor/outdoor ratio from it: the entering outdoor
    /// particles' rate times their mean residence time.
    pub steady_indoor_outdoor: Option<Estimate>,
}

/// The time by which `share` of `records` had deposited, s; `None` if they never did.
fn deposited_by(records: &[crate::tracking::Record], share: f64) -> Option<f64> {
    let mut times: Vec<f64> =
        records.iter().filter(|r| matches!(r.fate, crate::tracking::Fate::Deposited(_))).map(|r| r.time).collect();
    let needed = (share * records.len() as f64).ceil() as usize;
    if needed == 0 || times.len() < needed {
        return None;
    }
    times.sort_by(f64::total_cmp);
    Some(times[needed - 1])
}

/// One furnishing's figures in a room study.
#[derive(Clone, Debug, PartialEq)]
pub struct FurnishingPoint {
    /// Its name ([`Furnishing::label`](crate::Furnishing::label)).
    pub name: String,
    /// The area of its faces, m^2.
    pub area: f64,
    /// Deposition velocity onto all its faces together, m/s.
    pub all: Estimate,
    /// Onto each face, in face order (bottom, top, x0, x1, y0, y1), m/s.
    pub faces: [Estimate; 6],
    /// Onto its four vertical faces together, m/s.
    pub sides: Estimate,
    /// Deposited count and mass (kg) over the whole run, on all its faces.
    pub deposited: (usize, f64),
    /// Deposited count and mass (kg) per face.
    pub face_deposited: [(usize, f64); 6],
}

/// The id of a room's first vertical wall, `x0`; `x1`, `y0` and `y1` follow it (see
/// [`crate::geometry`]).
const FIRST_WALL: usize = 2;

/// The deposition maps' grid.
pub const MAP_BINS: [usize; 2] = [20, 20];

/// A room study's error in its own terms: its particles' sizes are the list `particles.diameters`.
fn for_diameters(mut e: SceneError) -> SceneError {
    if e.field == "particles.diameter" {
        e.field = "particles.diameters".into();
    }
    e
}

fn total(tallies: &[WallTally]) -> WallTally {
    let mut sum = WallTally::default();
    for t in tallies {
        sum += *t;
    }
    sum
}

impl RoomStudy {
    /// The figures a size must resolve in `run`: `beta`, and each orientation of the room's
    /// walls where Lai & Nazaroff give at least [`RESOLVED_FROM`]; each with the
    /// [`crossing_class`]es of the surfaces it counts.
    fn resolved_figures(run: &Run, model: &LaiNazaroff) -> Vec<(Estimate, [bool; CROSSING_CLASSES])> {
        let mut figures = vec![(run.loss_rate(), [true; CROSSING_CLASSES])];
        for (orientation, reference) in
            [(Orientation::Floor, model.floor), (Orientation::Ceiling, model.ceiling), (Orientation::Wall, model.wall)]
        {
            if reference >= RESOLVED_FROM {
                let walls = run.walls_facing(orientation);
                let onto = std::array::from_fn(|c| walls.iter().any(|&w| crossing_class(w) == c));
                figures.push((run.deposition_velocity(&walls), onto));
            }
        }
        figures
    }

    /// The particles a size needs for its figures to reach `target` ([`RoomStudy::target_error`]),
    /// from the errors of `first`'s: at least the particles already run, at most `max_count`.
    fn needed(&self, first: &Run, model: &LaiNazaroff, target: f64) -> usize {
        let n = first.records.len();
        let figures = Self::resolved_figures(first, model);
        let needed = figures.iter().map(|(e, _)| particles_for(e, n, target)).max().unwrap_or(n);
        needed.clamp(n, self.max_count.max(n))
    }

    /// The particles to run for `target` (about `needed`, at most `max_count`) and the
    /// sampling multipliers per class of crossing for those after `first`, the first
    /// particles, all run at the full sampling
    /// ([`allocation::plan`]): from the first particles' figures and steps, with
    /// [`TARGET_MARGIN`] for the spread of their errors.
    fn plan(&self, first: &Run, model: &LaiNazaroff, needed: usize, target: f64) -> (usize, [f64; CROSSING_CLASSES]) {
        let figures: Vec<_> =
            Self::resolved_figures(first, model).iter().map(|(e, onto)| Figure::of(first, e, *onto)).collect();
        let tracked = first.records.iter().map(|r| r.steps as f64).sum();
        let steps = std::array::from_fn(|c| first.particles.iter().map(|p| p.class_steps[c] as f64).sum());
        let n = first.records.len();
        allocation::plan(&figures, (tracked, steps), n, (needed, self.max_count.max(n)), (target, TARGET_MARGIN))
    }

    /// `first`, a run of `scene` with the first particles, carried on until its figures reach
    /// `target` or `max_count` particles have run: in up to [`ROUNDS`] rounds, each but the
    /// last to at most [`ROUND_GROWTH`] times the particles run, as the
    /// [`RoomStudy::target_error`] says. The errors of the first particles, which rest on
    /// fewer deposits, are rough, and later rounds stop where every figure is resolved rather
    /// than at what those said. The cuts are planned once, from the first particles, which
    /// all ran at the full sampling, and set in `scene`.
    fn resolve(
        &self,
        scene: &mut Scene,
        injection: &Injection,
        model: &LaiNazaroff,
        target: f64,
        first: Run,
    ) -> Result<Run, SceneError> {
        let mut result = first;
        let mut have = injection.count;
        for round in 0..ROUNDS {
            if round > 0 && Self::resolved_figures(&result, model).iter().all(|(e, _)| resolved(e, target)) {
                break;
            }
            let mut needed = self.needed(&result, model, target);
            if needed <= have {
                break;
            }
            if round == 0 {
                let (planned, sampling) = self.plan(&result, model, needed, target);
                if let Some(excursions) = scene.excursions.as_mut() {
                    excursions.class_sampling = sampling;
                }
                needed = planned;
            } else if round + 1 < ROUNDS {
                needed = topped_up(have, needed);
            }
            have = if round + 1 < ROUNDS { needed.min(have * ROUND_GROWTH) } else { needed };
            result = run_more(scene, &Injection { count: have, ..*injection }, result)?;
        }
        Ok(result)
    }

    /// Runs every size; `progress` is told after each.
    pub fn run(&self, mut progress: impl FnMut(usize)) -> Result<Vec<RoomPoint>, SceneError> {
        if !(0.0..=1.0).contains(&self.penetration) {
            return Err(SceneError::new("penetration", self.penetration, "must be in [0, 1]"));
        }
        self.filtration.validate()?;
        if !self.scene.openings.is_empty() && self.filtration.recirculation > 0.0 {
            // Its removal acts wherever particles are, as the uniform exhaust does, which
            // openings replace.
            return Err(SceneError::new(
                "recirculation",
                self.filtration.recirculation,
                "must be 0 with openings: a recirculation filter is not modelled beside them",
            ));
        }
        let u_star = self.scene.flow.friction_velocity().unwrap_or(0.0);
        let g = self.scene.gravity.iter().map(|g| g * g).sum::<f64>().sqrt();
        let size = self.scene.geometry.size();
        let mut points = Vec::new();
        for (i, &d) in self.diameters.iter().enumerate() {
            let injection = Injection::new(self.count, SizeDistribution::Monodisperse { diameter: d }, self.density);
            let mut plain = self.scene.clone();
            plain.average_from = self.transient * plain.steps() as f64 * plain.dt;
            plain.air_exchange += self.filtration.removal(d);
            let model = LaiNazaroff::new(d, self.density, &self.scene.air, g, u_star);
            // Excursions down to 0.05 wall units (75 um at u* = 1 cm/s), inside the Brownian
            // sublayer of every size, calibrated by a pilot of a quarter of the first
            // particles; given up after `ROOM_LONGEST_EXCURSION`, twice as long while the
            // pilot gives up too much of their weight, and again, the size started afresh,
            // while the whole run does: the share given up rests on rare branches that hover
            // long, and a pilot's few particles can miss them.
            let most = ROOM_LONGEST_EXCURSION * f64::from(1u32 << LONGEST_DOUBLINGS);
            let mut longest = ROOM_LONGEST_EXCURSION;
            let mut calibration_seconds = 0.0;
            let (scene, result) = loop {
                // A wall function counts expected deposits itself: no excursions.
                let (mut scene, duration) = if self.excursions && self.scene.wall_function.is_none() {
                    let pilot = (self.count / PILOT.0).max(1);
                    let (scene, duration, seconds) =
                        with_excursions(plain.clone(), &injection, pilot, 0.05, (longest, most), 16, None, 1)
                            .map_err(for_diameters)?;
                    calibration_seconds += seconds;
                    (scene, duration)
                } else {
                    (plain.clone(), most)
                };
                let start = std::time::Instant::now();
                let mut result = run(&scene, &injection).map_err(for_diameters)?;
                if let Some(target) = self.target_error {
                    result = self.resolve(&mut scene, &injection, &model, target, result)?;
                }
                match lengthened(duration, result.truncated_share(), most) {
                    Some(longer) if scene.excursions.is_some() => {
                        calibration_seconds += start.elapsed().as_secs_f64();
                        longest = longer;
                    }
                    _ => break (scene, result),
                }
            };
            // Every particle gone before the window opened (they settle within it): the size
            // is run again, plainly, averaged over the release from its start.
            let exposure: f64 = result.particles.iter().map(|p| p.exposure).sum();
            let (scene, result) = if exposure > 0.0 {
                (scene, result)
            } else {
                let mut from_release = plain.clone();
                from_release.average_from = 0.0;
                let result = run(&from_release, &injection).map_err(for_diameters)?;
                (from_release, result)
            };
            let v = |o| result.deposition_velocity(&result.walls_facing(o));
            let balance = result.balance();
            let beta = result.loss_rate();
            // The outdoor air exchange (the openings' with openings); the scene's exhaust adds
            // the recirculation filter's removal to it, and the decay fit takes both off.
            let a = self.scene.exchange_rate();
            let f = &self.filtration;
            let indoor_outdoor = (a > 0.0).then(|| {
                let ratio = f.indoor_outdoor(d, a, self.penetration, beta.value);
                let slope = f.indoor_outdoor_slope(d, a, self.penetration, beta.value).abs();
                Estimate {
                    value: ratio,
                    error: slope * beta.error,
                    events: beta.events,
                    upper_bound: (ratio + 2.0 * slope * beta.error).min(f.indoor_outdoor(d, a, self.penetration, 0.0)),
                }
            });
            // The late rates (1/s) at which an airborne particle ends in each steady fate.
            let late = |surfaces: &[usize]| {
                let area: f64 = surfaces.iter().map(|&w| result.walls[w].area).sum();
                let v = result.deposition_velocity(surfaces).value;
                if area > 0.0 && v.is_finite() {
                    v * area / result.volume
                } else {
                    0.0
                }
            };
            let furnished: Vec<usize> = result.walls.iter().filter(|w| w.furnishing.is_some()).map(|w| w.id).collect();
            let lambda = [
                late(&result.walls_facing(Orientation::Floor)),
                late(&result.walls_facing(Orientation::Ceiling)),
                late(&result.walls_facing(Orientation::Wall)),
                late(&furnished),
                scene.exchange_rate(),
            ];
            let steady = SteadyState::from_release(&result, lambda);
            let steady_indoor_outdoor = steady.filter(|_| a > 0.0).map(|s| {
                let q = f.entering(d, a, self.penetration);
                Estimate {
                    value: q * s.residence.value,
                    error: q * s.residence.error,
                    events: s.residence.events,
                    upper_bound: f64::NAN,
                }
            });
            let decay = result.decay_curve(DECAY_INTERVALS);
            let decay_fit = result.decay_fit(&decay, scene.exchange_rate());
            points.push(RoomPoint {
                diameter: d,
                floor: v(Orientation::Floor),
                ceiling: v(Orientation::Ceiling),
                walls: v(Orientation::Wall),
                each_wall: std::array::from_fn(|k| result.deposition_velocity(&[FIRST_WALL + k])),
                beta,
                indoor_outdoor,
                filter_removal: f.removal(d),
                model,
                model_beta: model.loss_rate(size),
                particle_steps: result.particle_steps(),
                particles: result.records.len(),
                excursions: scene.excursions.as_ref().map(|_| result.truncated_share()),
                longest_excursion: scene.excursions.as_ref().map(|e| e.max_duration),
                class_sampling: scene.excursions.as_ref().map(|e| e.class_sampling),
                calibration_seconds,
                tally: total(&result.tallies),
                tallies: result.tallies.clone(),
                maps: result
                    .walls
                    .iter()
                    .map(|w| match w.furnishing {
                        None => result.deposition_map(w.id, size, MAP_BINS),
                        Some(k) => {
                            let b = &scene.furnishings[k];
                            result.deposition_map_within(w.id, b.low, b.high, MAP_BINS)
                        }
                    })
                    .collect(),
                furnishings: scene
                    .furnishings
                    .iter()
                    .enumerate()
                    .map(|(k, b)| {
                        let faces = result.furnishing_faces(k);
                        let face_deposited: [(usize, f64); 6] =
                            std::array::from_fn(|f| (balance.deposited[faces[f]], balance.deposited_mass[faces[f]]));
                        FurnishingPoint {
                            name: b.label(k),
                            area: b.area(),
                            all: result.deposition_velocity(&faces),
                            faces: std::array::from_fn(|f| result.deposition_velocity(&faces[f..=f])),
                            sides: result.deposition_velocity(&faces[2..]),
                            deposited: face_deposited.iter().fold((0, 0.0), |(n, m), &(dn, dm)| (n + dn, m + dm)),
                            face_deposited,
                        }
                    })
                    .collect(),
                surface_to_volume: result.surface_to_volume(),
                deposited: [Orientation::Floor, Orientation::Ceiling, Orientation::Wall].map(|o| {
                    result
                        .walls_facing(o)
                        .iter()
                        .fold((0, 0.0), |(n, m), &w| (n + balance.deposited[w], m + balance.deposited_mass[w]))
                }),
                wall_deposited: std::array::from_fn(|k| {
                    (balance.deposited[FIRST_WALL + k], balance.deposited_mass[FIRST_WALL + k])
                }),
                decay,
                decay_fit,
                balance,
                averaged_from: scene.average_from,
                deposited_by: [0.5, 0.9].map(|share| deposited_by(&result.records, share)),
                steady,
                steady_indoor_outdoor,
            });
            progress(i + 1);
        }
        Ok(points)
    }
}

/// A channel study: one run per `tau+` in a turbulent channel.
#[derive(Clone, Debug, PartialEq)]
pub struct ChannelStudy {
    /// The channel, its air, flow (a [`Flow::TurbulentChannel`]), walls and time stepping.
    pub scene: Scene,
    /// Dimensionless relaxation times `tau+ = tau u*^2 / nu`.
    pub tau_plus: Vec<f64>,
    /// Particles per `tau+`.
    pub count: usize,
    /// Particle density, kg/m^3.
    pub density: f64,
    /// Share of the run left out of the averages, in `[0, 1)`.
    pub transient: f64,
    /// Count deposits by near-wall excursions below this `tau+` (10 by default: above it
    /// deposition is frequent and plain tracking resolves it faster).
    pub excursions_below: f64,
    /// Particles per `tau+` where excursions count the deposits (each costs far more than a
    /// plainly tracked one).
    pub excursion_count: usize,
    /// The relative standard error to resolve each `V+` to. When the first particles (`count`
    /// or `excursion_count`) leave it less resolved, as many more are run (and pooled with
    /// them) as its error, falling as `1 / sqrt(n)`, says it needs, times [`TARGET_MARGIN`],
    /// provided that is at most `max_factor` times the first particles, and once more the
    /// same way if the pooled error is still above the target; a `tau+` that would need more
    /// keeps what it ran, and its printed error says how far it is. `None`: the
    /// first particles, whatever the errors.
    pub target_error: Option<f64>,
    /// The most particles per `tau+` with `target_error`, as a multiple of its first ones.
    pub max_factor: f64,
}

impl Default for ChannelStudy {
    /// A channel of `Re_tau = 150` (`u* = 0.3 m/s`, height 15 mm in standard air), no gravity
    /// (the correlations are for vertical flows), Brownian motion, absorbing walls, particles
    /// of 1000 kg/m^3, steps of 0.2 and runs of 3000 wall time units, averages over the second
    /// half; 1000 particles per `tau+` with excursions (below 10) and 4000 without, and up to
    /// eight times as many where `V+` needs them for a 5 % error (in up to two rounds).
    fn default() -> Self {
        let air = Air::standard();
        let u_star = 0.3;
        let unit = air.kinematic_viscosity() / u_star;
        let time = unit / u_star;
        let mut scene = Scene::new(
            Geometry::Channel { length: 1000.0 * unit, width: 300.0 * unit, height: 300.0 * unit },
            0.2 * time,
            3000.0 * time,
        );
        scene.gravity = [0.0; 3];
        scene.flow = Flow::TurbulentChannel { friction_velocity: u_star };
        scene.brownian = true;
        Self {
            scene,
            tau_plus: vec![0.1, 0.3, 1.0, 3.0, 10.0, 30.0, 100.0],
            count: 4000,
            density: 1000.0,
            transient: 0.5,
            excursions_below: 10.0,
            excursion_count: 1000,
            target_error: Some(TARGET_ERROR),
            max_factor: 8.0,
        }
    }
}

/// One `tau+` of a channel study.
#[derive(Clone, Debug, PartialEq)]
pub struct ChannelPoint {
    /// `tau+`.
    pub tau_plus: f64,
    /// The particle diameter giving it, m.
    pub diameter: f64,
    /// Schmidt number `nu / D`.
    pub schmidt: f64,
    /// Dimensionless deposition velocity `V+ = v_d / u*`.
    pub v_plus: Estimate,
    /// Wood (1981) at this `tau+` and `Sc`.
    pub wood: f64,
    /// Papavergos & Hedley (1984).
    pub papavergos_hedley: f64,
    /// Particle-steps the run took (of the tracked particles; excursions not included).
    pub particle_steps: u64,
    /// Particles run (more than the first ones where [`ChannelStudy::target_error`] needed
    /// them).
    pub particles: usize,
    /// Whether deposits were counted by near-wall excursions, and if so the share of their
    /// weight given up at their longest duration ([`Run::truncated_share`](crate::Run::truncated_share)).
    pub excursions: Option<f64>,
    /// Wall-clock time of the excursions' pilot calibration, s (0 without excursions): a
    /// cost fixed per run, which does not grow with the particles run.
    pub calibration_seconds: f64,
    /// Whether the excursions also caught strong sweeps before the layer
    /// ([`Excursions::sweeps`]; from [`CHANNEL_SWEEPS_FROM`]).
    pub sweeps: bool,
    /// The wall-law tallies summed over both walls.
    pub tally: WallTally,
    /// With a wall function: the concentration in its layers over the mean, `C_w / C`, which
    /// the deposition velocity is proportional to (1 where the layers hold the bulk
    /// concentration the correlation is defined against; [`crate::wall_function`]).
    pub layer_concentration: Option<Estimate>,
}

impl ChannelStudy {
    /// Runs every `tau+`; `progress` is told after each.
    pub fn run(&self, mut progress: impl FnMut(usize)) -> Result<Vec<ChannelPoint>, SceneError> {
        let u_star = self.scene.flow.friction_velocity().unwrap_or(1.0);
        let air = &self.scene.air;
        let mut points = Vec::new();
        for (i, &tp) in self.tau_plus.iter().enumerate() {
            let d = diameter_for_tau_plus(tp, self.density, air, u_star).ok_or_else(|| {
                SceneError::new("particles.tau_plus", tp, "needs a particle diameter outside 0.1 nm to 1 cm here")
            })?;
            // A wall function counts expected deposits itself: no excursions.
            let excursions = tp < self.excursions_below && self.scene.wall_function.is_none();
            let count = if excursions { self.excursion_count } else { self.count };
            let injection = Injection::new(count, SizeDistribution::Monodisperse { diameter: d }, self.density);
            let mut scene = self.scene.clone();
            scene.average_from = self.transient * scene.steps() as f64 * scene.dt;
            let mut calibration_seconds = 0.0;
            if excursions {
                // Factors up to 4 (larger ones made the deep branches, which live long in
                // the Brownian sublayer, too many: 3-5 times the run time for the same error).
                let pilot = (count / PILOT.0).max(1);
                let sweeps = (tp >= CHANNEL_SWEEPS_FROM).then_some(CHANNEL_SWEEPS);
                let (inner, longest) = (CHANNEL_INNERMOST_LEVEL, CHANNEL_LONGEST_EXCURSION);
                // Without sweeps the branches hover in the viscous sublayer: coarse steps there.
                let coarse = if sweeps.is_some() { 1 } else { CHANNEL_COARSE_FACTOR };
                (scene, _, calibration_seconds) =
                    with_excursions(scene, &injection, pilot, inner, (longest, longest), 4, sweeps, coarse)?;
            }
            let all_walls = |r: &Run| r.deposition_velocity(&(0..r.walls.len()).collect::<Vec<_>>());
            let mut result = run(&scene, &injection)?;
            if let Some(target) = self.target_error {
                // Two rounds: the second where the pooled estimate still misses the target (an
                // error that rests on rare events is itself rough from the first particles).
                let mut have = count;
                for round in 0..2 {
                    let e = all_walls(&result);
                    if round > 0 && resolved(&e, target) {
                        break;
                    }
                    let needed = particles_for(&e, have, target);
                    if needed <= have || needed as f64 > self.max_factor * count as f64 {
                        break;
                    }
                    result = run_more(&scene, &Injection { count: needed, ..injection }, result)?;
                    have = needed;
                }
            }
            let v = all_walls(&result);
            let sc = schmidt(d, air);
            let layer_concentration = scene.wall_function.map(|wf| {
                let layer = wf.layer(air, u_star);
                result.layer_concentration(result.walls.iter().map(|w| w.area * layer).sum())
            });
            points.push(ChannelPoint {
                tau_plus: tp,
                diameter: d,
                schmidt: sc,
                v_plus: Estimate {
                    value: v.value / u_star,
                    error: v.error / u_star,
                    events: v.events,
                    upper_bound: v.upper_bound / u_star,
                },
                wood: wood(tp, sc),
                papavergos_hedley: papavergos_hedley(tp, sc),
                particle_steps: result.particle_steps(),
                particles: result.records.len(),
                excursions: scene.excursions.as_ref().map(|_| result.truncated_share()),
                calibration_seconds,
                sweeps: scene.excursions.as_ref().is_some_and(|e| e.sweeps.is_some()),
                tally: total(&result.tallies),
                layer_concentration,
            });
            progress(i + 1);
        }
        Ok(points)
    }
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
/// the pooled figures' spread is what they showed, and only the added particles' is unknown.
/// In the furnished, ventilated room at 0.1 um, whose worst figure was 5.6 % after 4000
/// particles, the margin on all ran 5772 to 4.6 %, on the added ones 5173 to 4.9 %. At
/// least one more.
#[must_use]
pub fn topped_up(have: usize, needed: usize) -> usize {
    let bare = needed as f64 / TARGET_MARGIN;
    let more = ((bare - have as f64) * TARGET_MARGIN).ceil().max(1.0);
    (have + more as usize).min(needed.max(have + 1))
}

#[cfg(test)]
mod tests {
    use super::*;

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
        let mut scene = RoomStudy::default().scene;
        scene.duration = 300.0;
        scene.average_from = 30.0;
        let injection = Injection::new(100, SizeDistribution::Monodisperse { diameter: 0.3e-6 }, 1000.0);
        let unit = scene.air.kinematic_viscosity() / 1e-4; // nu / u*^2, s
        let longest = |base: f64, lengthen: bool| {
            let most = if lengthen { 8.0 * base } else { base };
            let (scene, ..) = with_excursions(scene.clone(), &injection, 100, 0.05, (base, most), 16, None, 1).unwrap();
            let max_duration = scene.excursions.as_ref().unwrap().max_duration;
            let share = run(&Scene { seed: 7, ..scene.clone() }, &injection).unwrap().truncated_share();
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
