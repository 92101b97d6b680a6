//! One subject, hence one file over 700 lines: the two studies and their excursions against plain tracking.
//!
//! The room and channel studies against their correlations, on small runs, and the near-wall
//! excursions against plain tracking.

use depo_tracker::studies::{ChannelStudy, RoomStudy, CHANNEL_COARSE_FACTOR, CHANNEL_INNERMOST_LEVEL, CHANNEL_SWEEPS};
use depo_tracker::{
    run, Correlation, Estimate, Excursions, Fate, Injection, NearWall, Orientation, RunSettings, Scene,
    SizeDistribution, WallBehaviour, WallFunction,
};

/// A `tau+` no particle can have at the channel's friction velocity is an error naming it, not
/// a run of the largest particle under the wrong label.
#[test]
fn an_impossible_tau_plus_is_an_error() {
    let mut study = ChannelStudy { tau_plus: vec![10.0], count: 10, target_error: None, ..ChannelStudy::default() };
    study.scene.flow = depo_tracker::Flow::TurbulentChannel { friction_velocity: 1e-4 };
    let err = study.run(|_| {}).unwrap_err();
    assert_eq!(err.field, "particles.tau_plus");
    assert_eq!(err.value, 10.0);
}

/// Turbulent channel, impaction regime: `V+` at `tau+ = 10` within a factor of 2 of Wood (1981)
/// and three standard errors (measured 1.24 +- 0.06 of Wood).
#[test]
fn channel_deposition_at_tau_plus_10_is_within_a_factor_2_of_wood() {
    let study = ChannelStudy { tau_plus: vec![10.0], count: 2000, target_error: None, ..ChannelStudy::default() };
    let points = study.run(|_| {}).unwrap();
    let p = &points[0];
    assert!(p.v_plus.events > 100, "{p:?}");
    within_a_factor_2_of_wood(p);
    assert!(
        (p.wood / wood_by_hand(10.0) - 1.0).abs() < 0.01,
        "the study's Wood {} against {}",
        p.wood,
        wood_by_hand(10.0)
    );
}

/// With a target error the channel study runs more particles where `V+` needs them, and
/// pools them with the first: resolved to the target (its 15 % margin covers the errors' own
/// spread); a `tau+` that would need more than `max_factor` times its first particles keeps
/// them.
#[test]
fn a_channel_study_runs_more_particles_where_v_plus_needs_them() {
    let study = ChannelStudy {
        tau_plus: vec![10.0, 100.0],
        count: 300,
        target_error: Some(0.05),
        max_factor: 40.0,
        ..ChannelStudy::default()
    };
    for p in study.run(|_| {}).unwrap() {
        assert!(p.particles > 600, "{p:?}");
        assert!(p.v_plus.error <= 0.05 * p.v_plus.value, "{p:?}");
    }
    let capped = ChannelStudy { max_factor: 1.5, ..study };
    for p in capped.run(|_| {}).unwrap() {
        assert_eq!(p.particles, 300, "{p:?}");
        assert!(p.v_plus.error > 0.08 * p.v_plus.value, "{p:?}");
    }
}

/// Where the pooled estimate still misses the target after the first round of more particles
/// (their number was read off a rough error from the first ones), the channel study runs a
/// second round: from 100 first particles at `tau+` 10 and 30, seeds 1, 4 and 5, the first
/// round left `tau+ = 30` at 5.4, 5.7 and 6.1 %; with the second, every point is within the
/// 5 % target.
#[test]
fn a_channel_study_runs_a_second_round_where_the_first_misses_its_target() {
    for seed in [1, 4, 5] {
        let mut study = ChannelStudy {
            tau_plus: vec![10.0, 30.0],
            count: 100,
            target_error: Some(0.05),
            max_factor: 100.0,
            ..ChannelStudy::default()
        };
        study.settings.seed = seed;
        for p in study.run(|_| {}).unwrap() {
            assert!(p.v_plus.error <= 0.05 * p.v_plus.value, "seed {seed}: {p:?}");
        }
    }
}

/// Asserts that `V+` of `p` is within a factor 2 of Wood (by hand) widened by three of its
/// standard errors: Wood's correlation is a fit through measurements scattered over a factor
/// of 2 about it. Prints the value and band.
fn within_a_factor_2_of_wood(p: &depo_tracker::studies::ChannelPoint) {
    let wood = wood_by_hand(p.tau_plus);
    let ratio = p.v_plus.value / wood;
    let band = 2.0 * (1.0 + 3.0 * p.v_plus.error / p.v_plus.value);
    println!(
        "tau+ {}: V+ {:.4e} +- {:.1e} against Wood {wood:.4e}: ratio {ratio:.3}, band {:.3}..{band:.3}",
        p.tau_plus,
        p.v_plus.value,
        p.v_plus.error,
        1.0 / band
    );
    assert!(ratio < band && ratio * band > 1.0, "V+ {} against Wood {wood}: ratio {ratio}", p.v_plus.value);
}

/// Wood's (1981) correlation, `V+ = 0.057 Sc^(-2/3) + 4.5e-4 tau+^2` (at most 0.13), with the
/// Schmidt number of [`particle_by_hand`].
fn wood_by_hand(tau_plus: f64) -> f64 {
    let (_, schmidt) = particle_by_hand(tau_plus);
    (0.057 * schmidt.powf(-2.0 / 3.0) + 4.5e-4 * tau_plus * tau_plus).min(0.13)
}

/// The kinematic viscosity of air at 20 C used by [`particle_by_hand`], m^2/s.
const NU_BY_HAND: f64 = 1.81e-5 / 1.204;

/// The diameter (m) and Schmidt number of the unit-density sphere of `tau+` in the default
/// channel (`u* = 0.3 m/s`, air at 20 C), worked out here from Hinds (1999): Stokes'
/// relaxation time and Stokes-Einstein diffusivity with Allen & Raabe's (1985) slip
/// correction, mean free path 0.0665 um (Hinds, Sec. 3.3, at 20 C); none of it from the code
/// under test.
fn particle_by_hand(tau_plus: f64) -> (f64, f64) {
    let (mu, nu, kt, lambda, u_star, rho_p) = (1.81e-5, NU_BY_HAND, 1.380_649e-23 * 293.15, 0.0665e-6, 0.3, 1000.0);
    let slip = |d: f64| 1.0 + 2.0 * lambda / d * (1.142 + 0.558 * (-0.999 * d / (2.0 * lambda)).exp());
    let tau = tau_plus * nu / (u_star * u_star);
    let mut d = (18.0 * mu * tau / rho_p).sqrt();
    for _ in 0..50 {
        d = (18.0 * mu * tau / (rho_p * slip(d))).sqrt();
    }
    (d, nu / (kt * slip(d) / (3.0 * std::f64::consts::PI * mu * d)))
}

/// The conductance of the near-wall layer to Brownian particles, `V+ = 1 / int dy+ / (1/Sc +
/// K+(y+))` from the particle's surface at contact (`y+ = r+`) to the centre of the default
/// channel (`y+ = 150`), with the eddy diffusivity `K+ = v+_rms^2 T_L+` of Kallio & Reeks'
/// (1989) wall-normal profile and Lagrangian time as the tracker's docs give them, typed here:
/// the deposition velocity of gradient diffusion through the profile, with the concentration
/// uniform beyond it. By the midpoint rule on 20000 log-spaced cells (converged to 1e-6).
fn sublayer_conductance_by_hand(r_plus: f64, schmidt: f64) -> f64 {
    conductance_by_hand(r_plus, 150.0, schmidt, kallio_reeks_eddy_diffusivity)
}

/// `K+ = v+_rms^2 T_L+` of Kallio & Reeks' (1989) fits, typed here.
fn kallio_reeks_eddy_diffusivity(y: f64) -> f64 {
    let v_rms = 0.0116 * y * y / (1.0 + 0.203 * y + 0.0014 * y.powf(2.421));
    let t_l = if y < 5.0 { 10.0 } else { 7.122 + 0.5731 * y - 0.00129 * y * y };
    v_rms * v_rms * t_l
}

