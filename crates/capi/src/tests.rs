//! One subject, hence one file over 700 lines: the C ABI's entry points tested from Rust.
//!
//! Every entry point from the Rust side: NULLs, zero lengths, NaN and infinity, extreme values,
//! random batches against the `wall-model` crate, and f64 against f32.

use super::*;
use depo_wall_model::CaptureMode;
use proptest::prelude::*;
use std::ptr::{null, null_mut};

fn last_error() -> String {
    unsafe { CStr::from_ptr(depo_last_error()) }.to_string_lossy().into_owned()
}

fn li1997() -> DepoLawParams {
    DepoLawParams { k1: 12.5, k2: 12.5, kappa1: 0.065, kappa2: 0.065, p: 1.0, q: 0.5, vc: 0.074, mu: 0.3 }
}

fn new_law(params: DepoLawParams) -> *mut DepoWallLaw {
    let mut law = null_mut();
    assert_eq!(unsafe { depo_law_new(&params, &mut law) }, DEPO_OK, "{}", last_error());
    law
}

/// One particle: velocity, spin, radius, normal.
type Row = ([f64; 3], [f64; 3], f64, [f64; 3]);

/// Owned arrays for one f64 batch, with a view builder.
struct Arrays {
    v: [Vec<f64>; 3],
    w: [Vec<f64>; 3],
    radius: Vec<f64>,
    normals: [Vec<f64>; 3],
    outcome: Vec<u8>,
}

impl Arrays {
    fn new(rows: &[Row]) -> Self {
        let col = |f: &dyn Fn(usize) -> f64| (0..rows.len()).map(f).collect::<Vec<_>>();
        Self {
            v: [col(&|i| rows[i].0[0]), col(&|i| rows[i].0[1]), col(&|i| rows[i].0[2])],
            w: [col(&|i| rows[i].1[0]), col(&|i| rows[i].1[1]), col(&|i| rows[i].1[2])],
            radius: col(&|i| rows[i].2),
            normals: [col(&|i| rows[i].3[0]), col(&|i| rows[i].3[1]), col(&|i| rows[i].3[2])],
            outcome: vec![255; rows.len()],
        }
    }

    fn batch(&mut self, spin: bool, per_particle: bool) -> DepoImpactsF64 {
        let [vx, vy, vz] = &mut self.v;
        let [wx, wy, wz] = &mut self.w;
        DepoImpactsF64 {
            n: self.outcome.len(),
            vx: vx.as_mut_ptr(),
            vy: vy.as_mut_ptr(),
            vz: vz.as_mut_ptr(),
            wx: if spin { wx.as_mut_ptr() } else { null_mut() },
            wy: if spin { wy.as_mut_ptr() } else { null_mut() },
            wz: if spin { wz.as_mut_ptr() } else { null_mut() },
            radius: if spin { self.radius.as_ptr() } else { null() },
            nx: if per_particle { self.normals[0].as_ptr() } else { null() },
            ny: if per_particle { self.normals[1].as_ptr() } else { null() },
            nz: if per_particle { self.normals[2].as_ptr() } else { null() },
            normal: [0.0, 0.0, 1.0],
            outcome: self.outcome.as_mut_ptr(),
        }
    }
}

#[test]
fn law_new_rejects_bad_parameters_by_name_and_makes_nothing() {
    let mut law = null_mut();
    let bad = DepoLawParams { kappa2: -1.0, ..li1997() };
    assert_eq!(unsafe { depo_law_new(&bad, &mut law) }, DEPO_ERR_INVALID);
    assert!(law.is_null());
    assert!(last_error().contains("kappa2 = -1"), "{}", last_error());
    let nan = DepoLawParams { vc: f64::NAN, ..li1997() };
    assert_eq!(unsafe { depo_law_new(&nan, &mut law) }, DEPO_ERR_INVALID);
    assert!(last_error().contains("vc"));
    assert_eq!(unsafe { depo_law_new(null(), &mut law) }, DEPO_ERR_NULL);
    assert!(last_error().contains("params"));
    assert_eq!(unsafe { depo_law_new(&li1997(), null_mut()) }, DEPO_ERR_NULL);
}

#[test]
fn presets_by_id_and_unknown_ids() {
    let mut law = null_mut();
    assert_eq!(unsafe { depo_law_preset(c"sim-70um".as_ptr(), &mut law) }, DEPO_OK);
    let mut params = DepoLawParams { k1: 0.0, k2: 0.0, kappa1: 0.0, kappa2: 0.0, p: 0.0, q: 0.0, vc: 0.0, mu: 0.0 };
    assert_eq!(unsafe { depo_law_params(law, &mut params) }, DEPO_OK);
    assert_eq!((params.k1, params.kappa1, params.vc, params.q), (12.5, 0.065, 0.074, 0.5));
    assert_eq!(unsafe { depo_law_params(null(), &mut params) }, DEPO_ERR_NULL);
    assert_eq!(unsafe { depo_law_params(law, null_mut()) }, DEPO_ERR_NULL);
    unsafe { depo_law_free(law) };
    let mut other = null_mut();
    assert_eq!(unsafe { depo_law_preset(c"granite".as_ptr(), &mut other) }, DEPO_ERR_INVALID);
    assert!(other.is_null());
    assert!(last_error().contains("granite") && last_error().contains("li1997-sio2"));
    assert_eq!(unsafe { depo_law_preset(null(), &mut other) }, DEPO_ERR_NULL);
    unsafe { depo_law_free(null_mut()) }; // NULL is fine
}

#[test]
fn a_huge_unknown_preset_id_is_quoted_short() {
    let id = CString::new("x".repeat(1_000_000)).unwrap();
    let mut law = null_mut();
    assert_eq!(unsafe { depo_law_preset(id.as_ptr(), &mut law) }, DEPO_ERR_INVALID);
    assert!(law.is_null());
    let message = last_error();
    assert!(message.len() < 1000, "{} bytes", message.len());
    assert!(message.contains(&format!("'{}... (1000000 bytes)'", "x".repeat(64))), "{message}");
    assert!(message.contains("li1997-sio2"), "{message}");
    // Multi-byte characters are cut on a character boundary.
    let id = CString::new("é".repeat(100)).unwrap();
    assert_eq!(unsafe { depo_law_preset(id.as_ptr(), &mut law) }, DEPO_ERR_INVALID);
    assert!(last_error().contains(&format!("'{}... (200 bytes)'", "é".repeat(32))), "{}", last_error());
}

