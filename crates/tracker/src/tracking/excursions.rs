//! One subject, hence one file over 700 lines: a particle tracked with its near-wall excursions.
//!
//! Plain tracking with near-wall excursions ([`Excursions`]): each injected particle is
//! tracked as alone, and each of its entries into the excursions' region (an inward crossing
//! of the near-wall layer, or in a channel with [`Excursions::sweeps`] a strong sweep) starts
//! sampled excursions, whose branches (split toward the wall, rouletted on the way out) are
//! taken depth first. The order, and with it every random number, depends on the particle
//! alone.
//!
//! One subject, kept whole though long: the excursions' loop (its unit tests are a quarter
//! of it).

use glam::DVec3;
use rand::rngs::Xoshiro256PlusPlus;
use rand::RngExt;

use crate::model::excursions::{crossing_class, Excursions, CROSSING_CLASSES, FURNISHINGS_CLASS, MAX_LEVELS};
use crate::model::furnishing::Furnishing;
use crate::model::geometry::{greater, lesser};
use crate::physics::noise::{branch_rng, particle_rng, Normals};

use super::{normals_per_step, wall_distance, Body, Fate, Flyer, Prepared, Record, Step, WallTally};
use crate::tracking::MAX_STEP_GRADIENT;

/// What one injected particle contributed to a run's averaging window.
#[derive(Clone, Debug, PartialEq)]
pub struct ParticleTally {
    /// Airborne time within the averaging window, s.
    pub exposure: f64,
    /// Deposits within the averaging window, per wall id (the room's six walls, or a
    /// channel's two): the particle's own without excursions, its excursions' weighted
    /// deposits with them.
    pub deposited: [f64; 6],
    /// Deposit events behind `deposited`, per wall id (unweighted).
    pub events: [u32; 6],
    /// Deposits within the averaging window on furnishings' faces (surface ids 6 and up), as
    /// `deposited` and `events` count them on the walls: `(surface, weight, events)`, one
    /// entry per surface reached, in the order first reached (empty, without allocating, in a
    /// bare room). [`ParticleTally::deposited_on`] and [`ParticleTally::events_on`] read both.
    pub on_furnishings: Vec<(usize, f64, u32)>,
    /// Excursions started.
    pub excursions: u32,
    /// Weight of the excursions' branches given up at [`Excursions::max_duration`] while
    /// still in the layer (an upper bound on the deposits missed by giving them up; branches
    /// that left or deposited on their last step count too).
    pub truncated: f64,
    /// Weighted arrivals of the excursions' branches into each splitting level (index `k` for
    /// level `k + 1`), times the sampling probability: what
    /// [`Splitting::calibrated`](crate::Splitting::calibrated) reads.
    pub arrivals: [f64; MAX_LEVELS],
    /// Branches that arrived into each level (unweighted).
    pub branches: [u64; MAX_LEVELS],
    /// The excursions' steps by the [`crossing_class`] of the crossing that started them:
    /// where a study's excursions spend their work.
    pub class_steps: [u64; CROSSING_CLASSES],
    /// The deposits of `deposited` and `on_furnishings` by the [`crossing_class`] of the
    /// crossing whose excursion made them (first index) and of the surface they landed on
    /// (second index): what each class of crossing adds to each figure, and to its spread.
    pub class_deposits: [[f64; CROSSING_CLASSES]; CROSSING_CLASSES],
    /// With a wall function ([`crate::wall_function`]): airborne time within the averaging
    /// window spent in a wall's layer, s (0 otherwise): the layer's concentration over the
    /// mean is this over `exposure`, over the layers' share of the volume.
    pub layer_exposure: f64,
    /// Where the deposits of `deposited` and `on_furnishings` landed, one entry per deposit
    /// event in the order made (empty, without allocating, for a particle that deposits
    /// nothing in the window): what a deposition map of the run's estimator spreads over its
    /// cells ([`Run::flux_map`](crate::run::Run::flux_map)). The wall function's walls keep
    /// expected deposits without a place: their entries are left out.
    pub landed: Vec<Landed>,
}

/// One weighted deposit of a [`ParticleTally`] and where it landed: 24 bytes, since a
/// particle with excursions keeps one per deposit event.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Landed {
    /// The surface's id ([`Run::walls`](crate::run::Run::walls)).
    pub surface: u32,
    /// Where, m (single precision: a map's cells are far coarser).
    pub at: [f32; 3],
    /// Its weight, as `deposited` counts it.
    pub weight: f64,
}

impl Default for ParticleTally {
    fn default() -> Self {
        Self {
            exposure: 0.0,
            deposited: [0.0; 6],
            events: [0; 6],
            on_furnishings: Vec::new(),
            excursions: 0,
            truncated: 0.0,
            arrivals: [0.0; MAX_LEVELS],
            branches: [0; MAX_LEVELS],
            class_steps: [0; CROSSING_CLASSES],
            class_deposits: [[0.0; CROSSING_CLASSES]; CROSSING_CLASSES],
            layer_exposure: 0.0,
            landed: Vec::new(),
        }
    }
}

