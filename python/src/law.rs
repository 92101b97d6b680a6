//! `depo.WallLaw` and `depo.Tally`: the Brach & Dunn law on numpy arrays.

use depo_wall_model::{CaptureMode, Impacts, LawParams, Normals, Outcome, Real, Tally, UnknownPreset, WallLaw};
use numpy::{Element, PyArray1, PyArrayMethods};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};

use crate::arrays::{describe, typed, Input, Output};
use crate::threads::run_batch;

/// Capture mode: a captured particle is deposited where it hit, velocity and spin zero (the
/// C header's `DEPO_CAPTURE_DEPOSIT`).
pub const CAPTURE_DEPOSIT: i32 = 0;
/// Capture mode: a captured particle stays on the wall with zero normal velocity (the C
/// header's `DEPO_CAPTURE_KEEP_ON_WALL`).
pub const CAPTURE_KEEP_ON_WALL: i32 = 1;

/// The longest preset id quoted whole in an error message, as the C ABI quotes it.
const ID_QUOTED_MAX: usize = 64;

fn value_error(e: impl ToString) -> PyErr {
    PyValueError::new_err(e.to_string())
}

fn capture_mode(mode: &Bound<'_, PyAny>) -> PyResult<CaptureMode> {
    if let Ok(code) = mode.extract::<i64>() {
        return match code {
            0 => Ok(CaptureMode::Deposit),
            1 => Ok(CaptureMode::KeepOnWall),
            other => Err(PyValueError::new_err(format!(
                "capture mode {other}: expected CAPTURE_DEPOSIT (0) or CAPTURE_KEEP_ON_WALL (1)"
            ))),
        };
    }
    if let Ok(name) = mode.extract::<String>() {
        return match name.as_str() {
            "deposit" => Ok(CaptureMode::Deposit),
            "keep-on-wall" | "keep_on_wall" => Ok(CaptureMode::KeepOnWall),
            other => Err(PyValueError::new_err(format!(
                "capture mode {other:?}: expected \"deposit\" or \"keep-on-wall\" (or CAPTURE_DEPOSIT, CAPTURE_KEEP_ON_WALL)"
            ))),
        };
    }
    Err(PyTypeError::new_err(format!("capture mode: expected an int or a str, got {}", describe(mode))))
}

fn capture_code(mode: CaptureMode) -> i32 {
    match mode {
        CaptureMode::Deposit => CAPTURE_DEPOSIT,
        CaptureMode::KeepOnWall => CAPTURE_KEEP_ON_WALL,
    }
}

/// The Brach & Dunn (1998) rebound/capture law with validated constants (SI units).
///
/// - k1, k2: material restitution velocities of Eq. (8), m/s, finite and > 0.
/// - kappa1, kappa2: adhesion velocities of Eq. (9), m/s, finite and > 0.
/// - p, q: the exponents of Eqs. (8) and (9), finite and > 0.
/// - vc: capture velocity, m/s, finite; <= 0 means the law never captures by speed.
/// - mu: Coulomb friction coefficient of the contact, finite and >= 0.
/// - capture_mode: CAPTURE_DEPOSIT (a captured particle stops) or CAPTURE_KEEP_ON_WALL (it
///   keeps its tangential velocity and spin, with zero normal velocity).
///
/// A value out of range is a ValueError naming it, e.g. "invalid wall-law parameter k1 = 0:
/// must be positive". WallLaw.preset(id) gives a row of the paper's Table 1 (depo.presets()).
/// Laws are immutable, compare equal by value, and pickle (for multiprocessing and Dask).
#[pyclass(name = "WallLaw", module = "depo", frozen, eq)]
#[derive(Clone, PartialEq)]
pub struct PyWallLaw {
    pub(crate) law: WallLaw,
}

#[pymethods]
impl PyWallLaw {
    #[new]
    #[pyo3(signature = (k1, k2, kappa1, kappa2, p = 1.0, q = 1.0, *, vc, mu = 0.0, capture_mode = None))]
    #[allow(clippy::too_many_arguments)] // the law's eight constants, by name, as in the C struct
    fn new(
        k1: f64,
        k2: f64,
        kappa1: f64,
        kappa2: f64,
        p: f64,
        q: f64,
        vc: f64,
        mu: f64,
        capture_mode: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        let law = WallLaw::new(LawParams { k1, k2, kappa1, kappa2, p, q, vc, mu }).map_err(value_error)?;
        let capture = capture_mode.map(self::capture_mode).transpose()?.unwrap_or_default();
        Ok(Self { law: law.with_capture_mode(capture) })
    }