#[test]
fn misaligned_arrays_are_refused_and_change_nothing() {
    let law = new_law(li1997());
    let rows = [([0.1, 0.0, -1.0], [0.0; 3], 1e-5, [0.0, 0.0, 1.0]); 4];
    let mut a = Arrays::new(&rows);
    // Four doubles one byte into a buffer: a valid address, but not aligned to 8 bytes.
    let mut words = [0u64; 5];
    let misaligned = unsafe { words.as_mut_ptr().cast::<u8>().add(1) }.cast::<f64>();
    let mut b = a.batch(false, false);
    b.vz = misaligned;
    assert_eq!(unsafe { depo_apply_f64(law, &mut b, null_mut()) }, DEPO_ERR_INVALID);
    assert!(last_error().contains("vz is not aligned to 8 bytes"), "{}", last_error());
    assert_eq!(a.outcome, [255; 4]);
    let mut tally_words = [0u64; std::mem::size_of::<DepoTally>() / 8 + 1];
    let tally = unsafe { tally_words.as_mut_ptr().cast::<u8>().add(4) }.cast::<DepoTally>();
    assert_eq!(unsafe { depo_apply_f64(law, &mut a.batch(false, false), tally) }, DEPO_ERR_INVALID);
    assert!(last_error().contains("tally is not aligned"), "{}", last_error());
    assert_eq!(a.outcome, [255; 4]);
    let vn = [1.0; 4];
    assert_eq!(
        unsafe { depo_coefficients(law, 4, vn.as_ptr(), misaligned, null_mut(), null_mut(), null_mut()) },
        DEPO_ERR_INVALID
    );
    assert_eq!(words, [0; 5]);
    assert_eq!(tally_words, [0; std::mem::size_of::<DepoTally>() / 8 + 1]);
    unsafe { depo_law_free(law) };
}

#[test]
fn outputs_that_overlap_inputs_are_refused_and_change_nothing() {
    let law = new_law(li1997());
    // Coefficients: an output on vn, or two outputs on one array.
    let mut vn = [1.0, 2.0, 3.0];
    let (mut e, mut r) = ([9.0; 3], [9.0; 3]);
    let p = vn.as_mut_ptr();
    assert_eq!(unsafe { depo_coefficients(law, 3, p, p, null_mut(), null_mut(), null_mut()) }, DEPO_ERR_INVALID);
    assert!(last_error().contains("vn and e overlap"), "{}", last_error());
    assert_eq!(vn, [1.0, 2.0, 3.0]);
    let e_ptr = e.as_mut_ptr();
    assert_eq!(
        unsafe { depo_coefficients(law, 3, vn.as_ptr(), e_ptr, e_ptr, null_mut(), null_mut()) },
        DEPO_ERR_INVALID
    );
    assert_eq!(e, [9.0; 3]);
    assert_eq!(
        unsafe { depo_coefficients(law, 3, vn.as_ptr(), e.as_mut_ptr(), r.as_mut_ptr(), null_mut(), null_mut()) },
        DEPO_OK
    );
    // Capture velocities written over the diameters.
    let mut d = [35e-6, 70e-6];
    let dp = d.as_mut_ptr();
    assert_eq!(unsafe { depo_capture_velocities(law, 70e-6, 1.51, 2, dp, dp) }, DEPO_ERR_INVALID);
    assert_eq!(d, [35e-6, 70e-6]);
    // Deposition counts over the face ids.
    let outcome = [DEPO_CAPTURED; 2];
    let mut face = [0i64, 1];
    let f = face.as_mut_ptr();
    assert_eq!(
        unsafe { depo_accumulate_deposits(2, outcome.as_ptr(), f, null(), 2, f.cast::<u64>(), null_mut()) },
        DEPO_ERR_INVALID
    );
    assert_eq!(face, [0, 1]);
    unsafe { depo_law_free(law) };
}

#[test]
fn version_matches_the_crate() {
    let v = unsafe { CStr::from_ptr(depo_version()) }.to_str().unwrap();
    assert_eq!(v, env!("CARGO_PKG_VERSION"));
}

#[test]
fn coefficients_match_the_law_with_optional_outputs() {
    let law = new_law(li1997());
    let vn = [-1.0, 0.05, 0.074, 5.0, 0.0, 1e300];
    let (mut e, mut r, mut rho, mut cap) = ([9.0; 6], [9.0; 6], [9.0; 6], [9u8; 6]);
    let status = unsafe {
        depo_coefficients(law, 6, vn.as_ptr(), e.as_mut_ptr(), r.as_mut_ptr(), rho.as_mut_ptr(), cap.as_mut_ptr())
    };
    assert_eq!(status, DEPO_OK);
    let reference = WallLaw::preset("li1997-sio2").unwrap();
    for i in 0..6 {
        let c = reference.coefficients(vn[i]);
        assert_eq!((e[i], r[i], rho[i], cap[i]), (c.overall, c.restitution, c.adhesion, u8::from(c.captured)));
    }
    assert!((e[0] - 0.731_990_683).abs() < 1e-9);
    assert_eq!(cap, [0, 1, 1, 0, 1, 0]);
    // Outputs may be NULL; vn may be NULL only when n = 0; non-finite vn writes nothing.
    assert_eq!(
        unsafe { depo_coefficients(law, 6, vn.as_ptr(), null_mut(), null_mut(), null_mut(), null_mut()) },
        DEPO_OK
    );
    assert_eq!(unsafe { depo_coefficients(law, 0, null(), null_mut(), null_mut(), null_mut(), null_mut()) }, DEPO_OK);
    assert_eq!(
        unsafe { depo_coefficients(law, 1, null(), e.as_mut_ptr(), null_mut(), null_mut(), null_mut()) },
        DEPO_ERR_NULL
    );
    let bad = [1.0, f64::NAN];
    let mut out = [7.0; 2];
    assert_eq!(
        unsafe { depo_coefficients(law, 2, bad.as_ptr(), out.as_mut_ptr(), null_mut(), null_mut(), null_mut()) },
        DEPO_ERR_INVALID
    );
    assert_eq!(out, [7.0; 2]);
    assert!(last_error().contains("vn[1]"));
    assert_eq!(
        unsafe { depo_coefficients(null(), 0, null(), null_mut(), null_mut(), null_mut(), null_mut()) },
        DEPO_ERR_NULL
    );
    unsafe { depo_law_free(law) };
}

