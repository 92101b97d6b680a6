//! One subject, hence one file over 700 lines: the C ABI's entry points, each a thin checked wrapper.
//!
//! # libdepo: the C ABI of depo
//!
//! Lets C, C++ and Fortran solvers apply the Brach & Dunn wall law to their own particle
//! arrays, without copies, and, where their meshes do not resolve the near-wall layer, take
//! the chance of a particle in a wall cell reaching the wall from a deposition correlation
//! (`depo_wall_function_probability`, in `wall_function`). The header `include/depo.h` is generated from this file by cbindgen
//! (`cbindgen.toml`); `fortran/depo.f90` and `include/depo.hpp` wrap it for Fortran and C++.
//!
//! Conventions, after rustls-ffi:
//! - Every function returns an `int32_t` status (`DEPO_OK`, `DEPO_ERR_*`); the message of the
//!   last failure on the calling thread is `depo_last_error()`.
//! - Every exported body runs inside `ffi_guard!`: a panic becomes `DEPO_ERR_PANIC` with its
//!   message kept, never an unwind into the host solver.
//! - Handles are opaque; `depo_law_new`/`depo_law_preset` make one, `depo_law_free` takes NULL.
//!   The handle comes first, then inputs, then outputs.
//! - Outputs are written only on success: a call that fails changes nothing.
//! - Status codes keep their values forever; a retired one stays as a comment.
//!
//! Bad particles are not errors: they are flagged `DEPO_INVALID` per particle and left
//! untouched while the rest of the batch is processed.

#![allow(clippy::missing_safety_doc)] // the safety contract of every function is in its C doc

use std::cell::RefCell;
use std::ffi::{c_char, CStr, CString};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::{Arc, RwLock};

use depo_wall_model::{
    CaptureMode, Impacts, LawParams, Normals, Outcome, Real, SizeDependence, Tally, UnknownPreset, WallLaw,
};

/// Success.
pub const DEPO_OK: i32 = 0;
/// A pointer that must not be NULL was NULL.
pub const DEPO_ERR_NULL: i32 = 1;
/// A value out of its valid range: a law parameter, a batch normal, an unknown preset id,
/// overlapping or misaligned arrays, a face id out of range, a thread count.
pub const DEPO_ERR_INVALID: i32 = 2;
/// depo panicked; the message is in `depo_last_error()`. A bug: please report it.
pub const DEPO_ERR_PANIC: i32 = 3;

/// The particle hit the wall and rebounded: velocity (and spin) updated.
pub const DEPO_REBOUND: u8 = 0;
/// The particle hit the wall and was captured: velocity (and spin) set to zero, or with
/// `DEPO_CAPTURE_KEEP_ON_WALL` only the velocity's normal component.
pub const DEPO_CAPTURED: u8 = 1;
/// Not an impact (`v . n >= 0`): untouched.
pub const DEPO_SKIPPED: u8 = 2;
/// Non-finite velocity or spin, a radius (with spin) that is not finite or below 1e-150 m in
/// double precision, 1e-18 m in single (subnormal and zero radii included: the spin change
/// goes as `1 / r`), or a per-particle normal not of unit length within 1e-4: untouched.
pub const DEPO_INVALID: u8 = 3;

/// The constants of the law (SI units; see docs/MODEL.md): restitution velocities `k1, k2` (m/s),
/// adhesion velocities `kappa1, kappa2` (m/s), exponents `p, q`, capture velocity `vc` (m/s,
/// `<= 0`: never captured by speed), friction coefficient `mu`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DepoLawParams {
    pub k1: f64,
    pub k2: f64,
    pub kappa1: f64,
    pub kappa2: f64,
    pub p: f64,
    pub q: f64,
    pub vc: f64,
    pub mu: f64,
}

impl From<DepoLawParams> for LawParams {
    fn from(c: DepoLawParams) -> Self {
        let DepoLawParams { k1, k2, kappa1, kappa2, p, q, vc, mu } = c;
        Self { k1, k2, kappa1, kappa2, p, q, vc, mu }
    }
}

impl From<LawParams> for DepoLawParams {
    fn from(r: LawParams) -> Self {
        let LawParams { k1, k2, kappa1, kappa2, p, q, vc, mu } = r;
        Self { k1, k2, kappa1, kappa2, p, q, vc, mu }
    }
}

/// Counts of each outcome, added to by every successful `depo_apply_*` call that is given it
/// (zero it before the first), and the energy lost by each mechanism, summed over impacts per
/// unit particle mass (J/kg).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct DepoTally {
    pub rebound: u64,
    pub captured: u64,
    pub skipped: u64,
    pub invalid: u64,
    /// Material dissipation, `T_n (1 - R^2)`.
    pub energy_material: f64,
    /// Adhesion dissipation, `T_n R^2 rho (2 - rho)`.
    pub energy_adhesion: f64,
    /// Friction dissipation in the contact.
    pub energy_friction: f64,
    /// Kinetic energy carried onto the wall by deposited particles.
    pub energy_deposition: f64,
}