impl ParticleTally {
    /// The tally of a particle tracked without excursions, from its record: in the air from 0
    /// until `record.time`.
    pub(crate) fn of(record: &Record, window: [f64; 2]) -> Self {
        let mut t = Self { exposure: overlap(0.0, record.time, window), ..Self::default() };
        if let Fate::Deposited(w) = record.fate {
            if record.time >= window[0] && record.time <= window[1] {
                t.add_deposit(w, 1.0, record.position);
            }
        }
        t
    }

    /// A deposit of `weight` on surface `w` at `at` (m).
    #[inline]
    fn add_deposit(&mut self, w: usize, weight: f64, at: [f64; 3]) {
        if self.landed.capacity() == 0 {
            // Most particles deposit once at most: no room for more until a second.
            self.landed.reserve_exact(1);
        }
        self.landed.push(Landed { surface: w as u32, at: at.map(|x| x as f32), weight });
        if w < self.deposited.len() {
            self.deposited[w] += weight;
            self.events[w] += 1;
        } else if let Some(entry) = self.on_furnishings.iter_mut().find(|(s, ..)| *s == w) {
            entry.1 += weight;
            entry.2 += 1;
        } else {
            self.on_furnishings.push((w, weight, 1));
        }
    }

    /// Deposits within the averaging window on surface `w` (a wall, or a furnishing's face).
    #[must_use]
    pub fn deposited_on(&self, w: usize) -> f64 {
        match self.deposited.get(w) {
            Some(&d) => d,
            None => self.on_furnishings.iter().filter(|(s, ..)| *s == w).map(|e| e.1).sum(),
        }
    }

    /// Deposit events within the averaging window on surface `w` (unweighted).
    #[must_use]
    pub fn events_on(&self, w: usize) -> u32 {
        match self.events.get(w) {
            Some(&e) => e,
            None => self.on_furnishings.iter().filter(|(s, ..)| *s == w).map(|e| e.2).sum(),
        }
    }

    /// All deposits within the averaging window, on every surface.
    #[must_use]
    pub fn deposited_total(&self) -> f64 {
        self.deposited.iter().sum::<f64>() + self.on_furnishings.iter().map(|e| e.1).sum::<f64>()
    }
}

/// Length of `[a, b]` within `window`.
#[inline]
fn overlap(a: f64, b: f64, [from, to]: [f64; 2]) -> f64 {
    (b.min(to) - a.max(from)).max(0.0)
}

/// Distance from the surface of a particle of radius `r` at `x` to the nearest wall or box
/// of `boxes` (`p.boxes`, or those the particle's [`Clearance`](crate::model::furnishing::Clearance)
/// leaves), m (infinite in a domain without walls); a box's is the Euclidean distance from
/// `x` to it.
#[inline]
fn wall_gap(p: &Prepared<'_>, boxes: &[Furnishing], x: DVec3, r: f64) -> f64 {
    // Along an unwalled axis the bounds, and so the distances, are infinite.
    let across = |a: usize| lesser(x[a] - p.lower[a], p.upper[a] - x[a]);
    let mut gap = lesser(across(0), lesser(across(1), across(2)));
    // The boxes' squared distances, and a square root only where the nearest is nearer than
    // the walls (the same minimum: a root below `gap` needs a square at most `gap^2` rounded).
    let squared = boxes.iter().fold(f64::INFINITY, |s, b| lesser(s, b.squared_distance(x.to_array())));
    if squared <= gap * gap * (1.0 + 1e-12) {
        gap = lesser(gap, squared.sqrt());
    }
    gap - r
}

/// [`free_flight_gap`]'s part for box `b`: along each axis on which the particle lies
/// outside the box, the separation less the stop distance `tau v` of its velocity towards
/// the box; in front of a face (outside along one axis only) that, as for a wall; beyond an
/// edge or corner, the Euclidean norm of the separations left (none below zero).
#[cfg(test)]
fn box_free_flight_gap(b: &Furnishing, x: DVec3, v: DVec3, tau: f64) -> f64 {
    match box_free_flight_separation(b, x, v, tau) {
        Separation::Face(gap) => gap,
        Separation::Squared(squares) => squares.sqrt(),
    }
}

/// [`box_free_flight_gap`] before its square root.
enum Separation {
    /// In front of a face: the gap itself.
    Face(f64),
    /// Beyond an edge or corner: the gap squared.
    Squared(f64),
}

/// [`box_free_flight_gap`] as a [`Separation`], so that the nearest box takes one square
/// root rather than each box one.
#[inline]
fn box_free_flight_separation(b: &Furnishing, x: DVec3, v: DVec3, tau: f64) -> Separation {
    let (mut outside, mut single, mut squares) = (0, 0.0, 0.0);
    for a in 0..3 {
        let separation = if x[a] < b.low[a] {
            b.low[a] - x[a] - tau * v[a].max(0.0)
        } else if x[a] > b.high[a] {
            x[a] - b.high[a] + tau * v[a].min(0.0)
        } else {
            continue;
        };
        outside += 1;
        single = separation;
        squares += greater(separation, 0.0).powi(2);
    }
    if outside == 1 {
        Separation::Face(single)
    } else {
        Separation::Squared(squares)
    }
}

