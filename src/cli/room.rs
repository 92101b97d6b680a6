//! `depo room`: deposition onto the floor, ceiling and walls of a room, per particle size,
//! beside Lai & Nazaroff (2000).

use std::path::PathBuf;

use clap::Args as ClapArgs;
use depo::tracker::correlations::LaiNazaroff;
use depo::tracker::decay::MIN_AIRBORNE;
use depo::tracker::distribution::{first_seen, DistributionStudy};
use depo::tracker::filtration::Filtration;
use depo::tracker::furnishing::FACE_NAMES;
use depo::tracker::geometry::in_plane_axes;
use depo::tracker::studies::{self, MAP_BINS};
use depo::tracker::studies::{RoomPoint, RoomStudy};
use depo::tracker::{binomial_error, DecayCurve, Estimate, Flow, Geometry, Scene, WallTally};
use serde::Serialize;

use super::plot::{self, Series};
use super::room_distribution::DistributionReport;
use super::{print_csv, progress_bar, scene_file, shown, Error, Format};

#[derive(ClapArgs, Debug)]
pub struct RoomArgs {
    /// A scene file (TOML; see examples/room.toml). Without it, the built-in room.
    scene: Option<PathBuf>,
    /// Output format.
    #[arg(long, value_enum, default_value_t)]
    format: Format,
    /// Directory for the figures and maps, written unless --no-plot (53 files for the built-in
    /// room, more with furnishings): room-deposition.svg, room-beta.svg, room-decay.svg and
    /// the decay curves room-decay.csv; each size's deposition maps (room-map-SIZEum.svg and
    /// room-map-SURFACE-SIZEum.csv); room-indoor-outdoor.svg when ventilated;
    /// room-distribution.svg and room-pm.svg with a size distribution.
    #[arg(long, default_value = "depo-room")]
    plot: PathBuf,
    /// Write no figures or maps.
    #[arg(long)]
    no_plot: bool,
}

/// A measured value with its standard error, the deposit events it rests on, and with no
/// event a 95 % upper bound.
#[derive(Serialize)]
pub struct Measured {
    pub value: f64,
    pub error: f64,
    pub events: usize,
    pub upper_bound: Option<f64>,
}

impl From<Estimate> for Measured {
    fn from(e: Estimate) -> Self {
        let upper_bound = (e.events == 0).then_some(e.upper_bound);
        Self { value: e.value, error: e.error, events: e.events, upper_bound }
    }
}

impl Measured {
    /// Back to the study's estimate (the upper bound, unused by the studies' rules, NaN where
    /// events were seen).
    fn estimate(&self) -> Estimate {
        let upper_bound = self.upper_bound.unwrap_or(f64::NAN);
        Estimate { value: self.value, error: self.error, events: self.events, upper_bound }
    }

    /// `value +- error [events]`, or `< bound [0]` when nothing deposited.
    pub fn cell(&self) -> String {
        match self.upper_bound {
            Some(bound) => format!("< {bound:.1e} [0]"),
            None => format!("{:.2e} +- {:.1e} [{}]", self.value, self.error, self.events),
        }
    }

    /// The same scaled by `k` (a change of unit).
    pub fn scaled(&self, k: f64) -> Self {
        Self {
            value: self.value * k,
            error: self.error * k,
            events: self.events,
            upper_bound: self.upper_bound.map(|b| b * k),
        }
    }
}

/// A surface's figure is resolved when its relative standard error is at most this (the
/// study's target)...
const RESOLVED_ERROR: f64 = studies::TARGET_ERROR;
/// ...where Lai & Nazaroff give at least this deposition velocity (m/s); below it the
/// relative error is not asked of a figure (a few events over a whole run).
const RESOLVABLE: f64 = studies::RESOLVED_FROM;

/// Whether a surface's deposition velocity `measured` is unresolved beside the model's `model`
/// (m/s), its run's excursions having given up the share `given_up` of their weight at their
/// longest duration: no deposit event; or, where the model gives at least [`RESOLVABLE`], a
/// relative standard error above [`RESOLVED_ERROR`] ([`too_uncertain`]), or a given-up share
/// above it (what giving them up may have missed, at most that share, could then exceed a
/// resolved figure's error).
fn unresolved(measured: &Measured, model: f64, given_up: f64) -> bool {
    measured.events == 0 || too_uncertain(measured, model) || (model >= RESOLVABLE && given_up > RESOLVED_ERROR)
}

/// Whether `measured`, with deposit events, has a relative standard error above
/// [`RESOLVED_ERROR`] where the model `model` (m/s) asks it ([`RESOLVABLE`]).
fn too_uncertain(measured: &Measured, model: f64) -> bool {
    model >= RESOLVABLE && measured.events > 0 && !studies::resolved(&measured.estimate(), RESOLVED_ERROR)
}

/// The particles that would bring the `figures` (each a measured deposition velocity beside
/// Lai & Nazaroff's) that are [`too_uncertain`] within [`RESOLVED_ERROR`], from a run of
/// `particles`: as the study itself would run more ([`studies::particles_for`]). `None` where
/// no figure is so (more particles cannot be told how far a figure without a deposit event is
/// from resolved, nor lower a share given up).
fn particles_to_resolve(particles: usize, figures: [(&Measured, f64); 3]) -> Option<usize> {
    figures
        .into_iter()
        .filter(|(m, model)| too_uncertain(m, *model))
        .map(|(m, _)| studies::particles_for(&m.estimate(), particles, RESOLVED_ERROR))
        .max()
}

/// `n` rounded up to two significant figures (12618 to 13000): what an estimate of a count
/// can claim.
fn two_figures_up(n: usize) -> usize {
    let mut unit = 1;
    while n / unit >= 100 {
        unit *= 10;
    }
    n.div_ceil(unit) * unit
}

/// The note under a study's table: what its numbers mean.
pub const ERROR_NOTE: &str = "+- one standard error; [n] deposit events; with none, < the 95 % upper \
bound; \"excursions (x % at T s)\": deposits counted by near-wall excursions, x the weight given up at \
their longest duration T (--help says more).";

#[derive(Serialize)]
struct Model {
    floor: f64,
    ceiling: f64,
    walls: f64,
    beta_per_hour: f64,
}

/// A run's wall-law tallies, summed over the surfaces; energy in J.
#[derive(Serialize)]
pub struct Tally {
    pub contacts: u64,
    pub rebounds: u64,
    pub captures: u64,
    pub resting: u64,
    pub energy_lost_material: f64,
    pub energy_lost_adhesion: f64,
    pub energy_lost_friction: f64,
    pub energy_deposited: f64,
}

impl From<WallTally> for Tally {
    fn from(t: WallTally) -> Self {
        Self {
            contacts: t.contacts,
            rebounds: t.rebounds,
            captures: t.captures,
            resting: t.resting,
            energy_lost_material: t.energy.material,
            energy_lost_adhesion: t.energy.adhesion,
            energy_lost_friction: t.energy.friction,
            energy_deposited: t.energy.deposition,
        }
    }
}

/// One surface's wall-law tally, named.
#[derive(Serialize)]
struct SurfaceTally {
    surface: String,
    #[serde(flatten)]
    tally: Tally,
}

/// The excursions per crossing of each class of surface, as multiples of the study's three
/// ([`depo::tracker::Excursions::class_sampling`]).
#[derive(Serialize)]
struct ClassSampling {
    floor: f64,
    ceiling: f64,
    walls: f64,
    furnishings: f64,
}