    /// The law of a row of the paper's Table 1 by id (e.g. "li1997-sio2"),
    /// friction 0. An unknown id is a ValueError listing the known ones.
    #[staticmethod]
    fn preset(id: &str) -> PyResult<Self> {
        let law = WallLaw::preset(id).map_err(|e| {
            if id.len() <= ID_QUOTED_MAX {
                return value_error(e);
            }
            let mut end = ID_QUOTED_MAX;
            while !id.is_char_boundary(end) {
                end -= 1;
            }
            value_error(UnknownPreset(format!("{}... ({} bytes)", &id[..end], id.len())))
        })?;
        Ok(Self { law })
    }

    /// The constants as a dict: k1, k2, kappa1, kappa2 (m/s), p, q, vc (m/s), mu.
    #[getter]
    fn params<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let LawParams { k1, k2, kappa1, kappa2, p, q, vc, mu } = *self.law.params();
        let d = PyDict::new(py);
        for (key, value) in
            [("k1", k1), ("k2", k2), ("kappa1", kappa1), ("kappa2", kappa2), ("p", p), ("q", q), ("vc", vc), ("mu", mu)]
        {
            d.set_item(key, value)?;
        }
        Ok(d)
    }

    /// What happens to captured particles: CAPTURE_DEPOSIT (0) or CAPTURE_KEEP_ON_WALL (1).
    #[getter]
    fn capture_mode(&self) -> i32 {
        capture_code(self.law.capture_mode())
    }

    /// A copy of the law that treats captured particles by `mode`,
    /// CAPTURE_DEPOSIT / "deposit" or CAPTURE_KEEP_ON_WALL / "keep-on-wall".
    fn with_capture_mode(&self, mode: &Bound<'_, PyAny>) -> PyResult<Self> {
        Ok(Self { law: self.law.with_capture_mode(capture_mode(mode)?) })
    }

    /// The law's coefficients (e, R, rho, captured) at normal speeds `vn` (m/s, any
    /// array-like; the sign is ignored): overall restitution e = R (1 - rho) (Eq. 2), material
    /// restitution R (Eq. 8), adhesion rho (Eq. 9, 1 where captured), and a bool array, True
    /// where captured. Each has the shape of `vn`. A non-finite vn is a ValueError.
    #[allow(non_snake_case)] // R is the paper's name
    fn coefficients<'py>(&self, py: Python<'py>, vn: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyTuple>> {
        let np = py.import("numpy")?;
        let vn = np.call_method1("ascontiguousarray", (vn, "float64"))?;
        let shape = vn.getattr("shape")?;
        let flat = vn.call_method1("reshape", (-1,))?;
        let flat = typed::<f64>(&flat, "vn", "float64")?;
        let flat = flat.readonly();
        let values = flat.as_slice()?;
        if let Some(i) = values.iter().position(|v| !v.is_finite()) {
            return Err(PyValueError::new_err(format!("vn[{i}] = {} is not finite", values[i])));
        }
        let law = self.law;
        let (e, R, rho, captured) = py.detach(|| {
            let n = values.len();
            let (mut e, mut R, mut rho, mut captured) =
                (Vec::with_capacity(n), Vec::with_capacity(n), Vec::with_capacity(n), Vec::with_capacity(n));
            for &v in values {
                let c = law.coefficients(v);
                e.push(c.overall);
                R.push(c.restitution);
                rho.push(c.adhesion);
                captured.push(c.captured);
            }
            (e, R, rho, captured)
        });
        let arrays = [
            PyArray1::from_vec(py, e).into_any(),
            PyArray1::from_vec(py, R).into_any(),
            PyArray1::from_vec(py, rho).into_any(),
            PyArray1::from_vec(py, captured).into_any(),
        ];
        let shaped = arrays.iter().map(|a| a.call_method1("reshape", (&shape,))).collect::<PyResult<Vec<_>>>()?;
        PyTuple::new(py, shaped)
    }

    /// Applies the law to a batch of wall contacts, in place, and returns one outcome per
    /// particle as a uint8 array: REBOUND (0), CAPTURED (1), SKIPPED (2, not an impact: v.n >= 0)
    /// or INVALID (3, non-finite values, a bad radius or per-particle normal: left untouched).
    ///
    /// - vx, vy, vz: velocity (m/s), updated in place; 1-D numpy arrays, all float64 or all
    ///   float32 (a TypeError otherwise), of one length.
    /// - normal: the wall's unit normal into the fluid for the whole batch (within 1e-4 of unit
    ///   length), used unless nx, ny, nz are given.
    /// - wx, wy, wz: spin (rad/s), updated in place, with radius (m): all four or none.
    /// - nx, ny, nz: one unit normal per particle.
    /// - capture_velocity: one capture velocity per particle (m/s), in place of the law's vc.
    /// - tally: a depo.Tally that this call's counts and energy are added to.
    /// - out: a uint8 array of n to write the outcomes into and return, in place of a new one
    ///   (saves allocating and first touching a new array on each call).
    ///
    /// Contiguous arrays are used in place, without a copy; strided views (a column of an
    /// (n, 3) array) are gathered into a copy and written back, with the same results bit for
    /// bit. The GIL is released while the law runs; batches of PARALLEL_MIN (65536) particles
    /// or more run on several threads (set_num_threads). Results are those of the C library's
    /// depo_apply_f64 / depo_apply_f32 on the same values, bit for bit.
    #[pyo3(signature = (vx, vy, vz, normal = None, wx = None, wy = None, wz = None, radius = None,
                        nx = None, ny = None, nz = None, capture_velocity = None, tally = None, out = None),
           text_signature = "($self, vx, vy, vz, normal=(0.0, 0.0, 1.0), wx=None, wy=None, wz=None, radius=None, nx=None, ny=None, nz=None, capture_velocity=None, tally=None, out=None)")]
    #[allow(clippy::too_many_arguments)] // the C batch's arrays, by name
    fn apply<'py>(
        &self,
        py: Python<'py>,
        vx: &Bound<'py, PyAny>,
        vy: &Bound<'py, PyAny>,
        vz: &Bound<'py, PyAny>,
        normal: Option<&Bound<'py, PyAny>>,
        wx: Option<&Bound<'py, PyAny>>,
        wy: Option<&Bound<'py, PyAny>>,
        wz: Option<&Bound<'py, PyAny>>,
        radius: Option<&Bound<'py, PyAny>>,
        nx: Option<&Bound<'py, PyAny>>,
        ny: Option<&Bound<'py, PyAny>>,
        nz: Option<&Bound<'py, PyAny>>,
        capture_velocity: Option<&Bound<'py, PyAny>>,
        tally: Option<Bound<'py, PyTally>>,
        out: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyArray1<u8>>> {
        let normal = match normal {
            None => [0.0, 0.0, 1.0],
            Some(n) => n.extract::<[f64; 3]>().map_err(|_| {
                PyValueError::new_err(format!("normal: expected 3 numbers (x, y, z), got {}", describe(n)))
            })?,
        };
        let out = out.map(|o| typed::<u8>(o, "out", "uint8")).transpose()?;
        let batch = Batch { v: [vx, vy, vz], w: [wx, wy, wz], radius, normals: [nx, ny, nz], capture_velocity, out };
        let (outcome, sums) = if vx.cast::<PyArray1<f64>>().is_ok() {
            apply_typed::<f64>(py, &self.law, batch, normal, "float64", tally.is_some())?
        } else if vx.cast::<PyArray1<f32>>().is_ok() {
            apply_typed::<f32>(py, &self.law, batch, normal, "float32", tally.is_some())?
        } else {
            return Err(typed::<f64>(vx, "vx", "float64 or float32").err().unwrap_or_else(|| {
                PyTypeError::new_err(format!(
                    "vx: expected a 1-D numpy array of float64 or float32, got {}",
                    describe(vx)
                ))
            }));
        };
        if let Some(tally) = tally {
            tally.borrow_mut().inner += sums;
        }
        Ok(outcome)
    }

    fn __repr__(&self) -> String {
        let LawParams { k1, k2, kappa1, kappa2, p, q, vc, mu } = *self.law.params();
        let mode = match self.law.capture_mode() {
            CaptureMode::Deposit => "",
            CaptureMode::KeepOnWall => ", capture_mode=CAPTURE_KEEP_ON_WALL",
        };
        format!("WallLaw(k1={k1:?}, k2={k2:?}, kappa1={kappa1:?}, kappa2={kappa2:?}, p={p:?}, q={q:?}, vc={vc:?}, mu={mu:?}{mode})")
    }

    /// For pickling: the constructor's arguments.
    fn __getnewargs_ex__<'py>(&self, py: Python<'py>) -> PyResult<(Bound<'py, PyTuple>, Bound<'py, PyDict>)> {
        let kwargs = self.params(py)?;
        kwargs.set_item("capture_mode", self.capture_mode())?;
        Ok((PyTuple::empty(py), kwargs))
    }
}

