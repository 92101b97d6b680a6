//! `depo fit DATA.csv`: measured restitution to the law's constants (the paper's Eq. 10 fits).

use std::path::{Path, PathBuf};

use clap::{Args, ValueEnum};
use depo::wall_model::fit::{fit, Exponents, FitReport, Sample};
use depo::wall_model::WallLaw;
use serde::Serialize;

use super::{shown, Error};
use depo::csv_input::CsvInput;
use depo::plot::{self, Series};

/// What `depo fit` prints: one fit, as a table or as JSON (not CSV, a format of rows).
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum FitFormat {
    #[default]
    Table,
    Json,
}

#[derive(Args, Debug)]
pub struct FitArgs {
    /// CSV with a header naming the columns `vn` and `e` (optional `weight`); speeds may be
    /// given as positive numbers.
    data: PathBuf,
    /// Exponent p of Eq. (8), held fixed unless --free-exponents (then the starting value).
    #[arg(long, default_value_t = 1.0, allow_negative_numbers = true)]
    p: f64,
    /// Exponent q of Eq. (9), held fixed unless --free-exponents (then the starting value).
    #[arg(long, default_value_t = 1.0, allow_negative_numbers = true)]
    q: f64,
    /// Fit p and q too.
    #[arg(long)]
    free_exponents: bool,
    /// Output format.
    #[arg(long, value_enum, default_value_t)]
    format: FitFormat,
    /// Also draw the data and the fitted e against |vn| into this SVG file.
    #[arg(long)]
    plot: Option<PathBuf>,
    /// The surface the printed scene entry is for: a `[walls]` key of a room (all, floor,
    /// ceiling, x0, x1, y0, y1) or a channel (lower, upper), or a face of a `[[furnishings]]`
    /// entry (all, bottom, top, x0, x1, y0, y1).
    #[arg(long, default_value = "floor", value_parser = SURFACES)]
    surface: String,
}

/// The surface keys a scene file takes a wall law under: the room's and the channel's
/// `[walls]` keys and the faces of a `[[furnishings]]` entry (`src/scene_file/walls.rs`).
const SURFACES: [&str; 11] = ["all", "floor", "ceiling", "x0", "x1", "y0", "y1", "lower", "upper", "bottom", "top"];

/// Where in a scene file the entry for `surface` goes.
fn entry_home(surface: &str) -> &'static str {
    match surface {
        "floor" | "ceiling" => "under [walls] of a room scene",
        "lower" | "upper" => "under [walls] of a channel scene",
        "bottom" | "top" => "into a [[furnishings]] entry",
        "all" => "under [walls] of a room or channel scene, or into a [[furnishings]] entry for all its faces",
        _ => "under [walls] of a room scene, or into a [[furnishings]] entry for that face",
    }
}

/// The fit as printed; the JSON keys are stable.
#[derive(Serialize)]
struct Output {
    k: f64,
    kappa: f64,
    vc: f64,
    p: f64,
    q: f64,
    fitting_index: f64,
    rmse: f64,
    vc_low: f64,
    vc_high: f64,
    k_se: f64,
    kappa_se: f64,
    vc_se: f64,
    p_se: f64,
    q_se: f64,
    vc_extrapolated: bool,
    samples: usize,
    /// The fitted law as a scene file's entry for `--surface`, to paste into a scene.
    scene_entry: String,
}

/// Reads the samples; an unreadable file or a bad row is one line naming the file and line.
fn read(path: &Path) -> Result<Vec<Sample>, Error> {
    let mut file = CsvInput::open(path)?;
    let (vn, e) = match (file.column("vn"), file.column("e")) {
        (Some(vn), Some(e)) => (vn, e),
        _ => return Err(file.header_error("the header must name the columns vn and e")),
    };
    let weight = file.column("weight");
    let mut samples = Vec::new();
    for row in file.rows()? {
        let speed = row.number(vn, "vn")?;
        if speed == 0.0 {
            return Err(row.error("vn is zero (not an impact)"));
        }
        let w = match weight {
            Some(index) => row.number(index, "weight")?,
            None => 1.0,
        };
        if w <= 0.0 {
            return Err(row.error("weight must be positive"));
        }
        let restitution = row.number(e, "e")?;
        if !(0.0..=1.0).contains(&restitution) {
            return Err(row.error(&format!("e = {restitution} is outside [0, 1]")));
        }
        samples.push(Sample { speed: speed.abs(), restitution, weight: w });
    }
    Ok(samples)
}

