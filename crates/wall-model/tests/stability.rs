//! No NaN, no infinity, no overflow for extreme but valid inputs; bad particles flagged and left
//! untouched, bit for bit, while the rest of the batch is processed.

use depo_wall_model::{Impacts, LawParams, Normals, Outcome, PowerMode, Real, Tally, WallLaw};

/// One particle: velocity, spin, radius, normal.
type Row = ([f64; 3], [f64; 3], f64, [f64; 3]);

/// One batch in SoA form with spin, owned.
struct Soa<T> {
    v: [Vec<T>; 3],
    w: [Vec<T>; 3],
    r: Vec<T>,
    n: [Vec<T>; 3],
    outcome: Vec<Outcome>,
}

impl<T: Real> Soa<T> {
    fn from_f64(rows: &[Row]) -> Self {
        let col = |f: &dyn Fn(&Row) -> f64| rows.iter().map(|r| T::from_f64(f(r))).collect();
        Self {
            v: [col(&|r| r.0[0]), col(&|r| r.0[1]), col(&|r| r.0[2])],
            w: [col(&|r| r.1[0]), col(&|r| r.1[1]), col(&|r| r.1[2])],
            r: col(&|r| r.2),
            n: [col(&|r| r.3[0]), col(&|r| r.3[1]), col(&|r| r.3[2])],
            outcome: vec![Outcome::default(); rows.len()],
        }
    }

    fn apply(&mut self, law: &WallLaw, spin: bool) -> Tally {
        let [vx, vy, vz] = &mut self.v;
        let normals = Normals::PerParticle([&self.n[0], &self.n[1], &self.n[2]]);
        let mut batch = Impacts::new([vx, vy, vz], normals, &mut self.outcome).unwrap();
        if spin {
            let [wx, wy, wz] = &mut self.w;
            batch = batch.with_spin([wx, wy, wz], &self.r).unwrap();
        }
        let mut tally = Tally::default();
        law.apply(batch, Some(&mut tally));
        tally
    }
}

fn extreme_rows() -> Vec<Row> {
    let mut rows = Vec::new();
    let s = 0.5f64.sqrt();
    for speed in [5e-324, 1e-300, 1e-12, 1e-3, 1.0, 1e2, 1e4] {
        for tangential in [0.0, 1e-3, 1e4] {
            for radius in [1e-9, 1e-3] {
                for spin in [0.0, 1e9] {
                    for n in [[0.0, 0.0, 1.0], [s, 0.0, -s]] {
                        let v = [tangential * n[2] - speed * n[0], tangential, -tangential * n[0] - speed * n[2]];
                        rows.push((v, [spin, -spin, 0.5 * spin], radius, n));
                    }
                }
            }
        }
    }
    rows
}

fn check_extremes<T: Real>() {
    let rows = extreme_rows();
    let mut laws = 0;
    for p in [0.1, 0.5, 1.0, 3.0, 20.0] {
        for q in [0.1, 0.5, 1.0, 3.0, 20.0] {
            for k in [1e-6, 1.0, 1e6] {
                for kappa in [1e-6, 1.0, 1e6] {
                    for (k1, kappa1) in [(k, kappa), (k * 1e-3, kappa * 1e3)] {
                        for vc in [-1.0, 0.0, 0.1, 1e3] {
                            for mu in [0.0, 0.5] {
                                for power in [PowerMode::Fast, PowerMode::Exact] {
                                    let params = LawParams { k1, k2: k, kappa1, kappa2: kappa, p, q, vc, mu };
                                    let law = WallLaw::new(params).unwrap().with_power_mode(power);
                                    for spin in [false, true] {
                                        let mut soa = Soa::<T>::from_f64(&rows);
                                        let tally = soa.apply(&law, spin);
                                        laws += 1;
                                        assert_eq!(tally.invalid, 0, "{params:?}");
                                        for i in 0..rows.len() {
                                            let out = [
                                                soa.v[0][i],
                                                soa.v[1][i],
                                                soa.v[2][i],
                                                soa.w[0][i],
                                                soa.w[1][i],
                                                soa.w[2][i],
                                            ];
                                            assert!(out.iter().all(|x| x.is_finite()), "{params:?} row {i}: {out:?}");
                                        }
                                        let e = tally.energy;
                                        for x in [e.material, e.adhesion, e.friction, e.deposition] {
                                            assert!(!x.is_nan(), "{params:?}: energy {e:?}");
                                        }
                                    }
                                }
                            }
                        }
                    }
                }
            }
        }
    }
    assert!(laws > 10_000);
}

#[test]
fn extreme_parameters_and_inputs_give_finite_results_f64() {
    check_extremes::<f64>();
}

#[test]
fn extreme_parameters_and_inputs_give_finite_results_f32() {
    check_extremes::<f32>();
}

