//! `depo curve`: R, rho, e and capture against |vn| (the paper's Figs. 2-5).

use std::path::PathBuf;

use clap::Args;
use serde::Serialize;

use super::{check_memory, fixed, print_csv, Error, Format, LawArgs, MAX_SPEED};
use depo::plot::{self, Series};

#[derive(Args, Debug)]
pub struct CurveArgs {
    #[command(flatten)]
    law: LawArgs,
    /// Smallest normal speed |vn| (m/s).
    #[arg(long, default_value_t = 0.01, allow_negative_numbers = true)]
    vn_min: f64,
    /// Largest normal speed |vn| (m/s).
    #[arg(long, default_value_t = 10.0, allow_negative_numbers = true)]
    vn_max: f64,
    /// Number of speeds, spaced logarithmically.
    #[arg(long, default_value_t = 60, allow_negative_numbers = true)]
    points: usize,
    /// Output format.
    #[arg(long, value_enum, default_value_t)]
    format: Format,
    /// Also draw e and R against |vn| into this SVG file.
    #[arg(long)]
    plot: Option<PathBuf>,
}

/// One point of the curve; the JSON keys are stable.
#[derive(Serialize)]
struct Point {
    vn: f64,
    #[serde(rename = "R")]
    r: f64,
    rho: f64,
    e: f64,
    captured: bool,
}

/// The law's constants as printed.
#[derive(Serialize)]
struct Law {
    k1: f64,
    k2: f64,
    kappa1: f64,
    kappa2: f64,
    p: f64,
    q: f64,
    vc: f64,
    mu: f64,
}

#[derive(Serialize)]
struct Curve {
    law: Law,
    points: Vec<Point>,
}

pub fn run(args: &CurveArgs) -> Result<(), Error> {
    let law = args.law.law()?;
    let (a, b) = (args.vn_min, args.vn_max);
    if !(a.is_finite() && b.is_finite() && a > 0.0 && a < b) {
        return Err(format!("--vn-min {a} and --vn-max {b}: need 0 < vn-min < vn-max"));
    }
    if b > MAX_SPEED {
        return Err(format!("--vn-max {b:e}: speeds up to {MAX_SPEED:e} m/s are taken"));
    }
    if args.points < 2 {
        return Err(format!("--points {}: need at least 2", args.points));
    }
    // A point and its line of output.
    check_memory(&format!("--points {}", args.points), args.points as u64, 256)?;
    let n = args.points;
    let points: Vec<Point> = (0..n)
        .map(|i| {
            let vn = a * (b / a).powf(i as f64 / (n - 1) as f64);
            let c = law.coefficients(vn);
            Point { vn, r: c.restitution, rho: c.adhesion, e: c.overall, captured: c.captured }
        })
        .collect();
    match args.format {
        Format::Json => {
            let lp = *law.params();
            let law = Law {
                k1: lp.k1,
                k2: lp.k2,
                kappa1: lp.kappa1,
                kappa2: lp.kappa2,
                p: lp.p,
                q: lp.q,
                vc: lp.vc,
                mu: lp.mu,
            };
            let curve = Curve { law, points };
            out!("{}", serde_json::to_string_pretty(&curve).map_err(|e| e.to_string())?);
            return write_plot(args, &curve.points);
        }
        Format::Csv => {
            let header = ["vn", "R", "rho", "e", "captured"];
            print_csv(
                &header,
                points.iter().map(|p| {
                    [
                        p.vn.to_string(),
                        p.r.to_string(),
                        p.rho.to_string(),
                        p.e.to_string(),
                        u8::from(p.captured).to_string(),
                    ]
                }),
            )?;
        }
        Format::Table => {
            let lp = law.params();
            out!(
                "k1 {} k2 {} kappa1 {} kappa2 {} p {} q {} vc {} m/s mu {}",
                lp.k1,
                lp.k2,
                lp.kappa1,
                lp.kappa2,
                lp.p,
                lp.q,
                lp.vc,
                lp.mu
            );
            out!("{:>10} {:>9} {:>9} {:>9}  outcome", "|vn| m/s", "R", "rho", "e");
            for p in &points {
                out!(
                    "{:>10} {:>9.5} {:>9.5} {:>9.5}  {}",
                    fixed(p.vn, 4),
                    p.r,
                    p.rho,
                    p.e,
                    if p.captured { "captured" } else { "rebound" }
                );
            }
        }
    }
    write_plot(args, &points)
}

fn write_plot(args: &CurveArgs, points: &[Point]) -> Result<(), Error> {
    let Some(path) = &args.plot else { return Ok(()) };
    let series = [
        Series::line("e = R (1 - rho)", points.iter().map(|p| (p.vn, p.e)).collect()),
        Series::line("R", points.iter().map(|p| (p.vn, p.r)).collect()),
    ];
    plot::lines(path, "Restitution against normal impact speed", "|vn| (m/s)", "coefficient", &series, true)?;
    eprintln!("wrote {}", path.display());
    Ok(())
}
