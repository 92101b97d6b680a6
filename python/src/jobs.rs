//! The `depo` command's other jobs from Python: `presets()`, `fit()`, `capture_velocity()`.
//! Each returns what the command prints with `--format json`, as dicts and lists with the same
//! keys, and fails with the command's one-line messages, naming the parameter instead of the
//! flag (src/cli/presets.rs, fit.rs, capture.rs; tests/test_jobs.py compares them).

use depo::scene_file::{check_fit, law_entry};
use depo_wall_model::fit::{fit as fit_law, Exponents, FitReport, Sample};
use depo_wall_model::theory::{
    dahneke_capture_velocity, effective_modulus, hamaker_well_depth, jkr_capture_velocity, jkr_energy_loss,
    sphere_mass, tabor_parameter, yield_velocity, CONTACT_SEPARATION, DMT_TABOR_MAX, JKR_TABOR_MIN,
};
use depo_wall_model::{WallLaw, PRESETS};
use numpy::PyArrayMethods;
use pyo3::exceptions::{PyUserWarning, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use crate::arrays::typed;

/// The paper's Table 1 as depo ships it, one dict per row, as
/// `depo presets --format json` prints it: id, source, particle, surface (what the row stands
/// for), k, kappa, vc (m/s), p, q, mu, restitution_at_vc (R(vc) for vc > 0, else None),
/// table_last_column (the table's last column as printed) and reconstructed (True where a
/// constant was reconstructed rather than read). depo.WallLaw.preset(id) makes the law.
#[pyfunction]
pub fn presets(py: Python<'_>) -> PyResult<Bound<'_, PyList>> {
    let list = PyList::empty(py);
    for p in &PRESETS {
        let lp = p.params;
        let law = WallLaw::new(lp).expect("presets are valid");
        let d = PyDict::new(py);
        d.set_item("id", p.id)?;
        d.set_item("source", p.source)?;
        d.set_item("particle", p.particle)?;
        d.set_item("surface", p.surface)?;
        d.set_item("k", lp.k1)?;
        d.set_item("kappa", lp.kappa1)?;
        d.set_item("vc", lp.vc)?;
        d.set_item("p", lp.p)?;
        d.set_item("q", lp.q)?;
        d.set_item("mu", lp.mu)?;
        d.set_item("restitution_at_vc", (lp.vc > 0.0).then(|| law.restitution(lp.vc)))?;
        d.set_item("table_last_column", p.last_column)?;
        d.set_item("reconstructed", p.reconstructed)?;
        list.append(d)?;
    }
    Ok(list)
}

/// The surface keys a scene file takes a wall law under (as `depo fit --surface`).
const SURFACES: [&str; 11] = ["all", "floor", "ceiling", "x0", "x1", "y0", "y1", "lower", "upper", "bottom", "top"];

/// The 1-D float64 values of an array-like, named for messages.
fn values(py: Python<'_>, obj: &Bound<'_, PyAny>, name: &str) -> PyResult<Vec<f64>> {
    let np = py.import("numpy")?;
    let array = np.call_method1("ascontiguousarray", (obj, "float64")).map_err(|e| {
        pyo3::exceptions::PyTypeError::new_err(format!("{name}: expected an array-like of numbers ({e})"))
    })?;
    Ok(typed::<f64>(&array, name, "float64")?.readonly().as_slice()?.to_vec())
}

/// Fits the law (Eq. 10: k1 = k2 = k, kappa1 = kappa2 = kappa) to measured restitution by
/// nonlinear least squares, as `depo fit` does.
///
/// - vn: normal impact speeds (m/s; the sign is ignored, zero is not an impact).
/// - e: measured overall restitution, in [0, 1], one per speed.
/// - p, q: the exponents of Eqs. (8) and (9), held fixed unless free_exponents (then the
///   starting values).
/// - weight: positive weights of the residuals (default all 1).
/// - surface: the scene-file key the returned scene entry is for (all, floor, ceiling, x0, x1,
///   y0, y1 of a room; lower, upper of a channel; bottom, top of a furnishing).
///
/// Returns the dict `depo fit --format json` prints: k, kappa, vc (m/s), p, q, their standard
/// errors k_se, kappa_se, vc_se, p_se, q_se (0 for fixed exponents), vc_low and vc_high (the 95 %
/// interval of vc, m/s), fitting_index (R^2 of e), rmse, vc_extrapolated, samples, and
/// scene_entry (the fitted law as a scene file's line for `surface`). A fit that fails (e.g. a
/// vc that is not positive with these exponents) is a ValueError saying what to try; a fitted vc
/// below the data's range is a UserWarning.
#[pyfunction]
#[pyo3(signature = (vn, e, p = 1.0, q = 1.0, weight = None, free_exponents = false, surface = "floor"))]
#[allow(clippy::too_many_arguments)] // the command's options, by name
pub fn fit<'py>(
    py: Python<'py>,
    vn: &Bound<'py, PyAny>,
    e: &Bound<'py, PyAny>,
    p: f64,
    q: f64,
    weight: Option<&Bound<'py, PyAny>>,
    free_exponents: bool,
    surface: &str,
) -> PyResult<Bound<'py, PyDict>> {
    for (name, value) in [("p", p), ("q", q)] {
        if !(value.is_finite() && value > 0.0) {
            return Err(PyValueError::new_err(format!("{name} {value}: the exponent must be finite and positive")));
        }
    }
    if !SURFACES.contains(&surface) {
        return Err(PyValueError::new_err(format!("surface {surface:?}: expected one of {}", SURFACES.join(", "))));
    }
    let speeds = values(py, vn, "vn")?;
    let restitution = values(py, e, "e")?;
    let weights = weight.map(|w| values(py, w, "weight")).transpose()?;
    if restitution.len() != speeds.len() {
        return Err(PyValueError::new_err(format!("e has {} values, vn {}", restitution.len(), speeds.len())));
    }
    if let Some(w) = &weights {
        if w.len() != speeds.len() {
            return Err(PyValueError::new_err(format!("weight has {} values, vn {}", w.len(), speeds.len())));
        }
    }
    let mut samples = Vec::with_capacity(speeds.len());
    for (i, (&speed, &r)) in speeds.iter().zip(&restitution).enumerate() {
        if !speed.is_finite() {
            return Err(PyValueError::new_err(format!("vn[{i}] = {speed} is not finite")));
        }
        if speed == 0.0 {
            return Err(PyValueError::new_err(format!("vn[{i}] is zero (not an impact)")));
        }
        let w = weights.as_ref().map_or(1.0, |w| w[i]);
        if !(w > 0.0 && w.is_finite()) {
            return Err(PyValueError::new_err(format!("weight[{i}] = {w}: weight must be positive")));
        }
        if !(0.0..=1.0).contains(&r) {
            return Err(PyValueError::new_err(format!("e[{i}] = {r} is outside [0, 1]")));
        }
        samples.push(Sample { speed: speed.abs(), restitution: r, weight: w });
    }
    let exponents = if free_exponents { Exponents::Free { p, q } } else { Exponents::Fixed { p, q } };
    let report = py.detach(|| fit_law(&samples, exponents)).map_err(|e| PyValueError::new_err(e.to_string()))?;
    check_fit(&report, free_exponents, "other p and q, or free_exponents=True").map_err(PyValueError::new_err)?;
    let FitReport { params, standard_errors: se, .. } = report;
    let d = PyDict::new(py);
    d.set_item("k", params.k1)?;
    d.set_item("kappa", params.kappa1)?;
    d.set_item("vc", params.vc)?;
    d.set_item("p", params.p)?;
    d.set_item("q", params.q)?;
    d.set_item("fitting_index", report.fitting_index)?;
    d.set_item("rmse", report.rmse)?;
    d.set_item("vc_low", report.vc_interval.0)?;
    d.set_item("vc_high", report.vc_interval.1)?;
    d.set_item("k_se", se.k1)?;
    d.set_item("kappa_se", se.kappa1)?;
    d.set_item("vc_se", se.vc)?;
    d.set_item("p_se", se.p)?;
    d.set_item("q_se", se.q)?;
    d.set_item("vc_extrapolated", report.vc_extrapolated)?;
    d.set_item("samples", report.samples)?;
    d.set_item("scene_entry", law_entry(surface, &params))?;
    if report.vc_extrapolated {
        PyErr::warn(
            py,
            &py.get_type::<PyUserWarning>(),
            c"the data stop above 1.5 vc; the fitted vc is an extrapolation (see its interval)",
            1,
        )?;
    }
    Ok(d)
}