#[test]
fn apply_checks_pointers_normal_and_overlap_and_changes_nothing_on_failure() {
    let law = new_law(li1997());
    let rows = [([0.1, 0.0, -1.0], [0.0; 3], 1e-5, [0.0, 0.0, 1.0]); 4];
    let mut a = Arrays::new(&rows);
    let mut tally = DepoTally::default();

    assert_eq!(unsafe { depo_apply_f64(null(), &mut a.batch(false, false), &mut tally) }, DEPO_ERR_NULL);
    assert_eq!(unsafe { depo_apply_f64(law, null_mut(), &mut tally) }, DEPO_ERR_NULL);
    let mut b = a.batch(false, false);
    b.vy = null_mut();
    assert_eq!(unsafe { depo_apply_f64(law, &mut b, &mut tally) }, DEPO_ERR_NULL);
    assert!(last_error().contains("vy"));
    let mut b = a.batch(true, false);
    b.wz = null_mut();
    assert_eq!(unsafe { depo_apply_f64(law, &mut b, &mut tally) }, DEPO_ERR_NULL);
    let mut b = a.batch(true, false);
    b.radius = null();
    assert_eq!(unsafe { depo_apply_f64(law, &mut b, &mut tally) }, DEPO_ERR_NULL);
    assert!(last_error().contains("radius"));
    let mut b = a.batch(false, true);
    b.ny = null();
    assert_eq!(unsafe { depo_apply_f64(law, &mut b, &mut tally) }, DEPO_ERR_NULL);
    let mut b = a.batch(false, false);
    b.normal = [0.0, 0.0, 1.01];
    assert_eq!(unsafe { depo_apply_f64(law, &mut b, &mut tally) }, DEPO_ERR_INVALID);
    assert!(last_error().contains("normal"));
    let mut b = a.batch(false, false);
    b.normal = [0.0, f64::NAN, 1.0];
    assert_eq!(unsafe { depo_apply_f64(law, &mut b, &mut tally) }, DEPO_ERR_INVALID);
    let mut b = a.batch(false, false);
    b.vy = b.vx; // overlapping arrays
    assert_eq!(unsafe { depo_apply_f64(law, &mut b, &mut tally) }, DEPO_ERR_INVALID);
    assert!(last_error().contains("overlap"), "{}", last_error());
    // Nothing was touched by any failed call.
    assert_eq!(a.outcome, [255; 4]);
    assert_eq!(a.v[2], [-1.0; 4]);
    assert_eq!(tally, DepoTally::default());

    // Zero length: every pointer may be NULL.
    let mut empty = DepoImpactsF64 {
        n: 0,
        vx: null_mut(),
        vy: null_mut(),
        vz: null_mut(),
        wx: null_mut(),
        wy: null_mut(),
        wz: null_mut(),
        radius: null(),
        nx: null(),
        ny: null(),
        nz: null(),
        normal: [0.0, 0.0, 0.0],
        outcome: null_mut(),
    };
    assert_eq!(unsafe { depo_apply_f64(law, &mut empty, &mut tally) }, DEPO_OK, "an empty batch is a no-op");
    assert_eq!(tally, DepoTally::default());
    assert_eq!(unsafe { depo_apply_f64(law, &mut a.batch(false, false), null_mut()) }, DEPO_OK);
    assert_eq!(a.outcome, [DEPO_REBOUND; 4]);
    unsafe { depo_law_free(law) };
}

#[test]
fn bad_particles_are_flagged_and_the_tally_adds_up() {
    let law = new_law(li1997());
    let up = [0.0, 0.0, 1.0];
    let rows = [
        ([0.1, 0.0, -1.0], [0.0, 50.0, 0.0], 1e-5, up),
        ([f64::NAN, 0.0, -1.0], [0.0; 3], 1e-5, up),
        ([0.1, 0.0, -1.0], [0.0; 3], 0.0, up),
        ([0.1, 0.0, -1.0], [0.0; 3], 1e-5, [0.0, 0.0, 1.1]),
        ([0.1, 0.0, 0.3], [0.0; 3], 1e-5, up),
        ([0.1, 0.0, -0.01], [0.0; 3], 1e-5, up),
        ([1e300, -1e300, -1e300], [1e9, 1e9, 1e9], 1e-9, up),
    ];
    let mut a = Arrays::new(&rows);
    let mut tally = DepoTally { rebound: 100, ..DepoTally::default() };
    assert_eq!(unsafe { depo_apply_f64(law, &mut a.batch(true, true), &mut tally) }, DEPO_OK);
    assert_eq!(
        a.outcome,
        [DEPO_REBOUND, DEPO_INVALID, DEPO_INVALID, DEPO_INVALID, DEPO_SKIPPED, DEPO_CAPTURED, DEPO_REBOUND]
    );
    assert_eq!((tally.rebound, tally.captured, tally.skipped, tally.invalid), (102, 1, 1, 3));
    assert!(a.v[0][1].is_nan() && a.radius[2] == 0.0 && a.v[2][3] == -1.0);
    assert_eq!([a.v[0][5], a.v[1][5], a.v[2][5]], [0.0; 3]);
    for k in 0..3 {
        assert!(a.v[k].iter().chain(&a.w[k]).enumerate().all(|(i, x)| i == 1 || x.is_finite()));
    }
    assert!(tally.energy_material > 0.0 && tally.energy_adhesion > 0.0 && tally.energy_friction > 0.0);
    assert!(tally.energy_deposition > 0.0, "the captured particle carried tangential energy");
    unsafe { depo_law_free(law) };
}

#[test]
fn tiny_radii_with_spin_are_invalid_not_infinite_spin() {
    let law = new_law(li1997());
    let row = |radius: f64| ([0.5, 0.0, -1.0], [0.0, 10.0, 0.0], radius, [0.0, 0.0, 1.0]);
    let rows = [row(1e-310), row(f64::MIN_POSITIVE), row(1e-200), row(1e-150), row(1e-9)];
    let mut a = Arrays::new(&rows);
    assert_eq!(unsafe { depo_apply_f64(law, &mut a.batch(true, false), null_mut()) }, DEPO_OK);
    assert_eq!(a.outcome, [DEPO_INVALID, DEPO_INVALID, DEPO_INVALID, DEPO_REBOUND, DEPO_REBOUND]);
    for k in 0..3 {
        assert!(a.w[k].iter().chain(&a.v[k]).all(|x| x.is_finite()), "{:?} {:?}", a.w, a.v);
    }
    assert_eq!(a.w[1][..3], [10.0; 3], "invalid particles are untouched");
    // Single precision: the floor is 1e-18 m.
    let (mut vx, mut vy, mut vz) = ([0.5f32; 3], [0.0f32; 3], [-1.0f32; 3]);
    let (mut wx, mut wy, mut wz) = ([0.0f32; 3], [10.0f32; 3], [0.0f32; 3]);
    let radius = [1e-40f32, 1e-20, 1e-9];
    let mut out = [9u8; 3];
    let mut b = DepoImpactsF32 {
        n: 3,
        vx: vx.as_mut_ptr(),
        vy: vy.as_mut_ptr(),
        vz: vz.as_mut_ptr(),
        wx: wx.as_mut_ptr(),
        wy: wy.as_mut_ptr(),
        wz: wz.as_mut_ptr(),
        radius: radius.as_ptr(),
        nx: null(),
        ny: null(),
        nz: null(),
        normal: [0.0, 0.0, 1.0],
        outcome: out.as_mut_ptr(),
    };
    assert_eq!(unsafe { depo_apply_f32(law, &mut b, null_mut()) }, DEPO_OK);
    assert_eq!(out, [DEPO_INVALID, DEPO_INVALID, DEPO_REBOUND]);
    assert!(wx.iter().chain(&wy).chain(&wz).all(|x| x.is_finite()));
    unsafe { depo_law_free(law) };
}

