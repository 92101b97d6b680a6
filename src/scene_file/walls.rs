//! `[walls]`: each surface's behaviour (a sink, a mirror, or the wall law with a preset or
//! its own constants); the faces of `[[furnishings]]` take the same keys.

use depo_tracker::{Geometry, Scene, WallBehaviour};
use depo_wall_model::fit::FitReport;
use depo_wall_model::{LawParams, SizeDependence, WallLaw};
use serde::Deserialize;

use super::{Error, SceneSource};
use crate::text::shown;

/// A number for a TOML file that reads back as the same `f64`: `{:?}` prints the shortest
/// digits that round-trip, as `{}` does, but always with a decimal point or an exponent
/// (`1.0`, `1e-7`), so that TOML reads a float, not an integer, and very small or large
/// values stay short.
fn toml_float(x: f64) -> String {
    format!("{x:?}")
}

/// The `[walls]` entry (or furnishing face) that gives `surface` a law of its own constants
/// `k = k1`, `kappa = kappa1`, `vc`, `p`, `q` (m/s for the first three), with the keys the
/// reader takes, every number reading back as the same `f64`: the line `depo fit` prints. It
/// leaves out `mu`: a fit has no friction coefficient (normal impacts do not measure one).
pub fn law_entry(surface: &str, params: &LawParams) -> String {
    format!(
        "{surface} = {{ behaviour = \"law\", k = {}, kappa = {}, vc = {}, p = {}, q = {} }}",
        toml_float(params.k1),
        toml_float(params.kappa1),
        toml_float(params.vc),
        toml_float(params.p),
        toml_float(params.q)
    )
}

/// Whether a converged fit can become a scene entry ([`law_entry`]); if not, the one line
/// saying why, which `depo fit` and the Python package's `fit()` both print: a capture velocity
/// that is not positive (the data do not show capture under these exponents), or an estimate,
/// standard error or fitting index that is not finite (the data do not determine the
/// constants, e.g. identical rows or an exponent far from the data's).
///
/// `free_exponents` says whether `p` and `q` were fitted; `retry` names, in the caller's own
/// terms, what to try instead when `vc` is not positive (the command's
/// `"other --p and --q, or --free-exponents"`).
pub fn check_fit(report: &FitReport, free_exponents: bool, retry: &str) -> Result<(), Error> {
    let (params, se) = (&report.params, &report.standard_errors);
    let exponents = if free_exponents { "fitted" } else { "fixed" };
    let values = [
        ("k", params.k1),
        ("kappa", params.kappa1),
        ("vc", params.vc),
        ("p", params.p),
        ("q", params.q),
        ("the standard error of k", se.k1),
        ("the standard error of kappa", se.kappa1),
        ("the standard error of vc", se.vc),
        ("the standard error of p", se.p),
        ("the standard error of q", se.q),
        ("the fitting index", report.fitting_index),
        ("the RMSE", report.rmse),
    ];
    if let Some((name, value)) = values.iter().find(|(_, v)| !v.is_finite()) {
        return Err(format!(
            "the fit failed: {name} is {value} (the data do not determine the constants with p = {}, q = {} {exponents})",
            params.p, params.q
        ));
    }
    if params.vc <= 0.0 {
        return Err(format!(
            "the fit failed: vc = {} m/s is not positive with p = {}, q = {} {exponents}; try {retry}",
            shown(params.vc),
            shown(params.p),
            shown(params.q)
        ));
    }
    Ok(())
}