/// `value` if it is finite and positive, else the command's message for `name`.
fn positive(name: &str, value: f64) -> PyResult<f64> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(PyValueError::new_err(format!("{name} {value}: must be finite and positive")))
    }
}

/// The capture velocity from material properties, per diameter, as `depo capture-velocity`
/// gives it (JKR after Thornton & Ning 1998, vc ~ d^(-5/6); Dahneke 1971 with a Hamaker
/// constant).
///
/// - density: particle density (kg/m^3).
/// - particle_modulus, wall_modulus: Young's moduli (Pa); wall_modulus=inf for a rigid wall.
/// - particle_poisson, wall_poisson: Poisson ratios, in [-1, 0.5].
/// - work_of_adhesion: of the pair (J/m^2), best from pull-off measurements.
/// - diameters: particle diameters (m), an array-like (the command's default seven).
/// - separation: separation at contact z0 (m), for Tabor's parameter and the van der Waals well.
/// - yield_pressure: limiting contact pressure (Pa); reports whether the impact at the capture
///   velocity stays elastic.
/// - hamaker (J) with restitution (in (0, 1], without adhesion): adds Dahneke's capture velocity.
///
/// Returns the dict of `depo capture-velocity --format json`: effective_modulus (Pa),
/// yield_velocity (m/s or None) and rows, one dict per diameter: diameter (m),
/// jkr_capture_velocity (m/s), jkr_energy_loss (J), tabor_parameter, contact_regime ("JKR",
/// "DMT" or "transition"), elastic (bool or None), dahneke_capture_velocity (m/s or None).
#[pyfunction]
#[pyo3(signature = (*, density, particle_modulus, particle_poisson, wall_modulus, wall_poisson, work_of_adhesion,
                    diameters = None, separation = CONTACT_SEPARATION, yield_pressure = None, hamaker = None,
                    restitution = None),
           text_signature = "(*, density, particle_modulus, particle_poisson, wall_modulus, wall_poisson, work_of_adhesion, diameters=(1e-07, 3e-07, 1e-06, 3e-06, 1e-05, 3e-05, 0.0001), separation=4e-10, yield_pressure=None, hamaker=None, restitution=None)")]