#[derive(Serialize)]
struct Row {
    diameter_um: f64,
    /// Particle density, kg/m^3 (a size distribution's bins can have several).
    density: f64,
    floor: Measured,
    ceiling: Measured,
    walls: Measured,
    /// Each vertical wall (`x0`, `x1`, `y0`, `y1`): its deposition velocity and what it
    /// collected; `walls` is the four together.
    each_wall: Vec<WallRow>,
    beta_per_hour: Measured,
    /// With ventilation: the steady indoor/outdoor ratio `P a / (a + beta)` (with filters,
    /// `(P (1 - s) a + (1 - eta_s) s a) / (a + eta_r a_r + beta)`).
    #[serde(skip_serializing_if = "Option::is_none")]
    indoor_outdoor: Option<Measured>,
    /// The recirculation filter's removal `eta_r a_r` at this size, 1/h (with one).
    #[serde(skip_serializing_if = "Option::is_none")]
    filter_removal_per_hour: Option<f64>,
    /// The supply filter's single-pass efficiency `eta_s` at this size (with a filtered
    /// supply share).
    #[serde(skip_serializing_if = "Option::is_none")]
    supply_filter_efficiency: Option<f64>,
    /// The recirculation filter's single-pass efficiency `eta_r` at this size (with
    /// recirculation).
    #[serde(skip_serializing_if = "Option::is_none")]
    recirculation_filter_efficiency: Option<f64>,
    lai_nazaroff: Model,
    particle_steps: u64,
    /// Particles run for this size.
    particles: usize,
    /// "excursions", "wall-function" (deposits from Lai & Nazaroff's rate within the walls'
    /// layers; docs/tracker.md) or "plain".
    method: &'static str,
    /// With excursions: the share of their weight given up at their longest duration.
    excursions_truncated: Option<f64>,
    /// With excursions: that longest duration, s.
    #[serde(skip_serializing_if = "Option::is_none")]
    longest_excursion_s: Option<f64>,
    /// With excursions: the multipliers of their sampling per class of crossing that the
    /// particles after the first ran with.
    #[serde(skip_serializing_if = "Option::is_none")]
    class_sampling: Option<ClassSampling>,
    wall_tally: Tally,
    /// Each surface's own tally, in id order: what each surface's material did.
    surface_tallies: Vec<SurfaceTally>,
    deposited: Deposited,
    /// Where the released particles are at the end: per surface, exhausted, airborne.
    release: Release,
    /// The start of this size's averaging window, s: the study's, or 0 where every particle
    /// had left the air before it opened (its figures are then over the release from its
    /// start, not a well-mixed room's rates).
    averaged_from_s: f64,
    /// When half and when nine tenths of the released particles had deposited, s (null where
    /// the run ended first).
    deposited_by_s: [Option<f64>; 2],
    /// The steady state under a continuous source of this size (null where nothing removes
    /// the particles).
    steady: Option<Steady>,
    /// `beta` fitted to the decay curve as decay experiments fit it; absent when fewer than 3
    /// sample times qualify.
    decay_fit: Option<DecayFitRow>,
    /// The airborne share of the release over the run.
    decay: Curve,
    /// The surfaces (floor, ceiling, walls) whose figure is unresolved: no deposit event, or
    /// a relative standard error above 5 % where Lai & Nazaroff give at least 1e-7 m/s.
    unresolved: Vec<&'static str>,
    /// Per furnishing: deposition velocities onto its faces and what it collected.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    furnishings: Vec<FurnishingRow>,
    /// Each surface's deposition map: the tracked particles' deposits over the run, per cell.
    maps: Vec<SurfaceMap>,
}

