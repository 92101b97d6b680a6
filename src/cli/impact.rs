//! `depo impact`: one impact explained.

use clap::Args;
use depo::wall_model::energy::energy_loss;
use depo::wall_model::impact::kinetic_energy;
use depo::wall_model::CaptureMode;
use glam::DVec3;
use serde::Serialize;

use super::{fixed, parse_vector, print_csv, Error, Format, LawArgs, MAX_SPEED};

#[derive(Args, Debug)]
pub struct ImpactArgs {
    #[command(flatten)]
    law: LawArgs,
    /// Velocity before the impact, VX,VY,VZ (m/s).
    #[arg(long, allow_hyphen_values = true)]
    velocity: String,
    /// Spin before the impact, WX,WY,WZ (rad/s) [default: not tracked].
    #[arg(long, allow_hyphen_values = true)]
    spin: Option<String>,
    /// Particle radius (m), used with --spin.
    #[arg(long, default_value_t = 1e-5, allow_negative_numbers = true)]
    radius: f64,
    /// Wall normal into the fluid, NX,NY,NZ (normalised).
    #[arg(long, default_value = "0,0,1", allow_hyphen_values = true)]
    normal: String,
    /// Keep a captured particle on the wall with its tangential motion instead of depositing it.
    #[arg(long)]
    keep_on_wall: bool,
    /// Output format: table, csv (one header line and one row) or json.
    #[arg(long, value_enum, default_value_t)]
    format: Format,
}

/// The explanation; the JSON keys are stable.
#[derive(Serialize)]
struct Report {
    normal_velocity: f64,
    impact: bool,
    outcome: &'static str,
    regime: &'static str,
    #[serde(rename = "R")]
    r: f64,
    rho: f64,
    e: f64,
    slip_before: f64,
    tangential_impulse: f64,
    velocity_after: [f64; 3],
    spin_after: Option<[f64; 3]>,
    kinetic_energy_before: f64,
    kinetic_energy_after: f64,
    loss_material: f64,
    loss_adhesion: f64,
    loss_friction: f64,
    loss_deposition: f64,
}