/// A batch of wall contacts in double precision, as structure-of-arrays pointers into the
/// host's memory: each array holds `n` contiguous values, aligned as its element type (as
/// malloc, new, std::vector and Fortran arrays give them; no wider alignment is needed, on x86
/// or elsewhere). Strided or array-of-structures data goes through `depo_apply_strided_f64`
/// with the same batch and its strides. Arrays must not overlap each other (`DEPO_ERR_INVALID`, as is a misaligned array)
/// nor the tally (not checked).
#[repr(C)]
#[derive(Debug)]
pub struct DepoImpactsF64 {
    /// Number of particles.
    pub n: usize,
    /// In/out velocity (m/s), required when `n > 0`.
    pub vx: *mut f64,
    pub vy: *mut f64,
    pub vz: *mut f64,
    /// In/out spin (rad/s); all three NULL: spin not tracked (taken as zero).
    pub wx: *mut f64,
    pub wy: *mut f64,
    pub wz: *mut f64,
    /// Radius (m), required when spin is tracked.
    pub radius: *const f64,
    /// Per-particle unit normals into the fluid; all three NULL: use `normal`.
    pub nx: *const f64,
    pub ny: *const f64,
    pub nz: *const f64,
    /// One unit normal for the whole batch (used when `nx, ny, nz` are NULL).
    pub normal: [f64; 3],
    /// Out: one `DEPO_*` outcome per particle, required when `n > 0`.
    pub outcome: *mut u8,
}

/// `DepoImpactsF64` in single precision.
#[repr(C)]
#[derive(Debug)]
pub struct DepoImpactsF32 {
    pub n: usize,
    pub vx: *mut f32,
    pub vy: *mut f32,
    pub vz: *mut f32,
    pub wx: *mut f32,
    pub wy: *mut f32,
    pub wz: *mut f32,
    pub radius: *const f32,
    pub nx: *const f32,
    pub ny: *const f32,
    pub nz: *const f32,
    pub normal: [f32; 3],
    pub outcome: *mut u8,
}

/// An opaque wall law: validated constants, made by `depo_law_new` or `depo_law_preset`, freed by
/// `depo_law_free`. Safe to share between threads for reading.
pub struct DepoWallLaw {
    law: WallLaw,
}

/// A failure to report: a status and its message.
struct Failure(i32, String);

impl Failure {
    fn null(what: &str) -> Self {
        Failure(DEPO_ERR_NULL, format!("{what} is NULL"))
    }
    fn invalid(message: impl Into<String>) -> Self {
        Failure(DEPO_ERR_INVALID, message.into())
    }
}

thread_local! {
    static LAST_ERROR: RefCell<CString> = RefCell::new(CString::default());
}

/// Keeps `message` for `depo_last_error()`. Never panics: while the thread is being torn down
/// (a host's pthread-key or thread-local destructor calling depo after depo's storage is gone)
/// the message is dropped and the status alone reports the failure.
fn set_last_error(message: &str) {
    let text = CString::new(message.replace('\0', " ")).unwrap_or_default();
    let _ = LAST_ERROR.try_with(|cell| {
        if let Ok(mut slot) = cell.try_borrow_mut() {
            *slot = text;
        }
    });
}

/// Runs an exported body: its `Result` becomes a status, a panic becomes `DEPO_ERR_PANIC`, and
/// every failure leaves its message for `depo_last_error()`.
macro_rules! ffi_guard {
    ($body:block) => {{
        let result: std::thread::Result<Result<(), Failure>> = catch_unwind(AssertUnwindSafe(|| $body));
        match result {
            Ok(Ok(())) => DEPO_OK,
            Ok(Err(Failure(status, message))) => {
                set_last_error(&message);
                status
            }
            Err(panic) => {
                let message = panic
                    .downcast_ref::<&str>()
                    .map(|s| s.to_string())
                    .or_else(|| panic.downcast_ref::<String>().cloned())
                    .unwrap_or_else(|| "unknown panic".into());
                set_last_error(&format!("depo panicked: {message}"));
                DEPO_ERR_PANIC
            }
        }
    }};
}

mod deposition;
pub use deposition::depo_accumulate_deposits;
mod wall_function;
pub use wall_function::{
    depo_deposition_velocity, depo_wall_function_probability, DepoAir, DEPO_CORRELATION_HUSSEIN,
    DEPO_CORRELATION_LAI_NAZAROFF, DEPO_CORRELATION_PAPAVERGOS_HEDLEY, DEPO_CORRELATION_WOOD, DEPO_SURFACE_CEILING,
    DEPO_SURFACE_FLOOR, DEPO_SURFACE_WALL,
};

/// `&T` from a pointer that must not be NULL.
unsafe fn required<'a, T>(ptr: *const T, what: &str) -> Result<&'a T, Failure> {
    ptr.as_ref().ok_or_else(|| Failure::null(what))
}

/// Fails unless `ptr` (not NULL) is aligned as `T`, which a slice requires.
fn check_aligned<T>(ptr: *const T, what: &str) -> Result<(), Failure> {
    if ptr.is_aligned() {
        Ok(())
    } else {
        Err(Failure::invalid(format!("{what} is not aligned to {} bytes", std::mem::align_of::<T>())))
    }
}