/// Lai & Nazaroff's (2000) eddy viscosity `nu_t / nu` near a wall, from which their
/// correlation is integrated: `7.669e-4 y+^3` below `y+ = 4.3`, `1.00e-3 y+^2.8214` to 12.5,
/// `1.07e-2 y+^1.8895` to 30.
fn lai_nazaroff_eddy_diffusivity(y: f64) -> f64 {
    if y < 4.3 {
        7.669e-4 * y.powi(3)
    } else if y < 12.5 {
        1.00e-3 * y.powf(2.8214)
    } else {
        1.07e-2 * y.powf(1.8895)
    }
}

/// `1 / int dy+ / (1/Sc + K+(y+))` from `from` to `to` by the midpoint rule on 20000
/// log-spaced cells.
fn conductance_by_hand(from: f64, to: f64, schmidt: f64, eddy: fn(f64) -> f64) -> f64 {
    let (a, b, n) = (from.ln(), to.ln(), 20_000);
    let h = (b - a) / f64::from(n);
    let resistance: f64 = (0..n)
        .map(|i| {
            let y = (a + h * (f64::from(i) + 0.5)).exp();
            y * h / (1.0 / schmidt + eddy(y))
        })
        .sum();
    1.0 / resistance
}

/// The Schmidt number of a unit-density sphere of diameter `d` (m) in air at 20 C, as
/// [`particle_by_hand`] works it out.
fn schmidt_by_hand(d: f64) -> f64 {
    let (mu, kt, lambda) = (1.81e-5, 1.380_649e-23 * 293.15, 0.0665e-6);
    let slip = 1.0 + 2.0 * lambda / d * (1.142 + 0.558 * (-0.999 * d / (2.0 * lambda)).exp());
    NU_BY_HAND / (kt * slip / (3.0 * std::f64::consts::PI * mu * d))
}

/// Turbulent channel, diffusion regime: `V+` at `tau+ = 0.1`, where Brownian diffusion through
/// the sublayer carries half of Wood's value, within a factor of 2 of Wood and three standard
/// errors (measured 0.58 +- 0.07 of Wood), with no excursion weight given up (the study follows them to the end). Without Brownian motion, or with
/// excursions given up after 1e4 wall time units, it falls below half.
#[test]
fn channel_deposition_at_tau_plus_0_1_is_within_a_factor_2_of_wood() {
    let study =
        ChannelStudy { tau_plus: vec![0.1], excursion_count: 400, target_error: None, ..ChannelStudy::default() };
    let points = study.run(|_| {}).unwrap();
    let p = &points[0];
    assert!(p.v_plus.events > 100 && p.v_plus.error < 0.15 * p.v_plus.value, "{p:?}");
    assert!(p.excursions.is_some_and(|share| share < 0.01), "weight given up: {:?}", p.excursions);
    within_a_factor_2_of_wood(p);
}

/// Turbulent channel, diffusion regime (`tau+` 1e-4 and 1e-2, Schmidt numbers about 1.4e3 and
/// 3.4e5, where inertia is negligible): particles cross the viscous sublayer by Brownian and
/// turbulent diffusion, so `V+` is the layer's conductance. depo's Lagrangian `V+` is within
/// three standard errors and 5 % of the gradient-diffusion conductance of the same profiles
/// worked out here: the same physics, except that gradient diffusion is the limit of a
/// Lagrangian time short against the time to cross the layer, and `T_L+ = 10` in the sublayer
/// is not. Measured 1.013 +- 0.044 and 1.167 +- 0.074 (an rms profile 1.5 times its source
/// raises the conductance by 1.5^(1/2) ~ 1.22 where `K+ ~ y+^4`; a Brownian diffusivity half
/// or double would move it 1.7 times, turbulence off far more). Also within a factor of 2 of
/// Wood (1.54 and 1.14), and falls with the Schmidt number with an exponent between -0.8 and
/// -0.6 (-0.72): Wood's and Papavergos & Hedley's correlations have -2/3, the model's eddy
/// diffusivity, growing as `y+^4` from the wall, -3/4 in the limit of large `Sc`.
#[test]
fn channel_diffusion_regime_follows_the_sublayer_conductance_and_the_schmidt_number() {
    let study = ChannelStudy {
        tau_plus: vec![1e-4, 1e-2],
        excursion_count: 1000,
        target_error: None,
        ..ChannelStudy::default()
    };
    let points = study.run(|_| {}).unwrap();
    let mut by_hand = Vec::new();
    for p in &points {
        let (d, schmidt) = particle_by_hand(p.tau_plus);
        // depo's slip correction is Hinds' Eq. 3.20, this one Allen & Raabe's: 2.4 % apart at
        // the 23 nm of tau+ = 1e-4.
        assert!((p.schmidt / schmidt - 1.0).abs() < 0.03, "Sc {} against {schmidt} by hand", p.schmidt);
        let v = p.v_plus.value;
        assert!(p.v_plus.events > 100 && p.v_plus.error < 0.12 * v, "{p:?}");
        let conductance = sublayer_conductance_by_hand(0.5 * d * 0.3 / NU_BY_HAND, schmidt);
        let (ratio, error) = (v / conductance, p.v_plus.error / conductance);
        let band = 3.0 * error + 0.05;
        println!(
            "tau+ {}: Sc {schmidt:.3e}, V+ {v:.4e} +- {:.1e}, conductance {conductance:.4e}: ratio {ratio:.4} +- {error:.4}, band 1 +- {band:.3}",
            p.tau_plus, p.v_plus.error,
        );
        assert!((ratio - 1.0).abs() < band, "tau+ {}: V+ {v} against the conductance {conductance}", p.tau_plus);
        let wood = wood_by_hand(p.tau_plus);
        assert!((0.5..2.0).contains(&(v / wood)), "tau+ {}: V+ {v} against Wood {wood}", p.tau_plus);
        by_hand.push((schmidt, v));
    }
    let [(sc0, v0), (sc1, v1)] = [by_hand[0], by_hand[1]];
    let exponent = (v1 / v0).ln() / (sc1 / sc0).ln();
    assert!((-0.8..-0.6).contains(&exponent), "V+ against Sc: exponent {exponent}");
}

