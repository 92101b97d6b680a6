//! A room study's rows: per size, what each surface collected and its deposition velocity,
//! the loss rate, the release's fate, the decay curve and its fit, the steady state, the
//! wall-law tallies and the deposition maps, as the JSON gives them (field for field) and the
//! other reports read them.

use depo_tracker::filtration::Filtration;
use depo_tracker::furnishing::FACE_NAMES;
use depo_tracker::geometry::in_plane_axes;
use depo_tracker::maps::FluxMap;
use depo_tracker::steady::{Source, NOT_WELL_MIXED};
use depo_tracker::studies::{RoomPoint, RoomStudy, MAP_BINS};
use depo_tracker::{binomial_error, DecayCurve, DecayFit, Estimate, Scene};
use serde::Serialize;

use super::resolution::unresolved;
use crate::report::{Measured, Tally};

/// Lai & Nazaroff's deposition velocities (m/s) and loss rate for the same size and room.
#[derive(Serialize)]
pub struct Model {
    pub floor: f64,
    pub ceiling: f64,
    pub walls: f64,
    pub beta_per_hour: f64,
}

/// One surface's wall-law tally, named.
#[derive(Serialize)]
pub struct SurfaceTally {
    pub surface: String,
    #[serde(flatten)]
    pub tally: Tally,
}

/// The excursions per crossing of each class of surface, as multiples of the study's three
/// ([`depo_tracker::Excursions::class_sampling`]).
#[derive(Serialize)]
pub struct ClassSampling {
    pub floor: f64,
    pub ceiling: f64,
    pub walls: f64,
    pub furnishings: f64,
}

/// One size's figures, as the JSON gives them.
#[derive(Serialize)]
pub struct Row {
    pub diameter_um: f64,
    /// Particle density, kg/m^3 (a size distribution's bins can have several).
    pub density: f64,
    pub floor: Measured,
    pub ceiling: Measured,
    pub walls: Measured,
    /// Each vertical wall (`x0`, `x1`, `y0`, `y1`): its deposition velocity and what it
    /// collected; `walls` is the four together.
    pub each_wall: Vec<WallRow>,
    pub beta_per_hour: Measured,
    /// With ventilation: the steady indoor/outdoor ratio `P a / (a + beta)` (with filters,
    /// `(P (1 - s) a + (1 - eta_s) s a) / (a + eta_r a_r + beta)`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub indoor_outdoor: Option<Measured>,
    /// The recirculation filter's removal `eta_r a_r` at this size, 1/h (with one).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub filter_removal_per_hour: Option<f64>,
    /// The supply filter's single-pass efficiency `eta_s` at this size (with a filtered
    /// supply share).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub supply_filter_efficiency: Option<f64>,
    /// The recirculation filter's single-pass efficiency `eta_r` at this size (with
    /// recirculation).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub recirculation_filter_efficiency: Option<f64>,
    pub lai_nazaroff: Model,
    pub particle_steps: u64,
    /// Particles run for this size.
    pub particles: usize,
    /// "excursions", "wall-function" (deposits from Lai & Nazaroff's rate within the walls'
    /// layers; docs/tracker.md) or "plain".
    pub method: &'static str,
    /// With excursions: the share of their weight given up at their longest duration.
    pub excursions_truncated: Option<f64>,
    /// With excursions: that longest duration, s.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub longest_excursion_s: Option<f64>,
    /// With excursions: the multipliers of their sampling per class of crossing that the
    /// particles after the first ran with.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub class_sampling: Option<ClassSampling>,
    pub wall_tally: Tally,
    /// Each surface's own tally, in id order: what each surface's material did.
    pub surface_tallies: Vec<SurfaceTally>,
    pub deposited: Deposited,
    /// Where the released particles are at the end: per surface, exhausted, airborne.
    pub release: Release,
    /// The start of this size's averaging window, s: the study's, or 0 where every particle
    /// had left the air before it opened (its figures are then over the release from its
    /// start, not a well-mixed room's rates).
    pub averaged_from_s: f64,
    /// When half and when nine tenths of the released particles had deposited, s (null where
    /// the run ended first).
    pub deposited_by_s: [Option<f64>; 2],
    /// The steady concentration in the lowest tenth of the room's height over the room's
    /// mean, under a source spread over the room (null where nothing removes the particles).
    pub near_floor_over_mean: Option<Ratio>,
    /// Whether the room is well mixed for this size: false where `near_floor_over_mean` is
    /// above 1.2, whose deposition velocities and `beta` are then not a well-mixed room's.
    pub well_mixed: Option<bool>,
    /// The steady state under a continuous source of this size (null where nothing removes
    /// the particles).
    pub steady: Option<Steady>,
    /// `beta` fitted to the decay curve as decay experiments fit it; absent when fewer than 3
    /// sample times qualify.
    pub decay_fit: Option<DecayFitRow>,
    /// Where `decay_fit` is absent (every particle gone before the window, or too soon for
    /// its sample times): the release's decay fitted from `t = 0` on its own time scale, to
    /// the last time 50 particles were airborne.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub release_fit: Option<DecayFitRow>,
    /// The airborne share of the release over the run.
    pub decay: Curve,
    /// The surfaces (floor, ceiling, walls) whose figure is unresolved: no deposit event, or
    /// a relative standard error above 5 % where Lai & Nazaroff give at least 1e-7 m/s.
    pub unresolved: Vec<&'static str>,
    /// Per furnishing: deposition velocities onto its faces and what it collected.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub furnishings: Vec<FurnishingRow>,
    /// Each surface's deposition map: the tracked particles' deposits over the run, per cell.
    pub maps: Vec<SurfaceMap>,
    /// Each surface's deposition velocity per cell, from the study's estimator (the figures'
    /// maps and their CSV files; not in the JSON, whose `maps` are the counts).
    #[serde(skip)]
    pub flux_maps: Vec<Option<FluxMap>>,
}