/// The gap a particle would have left after flying freely towards the nearest wall, m: for
/// each wall, its surface's distance less the stop distance `tau v` of its velocity towards
/// that wall; the smallest over the walls. This, rather than the plain distance, sets a
/// branch's splitting level: an inertial particle close to a wall and moving away from it is
/// far less likely to deposit than one coasting towards it.
///
/// The boxes farther than the layer beyond the particle's reach (`tau |v|`) are left out
/// where its [`Clearance`](crate::model::furnishing::Clearance) shows them to be: they could only
/// set a gap beyond the layer, whose splitting level, 0, is the walls' then too.
#[inline]
fn free_flight_gap(p: &Prepared<'_>, excursions: &Excursions, flyer: &Flyer) -> f64 {
    let (x, v, r, tau) = (flyer.x, flyer.v, flyer.body.contact, flyer.body.tau);
    // `|v|` bounded by the sum of its components' sizes.
    let reach = excursions.layer + r + tau * (v.x.abs() + v.y.abs() + v.z.abs());
    let boxes = flyer.clearance.near(p.boxes, x.to_array(), reach);
    // Along an unwalled axis the bounds, and so the gaps, are infinite.
    let across = |a: usize| {
        let lower = x[a] - p.lower[a] - r + tau * lesser(v[a], 0.0);
        let upper = p.upper[a] - x[a] - r - tau * greater(v[a], 0.0);
        lesser(lower, upper)
    };
    let mut gap = lesser(across(0), lesser(across(1), across(2)));
    let mut squared = f64::INFINITY;
    for b in boxes {
        match box_free_flight_separation(b, x, v, tau) {
            Separation::Face(face) => gap = lesser(gap, face - r),
            Separation::Squared(squares) => squared = lesser(squared, squares),
        }
    }
    // A root only where an edge or corner may be the nearest (as in `wall_gap`).
    let bound = gap + r;
    if bound > 0.0 && squared <= bound * bound * (1.0 + 1e-12) {
        gap = lesser(gap, squared.sqrt() - r);
    }
    gap
}

/// The [`crossing_class`] of the surface nearest `x`: the nearest of the room's (or a
/// channel's) walls, or a furnishing's face where a box is nearer.
fn nearest_class(p: &Prepared<'_>, x: DVec3) -> usize {
    let mut nearest = (2, f64::INFINITY);
    for w in &p.walls {
        let gap = if w.upper { w.position - x[w.axis] } else { x[w.axis] - w.position };
        if gap < nearest.1 {
            nearest = (crossing_class(w.id), gap);
        }
    }
    for b in p.boxes {
        if b.squared_distance(x.to_array()) < nearest.1 * nearest.1 {
            return FURNISHINGS_CLASS;
        }
    }
    nearest.0
}

/// Whether a particle whose [`free_flight_gap`] is `gap` lies within the layer, for certain
/// (so that [`zone`] would say [`Zone::Inside`]; `false` says nothing). Surface by surface, the
/// free-flight gap falls short of the distance by the stop distance of the velocity towards
/// it, at most `tau |v|` (along each axis, and so in norm beyond a box's edge or corner); so
/// the distance to the nearest surface is at most `gap + tau (|v_x| + |v_y| + |v_z|)`. A
/// millionth of the layer keeps the two computations' rounding out of the answer. Deep in the
/// layer, where an excursion takes most of its steps, this spares the distance's own pass
/// over the walls and boxes.
#[inline]
fn surely_inside(excursions: &Excursions, flyer: &Flyer, gap: f64) -> bool {
    let v = flyer.v;
    let slack = flyer.body.tau * (v.x.abs() + v.y.abs() + v.z.abs());
    gap + slack < excursions.layer * (1.0 - 1e-6)
}

/// Where a particle stands against the excursions' region ([`Excursions::sweeps`]): inside
/// (within the layer, or in a strong sweep), outside, or between a sweep's two thresholds,
/// where it stays as it was.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Zone {
    Inside,
    Between,
    Outside,
}

#[inline]
fn zone(p: &Prepared<'_>, excursions: &Excursions, flyer: &Flyer) -> Zone {
    // Boxes farther than the layer cannot bring the gap within it.
    let r = flyer.body.contact;
    let boxes = flyer.clearance.near(p.boxes, flyer.x.to_array(), excursions.layer + r);
    if wall_gap(p, boxes, flyer.x, r) < excursions.layer {
        return Zone::Inside;
    }
    let Some(sweeps) = &excursions.sweeps else { return Zone::Outside };
    // A channel's walls are across z, and `zeta` points along +z: towards the nearer wall is
    // `-sign zeta`, `sign` that of d(distance)/dz.
    let (_, sign) = super::wall_distance(flyer.x.z, p.size[2]);
    let wallward = -sign * flyer.zeta[2];
    if wallward > sweeps.enter {
        Zone::Inside
    } else if wallward < sweeps.leave {
        Zone::Outside
    } else {
        Zone::Between
    }
}