#[test]
fn f32_and_f64_entry_points_agree() {
    let law = new_law(li1997());
    let n = 1000;
    let rows: Vec<_> = (0..n)
        .map(|i| {
            let t = i as f64 / n as f64;
            (
                [0.3 * (7.0 * t).sin(), 0.2 * (3.0 * t).cos(), -0.2 - 4.0 * t],
                [1e3 * t, -2e3, 5e2],
                2e-5,
                [0.0, 0.0, 1.0],
            )
        })
        .collect();
    let mut a = Arrays::new(&rows);
    assert_eq!(unsafe { depo_apply_f64(law, &mut a.batch(true, false), null_mut()) }, DEPO_OK);
    let f = |c: &[f64]| c.iter().map(|&x| x as f32).collect::<Vec<f32>>();
    let mut v32 = [f(&Arrays::new(&rows).v[0]), f(&Arrays::new(&rows).v[1]), f(&Arrays::new(&rows).v[2])];
    let mut w32 = [f(&Arrays::new(&rows).w[0]), f(&Arrays::new(&rows).w[1]), f(&Arrays::new(&rows).w[2])];
    let r32 = f(&a.radius);
    let mut out32 = vec![0u8; n];
    let [vx, vy, vz] = &mut v32;
    let [wx, wy, wz] = &mut w32;
    let mut b = DepoImpactsF32 {
        n,
        vx: vx.as_mut_ptr(),
        vy: vy.as_mut_ptr(),
        vz: vz.as_mut_ptr(),
        wx: wx.as_mut_ptr(),
        wy: wy.as_mut_ptr(),
        wz: wz.as_mut_ptr(),
        radius: r32.as_ptr(),
        nx: null(),
        ny: null(),
        nz: null(),
        normal: [0.0, 0.0, 1.0],
        outcome: out32.as_mut_ptr(),
    };
    assert_eq!(unsafe { depo_apply_f32(law, &mut b, null_mut()) }, DEPO_OK);
    let vc = 0.074;
    let mut compared = 0;
    for i in 0..n {
        let speed = -rows[i].0[2];
        if (speed - vc).abs() < 0.01 {
            continue; // at the capture threshold a last-bit difference may flip the outcome
        }
        assert_eq!(out32[i], a.outcome[i]);
        let scale = (rows[i].0.iter().map(|x| x * x).sum::<f64>()).sqrt();
        for k in 0..3 {
            assert!((f64::from(v32[k][i]) - a.v[k][i]).abs() <= 1e-4 * scale, "particle {i}");
            assert!((f64::from(w32[k][i]) - a.w[k][i]).abs() * 2e-5 <= 1e-4 * scale, "particle {i} spin");
        }
        compared += 1;
    }
    assert!(compared > 900);
    unsafe { depo_law_free(law) };
}

/// Held by the tests that change the process-wide thread setting.
static THREAD_SETTING: std::sync::Mutex<()> = std::sync::Mutex::new(());

#[test]
fn thread_cap_gives_the_same_results() {
    let _setting = THREAD_SETTING.lock().unwrap_or_else(|e| e.into_inner());
    let law = new_law(DepoLawParams { p: 1.3, q: 0.7, ..li1997() });
    let rows: Vec<_> = (0..150_000)
        .map(|i| {
            (
                [((i * 37) % 101) as f64 / 101.0, 0.1, -0.01 - ((i * 13) % 97) as f64 / 20.0],
                [0.0; 3],
                1e-5,
                [0.0, 0.0, 1.0],
            )
        })
        .collect();
    let run = |threads: usize| {
        assert_eq!(depo_set_num_threads(threads), DEPO_OK);
        let mut a = Arrays::new(&rows);
        let mut tally = DepoTally::default();
        assert_eq!(unsafe { depo_apply_f64(law, &mut a.batch(false, false), &mut tally) }, DEPO_OK);
        (a.v, a.outcome, tally)
    };
    let one = run(1);
    let two = run(2);
    let default = run(0);
    assert_eq!(one.2, two.2);
    assert_eq!(one.2, default.2);
    assert!(one.0.iter().zip(&two.0).all(|(a, b)| a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits())));
    assert_eq!(one.1, two.1);
    unsafe { depo_law_free(law) };
}

#[test]
fn small_batches_run_on_the_calling_thread_whatever_the_cap_and_1_never_leaves_it() {
    let _setting = THREAD_SETTING.lock().unwrap_or_else(|e| e.into_inner());
    let here = std::thread::current().id();
    let whereabouts = |n: usize| run_batch(n, |parallel| (std::thread::current().id(), parallel));
    for cap in [0, 1, 2, 3] {
        assert_eq!(depo_set_num_threads(cap), DEPO_OK);
        for n in [1, 10, 2000, DEPO_PARALLEL_MIN - 1] {
            assert_eq!(whereabouts(n), (here, false), "cap {cap}, {n} particles");
        }
    }
    // 1: large batches stay on the calling thread too, in pieces run one after the other.
    assert_eq!(depo_set_num_threads(1), DEPO_OK);
    assert_eq!(whereabouts(DEPO_PARALLEL_MIN), (here, false));
    assert_eq!(whereabouts(10 * DEPO_PARALLEL_MIN), (here, false));
    // A cap of 2 or more: large batches go to depo's own pool.
    assert_eq!(depo_set_num_threads(2), DEPO_OK);
    // (Either of its threads may take the job: the name says whose pool it is.)
    let (name, parallel) =
        run_batch(DEPO_PARALLEL_MIN, |parallel| (std::thread::current().name().map(String::from), parallel));
    assert!(parallel && name.as_deref().is_some_and(|n| n.starts_with("depo-")), "{name:?} {parallel}");
    // No cap: rayon's global pool, parallel.
    assert_eq!(depo_set_num_threads(0), DEPO_OK);
    assert!(run_batch(DEPO_PARALLEL_MIN, |parallel| parallel));
    // Absurd caps are refused and change nothing.
    assert_eq!(depo_set_num_threads(1), DEPO_OK);
    for absurd in [DEPO_MAX_THREADS + 1, usize::MAX] {
        assert_eq!(depo_set_num_threads(absurd), DEPO_ERR_INVALID);
        assert!(last_error().contains("DEPO_MAX_THREADS"), "{}", last_error());
        assert_eq!(whereabouts(10 * DEPO_PARALLEL_MIN), (here, false), "the setting 1 holds");
    }
    assert_eq!(depo_set_num_threads(0), DEPO_OK);
}

#[test]
fn deposition_map_counts_captured_particles_per_face() {
    let outcome = [DEPO_CAPTURED, DEPO_REBOUND, DEPO_CAPTURED, DEPO_CAPTURED, DEPO_INVALID];
    let face = [2i64, 99, 0, 2, -5]; // ids of non-captured particles are not read
    let mass = [1e-12, 5.0, 2e-12, 3e-12, 7.0];
    let (mut count, mut deposited) = ([0u64; 3], [0.0f64; 3]);
    let status = unsafe {
        depo_accumulate_deposits(
            5,
            outcome.as_ptr(),
            face.as_ptr(),
            mass.as_ptr(),
            3,
            count.as_mut_ptr(),
            deposited.as_mut_ptr(),
        )
    };
    assert_eq!(status, DEPO_OK);
    assert_eq!(count, [1, 0, 2]);
    assert_eq!(deposited, [2e-12, 0.0, 4e-12]);
    // Without masses only counts; an id out of range changes nothing.
    let status = unsafe {
        depo_accumulate_deposits(5, outcome.as_ptr(), face.as_ptr(), null(), 3, count.as_mut_ptr(), null_mut())
    };
    assert_eq!((status, count), (DEPO_OK, [2, 0, 4]));
    let bad_face = [2i64, 0, 3, 0, 0];
    let status = unsafe {
        depo_accumulate_deposits(5, outcome.as_ptr(), bad_face.as_ptr(), null(), 3, count.as_mut_ptr(), null_mut())
    };
    assert_eq!((status, count), (DEPO_ERR_INVALID, [2, 0, 4]));
    assert!(last_error().contains("face[2] = 3"));
    assert_eq!(unsafe { depo_accumulate_deposits(0, null(), null(), null(), 0, null_mut(), null_mut()) }, DEPO_OK);
}