/// One surface's deposition map for one size, as the JSON, the CSV files and the figure give
/// it: the deposits of the tracked particles over the whole run on a [`MAP_BINS`] grid over
/// the surface's two in-plane axes in the order x, y, z (over the room, or the furnishing).
#[derive(Serialize)]
struct SurfaceMap {
    /// Its name: floor, ceiling, x0, ..., or a furnishing's face as `table.top`.
    surface: String,
    /// "wall" or "furnishing face".
    kind: &'static str,
    /// The axis the surface is normal to, and its position along it, m.
    normal: (&'static str, f64),
    /// The rows' axis and its range, m.
    rows: (&'static str, f64, f64),
    /// The columns' axis and its range, m.
    columns: (&'static str, f64, f64),
    /// Deposits per cell, row by row.
    #[serde(serialize_with = "rows_on_one_line")]
    cells: Vec<Vec<u32>>,
}

/// Serialises `cells` with each row as one compact JSON array, so that the pretty-printed
/// report gives a row a line rather than every cell a line of its own.
fn rows_on_one_line<S: serde::Serializer>(cells: &[Vec<u32>], s: S) -> Result<S::Ok, S::Error> {
    use serde::ser::{Error as _, SerializeSeq};
    let mut seq = s.serialize_seq(Some(cells.len()))?;
    for row in cells {
        let text = serde_json::to_string(row).map_err(S::Error::custom)?;
        seq.serialize_element(&serde_json::value::RawValue::from_string(text).map_err(S::Error::custom)?)?;
    }
    seq.end()
}

/// The maps `p` holds, one per surface of `scene` in id order, with their axes.
fn surface_maps(scene: &Scene, p: &RoomPoint) -> Vec<SurfaceMap> {
    let axis = ["x", "y", "z"];
    let size = scene.geometry.size();
    scene
        .surfaces()
        .iter()
        .zip(&p.maps)
        .map(|(wall, map)| {
            let (low, high) = match wall.furnishing {
                Some(k) => (scene.furnishings[k].low, scene.furnishings[k].high),
                None => ([0.0; 3], size),
            };
            let [a, b] = in_plane_axes(wall.axis);
            SurfaceMap {
                surface: scene.surface_name(wall.id),
                kind: if wall.furnishing.is_some() { "furnishing face" } else { "wall" },
                normal: (axis[wall.axis], wall.position),
                rows: (axis[a], low[a], high[a]),
                columns: (axis[b], low[b], high[b]),
                cells: map.chunks(MAP_BINS[1]).map(<[u32]>::to_vec).collect(),
            }
        })
        .collect()
}

/// One furnishing in a size's row.
#[derive(Serialize)]
struct FurnishingRow {
    name: String,
    area_m2: f64,
    /// Deposition velocity onto all its faces together, m/s.
    all: Measured,
    top: Measured,
    bottom: Measured,
    /// Its four vertical faces together.
    sides: Measured,
    /// Per face, in face order (bottom, top, x0, x1, y0, y1): name, deposition velocity, and
    /// deposited count and mass.
    faces: Vec<FaceRow>,
    /// What it collected over the whole run, as a share of the release.
    deposited: Share,
}

/// One vertical wall of the room.
#[derive(Serialize)]
struct WallRow {
    wall: &'static str,
    velocity: Measured,
    deposited: usize,
    deposited_kg: f64,
}

/// The vertical walls' names, in id order.
const WALL_NAMES: [&str; 4] = ["x0", "x1", "y0", "y1"];

/// One face of a furnishing.
#[derive(Serialize)]
struct FaceRow {
    face: &'static str,
    velocity: Measured,
    deposited: usize,
    deposited_kg: f64,
}

/// Deposited count and mass (kg) per orientation over the whole run.
#[derive(Serialize)]
struct Deposited {
    floor: usize,
    floor_kg: f64,
    ceiling: usize,
    ceiling_kg: f64,
    walls: usize,
    walls_kg: f64,
}

/// One fate of the release: the count of tracked particles, their share of the released
/// number with its binomial standard error, their mass (kg) and its share of the released
/// mass, and on a surface the deposited mass per unit area per unit released mass (1/m^2,
/// i.e. kg/m^2 per kg released).
#[derive(Serialize)]
struct Share {
    count: usize,
    share: f64,
    share_error: f64,
    kg: f64,
    mass_share: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    loading_per_m2: Option<f64>,
}

impl Share {
    /// `(count, kg)` of `released`, onto a surface of `area` (m^2) if any.
    fn of((count, kg): (usize, f64), released: (usize, f64), area: Option<f64>) -> Self {
        let share = count as f64 / released.0.max(1) as f64;
        let mass_share = if released.1 > 0.0 { kg / released.1 } else { 0.0 };
        Self {
            count,
            share,
            share_error: binomial_error(share, released.0),
            kg,
            mass_share,
            loading_per_m2: area.map(|a| mass_share / a),
        }
    }
}

/// The steady state under a continuous source of one size (`depo_tracker::steady`).
#[derive(Serialize)]
struct Steady {
    /// Mean time an emitted particle stays in the air, h: the steady airborne number per
    /// particle emitted an hour.
    residence_h: Measured,
    /// The share of the source ending on the floor, ceiling, walls, furnishings, exhausted.
    floor: f64,
    ceiling: f64,
    walls: f64,
    furnishings: f64,
    exhausted: f64,
    /// Steady deposition velocities, m/s.
    floor_velocity: Measured,
    ceiling_velocity: Measured,
    walls_velocity: Measured,
    /// The share of the residence time taken from the room's late rates beyond the run.
    beyond_run: f64,
    /// With ventilation: the steady indoor/outdoor ratio, the entering outdoor particles' rate
    /// times their mean residence.
    #[serde(skip_serializing_if = "Option::is_none")]
    indoor_outdoor: Option<Measured>,
}

/// The release at the end of the run.
#[derive(Serialize)]
struct Release {
    particles: usize,
    kg: f64,
    floor: Share,
    ceiling: Share,
    walls: Share,
    /// On the furnishings' faces (present in a furnished room).
    #[serde(skip_serializing_if = "Option::is_none")]
    furnishings: Option<Share>,
    exhausted: Share,
    airborne: Share,
}

/// `beta` fitted to the decay curve: the total loss rate `k`, `beta = k - a`, both per hour
/// with the delta method's standard error, the fit's window and points, the fitted `beta`
/// less the study's with the standard error of that difference (paired over the particles,
/// which both rest on), and `z`, the difference in those standard errors: absent when either
/// `beta` rests on no event or has no error.
#[derive(Serialize)]
struct DecayFitRow {
    beta_per_hour: Measured,
    total_per_hour: Measured,
    window_s: [f64; 2],
    points: usize,
    difference_per_hour: Difference,
    z: Option<f64>,
}

/// A difference of two estimates from the same particles, with its paired standard error.
#[derive(Serialize)]
struct Difference {
    value: f64,
    error: f64,
}

/// A decay curve: sample times (s), the airborne share, its standard error, and the count.
#[derive(Serialize)]
struct Curve {
    times_s: Vec<f64>,
    airborne: Vec<f64>,
    error: Vec<f64>,
    count: Vec<usize>,
    #[serde(skip)]
    intercept: Option<f64>,
}

impl Curve {
    fn of(c: &DecayCurve) -> Self {
        Self {
            times_s: c.times.clone(),
            airborne: c.airborne.clone(),
            error: c.errors.clone(),
            count: c.counts.clone(),
            intercept: None,
        }
    }
}

#[derive(Serialize)]
struct Report<'a> {
    size_m: [f64; 3],
    friction_velocity: f64,
    air_changes_per_hour: f64,
    penetration: f64,
    /// Share of the air exchange through the filtered supply.
    supply_share: f64,
    /// Recirculation through its filter, room volumes per hour.
    recirculation_per_hour: f64,
    particles_per_size: usize,
    /// With a target: the relative standard error each size was run to reach, and the most
    /// particles it could take.
    target_error: Option<f64>,
    max_particles_per_size: usize,
    duration_s: f64,
    /// The air's volume (the room's less the furnishings'), m^3.
    air_volume_m3: f64,
    /// All surfaces' area (walls and furnishing faces) over the air's volume, 1/m.
    surface_to_volume_per_m: f64,
    sizes: &'a [Row],
    /// With a size distribution: where its mass went.
    #[serde(skip_serializing_if = "Option::is_none")]
    distribution: Option<&'a DistributionReport>,
}

/// A size's row of `scene`'s study; `density` its particles', kg/m^3; `filtration` the
/// study's filters.
fn row(p: &RoomPoint, scene: &Scene, density: f64, filtration: &Filtration) -> Row {
    let size = scene.geometry.size();
    let per_hour = |e: Estimate| Measured::from(e).scaled(3600.0);
    let (floor, ceiling, walls) = (Measured::from(p.floor), Measured::from(p.ceiling), Measured::from(p.walls));
    let unresolved =
        [("floor", &floor, p.model.floor), ("ceiling", &ceiling, p.model.ceiling), ("walls", &walls, p.model.wall)]
            .into_iter()
            .filter(|(_, m, model)| unresolved(m, *model, p.excursions.unwrap_or(0.0)))
            .map(|(name, ..)| name)
            .collect();
    Row {
        diameter_um: p.diameter * 1e6,
        density,
        floor,
        ceiling,
        walls,
        each_wall: (0..4)
            .map(|k| WallRow {
                wall: WALL_NAMES[k],
                velocity: p.each_wall[k].into(),
                deposited: p.wall_deposited[k].0,
                deposited_kg: p.wall_deposited[k].1,
            })
            .collect(),
        beta_per_hour: per_hour(p.beta),
        indoor_outdoor: p.indoor_outdoor.map(Measured::from),
        filter_removal_per_hour: (p.filter_removal > 0.0).then_some(p.filter_removal * 3600.0),
        // The supply filter acts on the exchange's air: only with ventilation.
        supply_filter_efficiency: (filtration.supply_share > 0.0 && p.indoor_outdoor.is_some())
            .then(|| filtration.supply_filter.at(p.diameter)),
        recirculation_filter_efficiency: (filtration.recirculation > 0.0)
            .then(|| filtration.recirculation_filter.at(p.diameter)),
        lai_nazaroff: Model {
            floor: p.model.floor,
            ceiling: p.model.ceiling,
            walls: p.model.wall,
            beta_per_hour: p.model_beta * 3600.0,
        },
        particle_steps: p.particle_steps,
        particles: p.particles,
        averaged_from_s: p.averaged_from,
        deposited_by_s: p.deposited_by,
        steady: p.steady.map(|st| {
            let [floor, ceiling, walls, furnishings, exhausted] = st.fates;
            let hours = |e: depo::tracker::Estimate| Estimate { value: e.value / 3600.0, error: e.error / 3600.0, ..e };
            Steady {
                residence_h: hours(st.residence).into(),
                floor,
                ceiling,
                walls,
                furnishings,
                exhausted,
                floor_velocity: st.deposition_velocity[0].into(),
                ceiling_velocity: st.deposition_velocity[1].into(),
                walls_velocity: st.deposition_velocity[2].into(),
                beyond_run: st.beyond_run,
                indoor_outdoor: p.steady_indoor_outdoor.map(Into::into),
            }
        }),
        method: match (&p.excursions, &scene.wall_function) {
            (Some(_), _) => "excursions",
            (None, Some(_)) => "wall-function",
            (None, None) => "plain",
        },
        excursions_truncated: p.excursions,
        longest_excursion_s: p.longest_excursion,
        class_sampling: p.class_sampling.map(|[floor, ceiling, walls, furnishings]| ClassSampling {
            floor,
            ceiling,
            walls,
            furnishings,
        }),
        wall_tally: p.tally.into(),
        surface_tallies: scene
            .surfaces()
            .iter()
            .zip(&p.tallies)
            .map(|(w, t)| SurfaceTally { surface: scene.surface_name(w.id), tally: (*t).into() })
            .collect(),
        release: {
            let floor = size[0] * size[1];
            let walls = 2.0 * (size[0] + size[1]) * size[2];
            let b = &p.balance;
            let released = (b.injected, b.injected_mass);
            Release {
                particles: b.injected,
                kg: b.injected_mass,
                floor: Share::of(p.deposited[0], released, Some(floor)),
                ceiling: Share::of(p.deposited[1], released, Some(floor)),
                walls: Share::of(p.deposited[2], released, Some(walls)),
                furnishings: (!p.furnishings.is_empty()).then(|| {
                    let on = p.furnishings.iter().fold((0, 0.0), |(n, m), f| (n + f.deposited.0, m + f.deposited.1));
                    Share::of(on, released, Some(p.furnishings.iter().map(|f| f.area).sum()))
                }),
                exhausted: Share::of((b.exhausted, b.exhausted_mass), released, None),
                airborne: Share::of((b.airborne, b.airborne_mass), released, None),
            }
        },
        decay_fit: p.decay_fit.map(|f| DecayFitRow {
            beta_per_hour: per_hour(f.beta),
            total_per_hour: per_hour(f.total),
            window_s: f.window,
            points: f.points,
            difference_per_hour: Difference {
                value: f.against_loss_rate.difference * 3600.0,
                error: f.against_loss_rate.error * 3600.0,
            },
            z: f.against_loss_rate.z,
        }),
        decay: Curve { intercept: p.decay_fit.map(|f| f.intercept), ..Curve::of(&p.decay) },
        deposited: Deposited {
            floor: p.deposited[0].0,
            floor_kg: p.deposited[0].1,
            ceiling: p.deposited[1].0,
            ceiling_kg: p.deposited[1].1,
            walls: p.deposited[2].0,
            walls_kg: p.deposited[2].1,
        },
        unresolved,
        furnishings: p
            .furnishings
            .iter()
            .map(|f| FurnishingRow {
                name: f.name.clone(),
                area_m2: f.area,
                all: f.all.into(),
                top: f.faces[1].into(),
                bottom: f.faces[0].into(),
                sides: f.sides.into(),
                faces: (0..6)
                    .map(|k| FaceRow {
                        face: FACE_NAMES[k],
                        velocity: f.faces[k].into(),
                        deposited: f.face_deposited[k].0,
                        deposited_kg: f.face_deposited[k].1,
                    })
                    .collect(),
                deposited: Share::of(f.deposited, (p.balance.injected, p.balance.injected_mass), Some(f.area)),
            })
            .collect(),
        maps: surface_maps(scene, p),
    }
}

pub fn run(args: &RoomArgs) -> Result<(), Error> {
    let scene = scene_file::room_scene(args.scene.as_deref())?;
    let mut study: RoomStudy = scene.study;
    if !args.no_plot {
        plot::check_directory(&args.plot)?;
    }
    // A size distribution runs the study at its bins instead of the study's diameters.
    let distribution = scene.distribution.map(|distribution| DistributionStudy { study: study.clone(), distribution });
    let runs = match &distribution {
        Some(d) => d.bins().map_err(|e| scene.source.scene_error(&e))?.0.len(),
        None => study.diameters.len(),
    };
    let progress = progress_bar(runs, "sizes")?;
    let start = std::time::Instant::now();
    let (points, balance) = match &distribution {
        Some(d) => {
            let (points, balance) =
                d.run(|done| progress.set_position(done as u64)).map_err(|e| scene.source.scene_error(&e))?;
            (points, Some(balance))
        }
        None => (study.run(|done| progress.set_position(done as u64)).map_err(|e| scene.source.scene_error(&e))?, None),
    };
    progress.finish_and_clear();
    if distribution.is_some() {
        study.diameters = points.iter().map(|p| p.diameter).collect();
    }
    let furnished = !study.scene.furnishings.is_empty();
    let distribution = balance.map(|b| {
        DistributionReport::new(&b, study.scene.free_volume(), (furnished, study.scene.exchange_rate() > 0.0))
    });
    let seconds = start.elapsed().as_secs_f64();
    let Geometry::Room { size } = study.scene.geometry else { unreachable!("a room study has a room") };
    let u_star = match study.scene.flow {
        Flow::TurbulentRoom { friction_velocity, .. } => friction_velocity,
        _ => 0.0,
    };
    // Each run's density: the bins' with a size distribution (in the points' order).
    let density = |i: usize| distribution.as_ref().map_or(study.density, |d| d.bins[i].density);
    let rows: Vec<Row> =
        points.iter().enumerate().map(|(i, p)| row(p, &study.scene, density(i), &study.filtration)).collect();
    let ventilated = study.scene.exchange_rate() > 0.0;
    let steps: u64 = rows.iter().map(|r| r.particle_steps).sum();
    match args.format {
        Format::Json => {
            let report = Report {
                size_m: size,
                friction_velocity: u_star,
                air_changes_per_hour: study.scene.exchange_rate() * 3600.0,
                penetration: study.penetration,
                supply_share: study.filtration.supply_share,
                recirculation_per_hour: study.filtration.recirculation * 3600.0,
                particles_per_size: study.count,
                target_error: study.target_error,
                max_particles_per_size: study.max_count,
                duration_s: study.scene.duration,
                air_volume_m3: study.scene.free_volume(),
                surface_to_volume_per_m: study.scene.surface_to_volume(),
                sizes: &rows,
                distribution: distribution.as_ref(),
            };
            out!("{}", serde_json::to_string_pretty(&report).map_err(|e| e.to_string())?);
        }
        // With a size distribution, the CSV is its mass balance (the per-size figures are in the JSON).
        Format::Csv if distribution.is_some() => distribution.as_ref().map_or(Ok(()), DistributionReport::csv)?,
        Format::Csv => {
            let mut header = vec![
                "diameter_um",
                "floor",
                "floor_error",
                "floor_deposits",
                "floor_lai_nazaroff",
                "ceiling",
                "ceiling_error",
                "ceiling_deposits",
                "ceiling_lai_nazaroff",
                "walls",
                "walls_error",
                "walls_deposits",
                "walls_lai_nazaroff",
                "x0",
                "x0_error",
                "x0_deposits",
                "x1",
                "x1_error",
                "x1_deposits",
                "y0",
                "y0_error",
                "y0_deposits",
                "y1",
                "y1_error",
                "y1_deposits",
                "beta_per_hour",
                "beta_error",
                "beta_lai_nazaroff",
            ];
            // Without ventilation the indoor/outdoor columns are left out.
            if ventilated {
                header.extend(["indoor_outdoor", "indoor_outdoor_error"]);
            }
            let supply_filtered = rows.iter().any(|r| r.supply_filter_efficiency.is_some());
            if supply_filtered {
                header.push("supply_filter_efficiency");
            }
            let recirculated = rows.iter().any(|r| r.recirculation_filter_efficiency.is_some());
            if recirculated {
                header.push("recirculation_filter_efficiency");
            }
            header.extend([
                "beta_fitted_per_hour",
                "beta_fitted_error",
                "floor_share",
                "ceiling_share",
                "walls_share",
                "exhausted_share",
                "airborne_share",
                "floor_kg",
                "ceiling_kg",
                "walls_kg",
                "exhausted_kg",
                "airborne_kg",
            ]);
            // A furnished room adds, per furnishing, its deposition velocity onto all its faces,
            // onto its top, and its share of the release; and the surface-to-volume ratio.
            let names: Vec<String> = study.scene.furnishings.iter().enumerate().map(|(k, f)| f.label(k)).collect();
            let furnishing_columns: Vec<String> = names
                .iter()
                .flat_map(|n| {
                    ["vd", "vd_error", "deposits", "top_vd", "top_vd_error", "share", "kg"].map(|c| format!("{n}_{c}"))
                })
                .collect();
            header.extend(furnishing_columns.iter().map(String::as_str));
            if furnished {
                header.extend(["furnishings_share", "surface_to_volume_per_m"]);
            }
            let surface_to_volume = study.scene.surface_to_volume();
            print_csv(
                &header,
                rows.iter().map(|r| {
                    let n = |m: &Measured| m.events.to_string();
                    let x = |v: f64| v.to_string();
                    let mut row = vec![
                        x(r.diameter_um),
                        x(r.floor.value),
                        x(r.floor.error),
                        n(&r.floor),
                        x(r.lai_nazaroff.floor),
                        x(r.ceiling.value),
                        x(r.ceiling.error),
                        n(&r.ceiling),
                        x(r.lai_nazaroff.ceiling),
                        x(r.walls.value),
                        x(r.walls.error),
                        n(&r.walls),
                        x(r.lai_nazaroff.walls),
                    ];
                    for w in &r.each_wall {
                        row.extend([x(w.velocity.value), x(w.velocity.error), n(&w.velocity)]);
                    }
                    row.extend([x(r.beta_per_hour.value), x(r.beta_per_hour.error), x(r.lai_nazaroff.beta_per_hour)]);
                    if ventilated {
                        let io = r.indoor_outdoor.as_ref().map_or([f64::NAN; 2], |m| [m.value, m.error]);
                        row.extend([x(io[0]), x(io[1])]);
                    }
                    if supply_filtered {
                        row.push(x(r.supply_filter_efficiency.unwrap_or(0.0)));
                    }
                    if recirculated {
                        row.push(x(r.recirculation_filter_efficiency.unwrap_or(0.0)));
                    }
                    let fitted =
                        r.decay_fit.as_ref().map_or([f64::NAN; 2], |f| [f.beta_per_hour.value, f.beta_per_hour.error]);
                    let release = &r.release;
                    row.extend([fitted[0], fitted[1]].map(x));
                    row.extend(
                        [&release.floor, &release.ceiling, &release.walls, &release.exhausted, &release.airborne]
                            .map(|s| x(s.share)),
                    );
                    row.extend(
                        [&release.floor, &release.ceiling, &release.walls, &release.exhausted, &release.airborne]
                            .map(|s| x(s.kg)),
                    );
                    for f in &r.furnishings {
                        row.extend([
                            x(f.all.value),
                            x(f.all.error),
                            n(&f.all),
                            x(f.top.value),
                            x(f.top.error),
                            x(f.deposited.share),
                            x(f.deposited.kg),
                        ]);
                    }
                    if let Some(share) = &release.furnishings {
                        row.extend([x(share.share), x(surface_to_volume)]);
                    }
                    row
                }),
            )?;
        }
        Format::Table => {
            let particles: Vec<String> = rows.iter().map(|r| r.particles.to_string()).collect();
            out!(
                "Room {} x {} x {} m, u* = {} m/s, {} particles per size, {} s; deposition velocity (m/s) per surface",
                shown(size[0]),
                shown(size[1]),
                shown(size[2]),
                shown(u_star),
                particles.join("/"),
                shown(study.scene.duration)
            );
            if let Some(target) = study.target_error {
                out!(
                    "({} first, more up to {} where beta or a surface with Lai & Nazaroff's v_d >= 1e-7 m/s was above {} % error.)",
                    study.count,
                    study.max_count,
                    shown(100.0 * target)
                );
            }
            out!("beside Lai & Nazaroff (2000) for the same u*; ratio = beta / Lai & Nazaroff's beta.");
            if ventilated {
                out!(
                    "Ventilated: {} air changes per hour, penetration {}; C_in/C_out = P a / (a + beta) at steady state.",
                    // To a thousandth: with openings the rate is a flow over a volume.
                    format!("{:.3}", study.scene.exchange_rate() * 3600.0).trim_end_matches('0').trim_end_matches('.'),
                    study.penetration
                );
            }
            if !study.scene.openings.is_empty() {
                out!(
                    "Through {} openings: air and particles from the supply to the exhaust in a potential flow; \
                     particles leave at the exhaust (a = exhaust flow / air volume).",
                    study.scene.openings.len()
                );
            }
            let f = &study.filtration;
            // Each filter's single-pass efficiency at the sizes run, where it acts.
            let efficiencies = |pick: &dyn Fn(&Row) -> Option<f64>| -> Option<String> {
                let values: Option<Vec<String>> = rows.iter().map(|r| pick(r).map(|e| format!("{e:.3}"))).collect();
                values.map(|v| v.join(", "))
            };
            if let Some(list) = efficiencies(&|r| r.supply_filter_efficiency) {
                out!("Supply filter efficiency eta_s at the sizes run: {list}.");
            }
            if let Some(list) = efficiencies(&|r| r.recirculation_filter_efficiency) {
                out!("Recirculation filter efficiency eta_r at the sizes run: {list}.");
            }
            if f.supply_share > 0.0 || f.recirculation > 0.0 {
                out!(
                    "Filters: a share {} of the exchange through the supply filter, recirculation {} per hour through its \
                     filter (its removal eta_r a_r, added to the exhaust: {} per hour at the sizes run); \
                     C_in/C_out = (P (1 - s) a + (1 - eta_s) s a) / (a + eta_r a_r + beta).",
                    f.supply_share,
                    f.recirculation * 3600.0,
                    rows.iter()
                        .map(|r| format!("{:.3}", r.filter_removal_per_hour.unwrap_or(0.0)))
                        .collect::<Vec<_>>()
                        .join(", ")
                );
            }
            out!(
                "{:>8}  {:>27} {:>9}  {:>27} {:>9}  {:>27} {:>9}  {:>20} {:>7} {:>6}{}  method",
                "d (um)",
                "floor",
                "L&N",
                "ceiling",
                "L&N",
                "walls",
                "L&N",
                "beta (1/h)",
                "L&N",
                "ratio",
                if ventilated { format!("  {:>18}", "C_in/C_out") } else { String::new() }
            );
            // A surface's figure, flagged with `*` when unresolved.
            let cell = |r: &Row, name: &str, m: &Measured| {
                format!("{}{}", m.cell(), if r.unresolved.contains(&name) { "*" } else { " " })
            };
            for (i, r) in rows.iter().enumerate() {
                density_heading(&rows, i);
                let method = match (r.excursions_truncated, r.longest_excursion_s) {
                    (Some(t), Some(s)) if t > 1e-3 => format!("excursions ({:.1} % at {s:.0} s)", 100.0 * t),
                    (Some(_), _) => "excursions".to_string(),
                    (None, _) => r.method.to_string(),
                };
                // Averaged from the release: every particle had left before the window.
                let method =
                    if r.averaged_from_s == 0.0 && study.transient > 0.0 { format!("{method} +") } else { method };
                out!(
                    "{:>8.3}  {:>27} {:>9}  {:>27} {:>9}  {:>27} {:>9}  {:>20} {:>7.3} {:>6.2}{}  {method}",
                    r.diameter_um,
                    cell(r, "floor", &r.floor),
                    model_cell(r.lai_nazaroff.floor),
                    cell(r, "ceiling", &r.ceiling),
                    model_cell(r.lai_nazaroff.ceiling),
                    cell(r, "walls", &r.walls),
                    model_cell(r.lai_nazaroff.walls),
                    rate_cell(&r.beta_per_hour),
                    r.lai_nazaroff.beta_per_hour,
                    r.beta_per_hour.value / r.lai_nazaroff.beta_per_hour,
                    r.indoor_outdoor
                        .as_ref()
                        .map_or(String::new(), |m| format!("  {:>18}", format!("{:.3} +- {:.3}", m.value, m.error)))
                );
            }
            // The four walls apart where they can differ: in material, or in the openings' flow.
            let walls = &study.scene.walls[2..6];
            if walls.iter().any(|w| *w != walls[0]) || !study.scene.openings.is_empty() {
                walls_table(&rows);
            }
            if furnished {
                furnishings_table(&rows, &study);
            }
            out!("{ERROR_NOTE}");
            let model = |r: &Row| [r.lai_nazaroff.floor, r.lai_nazaroff.ceiling, r.lai_nazaroff.walls];
            if rows.iter().flat_map(model).any(|v| v < MODEL_NONE) {
                out!(
                    "L&N < {MODEL_NONE:.0e}: Lai & Nazaroff give below {MODEL_NONE:.0e} m/s (the ceiling for coarse particles), no deposition."
                );
            }
            if rows.iter().any(|r| r.averaged_from_s == 0.0) && study.transient > 0.0 {
                out!(
                    "+ every particle left the air before the averaging window opened: averaged over the release from t = 0 (what became of it, not a well-mixed room's rates; the times by which half and 90 % had deposited are in the release table)."
                );
            }
            if rows.iter().any(|r| !r.unresolved.is_empty()) {
                out!(
                    "* unresolved: no deposit event, or, where Lai & Nazaroff give at least {:.0e} m/s, a relative standard error or a share given up above {} %.",
                    RESOLVABLE,
                    100.0 * RESOLVED_ERROR
                );
                let more: Vec<String> = rows
                    .iter()
                    .filter_map(|r| {
                        let model = &r.lai_nazaroff;
                        let figures = [(&r.floor, model.floor), (&r.ceiling, model.ceiling), (&r.walls, model.walls)];
                        particles_to_resolve(r.particles, figures).map(|n| {
                            format!("{} particles at {} um", two_figures_up(n), (r.diameter_um * 1e4).round() / 1e4)
                        })
                    })
                    .collect();
                if !more.is_empty() {
                    out!(
                        "  Errors above {} % would take about {} (an error falls as one over the square root of the particles; particles.max_count in a scene file).",
                        100.0 * RESOLVED_ERROR,
                        more.join(", ")
                    );
                }
            }
            out!(
                "Averages from {} s to {} s; {steps} particle-steps tracked (excursions not counted) in {seconds:.1} s.",
                shown(study.transient * study.scene.duration),
                shown(study.scene.duration)
            );
            decay_table(&rows, study.scene.exchange_rate() * 3600.0, !study.scene.openings.is_empty());
            steady_table(&rows);
        }
    }
    if let (Format::Table, Some(d)) = (args.format, &distribution) {
        d.table();
    }
    if !args.no_plot {
        plot_room(&args.plot, &study, &rows)?;
        if let Some(d) = &distribution {
            let figure = args.plot.join("room-distribution.svg");
            d.plot(&figure)?;
            let pm = args.plot.join("room-pm.svg");
            d.plot_pm(&pm)?;
            eprintln!("figures: {} and {}", figure.display(), pm.display());
        }
    }
    Ok(())
}

/// Before the first row of each density, where the rows have several: the density.
fn density_heading(rows: &[Row], i: usize) {
    let several = rows.iter().any(|r| r.density != rows[0].density);
    if several && (i == 0 || rows[i - 1].density != rows[i].density) {
        out!("particle density {} kg/m^3:", shown(rows[i].density));
    }
}

/// The rows' densities after a diameter or in a file name, where they have several: `""`
/// or `", 1500 kg/m^3"` (`sep` `", "`, `unit` `" kg/m^3"`).
fn density_label(rows: &[Row], density: f64, sep: &str, unit: &str) -> String {
    if rows.iter().any(|r| r.density != rows[0].density) {
        format!("{sep}{density}{unit}")
    } else {
        String::new()
    }
}

/// Each vertical wall's deposition velocity, where the walls differ.
fn walls_table(rows: &[Row]) {
    out!("Each vertical wall (m/s; x0 at x = 0, x1 opposite it, y0 at y = 0, y1 opposite it):");
    out!("{:>8}  {:>27}  {:>27}  {:>27}  {:>27}", "d (um)", "x0", "x1", "y0", "y1");
    for r in rows {
        let cells: Vec<String> = r.each_wall.iter().map(|w| w.velocity.cell()).collect();
        out!("{:>8.3}  {:>27}  {:>27}  {:>27}  {:>27}", r.diameter_um, cells[0], cells[1], cells[2], cells[3]);
    }
}

/// The furnishings' table under the per-size one: per size and furnishing, the deposition
/// velocity (m/s) onto all its faces, its top, its bottom and its sides, and its share of the
/// release.
fn furnishings_table(rows: &[Row], study: &RoomStudy) {
    let scene = &study.scene;
    out!(
        "Furnishings: {} boxes, {:.3} m^3 of air; surface-to-volume ratio {:.3} 1/m (walls and faces over the air's volume); Lai & Nazaroff's beta above is the bare room's.",
        scene.furnishings.len(),
        scene.free_volume(),
        scene.surface_to_volume()
    );
    out!(
        "{:>8}  {:>12} {:>8}  {:>27}  {:>27}  {:>27}  {:>27}  {:>16}",
        "d (um)",
        "furnishing",
        "area m^2",
        "all faces",
        "top",
        "bottom",
        "sides",
        "share of release"
    );
    for r in rows {
        for f in &r.furnishings {
            out!(
                "{:>8.3}  {:>12} {:>8.3}  {:>27}  {:>27}  {:>27}  {:>27}  {:>16}",
                r.diameter_um,
                f.name,
                f.area_m2,
                f.all.cell(),
                f.top.cell(),
                f.bottom.cell(),
                f.sides.cell(),
                format!("{:.4} +- {:.4}", f.deposited.share, f.deposited.share_error)
            );
        }
    }
}

/// A rate per hour with its standard error: fixed-point from 0.1/h, else in e-notation.
fn rate_cell(m: &Measured) -> String {
    if m.value.abs() >= 0.1 {
        format!("{:.3} +- {:.3}", m.value, m.error)
    } else {
        format!("{:.2e} +- {:.1e}", m.value, m.error)
    }
}

/// Fewer deposits than this within the decay fit's window are flagged in the table: the
/// fitted `beta` then rests on a handful of events (a relative Poisson error above 30 %) and
/// its delta-method error is itself uncertain.
const FEW_DEPOSITS: usize = 10;

/// The fitted `beta` per hour: `value +- error [deposits]`, flagged `?` with fewer than
/// [`FEW_DEPOSITS`], or `< bound [0]` (the 95 % upper bound) with none.
fn fitted_cell(m: &Measured) -> String {
    match m.upper_bound {
        Some(bound) => format!("< {bound:.2e} [0]"),
        None => format!("{} [{}]{}", rate_cell(m), m.events, if m.events < FEW_DEPOSITS { "?" } else { "" }),
    }
}

/// The table's second part: each size read as a decay experiment (the fitted `beta` beside
/// the study's) and where the release ends; `ach` the air changes per hour, `openings`
/// whether the exhaust is through openings (whose air need not be the room's mean).
fn decay_table(rows: &[Row], ach: f64, openings: bool) {
    out!("");
    out!(
        "After the release at t = 0, as a decay experiment reads it: beta fitted = the least-squares slope of ln N(t) \
         over the window (from the averages' start while >= {MIN_AIRBORNE} particles are airborne), less a = {ach} /h, \
         [deposits in the window], ? fewer than {FEW_DEPOSITS}; z = (fitted - beta) / the standard error of that \
         difference, paired over the particles both rest on (- where either has no event or no error). Then where the released \
         particles are at the end, % of the number (for one size also of the mass), and the floor's loading per mg \
         released."
    );
    out!(
        "{:>8}  {:>28} {:>6} {:>12}  {:>7} {:>7} {:>7}{} {:>9} {:>8}  {:>20}  {:>28}",
        "d (um)",
        "beta fitted (1/h)",
        "z",
        "window (s)",
        "floor",
        "ceiling",
        "walls",
        // A furnished room's release has a part on the furnishings.
        if rows.iter().any(|r| r.release.furnishings.is_some()) {
            format!(" {:>11}", "furnishings")
        } else {
            String::new()
        },
        "exhausted",
        "airborne",
        "floor (ug/m2 per mg)",
        "50 % / 90 % deposited by (s)"
    );
    for (i, r) in rows.iter().enumerate() {
        density_heading(rows, i);
        let (fitted, z, window) = match &r.decay_fit {
            Some(f) => (
                fitted_cell(&f.beta_per_hour),
                f.z.map_or("-".to_string(), |z| format!("{z:.1}")),
                format!("{:.0}-{:.0}", f.window_s[0], f.window_s[1]),
            ),
            None => ("no fit".to_string(), "-".to_string(), "-".to_string()),
        };
        let release = &r.release;
        let pct = |s: &Share| format!("{:.1}", 100.0 * s.share);
        out!(
            "{:>8.3}  {:>28} {:>6} {:>12}  {:>7} {:>7} {:>7}{} {:>9} {:>8}  {:>20.3e}  {:>28}",
            r.diameter_um,
            fitted,
            z,
            window,
            pct(&release.floor),
            pct(&release.ceiling),
            pct(&release.walls),
            release.furnishings.as_ref().map_or(String::new(), |s| format!(" {:>11}", pct(s))),
            pct(&release.exhausted),
            pct(&release.airborne),
            // kg/m^2 per kg released, for 1 mg released, in ug/m^2.
            release.floor.loading_per_m2.unwrap_or(0.0) * 1e3,
            r.deposited_by_s.map(|t| t.map_or("-".to_string(), |t| format!("{t:.0}"))).join(" / ")
        );
    }
    out!(
        "The curve counts the tracked particles, which leave the air by their own deposits: where deposition \
         is rare it resolves beta far less well than the study's excursions (compare the errors)."
    );
    let apart = rows.iter().filter_map(|r| r.decay_fit.as_ref()?.z).any(|z| z.abs() > 3.0);
    if openings && apart {
        out!(
            "! beta fitted differs from the study's beta by more than 3 standard errors: through openings the exhaust \
             draws the air near it, older or fresher than the room's mean, so the decay less a holds that difference \
             too and is no deposition rate; the study's beta (deposits over airborne time) is (docs/tracker.md, \
             \"What it means\")."
        );
    }
}

/// The steady state under a continuous source, per size (`depo_tracker::steady`).
fn steady_table(rows: &[Row]) {
    out!("");
    out!(
        "Under a continuous source (emitted uniformly over the room at a constant rate: indoors, or outdoor air \
         infiltrating), at steady state, from the release followed from t = 0: the mean time in the air (the airborne \
         number per particle emitted an hour), the deposition velocities (flux over the mean concentration), the share \
         of the source ending in each place, % (and the share of the time in the air from beyond the run, the room's \
         late rates'), and with ventilation C_in/C_out."
    );
    let ventilated = rows.iter().any(|r| r.steady.as_ref().is_some_and(|s| s.indoor_outdoor.is_some()));
    out!(
        "{:>8}  {:>18}  {:>27} {:>27} {:>27}  {:>6} {:>7} {:>6} {:>7} {:>9} {:>7}{}",
        "d (um)",
        "time in air (h)",
        "floor (m/s)",
        "ceiling (m/s)",
        "walls (m/s)",
        "floor",
        "ceiling",
        "walls",
        "furnish",
        "exhausted",
        "beyond",
        if ventilated { format!("  {:>18}", "C_in/C_out") } else { String::new() }
    );
    for (i, r) in rows.iter().enumerate() {
        density_heading(rows, i);
        let Some(st) = &r.steady else {
            out!("{:>8.3}  nothing removes these particles: no steady state", r.diameter_um);
            continue;
        };
        let pct = |x: f64| format!("{:.1}", 100.0 * x);
        out!(
            "{:>8.3}  {:>18}  {:>27} {:>27} {:>27}  {:>6} {:>7} {:>6} {:>7} {:>9} {:>7}{}",
            r.diameter_um,
            format!("{:.3} +- {:.3}", st.residence_h.value, st.residence_h.error),
            st.floor_velocity.cell(),
            st.ceiling_velocity.cell(),
            st.walls_velocity.cell(),
            pct(st.floor),
            pct(st.ceiling),
            pct(st.walls),
            pct(st.furnishings),
            pct(st.exhausted),
            pct(st.beyond_run),
            st.indoor_outdoor
                .as_ref()
                .map_or(String::new(), |m| format!("  {:>18}", format!("{:.3} +- {:.3}", m.value, m.error)))
        );
    }
}

/// Below this deposition velocity (m/s) the table prints Lai & Nazaroff's as `< 1e-30`: their
/// ceiling velocity for coarse particles falls to 1e-138 m/s and to 0 in double precision,
/// no deposit a room could show.
const MODEL_NONE: f64 = 1e-30;

/// Lai & Nazaroff's deposition velocity (m/s) in the table: `1.78e-5`, or `< 1e-30` below
/// [`MODEL_NONE`].
fn model_cell(v: f64) -> String {
    if v < MODEL_NONE {
        format!("< {MODEL_NONE:.0e}")
    } else {
        format!("{v:.2e}")
    }
}

/// Below this deposition velocity (m/s) a model curve is not drawn: Lai & Nazaroff's ceiling
/// for coarse particles reaches 1e-138 m/s, nothing a room shows. The legend says where.
const MODEL_FLOOR: f64 = 1e-10;

/// What a deposition map of the surface `name` outlines, in its in-plane coordinates in the
/// order x, y, z: the openings in it, and on the floor the furnishings' footprints.
fn outlines(study: &RoomStudy, r: &Row, name: &str) -> Vec<(String, [(f64, f64); 2])> {
    let scene = &study.scene;
    let mut out: Vec<(String, [(f64, f64); 2])> = scene
        .openings
        .iter()
        .filter(|o| scene.surface_name(o.wall) == name)
        .map(|o| {
            let ([c0, c1], [s0, s1]) = (o.center, o.size);
            let kind = format!("{:?}", o.kind).to_lowercase();
            (kind, [(c0 - s0 / 2.0, c1 - s1 / 2.0), (c0 + s0 / 2.0, c1 + s1 / 2.0)])
        })
        .collect();
    if name == "floor" {
        for (box_, row) in scene.furnishings.iter().zip(&r.furnishings) {
            out.push((row.name.clone(), [(box_.low[0], box_.low[1]), (box_.high[0], box_.high[1])]));
        }
    }
    out
}

/// `x` to `n` significant digits (all of its integer part), without trailing zeros: `12.3`
/// for 12.2828.
fn significant(x: f64, n: i32) -> String {
    if x == 0.0 || !x.is_finite() {
        return x.to_string();
    }
    let decimals = (n - 1 - x.abs().log10().floor() as i32).max(0) as usize;
    let s = format!("{x:.decimals$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

/// `n` log-spaced points from `from` to `to`; around `from` when the two are equal.
pub fn log_grid(from: f64, to: f64, n: usize) -> Vec<f64> {
    let (from, to) = if from < to { (from, to) } else { (from / 2.0, to * 2.0) };
    (0..n).map(|i| from * (to / from).powf(i as f64 / (n - 1) as f64)).collect()
}

/// The room's figures and deposition maps into `dir`.
fn plot_room(dir: &std::path::Path, study: &RoomStudy, rows: &[Row]) -> Result<(), Error> {
    // Lai & Nazaroff on 100 sizes across the study's, from the same model and inputs the
    // study compares with (its air, gravity and friction velocity).
    let u_star = study.scene.flow.friction_velocity().unwrap_or(0.0);
    let g = study.scene.gravity.iter().map(|g| g * g).sum::<f64>().sqrt();
    let size = study.scene.geometry.size();
    // Per density (a size distribution's bins can have several): Lai & Nazaroff for it across
    // its sizes, depo's values in their own colours.
    let mut deposition_series = Vec::new();
    let mut beta_series = Vec::new();
    for (k, rho) in first_seen(rows.iter().map(|r| r.density)).into_iter().enumerate() {
        let own: Vec<&Row> = rows.iter().filter(|r| r.density == rho).collect();
        let of = density_label(rows, rho, ", ", " kg/m^3");
        let (lo, hi) =
            own.iter().fold((f64::INFINITY, 0.0f64), |(a, b), r| (a.min(r.diameter_um), b.max(r.diameter_um)));
        let model: Vec<(f64, LaiNazaroff)> = log_grid(lo * 1e-6, hi * 1e-6, 100)
            .into_iter()
            .map(|d| (d * 1e6, LaiNazaroff::new(d, rho, &study.scene.air, g, u_star)))
            .collect();
        let curve = |name: &str, pick: &dyn Fn(&LaiNazaroff) -> f64, color: usize| {
            let points: Vec<(f64, f64)> =
                model.iter().map(|(d, m)| (*d, pick(m))).filter(|p| p.1 > MODEL_FLOOR).collect();
            let name = if points.len() < model.len() {
                format!("{name} (Lai & Nazaroff{of}; below {MODEL_FLOOR:.0e} m/s not shown)")
            } else {
                format!("{name} (Lai & Nazaroff{of})")
            };
            Series::line(name, points).color(color)
        };
        // depo's values with their standard errors, and where a surface had no deposit its 95 %
        // upper bound.
        let measured = |name: &str, pick: &dyn Fn(&Row) -> &Measured, color: usize| {
            let hit: Vec<&&Row> = own.iter().filter(|r| pick(r).upper_bound.is_none()).collect();
            let bounds: Vec<(f64, f64)> =
                own.iter().filter_map(|r| pick(r).upper_bound.map(|b| (r.diameter_um, b))).collect();
            let mut series = vec![Series::markers(
                format!("{name}{of} (depo, +- 1 s.e.)"),
                hit.iter().map(|r| (r.diameter_um, pick(r).value)).collect(),
            )
            .with_errors(hit.iter().map(|r| pick(r).error).collect())
            .color(color)];
            if !bounds.is_empty() {
                series.push(
                    Series::upper_bounds(format!("{name}{of}: no deposit, 95 % upper bound"), bounds).color(color),
                );
            }
            series
        };
        // Each density in its own colours: three for the room's surfaces, then one for each
        // furnishing's faces together, beside them.
        let boxes = own.first().map_or(0, |r| r.furnishings.len());
        let c = (3 + boxes) * k;
        deposition_series.extend(measured("floor", &|r| &r.floor, c));
        deposition_series.extend(measured("ceiling", &|r| &r.ceiling, c + 1));
        deposition_series.extend(measured("walls", &|r| &r.walls, c + 2));
        for j in 0..boxes {
            let name = format!("{} (all faces)", own[0].furnishings[j].name);
            deposition_series.extend(measured(&name, &|r| &r.furnishings[j].all, c + 3 + j));
        }
        deposition_series.push(curve("floor", &|m| m.floor, c));
        deposition_series.push(curve("ceiling", &|m| m.ceiling, c + 1));
        deposition_series.push(curve("walls", &|m| m.wall, c + 2));
        beta_series.extend(measured("beta", &|r| &r.beta_per_hour, 2 * k));
        beta_series.push(
            Series::line(
                format!("Lai & Nazaroff (2000){of}"),
                model.iter().map(|(d, m)| (*d, m.loss_rate(size) * 3600.0)).collect(),
            )
            .color(2 * k + 1),
        );
    }
    let deposition = dir.join("room-deposition.svg");
    plot::log_log(
        &deposition,
        "Deposition velocity in a room",
        "particle diameter (um)",
        "deposition velocity (m/s)",
        &deposition_series,
    )?;
    let beta = dir.join("room-beta.svg");
    plot::log_log(&beta, "Loss-rate coefficient", "particle diameter (um)", "beta (1/h)", &beta_series)?;
    // With ventilation, the steady indoor/outdoor ratio per size, with its error from beta's.
    let indoor_outdoor = dir.join("room-indoor-outdoor.svg");
    let ventilated = rows.iter().any(|r| r.indoor_outdoor.is_some());
    if ventilated {
        let series: Vec<Series> = first_seen(rows.iter().map(|r| r.density))
            .into_iter()
            .enumerate()
            .map(|(k, rho)| {
                let own: Vec<(f64, &Measured)> = rows
                    .iter()
                    .filter(|r| r.density == rho)
                    .filter_map(|r| r.indoor_outdoor.as_ref().map(|m| (r.diameter_um, m)))
                    .collect();
                let of = density_label(rows, rho, ", ", " kg/m^3");
                Series::markers(
                    format!("C_in / C_out{of} (depo, +- 1 s.e.)"),
                    own.iter().map(|(d, m)| (*d, m.value)).collect(),
                )
                .with_errors(own.iter().map(|(_, m)| m.error).collect())
                .color(k)
            })
            .collect();
        plot::lines(
            &indoor_outdoor,
            "Indoor/outdoor concentration ratio at steady state",
            "particle diameter (um)",
            "C_in / C_out",
            &series,
            true,
        )?;
        eprintln!("figure: {}", indoor_outdoor.display());
    }
    // The decay curves, a panel per size on shared axes (the sizes' curves, all near 1 where
    // deposition is slow, would hide each other on one chart): the airborne share with its
    // standard error, the fitted line over its window, and what ventilation alone would leave;
    // the curves also as one CSV.
    let decay = dir.join("room-decay.svg");
    let a = study.scene.exchange_rate();
    let end = study.scene.duration;
    let ventilation = |name: &str| Series::line(name, vec![(0.0, 1.0), (end / 60.0, (-a * end).exp())]).color(7);
    let mut panels = Vec::new();
    // One row per size and time; the particle density beside the diameter, since a study
    // of several densities (distribution modes) has sizes of the same diameter.
    let mut text = String::from("diameter_um,density_kg_m3,time_s,airborne,error,count\n");
    for r in rows {
        let c = &r.decay;
        let label = format!("{} um{}", significant(r.diameter_um, 3), density_label(rows, r.density, ", ", " kg/m^3"));
        let minutes: Vec<f64> = c.times_s.iter().map(|t| t / 60.0).collect();
        let mut series =
            vec![Series::markers("depo", minutes.iter().copied().zip(c.airborne.iter().copied()).collect())
                .with_errors(c.error.clone())
                .color(0)];
        let mut notes = Vec::new();
        if let (Some(f), Some(intercept)) = (&r.decay_fit, c.intercept) {
            let k = f.total_per_hour.value / 3600.0;
            let line = f.window_s.iter().map(|&t| (t / 60.0, (intercept - k * t).exp())).collect();
            series.push(Series::line("fit", line).dashed().color(1));
            let beta = match f.beta_per_hour.upper_bound {
                Some(bound) => format!("< {bound:.2e}"),
                None => rate_cell(&f.beta_per_hour),
            };
            notes.push(format!("fitted beta {beta} /h"));
        }
        if a > 0.0 {
            series.push(ventilation("ventilation"));
        }
        panels.push(plot::Panel { name: label, series, notes });
        for k in 0..c.times_s.len() {
            text.push_str(&format!(
                "{},{},{},{},{},{}\n",
                r.diameter_um, r.density, c.times_s[k], c.airborne[k], c.error[k], c.count[k]
            ));
        }
    }
    let mut key = vec![
        // A point for its error bar's symbol; the key draws no points.
        Series::markers("airborne share (depo, +- 1 s.e.)", vec![(0.0, 1.0)]).with_errors(vec![0.0]).color(0),
        Series::line("exponential fitted over its window, beta = its slope less a", Vec::new()).dashed().color(1),
    ];
    if a > 0.0 {
        key.push(ventilation(&format!("ventilation alone, exp(-a t), a = {} /h", shown(a * 3600.0))));
    }
    plot::small_multiples(
        &decay,
        "Airborne share after a release, per particle size",
        ("time (min)", "N(t) / N(0)"),
        &panels,
        &key,
        (false, true),
    )?;
    let curves = dir.join("room-decay.csv");
    std::fs::write(&curves, text).map_err(|e| format!("cannot write {}: {e}", curves.display()))?;
    // Deposition maps, one CSV per surface (walls, then furnishing faces, named as
    // `table.top`) and size, under a header of `#` lines, and a figure per size.
    for r in rows {
        let label = (r.diameter_um * 1e4).round() / 1e4;
        let mut panels = Vec::new();
        for m in &r.maps {
            let ((ra, r0, r1), (ca, c0, c1)) = (m.rows, m.columns);
            let (n, k) = (m.cells.len(), m.cells.first().map_or(0, Vec::len));
            let mut text = format!(
                "# depo room deposition map: {} {} ({} = {} m), particle diameter {label} um, density {} kg/m^3; \
                 deposits of the tracked particles over the whole run, per cell\n\
                 # rows: {ra} from {r0} to {r1} m in {n} cells; columns: {ca} from {c0} to {c1} m in {k} cells\n\
                 # cell size {} m ({ra}) x {} m ({ca})\n",
                m.kind,
                m.surface,
                m.normal.0,
                m.normal.1,
                r.density,
                (r1 - r0) / n as f64,
                (c1 - c0) / k as f64,
            );
            for row in &m.cells {
                let cells: Vec<String> = row.iter().map(u32::to_string).collect();
                text.push_str(&cells.join(","));
                text.push('\n');
            }
            // Bins of two densities can share a diameter: the density tells their files apart.
            let name = &m.surface;
            let path =
                dir.join(format!("room-map-{name}-{label}um{}.csv", density_label(rows, r.density, "-", "kgm3")));
            std::fs::write(&path, text).map_err(|e| format!("cannot write {}: {e}", path.display()))?;
            // The figure shows the room's six surfaces and each furnishing's top, the second
            // in-plane axis up (z on a wall, y on the floor and ceiling).
            if m.kind == "wall" || name.ends_with(".top") {
                let cells = (0..k).map(|j| (0..n).map(|i| m.cells[i][j]).collect());
                let axes = [m.columns, m.rows];
                let outlines = outlines(study, r, name);
                panels.push(plot::MapPanel { name: name.clone(), cells: cells.collect(), axes, outlines });
            }
        }
        let figure = dir.join(format!("room-map-{label}um{}.svg", density_label(rows, r.density, "-", "kgm3")));
        let title =
            format!("Deposits of the tracked particles, {label} um{}", density_label(rows, r.density, ", ", " kg/m^3"));
        plot::maps(&figure, &title, &panels)?;
    }
    eprintln!(
        "figures: {}, {} and {}; decay curves: {}; deposition maps ({}x{} cells per surface): {}/room-map-SURFACE-SIZEum{}.csv, drawn per size as room-map-SIZEum.svg",
        deposition.display(),
        beta.display(),
        decay.display(),
        curves.display(),
        MAP_BINS[0],
        MAP_BINS[1],
        dir.display(),
        if first_seen(rows.iter().map(|r| r.density)).len() > 1 { "-DENSITYkgm3" } else { "" }
    );
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Resolved: events, and where the model asks it, an error and a given-up share within 5 %.
    /// `depo room --help` states the excursions' longest duration and its doublings in words.
    #[test]
    fn the_help_s_excursion_numbers_are_the_study_s() {
        assert_eq!(studies::ROOM_LONGEST_EXCURSION, 16000.0);
        assert_eq!(studies::LONGEST_SHARE, 0.025);
        assert_eq!(1 << studies::LONGEST_DOUBLINGS, 8);
    }

    #[test]
    fn a_vanishing_model_velocity_reads_as_a_bound() {
        assert_eq!(model_cell(1.97e-138), "< 1e-30");
        assert_eq!(model_cell(0.0), "< 1e-30");
        assert_eq!(model_cell(1.78e-5), "1.78e-5");
    }

    #[test]
    fn significant_digits_drop_trailing_zeros() {
        assert_eq!(significant(12.2828, 3), "12.3");
        assert_eq!(significant(0.011719, 3), "0.0117");
        assert_eq!(significant(10.0, 3), "10");
        assert_eq!(significant(0.3, 3), "0.3");
        assert_eq!(significant(1234.6, 3), "1235");
    }

    #[test]
    fn a_figure_is_unresolved_by_its_error_or_by_what_its_excursions_gave_up() {
        let m = |error: f64, events| Measured { value: 1e-6, error, events, upper_bound: None };
        assert!(!unresolved(&m(4e-8, 100), 1e-6, 0.01));
        assert!(unresolved(&m(6e-8, 100), 1e-6, 0.01));
        assert!(unresolved(&m(4e-8, 100), 1e-6, 0.06));
        assert!(unresolved(&m(0.0, 0), 1e-9, 0.0));
        // Below the model's 1e-7 m/s neither the error nor the given-up share is asked.
        assert!(!unresolved(&m(6e-7, 100), 1e-8, 0.06));
    }

    /// 8000 particles left the walls at 10 % and the ceiling at 7.4 %: four times the
    /// particles halve the walls' error, so 32000, with the study's margin of 1.15 36800,
    /// resolve both; the ceiling alone 8000 x 1.48^2 x 1.15 = 20151.7. A figure within 5 %,
    /// one without an event and one the model does not ask to resolve set nothing.
    #[test]
    fn the_particles_to_resolve_a_figure_grow_with_its_error_squared() {
        let m = |error: f64, events| Measured { value: 1e-6, error, events, upper_bound: None };
        let (walls, ceiling, floor) = (m(1e-7, 900), m(7.4e-8, 300), m(4e-8, 5000));
        assert_eq!(particles_to_resolve(8000, [(&floor, 1e-6), (&ceiling, 1e-6), (&walls, 1e-6)]), Some(36800));
        assert_eq!(particles_to_resolve(8000, [(&floor, 1e-6), (&ceiling, 1e-6), (&walls, 1e-8)]), Some(20152));
        assert_eq!(
            [two_figures_up(20152), two_figures_up(36800), two_figures_up(99), two_figures_up(101)],
            [21000, 37000, 99, 110]
        );
        let none = m(0.0, 0);
        assert_eq!(particles_to_resolve(8000, [(&floor, 1e-6), (&none, 1e-6), (&walls, 1e-8)]), None);
    }
}
