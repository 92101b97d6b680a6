//! Fits of noisy synthetic data: constants recovered, the vc interval covers the truth in at
//! least 90 % of seeded trials, and data that stop far above vc give a wide interval and the
//! extrapolation warning.

use depo_wall_model::fit::{fit, Exponents, Sample};
use depo_wall_model::{LawParams, WallLaw};
use rand::rngs::StdRng;
use rand::{RngExt, SeedableRng};
use rand_distr::{Distribution, Normal};

/// `n` impacts between `from` and `to` m/s, one log-uniform in each of `n` equal log-strata (a
/// jittered grid, so the low end is always sampled), `e` with Gaussian noise of `sigma`.
fn noisy(params: LawParams, from: f64, to: f64, n: usize, sigma: f64, seed: u64) -> Vec<Sample> {
    let law = WallLaw::new(params).unwrap();
    let mut rng = StdRng::seed_from_u64(seed);
    let noise = Normal::new(0.0, sigma).unwrap();
    (0..n)
        .map(|i| {
            let speed = from * (to / from).powf((i as f64 + rng.random_range(0.0..1.0)) / n as f64);
            Sample { speed, restitution: law.overall_restitution(speed) + noise.sample(&mut rng), weight: 1.0 }
        })
        .collect()
}

#[test]
fn the_vc_interval_covers_the_truth_in_at_least_90_percent_of_trials() {
    let truth = depo_wall_model::presets::preset("li1997-sio2").unwrap().params;
    let trials = 100;
    let mut covered = 0;
    let mut k_errors = Vec::new();
    for seed in 0..trials {
        let data = noisy(truth, 1.05 * truth.vc, 5.0, 40, 0.02, seed);
        let report = fit(&data, Exponents::Fixed { p: 1.0, q: 0.5 }).unwrap();
        let (low, high) = report.vc_interval;
        if low <= truth.vc && truth.vc <= high {
            covered += 1;
        }
        assert!(!report.vc_extrapolated, "data reach down to vc");
        assert!(report.fitting_index > 0.8, "R^2 {}", report.fitting_index);
        k_errors.push(((report.params.k1 - truth.k1) / truth.k1).abs());
    }
    eprintln!("vc interval covered the truth in {covered} of {trials} trials");
    k_errors.sort_by(f64::total_cmp);
    assert!(covered >= 90, "vc covered in {covered} of {trials} trials");
    assert!(k_errors[trials as usize / 2] < 0.1, "median relative error of k: {}", k_errors[trials as usize / 2]);
}

#[test]
fn data_far_above_vc_warn_and_widen_the_interval() {
    let truth = depo_wall_model::presets::preset("li1997-sio2").unwrap().params;
    let near = fit(&noisy(truth, 1.05 * truth.vc, 5.0, 40, 0.02, 7), Exponents::Fixed { p: 1.0, q: 0.5 }).unwrap();
    let far = fit(&noisy(truth, 10.0 * truth.vc, 5.0, 40, 0.02, 7), Exponents::Fixed { p: 1.0, q: 0.5 }).unwrap();
    let width = |r: &depo_wall_model::fit::FitReport| r.vc_interval.1 - r.vc_interval.0;
    assert!(far.vc_extrapolated && !near.vc_extrapolated);
    assert!(width(&far) > 3.0 * width(&near), "far {:?} near {:?}", far.vc_interval, near.vc_interval);
}

#[test]
fn free_exponents_recover_q() {
    let truth = LawParams::symmetric(12.5, 0.065, 0.074, 1.0, 0.5);
    let data = noisy(truth, 1.05 * truth.vc, 8.0, 80, 0.002, 3);
    let report = fit(&data, Exponents::Free { p: 1.0, q: 1.0 }).unwrap();
    assert!((report.params.q - 0.5).abs() < 0.1, "q = {}", report.params.q);
    assert!((report.params.vc - truth.vc).abs() < 0.01, "vc = {}", report.params.vc);
    assert!(report.standard_errors.q > 0.0);
}