/// Room: floor deposition of 3 um particles and the loss rate of 0.01 um particles (Brownian)
/// against Lai & Nazaroff (2000) for the same friction velocity, both resolved to a few per
/// cent by the study's excursions, each within three standard errors and a model tolerance:
///
/// - 0.01 um: not the same physics near the wall. Lai & Nazaroff's eddy diffusivity grows as
///   `7.669e-4 y+^3`, the room's (Kallio & Reeks') as about `1.35e-3 y+^4`; gradient
///   diffusion through each from the particle's surface to `y+ = 30`, worked out here, gives
///   conductances 1.19 apart at this Schmidt number (274): that spread is the tolerance.
///   Measured 1.046 +- 0.037 (the room's near-wall `T_L` x1.5 put it at 1.16, inside this
///   band: that error is caught by the room profile's own unit test in `physics/turbulence.rs`; the
///   wall-normal rms x1.5 put it at 1.31, outside).
/// - 3 um floor: the same physics, settling through a layer the turbulence keeps at the
///   room's mean concentration (Lai & Nazaroff's floor velocity here is the settling
///   velocity); the tolerance is the dispersion model's residual near a wall, 5 % of uniform
///   for tracers (docs/validation.md). Measured 1.075 +- 0.063.
#[test]
fn room_deposition_matches_lai_nazaroff_where_it_is_measurable() {
    let study = RoomStudy { diameters: vec![0.01e-6, 3e-6], count: 600, target_error: None, ..RoomStudy::default() };
    let points = study.run(|_| {}).unwrap();
    let (ultrafine, coarse) = (&points[0], &points[1]);
    assert!(ultrafine.beta.error < 0.1 * ultrafine.beta.value, "{:?}", ultrafine.beta);
    let (schmidt, r_plus) = (schmidt_by_hand(0.01e-6), 0.5 * 0.01e-6 * 0.01 / NU_BY_HAND);
    let spread = conductance_by_hand(r_plus, 30.0, schmidt, kallio_reeks_eddy_diffusivity)
        / conductance_by_hand(r_plus, 30.0, schmidt, lai_nazaroff_eddy_diffusivity)
        - 1.0;
    assert!((0.15..0.25).contains(&spread), "the eddy diffusivities' spread {spread} at Sc {schmidt}");
    let ratio = ultrafine.beta.value / ultrafine.model_beta;
    let error = ultrafine.beta.error / ultrafine.model_beta;
    let band = 3.0 * error + spread.abs();
    println!(
        "0.01 um: beta ratio {ratio:.4} +- {error:.4}, band 1 +- {band:.3} (model spread {spread:.3}, Sc {schmidt:.0})"
    );
    assert!((ratio - 1.0).abs() < band, "0.01 um: beta ratio {ratio} +- {error} ({:?})", ultrafine.beta);
    assert!(coarse.floor.error < 0.1 * coarse.floor.value, "{:?}", coarse.floor);
    let ratio = coarse.floor.value / coarse.model.floor;
    let error = coarse.floor.error / coarse.model.floor;
    let band = 3.0 * error + 0.05;
    println!(
        "3 um floor: ratio {ratio:.4} +- {error:.4}, band 1 +- {band:.3}; Lai & Nazaroff {:.4e} m/s",
        coarse.model.floor
    );
    assert!((ratio - 1.0).abs() < band, "3 um floor: ratio {ratio} +- {error}");
    assert_eq!(coarse.ceiling.events, 0, "nothing settles upwards");
    assert!(coarse.ceiling.upper_bound > 0.0 && coarse.ceiling.upper_bound < coarse.floor.value);
}

/// Room: each vertical wall is a figure of its own, and the four together are the walls'
/// figure. With the `x0` wall a mirror and the others sinks, 0.03 um particles (which reach
/// every wall by Brownian and turbulent diffusion) deposit on `x0` not at all and on the
/// other three each at about the sinks' own rate: the walls' figure spreads their deposits
/// over all four walls' 35 m^2, so the sinks' rate is 35 / 27.5 of it (x0 is 7.5 m^2).
#[test]
fn a_room_reports_each_vertical_wall_and_a_mirror_wall_takes_nothing() {
    let mut study = RoomStudy { diameters: vec![0.03e-6], count: 1200, target_error: None, ..RoomStudy::default() };
    study.scene.walls[2] = WallBehaviour::Reflect;
    let p = &study.run(|_| {}).unwrap()[0];
    assert_eq!(p.each_wall[0].events, 0, "{:?}", p.each_wall[0]);
    assert_eq!(p.wall_deposited[0].0, 0);
    let sinks = &p.each_wall[1..];
    assert!(sinks.iter().all(|e| e.events > 300 && e.error < 0.15 * e.value), "{sinks:?}");
    assert_eq!(p.each_wall.iter().map(|e| e.events).sum::<usize>(), p.walls.events);
    let counted: usize = p.wall_deposited.iter().map(|d| d.0).sum();
    let mass: f64 = p.wall_deposited.iter().map(|d| d.1).sum();
    assert_eq!(counted, p.deposited[2].0);
    assert!((mass - p.deposited[2].1).abs() <= 1e-12 * p.deposited[2].1);
    // The walls' figure is the area-weighted mean of the four: x0 and x1 are 3 m x 2.5 m,
    // y0 and y1 4 m x 2.5 m.
    let areas = [7.5, 7.5, 10.0, 10.0];
    let mean = p.each_wall.iter().zip(areas).map(|(e, a)| e.value * a).sum::<f64>() / 35.0;
    assert!((mean - p.walls.value).abs() <= 1e-9 * p.walls.value, "{mean} against {:?}", p.walls);
    let over_sinks = p.walls.value * 35.0 / 27.5;
    for (k, e) in sinks.iter().enumerate() {
        let z = (e.value - over_sinks) / e.error;
        assert!(z.abs() < 4.0, "wall {}: {:?} against the sinks' mean {over_sinks} (z = {z})", k + 1, e);
    }
}

/// Saffman lift, optional: it raises deposition in the diffusion-impaction regime, where the
/// random walk alone falls short of the correlations. Plain tracking of 10000 particles: with
/// lift about 70 deposit, without it a handful (2000 gave 9 against 2, too few to compare).
#[test]
fn saffman_lift_raises_channel_deposition_at_tau_plus_3() {
    let mut study = ChannelStudy {
        tau_plus: vec![3.0],
        count: 10_000,
        excursions_below: 0.0,
        target_error: None,
        ..ChannelStudy::default()
    };
    let without = study.run(|_| {}).unwrap()[0].v_plus;
    study.scene.lift = true;
    let with = study.run(|_| {}).unwrap()[0].v_plus;
    assert!(with.events > 40 && with.value > 5.0 * without.value, "with {with:?}, without {without:?}");
}

/// How many combined standard errors apart two estimates are.
fn z(a: Estimate, b: Estimate) -> f64 {
    (a.value - b.value).abs() / (a.error * a.error + b.error * b.error).sqrt()
}

/// The excursions' estimate is unbiased: where plain tracking reaches the steady state and
/// resolves it, the two agree within three combined standard errors. Three regimes: Brownian
/// diffusion to every surface of a room (0.01 um), settling onto its floor (3 um), and
/// turbophoretic impaction in a channel (`tau+ = 10`, inertial: 1.49 combined standard errors
/// apart here, plain 2.7 % and excursions 3.8 %; with 1000 excursion particles, over six
/// seeds 0.2 to 1.9 apart, the excursions lower in five, 0.95 of plain on average, so a bias
/// of a few per cent is not excluded at that resolution); and settling in a ventilated room.
/// A wrong weight (`1 / sqrt(sampling)` for `1 / sampling`) put them 9 combined standard
/// errors apart at 0.01 um.
#[test]
fn excursions_agree_with_plain_tracking_where_both_resolve() {
    let compare = |(scene, settings): (&Scene, &RunSettings),
                   injection: &Injection,
                   excursions: Excursions,
                   plain_count: usize,
                   walls: &[usize]| {
        let plain = run(scene, settings, &Injection { count: plain_count, ..*injection }).unwrap();
        let mut split = settings.clone();
        split.seed += 1;
        let excursions = excursions.calibrated(scene, &split, injection, injection.count / 4, 1, 8).unwrap().0;
        split.excursions = Some(excursions);
        let split = run(scene, &split, injection).unwrap();
        let (a, b) = (plain.deposition_velocity(walls), split.deposition_velocity(walls));
        println!(
            "plain {:.4e} +- {:.1e} ({} events), excursions {:.4e} +- {:.1e}: {:.2} combined standard errors apart",
            a.value,
            a.error,
            a.events,
            b.value,
            b.error,
            z(a, b)
        );
        assert!(a.events > 150 && b.error < 0.1 * b.value, "plain {a:?}, excursions {b:?}");
        assert!(split.truncated_share() < 0.01, "{}", split.truncated_share());
        (a, b)
    };
    let room = RoomStudy::default();
    let scene = room.scene.clone();
    let settings = RunSettings { average_from: 180.0, ..room.settings.clone() };
    let nu = scene.air.kinematic_viscosity();
    let all: Vec<usize> = (0..6).collect();
    for (d, plain_count, walls) in [(0.01e-6, 12_000, &all[..]), (3e-6, 2000, &[0][..])] {
        let injection = Injection::new(500, SizeDistribution::Monodisperse { diameter: d }, 1000.0);
        let excursions = Excursions::in_wall_units(0.01, nu, 0.05, 3.0, 16_000.0);
        let (plain, split) = compare((&scene, &settings), &injection, excursions, plain_count, walls);
        assert!(z(plain, split) < 3.0, "{d} m: plain {plain:?}, excursions {split:?}");
    }
    // Ventilated, 6 air changes per hour: exhaust scales crossings and deposits alike, and the
    // excursions need no weight for it (weighting each deposit by the chance `exp(-a s)` that
    // the particle was not exhausted first put them 3 combined standard errors low).
    let mut ventilated = scene.clone();
    ventilated.air_exchange = 6.0 / 3600.0;
    let injection = Injection::new(1000, SizeDistribution::Monodisperse { diameter: 3e-6 }, 1000.0);
    let excursions = Excursions::in_wall_units(0.01, nu, 0.05, 3.0, 16_000.0);
    let (plain, split) = compare((&ventilated, &settings), &injection, excursions, 6000, &[0]);
    assert!(z(plain, split) < 3.0, "ventilated, 3 um: plain {plain:?}, excursions {split:?}");
    let channel = ChannelStudy::default();
    let scene = channel.scene.clone();
    let settings = RunSettings { average_from: 0.5 * channel.settings.duration, ..channel.settings.clone() };
    let d = depo_tracker::correlations::diameter_for_tau_plus(10.0, 1000.0, &scene.air, 0.3).unwrap();
    // Inertial: resolved so that an error of 30 % in the excursions' deposited weight would
    // be more than 3.5 combined standard errors. With 400 particles (8 %) and with 1000 (5 %,
    // 2.5 combined standard errors) such an error passed; with 2000 (3.8 %) it fails at 4.
    let injection = Injection::new(2000, SizeDistribution::Monodisperse { diameter: d }, 1000.0);
    let excursions = Excursions::in_wall_units(0.3, nu, CHANNEL_INNERMOST_LEVEL, 3.0, 1e4);
    let (plain, split) = compare((&scene, &settings), &injection, excursions, 6000, &[0, 1]);
    let combined = (plain.error / plain.value).hypot(split.error / split.value);
    assert!(combined < 0.3 / 3.5, "tau+ 10: a combined relative error of {combined}");
    assert!(z(plain, split) < 3.0, "tau+ 10: plain {plain:?}, excursions {split:?}");
}