/// Tracks injected particle `id`, with sampled excursions at each of its entries into the
/// excursions' region within the window; returns its record and its tally.
pub(crate) fn run_with_excursions<
    const BROWN: bool,
    const TURB: bool,
    const FINITE_RE: bool,
    const EULER: bool,
    const LIFT: bool,
>(
    p: &Prepared<'_>,
    excursions: &Excursions,
    id: u64,
    tally: &mut [WallTally],
) -> (Record, ParticleTally) {
    let dt = p.settings.dt;
    let window = p.window;
    let mut sampler = particle_rng(p.settings.seed ^ SAMPLER_SALT, id);
    let mut copies = 0u64;
    let mut stats = ParticleTally::default();
    // Excursions' own wall contacts are not the run's: they go to a scratch tally.
    let mut scratch = vec![WallTally::default(); tally.len()];

    let mut flyer = Flyer::inject(p, id, TURB, BROWN);
    // The particle's constants for coarse steps, once for all its excursions.
    let mut coarse = p.coarse.as_deref().map(|c| Coarse {
        p: c,
        body: Body::new(c, flyer.body.aero.diameter),
        factor: excursions.coarse_factor as usize,
    });
    let mut inside = zone(p, excursions, &flyer) == Zone::Inside;
    for n in 0..flyer.end {
        if p.stopped_at(n) {
            break; // an incomplete record, which the stopped run discards
        }
        let t0 = n as f64 * dt;
        match flyer.step::<BROWN, TURB, FINITE_RE, EULER, LIFT>(p, n, tally) {
            Step::Left(fate, t, at) => {
                stats.exposure += overlap(t0, t0 + t, window);
                return (flyer.record(fate, t0 + t, at, n as u64 + 1), stats);
            }
            Step::Airborne => {
                stats.exposure += overlap(t0, t0 + dt, window);
                let entered = match zone(p, excursions, &flyer) {
                    Zone::Inside => true,
                    Zone::Between => inside,
                    Zone::Outside => false,
                };
                let t1 = t0 + dt;
                if entered && !inside && t1 >= window[0] && t1 <= window[1] {
                    // Entered by a sweep (outside the layer) or across the layer; the
                    // crossing's class by the surface nearest its end.
                    let class = nearest_class(p, flyer.x);
                    let sampling = match &excursions.sweeps {
                        Some(s) if wall_gap(p, p.boxes, flyer.x, flyer.body.contact) >= excursions.layer => s.sampling,
                        _ => excursions.sampling * excursions.class_sampling[class],
                    };
                    // `sampling` excursions per entry on average: its whole part, and one more
                    // with the probability of its fraction.
                    let count = sampling.floor() as u64 + u64::from(sampler.random::<f64>() < sampling.fract());
                    for _ in 0..count {
                        let streams = (p.settings.seed, id, &mut copies);
                        excursion::<BROWN, TURB, FINITE_RE, EULER, LIFT>(
                            p,
                            (excursions, sampling, class),
                            &flyer,
                            coarse.as_mut(),
                            n + 1,
                            streams,
                            &mut sampler,
                            &mut stats,
                            &mut scratch,
                        );
                    }
                }
                inside = entered;
            }
        }
    }
    (flyer.finish(p), stats)
}

/// A branch of an excursion waiting to be stepped: the particle, its weight and level, and
/// the next step.
struct Branch {
    flyer: Flyer,
    weight: f64,
    level: usize,
    next: usize,
    /// The excursion's clock, in the scene's steps ([`Excursions::max_duration`] is counted
    /// on it; a coarse step counts as several).
    clock: usize,
}