pub fn run(args: &FitArgs) -> Result<(), Error> {
    for (name, value) in [("--p", args.p), ("--q", args.q)] {
        if !(value.is_finite() && value > 0.0) {
            return Err(format!("{name} {value}: the exponent must be finite and positive"));
        }
    }
    let samples = read(&args.data)?;
    let exponents = if args.free_exponents {
        Exponents::Free { p: args.p, q: args.q }
    } else {
        Exponents::Fixed { p: args.p, q: args.q }
    };
    let report = fit(&samples, exponents).map_err(|e| format!("{}: {e}", args.data.display()))?;
    depo::scene_file::check_fit(&report, args.free_exponents, "other --p and --q, or --free-exponents")
        .map_err(|e| format!("{}: {e}", args.data.display()))?;
    let FitReport { params, standard_errors: se, .. } = report;
    let out = Output {
        k: params.k1,
        kappa: params.kappa1,
        vc: params.vc,
        p: params.p,
        q: params.q,
        fitting_index: report.fitting_index,
        rmse: report.rmse,
        vc_low: report.vc_interval.0,
        vc_high: report.vc_interval.1,
        k_se: se.k1,
        kappa_se: se.kappa1,
        vc_se: se.vc,
        p_se: se.p,
        q_se: se.q,
        vc_extrapolated: report.vc_extrapolated,
        samples: report.samples,
        scene_entry: depo::scene_file::law_entry(&args.surface, &params),
    };
    match args.format {
        FitFormat::Json => out!("{}", serde_json::to_string_pretty(&out).map_err(|e| e.to_string())?),
        FitFormat::Table => {
            out!("{} samples from {}", out.samples, args.data.display());
            out!("k      {:.6} +- {:.2e} m/s", out.k, out.k_se);
            out!("kappa  {:.6} +- {:.2e} m/s", out.kappa, out.kappa_se);
            out!(
                "vc     {:.6} +- {:.2e} m/s   95 % interval [{:.6}, {:.6}]",
                out.vc,
                out.vc_se,
                out.vc_low,
                out.vc_high
            );
            if args.free_exponents {
                out!("p, q   {} +- {:.2e}, {} +- {:.2e} (fitted)", shown(out.p), out.p_se, shown(out.q), out.q_se);
            } else {
                out!("p, q   {}, {} (fixed)", shown(out.p), shown(out.q));
            }
            out!("fitting index (R^2 of e) {:.5}   RMSE {:.4}", out.fitting_index, out.rmse);
            out!(
                "R(vc)  {:.4}   (Eq. 14: work of adhesion at capture / (m vc^2 / 2) = R(vc)^2 = {:.4})",
                rc(&report),
                rc(&report).powi(2)
            );
            out!("scene: {}", out.scene_entry);
            out!("       # paste {}", entry_home(&args.surface));
            out!("       # friction is not fitted (normal impacts do not measure it): add mu = ... by hand");
        }
    }
    if report.vc_extrapolated {
        eprintln!("depo: warning: the data stop above 1.5 vc; the fitted vc is an extrapolation (see its interval)");
    }
    if let Some(path) = &args.plot {
        let law = WallLaw::new(params).map_err(|e| e.to_string())?;
        let lo = samples.iter().map(|s| s.speed).fold(f64::INFINITY, f64::min).min(params.vc.max(1e-6)) * 0.8;
        let hi = samples.iter().map(|s| s.speed).fold(0.0, f64::max) * 1.25;
        let curve =
            (0..200).map(|i| lo * (hi / lo).powf(i as f64 / 199.0)).map(|v| (v, law.overall_restitution(v))).collect();
        let mut data: Vec<(f64, f64)> = samples.iter().map(|s| (s.speed, s.restitution)).collect();
        data.sort_by(|a, b| a.0.total_cmp(&b.0));
        let series = [Series::markers("data", data), Series::line("fit: e = R (1 - rho)", curve)];
        plot::lines(path, "Fit of Eq. (10)", "|vn| (m/s)", "e", &series, true)?;
        eprintln!("wrote {}", path.display());
    }
    Ok(())
}

/// `R(vc)` of the fitted law (`NaN` when `vc <= 0`).
fn rc(report: &FitReport) -> f64 {
    let vc = report.params.vc;
    if vc > 0.0 {
        WallLaw::new(report.params).map_or(f64::NAN, |law| law.restitution(vc))
    } else {
        f64::NAN
    }
}