/// Strong sweeps caught before the layer (the channel study's excursions from `tau+ = 3`)
/// keep the estimate unbiased: at `tau+ = 10`, where plain tracking resolves `V+` and the
/// sweeps carry the deposits, the two agree within three combined standard errors; and the
/// sweeps do start excursions of their own (more than the layer's crossings alone start).
#[test]
fn excursions_with_sweeps_agree_with_plain_tracking() {
    let ChannelStudy { scene, settings, .. } = ChannelStudy::default();
    let settings = RunSettings { average_from: 0.5 * settings.duration, ..settings };
    let nu = scene.air.kinematic_viscosity();
    let d = depo_tracker::correlations::diameter_for_tau_plus(10.0, 1000.0, &scene.air, 0.3).unwrap();
    let injection = Injection::new(400, SizeDistribution::Monodisperse { diameter: d }, 1000.0);
    let plain = run(&scene, &settings, &Injection { count: 3000, ..injection }).unwrap();
    let mut split = settings.clone();
    split.seed += 1;
    let layer_only = Excursions::in_wall_units(0.3, nu, CHANNEL_INNERMOST_LEVEL, 1.0, 1e4);
    let with_sweeps = Excursions { sweeps: Some(CHANNEL_SWEEPS), ..layer_only.clone() };
    let started = |excursions: Excursions| {
        let mut settings = split.clone();
        settings.excursions = Some(excursions.calibrated(&scene, &settings, &injection, 100, 1, 4).unwrap().0);
        let result = run(&scene, &settings, &injection).unwrap();
        let started: u32 = result.particles.iter().map(|p| p.excursions).sum();
        (result, started)
    };
    let (split, with) = started(with_sweeps);
    let (_, without) = started(layer_only);
    assert!(with > without + without / 10, "excursions started: {with} with sweeps, {without} without");
    let (a, b) = (plain.deposition_velocity(&[0, 1]), split.deposition_velocity(&[0, 1]));
    assert!(a.events > 150 && b.error < 0.1 * b.value, "plain {a:?}, excursions {b:?}");
    assert!(z(a, b) < 3.0, "tau+ 10 with sweeps: plain {a:?}, excursions {b:?}");
}

/// The excursions' coarse steps (the channel study's below `tau+ = 3`) give the scene's step's
/// `V+` where the branches hover in the viscous sublayer: at `tau+ = 0.3`, 1000 particles each
/// (independent seeds), within three combined standard errors. (Coarse steps of the first-order
/// scheme instead put `V+` 40 % high, four combined standard errors here.)
#[test]
fn coarse_excursion_steps_agree_with_the_scenes_step() {
    let ChannelStudy { scene, settings, .. } = ChannelStudy::default();
    let settings = RunSettings { average_from: 0.5 * settings.duration, ..settings };
    let nu = scene.air.kinematic_viscosity();
    let d = depo_tracker::correlations::diameter_for_tau_plus(0.3, 1000.0, &scene.air, 0.3).unwrap();
    let injection = Injection::new(1000, SizeDistribution::Monodisperse { diameter: d }, 1000.0);
    let fine = Excursions::in_wall_units(0.3, nu, CHANNEL_INNERMOST_LEVEL, 3.0, 1e5);
    let estimate = |excursions: Excursions, seed: u64| {
        let mut settings = RunSettings { seed, ..settings.clone() };
        settings.excursions = Some(excursions.calibrated(&scene, &settings, &injection, 250, 1, 4).unwrap().0);
        run(&scene, &settings, &injection).unwrap().deposition_velocity(&[0, 1])
    };
    let coarse = Excursions { coarse_factor: CHANNEL_COARSE_FACTOR, ..fine.clone() };
    let (a, b) = (estimate(fine, 11), estimate(coarse, 12));
    assert!(a.error < 0.1 * a.value && b.error < 0.1 * b.value, "scene's step {a:?}, coarse {b:?}");
    assert!(z(a, b) < 3.0, "tau+ 0.3: scene's step {a:?}, coarse steps {b:?}");
}

/// The same with the intermittent near-wall model, whose deposits at `tau+ = 3` come from
/// rare strong sweeps: the excursions' estimate against plain tracking, within three combined
/// standard errors, from the layer alone and with the sweeps caught before it (as the
/// channel study takes them at this `tau+`).
#[test]
fn excursions_agree_with_plain_tracking_under_the_intermittent_model() {
    let ChannelStudy { mut scene, settings, .. } = ChannelStudy::default();
    scene.near_wall = NearWall::Intermittent;
    let settings = RunSettings { average_from: 0.5 * settings.duration, ..settings };
    let nu = scene.air.kinematic_viscosity();
    let d = depo_tracker::correlations::diameter_for_tau_plus(3.0, 1000.0, &scene.air, 0.3).unwrap();
    let injection = Injection::new(2000, SizeDistribution::Monodisperse { diameter: d }, 1000.0);
    let plain = run(&scene, &settings, &Injection { count: 9000, ..injection }).unwrap();
    let a = plain.deposition_velocity(&[0, 1]);
    assert!(a.events > 100, "plain {a:?}");
    let layer = Excursions::in_wall_units(0.3, nu, CHANNEL_INNERMOST_LEVEL, 3.0, 1e5);
    let sweeps = Excursions { sampling: 1.0, sweeps: Some(CHANNEL_SWEEPS), ..layer.clone() };
    for (excursions, what) in [(layer, "layer"), (sweeps, "sweeps")] {
        let mut split = settings.clone();
        split.seed += 1;
        split.excursions = Some(excursions.calibrated(&scene, &split, &injection, 500, 1, 4).unwrap().0);
        let b = run(&scene, &split, &injection).unwrap().deposition_velocity(&[0, 1]);
        assert!(b.error < 0.2 * b.value, "{what}: plain {a:?}, excursions {b:?}");
        assert!(z(a, b) < 3.0, "tau+ 3, intermittent, {what}: plain {a:?}, excursions {b:?}");
    }
}

