//! The room and channel studies against their correlations, on small runs.

use depo_tracker::studies::{ChannelStudy, RoomStudy};

/// Turbulent channel, impaction regime: `V+` at `tau+ = 10` within a factor of 2 of Wood (1981).
#[test]
fn channel_deposition_at_tau_plus_10_is_within_a_factor_2_of_wood() {
    let study = ChannelStudy { tau_plus: vec![10.0], count: 2000, ..ChannelStudy::default() };
    let points = study.run(|_| {}).unwrap();
    let p = &points[0];
    assert!(p.v_plus.events > 100, "{p:?}");
    let ratio = p.v_plus.value / p.wood;
    assert!((0.5..2.0).contains(&ratio), "V+ {} against Wood {}: ratio {ratio}", p.v_plus.value, p.wood);
}

/// Room: floor deposition of 3 um particles and of 0.01 um particles (Brownian) onto all
/// surfaces within 30 % of Lai & Nazaroff (2000) for the same friction velocity.
#[test]
fn room_deposition_matches_lai_nazaroff_where_it_is_measurable() {
    // The ultrafine loss rate is counted in deposits (about 7 per 100 particles here): 12000
    // particles put its statistical error near 4 %, well inside the 30 % asked for (1500 gave
    // 12 %, and ratios from 1.0 to 1.4 across seeds).
    let study = RoomStudy { diameters: vec![0.01e-6], count: 12_000, ..RoomStudy::default() };
    let ultrafine = &study.run(|_| {}).unwrap()[0];
    assert!(ultrafine.beta.events > 500, "{ultrafine:?}");
    let ratio = ultrafine.beta.value / ultrafine.model_beta;
    assert!(
        (0.7..1.3).contains(&ratio),
        "0.01 um: beta ratio {ratio} +- {}",
        ultrafine.beta.error / ultrafine.model_beta
    );
    let study = RoomStudy { diameters: vec![3e-6], count: 1500, ..RoomStudy::default() };
    let points = study.run(|_| {}).unwrap();
    let coarse = &points[0];
    assert!(coarse.floor.events > 100, "{coarse:?}");
    let ratio = coarse.floor.value / coarse.model.floor;
    assert!((0.7..1.3).contains(&ratio), "3 um floor: ratio {ratio}");
    assert_eq!(coarse.ceiling.events, 0, "nothing settles upwards");
}

/// Saffman lift, optional: it raises deposition in the diffusion-impaction regime, where the
/// random walk alone falls short of the correlations. 10000 particles: with lift about 70
/// deposit, without it a handful (2000 gave 9 against 2, too few to compare reliably).
#[test]
fn saffman_lift_raises_channel_deposition_at_tau_plus_3() {
    let mut study = ChannelStudy { tau_plus: vec![3.0], count: 10_000, ..ChannelStudy::default() };
    let without = study.run(|_| {}).unwrap()[0].v_plus;
    study.scene.lift = true;
    let with = study.run(|_| {}).unwrap()[0].v_plus;
    assert!(with.events > 40 && with.value > 5.0 * without.value, "with {with:?}, without {without:?}");
}