/// One excursion from `start` (just inside the region, before step `next`), with the
/// particle's `coarse` steps where the scene has them, one of
/// `sampling` per entry on average: its branches' weighted deposits, times `1 / sampling`,
/// go to `stats`.
///
/// Ventilation ([`Scene::air_exchange`](crate::Scene::air_exchange)) does not touch the
/// excursions: it exhausts particles at a rate that does not depend on where they are, so it
/// scales the airborne number, the crossings into the layer and the deposits of a decaying
/// room alike by `exp(-a t)`, and the deposits per airborne particle-second (the loss rate
/// `beta` a decay experiment measures) are the closed room's. Weighting an excursion's
/// deposits by the chance `exp(-a s)` that the particle was not exhausted first would give
/// the steady state of a continuous source instead, and disagree with plain tracking of the
/// same decay (a test showed 3 standard errors at 6 air changes per hour). Exhaust
/// openings ([`Scene::openings`](crate::Scene::openings)) do touch them: a branch that
/// reaches an exhaust leaves, as the particle would, and deposits nothing.
#[allow(clippy::too_many_arguments)]
fn excursion<const BROWN: bool, const TURB: bool, const FINITE_RE: bool, const EULER: bool, const LIFT: bool>(
    p: &Prepared<'_>,
    (excursions, sampling, class): (&Excursions, f64, usize),
    start: &Flyer,
    mut coarse: Option<&mut Coarse<'_, '_>>,
    next: usize,
    (seed, id, copies): (u64, u64, &mut u64),
    roulette: &mut Xoshiro256PlusPlus,
    stats: &mut ParticleTally,
    scratch: &mut [WallTally],
) {
    let splitting = &excursions.splitting;
    stats.excursions += 1;
    let (_, per_step) = normals_per_step(TURB, BROWN, EULER);
    // The branches' clock, in the scene's steps: a coarse step counts `factor` of them.
    let last = next + (excursions.max_duration / p.settings.dt).ceil() as usize;
    let mut stack = Vec::new();
    *copies += 1;
    let flyer = start.with_streams(Normals::from_rng(&mut branch_rng(seed, id, *copies)), next, per_step);
    let level = splitting.level(free_flight_gap(p, excursions, &flyer));
    let first = Branch { flyer, weight: 1.0 / sampling, level: 0, next, clock: next };
    let target = first.weight * splitting.weight(level);
    window_weight(first, level, target, &mut stack, (seed, id, copies, per_step), roulette, stats, sampling);

    while let Some(Branch { mut flyer, weight, level, next, mut clock }) = stack.pop() {
        if clock >= last {
            stats.truncated += weight;
            continue;
        }
        let mut gap = free_flight_gap(p, excursions, &flyer);
        let mut n = next;
        loop {
            // A coarse step where it cannot reach a wall and the turbulence is smooth enough
            // for it, the scene's step elsewhere.
            let coarse_step = coarse.as_deref_mut().filter(|c| c.allows(&flyer, gap));
            let ticks = coarse_step.as_ref().map_or(1, |c| c.factor);
            let is_last = clock + ticks >= last;
            if is_last {
                // Its last step: whatever it does, it is given up after it.
                stats.truncated += weight;
            }
            let step = match coarse_step {
                Some(c) => {
                    std::mem::swap(&mut flyer.body, &mut c.body);
                    let step = flyer.step::<BROWN, TURB, FINITE_RE, EULER, LIFT>(c.p, n, scratch);
                    std::mem::swap(&mut flyer.body, &mut c.body);
                    step
                }
                None => flyer.step::<BROWN, TURB, FINITE_RE, EULER, LIFT>(p, n, scratch),
            };
            n += 1;
            clock += ticks;
            stats.class_steps[class] += 1;
            match step {
                Step::Left(Fate::Deposited(w), _, at) => {
                    stats.add_deposit(w, weight, at.to_array());
                    stats.class_deposits[class][crossing_class(w)] += weight;
                    break;
                }
                Step::Left(..) => break,
                Step::Airborne => {
                    gap = free_flight_gap(p, excursions, &flyer);
                    if !surely_inside(excursions, &flyer, gap) && zone(p, excursions, &flyer) == Zone::Outside {
                        break;
                    }
                    let new_level = splitting.level(gap);
                    // `level` is the level whose weight the branch carries. A branch splits as soon
                    // as it goes deeper, but plays roulette only two levels out: a branch
                    // that hovers at a level's edge (as Brownian motion makes it do) is not
                    // split and rouletted over and over.
                    if new_level > level || new_level + 1 < level {
                        // Split or roulette; what goes on is taken from the stack next.
                        let target = splitting.weight(new_level) / sampling;
                        let branch = Branch { flyer, weight, level, next: n, clock };
                        let streams = (seed, id, &mut *copies, per_step);
                        window_weight(branch, new_level, target, &mut stack, streams, roulette, stats, sampling);
                        break;
                    }
                }
            }
            if is_last {
                break;
            }
        }
    }
}

/// The excursions' coarse steps: the scene prepared for them, the particle's constants for
/// them, and how many of the scene's steps one is.
struct Coarse<'p, 'a> {
    p: &'p Prepared<'a>,
    body: Body,
    factor: usize,
}

impl Coarse<'_, '_> {
    /// Whether `flyer`, whose free-flight gap to the nearest wall is `gap` (m), may take a
    /// coarse step: along every walled axis, the turbulence's rms changes by at most
    /// [`MAX_STEP_GRADIENT`] over a coarse step (what the scene's own step must meet, so the
    /// well-mixed drift stays accurate), and the farthest the particle can move towards a wall
    /// in one (its relaxation towards the fluid velocity it sees, which is held over the step,
    /// plus five standard deviations of its Brownian displacement) is less than `gap`. So a
    /// coarse step neither reaches a wall nor steps over the turbulence's gradients.
    #[inline]
    fn allows(&self, flyer: &Flyer, gap: f64) -> bool {
        let (c, body, dt) = (self.p, &self.body, self.p.dt);
        let mut reach = 0.0_f64;
        for a in 0..3 {
            if !c.walled[a] {
                continue;
            }
            let (sigma, slope) = match &c.field.turbulence {
                Some(turbulence) => {
                    let axis = turbulence[a].axis;
                    let node = turbulence[a].table.at(wall_distance(flyer.x[axis], c.size[axis]).0);
                    (node.sigma + node.rise.abs(), node.slope)
                }
                None => (0.0, 0.0),
            };
            if dt * slope.abs() > MAX_STEP_GRADIENT {
                return false;
            }
            let fluid = sigma * flyer.zeta[a].abs() + body.settling[a].abs();
            reach = reach.max(body.tau * flyer.v[a].abs() + (body.tau + dt) * fluid);
        }
        gap > reach + 5.0 * body.brownian[0]
    }
}