/// With excursions too, the same seed gives the same estimate, bit for bit, on one thread and
/// on two.
#[test]
fn excursions_do_not_depend_on_the_thread_count() {
    let RoomStudy { scene, mut settings, .. } = RoomStudy::default();
    settings.duration = 300.0;
    settings.average_from = 60.0;
    let nu = scene.air.kinematic_viscosity();
    settings.excursions = Some(Excursions::in_wall_units(0.01, nu, 0.05, 2.0, 4000.0));
    let injection = Injection::new(300, SizeDistribution::Monodisperse { diameter: 0.1e-6 }, 1000.0);
    let pool = |n| rayon::ThreadPoolBuilder::new().num_threads(n).build().unwrap();
    let one = pool(1).install(|| run(&scene, &settings, &injection).unwrap());
    let two = pool(2).install(|| run(&scene, &settings, &injection).unwrap());
    assert_eq!(one, two);
    assert!(one.particles.iter().any(|p| p.excursions > 0 && p.deposited.iter().sum::<f64>() > 0.0));
}

/// A ventilated room study reports the steady indoor/outdoor ratio `P a / (a + beta)` from its
/// own `beta`, with the error carried from `beta`'s; a penetration outside `[0, 1]` is an error
/// that names it.
#[test]
fn ventilated_room_reports_the_indoor_outdoor_ratio() {
    let mut study =
        RoomStudy { diameters: vec![3e-6], count: 200, penetration: 0.8, target_error: None, ..RoomStudy::default() };
    study.settings.duration = 600.0;
    study.scene.air_exchange = 2.0 / 3600.0;
    let point = &study.run(|_| {}).unwrap()[0];
    let (a, beta) = (study.scene.air_exchange, point.beta);
    let io = point.indoor_outdoor.expect("ventilated");
    // By hand: 0.8 a / (a + beta), and its derivative in beta times beta's error.
    assert!((io.value - 0.8 * a / (a + beta.value)).abs() < 1e-12, "{io:?} {beta:?}");
    assert!((io.error - 0.8 * a / (a + beta.value).powi(2) * beta.error).abs() < 1e-12);
    assert!(beta.value > 0.0 && io.value < 0.8 && io.error > 0.0);
    study.scene.air_exchange = 0.0;
    assert!(study.run(|_| {}).unwrap()[0].indoor_outdoor.is_none());
    study.penetration = 1.5;
    assert_eq!(study.run(|_| {}).unwrap_err().field, "penetration");
}

/// With a target error, a room study runs more particles where the first ones leave a figure
/// less resolved, and then resolves it: 3 um in a short run, floor and `beta` to 10 %.
#[test]
fn a_room_study_runs_more_particles_to_reach_its_target_error() {
    let mut study = RoomStudy {
        diameters: vec![3e-6],
        count: 100,
        target_error: Some(0.1),
        max_count: 3000,
        ..RoomStudy::default()
    };
    study.settings.duration = 600.0;
    let point = &study.run(|_| {}).unwrap()[0];
    assert!(point.particles > 100 && point.particles < 3000, "{}", point.particles);
    // The errors fall as 1 / sqrt(n); the margin covers their own spread.
    for e in [point.floor, point.beta] {
        assert!(e.error < 0.11 * e.value, "{} particles: {e:?}", point.particles);
    }
    // The ceiling takes no 3 um particle and has no figure to resolve: the particles after
    // the first start fewer excursions at its crossings.
    let sampling = point.class_sampling.expect("counted by excursions");
    assert!(sampling[1] < 1.0, "{sampling:?}");
    // Without a target, the first 100 alone, and less resolved.
    study.target_error = None;
    let first = &study.run(|_| {}).unwrap()[0];
    assert_eq!(first.particles, 100);
    assert!(first.floor.error / first.floor.value > point.floor.error / point.floor.value);
}

/// A recirculation filter removes particles at `eta_r(d) a_r` as the exhaust does at `a`: in a
/// room of mirror walls (no deposition, no settling) with 0.5 air changes per hour and 4 per hour through a
/// filter of 50 % at 1 um, the decay falls at 0.5 + 2 = 2.5 per hour (within 3 standard errors);
/// the indoor/outdoor ratio with half the exchange through an 80 % supply filter and `P = 0.9`
/// is, by hand, `(0.9 x 0.5 + 0.2 x 0.5) 0.5 / (2.5 + beta)` with the study's own (zero) `beta`.
#[test]
fn a_recirculation_filter_adds_its_removal_to_the_exhaust() {
    use depo_tracker::filtration::{FilterEfficiency, Filtration};
    use depo_tracker::WallBehaviour;
    let h = 1.0 / 3600.0;
    let mut study = RoomStudy {
        diameters: vec![1e-6],
        count: 2000,
        target_error: None,
        excursions: false,
        penetration: 0.9,
        ..RoomStudy::default()
    };
    // Mirror walls, and no settling or Brownian motion to pin a particle at a wall (one still
    // bouncing after many contacts in a step counts as come to rest there).
    study.scene = study.scene.with_walls(WallBehaviour::Reflect);
    study.scene.gravity = [0.0; 3];
    study.scene.brownian = false;
    study.settings.duration = 1800.0;
    study.scene.air_exchange = 0.5 * h;
    study.filtration = Filtration {
        supply_share: 0.5,
        supply_filter: FilterEfficiency::constant(0.8).unwrap(),
        recirculation: 4.0 * h,
        recirculation_filter: FilterEfficiency::new(vec![(0.3e-6, 0.2), (1e-6, 0.5), (3e-6, 0.9)]).unwrap(),
    };
    let point = &study.run(|_| {}).unwrap()[0];
    assert_eq!(point.beta.value, 0.0, "mirror walls take nothing: {:?} {:?}", point.deposited, point.balance);
    assert!((point.filter_removal - 2.0 * h).abs() < 1e-15);
    let fit = point.decay_fit.expect("a fit");
    let z = (fit.total.value - 2.5 * h) / fit.total.error;
    assert!(z.abs() < 3.0, "decay {} /h against 2.5 /h (z = {z})", fit.total.value / h);
    let ratio = point.indoor_outdoor.expect("ventilated").value;
    assert!((ratio - (0.9 * 0.5 + 0.2 * 0.5) * 0.5 / 2.5).abs() < 1e-12, "{ratio}");
    // Without the filter's removal in the exhaust the decay would be 0.5 /h: 5 times slower.
    assert!(fit.total.value > 2.0 * h);
}

/// The channel's wall function deposits, for each step a particle spends in its layer, the
/// Poisson chance `P = 1 - exp(-x)` of the correlation's rate, `x = v_d dt / y_w`: its `V+` is
/// Wood's times the layer's concentration over the mean, `C_w / C`, times `P / x`, exactly
/// (the derivation in docs/tracker.md). A layer of another thickness, a first-order chance
/// `x`, or a rate counted against another concentration fails it. Wood's value is worked out
/// here by hand (its Schmidt number within 0.3 % of the code's: the slip correction's
/// constants), and tracers (`tau+ = 0.1`) keep the bulk concentration in the layer: within
/// three standard errors and 5 %, the well-mixed dispersion model's residual near a wall
/// (docs/validation.md).
#[test]
fn the_channel_wall_function_deposits_wood_s_flux_on_the_layer_s_concentration() {
    let mut study =
        ChannelStudy { tau_plus: vec![0.1, 3.0, 30.0], count: 400, target_error: None, ..ChannelStudy::default() };
    study.scene.wall_function = Some(WallFunction::new(Correlation::Wood));
    let dt_plus = study.settings.dt * 0.3 * 0.3 / NU_BY_HAND;
    for p in study.run(|_| {}).unwrap() {
        let c = p.layer_concentration.expect("a wall function's layer concentration");
        let x = p.wood * dt_plus / WallFunction::LAYER_PLUS;
        let expected = p.wood * c.value * -(-x).exp_m1() / x;
        println!(
            "tau+ {}: V+ {:.4e} +- {:.1e}, Wood {:.4e} (by hand {:.4e}), C_w/C {:.3} +- {:.3}",
            p.tau_plus,
            p.v_plus.value,
            p.v_plus.error,
            p.wood,
            wood_by_hand(p.tau_plus),
            c.value,
            c.error
        );
        assert!((p.v_plus.value / expected - 1.0).abs() < 1e-9, "{} against {expected}", p.v_plus.value);
        assert!((p.wood / wood_by_hand(p.tau_plus) - 1.0).abs() < 3e-3, "{} {}", p.wood, wood_by_hand(p.tau_plus));
        assert!(p.v_plus.error < 0.1 * p.v_plus.value, "resolved from 400 particles: {:?}", p.v_plus);
        assert_eq!(p.excursions, None);
        if p.tau_plus < 1.0 {
            assert!((c.value - 1.0).abs() < 3.0 * c.error + 0.05, "tracers in the layer: {c:?}");
        }
    }
}