/// A slice from a pointer that must not be NULL, and must be aligned, when `n > 0`.
unsafe fn slice<'a, T>(ptr: *const T, n: usize, what: &str) -> Result<&'a [T], Failure> {
    if n == 0 {
        Ok(&[])
    } else if ptr.is_null() {
        Err(Failure::null(what))
    } else {
        check_aligned(ptr, what)?;
        Ok(std::slice::from_raw_parts(ptr, n))
    }
}

/// A mutable slice from a pointer that must not be NULL, and must be aligned, when `n > 0`.
unsafe fn slice_mut<'a, T>(ptr: *mut T, n: usize, what: &str) -> Result<&'a mut [T], Failure> {
    if n == 0 {
        Ok(&mut [])
    } else if ptr.is_null() {
        Err(Failure::null(what))
    } else {
        check_aligned(ptr, what)?;
        Ok(std::slice::from_raw_parts_mut(ptr, n))
    }
}

/// The message of the last failure on the calling thread ("" if none), valid until the next
/// failing depo call on this thread. Never NULL. Safe to call from a thread-exit destructor;
/// the message of a failure during the thread's teardown may be "".
#[no_mangle]
pub extern "C" fn depo_last_error() -> *const c_char {
    LAST_ERROR.try_with(|cell| cell.try_borrow().map(|text| text.as_ptr()).ok()).ok().flatten().unwrap_or(c"".as_ptr())
}

/// The library version, "MAJOR.MINOR.PATCH", the same as `DEPO_VERSION` in the header it was
/// built with. Never NULL.
#[no_mangle]
pub extern "C" fn depo_version() -> *const c_char {
    concat!(env!("CARGO_PKG_VERSION"), "\0").as_ptr().cast()
}

/// Makes a law from `params`. On `DEPO_ERR_INVALID` no law is made, `*out` is unchanged, and
/// `depo_last_error()` names the bad field and its value.
#[no_mangle]
pub unsafe extern "C" fn depo_law_new(params: *const DepoLawParams, out: *mut *mut DepoWallLaw) -> i32 {
    ffi_guard!({
        let p = required(params, "params")?;
        if out.is_null() {
            return Err(Failure::null("out"));
        }
        let params = LawParams::from(*p);
        let law = WallLaw::new(params).map_err(|e| Failure::invalid(e.to_string()))?;
        *out = Box::into_raw(Box::new(DepoWallLaw { law }));
        Ok(())
    })
}

/// The longest preset id quoted whole in an error message.
const ID_QUOTED_MAX: usize = 64;

/// Makes the law of a preset of the paper's Table 1 by id (e.g. "li1997-sio2"; friction 0).
/// An unknown id is `DEPO_ERR_INVALID`, with the known ids in `depo_last_error()` (and the id
/// quoted up to 64 bytes).
#[no_mangle]
pub unsafe extern "C" fn depo_law_preset(id: *const c_char, out: *mut *mut DepoWallLaw) -> i32 {
    ffi_guard!({
        if id.is_null() {
            return Err(Failure::null("id"));
        }
        if out.is_null() {
            return Err(Failure::null("out"));
        }
        let id = CStr::from_ptr(id).to_str().map_err(|_| Failure::invalid("preset id is not UTF-8"))?;
        let law = WallLaw::preset(id).map_err(|e| {
            if id.len() <= ID_QUOTED_MAX {
                return Failure::invalid(e.to_string());
            }
            let mut end = ID_QUOTED_MAX;
            while !id.is_char_boundary(end) {
                end -= 1;
            }
            Failure::invalid(UnknownPreset(format!("{}... ({} bytes)", &id[..end], id.len())).to_string())
        })?;
        *out = Box::into_raw(Box::new(DepoWallLaw { law }));
        Ok(())
    })
}

/// Writes the constants of `law` to `*params`.
#[no_mangle]
pub unsafe extern "C" fn depo_law_params(law: *const DepoWallLaw, params: *mut DepoLawParams) -> i32 {
    ffi_guard!({
        let law = required(law, "law")?;
        if params.is_null() {
            return Err(Failure::null("params"));
        }
        *params = DepoLawParams::from(*law.law.params());
        Ok(())
    })
}

/// Capture mode: a captured particle is deposited where it hit, velocity and spin zero. The
/// default of every law.
pub const DEPO_CAPTURE_DEPOSIT: i32 = 0;
/// Capture mode: a captured particle stays on the wall with zero normal velocity, its
/// tangential velocity and spin after the impact's friction impulse left as they are (the
/// paper's remark that an obliquely captured particle may migrate along the surface); the host
/// decides what to do with it (its outcome is `DEPO_CAPTURED`).
pub const DEPO_CAPTURE_KEEP_ON_WALL: i32 = 1;

