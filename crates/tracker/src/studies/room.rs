//! The room study: one run per particle size in a room, beside Lai & Nazaroff (2000) (see
//! [`super::study`] for what both studies share).

use crate::estimation::allocation::{self, Figure};
use crate::estimation::decay::{DecayCurve, DecayFit, DECAY_INTERVALS};
use crate::estimation::maps::FluxMap;
use crate::estimation::run::{run, run_more, Balance, Estimate, Run};
use crate::model::error::SceneError;
use crate::model::excursions::{crossing_class, CROSSING_CLASSES};
use crate::model::flow::Flow;
use crate::model::geometry::{Geometry, Orientation};
use crate::model::scene::{Injection, Scene, SizeDistribution};
use crate::model::settings::{RunSettings, Scheme};
use crate::physics::correlations::LaiNazaroff;
use crate::studies::filtration::Filtration;
use crate::studies::steady::{near_floor, near_floor_volume, Source, SteadyState};
use crate::tracking::WallTally;

use crate::studies::study::*;

/// A room study: one run per diameter in `scene` (a room with a turbulent-room flow).
#[derive(Clone, Debug, PartialEq)]
pub struct RoomStudy {
    /// The room, its air, flow and walls.
    pub scene: Scene,
    /// How each size is run: time step, scheme, duration and seed. The study sets the
    /// averaging window from `transient`, and with `excursions` the excursions.
    pub settings: RunSettings,
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
    /// Where the continuous source of the steady state ([`RoomPoint::steady`]) enters;
    /// `None` (the default): spread over the room, as infiltration where the room is
    /// ventilated (with its indoor/outdoor ratio) and as an indoor source where it is not.
    pub source: Option<Source>,
}

impl Default for RoomStudy {
    /// A 4 m x 3 m x 2.5 m room, `u* = 1 cm/s` with a well-mixed core ([`Flow::indoor_room`]),
    /// Brownian motion, perfectly absorbing surfaces (as Lai & Nazaroff assume), 0.01-10 um
    /// unit-density particles, 1800 s of 0.1 s steps of the midpoint scheme, averages from
    /// 180 s on. The midpoint scheme ([`Scheme::Midpoint`]) at 0.1 s gives `beta` within the
    /// errors of the default scheme at 0.01 s, where the default scheme at longer steps is
    /// biased high, in about the same run time (docs/validation.md, "The time step").
    fn default() -> Self {
        let mut scene = Scene::new(Geometry::Room { size: [4.0, 3.0, 2.5] });
        scene.flow = Flow::indoor_room();
        scene.brownian = true;
        Self {
            scene,
            settings: RunSettings { scheme: Scheme::Midpoint, ..RunSettings::new(0.1, 1800.0) },
            diameters: vec![0.01e-6, 0.03e-6, 0.1e-6, 0.3e-6, 1e-6, 3e-6, 10e-6],
            count: 1000,
            target_error: Some(TARGET_ERROR),
            max_count: 8000,
            density: 1000.0,
            transient: 0.1,
            excursions: true,
            penetration: 1.0,
            filtration: Filtration::default(),
            source: None,
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
    /// With excursions, their longest duration
    /// ([`Excursions::max_duration`](crate::model::excursions::Excursions::max_duration)), s:
    /// [`ROOM_LONGEST_EXCURSION`], doubled while the pilot or the whole run gave up more than
    /// [`LONGEST_SHARE`] of the weight ([`lengthened`]).
    pub longest_excursion: Option<f64>,
    /// With excursions, the multipliers of their sampling per class of crossing (floor, ceiling,
    /// walls, furnishings;
    /// [`Excursions::class_sampling`](crate::model::excursions::Excursions::class_sampling)) that
    /// the particles after the first ran with: 1 where the study cut none, or ran no more
    /// particles.
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
    /// Each surface's deposition velocity per cell from the run's own estimator (the weighted
    /// deposits and exposure of the averaging window, as `floor`, `ceiling`, `walls` and
    /// `furnishings` count them), on the grid [`Run::resolved_flux_map`] chooses, in id order
    /// as `maps`; `None` for the wall function's walls (their deposits have no place).
    pub flux_maps: Vec<Option<FluxMap>>,
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
    /// Where `decay_fit` has no fit (every particle gone before the window, or too soon for
    /// its sample times): the release's decay fitted from `t = 0` on a curve of its own time
    /// scale ([`Run::release_decay`]), its window and rate.
    pub release_fit: Option<DecayFit>,
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
    /// The steady state under a continuous source of this size entering where
    /// [`RoomStudy::source`] says ([`crate::steady`]); `None` where nothing removes the
    /// particles.
    pub steady: Option<SteadyState>,
    /// For a source of outdoor air (infiltration, a supply opening, or the default source in
    /// a ventilated room), the steady indoor/outdoor ratio from it: the entering outdoor
    /// particles' rate times their mean residence time.
    pub steady_indoor_outdoor: Option<Estimate>,
    /// The steady near-floor concentration over the room's mean under a source spread over
    /// the room ([`SteadyState::near_floor`]), whatever [`RoomStudy::source`]: above
    /// [`NOT_WELL_MIXED`](crate::steady::NOT_WELL_MIXED) the room is not well mixed for this
    /// size. `None` where the particles had no time in the air.
    pub near_floor: Option<Estimate>,
}

/// The time by which `share` of `records` had deposited, s; `None` if they never did.
pub(crate) fn deposited_by(records: &[crate::tracking::Record], share: f64) -> Option<f64> {
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
pub(crate) const FIRST_WALL: usize = 2;

/// The deposition maps' grid.
pub const MAP_BINS: [usize; 2] = [20, 20];

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

    /// `first`, a run of `scene` with `settings` and the first particles, carried on until its figures reach
    /// `target` or `max_count` particles have run: in up to [`ROUNDS`] rounds, each but the
    /// last to at most [`ROUND_GROWTH`] times the particles run, as the
    /// [`RoomStudy::target_error`] says. The errors of the first particles, which rest on
    /// fewer deposits, are rough, and later rounds stop where every figure is resolved rather
    /// than at what those said. The cuts are planned once, from the first particles, which
    /// all ran at the full sampling, and set in `settings`.
    fn resolve(
        &self,
        scene: &Scene,
        settings: &mut RunSettings,
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
                if let Some(excursions) = settings.excursions.as_mut() {
                    excursions.class_sampling = sampling;
                }
                needed = planned;
            } else if round + 1 < ROUNDS {
                needed = topped_up(have, needed);
            }
            have = if round + 1 < ROUNDS { needed.min(have * ROUND_GROWTH) } else { needed };
            result = run_more(scene, settings, &Injection { count: have, ..*injection }, result)?;
        }
        Ok(result)
    }