/// The wall function's particles deposit as its expected deposits say: the particles' own
/// deposits within the window (sampled with the layer's chance) give the same deposition
/// velocity as the expected ones the run counts, within three combined standard errors, at
/// `tau+ = 10` where most particles deposit. An arrival drawn with another chance than the
/// one counted, or a deposit recorded on the wrong wall, fails it.
#[test]
fn the_wall_function_s_particles_deposit_as_its_expected_deposits_say() {
    let ChannelStudy { mut scene, mut settings, .. } = ChannelStudy::default();
    scene.wall_function = Some(WallFunction::new(Correlation::Wood));
    settings.duration *= 0.5;
    settings.average_from = 0.2 * settings.duration;
    let d = depo_tracker::correlations::diameter_for_tau_plus(10.0, 1000.0, &scene.air, 0.3).unwrap();
    let injection = Injection::new(1500, SizeDistribution::Monodisperse { diameter: d }, 1000.0);
    let result = run(&scene, &settings, &injection).unwrap();
    let expected = result.deposition_velocity(&[0, 1]);
    // The sampled deposits' ratio estimate, with the delta method's error, by hand.
    let window = result.window;
    let samples: Vec<(f64, f64)> = result
        .records
        .iter()
        .zip(&result.particles)
        .map(|(r, p)| {
            let hit = matches!(r.fate, Fate::Deposited(0 | 1)) && r.time >= window[0] && r.time <= window[1];
            (f64::from(u8::from(hit)), p.exposure)
        })
        .collect();
    let (sx, se): (f64, f64) = samples.iter().fold((0.0, 0.0), |(a, b), (x, e)| (a + x, b + e));
    let ratio = sx / se;
    let n = samples.len() as f64;
    let spread: f64 = samples.iter().map(|(x, e)| (x - ratio * e).powi(2)).sum();
    let scale = result.volume / (result.walls[0].area + result.walls[1].area);
    let (sampled, sampled_error) = (ratio * scale, (spread * n / (n - 1.0)).sqrt() / se * scale);
    let band = 3.0 * expected.error.hypot(sampled_error);
    println!(
        "expected {:.4e} +- {:.1e}, sampled {sampled:.4e} +- {sampled_error:.1e} ({sx} deposits); band {band:.1e}",
        expected.value, expected.error
    );
    assert!(sx > 300.0, "{sx} deposits");
    assert!((expected.value - sampled).abs() < band, "{} against {sampled} +- {band}", expected.value);
    // The layer's arrivals are the walls' contacts: every one a capture on sinks.
    let contacts: u64 = result.tallies.iter().map(|t| t.contacts).sum();
    let captures: u64 = result.tallies.iter().map(|t| t.captures).sum();
    assert_eq!(contacts, captures);
    assert_eq!(captures as usize, result.records.iter().filter(|r| matches!(r.fate, Fate::Deposited(_))).count());
}

/// With a wall law, the wall function's arrivals are the law's to decide: a law that captures
/// at every speed deposits exactly as sinks do, one that captures at none deposits nothing
/// (and counts every arrival a rebound).
#[test]
fn a_wall_law_decides_what_the_wall_function_brings() {
    use depo_wall_model::{LawParams, WallLaw};
    let ChannelStudy { mut scene, mut settings, .. } = ChannelStudy::default();
    scene.wall_function = Some(WallFunction::new(Correlation::Wood));
    settings.duration *= 0.2;
    let injection = Injection::new(200, SizeDistribution::Monodisperse { diameter: 20e-6 }, 1000.0);
    let with = |vc: f64| {
        let mut scene = scene.clone();
        let params = LawParams { vc, ..*WallLaw::preset("li1997-sio2").unwrap().params() };
        scene = scene.with_walls(WallBehaviour::Law { law: WallLaw::new(params).unwrap(), size: None });
        run(&scene, &settings, &injection).unwrap()
    };
    let sink = run(&scene, &settings, &injection).unwrap();
    let sticky = with(1e3);
    assert_eq!(sink.records, sticky.records);
    assert_eq!(sink.deposition_velocity(&[0, 1]), sticky.deposition_velocity(&[0, 1]));
    assert!(sink.deposition_velocity(&[0, 1]).value > 0.0);
    let bouncy = with(1e-12);
    assert!(bouncy.records.iter().all(|r| !matches!(r.fate, Fate::Deposited(_))));
    assert_eq!(bouncy.deposition_velocity(&[0, 1]).value, 0.0);
    let t = bouncy.tallies[0];
    assert!(t.contacts > 10 && t.rebounds == t.contacts, "{t:?}");
}

/// A room's wall function takes Lai & Nazaroff (2000) by orientation: 1 um particles, well
/// mixed in the default room, deposit onto the floor, the walls and the ceiling at Lai &
/// Nazaroff's velocities within three standard errors and 15 % (the layers' concentration
/// over the room's mean: their tracers' within a few per cent, and 1 um settles 3.5e-5 m/s,
/// an exchange the near-floor turbulence keeps up with). Lai & Nazaroff's own values are
/// checked against hand-computed ones in their unit tests.
#[test]
fn the_room_wall_function_gives_lai_nazaroff_by_orientation() {
    let RoomStudy { mut scene, mut settings, .. } = RoomStudy::default();
    scene.wall_function = Some(WallFunction::new(Correlation::LaiNazaroff));
    settings.duration = 900.0;
    settings.average_from = 60.0;
    let injection = Injection::new(2000, SizeDistribution::Monodisperse { diameter: 1e-6 }, 1000.0);
    let result = run(&scene, &settings, &injection).unwrap();
    let ln = depo_tracker::correlations::LaiNazaroff::new(1e-6, 1000.0, &scene.air, 9.80665, 0.01);
    for (orientation, model) in
        [(Orientation::Floor, ln.floor), (Orientation::Wall, ln.wall), (Orientation::Ceiling, ln.ceiling)]
    {
        let v = result.deposition_velocity(&result.walls_facing(orientation));
        println!("{orientation:?}: {:.3e} +- {:.1e} against Lai & Nazaroff {model:.3e}", v.value, v.error);
        assert!((v.value / model - 1.0).abs() < 3.0 * v.error / model + 0.15, "{orientation:?}: {v:?} against {model}");
        assert!(v.error < 0.07 * v.value, "{orientation:?}: {v:?}");
    }
}