/// Makes a copy of `law` that treats captured particles by `mode` (`DEPO_CAPTURE_DEPOSIT` or
/// `DEPO_CAPTURE_KEEP_ON_WALL`), freed by `depo_law_free`. Another mode is `DEPO_ERR_INVALID`;
/// on any failure `*out` is unchanged.
#[no_mangle]
pub unsafe extern "C" fn depo_law_with_capture_mode(
    law: *const DepoWallLaw,
    mode: i32,
    out: *mut *mut DepoWallLaw,
) -> i32 {
    ffi_guard!({
        let law = required(law, "law")?;
        if out.is_null() {
            return Err(Failure::null("out"));
        }
        let capture = match mode {
            DEPO_CAPTURE_DEPOSIT => CaptureMode::Deposit,
            DEPO_CAPTURE_KEEP_ON_WALL => CaptureMode::KeepOnWall,
            other => {
                return Err(Failure::invalid(format!(
                    "capture mode {other}: expected DEPO_CAPTURE_DEPOSIT (0) or DEPO_CAPTURE_KEEP_ON_WALL (1)"
                )))
            }
        };
        *out = Box::into_raw(Box::new(DepoWallLaw { law: law.law.with_capture_mode(capture) }));
        Ok(())
    })
}

/// Writes the capture mode of `law` (`DEPO_CAPTURE_DEPOSIT` or `DEPO_CAPTURE_KEEP_ON_WALL`) to
/// `*mode`.
#[no_mangle]
pub unsafe extern "C" fn depo_law_capture_mode(law: *const DepoWallLaw, mode: *mut i32) -> i32 {
    ffi_guard!({
        let law = required(law, "law")?;
        if mode.is_null() {
            return Err(Failure::null("mode"));
        }
        *mode = match law.law.capture_mode() {
            CaptureMode::Deposit => DEPO_CAPTURE_DEPOSIT,
            CaptureMode::KeepOnWall => DEPO_CAPTURE_KEEP_ON_WALL,
        };
        Ok(())
    })
}

/// Frees a law made by `depo_law_new`, `depo_law_preset` or `depo_law_with_capture_mode`. NULL
/// is fine.
#[no_mangle]
pub unsafe extern "C" fn depo_law_free(law: *mut DepoWallLaw) {
    if !law.is_null() {
        let _ = catch_unwind(AssertUnwindSafe(|| drop(Box::from_raw(law))));
    }
}

/// The law's coefficients at `n` normal velocities `vn` (m/s; the sign is ignored): overall
/// restitution `e`, material restitution `R`, adhesion `rho`, and 1 where captured else 0.
/// Any output may be NULL. A non-finite `vn`, or outputs that overlap `vn` or each other, is
/// `DEPO_ERR_INVALID` and writes nothing.
#[no_mangle]
#[allow(non_snake_case)] // `R` is the paper's name, and the header's
pub unsafe extern "C" fn depo_coefficients(
    law: *const DepoWallLaw,
    n: usize,
    vn: *const f64,
    e: *mut f64,
    R: *mut f64,
    rho: *mut f64,
    captured: *mut u8,
) -> i32 {
    ffi_guard!({
        let law = &required(law, "law")?.law;
        let vn = slice(vn, n, "vn")?;
        if let Some(i) = vn.iter().position(|v| !v.is_finite()) {
            return Err(Failure::invalid(format!("vn[{i}] = {} is not finite", vn[i])));
        }
        let mut outputs = (
            (!e.is_null()).then(|| slice_mut(e, n, "e")).transpose()?,
            (!R.is_null()).then(|| slice_mut(R, n, "R")).transpose()?,
            (!rho.is_null()).then(|| slice_mut(rho, n, "rho")).transpose()?,
            (!captured.is_null()).then(|| slice_mut(captured, n, "captured")).transpose()?,
        );
        let mut arrays = vec![("vn", span(vn))];
        arrays.extend(outputs.0.as_deref().map(|s| ("e", span(s))));
        arrays.extend(outputs.1.as_deref().map(|s| ("R", span(s))));
        arrays.extend(outputs.2.as_deref().map(|s| ("rho", span(s))));
        arrays.extend(outputs.3.as_deref().map(|s| ("captured", span(s))));
        check_disjoint(&arrays)?;
        for (i, &v) in vn.iter().enumerate() {
            let c = law.coefficients(v);
            if let Some(out) = outputs.0.as_deref_mut() {
                out[i] = c.overall;
            }
            if let Some(out) = outputs.1.as_deref_mut() {
                out[i] = c.restitution;
            }
            if let Some(out) = outputs.2.as_deref_mut() {
                out[i] = c.adhesion;
            }
            if let Some(out) = outputs.3.as_deref_mut() {
                out[i] = u8::from(c.captured);
            }
        }
        Ok(())
    })
}

/// Batches of this many particles or more may be run on several threads (see
/// `depo_set_num_threads`); smaller ones always run on the calling thread, in one piece.
pub const DEPO_PARALLEL_MIN: usize = 65536;
const _: () = assert!(DEPO_PARALLEL_MIN == depo_wall_model::kernel::PARALLEL_MIN);

/// The largest thread cap `depo_set_num_threads` accepts.
pub const DEPO_MAX_THREADS: usize = 1024;
const _: () = assert!(DEPO_MAX_THREADS == depo_wall_model::kernel::MAX_THREADS);

