//! Invariants of the law over random inputs: `0 <= e <= 1`, kinetic energy never grows, rolling
//! leaves no slip, the energy budget closes, f32 follows f64, batch equals scalar, and thread
//! count does not change results.

use depo_wall_model::impact::kinetic_energy;
use depo_wall_model::{CaptureMode, ImpactResult, Impacts, LawParams, Normals, Outcome, PowerMode, Tally, WallLaw};
use glam::DVec3;
use proptest::prelude::*;

/// Random batches have up to this many particles: a sweep works in blocks of 512 (general
/// exponents' powers and the tally), so most batches span more than one block and end on a
/// partial one.
const BATCH_MAX: usize = 1300;

/// Laws with `k1 <= k2`, any `kappa`s, exponents in [0.25, 4] (1 and 1/2 included), any `vc`.
fn law_strategy() -> impl Strategy<Value = WallLaw> {
    let exponent = prop_oneof![Just(1.0), Just(0.5), 0.25f64..4.0];
    (
        (0.0f64..4.0, 0.0f64..1.0),
        (-2.0f64..1.0, -2.0f64..1.0),
        exponent.clone(),
        exponent,
        -0.5f64..2.0,
        0.0f64..1.0,
        prop_oneof![Just(CaptureMode::Deposit), Just(CaptureMode::KeepOnWall)],
        prop_oneof![Just(PowerMode::Fast), Just(PowerMode::Exact)],
    )
        .prop_map(|((lk2, shrink), (lka1, lka2), p, q, vc, mu, capture, power)| {
            let k2 = 10f64.powf(lk2);
            let params = LawParams {
                k1: k2 * (1.0 - 0.9 * shrink),
                k2,
                kappa1: 10f64.powf(lka1),
                kappa2: 10f64.powf(lka2),
                p,
                q,
                vc,
                mu,
            };
            WallLaw::new(params).unwrap().with_capture_mode(capture).with_power_mode(power)
        })
}

fn unit(theta: f64, phi: f64) -> DVec3 {
    DVec3::new(theta.sin() * phi.cos(), theta.sin() * phi.sin(), theta.cos())
}

/// An impact: velocity with `vn < 0` against a random unit normal, spin and radius.
fn contact_strategy() -> impl Strategy<Value = (DVec3, DVec3, f64, DVec3)> {
    (
        0.0f64..core::f64::consts::PI,
        0.0f64..core::f64::consts::TAU,
        -3.0f64..1.5,
        -2.0f64..2.0,
        -2.0f64..2.0,
        prop::array::uniform3(-1.0f64..1.0),
        -6.0f64..-3.0,
    )
        .prop_map(|(theta, phi, log_speed, t1, t2, w, log_r)| {
            let n = unit(theta, phi);
            let a = n.any_orthonormal_vector();
            let b = n.cross(a);
            let speed = 10f64.powf(log_speed);
            let r = 10f64.powf(log_r);
            let v = -speed * n + speed * (t1 * a + t2 * b);
            // Spins up to a few times |v|/r, so that slip can change sign.
            let w = DVec3::from_array(w) * (3.0 * speed / r);
            (v, w, r, n)
        })
}

fn ke(v: DVec3, w: DVec3, r: f64) -> f64 {
    kinetic_energy(v.to_array(), w.to_array(), r)
}