/// The vertical walls take their own correlation where the wall function names one, and only
/// they: with Wood's on the walls (0.75 of Lai & Nazaroff's for 1 um at u* = 1 cm/s), the
/// walls deposit at Wood's velocity within three standard errors and 8 % (the walls' layers
/// held 0.99 of the mean concentration in the test above) and away from Lai & Nazaroff's by
/// more than that, and the floor and ceiling still at Lai & Nazaroff's, within three
/// standard errors and 15 % as above.
#[test]
fn the_room_s_vertical_walls_take_their_own_correlation() {
    let RoomStudy { mut scene, mut settings, .. } = RoomStudy::default();
    scene.wall_function =
        Some(WallFunction { vertical: Some(Correlation::Wood), ..WallFunction::new(Correlation::LaiNazaroff) });
    settings.duration = 900.0;
    settings.average_from = 60.0;
    let injection = Injection::new(2000, SizeDistribution::Monodisperse { diameter: 1e-6 }, 1000.0);
    let result = run(&scene, &settings, &injection).unwrap();
    let ln = depo_tracker::correlations::LaiNazaroff::new(1e-6, 1000.0, &scene.air, 9.80665, 0.01);
    let nu = scene.air.kinematic_viscosity();
    let sc = depo_tracker::correlations::schmidt(1e-6, &scene.air);
    let aero = depo_tracker::Aerodynamics::new(1e-6, 1000.0, &scene.air, 9.80665);
    let wood = depo_tracker::correlations::wood(aero.relaxation_time * 1e-4 / nu, sc) * 0.01;
    let walls = result.deposition_velocity(&result.walls_facing(Orientation::Wall));
    println!(
        "walls: {:.3e} +- {:.1e} against Wood {wood:.3e}, Lai & Nazaroff {:.3e}",
        walls.value, walls.error, ln.wall
    );
    let band = |model: f64| 3.0 * walls.error / model + 0.08;
    assert!((walls.value / wood - 1.0).abs() < band(wood), "{walls:?} against {wood}");
    assert!((walls.value / ln.wall - 1.0).abs() > band(ln.wall), "{walls:?} against {}", ln.wall);
    for (orientation, model) in [(Orientation::Floor, ln.floor), (Orientation::Ceiling, ln.ceiling)] {
        let v = result.deposition_velocity(&result.walls_facing(orientation));
        println!("{orientation:?}: {:.3e} +- {:.1e} against {model:.3e}", v.value, v.error);
        assert!((v.value / model - 1.0).abs() < 3.0 * v.error / model + 0.15, "{orientation:?}: {v:?} against {model}");
    }
}

/// A furnished room with a supply and an exhaust runs with the wall function, and where the
/// resolved model is right (0.01 um, the diffusion regime, 1.05 of Lai & Nazaroff in the bare
/// room: docs/validation.md) the two give the same loss rate onto the room's walls within three
/// combined standard errors and 10 % (the two models' difference there, Lai & Nazaroff's
/// correlation against the resolved sublayer). The table's faces keep the resolved model in
/// both runs; the exhaust takes what reaches it in both.
#[test]
fn a_furnished_ventilated_room_runs_with_the_wall_function_as_the_resolved_model_in_the_diffusion_regime() {
    use depo_tracker::{Furnishing, Opening};
    let RoomStudy { mut scene, mut settings, .. } = RoomStudy::default();
    settings.duration = 1200.0;
    settings.average_from = 120.0;
    scene.furnishings = vec![Furnishing::new([1.0, 1.0, 0.7], [2.0, 1.6, 0.75]).named("table")];
    let q = 1.0 * 30.0 / 3600.0; // one air change an hour
    scene.openings =
        vec![Opening::supply(2, [1.5, 2.0], [0.3, 0.3], q), Opening::exhaust(3, [1.5, 0.5], [0.3, 0.3], q)];
    let injection = Injection::new(4000, SizeDistribution::Monodisperse { diameter: 0.01e-6 }, 1000.0);
    let walls: Vec<usize> = (0..6).collect();
    let resolved = run(&scene, &settings, &injection).unwrap().deposition_velocity(&walls);
    scene.wall_function = Some(WallFunction::new(Correlation::LaiNazaroff));
    let with = run(&scene, &settings, &injection).unwrap();
    let wall_function = with.deposition_velocity(&walls);
    let band = 3.0 * resolved.error.hypot(wall_function.error) + 0.1 * resolved.value;
    println!(
        "room walls' v_d: resolved {:.3e} +- {:.1e} [{}], wall function {:.3e} +- {:.1e}; band {band:.1e}",
        resolved.value, resolved.error, resolved.events, wall_function.value, wall_function.error
    );
    assert!(resolved.events > 100, "{resolved:?}");
    assert!((wall_function.value - resolved.value).abs() < band, "{wall_function:?} against {resolved:?}");
    // Particles still leave by the exhaust and reach the table.
    assert!(with.records.iter().any(|r| r.fate == Fate::Exhausted));
    assert!(with.records.iter().any(|r| matches!(r.fate, Fate::Deposited(s) if s >= 6)));
}

/// A size that settles out before the averaging window opens (50 um: 7.5 cm/s, 33 s for the
/// room's height) is averaged over the release from its start, closed or ventilated: finite
/// deposition velocities and loss rate, never 0 +- 0, with the times by which half and 90 %
/// had deposited (by hand: a uniform column settling at v_s empties its lower half first,
/// half deposited at H / (2 v_s) = 17 s and 90 % at 0.9 H / v_s = 30 s, the turbulence
/// spreading them a little); 20 um, which leaves some particles in the window, keeps the
/// study's window.
#[test]
fn a_size_that_settles_before_the_window_is_averaged_from_the_release() {
    for air_exchange in [0.0, 0.5 / 3600.0] {
        let mut study =
            RoomStudy { diameters: vec![20e-6, 50e-6], count: 500, target_error: None, ..RoomStudy::default() };
        study.scene.air_exchange = air_exchange;
        study.excursions = false;
        let points = study.run(|_| {}).unwrap();
        let (twenty, fifty) = (&points[0], &points[1]);
        assert!(twenty.averaged_from > 0.0, "{}", twenty.averaged_from);
        assert_eq!(fifty.averaged_from, 0.0);
        // Stokes settling, slip (1.003) left out: rho_p d^2 g / (18 mu).
        let v_s = 1000.0 * 50e-6_f64.powi(2) * 9.80665 / (18.0 * 1.81e-5);
        for p in [twenty, fifty] {
            assert!(
                p.floor.value.is_finite() && p.floor.value > 0.0 && p.floor.error < 0.15 * p.floor.value,
                "{:?}",
                p.floor
            );
            assert!(p.beta.value.is_finite() && p.beta.value > 0.0, "{:?}", p.beta);
            if air_exchange > 0.0 {
                let io = p.indoor_outdoor.expect("ventilated");
                assert!(io.value > 0.0 && io.value < 1.0, "{io:?}");
            }
        }
        let [half, most] = fifty.deposited_by.map(|t| t.expect("all deposit"));
        println!("50 um: half by {half} s, 90 % by {most} s; H / (2 v_s) = {:.1} s", 1.25 / v_s);
        assert!((half / (1.25 / v_s) - 1.0).abs() < 0.25, "{half}");
        assert!((most / (2.25 / v_s) - 1.0).abs() < 0.25, "{most}");
    }
}