/// Where depo runs large batches, as set by `depo_set_num_threads`.
enum Threads {
    /// rayon's global pool.
    Global,
    /// The calling thread: no thread is started or woken.
    Caller,
    /// A pool of depo's own, of the capped size.
    Pool(Arc<rayon::ThreadPool>),
}

static THREADS: RwLock<Threads> = RwLock::new(Threads::Global);

/// Sets how many threads depo runs a large batch on (`DEPO_PARALLEL_MIN` particles or more).
/// Smaller batches always run on the calling thread, in one piece, whatever this setting.
///
/// - `0` (the default): rayon's global pool, one thread per core or `RAYON_NUM_THREADS`. It
///   starts at the first large batch and lives until the process exits.
/// - `1`: the calling thread, for large batches too: depo never starts or wakes a thread. Host
///   solvers that run their own OpenMP threads, or one MPI rank per core, call it with 1.
/// - `2..=DEPO_MAX_THREADS`: a pool of that many threads of depo's own, started by this call;
///   it ends when a later call replaces it, once the batches running on it have finished.
///
/// A value above `DEPO_MAX_THREADS` is `DEPO_ERR_INVALID` and changes nothing. The setting is
/// process-wide: it holds for every thread and every law, and may be changed at any time
/// (batches already running keep the threads they started with). Results are identical, bit
/// for bit, for every setting.
#[no_mangle]
pub extern "C" fn depo_set_num_threads(threads: usize) -> i32 {
    ffi_guard!({
        let setting = match threads {
            0 => Threads::Global,
            1 => Threads::Caller,
            2..=DEPO_MAX_THREADS => {
                let pool = rayon::ThreadPoolBuilder::new()
                    .num_threads(threads)
                    .thread_name(|i| format!("depo-{i}"))
                    .build()
                    .map_err(|e| Failure::invalid(format!("cannot start {threads} threads: {e}")))?;
                Threads::Pool(Arc::new(pool))
            }
            _ => {
                return Err(Failure::invalid(format!(
                    "threads = {threads} is above the most depo accepts (DEPO_MAX_THREADS = {DEPO_MAX_THREADS})"
                )))
            }
        };
        *THREADS.write().unwrap_or_else(|e| e.into_inner()) = setting;
        Ok(())
    })
}

/// Runs the application of the law to a batch of `n` particles where `depo_set_num_threads`
/// says: `apply(parallel)` is called on the calling thread unless `n` reaches
/// `DEPO_PARALLEL_MIN` and a pool is allowed, and with `parallel` false it must keep every
/// piece on the calling thread (`WallLaw::apply_on_calling_thread`). Small batches take no lock.
fn run_batch<R: Send>(n: usize, apply: impl FnOnce(bool) -> R + Send) -> R {
    if n < DEPO_PARALLEL_MIN {
        return apply(false);
    }
    let pool = match &*THREADS.read().unwrap_or_else(|e| e.into_inner()) {
        Threads::Global => None,
        Threads::Caller => return apply(false),
        Threads::Pool(pool) => Some(Arc::clone(pool)),
    };
    match pool {
        Some(pool) => pool.install(|| apply(true)),
        None => apply(true),
    }
}

/// The byte range an array occupies, for the overlap check.
fn span<T>(s: &[T]) -> (usize, usize) {
    let start = s.as_ptr() as usize;
    (start, start + std::mem::size_of_val(s))
}

/// Fails if any two non-empty arrays overlap (creating the slices would otherwise be undefined
/// behaviour). O(arrays^2), independent of `n`.
fn check_disjoint(arrays: &[(&str, (usize, usize))]) -> Result<(), Failure> {
    for (i, (name_a, (a0, a1))) in arrays.iter().enumerate() {
        for (name_b, (b0, b1)) in &arrays[i + 1..] {
            if a0 < a1 && b0 < b1 && a0 < b1 && b0 < a1 {
                return Err(Failure::invalid(format!("arrays {name_a} and {name_b} overlap")));
            }
        }
    }
    Ok(())
}

/// The raw pointers of one batch, either precision.
struct RawBatch<T> {
    n: usize,
    v: [*mut T; 3],
    w: [*mut T; 3],
    radius: *const T,
    normals: [*const T; 3],
    normal: [T; 3],
    outcome: *mut u8,
}

macro_rules! raw_batch_from {
    ($name:ident, $c_type:ty, $t:ty) => {
        impl RawBatch<$t> {
            unsafe fn $name(batch: *mut $c_type) -> Result<Self, Failure> {
                let b = required(batch.cast_const(), "batch")?;
                Ok(Self {
                    n: b.n,
                    v: [b.vx, b.vy, b.vz],
                    w: [b.wx, b.wy, b.wz],
                    radius: b.radius,
                    normals: [b.nx, b.ny, b.nz],
                    normal: b.normal,
                    outcome: b.outcome,
                })
            }
        }
    };
}
raw_batch_from!(from_f64, DepoImpactsF64, f64);
raw_batch_from!(from_f32, DepoImpactsF32, f32);

