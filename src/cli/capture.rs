//! `depo capture-velocity`: the capture velocity from material properties, per diameter, with
//! where each theory holds (`depo_wall_model::theory`).

use clap::Args;
use depo::wall_model::theory::{
    dahneke_capture_velocity, effective_modulus, hamaker_well_depth, jkr_capture_velocity, jkr_energy_loss,
    sphere_mass, tabor_parameter, yield_velocity, CONTACT_SEPARATION, DMT_TABOR_MAX, JKR_TABOR_MIN,
};
use serde::Serialize;

use super::{print_csv, Error, Format};

#[derive(Args, Debug)]
pub struct CaptureArgs {
    /// Particle diameters (m), comma-separated.
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true, default_values_t = [1e-7, 3e-7, 1e-6, 3e-6, 1e-5, 3e-5, 1e-4])]
    diameters: Vec<f64>,
    /// Particle density (kg/m^3).
    #[arg(long, allow_negative_numbers = true)]
    density: f64,
    /// Particle Young's modulus (Pa).
    #[arg(long, allow_negative_numbers = true)]
    particle_modulus: f64,
    /// Particle Poisson ratio.
    #[arg(long, allow_negative_numbers = true)]
    particle_poisson: f64,
    /// Wall Young's modulus (Pa); inf for a rigid wall.
    #[arg(long, allow_negative_numbers = true)]
    wall_modulus: f64,
    /// Wall Poisson ratio.
    #[arg(long, allow_negative_numbers = true)]
    wall_poisson: f64,
    /// Work of adhesion w of the pair (J/m^2), best from pull-off measurements.
    #[arg(long, allow_negative_numbers = true)]
    work_of_adhesion: f64,
    /// Separation at contact z0 (m), for Tabor's parameter and the van der Waals well.
    #[arg(long, default_value_t = CONTACT_SEPARATION, allow_negative_numbers = true)]
    separation: f64,
    /// Limiting contact pressure (Pa, about 1.6 x the softer yield stress): reports whether the
    /// impact at the capture velocity stays elastic.
    #[arg(long, allow_negative_numbers = true)]
    yield_pressure: Option<f64>,
    /// Hamaker constant (J): adds Dahneke's rigid-particle capture velocity.
    #[arg(long, requires = "restitution", allow_negative_numbers = true)]
    hamaker: Option<f64>,
    /// Restitution without adhesion for Dahneke's theory, in (0, 1].
    #[arg(long, requires = "hamaker", allow_negative_numbers = true)]
    restitution: Option<f64>,
    /// Output format.
    #[arg(long, value_enum, default_value_t)]
    format: Format,
}

/// One diameter; the JSON keys are stable.
#[derive(Serialize)]
struct Row {
    diameter: f64,
    /// Thornton & Ning (1998), m/s.
    jkr_capture_velocity: f64,
    /// Energy the JKR neck dissipates, J.
    jkr_energy_loss: f64,
    tabor_parameter: f64,
    /// "JKR" (Tabor above 5), "DMT" (below 0.1) or "transition".
    contact_regime: &'static str,
    /// Whether the impact at the JKR capture velocity stays below the yield velocity.
    elastic: Option<bool>,
    /// Dahneke (1971), m/s.
    dahneke_capture_velocity: Option<f64>,
}

#[derive(Serialize)]
struct Report {
    effective_modulus: f64,
    yield_velocity: Option<f64>,
    rows: Vec<Row>,
}

/// The value of `--flag` if it is finite and positive.
fn arg(flag: &str, value: f64) -> Result<f64, Error> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(format!("--{flag} {value}: must be finite and positive"))
    }
}

fn regime(tabor: f64) -> &'static str {
    if tabor > JKR_TABOR_MIN {
        "JKR"
    } else if tabor < DMT_TABOR_MAX {
        "DMT"
    } else {
        "transition"
    }
}

