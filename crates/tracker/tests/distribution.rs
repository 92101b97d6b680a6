//! Size distributions through a room study: the mass balance sums, and a narrow mode is the
//! monodisperse study.

use depo_tracker::distribution::{Amount, Distribution, DistributionStudy, Median, Mode};
use depo_tracker::studies::RoomStudy;
use depo_tracker::Geometry;

/// A small, fast room: 1 m cube, plain tracking, no target error.
fn small_room(count: usize, duration: f64) -> RoomStudy {
    let mut study = RoomStudy { count, target_error: None, excursions: false, ..RoomStudy::default() };
    study.scene.geometry = Geometry::Room { size: [1.0, 1.0, 1.0] };
    study.settings.duration = duration;
    study
}

/// Two modes of different densities in a ventilated room: every bin's particles are
/// accounted for, and the distribution's mass (all of it, PM10, PM2.5) is deposited per
/// surface, exhausted or airborne, summing to the injected mass but for rounding. The mass
/// outside the bins is the rest of the modes' given concentrations.
#[test]
fn a_distribution_mass_balance_sums_exactly() {
    let mut study = small_room(60, 120.0);
    study.scene.air_exchange = 6.0 / 3600.0;
    let fine = Mode {
        median: Median::Count(0.1e-6),
        geometric_sd: 1.8,
        density: 1500.0,
        amount: Amount::MassConcentration(20e-9),
    };
    let coarse = Mode {
        median: Median::Mass(6e-6),
        geometric_sd: 2.0,
        density: 2600.0,
        amount: Amount::MassConcentration(30e-9),
    };
    let distribution = Distribution::Modes { modes: vec![fine, coarse], bins: 4, range: None };
    let study = DistributionStudy { study, distribution };
    let mut calls = 0;
    let (points, balance) = study.run(|_| calls += 1).unwrap();
    assert_eq!((points.len(), balance.bins.len(), calls), (8, 8, 8));
    assert!(balance.absolute);
    for (bin, fates) in &balance.bins {
        let counted = fates.deposited.iter().sum::<usize>() + fates.airborne + fates.exhausted + fates.escaped;
        assert_eq!(counted, fates.particles, "{bin:?}");
    }
    let injected: f64 = balance.bins.iter().map(|(b, _)| b.mass).sum();
    assert_eq!(balance.all.injected, injected);
    assert!(((injected + balance.outside) / 50e-9 - 1.0).abs() < 1e-12, "{injected} + {}", balance.outside);
    assert!(balance.outside < 0.01 * injected, "the default range holds all but the tails");
    for split in [balance.all, balance.pm[0], balance.pm[1]] {
        assert!((split.accounted() - split.injected).abs() <= 1e-12 * split.injected, "{split:?}");
    }
    // Ventilation takes some of every class; 20 um particles of 2600 kg/m^3 settle onto the
    // floor; PM2.5 within PM10 within all.
    assert!(balance.all.exhausted.value > 0.0 && balance.all.deposited[0].value > 0.0);
    assert!(balance.pm[0].injected < balance.pm[1].injected && balance.pm[1].injected < balance.all.injected);
    assert!(balance.pm[0].deposited[0].value <= balance.pm[1].deposited[0].value);
    let beta = |s: &depo_tracker::distribution::MassSplit| s.beta.expect("measured").value;
    assert!(beta(&balance.all) > beta(&balance.pm[0]), "coarse mass settles faster");
}

/// A single narrow mode (sigma_g 1.01 about 5 um) gives the monodisperse study's answers
/// within their errors: the share of mass on the floor and the loss rate.
#[test]
fn a_narrow_mode_is_the_monodisperse_study() {
    let study = small_room(400, 300.0);
    let mode =
        Mode { median: Median::Count(5e-6), geometric_sd: 1.01, density: 1000.0, amount: Amount::NumberShare(1.0) };
    let narrow = DistributionStudy {
        study: study.clone(),
        distribution: Distribution::Modes { modes: vec![mode], bins: 3, range: None },
    };
    let (_, balance) = narrow.run(|_| {}).unwrap();
    assert!(!balance.absolute);
    let floor = balance.all.deposited[0];
    let share = floor.value / balance.all.injected;
    let share_error = floor.error / balance.all.injected;
    let mono = &RoomStudy { diameters: vec![5e-6], ..study }.run(|_| {}).unwrap()[0];
    let n = mono.balance.injected as f64;
    let mono_share = mono.deposited[0].0 as f64 / n;
    let mono_error = (mono_share * (1.0 - mono_share) / n).sqrt();
    assert!(mono_share > 0.1, "{mono_share}");
    let z = (share - mono_share).abs() / (share_error.powi(2) + mono_error.powi(2)).sqrt();
    assert!(z < 3.0, "floor share {share} +- {share_error} against {mono_share} +- {mono_error}");
    let beta = balance.all.beta.expect("measured");
    let z = (beta.value - mono.beta.value).abs() / (beta.error.powi(2) + mono.beta.error.powi(2)).sqrt();
    assert!(z < 3.0, "beta {beta:?} against {:?}", mono.beta);
}