#[test]
fn capture_velocities_from_diameters() {
    let mut law = null_mut();
    assert_eq!(unsafe { depo_law_preset(c"sim-70um".as_ptr(), &mut law) }, DEPO_OK);
    let d = [35e-6, 70e-6, 140e-6];
    let mut vc = [0.0; 3];
    assert_eq!(unsafe { depo_capture_velocities(law, 70e-6, 1.51, 3, d.as_ptr(), vc.as_mut_ptr()) }, DEPO_OK);
    // 0.074 * 2^1.51 = 0.21076, 0.074, 0.074 * 2^-1.51 = 0.025982 (Table 1: 0.212, 0.074, 0.026).
    assert!((vc[0] - 0.074 * 2f64.powf(1.51)).abs() < 1e-15 && (vc[0] - 0.2108).abs() < 1e-4);
    assert_eq!(vc[1], 0.074);
    assert!((vc[2] - 0.025_98).abs() < 1e-5);
    let bad = [35e-6, -1.0, 1e-5];
    let mut out = [9.0; 3];
    assert_eq!(
        unsafe { depo_capture_velocities(law, 70e-6, 1.51, 3, bad.as_ptr(), out.as_mut_ptr()) },
        DEPO_ERR_INVALID
    );
    assert_eq!(out, [9.0; 3]);
    assert!(last_error().contains("diameter[1]"));
    assert_eq!(unsafe { depo_capture_velocities(law, 0.0, 1.51, 3, d.as_ptr(), out.as_mut_ptr()) }, DEPO_ERR_INVALID);
    assert!(last_error().contains("reference_diameter"));
    assert_eq!(
        unsafe { depo_capture_velocities(law, 70e-6, f64::NAN, 3, d.as_ptr(), out.as_mut_ptr()) },
        DEPO_ERR_INVALID
    );
    assert_eq!(unsafe { depo_capture_velocities(law, 70e-6, 1.51, 3, d.as_ptr(), null_mut()) }, DEPO_ERR_NULL);
    assert_eq!(unsafe { depo_capture_velocities(null(), 70e-6, 1.51, 3, d.as_ptr(), out.as_mut_ptr()) }, DEPO_ERR_NULL);
    assert_eq!(unsafe { depo_capture_velocities(law, 70e-6, 1.51, 0, null(), null_mut()) }, DEPO_OK);
    unsafe { depo_law_free(law) };
}

#[test]
fn sized_apply_uses_each_particle_s_capture_velocity() {
    let law = new_law(li1997());
    // All at 0.1 m/s normal speed: captured where the particle's vc is above 0.1 m/s.
    let rows = [([0.05, 0.0, -0.1], [0.0; 3], 1e-5, [0.0, 0.0, 1.0]); 4];
    let vc = [0.2, 0.05, f64::NAN, -1.0];
    let mut a = Arrays::new(&rows);
    let mut tally = DepoTally::default();
    assert_eq!(unsafe { depo_apply_sized_f64(law, &mut a.batch(false, false), vc.as_ptr(), &mut tally) }, DEPO_OK);
    assert_eq!(a.outcome, [DEPO_CAPTURED, DEPO_REBOUND, DEPO_INVALID, DEPO_REBOUND]);
    // Each rebound equals the law with that particle's vc.
    for i in [1, 3] {
        let own = WallLaw::new(LawParams {
            vc: vc[i],
            ..WallLaw::preset("li1997-sio2").unwrap().params().with_friction(0.3)
        })
        .unwrap();
        let res = own.impact(glam::DVec3::from_array(rows[i].0), None, glam::DVec3::Z);
        assert_eq!([a.v[0][i], a.v[1][i], a.v[2][i]], res.velocity);
    }
    let mut b = Arrays::new(&rows);
    assert_eq!(unsafe { depo_apply_sized_f64(law, &mut b.batch(false, false), null(), &mut tally) }, DEPO_ERR_NULL);
    assert!(last_error().contains("capture_velocity"));
    assert_eq!(
        unsafe { depo_apply_sized_f64(null(), &mut b.batch(false, false), vc.as_ptr(), &mut tally) },
        DEPO_ERR_NULL
    );
    assert_eq!(unsafe { depo_apply_sized_f64(law, null_mut(), vc.as_ptr(), &mut tally) }, DEPO_ERR_NULL);
    assert_eq!(unsafe { depo_apply_f32(law, null_mut(), &mut tally) }, DEPO_ERR_NULL);
    let mut batch = b.batch(false, false);
    let overlapping = batch.vx.cast_const();
    assert_eq!(unsafe { depo_apply_sized_f64(law, &mut batch, overlapping, null_mut()) }, DEPO_ERR_INVALID);
    assert_eq!(b.outcome, [255; 4]);
    // Single precision too.
    let (mut vx, mut vy, mut vz) = ([0.05f32; 2], [0.0f32; 2], [-0.1f32; 2]);
    let vc32 = [0.2f32, 0.05];
    let mut out = [9u8; 2];
    let mut b32 = DepoImpactsF32 {
        n: 2,
        vx: vx.as_mut_ptr(),
        vy: vy.as_mut_ptr(),
        vz: vz.as_mut_ptr(),
        wx: null_mut(),
        wy: null_mut(),
        wz: null_mut(),
        radius: null(),
        nx: null(),
        ny: null(),
        nz: null(),
        normal: [0.0, 0.0, 1.0],
        outcome: out.as_mut_ptr(),
    };
    assert_eq!(unsafe { depo_apply_sized_f32(law, &mut b32, vc32.as_ptr(), null_mut()) }, DEPO_OK);
    assert_eq!(out, [DEPO_CAPTURED, DEPO_REBOUND]);
    unsafe { depo_law_free(law) };
}