/// Checks a raw batch and applies the law to it, with per-particle capture velocities when
/// `capture_velocity` is given; the tally is added to only on success.
unsafe fn apply_raw<T: Real>(
    law: *const DepoWallLaw,
    raw: RawBatch<T>,
    capture_velocity: Option<*const T>,
    tally: *mut DepoTally,
) -> Result<(), Failure> {
    let law = &required(law, "law")?.law;
    let n = raw.n;
    if n == 0 {
        // Nothing to do, whatever the other fields hold (an empty std::vector's data() is NULL
        // and a zeroed batch has a zero normal).
        return Ok(());
    }
    let [vx, vy, vz] = raw.v;
    let vx = slice_mut(vx, n, "vx")?;
    let vy = slice_mut(vy, n, "vy")?;
    let vz = slice_mut(vz, n, "vz")?;
    let outcome = slice_mut(raw.outcome.cast::<Outcome>(), n, "outcome")?;
    let spin_given = raw.w.map(|p| !p.is_null());
    let spin = match spin_given {
        [false, false, false] => None,
        [true, true, true] => Some((
            slice_mut(raw.w[0], n, "wx")?,
            slice_mut(raw.w[1], n, "wy")?,
            slice_mut(raw.w[2], n, "wz")?,
            slice(raw.radius, n, "radius (required with spin)")?,
        )),
        _ => return Err(Failure::null("one of wx, wy, wz (give all three or none)")),
    };
    let vc = match capture_velocity {
        Some(ptr) => Some(slice(ptr, n, "capture_velocity")?),
        None => None,
    };
    let normals_given = raw.normals.map(|p| !p.is_null());
    let per_particle = match normals_given {
        [false, false, false] => None,
        [true, true, true] => {
            Some([slice(raw.normals[0], n, "nx")?, slice(raw.normals[1], n, "ny")?, slice(raw.normals[2], n, "nz")?])
        }
        _ => return Err(Failure::null("one of nx, ny, nz (give all three or none)")),
    };

    let mut arrays = vec![("vx", span(vx)), ("vy", span(vy)), ("vz", span(vz)), ("outcome", span(outcome))];
    if let Some((wx, wy, wz, radius)) = &spin {
        arrays.extend([("wx", span(wx)), ("wy", span(wy)), ("wz", span(wz)), ("radius", span(radius))]);
    }
    if let Some([nx, ny, nz]) = &per_particle {
        arrays.extend([("nx", span(nx)), ("ny", span(ny)), ("nz", span(nz))]);
    }
    if let Some(vc) = vc {
        arrays.push(("capture_velocity", span(vc)));
    }
    // The tally is written after the kernel has finished with the arrays: an overlap is the
    // host's own data overwritten, documented rather than checked (checking it cost a small
    // batch about 10 ns a call).
    if !tally.is_null() {
        check_aligned(tally.cast_const(), "tally")?;
    }
    check_disjoint(&arrays)?;

    let normals = match per_particle {
        Some(n) => Normals::PerParticle(n),
        None => Normals::Uniform(raw.normal),
    };
    let mut batch = Impacts::new([vx, vy, vz], normals, outcome).map_err(|e| Failure::invalid(e.to_string()))?;
    if let Some((wx, wy, wz, radius)) = spin {
        batch = batch.with_spin([wx, wy, wz], radius).map_err(|e| Failure::invalid(e.to_string()))?;
    }
    if let Some(vc) = vc {
        batch = batch.with_capture_velocity(vc).map_err(|e| Failure::invalid(e.to_string()))?;
    }
    let want_tally = !tally.is_null();
    let sums = run_batch(n, |parallel| {
        let mut sums = Tally::default();
        let want = want_tally.then_some(&mut sums);
        if parallel {
            law.apply(batch, want);
        } else {
            law.apply_on_calling_thread(batch, want);
        }
        sums
    });
    if want_tally {
        let t = &mut *tally;
        t.rebound += sums.rebound;
        t.captured += sums.captured;
        t.skipped += sums.skipped;
        t.invalid += sums.invalid;
        t.energy_material += sums.energy.material;
        t.energy_adhesion += sums.energy.adhesion;
        t.energy_friction += sums.energy.friction;
        t.energy_deposition += sums.energy.deposition;
    }
    Ok(())
}

/// Applies `law` to every particle of `batch` in place, writing one outcome per particle, and
/// adds the batch's counts and energy to `*tally` unless it is NULL (aligned as `DepoTally`,
/// and not overlapping the batch's arrays, which is not checked). A batch normal not of unit
/// length within 1e-4 is `DEPO_ERR_INVALID`; bad particles are flagged `DEPO_INVALID`. An empty
/// batch (`n == 0`) is `DEPO_OK` and reads no other field.
#[no_mangle]
pub unsafe extern "C" fn depo_apply_f64(
    law: *const DepoWallLaw,
    batch: *mut DepoImpactsF64,
    tally: *mut DepoTally,
) -> i32 {
    ffi_guard!({ apply_raw(law, RawBatch::from_f64(batch)?, None, tally) })
}

