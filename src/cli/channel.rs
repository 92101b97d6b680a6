//! `depo channel`: dimensionless deposition velocity `V+` against `tau+` in a turbulent
//! channel, beside Wood (1981), Papavergos & Hedley (1984) and Sippola & Nazaroff's (2004)
//! measurements.

use std::path::PathBuf;

use clap::Args as ClapArgs;
use depo::tracker::correlations::{band_factor, diameter_for_tau_plus, papavergos_hedley, schmidt, wood};
use depo::tracker::measurements::SIPPOLA_NAZAROFF_2004;
use depo::tracker::studies::ChannelStudy;
use depo::tracker::studies::CHANNEL_SWEEPS;
use depo::tracker::{Air, Correlation, Geometry, WallFunction};
use serde::Serialize;

use super::plot::{self, Series};
use super::room::{log_grid, Measured, Tally, ERROR_NOTE};
use super::{print_csv, progress_bar, scene_file, shown, Error, Format};

#[derive(ClapArgs, Debug)]
pub struct ChannelArgs {
    /// A scene file (TOML; see examples/channel.toml). Without it, the built-in channel.
    scene: Option<PathBuf>,
    /// The tau+ values to run, e.g. 1,3,10 (overrides the scene's).
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    tau_plus: Option<Vec<f64>>,
    /// Output format.
    #[arg(long, value_enum, default_value_t)]
    format: Format,
    /// Write the figure (V+ against tau+) to this SVG file.
    #[arg(long)]
    plot: Option<PathBuf>,
    /// How deposition at the walls is modelled: `resolved` (the near-wall layer tracked to
    /// the wall), `wall-function` (a particle within 30 wall units deposits at the rate of
    /// Wood's correlation; docs/tracker.md), or `all`: both, and the figure beside Code_Saturne's
    /// own deposition model and the measurements. Without it, the scene's `run.near_wall`.
    #[arg(long, value_enum)]
    near_wall: Option<NearWallChoice>,
}

/// The deposition models `--near-wall` chooses between.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum NearWallChoice {
    Resolved,
    WallFunction,
    All,
}

/// Code_Saturne 6.0.2's own Lagrangian deposition in a channel meshed with wall functions
/// (integrations/code_saturne/channel_case: its results as run there).
const CODE_SATURNE_PEER: &str = include_str!("../../integrations/code_saturne/channel_peer.csv");

/// One `tau+` of the peer's channel case: `tau+`, `V+`, its standard error and Wood's `V+`.
type PeerPoint = (f64, f64, f64, f64);

/// The peer's points for one `model` of its CSV (`guingo-minier`, `no-model`,
/// `depo-wall-function`).
fn peer_points(model: &str) -> Vec<PeerPoint> {
    let mut lines = CODE_SATURNE_PEER.lines();
    let header: Vec<&str> = lines.next().unwrap_or("").split(',').collect();
    let column = |name: &str| header.iter().position(|h| *h == name);
    let (Some(t), Some(m), Some(v), Some(e), Some(w)) =
        (column("tau_plus"), column("model"), column("v_plus"), column("v_plus_error"), column("wood"))
    else {
        return Vec::new();
    };
    let number = |f: &[&str], i: usize| f.get(i)?.parse::<f64>().ok();
    lines
        .map(|l| l.split(',').collect::<Vec<_>>())
        .filter(|f| f.get(m) == Some(&model))
        .filter_map(|f| Some((number(&f, t)?, number(&f, v)?, number(&f, e)?, number(&f, w)?)))
        .collect()
}

#[derive(Serialize)]
struct Row {
    tau_plus: f64,
    diameter_um: f64,
    schmidt: f64,
    v_plus: Measured,
    wood: f64,
    papavergos_hedley: f64,
    ratio_to_wood: f64,
    /// `V+` against the band between Wood and Papavergos & Hedley: 1 within it, else the
    /// factor to its nearer edge (`correlations::band_factor`); null with no deposit.
    band_factor: Option<f64>,
    particle_steps: u64,
    /// Particles run at this `tau+`.
    particles: usize,
    /// "excursions", "excursions+sweeps" (strong sweeps caught before the layer too),
    /// "plain", or "wall-function" (deposition from the layer's correlation).
    method: &'static str,
    /// With a wall function: the concentration in its layers over the mean, `C_w / C` (`V+`
    /// is proportional to it; 1 where the layers hold the bulk concentration).
    layer_concentration: Option<Measured>,
    /// With excursions: the share of their weight given up at their longest duration.
    excursions_truncated: Option<f64>,
    /// Beside a target error: no deposit event, or a relative standard error above the target
    /// (which `max_factor` times the first particles would not reach).
    unresolved: bool,
    wall_tally: Tally,
}