/// A host whose thread-exit destructor (a pthread key's, a C++ or Rust thread-local's) calls
/// depo after depo's own thread-local storage is gone: the call fails with its status, and
/// neither it nor `depo_last_error` may abort the process. Run in a child process, since the
/// failure was an abort.
#[test]
fn failing_calls_during_thread_teardown_return_their_status() {
    use std::sync::atomic::{AtomicI32, AtomicUsize, Ordering};
    const CHILD: &str = "DEPO_TEST_TEARDOWN_CHILD";
    static STATUS: AtomicI32 = AtomicI32::new(-1);
    static MESSAGE_LEN: AtomicUsize = AtomicUsize::new(usize::MAX);

    if std::env::var_os(CHILD).is_some() {
        struct CallsDepoOnExit;
        impl Drop for CallsDepoOnExit {
            fn drop(&mut self) {
                let mut law = null_mut();
                let bad = DepoLawParams { kappa2: -1.0, ..li1997() };
                STATUS.store(unsafe { depo_law_new(&bad, &mut law) }, Ordering::SeqCst);
                MESSAGE_LEN.store(unsafe { CStr::from_ptr(depo_last_error()) }.to_bytes().len(), Ordering::SeqCst);
            }
        }
        thread_local! {
            static ON_EXIT: CallsDepoOnExit = const { CallsDepoOnExit };
        }
        std::thread::spawn(|| {
            ON_EXIT.with(|_| ()); // set up first, so torn down after depo's storage
            let mut law = null_mut();
            let bad = DepoLawParams { vc: f64::NAN, ..li1997() };
            assert_eq!(unsafe { depo_law_new(&bad, &mut law) }, DEPO_ERR_INVALID);
        })
        .join()
        .unwrap();
        assert_eq!(STATUS.load(Ordering::SeqCst), DEPO_ERR_INVALID);
        assert_ne!(MESSAGE_LEN.load(Ordering::SeqCst), usize::MAX, "depo_last_error returned");
        println!("teardown calls returned");
        return;
    }
    let out = std::process::Command::new(std::env::current_exe().unwrap())
        .args(["--exact", "tests::failing_calls_during_thread_teardown_return_their_status", "--nocapture"])
        .env(CHILD, "1")
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success() && stdout.contains("teardown calls returned"),
        "{:?}\n{stdout}\n{}",
        out.status,
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn a_panic_becomes_a_status_with_its_message() {
    let status = ffi_guard!({
        if true {
            panic!("deliberate test panic");
        }
        Ok(())
    });
    assert_eq!(status, DEPO_ERR_PANIC);
    assert!(last_error().contains("deliberate test panic"));
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    /// Random batches through the C entry point equal the `wall-model` crate's results bit for bit.
    #[test]
    fn random_batches_match_the_wall_model_crate(
        rows in prop::collection::vec(
            (prop::array::uniform3(-3.0f64..3.0), prop::array::uniform3(-1e4f64..1e4), 1e-6f64..1e-3),
            0..200,
        ),
        vc in -0.5f64..1.0,
        mu in 0.0f64..1.0,
        q in prop_oneof![Just(1.0), Just(0.5), 0.3f64..3.0],
    ) {
        let params = DepoLawParams { vc, mu, q, ..li1997() };
        let law = new_law(params);
        let full: Vec<_> = rows.iter().map(|(v, w, r)| (*v, *w, *r, [0.0, 0.0, 1.0])).collect();
        let mut a = Arrays::new(&full);
        prop_assert_eq!(unsafe { depo_apply_f64(law, &mut a.batch(true, false), null_mut()) }, DEPO_OK);
        let reference = WallLaw::new(LawParams { k1: 12.5, k2: 12.5, kappa1: 0.065, kappa2: 0.065, p: 1.0, q, vc, mu })
            .unwrap()
            .with_capture_mode(CaptureMode::Deposit);
        let mut b = Arrays::new(&full);
        let [vx, vy, vz] = &mut b.v;
        let [wx, wy, wz] = &mut b.w;
        let outcome: &mut [Outcome] = unsafe { std::slice::from_raw_parts_mut(b.outcome.as_mut_ptr().cast(), b.outcome.len()) };
        let batch = Impacts::new([vx, vy, vz], Normals::Uniform([0.0, 0.0, 1.0]), outcome)
            .unwrap()
            .with_spin([wx, wy, wz], &b.radius)
            .unwrap();
        reference.apply(batch, None);
        prop_assert_eq!(&a.outcome, &b.outcome);
        for k in 0..3 {
            prop_assert!(a.v[k].iter().zip(&b.v[k]).all(|(x, y)| x.to_bits() == y.to_bits()));
            prop_assert!(a.w[k].iter().zip(&b.w[k]).all(|(x, y)| x.to_bits() == y.to_bits()));
        }
        unsafe { depo_law_free(law) };
    }
}

/// The keep-on-wall capture mode through the C ABI: a copy of the law that leaves a captured
/// particle's tangential velocity (as the Rust law does, bit for bit), read back; an unknown
/// mode is refused and makes nothing.
#[test]
fn keep_on_wall_capture_mode_through_the_abi() {
    let law = new_law(li1997());
    let mut kept = null_mut();
    assert_eq!(unsafe { depo_law_with_capture_mode(law, DEPO_CAPTURE_KEEP_ON_WALL, &mut kept) }, DEPO_OK);
    let mut mode = -1;
    assert_eq!(unsafe { depo_law_capture_mode(kept, &mut mode) }, DEPO_OK);
    assert_eq!(mode, DEPO_CAPTURE_KEEP_ON_WALL);
    assert_eq!(unsafe { depo_law_capture_mode(law, &mut mode) }, DEPO_OK);
    assert_eq!(mode, DEPO_CAPTURE_DEPOSIT);
    // A slow oblique impact, captured (|vn| = 0.03 m/s < vc = 0.074 m/s).
    let rows: Vec<Row> = vec![([0.2, -0.1, -0.03], [0.0; 3], 1e-5, [0.0, 0.0, 1.0])];
    let (mut a, mut b) = (Arrays::new(&rows), Arrays::new(&rows));
    assert_eq!(unsafe { depo_apply_f64(kept, &mut a.batch(false, false), null_mut()) }, DEPO_OK);
    assert_eq!(unsafe { depo_apply_f64(law, &mut b.batch(false, false), null_mut()) }, DEPO_OK);
    assert_eq!((a.outcome[0], b.outcome[0]), (DEPO_CAPTURED, DEPO_CAPTURED));
    let reference = WallLaw::new(LawParams::from(li1997())).unwrap().with_capture_mode(CaptureMode::KeepOnWall);
    let r = reference.impact(glam::DVec3::new(0.2, -0.1, -0.03), None, glam::DVec3::Z);
    assert!(r.coefficients.captured);
    let kept_v = [a.v[0][0], a.v[1][0], a.v[2][0]];
    assert_eq!(kept_v.map(f64::to_bits), r.velocity.map(f64::to_bits));
    assert!(kept_v[2] == 0.0 && kept_v[0] != 0.0, "{kept_v:?}");
    assert_eq!([b.v[0][0], b.v[1][0], b.v[2][0]], [0.0; 3], "the default deposits");
    let mut untouched = law;
    assert_eq!(unsafe { depo_law_with_capture_mode(law, 7, &mut untouched) }, DEPO_ERR_INVALID);
    assert_eq!(untouched, law);
    assert!(last_error().contains("capture mode 7"), "{}", last_error());
    unsafe {
        depo_law_free(kept);
        depo_law_free(law);
    }
}

/// A particle as an array-of-structures host keeps it.
#[repr(C)]
#[derive(Clone, Copy, Default)]
struct Parcel {
    v: [f64; 3],
    w: [f64; 3],
    radius: f64,
    n: [f64; 3],
    outcome: u8,
}

/// Strided arrays (a host's array of structures) give what contiguous arrays of the same values
/// give, bit for bit, tally too, across several pieces; bad strides, misaligned bases and
/// outputs that share memory are refused and change nothing.
#[test]
fn strided_arrays_of_structures_match_contiguous_arrays() {
    let law = new_law(li1997());
    let n = 40_000; // three pieces
    let mut parcels: Vec<Parcel> = (0..n)
        .map(|i| {
            let t = i as f64;
            let n = [0.6 * (t * 0.37).sin(), 0.0, 0.8];
            let len = (n[0] * n[0] + n[2] * n[2]).sqrt();
            Parcel {
                v: [(t * 0.013).sin(), (t * 0.029).cos(), -0.02 - 3.0 * ((t * 0.007).sin()).abs()],
                w: [10.0 * (t * 0.3).cos(), 0.0, 5.0],
                radius: 1e-5,
                n: [n[0] / len, 0.0, n[2] / len],
                outcome: 9,
            }
        })
        .collect();
    let rows: Vec<Row> = parcels.iter().map(|p| (p.v, p.w, p.radius, p.n)).collect();
    let mut soa = Arrays::new(&rows);
    let mut expected = DepoTally::default();
    assert_eq!(unsafe { depo_apply_f64(law, &mut soa.batch(true, true), &mut expected) }, DEPO_OK);

    let size = std::mem::size_of::<Parcel>();
    let base = parcels.as_mut_ptr();
    let field = |offset: usize| unsafe { base.cast::<u8>().add(offset).cast::<f64>() };
    let strided = |vx: usize| DepoImpactsF64 {
        n,
        vx: field(vx),
        vy: field(8),
        vz: field(16),
        wx: field(24),
        wy: field(32),
        wz: field(40),
        radius: field(48),
        nx: field(56),
        ny: field(64),
        nz: field(72),
        normal: [0.0; 3],
        outcome: unsafe { base.cast::<u8>().add(80) },
    };
    let strides = DepoStrides { v: [size; 3], w: [size; 3], radius: size, normals: [size; 3], outcome: size };
    // Refused, and nothing changed: a stride below the value's size, a misaligned base, and vx
    // on top of vy.
    let bad = DepoStrides { v: [4, size, size], ..strides };
    assert_eq!(unsafe { depo_apply_strided_f64(law, &mut strided(0), &bad, null_mut()) }, DEPO_ERR_INVALID);
    assert!(last_error().contains("vx"), "{}", last_error());
    let shifted = unsafe { base.cast::<u8>().add(1).cast::<f64>() };
    let mut misaligned = DepoImpactsF64 { vx: shifted, ..strided(0) };
    assert_eq!(unsafe { depo_apply_strided_f64(law, &mut misaligned, &strides, null_mut()) }, DEPO_ERR_INVALID);
    assert_eq!(unsafe { depo_apply_strided_f64(law, &mut strided(8), &strides, null_mut()) }, DEPO_ERR_INVALID);
    assert!(last_error().contains("share memory"), "{}", last_error());
    assert!(parcels.iter().all(|p| p.outcome == 9), "a refused call changed nothing");

    let mut tally = DepoTally::default();
    assert_eq!(
        unsafe { depo_apply_strided_f64(law, &mut strided(0), &strides, &mut tally) },
        DEPO_OK,
        "{}",
        last_error()
    );
    for (i, p) in parcels.iter().enumerate() {
        assert_eq!(p.outcome, soa.outcome[i], "{i}");
        for k in 0..3 {
            assert_eq!(p.v[k].to_bits(), soa.v[k][i].to_bits(), "{i}");
            assert_eq!(p.w[k].to_bits(), soa.w[k][i].to_bits(), "{i}");
        }
    }
    assert_eq!(
        (tally.rebound, tally.captured, tally.skipped, tally.invalid),
        (expected.rebound, expected.captured, expected.skipped, expected.invalid)
    );
    assert!(tally.rebound > 0 && tally.captured > 0);
    assert!((tally.energy_material - expected.energy_material).abs() <= 1e-9 * expected.energy_material);
    unsafe { depo_law_free(law) };
}

const AIR: DepoAir = DepoAir { temperature: 293.15, pressure: 101_325.0, density: 1.204, viscosity: 1.81e-5 };

/// One particle's wall-function chance, or the call's status and message.
fn chance(
    correlation: i32,
    orientation: i32,
    dt: f64,
    u: f64,
    layer: f64,
    d: f64,
    rho: f64,
) -> Result<f64, (i32, String)> {
    let mut p = f64::NAN;
    let status = unsafe {
        depo_wall_function_probability(correlation, orientation, &AIR, 9.80665, dt, 1, &u, &layer, &d, &rho, &mut p)
    };
    if status == DEPO_OK {
        Ok(p)
    } else {
        assert!(p.is_nan(), "a failing call wrote {p}");
        Err((status, last_error()))
    }
}

/// A 5 um unit-density sphere at u* = 0.3 m/s in air at 20 C, worked out by hand from Hinds
/// (1999): mean free path 0.066434 um (0.0673 um at 23 C carried by Sutherland's form), slip
/// 1 + (lambda/d)(2.34 + 1.05 exp(-0.39 d/lambda)) = 1.031091, tau = rho d^2 Cc / (18 mu) =
/// 7.91199e-5 s, tau+ = 0.473670, D = kT Cc / (3 pi mu d) = 4.89272e-12 m^2/s, Sc = 3.07257e6;
/// Wood's V+ = 0.057 Sc^(-2/3) + 4.5e-4 tau+^2 = 1.036606e-4, v_d = 3.109819e-5 m/s; over a
/// 1.5 mm layer and 1 ms, 1 - exp(-2.073213e-5) = 2.073191e-5.
#[test]
fn the_wall_function_chance_is_wood_s_rate_over_the_layer() {
    let p = chance(DEPO_CORRELATION_WOOD, DEPO_SURFACE_WALL, 1e-3, 0.3, 1.5e-3, 5e-6, 1000.0).unwrap();
    assert!((p / 2.073_191e-5 - 1.0).abs() < 1e-6, "{p}");
    let mut v = 0.0;
    let status = unsafe {
        depo_deposition_velocity(DEPO_CORRELATION_WOOD, DEPO_SURFACE_WALL, &AIR, 0.0, 1, &0.3, &5e-6, &1000.0, &mut v)
    };
    assert_eq!(status, DEPO_OK);
    assert!((v / 3.109_819e-5 - 1.0).abs() < 1e-6, "{v}");
    // Lai & Nazaroff orders the surfaces; Wood does not tell them apart.
    let ln = |o| chance(DEPO_CORRELATION_LAI_NAZAROFF, o, 0.1, 0.01, 0.045, 3e-6, 1000.0).unwrap();
    assert!(ln(DEPO_SURFACE_FLOOR) > ln(DEPO_SURFACE_WALL) && ln(DEPO_SURFACE_WALL) > ln(DEPO_SURFACE_CEILING));
    let wood = |o| chance(DEPO_CORRELATION_WOOD, o, 0.1, 0.01, 0.045, 3e-6, 1000.0).unwrap();
    assert_eq!(wood(DEPO_SURFACE_FLOOR), wood(DEPO_SURFACE_CEILING));
    // Zero particles: nothing read, nothing written.
    let status =
        unsafe { depo_wall_function_probability(0, 0, &AIR, 9.8, 0.1, 0, null(), null(), null(), null(), null_mut()) };
    assert_eq!(status, DEPO_OK);
}

/// A wall-function call's inputs: correlation, orientation, dt, u*, layer, diameter, density.
type WallFunctionCall = (i32, i32, f64, f64, f64, f64, f64);

#[test]
fn wall_function_inputs_out_of_range_are_refused_by_name() {
    let ok = (DEPO_CORRELATION_WOOD, DEPO_SURFACE_FLOOR, 1e-3, 0.3, 1e-3, 5e-6, 1000.0);
    let cases: [(WallFunctionCall, &str); 10] = [
        ((7, ok.1, ok.2, ok.3, ok.4, ok.5, ok.6), "correlation"),
        ((ok.0, 9, ok.2, ok.3, ok.4, ok.5, ok.6), "orientation"),
        ((ok.0, ok.1, 0.0, ok.3, ok.4, ok.5, ok.6), "dt"),
        ((ok.0, ok.1, f64::INFINITY, ok.3, ok.4, ok.5, ok.6), "dt"),
        ((ok.0, ok.1, ok.2, -0.3, ok.4, ok.5, ok.6), "friction_velocity[0]"),
        ((ok.0, ok.1, ok.2, ok.3, f64::NAN, ok.5, ok.6), "layer[0]"),
        ((ok.0, ok.1, ok.2, ok.3, 0.0, ok.5, ok.6), "layer[0]"),
        ((ok.0, ok.1, ok.2, ok.3, ok.4, 1.0, ok.6), "diameter[0]"),
        ((ok.0, ok.1, ok.2, ok.3, ok.4, 1e-12, ok.6), "diameter[0]"),
        ((ok.0, ok.1, ok.2, ok.3, ok.4, ok.5, 1.0), "density[0]"),
    ];
    for ((c, o, dt, u, y, d, rho), name) in cases {
        let (status, message) = chance(c, o, dt, u, y, d, rho).unwrap_err();
        assert_eq!(status, DEPO_ERR_INVALID, "{name}");
        assert!(message.contains(name), "{name}: {message}");
    }
    let mut p = 0.5;
    let status =
        unsafe { depo_wall_function_probability(0, 0, null(), 9.8, 0.1, 1, &0.3, &1e-3, &5e-6, &1000.0, &mut p) };
    assert_eq!((status, p), (DEPO_ERR_NULL, 0.5));
}

/// Hussein et al.'s velocity of the tracker's `wall_function::deposition_velocity` for one
/// particle, from an independent path: the tracker's own types.
fn hussein_in_rust(orientation: depo_tracker::Orientation, u: f64, d: f64, rho: f64) -> f64 {
    use depo_tracker::wall_function::{deposition_velocity, Correlation};
    let air = depo_tracker::Air {
        temperature: AIR.temperature,
        pressure: AIR.pressure,
        density: AIR.density,
        viscosity: AIR.viscosity,
    };
    let aero = depo_tracker::Aerodynamics::new(d, rho, &air, 9.80665);
    deposition_velocity(Correlation::Hussein, &aero, &air, u, orientation)
}

#[test]
fn hussein_s_chance_is_the_tracker_s_velocity_by_orientation_cached_or_not() {
    use depo_tracker::Orientation;
    let surfaces = [
        (DEPO_SURFACE_FLOOR, Orientation::Floor),
        (DEPO_SURFACE_CEILING, Orientation::Ceiling),
        (DEPO_SURFACE_WALL, Orientation::Wall),
    ];
    // A duct's 5 um particle at u* = 0.3 m/s, a room's 3 um one at 1 cm/s, a 40 um one.
    for (u, d, rho, layer, dt) in
        [(0.3, 5e-6, 1000.0, 1.5e-3, 1e-3), (0.01, 3e-6, 1500.0, 0.045, 0.1), (0.5, 40e-6, 2500.0, 2e-3, 1e-4)]
    {
        let mut by_surface = Vec::new();
        for (surface, orientation) in surfaces {
            let expected = hussein_in_rust(orientation, u, d, rho);
            let mut v = [f64::NAN; 2];
            for v in &mut v {
                // The second call is answered from the thread's cache: the same bits.
                let status = unsafe {
                    depo_deposition_velocity(DEPO_CORRELATION_HUSSEIN, surface, &AIR, 9.80665, 1, &u, &d, &rho, v)
                };
                assert_eq!(status, DEPO_OK, "{}", last_error());
            }
            assert_eq!(v[0].to_bits(), expected.to_bits(), "{orientation:?} u* {u} d {d}: {} {expected}", v[0]);
            assert_eq!(v[1].to_bits(), expected.to_bits());
            // Another thread, with a cache of its own, computes the same.
            let other = std::thread::spawn(move || chance(DEPO_CORRELATION_HUSSEIN, surface, dt, u, layer, d, rho))
                .join()
                .unwrap()
                .unwrap();
            let p = chance(DEPO_CORRELATION_HUSSEIN, surface, dt, u, layer, d, rho).unwrap();
            assert_eq!(p.to_bits(), other.to_bits());
            let poisson = -(-expected * dt / layer).exp_m1();
            assert!((p - poisson).abs() <= 1e-15 * poisson, "{orientation:?} u* {u} d {d}: {p} {poisson}");
            by_surface.push(expected);
        }
        // Settling: a floor takes more than a wall, a wall more than a ceiling.
        assert!(by_surface[0] > by_surface[2] && by_surface[2] > by_surface[1], "{by_surface:?}");
    }
}

#[test]
fn hussein_refuses_a_particle_larger_than_its_layer() {
    // r+ = d u* / (2 nu): 1 mm at 10 m/s is 332 wall units; at 2 m/s, 66.
    let (status, message) =
        chance(DEPO_CORRELATION_HUSSEIN, DEPO_SURFACE_WALL, 1e-3, 10.0, 1e-3, 1e-3, 1000.0).unwrap_err();
    assert_eq!(status, DEPO_ERR_INVALID);
    assert!(message.contains("diameter[0]") && message.contains("wall units"), "{message}");
    assert!(chance(DEPO_CORRELATION_HUSSEIN, DEPO_SURFACE_WALL, 1e-3, 2.0, 1e-3, 1e-3, 1000.0).is_ok());
    // The others take it.
    assert!(chance(DEPO_CORRELATION_WOOD, DEPO_SURFACE_WALL, 1e-3, 10.0, 1e-3, 1e-3, 1000.0).is_ok());
}

proptest! {
    /// From any inputs in range, extreme ones included, a chance in [0, 1], never NaN; Hussein
    /// et al.'s refuses exactly the particles whose radius reaches its layer's 100 wall units.
    #[test]
    fn wall_function_chances_are_probabilities(
        correlation in 0i32..4,
        orientation in 0i32..3,
        dt in 1e-9f64..1e4,
        u in 1e-6f64..1e3,
        layer in 1e-9f64..10.0,
        log_d in -9f64..-3.0,
        rho in 1.3f64..2e4,
    ) {
        let d = 10f64.powf(log_d);
        let r_plus = 0.5 * d * u * AIR.density / AIR.viscosity;
        match chance(correlation, orientation, dt, u, layer, d, rho) {
            Ok(p) => prop_assert!((0.0..=1.0).contains(&p), "{}", p),
            Err((status, message)) => {
                prop_assert!(correlation == DEPO_CORRELATION_HUSSEIN && r_plus >= 100.0 && status == DEPO_ERR_INVALID);
                prop_assert!(message.contains("wall units"), "{}", message);
            }
        }
    }
}
