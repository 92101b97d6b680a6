//! `depo figures --out DIR`: the paper's figures that need no impact data, redrawn with depo.
//!
//! - `fig6-tilt.svg`: apparent restitution of nominally normal impacts on the copper preset
//!   (`mu = 0.3`) with the surface tilted by 0 and 2 degrees, and the refitted capture velocities
//!   (Fig. 6).
//! - `fig8-size.svg`: capture velocity against diameter on log-log axes: the simulation rows of
//!   Table 1, their fitted power law, and the `-5/6` (JKR) and `-5/2` reference slopes through
//!   the 70 um row (Fig. 8).
//! - `e-curves.svg`: `e` against `|vn|` for every preset (Figs. 3-5 without data;
//!   `depo fit --plot` draws data and fit).

use std::path::PathBuf;

use clap::Args;
use depo::wall_model::size::fit_size_scaling;
use depo::wall_model::tilt::{apparent_restitution, tilt_refit};
use depo::wall_model::{presets, LawParams, WallLaw, PRESETS};

use super::Error;
use depo::plot::{self, Series};

#[derive(Args, Debug)]
pub struct FiguresArgs {
    /// Directory to write the SVG files into (created if missing).
    #[arg(long, default_value = "figures")]
    out: PathBuf,
}

fn log_space(from: f64, to: f64, n: usize) -> impl Iterator<Item = f64> {
    (0..n).map(move |i| from * (to / from).powf(i as f64 / (n - 1) as f64))
}

pub fn run(args: &FiguresArgs) -> Result<(), Error> {
    std::fs::create_dir_all(&args.out).map_err(|e| format!("{}: {e}", args.out.display()))?;

    // Fig. 6: tilt sensitivity.
    let copper = presets::preset("dunn1995-copper").expect("preset").params;
    let law = WallLaw::new(LawParams { mu: 0.3, ..copper }).map_err(|e| e.to_string())?;
    let speeds: Vec<f64> = log_space(0.3, 4.0, 120).collect();
    let mut series = Vec::new();
    for degrees in [0.0f64, 2.0] {
        let phi = degrees.to_radians();
        let fitted = tilt_refit(&law, phi, &log_space(0.32, 3.2, 40).collect::<Vec<_>>()).map_err(|e| e.to_string())?;
        series.push(Series::line(
            format!("e, tilt {degrees} deg (refit vc = {:.4} m/s)", fitted.params.vc),
            speeds.iter().map(|&s| (s, apparent_restitution(&law, s, phi))).collect(),
        ));
    }
    series.push(Series::line("R", speeds.iter().map(|&s| (s, law.restitution(s))).collect()));
    let path = args.out.join("fig6-tilt.svg");
    plot::lines(&path, "Tilt sensitivity, Ag-coated glass on copper (Fig. 6)", "|vn| (m/s)", "e", &series, true)?;
    out!("wrote {}", path.display());

    // Fig. 8: capture velocity against diameter.
    let rows: Vec<(f64, &presets::Preset)> = [(35e-6, "sim-35um"), (70e-6, "sim-70um"), (140e-6, "sim-140um")]
        .iter()
        .map(|&(d, id)| (d, presets::preset(id).expect("preset")))
        .collect();
    let scaling = fit_size_scaling(&rows).ok_or("the simulation rows do not fit a power law")?;
    let diameters: Vec<f64> = log_space(20e-6, 250e-6, 50).collect();
    let at_70 = rows[1].1.params.vc;
    let slope = |b: f64| diameters.iter().map(|&d| (d * 1e6, at_70 * (d / 70e-6).powf(b))).collect::<Vec<_>>();
    let series = [
        Series::markers("Table 1 simulation rows", rows.iter().map(|(d, p)| (d * 1e6, p.params.vc)).collect()),
        Series::line(
            format!("fit: vc ~ d^{:.2}", scaling.vc.exponent),
            diameters.iter().map(|&d| (d * 1e6, scaling.vc.at(d))).collect(),
        ),
        Series::line("slope -5/6 (JKR)", slope(-5.0 / 6.0)),
        Series::line("slope -5/2", slope(-2.5)),
    ];
    let path = args.out.join("fig8-size.svg");
    plot::log_log(&path, "Capture velocity against diameter (Fig. 8)", "diameter (um)", "vc (m/s)", &series)?;
    out!("wrote {}", path.display());

    // e(vn) of every preset, each in its own colour; a preset with the same constants as one
    // drawn before it (sim-70um is li1997-sio2's row) would hide under it, so it is dashed and
    // its legend entry names the other. The two with a negative vc (Dunn et al.'s tedlar and
    // stainless steel) capture at no speed: their entries say so.
    let series: Vec<Series> = PRESETS
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let law = WallLaw::new(p.params).expect("presets are valid");
            let points = log_space(0.01, 20.0, 200).map(|v| (v, law.overall_restitution(v))).collect();
            let name = if p.params.vc > 0.0 { p.id.to_string() } else { format!("{} (vc < 0: no capture)", p.id) };
            match PRESETS[..i].iter().find(|q| q.params == p.params) {
                Some(twin) => Series::line(format!("{name} (same constants as {})", twin.id), points).dashed(),
                None => Series::line(name, points),
            }
        })
        .collect();
    let path = args.out.join("e-curves.svg");
    plot::lines(&path, "Overall restitution of the Table 1 presets", "|vn| (m/s)", "e", &series, true)?;
    out!("wrote {}", path.display());
    Ok(())
}