/// Brings a branch's weight to `target`, that of its new `level`: it splits into copies (each
/// with fresh random streams from then on) or plays Russian roulette; what goes on is pushed
/// onto `stack`, the branch itself last. An arrival deeper is counted in `stats`.
#[allow(clippy::too_many_arguments)]
fn window_weight(
    mut branch: Branch,
    level: usize,
    target: f64,
    stack: &mut Vec<Branch>,
    (seed, id, copies, per_step): (u64, u64, &mut u64, usize),
    roulette: &mut Xoshiro256PlusPlus,
    stats: &mut ParticleTally,
    sampling: f64,
) {
    for l in branch.level..level {
        stats.arrivals[l] += branch.weight * sampling;
        stats.branches[l] += 1;
    }
    branch.level = level;
    if branch.weight < target * (1.0 - 1e-9) {
        if roulette.random::<f64>() * target >= branch.weight {
            return;
        }
        branch.weight = target;
    }
    let count = (branch.weight / target).round().max(1.0) as u64;
    branch.weight /= count as f64;
    for _ in 1..count {
        *copies += 1;
        let streams = Normals::from_rng(&mut branch_rng(seed, id, *copies));
        let flyer = branch.flyer.with_streams(streams, branch.next, per_step);
        stack.push(Branch { flyer, weight: branch.weight, level, next: branch.next, clock: branch.clock });
    }
    stack.push(branch);
}

/// Salt of the stream that samples crossings and plays roulette (any constant other than the
/// particle streams' own).
const SAMPLER_SALT: u64 = 0x7f4a_7c15_9e37_79b9;

#[cfg(test)]
mod tests {
    use super::*;

    /// A coarse step is taken in the viscous sublayer, and not where it could reach the wall
    /// (too close, or coasting towards it fast) nor where the turbulence's rms changes too
    /// fast for it. Channel study's scene, `tau+ = 0.3`, coarse steps 8 times its step of 0.2
    /// wall time units: the wall-normal rms' slope (Kallio & Reeks' fit, worked out by hand)
    /// is 0.028 at `y+ = 2` and 0.038 at `y+ = 4`, so `1.6 x slope` is below
    /// `MAX_STEP_GRADIENT` (0.05) at 2 and above it at 4.
    #[test]
    fn coarse_steps_keep_clear_of_the_wall_and_of_the_buffer_layer() {
        let crate::studies::channel::ChannelStudy { scene, mut settings, .. } = Default::default();
        let nu = scene.air.kinematic_viscosity();
        let u_star = 0.3;
        let unit = nu / u_star;
        settings.excursions =
            Some(Excursions { coarse_factor: 8, ..Excursions::in_wall_units(u_star, nu, 0.2, 3.0, 1e5) });
        let d = crate::physics::correlations::diameter_for_tau_plus(0.3, 1000.0, &scene.air, u_star).unwrap();
        let injection = crate::Injection::new(1, crate::SizeDistribution::Monodisperse { diameter: d }, 1000.0);
        let p = Prepared::new(&scene, &settings, &injection).unwrap();
        let c = p.coarse.as_deref().expect("coarse steps prepared");
        assert!((c.dt / p.dt - 8.0).abs() < 1e-12);
        let coarse = Coarse { p: c, body: Body::new(c, d), factor: 8 };
        let mut flyer = Flyer::inject(&p, 0, true, true);
        // `gap_plus`: from the particle's surface to the wall, in wall units.
        let radius_plus = 0.5 * d / unit;
        let allows = |flyer: &mut Flyer, gap_plus: f64, v_plus: f64| {
            flyer.x.z = (gap_plus + radius_plus) * unit;
            flyer.v = DVec3::new(0.0, 0.0, v_plus * u_star);
            flyer.zeta = [1.0; 3];
            coarse.allows(flyer, free_flight_gap(&p, p.settings.excursions.as_ref().unwrap(), flyer))
        };
        assert!(allows(&mut flyer, 0.5, 0.0), "0.5 wall units off, at rest");
        assert!(allows(&mut flyer, 2.0, 0.0), "2 wall units off, at rest");
        // Five Brownian standard deviations over a coarse step (Sc = 2.4e6, 1.6 wall time
        // units): 5 sqrt(2 x 1.6 / 2.4e6) = 0.0058 wall units; the fluid adds little here.
        assert!(allows(&mut flyer, 0.02, 0.0), "0.02 wall units off: beyond a coarse step's reach");
        assert!(!allows(&mut flyer, 0.004, 0.0), "0.004 wall units off: a coarse step could reach the wall");
        assert!(!allows(&mut flyer, 0.5, -2.0), "0.5 wall units off, coasting at 2 u* towards the wall");
        assert!(!allows(&mut flyer, 4.0 - radius_plus, 0.0), "y+ 4: the rms changes too fast for a coarse step");
    }