/// The arrays of one `apply` call, as given.
struct Batch<'a, 'py> {
    v: [&'a Bound<'py, PyAny>; 3],
    w: [Option<&'a Bound<'py, PyAny>>; 3],
    radius: Option<&'a Bound<'py, PyAny>>,
    normals: [Option<&'a Bound<'py, PyAny>>; 3],
    capture_velocity: Option<&'a Bound<'py, PyAny>>,
    /// The outcome array to write, else a new one.
    out: Option<Bound<'py, PyArray1<u8>>>,
}

/// `apply` in one precision: borrows the arrays (see `arrays`), builds the batch with the
/// crate's own checks, runs it with the GIL released, and writes gathered copies back.
fn apply_typed<'py, T: Real + Element>(
    py: Python<'py>,
    law: &WallLaw,
    batch: Batch<'_, 'py>,
    normal: [f64; 3],
    dtype: &str,
    want_tally: bool,
) -> PyResult<(Bound<'py, PyArray1<u8>>, Tally)> {
    let same = format!("{dtype} (as vx)");
    let array = |obj: &Bound<'py, PyAny>, name: &str| typed::<T>(obj, name, &same);
    let [vx, vy, vz] = [(batch.v[0], "vx"), (batch.v[1], "vy"), (batch.v[2], "vz")].map(|(o, name)| array(o, name));
    let (vx, vy, vz) = (vx?, vy?, vz?);
    let mut velocity = [Output::new(&vx, "vx")?, Output::new(&vy, "vy")?, Output::new(&vz, "vz")?];
    let n = velocity[0].len();

    let spin_arrays = match (batch.w, batch.radius) {
        ([None, None, None], None) => None,
        ([Some(wx), Some(wy), Some(wz)], Some(r)) => {
            Some([array(wx, "wx")?, array(wy, "wy")?, array(wz, "wz")?, array(r, "radius")?])
        }
        ([Some(_), Some(_), Some(_)], None) => {
            return Err(PyValueError::new_err("radius is required with spin (wx, wy, wz)"))
        }
        _ => return Err(PyValueError::new_err("wx, wy, wz: give all three, with radius, or none")),
    };
    let mut spin = match &spin_arrays {
        Some([wx, wy, wz, r]) => {
            Some(([Output::new(wx, "wx")?, Output::new(wy, "wy")?, Output::new(wz, "wz")?], Input::new(r, "radius")?))
        }
        None => None,
    };
    let normal_arrays = match batch.normals {
        [None, None, None] => None,
        [Some(nx), Some(ny), Some(nz)] => Some([array(nx, "nx")?, array(ny, "ny")?, array(nz, "nz")?]),
        _ => return Err(PyValueError::new_err("nx, ny, nz: give all three or none")),
    };
    let normals = match &normal_arrays {
        Some([nx, ny, nz]) => Some([Input::new(nx, "nx")?, Input::new(ny, "ny")?, Input::new(nz, "nz")?]),
        None => None,
    };
    let vc_array = batch.capture_velocity.map(|vc| array(vc, "capture_velocity")).transpose()?;
    let vc = vc_array.as_ref().map(|a| Input::new(a, "capture_velocity")).transpose()?;

    let outcome = batch.out.unwrap_or_else(|| PyArray1::<u8>::zeros(py, n, false));
    let mut outcome_guard = Output::new(&outcome, "out")?;
    let outcome_bytes = outcome_guard.slice();
    let [vx, vy, vz] = &mut velocity;
    let normals = match &normals {
        Some([nx, ny, nz]) => Normals::PerParticle([nx.slice(), ny.slice(), nz.slice()]),
        None => Normals::Uniform(normal.map(T::from_f64)),
    };
    let mut impacts = Impacts::new(
        [vx.slice(), vy.slice(), vz.slice()],
        normals,
        bytemuck::cast_slice_mut::<u8, Outcome>(outcome_bytes),
    )
    .map_err(value_error)?;
    if let Some(([wx, wy, wz], radius)) = &mut spin {
        impacts = impacts.with_spin([wx.slice(), wy.slice(), wz.slice()], radius.slice()).map_err(value_error)?;
    }
    if let Some(vc) = &vc {
        impacts = impacts.with_capture_velocity(vc.slice()).map_err(value_error)?;
    }
    let law = *law;
    let sums = py.detach(move || {
        run_batch(n, move |parallel| {
            let mut sums = Tally::default();
            let tally = want_tally.then_some(&mut sums);
            if parallel {
                law.apply(impacts, tally);
            } else {
                law.apply_on_calling_thread(impacts, tally);
            }
            sums
        })
    });
    for v in velocity {
        v.finish();
    }
    if let Some((w, _)) = spin {
        for w in w {
            w.finish();
        }
    }
    outcome_guard.finish();
    Ok((outcome, sums))
}