#[derive(Deserialize, Default, Clone)]
#[serde(deny_unknown_fields)]
pub(super) struct WallFile {
    /// "sink", "reflect" or "law".
    pub(super) behaviour: Option<String>,
    pub(super) preset: Option<String>,
    /// A law's own constants instead of a preset, as `depo fit` prints them (m/s; `p` and `q`
    /// default to 1).
    pub(super) k: Option<f64>,
    pub(super) kappa: Option<f64>,
    pub(super) vc: Option<f64>,
    pub(super) p: Option<f64>,
    pub(super) q: Option<f64>,
    pub(super) mu: Option<f64>,
    pub(super) size_exponent: Option<f64>,
    pub(super) reference_diameter: Option<f64>,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub(super) struct WallsFile {
    pub(super) all: Option<WallFile>,
    pub(super) floor: Option<WallFile>,
    pub(super) ceiling: Option<WallFile>,
    pub(super) x0: Option<WallFile>,
    pub(super) x1: Option<WallFile>,
    pub(super) y0: Option<WallFile>,
    pub(super) y1: Option<WallFile>,
    pub(super) lower: Option<WallFile>,
    pub(super) upper: Option<WallFile>,
}

/// The behaviour `file` gives a surface whose keys start `prefix` (`walls.floor`,
/// `furnishings[0].top`); an error names the file and the line of the key at fault, or of the
/// surface where a key is missing.
pub(super) fn wall_behaviour(src: &SceneSource, prefix: &str, file: &WallFile) -> Result<WallBehaviour, Error> {
    let key = |k: &str| format!("{prefix}.{k}");
    // The line of the surface's key `k`, or of the surface.
    let at = |k: &str, message: String| src.at(&[&key(k), prefix], message);
    let at_surface = |message: String| src.at(&[prefix], message);
    let constants = [file.k, file.kappa, file.vc, file.p, file.q];
    let has_constants = constants.iter().any(Option::is_some);
    let default = if file.preset.is_some() || has_constants { "law" } else { "sink" };
    match file.behaviour.as_deref().unwrap_or(default) {
        "sink" => Ok(WallBehaviour::Sink),
        "reflect" => Ok(WallBehaviour::Reflect),
        "law" => {
            let mut law = match (file.preset.as_deref(), has_constants) {
                (Some(_), true) => {
                    return Err(at_surface(format!(
                        "`{prefix}`: give a `preset` or the constants `k`, `kappa`, `vc`, not both"
                    )))
                }
                (Some(id), false) => {
                    WallLaw::preset(id).map_err(|e| at("preset", format!("`{}`: {e}", key("preset"))))?
                }
                (None, true) => {
                    let need = |v: Option<f64>, k: &str| {
                        v.ok_or_else(|| at_surface(format!("`{}` is needed with the law's constants", key(k))))
                    };
                    let (k, kappa, vc) = (need(file.k, "k")?, need(file.kappa, "kappa")?, need(file.vc, "vc")?);
                    let params = LawParams::symmetric(k, kappa, vc, file.p.unwrap_or(1.0), file.q.unwrap_or(1.0));
                    // The law's field as the file's key: `k1`/`k2` are the file's `k`, and so on.
                    WallLaw::new(params).map_err(|e| {
                        let file_key = e.field.trim_end_matches(['1', '2']);
                        at(file_key, format!("`{prefix}`: {e}"))
                    })?
                }
                (None, false) => {
                    return Err(at_surface(format!(
                        "`{}` (or the constants `k`, `kappa`, `vc`) is needed for a wall law",
                        key("preset")
                    )))
                }
            };
            if let Some(mu) = file.mu {
                law = WallLaw::new(law.params().with_friction(mu))
                    .map_err(|e| at("mu", format!("`{}`: {e}", key("mu"))))?;
            }
            let size = match file.size_exponent {
                None => None,
                Some(alpha) => {
                    let d_ref = file.reference_diameter.ok_or_else(|| {
                        at("size_exponent", format!("`{}` is needed with a size exponent", key("reference_diameter")))
                    })?;
                    let size = SizeDependence::new(d_ref, alpha).map_err(|e| {
                        let file_key = if e.field == "reference_diameter" { e.field } else { "size_exponent" };
                        at(file_key, format!("`{prefix}`: {e}"))
                    })?;
                    Some(size)
                }
            };
            Ok(WallBehaviour::Law { law, size })
        }
        other => Err(at(
            "behaviour",
            format!("`{}` = \"{other}\": expected \"sink\", \"reflect\" or \"law\"", key("behaviour")),
        )),
    }
}

/// The `[walls]` of a scene onto its walls: `all` first, then each wall's own table.
pub(super) fn apply_walls(src: &SceneSource, scene: &mut Scene, walls: &WallsFile) -> Result<(), Error> {
    if let Some(all) = &walls.all {
        let behaviour = wall_behaviour(src, "walls.all", all)?;
        scene.walls.iter_mut().for_each(|w| *w = behaviour);
    }
    let geometry = scene.geometry;
    for wall in geometry.walls() {
        let name = wall.name(&geometry);
        let file = match name {
            "floor" => &walls.floor,
            "ceiling" => &walls.ceiling,
            "x0" => &walls.x0,
            "x1" => &walls.x1,
            "y0" => &walls.y0,
            "y1" => &walls.y1,
            "lower" => &walls.lower,
            _ => &walls.upper,
        };
        if let Some(file) = file {
            scene.walls[wall.id] = wall_behaviour(src, &format!("walls.{name}"), file)?;
        }
    }
    let room_only = [&walls.floor, &walls.ceiling, &walls.x0, &walls.x1, &walls.y0, &walls.y1];
    let channel_only = [&walls.lower, &walls.upper];
    // The other kind's walls, by key.
    let (foreign, keys) = match geometry {
        Geometry::Room { .. } => (channel_only.iter().any(|w| w.is_some()), &["walls.lower", "walls.upper"][..]),
        Geometry::Channel { .. } => (
            room_only.iter().any(|w| w.is_some()),
            &["walls.floor", "walls.ceiling", "walls.x0", "walls.x1", "walls.y0", "walls.y1"][..],
        ),
    };
    if foreign {
        // At the first of the foreign keys in the file.
        let keys = src.in_file_order(keys);
        return Err(src.at(&keys, "`walls`: a room has floor, ceiling, x0, x1, y0, y1; a channel has lower and upper"));
    }
    Ok(())
}