pub fn run(args: &CaptureArgs) -> Result<(), Error> {
    let density = arg("density", args.density)?;
    let particle_modulus = arg("particle-modulus", args.particle_modulus)?;
    let wall_modulus =
        if args.wall_modulus == f64::INFINITY { f64::INFINITY } else { arg("wall-modulus", args.wall_modulus)? };
    for (flag, nu) in [("particle-poisson", args.particle_poisson), ("wall-poisson", args.wall_poisson)] {
        if !(-1.0..=0.5).contains(&nu) {
            return Err(format!("--{flag} {nu}: must lie in [-1, 0.5]"));
        }
    }
    let w = arg("work-of-adhesion", args.work_of_adhesion)?;
    let separation = arg("separation", args.separation)?;
    let modulus = effective_modulus(particle_modulus, args.particle_poisson, wall_modulus, args.wall_poisson);
    let yield_speed = match args.yield_pressure {
        Some(p) => Some(yield_velocity(density, modulus, arg("yield-pressure", p)?)),
        None => None,
    };
    let dahneke = match (args.hamaker, args.restitution) {
        (Some(a), Some(e0)) => {
            if !(e0 > 0.0 && e0 <= 1.0) {
                return Err(format!("--restitution {e0}: must lie in (0, 1]"));
            }
            Some((arg("hamaker", a)?, e0))
        }
        _ => None,
    };
    let mut rows = Vec::with_capacity(args.diameters.len());
    for &d in &args.diameters {
        let radius = 0.5 * arg("diameters", d)?;
        let vc = jkr_capture_velocity(radius, density, modulus, w);
        let tabor = tabor_parameter(radius, modulus, w, separation);
        rows.push(Row {
            diameter: d,
            jkr_capture_velocity: vc,
            jkr_energy_loss: jkr_energy_loss(radius, modulus, w),
            tabor_parameter: tabor,
            contact_regime: regime(tabor),
            elastic: yield_speed.map(|vy| vc < vy),
            dahneke_capture_velocity: dahneke.map(|(a, e0)| {
                dahneke_capture_velocity(sphere_mass(radius, density), hamaker_well_depth(a, radius, separation), e0)
            }),
        });
    }
    let report = Report { effective_modulus: modulus, yield_velocity: yield_speed, rows };
    print(&report, args.format)
}

fn print(report: &Report, format: Format) -> Result<(), Error> {
    let opt = |x: Option<f64>| x.map_or(String::new(), |v| format!("{v:.4e}"));
    let elastic = |x: Option<bool>| x.map_or("", |e| if e { "yes" } else { "no" });
    match format {
        Format::Json => out!("{}", serde_json::to_string_pretty(report).map_err(|e| e.to_string())?),
        Format::Csv => {
            let header = [
                "diameter",
                "jkr_capture_velocity",
                "jkr_energy_loss",
                "tabor_parameter",
                "contact_regime",
                "elastic",
                "dahneke_capture_velocity",
            ];
            print_csv(
                &header,
                report.rows.iter().map(|r| {
                    [
                        format!("{:e}", r.diameter),
                        format!("{:e}", r.jkr_capture_velocity),
                        format!("{:e}", r.jkr_energy_loss),
                        format!("{:e}", r.tabor_parameter),
                        r.contact_regime.to_string(),
                        elastic(r.elastic).to_string(),
                        r.dahneke_capture_velocity.map_or(String::new(), |v| format!("{v:e}")),
                    ]
                }),
            )?;
        }
        Format::Table => {
            out!("effective modulus E* = {:.4e} Pa", report.effective_modulus);
            if let Some(vy) = report.yield_velocity {
                out!("yield velocity = {vy:.4e} m/s (impacts above it are not elastic)");
            }
            out!(
                "{:>11} {:>14} {:>12} {:>9} {:>10} {:>7} {:>14}",
                "d (m)",
                "vc JKR (m/s)",
                "W_L (J)",
                "Tabor",
                "regime",
                "elastic",
                "vc Dahneke"
            );
            for r in &report.rows {
                out!(
                    "{:>11.3e} {:>14.4e} {:>12.4e} {:>9.3} {:>10} {:>7} {:>14}",
                    r.diameter,
                    r.jkr_capture_velocity,
                    r.jkr_energy_loss,
                    r.tabor_parameter,
                    r.contact_regime,
                    elastic(r.elastic),
                    opt(r.dahneke_capture_velocity)
                );
            }
            out!("JKR: Thornton & Ning (1998), vc ~ d^(-5/6); holds where the regime is JKR and the impact elastic.");
        }
    }
    Ok(())
}