/// Counts of each outcome over one or more `apply` calls, and the energy lost by each
/// mechanism, summed over impacts per unit particle mass (J/kg; multiply by the particle mass
/// for joules).
///
/// Tally() starts at zero; law.apply(..., tally=t) adds to it. Fields: rebound, captured,
/// skipped, invalid (counts), energy_material (T_n (1 - R^2)), energy_adhesion
/// (T_n R^2 rho (2 - rho)), energy_friction, energy_deposition (kinetic energy carried onto
/// the wall by deposited particles), all J/kg. Tallies add with +.
#[pyclass(name = "Tally", module = "depo")]
#[derive(Clone, Default)]
pub struct PyTally {
    inner: Tally,
}

#[pymethods]
impl PyTally {
    #[new]
    #[pyo3(signature = (*, rebound = 0, captured = 0, skipped = 0, invalid = 0, energy_material = 0.0,
                        energy_adhesion = 0.0, energy_friction = 0.0, energy_deposition = 0.0))]
    #[allow(clippy::too_many_arguments)] // the C struct's fields, by name
    fn new(
        rebound: u64,
        captured: u64,
        skipped: u64,
        invalid: u64,
        energy_material: f64,
        energy_adhesion: f64,
        energy_friction: f64,
        energy_deposition: f64,
    ) -> Self {
        let mut inner = Tally { rebound, captured, skipped, invalid, ..Tally::default() };
        inner.energy.material = energy_material;
        inner.energy.adhesion = energy_adhesion;
        inner.energy.friction = energy_friction;
        inner.energy.deposition = energy_deposition;
        Self { inner }
    }

    /// Particles that rebounded.
    #[getter]
    fn rebound(&self) -> u64 {
        self.inner.rebound
    }
    /// Particles captured.
    #[getter]
    fn captured(&self) -> u64 {
        self.inner.captured
    }
    /// Particles skipped (not an impact).
    #[getter]
    fn skipped(&self) -> u64 {
        self.inner.skipped
    }
    /// Particles flagged invalid.
    #[getter]
    fn invalid(&self) -> u64 {
        self.inner.invalid
    }
    /// Material dissipation, J/kg summed over impacts.
    #[getter]
    fn energy_material(&self) -> f64 {
        self.inner.energy.material
    }
    /// Adhesion dissipation, J/kg summed over impacts.
    #[getter]
    fn energy_adhesion(&self) -> f64 {
        self.inner.energy.adhesion
    }
    /// Friction dissipation, J/kg summed over impacts.
    #[getter]
    fn energy_friction(&self) -> f64 {
        self.inner.energy.friction
    }
    /// Kinetic energy carried onto the wall by deposited particles, J/kg summed over impacts.
    #[getter]
    fn energy_deposition(&self) -> f64 {
        self.inner.energy.deposition
    }
    /// Particles counted, whatever their outcome.
    #[getter]
    fn particles(&self) -> u64 {
        self.inner.particles()
    }

    /// The fields as a dict.
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        let t = &self.inner;
        d.set_item("rebound", t.rebound)?;
        d.set_item("captured", t.captured)?;
        d.set_item("skipped", t.skipped)?;
        d.set_item("invalid", t.invalid)?;
        d.set_item("energy_material", t.energy.material)?;
        d.set_item("energy_adhesion", t.energy.adhesion)?;
        d.set_item("energy_friction", t.energy.friction)?;
        d.set_item("energy_deposition", t.energy.deposition)?;
        Ok(d)
    }

    fn __add__(&self, other: PyRef<'_, PyTally>) -> Self {
        let mut inner = self.inner;
        inner += other.inner;
        Self { inner }
    }

    fn __eq__(&self, other: &Bound<'_, PyAny>) -> bool {
        other.cast::<PyTally>().is_ok_and(|o| o.borrow().inner == self.inner)
    }

    fn __repr__(&self) -> String {
        let t = &self.inner;
        format!(
            "Tally(rebound={}, captured={}, skipped={}, invalid={}, energy_material={:?}, energy_adhesion={:?}, \
             energy_friction={:?}, energy_deposition={:?})",
            t.rebound,
            t.captured,
            t.skipped,
            t.invalid,
            t.energy.material,
            t.energy.adhesion,
            t.energy.friction,
            t.energy.deposition
        )
    }

    /// For pickling: the constructor's arguments.
    fn __getnewargs_ex__<'py>(&self, py: Python<'py>) -> PyResult<(Bound<'py, PyTuple>, Bound<'py, PyDict>)> {
        Ok((PyTuple::empty(py), self.to_dict(py)?))
    }
}