#[allow(clippy::too_many_arguments)] // the command's options, by name
pub fn capture_velocity<'py>(
    py: Python<'py>,
    density: f64,
    particle_modulus: f64,
    particle_poisson: f64,
    wall_modulus: f64,
    wall_poisson: f64,
    work_of_adhesion: f64,
    diameters: Option<&Bound<'py, PyAny>>,
    separation: f64,
    yield_pressure: Option<f64>,
    hamaker: Option<f64>,
    restitution: Option<f64>,
) -> PyResult<Bound<'py, PyDict>> {
    let density = positive("density", density)?;
    let particle_modulus = positive("particle_modulus", particle_modulus)?;
    let wall_modulus =
        if wall_modulus == f64::INFINITY { f64::INFINITY } else { positive("wall_modulus", wall_modulus)? };
    for (name, nu) in [("particle_poisson", particle_poisson), ("wall_poisson", wall_poisson)] {
        if !(-1.0..=0.5).contains(&nu) {
            return Err(PyValueError::new_err(format!("{name} {nu}: must lie in [-1, 0.5]")));
        }
    }
    let w = positive("work_of_adhesion", work_of_adhesion)?;
    let separation = positive("separation", separation)?;
    let modulus = effective_modulus(particle_modulus, particle_poisson, wall_modulus, wall_poisson);
    let yield_speed =
        yield_pressure.map(|p| positive("yield_pressure", p)).transpose()?.map(|p| yield_velocity(density, modulus, p));
    let dahneke = match (hamaker, restitution) {
        (Some(a), Some(e0)) => {
            if !(e0 > 0.0 && e0 <= 1.0) {
                return Err(PyValueError::new_err(format!("restitution {e0}: must lie in (0, 1]")));
            }
            Some((positive("hamaker", a)?, e0))
        }
        (None, None) => None,
        _ => return Err(PyValueError::new_err("hamaker and restitution: give both or neither")),
    };
    let diameters = match diameters {
        Some(d) => values(py, d, "diameters")?,
        None => vec![1e-7, 3e-7, 1e-6, 3e-6, 1e-5, 3e-5, 1e-4],
    };
    let rows = PyList::empty(py);
    for &d in &diameters {
        let radius = 0.5 * positive("diameters", d)?;
        let vc = jkr_capture_velocity(radius, density, modulus, w);
        let tabor = tabor_parameter(radius, modulus, w, separation);
        let regime = if tabor > JKR_TABOR_MIN {
            "JKR"
        } else if tabor < DMT_TABOR_MAX {
            "DMT"
        } else {
            "transition"
        };
        let row = PyDict::new(py);
        row.set_item("diameter", d)?;
        row.set_item("jkr_capture_velocity", vc)?;
        row.set_item("jkr_energy_loss", jkr_energy_loss(radius, modulus, w))?;
        row.set_item("tabor_parameter", tabor)?;
        row.set_item("contact_regime", regime)?;
        row.set_item("elastic", yield_speed.map(|vy| vc < vy))?;
        row.set_item(
            "dahneke_capture_velocity",
            dahneke.map(|(a, e0)| {
                dahneke_capture_velocity(sphere_mass(radius, density), hamaker_well_depth(a, radius, separation), e0)
            }),
        )?;
        rows.append(row)?;
    }
    let report = PyDict::new(py);
    report.set_item("effective_modulus", modulus)?;
    report.set_item("yield_velocity", yield_speed)?;
    report.set_item("rows", rows)?;
    Ok(report)
}