fn slip_after(res: &ImpactResult<f64>, r: f64, n: DVec3) -> DVec3 {
    let v = DVec3::from_array(res.velocity);
    let w = DVec3::from_array(res.spin);
    let v_t = v - v.dot(n) * n;
    v_t - r * w.cross(n)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    #[test]
    fn restitution_stays_in_zero_one(law in law_strategy(), log_speed in -6.0f64..4.0) {
        let co = law.coefficients(10f64.powf(log_speed));
        prop_assert!((0.0..=1.0).contains(&co.overall), "e = {}", co.overall);
        prop_assert!(co.restitution > 0.0 && co.restitution <= 1.0);
        prop_assert!(co.adhesion > 0.0 && co.adhesion <= 1.0);
        prop_assert!((co.overall - co.restitution * (1.0 - co.adhesion)).abs() <= 1e-12);
        prop_assert_eq!(co.captured, co.overall == 0.0);
    }

    #[test]
    fn kinetic_energy_never_grows_and_the_budget_closes(law in law_strategy(), (v, w, r, n) in contact_strategy()) {
        let res = law.impact(v, Some((w, r)), n);
        let before = ke(v, w, r);
        let after = ke(DVec3::from_array(res.velocity), DVec3::from_array(res.spin), r);
        prop_assert!(after <= before * (1.0 + 1e-12), "{after} > {before}");
        let loss = depo_wall_model::energy::energy_loss(&res);
        prop_assert!(loss.material >= 0.0 && loss.adhesion >= 0.0 && loss.friction >= -1e-15 * before && loss.deposition >= 0.0);
        prop_assert!((loss.total() - (before - after)).abs() <= 1e-12 * before, "budget {} vs {}", loss.total(), before - after);
    }

    #[test]
    fn rolling_leaves_no_slip(law in law_strategy(), (v, w, r, n) in contact_strategy()) {
        let law = law.with_capture_mode(CaptureMode::KeepOnWall);
        let res = law.impact(v, Some((w, r)), n);
        if res.rolling {
            let scale = v.length() + r * w.length();
            prop_assert!(slip_after(&res, r, n).length() <= 1e-12 * scale, "slip {}", slip_after(&res, r, n).length());
        } else if law.params().mu > 0.0 && res.slip > 0.0 {
            // Sliding: slip keeps its direction and shrinks.
            let after = slip_after(&res, r, n);
            prop_assert!(after.length() < res.slip * (1.0 + 1e-12));
        }
    }

    #[test]
    fn batch_equals_scalar_bit_for_bit(law in law_strategy(), contacts in prop::collection::vec(contact_strategy(), 1..BATCH_MAX)) {
        let n = contacts.len();
        let mut cols: [Vec<f64>; 6] = Default::default();
        let mut normals: [Vec<f64>; 3] = Default::default();
        let mut radius = Vec::new();
        for (v, w, r, nrm) in &contacts {
            for k in 0..3 {
                cols[k].push(v[k]);
                cols[3 + k].push(w[k]);
                normals[k].push(nrm[k]);
            }
            radius.push(*r);
        }
        let mut outcome = vec![Outcome::default(); n];
        let [vx, vy, vz, wx, wy, wz] = &mut cols;
        let batch = Impacts::new([vx, vy, vz], Normals::PerParticle([&normals[0], &normals[1], &normals[2]]), &mut outcome)
            .unwrap()
            .with_spin([wx, wy, wz], &radius)
            .unwrap();
        law.apply(batch, None);
        for (i, (v, w, r, nrm)) in contacts.iter().enumerate() {
            let res = law.impact(*v, Some((*w, *r)), *nrm);
            let expected = if res.coefficients.captured { Outcome::CAPTURED } else { Outcome::REBOUND };
            prop_assert_eq!(outcome[i], expected);
            for k in 0..3 {
                prop_assert_eq!(cols[k][i].to_bits(), res.velocity[k].to_bits());
                prop_assert_eq!(cols[3 + k][i].to_bits(), res.spin[k].to_bits());
            }
        }
    }

    /// f32 follows f64 to 1e-4 of the incoming state away from the capture and rolling
    /// thresholds (where a last-bit difference flips the branch).
    #[test]
    fn f32_follows_f64(law in law_strategy(), (v, w, r, n) in contact_strategy()) {
        let res64 = law.impact(v, Some((w, r)), n);
        let speed = -v.dot(n);
        let vc = law.params().vc;
        let limit = law.params().mu * (1.0 + res64.coefficients.overall) * speed;
        let near_capture = (speed - vc).abs() < 1e-2 * speed.max(vc.abs()) || res64.coefficients.overall < 1e-3;
        let near_rolling = (2.0 / 7.0 * res64.slip - limit).abs() < 1e-2 * limit.max(1e-300);
        prop_assume!(!near_capture && !near_rolling);
        let f = |x: DVec3| x.to_array().map(|c| c as f32);
        let (mut vx, mut vy, mut vz) = ([f(v)[0]], [f(v)[1]], [f(v)[2]]);
        let (mut wx, mut wy, mut wz) = ([f(w)[0]], [f(w)[1]], [f(w)[2]]);
        let radius = [r as f32];
        let nn = f(n);
        let (nx, ny, nz) = ([nn[0]], [nn[1]], [nn[2]]);
        let mut outcome = [Outcome::default()];
        let batch = Impacts::new([&mut vx, &mut vy, &mut vz], Normals::PerParticle([&nx, &ny, &nz]), &mut outcome)
            .unwrap()
            .with_spin([&mut wx, &mut wy, &mut wz], &radius)
            .unwrap();
        law.apply(batch, None);
        let v32 = DVec3::new(vx[0] as f64, vy[0] as f64, vz[0] as f64);
        let w32 = DVec3::new(wx[0] as f64, wy[0] as f64, wz[0] as f64);
        let v_scale = v.length() + r * w.length();
        prop_assert!((v32 - DVec3::from_array(res64.velocity)).length() <= 1e-4 * v_scale, "{v32} vs {:?}", res64.velocity);
        prop_assert!((w32 - DVec3::from_array(res64.spin)).length() <= 1e-4 * v_scale / r);
    }
}