/// The steady state under a continuous source, against independent calculations: between
/// mirrors with air exchange `a` nothing deposits and a particle leaves at the end of the
/// step in which its exponential exhaust time falls, so its mean time in the air is
/// `dt / (1 - exp(-a dt))` and `C_in/C_out` the penetration times `a` times that (no gravity,
/// on which a settling particle would come to rest on a mirror floor); 100 um
/// particles (Stokes settling `rho_p d^2 g / (18 mu)` = 0.30 m/s, far above the room's
/// turbulence) fall from a uniform start through the 2.5 m room, `E[T] = H / (2 v_s)`, all
/// of them onto the floor.
#[test]
fn the_steady_state_under_a_continuous_source_matches_independent_calculations() {
    let a = 2.0 / 3600.0;
    let mut study = RoomStudy { diameters: vec![1e-6], count: 2000, target_error: None, ..RoomStudy::default() };
    study.scene = study.scene.with_walls(WallBehaviour::Reflect);
    // Without gravity: a settling particle comes to rest on a mirror floor.
    study.scene.gravity = [0.0; 3];
    study.scene.air_exchange = a;
    study.settings.duration = 7200.0;
    study.excursions = false;
    study.penetration = 0.8;
    let p = &study.run(|_| {}).unwrap()[0];
    let steady = p.steady.expect("ventilated");
    let dt = study.settings.dt;
    let residence = dt / -(-a * dt).exp_m1();
    let io = p.steady_indoor_outdoor.unwrap();
    println!(
        "mirrors: E[T] {:.1} +- {:.1} s against {residence:.1}; C_in/C_out {:.4} +- {:.4} against {:.4}",
        steady.residence.value,
        steady.residence.error,
        io.value,
        io.error,
        0.8 * a * residence
    );
    assert!((steady.residence.value - residence).abs() < 3.0 * steady.residence.error, "{steady:?}");
    assert!((io.value - 0.8 * a * residence).abs() < 3.0 * io.error, "{io:?}");
    assert!((steady.fates[4] - 1.0).abs() < 1e-12, "all exhausted: {:?}", steady.fates);

    let coarse = RoomStudy {
        diameters: vec![100e-6],
        count: 500,
        target_error: None,
        excursions: false,
        ..RoomStudy::default()
    };
    let p = &coarse.run(|_| {}).unwrap()[0];
    let steady = p.steady.expect("deposition removes them");
    let v_s = 1000.0 * 100e-6_f64.powi(2) * 9.80665 / (18.0 * 1.81e-5);
    let by_hand = 2.5 / (2.0 * v_s);
    println!(
        "100 um: E[T] {:.3} +- {:.3} s against H / (2 v_s) = {by_hand:.3} s",
        steady.residence.value, steady.residence.error
    );
    assert!(
        (steady.residence.value / by_hand - 1.0).abs() < 3.0 * steady.residence.error / by_hand + 0.05,
        "{steady:?}"
    );
    assert!(steady.fates[0] > 0.99, "{:?}", steady.fates);
    // The floor's steady flux is the source's share onto it: v_d A C = S P(floor), C = S E[T] / V.
    let floor = steady.deposition_velocity[0];
    assert!((floor.value * 12.0 * steady.residence.value / 30.0 / steady.fates[0] - 1.0).abs() < 1e-12);
}

/// The channel's wall function against Sippola & Nazaroff's (2004) duct side-wall
/// measurements, at four tests' own friction velocity, particle size and density. The wall
/// function gives Wood's `V+` times the layer's concentration over the mean (checked here
/// again to 1e-9 with the chance's `P / x`, Wood within 0.2 % of a hand calculation at the
/// test's `tau+` and Schmidt number); beside the measurements its ratio is printed per test:
/// 0.03, 0.39, 0.85 and 3.0 for tests 3, 9, 14 and 16 (`tau+` 0.10, 0.50, 1.4 and 8.9). Where
/// the smooth-wall correlations are fitted to their regime (`tau+` >= 1) the ratio over
/// `C_w/C` (Wood's own) is within a factor 2 of the measurement, and `C_w/C` (1.3 and 2.0) is
/// the wall function's own departure; below, the measurements lie far above every smooth-wall
/// correlation (Wood is 0.03 of test 3), which a wall function on Wood inherits.
#[test]
fn the_wall_function_beside_sippola_and_nazaroff_s_duct_measurements() {
    use depo_tracker::measurements::SIPPOLA_NAZAROFF_2004;
    use depo_tracker::{Flow, Geometry};
    for number in [3, 9, 14, 16] {
        let t = SIPPOLA_NAZAROFF_2004[number - 1];
        let u = t.friction_velocity;
        let mut study = ChannelStudy { count: 300, target_error: None, density: t.density, ..ChannelStudy::default() };
        let unit = NU_BY_HAND / u;
        study.scene.geometry = Geometry::Channel { length: 1000.0 * unit, width: 300.0 * unit, height: 300.0 * unit };
        study.scene.flow = Flow::TurbulentChannel { friction_velocity: u };
        study.settings.dt = 0.2 * unit / u;
        study.settings.duration = 2000.0 * unit / u;
        study.scene.wall_function = Some(WallFunction::new(Correlation::Wood));
        let tau_plus = t.tau_plus(&study.scene.air);
        study.tau_plus = vec![tau_plus];
        let p = &study.run(|_| {}).unwrap()[0];
        assert!((p.diameter / t.diameter - 1.0).abs() < 1e-6, "the test's particle: {} m", p.diameter);
        // Wood by hand: Stokes-Einstein with Hinds' slip (mean free path 0.0664 um).
        let (mu, kt, lambda) = (1.81e-5, 1.380_649e-23 * 293.15, 0.0664e-6);
        let kn = lambda / t.diameter;
        let slip = 1.0 + kn * (2.34 + 1.05 * (-0.39 / kn).exp());
        let schmidt = NU_BY_HAND / (kt * slip / (3.0 * std::f64::consts::PI * mu * t.diameter));
        let wood = (0.057 * schmidt.powf(-2.0 / 3.0) + 4.5e-4 * tau_plus * tau_plus).min(0.13);
        assert!((p.wood / wood - 1.0).abs() < 2e-3, "test {number}: Wood {} against {wood} by hand", p.wood);
        let c = p.layer_concentration.unwrap();
        let x = p.wood * 0.2 / WallFunction::LAYER_PLUS;
        assert!((p.v_plus.value / (p.wood * c.value * -(-x).exp_m1() / x) - 1.0).abs() < 1e-9, "test {number}");
        let ratio = p.v_plus.value / t.v_plus;
        println!(
            "test {number}: tau+ {tau_plus:.3}, V+ {:.3e} +- {:.1e} (Wood {wood:.3e}, C_w/C {:.2}) against measured {:.1e}: ratio {ratio:.2}",
            p.v_plus.value, p.v_plus.error, c.value, t.v_plus
        );
        if tau_plus >= 1.0 {
            // The correlation it applies within a factor 2 of the measurement; the layer's
            // gathering of inertial particles (C_w/C) is the wall function's own departure.
            assert!((0.5..2.0).contains(&(ratio / c.value)), "test {number}: {ratio} over C_w/C {}", c.value);
        }
    }
}

/// In a well-mixed room the steady state under a continuous source of a tracer-like size
/// (0.01 um) deposits at the release's loss rate: the steady `beta`, each orientation's
/// steady deposition velocity times its area over the volume, agrees with the release
/// study's `beta` within three combined standard errors (ventilated at 4 air changes an hour,
/// so that most particles leave within the run and the steady figures rest on their own
/// histories, not on the late rates).
#[test]
fn a_tracer_s_steady_state_deposits_at_the_release_s_loss_rate() {
    let mut study = RoomStudy { diameters: vec![0.01e-6], count: 2000, target_error: None, ..RoomStudy::default() };
    study.scene.air_exchange = 4.0 / 3600.0;
    let p = &study.run(|_| {}).unwrap()[0];
    let steady = p.steady.unwrap();
    let areas = [12.0, 12.0, 2.0 * (4.0 + 3.0) * 2.5];
    let (value, variance) = steady
        .deposition_velocity
        .iter()
        .zip(areas)
        .fold((0.0, 0.0), |(v, e), (d, a)| (v + d.value * a / 30.0, e + (d.error * a / 30.0).powi(2)));
    let band = 3.0 * variance.sqrt().hypot(p.beta.error);
    println!(
        "steady beta {value:.3e} +- {:.1e} /s against the release's {:.3e} +- {:.1e}; beyond the run {:.0} %",
        variance.sqrt(),
        p.beta.value,
        p.beta.error,
        100.0 * steady.beyond_run
    );
    assert!(steady.beyond_run < 0.2, "{steady:?}");
    assert!((value - p.beta.value).abs() < band, "{value} against {:?}", p.beta);
}