pub fn run(args: &ImpactArgs) -> Result<(), Error> {
    let law = args.law.law()?;
    let law = if args.keep_on_wall { law.with_capture_mode(CaptureMode::KeepOnWall) } else { law };
    let v = DVec3::from_array(parse_vector(&args.velocity).map_err(|e| format!("--velocity: {e}"))?);
    let n = DVec3::from_array(parse_vector(&args.normal).map_err(|e| format!("--normal: {e}"))?);
    if n.length() == 0.0 {
        return Err("--normal: the zero vector has no direction".into());
    }
    let n = n.normalize();
    if v.abs().max_element() > MAX_SPEED {
        return Err(format!("--velocity {}: speeds up to {MAX_SPEED:e} m/s are taken", args.velocity));
    }
    // Refused whether or not --spin uses it: a value is checked where it is given.
    if !(args.radius.is_finite() && args.radius > 0.0) {
        return Err(format!("--radius {}: must be positive", args.radius));
    }
    let spin = match &args.spin {
        Some(text) => {
            let w = DVec3::from_array(parse_vector(text).map_err(|e| format!("--spin: {e}"))?);
            // The spin's speed at the surface, as the velocity's.
            if w.abs().max_element() * args.radius > MAX_SPEED {
                return Err(format!(
                    "--spin {text} with --radius {}: surface speeds up to {MAX_SPEED:e} m/s are taken",
                    args.radius
                ));
            }
            Some((w, args.radius))
        }
        None => None,
    };
    let res = law.impact(v, spin, n);
    let impact = res.normal_velocity < 0.0;
    let (w0, r) = spin.unwrap_or((DVec3::ZERO, args.radius));
    let before = kinetic_energy(v.to_array(), w0.to_array(), r);
    let (velocity_after, spin_after) = if impact { (res.velocity, res.spin) } else { (v.to_array(), w0.to_array()) };
    let loss = if impact { energy_loss(&res) } else { Default::default() };
    let c = res.coefficients;
    let report = Report {
        normal_velocity: res.normal_velocity,
        impact,
        outcome: match (impact, c.captured, law.capture_mode()) {
            (false, ..) => "skipped (not an impact: v . n >= 0)",
            (true, false, _) => "rebound",
            (true, true, CaptureMode::Deposit) => "captured (deposited)",
            (true, true, CaptureMode::KeepOnWall) => "captured (kept on the wall)",
        },
        regime: match (law.params().mu > 0.0, res.slip > 0.0, res.rolling) {
            (false, ..) => "no friction (mu = 0)",
            (true, false, _) => "no slip",
            (true, true, true) => "rolling at separation",
            (true, true, false) => "sliding throughout contact",
        },
        r: c.restitution,
        rho: c.adhesion,
        e: c.overall,
        slip_before: res.slip,
        tangential_impulse: res.tangential_impulse,
        velocity_after,
        spin_after: spin.map(|_| spin_after),
        kinetic_energy_before: before,
        kinetic_energy_after: kinetic_energy(velocity_after, if spin.is_some() { spin_after } else { [0.0; 3] }, r),
        loss_material: loss.material,
        loss_adhesion: loss.adhesion,
        loss_friction: loss.friction,
        loss_deposition: loss.deposition,
    };
    match args.format {
        Format::Json => out!("{}", serde_json::to_string_pretty(&report).map_err(|e| e.to_string())?),
        Format::Csv => {
            let r = &report;
            let [vx, vy, vz] = r.velocity_after;
            // Spin columns are empty when spin is not tracked.
            let [wx, wy, wz] =
                r.spin_after.map_or([String::new(), String::new(), String::new()], |w| w.map(|x| x.to_string()));
            print_csv(
                &[
                    "normal_velocity",
                    "impact",
                    "outcome",
                    "regime",
                    "R",
                    "rho",
                    "e",
                    "slip_before",
                    "tangential_impulse",
                    "vx_after",
                    "vy_after",
                    "vz_after",
                    "wx_after",
                    "wy_after",
                    "wz_after",
                    "kinetic_energy_before",
                    "kinetic_energy_after",
                    "loss_material",
                    "loss_adhesion",
                    "loss_friction",
                    "loss_deposition",
                ],
                [[
                    r.normal_velocity.to_string(),
                    r.impact.to_string(),
                    r.outcome.to_string(),
                    r.regime.to_string(),
                    r.r.to_string(),
                    r.rho.to_string(),
                    r.e.to_string(),
                    r.slip_before.to_string(),
                    r.tangential_impulse.to_string(),
                    vx.to_string(),
                    vy.to_string(),
                    vz.to_string(),
                    wx,
                    wy,
                    wz,
                    r.kinetic_energy_before.to_string(),
                    r.kinetic_energy_after.to_string(),
                    r.loss_material.to_string(),
                    r.loss_adhesion.to_string(),
                    r.loss_friction.to_string(),
                    r.loss_deposition.to_string(),
                ]],
            )?
        }
        Format::Table => {
            let r = &report;
            let f = |x: f64| fixed(x, 6);
            out!("normal velocity vn     {} m/s", f(r.normal_velocity));
            out!("outcome                {}", r.outcome);
            if r.impact {
                out!("coefficients           R {:.6}  rho {:.6}  e {:.6}", r.r, r.rho, r.e);
                out!(
                    "tangential             {} (slip {} m/s, impulse {} m/s)",
                    r.regime,
                    f(r.slip_before),
                    f(r.tangential_impulse)
                );
            }
            let [x, y, z] = r.velocity_after;
            out!("velocity after         {}, {}, {} m/s", f(x), f(y), f(z));
            if let Some([x, y, z]) = r.spin_after {
                out!("spin after             {}, {}, {} rad/s", fixed(x, 4), fixed(y, 4), fixed(z, 4));
            }
            out!(
                "kinetic energy         {:.6e} -> {:.6e} J/kg (per unit particle mass)",
                r.kinetic_energy_before,
                r.kinetic_energy_after
            );
            out!(
                "lost to                material {:.6e}  adhesion {:.6e}  friction {:.6e}  deposition {:.6e} J/kg",
                r.loss_material,
                r.loss_adhesion,
                r.loss_friction,
                r.loss_deposition
            );
        }
    }
    Ok(())
}