    /// Every check a step or an excursion asks with the boxes a particle's clearance leaves
    /// gives what it gives with all boxes: the fluid read (bit for bit), the contact test,
    /// the layer's test and the splitting level. A table and a shelf by a wall (as in
    /// `examples/room.toml`); flyers at random points, each with the ball from a random point
    /// up to 0.6 m off, so that the balls' edges fall near and far from the boxes.
    #[test]
    fn boxes_a_clearance_leaves_out_change_no_read_contact_gap_or_level() {
        use super::super::contacts::inside;
        use super::super::fluid::furnished_fluid_velocity;
        use crate::model::furnishing::Clearance;
        use rand::RngExt;

        let mut scene = crate::Scene::new(crate::Geometry::Room { size: [4.0, 3.0, 2.5] });
        scene.flow = crate::Flow::indoor_room();
        scene.brownian = true;
        scene.furnishings =
            vec![Furnishing::new([1.0, 1.0, 0.7], [2.2, 1.8, 0.75]), Furnishing::new([3.5, 0.2, 0.3], [3.9, 2.8, 2.0])];
        let nu = scene.air.kinematic_viscosity();
        let settings = crate::RunSettings {
            scheme: crate::Scheme::Midpoint,
            excursions: Some(Excursions::in_wall_units(0.01, nu, 0.05, 3.0, 16_000.0)),
            ..crate::RunSettings::new(0.1, 10.0)
        };
        let injection = crate::Injection::new(1, crate::SizeDistribution::Monodisperse { diameter: 1e-6 }, 1000.0);
        let p = Prepared::new(&scene, &settings, &injection).unwrap();
        let excursions = settings.excursions.as_ref().unwrap();
        let (layer, reads) = (excursions.layer, p.field.turbulence_flat_from);
        let mut flyer = Flyer::inject(&p, 0, true, true);
        let r = flyer.body.contact;
        let mut rng = particle_rng(11, 0);
        let (mut skipped, mut kept) = (0, 0);
        for _ in 0..50_000 {
            let x: [f64; 3] = std::array::from_fn(|a| rng.random_range(0.001..p.size[a] - 0.001));
            let centre: [f64; 3] = std::array::from_fn(|a| x[a] + rng.random_range(-0.6..0.6));
            let clearance = Clearance::around(centre, p.boxes);
            let all = Clearance::NONE;
            flyer.x = DVec3::from_array(x);
            flyer.v = DVec3::from_array(std::array::from_fn(|_| rng.random_range(-0.05..0.05)));
            let zeta: [f64; 3] = std::array::from_fn(|_| rng.random_range(-3.0..3.0));
            let normals = Some(std::array::from_fn(|_| rng.random_range(-3.0..3.0)));

            let near = clearance.near(p.boxes, x, reads);
            let (mut z_near, mut z_all) = (zeta, zeta);
            let read_near = furnished_fluid_velocity(&p.field, p.size, near, flyer.x, &mut z_near, normals);
            let read_all = furnished_fluid_velocity(&p.field, p.size, p.boxes, flyer.x, &mut z_all, normals);
            assert_eq!((read_near, z_near), (read_all, z_all), "read at {x:?}");

            // A box grown by `r` along each axis reaches `sqrt(3) r` at its corners.
            let near = clearance.near(p.boxes, x, 2.0 * r);
            assert_eq!(inside(flyer.x, r, &p, near), inside(flyer.x, r, &p, p.boxes), "contact at {x:?}");

            let near = clearance.near(p.boxes, x, layer + r);
            assert_eq!(wall_gap(&p, near, flyer.x, r) < layer, wall_gap(&p, p.boxes, flyer.x, r) < layer);

            flyer.clearance = all;
            let level = excursions.splitting.level(free_flight_gap(&p, excursions, &flyer));
            flyer.clearance = clearance;
            assert_eq!(excursions.splitting.level(free_flight_gap(&p, excursions, &flyer)), level, "level at {x:?}");

            if near.is_empty() {
                skipped += 1;
            } else {
                kept += 1;
            }
        }
        // Both cases well sampled.
        assert!(skipped > 5000 && kept > 5000, "{skipped} {kept}");
        // Off a box's corner along its diagonal, 0.9 `r` beyond each face: `sqrt(3) 0.9 r` away,
        // but within the box grown by `r`. A ball of that radius must not leave the box out.
        let corner = DVec3::from_array(p.boxes[0].low) - DVec3::splat(0.9 * r);
        let clearance = Clearance::around(corner.to_array(), p.boxes);
        assert!(!inside(corner, r, &p, p.boxes));
        assert!(!inside(corner, r, &p, clearance.near(p.boxes, corner.to_array(), 2.0 * r)));
        assert!(clearance.near(p.boxes, corner.to_array(), r).is_empty(), "a reach of r alone would miss it");
    }