#[derive(Serialize)]
struct Report<'a> {
    friction_velocity: f64,
    re_tau: f64,
    particles_per_point: usize,
    /// Particles per point where excursions count the deposits (`tau+` below
    /// `excursions_below_tau_plus`).
    excursion_particles_per_point: usize,
    excursions_below_tau_plus: f64,
    /// The relative standard error each `V+` is run to, where its first particles times
    /// `max_factor` reach it.
    target_error: Option<f64>,
    max_factor: f64,
    duration_plus: f64,
    points: &'a [Row],
}

pub fn run(args: &ChannelArgs) -> Result<(), Error> {
    let (mut study, source) = scene_file::channel(args.scene.as_deref())?;
    if let Some(path) = &args.plot {
        plot::check_writable(path)?;
    }
    if let Some(list) = &args.tau_plus {
        if list.is_empty() {
            return Err("--tau-plus: give at least one value".into());
        }
        if let Some(bad) = list.iter().find(|t| !(t.is_finite() && **t > 0.0)) {
            return Err(format!("--tau-plus: {bad} is not a positive number"));
        }
        study.tau_plus.clone_from(list);
    }
    let with_wall_function = |mut study: ChannelStudy| {
        study.scene.wall_function = Some(study.scene.wall_function.unwrap_or(WallFunction::new(Correlation::Wood)));
        study
    };
    let resolved = |mut study: ChannelStudy| {
        study.scene.wall_function = None;
        study
    };
    let studies = match args.near_wall {
        None => vec![study],
        Some(NearWallChoice::Resolved) => vec![resolved(study)],
        Some(NearWallChoice::WallFunction) => vec![with_wall_function(study)],
        Some(NearWallChoice::All) => vec![resolved(study.clone()), with_wall_function(study)],
    };
    let mut figure = Vec::new();
    for study in &studies {
        figure.push(run_one(args, study, &source)?);
    }
    let all = args.near_wall == Some(NearWallChoice::All);
    if all && args.format == Format::Table {
        peer_table();
    }
    if let Some(path) = &args.plot {
        draw(path, &studies[0], &figure, all)?;
    }
    Ok(())
}

/// The models of the peer's CSV with their names, in the table's and the figure's order.
const PEER_MODELS: [(&str, &str); 3] = [
    ("guingo-minier", "Code_Saturne 6.0.2, its deposition model (wall-function mesh)"),
    ("no-model", "Code_Saturne 6.0.2, deposition walls, no model"),
    ("depo-wall-function", "Code_Saturne 6.0.2 with depo's wall function (Wood)"),
];

/// Code_Saturne's `V+` beside Wood, as measured in its channel case.
fn peer_table() {
    out!(
        "Code_Saturne 6.0.2 in a channel meshed with wall functions (k-epsilon, first cell at y+ 40, Re_tau 479, u* = 0.30 m/s; integrations/code_saturne), V+:"
    );
    out!(
        "{:>8}  {:>26}  {:>26}  {:>26}  {:>9}",
        "tau+",
        "its deposition model",
        "no model",
        "depo's wall function",
        "Wood"
    );
    let columns: Vec<Vec<PeerPoint>> = PEER_MODELS.iter().map(|(m, _)| peer_points(m)).collect();
    for &(tau_plus, _, _, wood) in &columns[0] {
        let cell = |c: &[PeerPoint]| {
            c.iter().find(|p| p.0 == tau_plus).map_or("-".to_string(), |&(_, v, e, _)| format!("{v:.2e} +- {e:.1e}"))
        };
        out!(
            "{:>8}  {:>26}  {:>26}  {:>26}  {:>9.2e}",
            tau_plus_cell(tau_plus),
            cell(&columns[0]),
            cell(&columns[1]),
            cell(&columns[2]),
            wood
        );
    }
    out!("The wall function's V+ there is Wood's times Code_Saturne's own wall-cell concentration over the mean, 1.3-1.9 (integrations/code_saturne/README.md).");
}