/// Byte strides of a batch's arrays, for hosts that keep their particles as arrays of
/// structures: the distance in bytes from one particle's value to the next's (a multiple of 8
/// for the `double` arrays, at least the value's size); 0 for a contiguous array.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct DepoStrides {
    /// Of `vx, vy, vz`.
    pub v: [usize; 3],
    /// Of `wx, wy, wz`.
    pub w: [usize; 3],
    /// Of `radius`.
    pub radius: usize,
    /// Of `nx, ny, nz`.
    pub normals: [usize; 3],
    /// Of `outcome` (bytes; any stride of at least 1).
    pub outcome: usize,
}

/// Particles per piece of a strided batch: gathered into contiguous scratch arrays, handed to
/// the kernel, and scattered back.
const STRIDED_PIECE: usize = 16384;

/// `depo_apply_f64` on arrays with byte strides (`strides` NULL: all contiguous): each piece of
/// 16384 particles is gathered into contiguous scratch arrays, goes through the same kernel
/// and checks, and is scattered back, so results are those of `depo_apply_f64` on the same
/// values, bit for bit. Every pointer must be aligned for its type and every `double` stride a
/// multiple of 8; outputs must not share memory with any other array (arrays with the same
/// stride may interleave, as a structure's fields do; arrays with different strides may not
/// overlap at all). A failing call changes nothing.
#[no_mangle]
pub unsafe extern "C" fn depo_apply_strided_f64(
    law: *const DepoWallLaw,
    batch: *mut DepoImpactsF64,
    strides: *const DepoStrides,
    tally: *mut DepoTally,
) -> i32 {
    ffi_guard!({
        let raw = RawBatch::from_f64(batch)?;
        let strides = if strides.is_null() { DepoStrides::default() } else { *strides };
        apply_strided(law, raw, strides, tally)
    })
}

/// One strided array of a batch: name, first element, stride and element size in bytes,
/// written or only read.
struct Strided {
    name: &'static str,
    start: usize,
    stride: usize,
    size: usize,
    output: bool,
}

impl Strided {
    /// The bytes from the first element's start to the last's end.
    fn span(&self, n: usize) -> (usize, usize) {
        (self.start, self.start + (n - 1) * self.stride + self.size)
    }

    /// Whether the two arrays may share a byte: their spans meet and, with equal strides, their
    /// elements fall on the same bytes of a stride; with different strides, spans that meet.
    fn may_overlap(&self, other: &Strided, n: usize) -> bool {
        let ((a0, a1), (b0, b1)) = (self.span(n), other.span(n));
        if a1 <= b0 || b1 <= a0 {
            return false;
        }
        if self.stride != other.stride {
            return true;
        }
        let s = self.stride;
        let d = (other.start as isize - self.start as isize).rem_euclid(s as isize) as usize;
        d < self.size || d + other.size > s
    }
}

unsafe fn apply_strided(
    law: *const DepoWallLaw,
    raw: RawBatch<f64>,
    strides: DepoStrides,
    tally: *mut DepoTally,
) -> Result<(), Failure> {
    let n = raw.n;
    if n == 0 {
        return apply_raw(law, raw, None, tally);
    }
    const F64: usize = std::mem::size_of::<f64>();
    let mut arrays = Vec::new();
    let mut add = |name: &'static str, ptr: usize, stride: usize, size: usize, output: bool| {
        if ptr == 0 {
            return Ok(());
        }
        let stride = if stride == 0 { size } else { stride };
        if stride < size || stride % size != 0 || ptr % size != 0 {
            return Err(Failure::invalid(format!(
                "{name}: stride {stride} bytes at address {ptr:#x}: each value must be aligned, {size} bytes apart or a multiple of that"
            )));
        }
        arrays.push(Strided { name, start: ptr, stride, size, output });
        Ok(())
    };
    for (k, name) in ["vx", "vy", "vz"].into_iter().enumerate() {
        add(name, raw.v[k] as usize, strides.v[k], F64, true)?;
    }
    for (k, name) in ["wx", "wy", "wz"].into_iter().enumerate() {
        add(name, raw.w[k] as usize, strides.w[k], F64, true)?;
    }
    add("radius", raw.radius as usize, strides.radius, F64, false)?;
    for (k, name) in ["nx", "ny", "nz"].into_iter().enumerate() {
        add(name, raw.normals[k] as usize, strides.normals[k], F64, false)?;
    }
    add("outcome", raw.outcome as usize, strides.outcome, 1, true)?;
    for (i, a) in arrays.iter().enumerate() {
        for b in &arrays[i + 1..] {
            if (a.output || b.output) && a.may_overlap(b, n) {
                return Err(Failure::invalid(format!("{} and {} share memory", a.name, b.name)));
            }
        }
    }
    // Each array's base and stride (`None` where the batch has no such array), and scratch
    // space for a piece of the arrays it has.
    let find = |name: &str| arrays.iter().find(|a| a.name == name).map(|a| (a.start, a.stride));
    let names = ["vx", "vy", "vz", "wx", "wy", "wz", "radius", "nx", "ny", "nz"];
    let located: [Option<(usize, usize)>; 10] = names.map(find);
    let out = find("outcome");
    let piece = n.min(STRIDED_PIECE);
    let mut scratch: [Vec<f64>; 10] = located.map(|at| if at.is_some() { vec![0.0; piece] } else { Vec::new() });
    let mut outcome = vec![0u8; if out.is_some() { piece } else { 0 }];
    for first in (0..n).step_by(STRIDED_PIECE) {
        let m = (n - first).min(STRIDED_PIECE);
        for (values, at) in scratch.iter_mut().zip(&located) {
            if let Some((start, stride)) = *at {
                for (k, x) in values[..m].iter_mut().enumerate() {
                    *x = *((start + (first + k) * stride) as *const f64);
                }
            }
        }
        let p: [*mut f64; 10] =
            std::array::from_fn(|k| if located[k].is_some() { scratch[k].as_mut_ptr() } else { std::ptr::null_mut() });
        let piece = RawBatch {
            n: m,
            v: [p[0], p[1], p[2]],
            w: [p[3], p[4], p[5]],
            radius: p[6].cast_const(),
            normals: [p[7].cast_const(), p[8].cast_const(), p[9].cast_const()],
            normal: raw.normal,
            outcome: if out.is_some() { outcome.as_mut_ptr() } else { std::ptr::null_mut() },
        };
        apply_raw(law, piece, None, tally)?;
        for (values, at) in scratch.iter().zip(&located).take(6) {
            if let Some((start, stride)) = *at {
                for (k, x) in values[..m].iter().enumerate() {
                    *((start + (first + k) * stride) as *mut f64) = *x;
                }
            }
        }
        if let Some((start, stride)) = out {
            for (k, o) in outcome[..m].iter().enumerate() {
                *((start + (first + k) * stride) as *mut u8) = *o;
            }
        }
    }
    Ok(())
}