/// One surface's deposition map for one size, as the JSON, the CSV files and the figure give
/// it: the deposits of the tracked particles over the whole run on a [`MAP_BINS`] grid over
/// the surface's two in-plane axes in the order x, y, z (over the room, or the furnishing).
#[derive(Serialize)]
pub struct SurfaceMap {
    /// Its name: floor, ceiling, x0, ..., or a furnishing's face as `table.top`.
    pub surface: String,
    /// "wall" or "furnishing face".
    pub kind: &'static str,
    /// The axis the surface is normal to, and its position along it, m.
    pub normal: (&'static str, f64),
    /// The rows' axis and its range, m.
    pub rows: (&'static str, f64, f64),
    /// The columns' axis and its range, m.
    pub columns: (&'static str, f64, f64),
    /// Deposits per cell, row by row.
    #[serde(serialize_with = "rows_on_one_line")]
    pub cells: Vec<Vec<u32>>,
}

impl Row {
    /// Where `beta` rests on no deposit (only its 95 % upper bound is known) and the room is
    /// ventilated: the steady `C_in/C_out` it spans, from the bound's (low) to no
    /// deposition's (high). `None` where `beta` was measured or there is no ratio.
    #[must_use]
    pub fn indoor_outdoor_range(&self, study: &RoomStudy) -> Option<(f64, f64)> {
        let bound = self.beta_per_hour.upper_bound?;
        self.indoor_outdoor.as_ref()?;
        let ratio = |beta: f64| {
            study.filtration.indoor_outdoor(
                self.diameter_um * 1e-6,
                study.scene.exchange_rate(),
                study.penetration,
                beta,
            )
        };
        Some((ratio(bound / 3600.0), ratio(0.0)))
    }
}

/// Serialises `cells` with each row as one compact JSON array, so that the pretty-printed
/// report gives a row a line rather than every cell a line of its own.
pub fn rows_on_one_line<S: serde::Serializer>(cells: &[Vec<u32>], s: S) -> Result<S::Ok, S::Error> {
    use serde::ser::{Error as _, SerializeSeq};
    let mut seq = s.serialize_seq(Some(cells.len()))?;
    for row in cells {
        let text = serde_json::to_string(row).map_err(S::Error::custom)?;
        seq.serialize_element(&serde_json::value::RawValue::from_string(text).map_err(S::Error::custom)?)?;
    }
    seq.end()
}

/// The maps `p` holds, one per surface of `scene` in id order, with their axes.
pub fn surface_maps(scene: &Scene, p: &RoomPoint) -> Vec<SurfaceMap> {
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
pub struct FurnishingRow {
    pub name: String,
    pub area_m2: f64,
    /// Deposition velocity onto all its faces together, m/s.
    pub all: Measured,
    pub top: Measured,
    pub bottom: Measured,
    /// Its four vertical faces together.
    pub sides: Measured,
    /// Per face, in face order (bottom, top, x0, x1, y0, y1): name, deposition velocity, and
    /// deposited count and mass.
    pub faces: Vec<FaceRow>,
    /// What it collected over the whole run, as a share of the release.
    pub deposited: Share,
}

/// One vertical wall of the room.
#[derive(Serialize)]
pub struct WallRow {
    pub wall: &'static str,
    pub velocity: Measured,
    pub deposited: usize,
    pub deposited_kg: f64,
}

/// The vertical walls' names, in id order.
pub const WALL_NAMES: [&str; 4] = ["x0", "x1", "y0", "y1"];

/// One face of a furnishing.
#[derive(Serialize)]
pub struct FaceRow {
    pub face: &'static str,
    pub velocity: Measured,
    pub deposited: usize,
    pub deposited_kg: f64,
}

/// Deposited count and mass (kg) per orientation over the whole run.
#[derive(Serialize)]
pub struct Deposited {
    pub floor: usize,
    pub floor_kg: f64,
    pub ceiling: usize,
    pub ceiling_kg: f64,
    pub walls: usize,
    pub walls_kg: f64,
}

/// One fate of the release: the count of tracked particles, their share of the released
/// number with its binomial standard error, their mass (kg) and its share of the released
/// mass, and on a surface the deposited mass per unit area per unit released mass (1/m^2,
/// i.e. kg/m^2 per kg released).
#[derive(Serialize)]
pub struct Share {
    pub count: usize,
    pub share: f64,
    pub share_error: f64,
    pub kg: f64,
    pub mass_share: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub loading_per_m2: Option<f64>,
}

impl Share {
    /// `(count, kg)` of `released`, onto a surface of `area` (m^2) if any.
    pub fn of((count, kg): (usize, f64), released: (usize, f64), area: Option<f64>) -> Self {
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
pub struct Steady {
    /// Mean time an emitted particle stays in the air, h: the steady airborne number per
    /// particle emitted an hour.
    pub residence_h: Measured,
    /// The share of the source ending on the floor, ceiling, walls, furnishings, exhausted.
    pub floor: f64,
    pub ceiling: f64,
    pub walls: f64,
    pub furnishings: f64,
    pub exhausted: f64,
    /// Steady deposition velocities, m/s.
    pub floor_velocity: Measured,
    pub ceiling_velocity: Measured,
    pub walls_velocity: Measured,
    /// The share of the residence time taken from the room's late rates beyond the run.
    pub beyond_run: f64,
    /// The steady concentration per particle emitted a second, s/m^3: the mean time in the
    /// air over the air's volume.
    pub concentration_per_emission_s_per_m3: Ratio,
    /// The steady concentration in the lowest tenth of the room's height over the room's
    /// mean, under this source.
    pub near_floor_over_mean: Ratio,
    /// For a source of outdoor air: the steady indoor/outdoor ratio, the entering outdoor
    /// particles' rate times their mean residence.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub indoor_outdoor: Option<Measured>,
}

/// A ratio (or a concentration) with its standard error.
#[derive(Clone, Copy, Serialize)]
pub struct Ratio {
    pub value: f64,
    pub error: f64,
}

impl From<Estimate> for Ratio {
    fn from(e: Estimate) -> Self {
        Self { value: e.value, error: e.error }
    }
}

/// Where `study`'s continuous source enters, as the reports say it.
pub fn source_label(study: &RoomStudy) -> String {
    let show = |v: [f64; 3]| v.map(crate::text::shown).join(", ");
    match study.source {
        None if study.scene.exchange_rate() > 0.0 => {
            "spread over the room: outdoor air infiltrating (or an indoor source)".into()
        }
        None => "spread over the room: an indoor source".into(),
        Some(Source::Indoor(None)) => "indoors, spread over the room".into(),
        Some(Source::Indoor(Some((low, high)))) => format!("indoors, in the box [{}] to [{}] m", show(low), show(high)),
        Some(Source::Infiltration) => "outdoor air infiltrating, spread over the room".into(),
        Some(Source::Supply(k)) => format!("outdoor air through the supply opening openings[{k}]"),
    }
}

/// The release at the end of the run.
#[derive(Serialize)]
pub struct Release {
    pub particles: usize,
    pub kg: f64,
    pub floor: Share,
    pub ceiling: Share,
    pub walls: Share,
    /// On the furnishings' faces (present in a furnished room).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub furnishings: Option<Share>,
    pub exhausted: Share,
    pub airborne: Share,
}

/// `beta` fitted to the decay curve: the total loss rate `k`, `beta = k - a`, both per hour
/// with the delta method's standard error, the fit's window and points, the fitted `beta`
/// less the study's with the standard error of that difference (paired over the particles,
/// which both rest on), and `z`, the difference in those standard errors: absent when either
/// `beta` rests on no event or has no error.
#[derive(Serialize)]
pub struct DecayFitRow {
    pub beta_per_hour: Measured,
    pub total_per_hour: Measured,
    pub window_s: [f64; 2],
    pub points: usize,
    pub difference_per_hour: Difference,
    pub z: Option<f64>,
}

impl DecayFitRow {
    /// The row of a fit, its rates per hour.
    fn of(f: DecayFit) -> Self {
        let per_hour = |e: Estimate| Measured::from(e).scaled(3600.0);
        Self {
            beta_per_hour: per_hour(f.beta),
            total_per_hour: per_hour(f.total),
            window_s: f.window,
            points: f.points,
            difference_per_hour: Difference {
                value: f.against_loss_rate.difference * 3600.0,
                error: f.against_loss_rate.error * 3600.0,
            },
            z: f.against_loss_rate.z,
        }
    }
}

/// A difference of two estimates from the same particles, with its paired standard error.
#[derive(Serialize)]
pub struct Difference {
    pub value: f64,
    pub error: f64,
}

/// A decay curve: sample times (s), the airborne share, its standard error, and the count.
#[derive(Serialize)]
pub struct Curve {
    pub times_s: Vec<f64>,
    pub airborne: Vec<f64>,
    pub error: Vec<f64>,
    pub count: Vec<usize>,
    #[serde(skip)]
    pub intercept: Option<f64>,
}

impl Curve {
    pub fn of(c: &DecayCurve) -> Self {
        Self {
            times_s: c.times.clone(),
            airborne: c.airborne.clone(),
            error: c.errors.clone(),
            count: c.counts.clone(),
            intercept: None,
        }
    }
}

/// A size's row of `scene`'s study; `density` its particles', kg/m^3; `filtration` the
/// study's filters.
pub(super) fn row(p: &RoomPoint, scene: &Scene, density: f64, filtration: &Filtration) -> Row {
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
        near_floor_over_mean: p.near_floor.map(Into::into),
        well_mixed: p.near_floor.map(|m| m.value <= NOT_WELL_MIXED),
        steady: p.steady.map(|st| {
            let [floor, ceiling, walls, furnishings, exhausted] = st.fates;
            let hours = |e: Estimate| Estimate { value: e.value / 3600.0, error: e.error / 3600.0, ..e };
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
                concentration_per_emission_s_per_m3: Ratio {
                    value: st.residence.value / scene.free_volume(),
                    error: st.residence.error / scene.free_volume(),
                },
                near_floor_over_mean: st.near_floor.into(),
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
        decay_fit: p.decay_fit.map(DecayFitRow::of),
        release_fit: p.release_fit.map(DecayFitRow::of),
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
        flux_maps: p.flux_maps.clone(),
    }
}