#[test]
fn results_are_identical_for_one_and_two_threads_and_on_the_calling_thread() {
    let law = WallLaw::new(LawParams::symmetric(12.5, 0.065, 0.074, 1.3, 0.7).with_friction(0.3)).unwrap();
    let n = 300_000; // above the parallel threshold: cut into many pieces
                     // `None`: `apply_on_calling_thread`, outside any pool.
    let run = |threads: Option<usize>| {
        let mut vx: Vec<f64> = (0..n).map(|i| ((i * 7919) % 1013) as f64 / 1013.0 - 0.5).collect();
        let mut vy: Vec<f64> = (0..n).map(|i| ((i * 104_729) % 997) as f64 / 997.0 - 0.5).collect();
        let mut vz: Vec<f64> = (0..n).map(|i| -0.01 - ((i * 31) % 1009) as f64 / 200.0).collect();
        let mut outcome = vec![Outcome::default(); n];
        let mut tally = Tally::default();
        let mut apply = || {
            let batch =
                Impacts::new([&mut vx, &mut vy, &mut vz], Normals::Uniform([0.0, 0.0, 1.0]), &mut outcome).unwrap();
            match threads {
                Some(_) => law.apply(batch, Some(&mut tally)),
                None => law.apply_on_calling_thread(batch, Some(&mut tally)),
            }
        };
        match threads {
            Some(threads) => rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap().install(apply),
            None => apply(),
        }
        (vx, vy, vz, outcome, tally)
    };
    let one = run(Some(1));
    for other in [run(Some(2)), run(None)] {
        assert!(one.0.iter().zip(&other.0).all(|(a, b)| a.to_bits() == b.to_bits()));
        assert!(one.2.iter().zip(&other.2).all(|(a, b)| a.to_bits() == b.to_bits()));
        assert_eq!(one.3, other.3);
        assert_eq!(one.4, other.4, "tallies, energies included, must match bit for bit");
    }
    assert_eq!(one.4.particles(), n as u64);
    assert!(one.4.rebound > 0 && one.4.captured > 0);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    /// A batch with one capture velocity per particle equals, particle by particle, the scalar
    /// impact under a law whose `vc` is that particle's.
    #[test]
    fn per_particle_capture_velocity_equals_a_law_with_that_vc(
        law in law_strategy(),
        rows in prop::collection::vec((contact_strategy(), -0.5f64..3.0), 1..BATCH_MAX),
    ) {
        let n = rows.len();
        let mut cols: [Vec<f64>; 3] = Default::default();
        let mut normals: [Vec<f64>; 3] = Default::default();
        let vcs: Vec<f64> = rows.iter().map(|r| r.1).collect();
        for ((v, _, _, nrm), _) in &rows {
            for k in 0..3 {
                cols[k].push(v[k]);
                normals[k].push(nrm[k]);
            }
        }
        let mut outcome = vec![Outcome::default(); n];
        let [vx, vy, vz] = &mut cols;
        let batch = Impacts::new([vx, vy, vz], Normals::PerParticle([&normals[0], &normals[1], &normals[2]]), &mut outcome)
            .unwrap()
            .with_capture_velocity(&vcs)
            .unwrap();
        law.apply(batch, None);
        for (i, ((v, _, _, nrm), vc)) in rows.iter().enumerate() {
            let own = WallLaw::new(LawParams { vc: *vc, ..*law.params() })
                .unwrap()
                .with_capture_mode(law.capture_mode())
                .with_power_mode(law.power_mode());
            let res = own.impact(*v, None, *nrm);
            prop_assert_eq!(outcome[i] == Outcome::CAPTURED, res.coefficients.captured);
            for (col, expected) in cols.iter().zip(res.velocity) {
                prop_assert_eq!(col[i].to_bits(), expected.to_bits());
            }
        }
    }
}