/// `depo_apply_f64` in single precision (results within 1e-4 of the incoming speed of the
/// double-precision ones away from the capture and rolling thresholds).
#[no_mangle]
pub unsafe extern "C" fn depo_apply_f32(
    law: *const DepoWallLaw,
    batch: *mut DepoImpactsF32,
    tally: *mut DepoTally,
) -> i32 {
    ffi_guard!({ apply_raw(law, RawBatch::from_f32(batch)?, None, tally) })
}

/// `depo_apply_f64` for a polydisperse batch: particle `i` is captured against its own capture
/// velocity `capture_velocity[i]` (m/s; from its diameter by `depo_capture_velocities`) instead
/// of the law's `vc`. `capture_velocity` is required when `n > 0`; a non-finite value flags
/// that particle `DEPO_INVALID`.
#[no_mangle]
pub unsafe extern "C" fn depo_apply_sized_f64(
    law: *const DepoWallLaw,
    batch: *mut DepoImpactsF64,
    capture_velocity: *const f64,
    tally: *mut DepoTally,
) -> i32 {
    ffi_guard!({ apply_raw(law, RawBatch::from_f64(batch)?, Some(capture_velocity), tally) })
}

/// `depo_apply_sized_f64` in single precision.
#[no_mangle]
pub unsafe extern "C" fn depo_apply_sized_f32(
    law: *const DepoWallLaw,
    batch: *mut DepoImpactsF32,
    capture_velocity: *const f32,
    tally: *mut DepoTally,
) -> i32 {
    ffi_guard!({ apply_raw(law, RawBatch::from_f32(batch)?, Some(capture_velocity), tally) })
}

/// Each particle's capture velocity from its diameter (paper Fig. 8):
/// `vc[i] = vc_law (diameter[i] / reference_diameter)^(-exponent)`, with `vc_law` the law's
/// capture velocity at `reference_diameter` (m). The paper's simulation rows give
/// `exponent = 1.51`, the JKR theory `5/6`. Only `vc` scales; `k` and `kappa` keep the law's
/// values. A reference diameter that is not finite and positive, a non-finite exponent, a
/// diameter that is not finite and positive, or `capture_velocity` overlapping `diameter` is
/// `DEPO_ERR_INVALID` and writes nothing.
#[no_mangle]
pub unsafe extern "C" fn depo_capture_velocities(
    law: *const DepoWallLaw,
    reference_diameter: f64,
    exponent: f64,
    n: usize,
    diameter: *const f64,
    capture_velocity: *mut f64,
) -> i32 {
    ffi_guard!({
        let law = &required(law, "law")?.law;
        let size = SizeDependence::new(reference_diameter, exponent).map_err(|e| Failure::invalid(e.to_string()))?;
        let diameter = slice(diameter, n, "diameter")?;
        if let Some(i) = diameter.iter().position(|d| !(d.is_finite() && *d > 0.0)) {
            return Err(Failure::invalid(format!("diameter[{i}] = {} is not finite and positive", diameter[i])));
        }
        let out = slice_mut(capture_velocity, n, "capture_velocity")?;
        check_disjoint(&[("diameter", span(diameter)), ("capture_velocity", span(out))])?;
        let vc_law = law.params().vc;
        for (vc, &d) in out.iter_mut().zip(diameter) {
            *vc = size.capture_velocity(vc_law, d);
        }
        Ok(())
    })
}

#[cfg(test)]
mod tests;