    /// Whether the steady state's source brings outdoor particles in (its indoor/outdoor ratio
    /// exists): infiltration and a supply opening do, an indoor source does not, and the
    /// default does where the room is ventilated. An error names `source.enters` where
    /// infiltration has no ventilation, or a supply no supply opening.
    fn source_is_outdoor(&self) -> Result<bool, SceneError> {
        let a = self.scene.exchange_rate();
        match self.source {
            None => Ok(a > 0.0),
            Some(Source::Indoor(_)) => Ok(false),
            Some(Source::Infiltration) if a > 0.0 => Ok(true),
            Some(Source::Infiltration) => Err(SceneError::new(
                "source.enters",
                a,
                "is infiltration, which needs ventilation: an air-exchange rate or openings",
            )),
            Some(Source::Supply(k)) => {
                let size = self.scene.geometry.size();
                let probe = Injection::new(1, SizeDistribution::Monodisperse { diameter: 1e-6 }, self.density);
                Source::Supply(k).injection(probe, size, &self.scene.openings).map(|_| true)
            }
        }
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
        let outdoor = self.source_is_outdoor()?;
        let floor_volume = near_floor_volume(size, &self.scene.furnishings);
        let mut points = Vec::new();
        for (i, &d) in self.diameters.iter().enumerate() {
            let injection = Injection::new(self.count, SizeDistribution::Monodisperse { diameter: d }, self.density);
            let mut plain = self.scene.clone();
            plain.air_exchange += self.filtration.removal(d);
            let mut plain_settings = self.settings.clone();
            plain_settings.average_from = self.transient * plain_settings.steps() as f64 * plain_settings.dt;
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
            let (settings, result) = loop {
                // A wall function counts expected deposits itself: no excursions.
                let (mut settings, duration) = if self.excursions && self.scene.wall_function.is_none() {
                    let pilot = (self.count / PILOT.0).max(1);
                    let (settings, duration, seconds) = with_excursions(
                        &plain,
                        plain_settings.clone(),
                        &injection,
                        pilot,
                        0.05,
                        (longest, most),
                        16,
                        None,
                        1,
                    )
                    .map_err(for_diameters)?;
                    calibration_seconds += seconds;
                    (settings, duration)
                } else {
                    (plain_settings.clone(), most)
                };
                let start = std::time::Instant::now();
                let mut result = run(&plain, &settings, &injection).map_err(for_diameters)?;
                if let Some(target) = self.target_error {
                    result = self.resolve(&plain, &mut settings, &injection, &model, target, result)?;
                }
                match lengthened(duration, result.truncated_share(), most) {
                    Some(longer) if settings.excursions.is_some() => {
                        calibration_seconds += start.elapsed().as_secs_f64();
                        longest = longer;
                    }
                    _ => break (settings, result),
                }
            };
            // Every particle gone before the window opened (they settle within it): the size
            // is run again, plainly, averaged over the release from its start.
            let exposure: f64 = result.particles.iter().map(|p| p.exposure).sum();
            let (settings, result) = if exposure > 0.0 {
                (settings, result)
            } else {
                let mut from_release = plain_settings.clone();
                from_release.average_from = 0.0;
                let result = run(&plain, &from_release, &injection).map_err(for_diameters)?;
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
            // With its standard error and deposit events: (rate, error, events).
            let late = |surfaces: &[usize]| {
                let area: f64 = surfaces.iter().map(|&w| result.walls[w].area).sum();
                let v = result.deposition_velocity(surfaces);
                if area > 0.0 && v.value.is_finite() {
                    (v.value * area / result.volume, v.error * area / result.volume, v.events)
                } else {
                    (0.0, 0.0, 0)
                }
            };
            let furnished: Vec<usize> = result.walls.iter().filter(|w| w.furnishing.is_some()).map(|w| w.id).collect();
            let rates = [
                late(&result.walls_facing(Orientation::Floor)),
                late(&result.walls_facing(Orientation::Ceiling)),
                late(&result.walls_facing(Orientation::Wall)),
                late(&furnished),
                (plain.exchange_rate(), 0.0, 0),
            ];
            let (lambda, lambda_error, lambda_events) = (rates.map(|r| r.0), rates.map(|r| r.1), rates.map(|r| r.2));
            let spread = SteadyState::from_release(&result, lambda, lambda_error, lambda_events, floor_volume);
            // A source elsewhere than over the whole room: its own release, tracked plainly.
            let at_source = match self.source {
                Some(source) => source.injection(
                    Injection { count: result.records.len(), ..injection },
                    size,
                    &self.scene.openings,
                )?,
                None => None,
            };
            let steady = match at_source {
                Some(placed) => {
                    let mut from_source = plain_settings.clone();
                    from_source.average_from = 0.0;
                    let run = run(&plain, &from_source, &placed).map_err(for_diameters)?;
                    SteadyState::from_release(&run, lambda, lambda_error, lambda_events, floor_volume)
                }
                None => spread,
            };
            // The outdoor particles entering per second per outdoor concentration and unit volume.
            let entering = match self.source {
                Some(Source::Supply(k)) => {
                    (1.0 - f.supply_filter.at(d)) * self.scene.openings[k].flow / self.scene.free_volume()
                }
                _ => f.entering(d, a, self.penetration),
            };
            let steady_indoor_outdoor = steady.filter(|_| outdoor).map(|s| {
                let q = entering;
                Estimate {
                    value: q * s.residence.value,
                    error: q * s.residence.error,
                    events: s.residence.events,
                    upper_bound: f64::NAN,
                }
            });
            let decay = result.decay_curve(DECAY_INTERVALS);
            let decay_fit = result.decay_fit(&decay, plain.exchange_rate());
            let release_fit = match decay_fit {
                None => result.release_decay(DECAY_INTERVALS, plain.exchange_rate()).map(|(_, f)| f),
                Some(_) => None,
            };
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
                excursions: settings.excursions.as_ref().map(|_| result.truncated_share()),
                longest_excursion: settings.excursions.as_ref().map(|e| e.max_duration),
                class_sampling: settings.excursions.as_ref().map(|e| e.class_sampling),
                calibration_seconds,
                tally: total(&result.tallies),
                tallies: result.tallies.clone(),
                maps: result
                    .walls
                    .iter()
                    .map(|w| match w.furnishing {
                        None => result.deposition_map(w.id, size, MAP_BINS),
                        Some(k) => {
                            let b = &plain.furnishings[k];
                            result.deposition_map_within(w.id, b.low, b.high, MAP_BINS)
                        }
                    })
                    .collect(),
                flux_maps: result
                    .walls
                    .iter()
                    .map(|w| match w.furnishing {
                        None => result.resolved_flux_map(w.id, [0.0; 3], size),
                        Some(k) => {
                            let b = &plain.furnishings[k];
                            result.resolved_flux_map(w.id, b.low, b.high)
                        }
                    })
                    .collect(),
                furnishings: plain
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
                release_fit,
                balance,
                averaged_from: settings.average_from,
                deposited_by: [0.5, 0.9].map(|share| deposited_by(&result.records, share)),
                steady,
                steady_indoor_outdoor,
                near_floor: Some(near_floor(&result, floor_volume)).filter(|m| m.value.is_finite()),
            });
            progress(i + 1);
        }
        Ok(points)
    }
}
