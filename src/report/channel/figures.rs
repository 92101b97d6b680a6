//! `depo channel --plot`: `V+` against `tau+` for each run, beside the correlations, Sippola &
//! Nazaroff's measurements and, with both near-wall models, Code_Saturne's own.

use std::path::Path;

use depo_tracker::correlations::{diameter_for_tau_plus, papavergos_hedley, schmidt, wood};
use depo_tracker::measurements::SIPPOLA_NAZAROFF_2004;
use depo_tracker::Air;

use super::peer::{peer_points, PeerPoint, PEER_MODELS};
use super::{ChannelResult, ChannelRun, Row};
use crate::plot::{self, Series};
use crate::report::log_grid;
use crate::Error;

/// The figure: each study's `V+` with its standard errors (with no deposit, the 95 % upper
/// bound), Wood, Papavergos & Hedley, Sippola & Nazaroff's measurements, and with `peer`
/// Code_Saturne's own deposition model on a wall-function mesh.
pub fn figure(path: &Path, result: &ChannelResult, note: &mut dyn FnMut(String)) -> Result<(), Error> {
    let study = &result.runs[0].study;
    let peer = result.all;
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
    for (k, ChannelRun { name, rows, .. }) in result.runs.iter().enumerate() {
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
    note(format!("figure: {}", path.display()));
    Ok(())
}