/// What a study's figure draws of it: its name and rows.
type Drawn = (&'static str, Vec<Row>);

/// Runs one channel study and prints it: its rows, for the figure.
fn run_one(args: &ChannelArgs, study: &ChannelStudy, source: &scene_file::SceneSource) -> Result<Drawn, Error> {
    let progress = progress_bar(study.tau_plus.len(), "tau+")?;
    let start = std::time::Instant::now();
    let points = study.run(|done| progress.set_position(done as u64)).map_err(|e| source.scene_error(&e))?;
    progress.finish_and_clear();
    let seconds = start.elapsed().as_secs_f64();
    let u_star = study.scene.flow.friction_velocity().unwrap_or(0.0);
    let nu = study.scene.air.kinematic_viscosity();
    let Geometry::Channel { height, .. } = study.scene.geometry else { unreachable!("a channel study has a channel") };
    let re_tau = 0.5 * height * u_star / nu;
    let rows: Vec<Row> = points
        .iter()
        .map(|p| Row {
            tau_plus: p.tau_plus,
            diameter_um: p.diameter * 1e6,
            schmidt: p.schmidt,
            v_plus: p.v_plus.into(),
            wood: p.wood,
            papavergos_hedley: p.papavergos_hedley,
            ratio_to_wood: p.v_plus.value / p.wood,
            band_factor: (p.v_plus.events > 0).then(|| band_factor(p.v_plus.value, p.wood, p.papavergos_hedley)),
            particle_steps: p.particle_steps,
            particles: p.particles,
            method: match (p.excursions, p.sweeps, p.layer_concentration) {
                (Some(_), true, _) => "excursions+sweeps",
                (Some(_), false, _) => "excursions",
                (None, _, Some(_)) => "wall-function",
                (None, _, None) => "plain",
            },
            layer_concentration: p.layer_concentration.map(Into::into),
            excursions_truncated: p.excursions,
            unresolved: study.target_error.is_some_and(|t| p.v_plus.events == 0 || p.v_plus.error > t * p.v_plus.value),
            wall_tally: p.tally.into(),
        })
        .collect();
    let steps: u64 = rows.iter().map(|r| r.particle_steps).sum();
    match args.format {
        Format::Json => {
            let report = Report {
                friction_velocity: u_star,
                re_tau,
                particles_per_point: study.count,
                excursion_particles_per_point: study.excursion_count,
                excursions_below_tau_plus: study.excursions_below,
                target_error: study.target_error,
                max_factor: study.max_factor,
                duration_plus: study.scene.duration * u_star * u_star / nu,
                points: &rows,
            };
            out!("{}", serde_json::to_string_pretty(&report).map_err(|e| e.to_string())?);
        }
        Format::Csv => {
            let header = [
                "tau_plus",
                "diameter_um",
                "schmidt",
                "v_plus",
                "v_plus_error",
                "deposits",
                "wood",
                "papavergos_hedley",
                "ratio_to_wood",
                "band_factor",
            ];
            print_csv(
                &header,
                rows.iter().map(|r| {
                    [
                        r.tau_plus.to_string(),
                        r.diameter_um.to_string(),
                        r.schmidt.to_string(),
                        r.v_plus.value.to_string(),
                        r.v_plus.error.to_string(),
                        r.v_plus.events.to_string(),
                        r.wood.to_string(),
                        r.papavergos_hedley.to_string(),
                        r.ratio_to_wood.to_string(),
                        r.band_factor.map_or(String::new(), |f| f.to_string()),
                    ]
                }),
            )?;
        }
        Format::Table => {
            let more = match study.target_error {
                Some(target) => format!(
                    ", up to {} times as many where V+ needs them for a {:.0} % error",
                    shown(study.max_factor),
                    100.0 * target
                ),
                None => String::new(),
            };
            match study.scene.wall_function {
                Some(wf) => out!(
                    "Turbulent channel, u* = {} m/s, Re_tau = {re_tau:.0}, {} particles per tau+{more}; V+ = v_d / u*; wall function: within {} wall units of a wall, deposition at the rate of {} (V+ = the correlation's times C_w/C, the layer's concentration over the mean)",
                    shown(u_star),
                    study.count,
                    shown(wf.layer_plus),
                    wf.correlation.name()
                ),
                None => out!(
                    "Turbulent channel, u* = {} m/s, Re_tau = {re_tau:.0}, {} particles per tau+ ({} below tau+ {} with excursions){more}; V+ = v_d / u*",
                    shown(u_star),
                    study.count,
                    study.excursion_count,
                    shown(study.excursions_below)
                ),
            }
            out!(
                "{:>8} {:>9} {:>9}  {:>28}  {:>9} {:>9} {:>7} {:>8} {:>9}  method",
                "tau+",
                "d (um)",
                "Sc",
                "V+ (depo) [deposits]",
                "Wood",
                "P&H",
                "ratio",
                "band",
                "particles"
            );
            for r in &rows {
                let method = match (r.excursions_truncated, &r.layer_concentration) {
                    (Some(t), _) if t > 1e-3 => format!("{} ({:.1} %)", r.method, 100.0 * t),
                    (_, Some(c)) => format!("{} (C_w/C {:.2} +- {:.2})", r.method, c.value, c.error),
                    _ => r.method.to_string(),
                };
                let ratio =
                    if r.v_plus.upper_bound.is_some() { "-".to_string() } else { format!("{:.2}", r.ratio_to_wood) };
                let flag = if r.unresolved { "*" } else { " " };
                out!(
                    "{:>8} {:>9.3} {:>9.2e}  {:>28}{flag} {:>9.2e} {:>9.2e} {:>7} {:>8} {:>9}  {method}",
                    tau_plus_cell(r.tau_plus),
                    r.diameter_um,
                    r.schmidt,
                    r.v_plus.cell(),
                    r.wood,
                    r.papavergos_hedley,
                    ratio,
                    band_cell(r.band_factor),
                    r.particles
                );
            }
            out!("ratio = depo / Wood. band: within the band between Wood and P&H, or the factor to its nearer edge. {ERROR_NOTE}");
            let below: Vec<f64> = rows
                .iter()
                .filter(|r| r.band_factor.is_some_and(|f| f < 1.0 / BAND_FACTOR))
                .map(|r| r.tau_plus)
                .collect();
            if below.iter().any(|t| (0.2..=5.0).contains(t)) {
                out!(
                    "! below the band by more than a factor 2: in the diffusion-impaction regime (tau+ about 0.3-3) the near-wall model deposits too little, as continuous random walks are known to (docs/validation.md); --near-wall wall-function takes the layer's transfer from Wood's correlation instead."
                );
            } else if !below.is_empty() {
                out!("! below the band by more than a factor 2.");
            }
            if rows.iter().any(|r| r.band_factor.is_some_and(|f| f > BAND_FACTOR)) {
                out!("! above the band by more than a factor 2.");
            }
            if rows.iter().any(|r| r.method == "excursions+sweeps") {
                out!(
                    "\"+sweeps\": strong sweeps (the fluid's wall-ward velocity above {} standard deviations) anywhere in the channel start excursions too, where inertia lets them carry particles to the wall.",
                    CHANNEL_SWEEPS.enter
                );
            }
            if let Some(target) = study.target_error.filter(|_| rows.iter().any(|r| r.unresolved)) {
                out!(
                    "* unresolved: no deposit event, or a relative standard error above the {:.0} % target that {} times the first particles would not reach.",
                    100.0 * target,
                    shown(study.max_factor)
                );
            }
            out!(
                "Averages over the last {:.0} % of the run; {steps} particle-steps tracked (excursions not counted) in {seconds:.1} s.",
                100.0 * (1.0 - study.transient)
            );
        }
    }
    let name = if study.scene.wall_function.is_some() { "depo, wall function" } else { "depo, resolved" };
    Ok((name, rows))
}

/// The figure: each study's `V+` with its standard errors (with no deposit, the 95 % upper
/// bound), Wood, Papavergos & Hedley, Sippola & Nazaroff's measurements, and with `peer`
/// Code_Saturne's own deposition model on a wall-function mesh.
fn draw(path: &std::path::Path, study: &ChannelStudy, drawn: &[Drawn], peer: bool) -> Result<(), Error> {
    // The correlations on 100 tau+ values across the study's and the measurements', each
    // at the diameter and Schmidt number the study would give that tau+ (its particles,
    // air and u*; in the Brownian range a measured point's own Schmidt number differs).
    // The measurements' tau+ in standard air, whatever the study's.
    let air = &study.scene.air;
    let u_star = study.scene.flow.friction_velocity().unwrap_or(0.0);
    let measured: Vec<(f64, f64)> =
        SIPPOLA_NAZAROFF_2004.iter().map(|t| (t.tau_plus(&Air::standard()), t.v_plus)).collect();
    let (lo, hi) = study
        .tau_plus
        .iter()
        .chain(measured.iter().map(|(t, _)| t))
        .fold((f64::INFINITY, 0.0f64), |(a, b), &t| (a.min(t), b.max(t)));
    let model: Vec<(f64, f64)> = log_grid(lo, hi, 100)
        .into_iter()
        .filter_map(|tp| diameter_for_tau_plus(tp, study.density, air, u_star).map(|d| (tp, schmidt(d, air))))
        .collect();
    let mut series = Vec::new();
    for (k, (name, rows)) in drawn.iter().enumerate() {
        let hit: Vec<&Row> = rows.iter().filter(|r| r.v_plus.upper_bound.is_none()).collect();
        let bounds: Vec<(f64, f64)> =
            rows.iter().filter_map(|r| r.v_plus.upper_bound.map(|b| (r.tau_plus, b))).collect();
        // Blue and red: the palette's later colours are the correlations', the measurements' and the peer's.
        let color = k.min(1);
        series.push(
            Series::markers(
                format!("{name} (+- 1 standard error)"),
                hit.iter().map(|r| (r.tau_plus, r.v_plus.value)).collect(),
            )
            .with_errors(hit.iter().map(|r| r.v_plus.error).collect())
            .color(color),
        );
        if !bounds.is_empty() {
            series.push(Series::upper_bounds(format!("{name}: no deposit, 95 % upper bound"), bounds).color(color));
        }
    }
    series.extend([
        Series::line("Wood (1981)", model.iter().map(|&(tp, sc)| (tp, wood(tp, sc))).collect()),
        Series::line(
            "Papavergos & Hedley (1984)",
            model.iter().map(|&(tp, sc)| (tp, papavergos_hedley(tp, sc))).collect(),
        ),
        Series::markers("Sippola & Nazaroff (2004), duct side wall, measured", measured),
    ]);
    if peer {
        for (model, name) in PEER_MODELS {
            // Points whose error is above 30 % (fewer than about ten deposits: the wall
            // function's at tau+ 0.1-0.3) say little; the table shows them.
            let points: Vec<PeerPoint> = peer_points(model).into_iter().filter(|p| p.2 < 0.3 * p.1).collect();
            series.push(
                Series::markers(name, points.iter().map(|&(t, v, ..)| (t, v)).collect())
                    .with_errors(points.iter().map(|&(_, _, e, _)| e).collect()),
            );
        }
    }
    plot::log_log(path, "Deposition in a turbulent channel", "tau+", "V+", &series)?;
    eprintln!("figure: {}", path.display());
    Ok(())
}

/// How far outside the band between Wood and Papavergos & Hedley a `V+` may lie and still
/// agree with them: the factor 2 deposition models are judged by.
const BAND_FACTOR: f64 = 2.0;

/// The band column: `within`, or the factor to the band's nearer edge, marked `!` beyond
/// [`BAND_FACTOR`]; `-` with no deposit.
fn band_cell(factor: Option<f64>) -> String {
    match factor {
        None => "-".to_string(),
        Some(1.0) => "within".to_string(),
        Some(f) => format!("{}{f:.2}", if (1.0 / BAND_FACTOR..=BAND_FACTOR).contains(&f) { "" } else { "!" }),
    }
}

/// `tau+` for the table: three decimals from 0.01 up, two significant digits in exponent form
/// below (the diffusion regime's 1e-5 would otherwise read 0.000).
fn tau_plus_cell(tau_plus: f64) -> String {
    if tau_plus >= 0.01 {
        format!("{tau_plus:.3}")
    } else {
        format!("{tau_plus:.1e}")
    }
}

#[cfg(test)]
mod tests {
    use super::{peer_points, tau_plus_cell, PEER_MODELS};

    #[test]
    fn the_peer_s_stored_points_are_read_whole() {
        for (model, _) in PEER_MODELS {
            let points = peer_points(model);
            let tau_plus: Vec<f64> = points.iter().map(|p| p.0).collect();
            assert_eq!(tau_plus, [0.1, 0.3, 1.0, 3.0, 10.0, 30.0], "{model}");
            assert!(points.iter().all(|&(_, v, e, w)| v > 0.0 && e > 0.0 && w > 0.0), "{model}: {points:?}");
        }
        // Code_Saturne's own model: 2150 times Wood at tau+ 0.1, as its README says.
        let (_, v, _, wood) = peer_points("guingo-minier")[0];
        assert!((v / wood / 2150.0 - 1.0).abs() < 0.01, "{}", v / wood);
    }

    #[test]
    fn small_tau_plus_reads_in_exponent_form() {
        assert_eq!(tau_plus_cell(1e-5), "1.0e-5");
        assert_eq!(tau_plus_cell(3e-3), "3.0e-3");
        assert_eq!(tau_plus_cell(0.01), "0.010");
        assert_eq!(tau_plus_cell(100.0), "100.000");
    }
}