    /// Where [`surely_inside`] says a branch is within the layer, [`zone`] says so too: near
    /// the walls and boxes of a furnished room, for a small particle and for one whose stop
    /// distance reaches across the layer.
    #[test]
    fn surely_inside_agrees_with_the_zone() {
        let mut scene = crate::Scene::new(crate::Geometry::Room { size: [4.0, 3.0, 2.5] });
        scene.flow = crate::Flow::indoor_room();
        scene.furnishings =
            vec![Furnishing::new([1.0, 1.0, 0.7], [2.2, 1.8, 0.75]), Furnishing::new([3.5, 0.2, 0.3], [3.9, 2.8, 2.0])];
        let nu = scene.air.kinematic_viscosity();
        let settings = crate::RunSettings {
            excursions: Some(Excursions::in_wall_units(0.01, nu, 0.05, 3.0, 16_000.0)),
            ..crate::RunSettings::new(0.1, 10.0)
        };
        let excursions = settings.excursions.clone().unwrap();
        let layer = excursions.layer;
        let mut rng = particle_rng(5, 0);
        for (diameter, speed) in [(1e-6, 0.05), (50e-6, 5.0)] {
            let injection = crate::Injection::new(1, crate::SizeDistribution::Monodisperse { diameter }, 1000.0);
            let p = Prepared::new(&scene, &settings, &injection).unwrap();
            let mut flyer = Flyer::inject(&p, 0, true, false);
            let r = flyer.body.contact;
            let (mut sure, mut unsure) = (0, 0);
            for i in 0..30_000 {
                let mut x: [f64; 3] = std::array::from_fn(|a| rng.random_range(r..p.size[a] - r));
                if i % 2 == 0 {
                    // Within a layer and a half of a wall.
                    let a = rng.random_range(0..3);
                    let off = r + rng.random_range(0.0..1.5 * layer);
                    x[a] = if rng.random::<bool>() { off } else { p.size[a] - off };
                } else {
                    // About a box, outside it grown by the radius.
                    let b = &p.boxes[i % 4 / 2];
                    x = std::array::from_fn(|a| rng.random_range(b.low[a] - 1.5 * layer..b.high[a] + 1.5 * layer));
                    if b.squared_distance(x) <= (2.0 * r) * (2.0 * r) {
                        continue;
                    }
                }
                flyer.x = DVec3::from_array(x);
                flyer.v = DVec3::from_array(std::array::from_fn(|_| rng.random_range(-speed..speed)));
                flyer.clearance = crate::model::furnishing::Clearance::around(x, p.boxes);
                let inside = zone(&p, &excursions, &flyer) == Zone::Inside;
                if surely_inside(&excursions, &flyer, free_flight_gap(&p, &excursions, &flyer)) {
                    assert!(inside, "d {diameter} at {x:?}, v {:?}", flyer.v);
                    sure += 1;
                } else if inside {
                    unsure += 1;
                }
            }
            // The small particle's slack is a few nanometres: sure wherever it is inside, but
            // for a millionth of the layer at its edge. The large one's reaches across the
            // layer: often inside without being sure.
            let both = if diameter < 1e-5 { sure > 10_000 } else { sure > 1000 && unsure > 1000 };
            assert!(both, "d {diameter}: {sure} sure, {unsure} inside but unsure");
        }
    }

    #[test]
    fn a_box_s_free_flight_gap_is_a_wall_s_in_front_of_a_face_and_euclidean_beyond_an_edge() {
        let b = Furnishing::new([1.0, 1.0, 1.0], [2.0, 2.0, 2.0]);
        // In front of the x0 face, 0.3 m off, coasting towards it: 0.3 - tau v, below zero
        // when it would reach the face, as for a wall.
        let x = DVec3::new(0.7, 1.5, 1.5);
        assert!((box_free_flight_gap(&b, x, DVec3::new(0.5, 0.0, 0.0), 0.2) - 0.2).abs() < 1e-12);
        assert!((box_free_flight_gap(&b, x, DVec3::new(2.0, 0.0, 0.0), 0.2) + 0.1).abs() < 1e-12);
        // Moving away: the plain separation.
        assert!((box_free_flight_gap(&b, x, DVec3::new(-2.0, 0.0, 0.0), 0.2) - 0.3).abs() < 1e-12);
        // Beyond an edge, 0.3 m out in x and 0.4 m in y: 0.5 m, less the coasting along x.
        let x = DVec3::new(0.7, 2.4, 1.5);
        assert!((box_free_flight_gap(&b, x, DVec3::ZERO, 0.2) - 0.5).abs() < 1e-12);
        let coasting = box_free_flight_gap(&b, x, DVec3::new(1.5, 0.0, 0.0), 0.2);
        assert!((coasting - 0.4).abs() < 1e-12, "{coasting}");
    }
}
