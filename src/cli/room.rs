//! `depo room`: deposition onto the floor, ceiling and walls of a room, per particle size,
//! beside Lai & Nazaroff (2000).

use std::path::PathBuf;

use clap::Args as ClapArgs;
use depo::tracker::studies::MAP_BINS;
use depo::tracker::studies::{RoomPoint, RoomStudy};
use depo::tracker::{Estimate, Flow, Geometry, WallTally};
use indicatif::{ProgressBar, ProgressStyle};
use serde::Serialize;

use super::plot::{self, Series};
use super::{print_csv, scene_file, Error, Format};

#[derive(ClapArgs, Debug)]
pub struct RoomArgs {
    /// A scene file (TOML; see examples/room.toml). Without it, the built-in room.
    scene: Option<PathBuf>,
    /// Output format.
    #[arg(long, value_enum, default_value_t)]
    format: Format,
    /// Directory for the figures (room-deposition.svg, room-beta.svg).
    #[arg(long, default_value = "depo-room")]
    plot: PathBuf,
    /// Write no figures.
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

/// The note under a study's table: what its numbers mean.
pub const ERROR_NOTE: &str = "+- is one standard error of the estimate over the run's randomness (delta method over \
the injected particles); [n] deposit events it rests on; with none, < the 95 % upper bound. \
\"excursions\": deposits counted by near-wall excursions, an unbiased estimate of the steady \
deposition rate (their share given up at their longest duration, a bound on what that may \
miss, in parentheses when above 0.1 %).";

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

#[derive(Serialize)]
struct Row {
    diameter_um: f64,
    floor: Measured,
    ceiling: Measured,
    walls: Measured,
    beta_per_hour: Measured,
    /// With ventilation: the steady indoor/outdoor ratio `P a / (a + beta)`.
    #[serde(skip_serializing_if = "Option::is_none")]
    indoor_outdoor: Option<Measured>,
    lai_nazaroff: Model,
    particle_steps: u64,
    /// Particles run for this size.
    particles: usize,
    /// "excursions" or "plain".
    method: &'static str,
    /// With excursions: the share of their weight given up at their longest duration.
    excursions_truncated: Option<f64>,
    wall_tally: Tally,
    deposited: Deposited,
    #[serde(skip)]
    maps: Vec<Vec<u32>>,
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

#[derive(Serialize)]
struct Report<'a> {
    size_m: [f64; 3],
    friction_velocity: f64,
    air_changes_per_hour: f64,
    penetration: f64,
    particles_per_size: usize,
    /// With a target: the relative standard error each size was run to reach, and the most
    /// particles it could take.
    target_error: Option<f64>,
    max_particles_per_size: usize,
    duration_s: f64,
    sizes: &'a [Row],
}

fn row(p: &RoomPoint) -> Row {
    let per_hour = |e: Estimate| Measured::from(e).scaled(3600.0);
    Row {
        diameter_um: p.diameter * 1e6,
        floor: p.floor.into(),
        ceiling: p.ceiling.into(),
        walls: p.walls.into(),
        beta_per_hour: per_hour(p.beta),
        indoor_outdoor: p.indoor_outdoor.map(Measured::from),
        lai_nazaroff: Model {
            floor: p.model.floor,
            ceiling: p.model.ceiling,
            walls: p.model.wall,
            beta_per_hour: p.model_beta * 3600.0,
        },
        particle_steps: p.particle_steps,
        particles: p.particles,
        method: if p.excursions.is_some() { "excursions" } else { "plain" },
        excursions_truncated: p.excursions,
        wall_tally: p.tally.into(),
        deposited: Deposited {
            floor: p.deposited[0].0,
            floor_kg: p.deposited[0].1,
            ceiling: p.deposited[1].0,
            ceiling_kg: p.deposited[1].1,
            walls: p.deposited[2].0,
            walls_kg: p.deposited[2].1,
        },
        maps: p.maps.clone(),
    }
}

pub fn run(args: &RoomArgs) -> Result<(), Error> {
    let study: RoomStudy = scene_file::room(args.scene.as_deref())?;
    let where_ = args.scene.as_ref().map_or("the built-in room".to_string(), |p| p.display().to_string());
    let progress = ProgressBar::new(study.diameters.len() as u64);
    progress
        .set_style(ProgressStyle::with_template("{bar:30} {pos}/{len} sizes {elapsed}").map_err(|e| e.to_string())?);
    let start = std::time::Instant::now();
    let points = study.run(|done| progress.set_position(done as u64)).map_err(|e| format!("{where_}: {e}"))?;
    progress.finish_and_clear();
    let seconds = start.elapsed().as_secs_f64();
    let Geometry::Room { size } = study.scene.geometry else { unreachable!("a room study has a room") };
    let u_star = match study.scene.flow {
        Flow::TurbulentRoom { friction_velocity, .. } => friction_velocity,
        _ => 0.0,
    };
    let rows: Vec<Row> = points.iter().map(row).collect();
    let ventilated = study.scene.air_exchange > 0.0;
    let steps: u64 = rows.iter().map(|r| r.particle_steps).sum();
    match args.format {
        Format::Json => {
            let report = Report {
                size_m: size,
                friction_velocity: u_star,
                air_changes_per_hour: study.scene.air_exchange * 3600.0,
                penetration: study.penetration,
                particles_per_size: study.count,
                target_error: study.target_error,
                max_particles_per_size: study.max_count,
                duration_s: study.scene.duration,
                sizes: &rows,
            };
            out!("{}", serde_json::to_string_pretty(&report).map_err(|e| e.to_string())?);
        }
        Format::Csv => {
            let header = [
                "diameter_um",
                "floor",
                "floor_error",
                "floor_lai_nazaroff",
                "ceiling",
                "ceiling_error",
                "ceiling_lai_nazaroff",
                "walls",
                "walls_error",
                "walls_lai_nazaroff",
                "beta_per_hour",
                "beta_error",
                "beta_lai_nazaroff",
                "indoor_outdoor",
                "indoor_outdoor_error",
            ];
            // Without ventilation the indoor/outdoor columns are left out.
            let columns = if ventilated { header.len() } else { header.len() - 2 };
            print_csv(
                &header[..columns],
                rows.iter().map(|r| {
                    let io = r.indoor_outdoor.as_ref().map_or([f64::NAN; 2], |m| [m.value, m.error]);
                    let row = [
                        r.diameter_um,
                        r.floor.value,
                        r.floor.error,
                        r.lai_nazaroff.floor,
                        r.ceiling.value,
                        r.ceiling.error,
                        r.lai_nazaroff.ceiling,
                        r.walls.value,
                        r.walls.error,
                        r.lai_nazaroff.walls,
                        r.beta_per_hour.value,
                        r.beta_per_hour.error,
                        r.lai_nazaroff.beta_per_hour,
                        io[0],
                        io[1],
                    ]
                    .map(|x| x.to_string());
                    row[..columns].to_vec()
                }),
            )?;
        }
        Format::Table => {
            let particles: Vec<String> = rows.iter().map(|r| r.particles.to_string()).collect();
            out!(
                "Room {} x {} x {} m, u* = {} m/s, {} particles per size, {} s; deposition velocity (m/s) per surface",
                size[0],
                size[1],
                size[2],
                u_star,
                particles.join("/"),
                study.scene.duration
            );
            if let Some(target) = study.target_error {
                out!(
                    "({} first, more up to {} where beta or a surface with Lai & Nazaroff's v_d >= 1e-7 m/s was above {} % error.)",
                    study.count,
                    study.max_count,
                    100.0 * target
                );
            }
            out!("beside Lai & Nazaroff (2000) for the same u*; ratio = beta / Lai & Nazaroff's beta.");
            if ventilated {
                out!(
                    "Ventilated: {} air changes per hour, penetration {}; C_in/C_out = P a / (a + beta) at steady state.",
                    study.scene.air_exchange * 3600.0,
                    study.penetration
                );
            }
            out!(
                "{:>8}  {:>26} {:>9}  {:>26} {:>9}  {:>26} {:>9}  {:>20} {:>7} {:>6}{}  method",
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
            let cell = Measured::cell;
            for r in &rows {
                let method = match r.excursions_truncated {
                    Some(t) if t > 1e-3 => format!("excursions ({:.1} %)", 100.0 * t),
                    Some(_) => "excursions".to_string(),
                    None => "plain".to_string(),
                };
                out!(
                    "{:>8.3}  {:>26} {:>9.2e}  {:>26} {:>9.2e}  {:>26} {:>9.2e}  {:>20} {:>7.3} {:>6.2}{}  {method}",
                    r.diameter_um,
                    cell(&r.floor),
                    r.lai_nazaroff.floor,
                    cell(&r.ceiling),
                    r.lai_nazaroff.ceiling,
                    cell(&r.walls),
                    r.lai_nazaroff.walls,
                    if r.beta_per_hour.value >= 0.1 {
                        format!("{:.3} +- {:.3}", r.beta_per_hour.value, r.beta_per_hour.error)
                    } else {
                        format!("{:.2e} +- {:.1e}", r.beta_per_hour.value, r.beta_per_hour.error)
                    },
                    r.lai_nazaroff.beta_per_hour,
                    r.beta_per_hour.value / r.lai_nazaroff.beta_per_hour,
                    r.indoor_outdoor
                        .as_ref()
                        .map_or(String::new(), |m| format!("  {:>18}", format!("{:.3} +- {:.3}", m.value, m.error)))
                );
            }
            out!("{ERROR_NOTE}");
            out!(
                "Averages from {} s to {} s; {steps} particle-steps tracked (excursions not counted) in {seconds:.1} s.",
                study.transient * study.scene.duration,
                study.scene.duration
            );
        }
    }
    if !args.no_plot {
        std::fs::create_dir_all(&args.plot).map_err(|e| format!("cannot create {}: {e}", args.plot.display()))?;
        let series = |name: &str, pick: &dyn Fn(&Row) -> f64, markers: bool| Series {
            name: name.to_string(),
            // Below 1e-10 m/s (the model's ceiling for coarse particles reaches 1e-138) is
            // nothing a room shows; such points are left off the log axis.
            points: rows.iter().map(|r| (r.diameter_um, pick(r))).filter(|p| p.1 > 1e-10).collect(),
            markers,
            errors: Vec::new(),
        };
        // depo's values with their standard errors; a surface without a deposit is left off.
        let measured = |name: &str, pick: &dyn Fn(&Row) -> &Measured| {
            let kept: Vec<&Row> = rows.iter().filter(|r| pick(r).value > 0.0).collect();
            Series {
                name: format!("{name} (depo, +- 1 s.e.)"),
                points: kept.iter().map(|r| (r.diameter_um, pick(r).value)).collect(),
                markers: true,
                errors: kept.iter().map(|r| pick(r).error).collect(),
            }
        };
        let deposition = args.plot.join("room-deposition.svg");
        plot::log_log(
            &deposition,
            "Deposition velocity in a room",
            "particle diameter (um)",
            "deposition velocity (m/s)",
            &[
                measured("floor", &|r| &r.floor),
                measured("ceiling", &|r| &r.ceiling),
                measured("walls", &|r| &r.walls),
                series("floor (Lai & Nazaroff)", &|r| r.lai_nazaroff.floor, false),
                series("ceiling (Lai & Nazaroff)", &|r| r.lai_nazaroff.ceiling, false),
                series("walls (Lai & Nazaroff)", &|r| r.lai_nazaroff.walls, false),
            ],
        )?;
        let beta = args.plot.join("room-beta.svg");
        plot::log_log(
            &beta,
            "Loss-rate coefficient",
            "particle diameter (um)",
            "beta (1/h)",
            &[
                measured("beta", &|r| &r.beta_per_hour),
                series("Lai & Nazaroff (2000)", &|r| r.lai_nazaroff.beta_per_hour, false),
            ],
        )?;
        // Deposition maps, one CSV per wall and size: rows and columns along the wall's two
        // in-plane axes in the order x, y, z.
        let walls = study.scene.geometry.walls();
        for r in &rows {
            let label = (r.diameter_um * 1e4).round() / 1e4;
            for (wall, map) in walls.iter().zip(&r.maps) {
                let name = wall.name(&study.scene.geometry);
                let path = args.plot.join(format!("room-map-{name}-{label}um.csv"));
                let mut text = String::new();
                for row in map.chunks(MAP_BINS[1]) {
                    let cells: Vec<String> = row.iter().map(u32::to_string).collect();
                    text.push_str(&cells.join(","));
                    text.push('\n');
                }
                std::fs::write(&path, text).map_err(|e| format!("cannot write {}: {e}", path.display()))?;
            }
        }
        eprintln!(
            "figures: {} and {}; deposition maps ({}x{} cells per wall): {}/room-map-WALL-SIZEum.csv",
            deposition.display(),
            beta.display(),
            MAP_BINS[0],
            MAP_BINS[1],
            args.plot.display()
        );
    }
    Ok(())
}