#[test]
fn thresholds_at_vc_and_one_ulp_either_side() {
    let law = WallLaw::preset("li1997-sio2").unwrap();
    let vc = law.params().vc;
    let speeds = [vc.next_down(), vc, vc.next_up(), 1e-300, 5e-324];
    let rows: Vec<_> = speeds.iter().map(|s| ([0.1, 0.0, -s], [0.0; 3], 1e-5, [0.0, 0.0, 1.0])).collect();
    let mut soa = Soa::<f64>::from_f64(&rows);
    soa.apply(&law, false);
    assert_eq!(
        soa.outcome,
        [Outcome::CAPTURED, Outcome::CAPTURED, Outcome::REBOUND, Outcome::CAPTURED, Outcome::CAPTURED]
    );
    // One ulp above vc, u = ulp(vc) and q = 1/2: e = R (1 - rho) ~ R sqrt(u / kappa), so the
    // rebound is tiny but positive: Vn ~ vc R sqrt(u/kappa) ~ 1.07e-9 m/s.
    let u = vc.next_up() - vc;
    let expected = vc.next_up() * law.restitution(vc) * (u / law.params().kappa1).sqrt();
    let vz = soa.v[2][2];
    assert!((vz / expected - 1.0).abs() < 1e-3, "just above vc: {vz} vs {expected}");
    // vn = 0 and vn = -0.0 touch without impact: skipped.
    let rows =
        [([0.3, 0.0, 0.0], [0.0; 3], 1e-5, [0.0, 0.0, 1.0]), ([0.3, 0.0, -0.0], [0.0; 3], 1e-5, [0.0, 0.0, 1.0])];
    let mut soa = Soa::<f64>::from_f64(&rows);
    soa.apply(&law, false);
    assert_eq!(soa.outcome, [Outcome::SKIPPED, Outcome::SKIPPED]);
    assert_eq!(soa.v[2][1].to_bits(), (-0.0f64).to_bits());
}

#[test]
fn bad_particles_are_flagged_and_untouched_while_the_rest_is_processed() {
    let law = WallLaw::new(LawParams::symmetric(12.5, 0.065, 0.074, 1.0, 0.5).with_friction(0.3)).unwrap();
    let nan = f64::from_bits(0x7ff8_dead_beef_0001); // a NaN with a payload to check bit for bit
    let up = [0.0, 0.0, 1.0];
    let good = ([0.2, 0.1, -1.0], [10.0, 0.0, 0.0], 1e-5, up);
    let rows = vec![
        good,
        ([nan, 0.0, -1.0], [0.0; 3], 1e-5, up),
        ([0.0, f64::INFINITY, -1.0], [0.0; 3], 1e-5, up),
        ([0.0, 0.0, f64::NEG_INFINITY], [0.0; 3], 1e-5, up),
        ([0.1, 0.0, -1.0], [0.0, nan, 0.0], 1e-5, up),
        ([0.1, 0.0, -1.0], [0.0; 3], 0.0, up),
        ([0.1, 0.0, -1.0], [0.0; 3], -1e-5, up),
        ([0.1, 0.0, -1.0], [0.0; 3], nan, up),
        ([0.1, 0.0, -1.0], [0.0; 3], f64::INFINITY, up),
        ([0.1, 0.0, -1.0], [0.0; 3], 1e-5, [0.0, 0.0, 0.0]),
        ([0.1, 0.0, -1.0], [0.0; 3], 1e-5, [0.0, 0.0, 1.0002]),
        ([0.1, 0.0, -1.0], [0.0; 3], 1e-5, [nan, 0.0, 1.0]),
        ([0.1, 0.0, 0.5], [0.0; 3], 1e-5, up), // leaving the wall: skipped
        // Invalid takes precedence over skipped and over captured (0.01 m/s is below vc).
        ([0.1, 0.0, 0.5], [0.0, nan, 0.0], 1e-5, up),
        ([0.0, 0.0, -0.01], [0.0; 3], 0.0, up),
        good,
    ];
    let mut soa = Soa::<f64>::from_f64(&rows);
    let tally = soa.apply(&law, true);
    let last = rows.len() - 1;
    for (i, row) in rows.iter().enumerate() {
        let expected = match i {
            0 => Outcome::REBOUND,
            12 => Outcome::SKIPPED,
            i if i == last => Outcome::REBOUND,
            _ => Outcome::INVALID,
        };
        assert_eq!(soa.outcome[i], expected, "row {i}");
        if expected != Outcome::REBOUND {
            for k in 0..3 {
                assert_eq!(soa.v[k][i].to_bits(), row.0[k].to_bits(), "row {i} velocity touched");
                assert_eq!(soa.w[k][i].to_bits(), row.1[k].to_bits(), "row {i} spin touched");
            }
        }
    }
    assert_eq!((tally.rebound, tally.captured, tally.skipped, tally.invalid), (2, 0, 1, 13));
    assert!((soa.v[2][0] - law.overall_restitution(1.0)).abs() < 1e-15);
    assert_eq!(soa.v[2][0].to_bits(), soa.v[2][last].to_bits());
}

#[test]
fn a_non_finite_per_particle_capture_velocity_flags_the_particle() {
    let law = WallLaw::preset("sim-70um").unwrap();
    let (mut vx, mut vy, mut vz) = (vec![0.0; 3], vec![0.0; 3], vec![-0.1; 3]);
    let mut outcome = vec![Outcome::default(); 3];
    let vcs = [0.2, f64::NAN, 0.01];
    let batch = Impacts::new([&mut vx, &mut vy, &mut vz], Normals::Uniform([0.0, 0.0, 1.0]), &mut outcome)
        .unwrap()
        .with_capture_velocity(&vcs)
        .unwrap();
    law.apply(batch, None);
    // 0.1 m/s is below a 0.2 m/s capture velocity and above 0.01 m/s.
    assert_eq!(outcome, [Outcome::CAPTURED, Outcome::INVALID, Outcome::REBOUND]);
    assert_eq!(vz[1], -0.1);
    let short = [0.1; 2];
    let mut outcome = vec![Outcome::default(); 3];
    let err = Impacts::new([&mut vx, &mut vy, &mut vz], Normals::Uniform([0.0, 0.0, 1.0]), &mut outcome)
        .unwrap()
        .with_capture_velocity(&short)
        .unwrap_err();
    assert_eq!(err, depo_wall_model::BatchError::LengthMismatch { field: "capture_velocity", expected: 3, found: 2 });
}