/// A wall normal along a coordinate axis (`axis`, `sign`) and contacts with it, a fifth of them
/// moving away from the wall (skipped), with spins up to a few times `|v|/r`.
fn axis_wall_strategy() -> impl Strategy<Value = (DVec3, Vec<(DVec3, DVec3, f64)>)> {
    let contact = (
        -3.0f64..1.5,
        prop::array::uniform2(-2.0f64..2.0),
        prop::array::uniform3(-1.0f64..1.0),
        -6.0f64..-3.0,
        prop::bool::weighted(0.8),
    );
    (0usize..3, prop::bool::ANY, prop::collection::vec(contact, 1..BATCH_MAX)).prop_map(|(axis, positive, raw)| {
        let sign = if positive { 1.0 } else { -1.0 };
        let mut n = DVec3::ZERO;
        n[axis] = sign;
        let contacts = raw
            .into_iter()
            .map(|(log_speed, t, w, log_r, approaching)| {
                let (speed, r) = (10f64.powf(log_speed), 10f64.powf(log_r));
                let mut v = DVec3::ZERO;
                v[axis] = if approaching { -sign * speed } else { sign * speed };
                v[(axis + 1) % 3] = speed * t[0];
                v[(axis + 2) % 3] = speed * t[1];
                (v, DVec3::from_array(w) * (3.0 * speed / r), r)
            })
            .collect();
        (n, contacts)
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// A batch against one wall along a coordinate axis (the kernel's cheaper loop, which skips
    /// the normal's zero components) gives what the general loop gives with that normal per
    /// particle: the same outcomes, velocities, spins and counts. Values are compared with `==`,
    /// so a zero may differ in sign. The energies agree to rounding: with the wall's axis
    /// rotated to third place, three-term sums such as `|w|^2` add in another order.
    #[test]
    fn axis_walls_equal_the_general_normal((n, contacts) in axis_wall_strategy(), law in law_strategy()) {
        for spin in [false, true] {
            let len = contacts.len();
            let run = |uniform: bool| {
                let mut cols: [Vec<f64>; 6] = Default::default();
                let mut radius = Vec::new();
                for (v, w, r) in &contacts {
                    for k in 0..3 {
                        cols[k].push(v[k]);
                        cols[3 + k].push(w[k]);
                    }
                    radius.push(*r);
                }
                let normals = n.to_array().map(|c| vec![c; len]);
                let mut outcome = vec![Outcome::default(); len];
                let mut tally = Tally::default();
                let [vx, vy, vz, wx, wy, wz] = &mut cols;
                let source = if uniform {
                    Normals::Uniform(n.to_array())
                } else {
                    Normals::PerParticle([&normals[0], &normals[1], &normals[2]])
                };
                let batch = Impacts::new([vx, vy, vz], source, &mut outcome).unwrap();
                let batch = if spin { batch.with_spin([wx, wy, wz], &radius).unwrap() } else { batch };
                law.apply(batch, Some(&mut tally));
                (cols, outcome, tally)
            };
            let (axis_cols, axis_outcome, axis_tally) = run(true);
            let (general_cols, general_outcome, general_tally) = run(false);
            prop_assert_eq!(axis_outcome, general_outcome);
            prop_assert_eq!(axis_cols, general_cols);
            let (a, g) = (axis_tally, general_tally);
            prop_assert_eq!([a.rebound, a.captured, a.skipped, a.invalid], [g.rebound, g.captured, g.skipped, g.invalid]);
            for (x, y) in [(a.energy.material, g.energy.material), (a.energy.adhesion, g.energy.adhesion),
                (a.energy.friction, g.energy.friction), (a.energy.deposition, g.energy.deposition)] {
                prop_assert!((x - y).abs() <= 1e-14 * y.abs(), "{x} vs {y}");
            }
        }
    }
}
