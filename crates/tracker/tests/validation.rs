//! The tracker against known results: settling, Brownian diffusion, diffusion onto a floor,
//! the well-mixed condition of the dispersion model, mass conservation and reproducibility.

use depo_tracker::air::Air;
use depo_tracker::correlations::settling_diffusion_flux;
use depo_tracker::{
    run, Drag, Fate, Flow, Geometry, Injection, NearWall, RunSettings, Scene, Scheme, SizeDistribution, WallBehaviour,
};
use depo_wall_model::{SizeDependence, WallLaw};

fn mono(count: usize, diameter: f64) -> Injection {
    Injection::new(count, SizeDistribution::Monodisperse { diameter }, 1000.0)
}

/// A sphere's transport properties in air at 20 C and 1 atm, worked out here from Hinds,
/// *Aerosol Technology* (2nd ed., 1999), not from the code under test: air of viscosity
/// 1.81e-5 Pa s, density 1.204 kg/m^3 and mean free path 0.066 um (Appendix A4); the slip
/// correction of Eq. 3.20, `Cc = 1 + (lambda / d) (2.34 + 1.05 exp(-0.39 d / lambda))`;
/// Stokes' relaxation time `rho_p d^2 Cc / (18 mu)` (Eq. 3.29) and settling velocity `tau g`
/// less buoyancy (`1 - rho_air / rho_p`, 0.12 % at unit density); and the Stokes-Einstein
/// diffusivity `k T Cc / (3 pi mu d)` (Eq. 7.23) at 293.15 K.
#[derive(Clone, Copy, Debug)]
struct ByHand {
    slip: f64,
    relaxation_time: f64,
    settling: f64,
    diffusivity: f64,
}

fn hinds_by_hand(d: f64, rho_p: f64) -> ByHand {
    let (mu, rho_air, lambda, g, kt) = (1.81e-5, 1.204, 0.066e-6, 9.80665, 1.380_649e-23 * 293.15);
    let slip = 1.0 + lambda / d * (2.34 + 1.05 * (-0.39 * d / lambda).exp());
    let relaxation_time = rho_p * d * d * slip / (18.0 * mu);
    let settling = relaxation_time * g * (1.0 - rho_air / rho_p);
    let diffusivity = kt * slip / (3.0 * std::f64::consts::PI * mu * d);
    ByHand { slip, relaxation_time, settling, diffusivity }
}

/// depo carries Allen & Raabe's mean free path, 0.0673 um at 23 C, to 20 C (0.0664 um);
/// Hinds' Appendix A4 gives 0.066 um: the slip correction, and with it settling and
/// diffusivity, differs from [`hinds_by_hand`]'s by up to 0.6 % (at 0.01 um; 0.45 % at 0.1 um).
const MEAN_FREE_PATH_TOLERANCE: f64 = 6e-3;

/// The hand computation against Hinds' appendix table of the properties of unit-density
/// spheres at 20 C and 1 atm: within 1 % from 1 um up; below 1 um the table's slip corrections (2.85 at
/// 0.1 um, 22.2 at 0.01 um) are 2.7 and 3.4 % below Eq. 3.20's (2.928, 22.98), and its
/// settling velocity and diffusivities with them, so within 5 % there.
#[test]
fn hand_values_agree_with_hinds_table() {
    let close = |a: f64, b: f64, rel: f64| (a / b - 1.0).abs() < rel;
    for (d, slip, settling, diffusivity, rel) in [
        (0.01e-6, 22.2, None, Some(5.2e-8), 0.05),
        (0.1e-6, 2.85, Some(8.6e-7), Some(6.8e-10), 0.05),
        (1e-6, 1.15, Some(3.5e-5), Some(2.7e-11), 0.015),
        (10e-6, 1.016, Some(3.06e-3), None, 0.01),
    ] {
        let h = hinds_by_hand(d, 1000.0);
        println!("{d:e} m: Cc {:.4}, settling {:.3e} m/s, D {:.3e} m^2/s", h.slip, h.settling, h.diffusivity);
        assert!(close(h.slip, slip, rel), "{d}: Cc {} against {slip}", h.slip);
        assert!(settling.is_none_or(|v| close(h.settling, v, rel)), "{d}: {} against {settling:?}", h.settling);
        let d_ok = diffusivity.is_none_or(|v| close(h.diffusivity, v, rel));
        assert!(d_ok, "{d}: {} against {diffusivity:?}", h.diffusivity);
    }
}

/// Still air, floor only: the deposition velocity `J / C0` equals the Cunningham-corrected
/// settling velocity within 4 standard errors, from 0.1 to 50 um.
#[test]
fn settling_onto_the_floor_deposits_at_the_terminal_velocity() {
    for (d, drag) in [
        (0.1e-6, Drag::Stokes),
        (1e-6, Drag::Stokes),
        (10e-6, Drag::Stokes),
        (50e-6, Drag::Stokes),
        (50e-6, Drag::SchillerNaumann),
    ] {
        let stokes = hinds_by_hand(d, 1000.0).settling;
        let vs = match drag {
            Drag::Stokes => stokes,
            // Schiller & Naumann: `vs (1 + 0.15 Re^0.687) = vs_Stokes`, `Re = vs d / nu`,
            // solved by bisection here.
            Drag::SchillerNaumann => {
                let nu = 1.81e-5 / 1.204;
                let (mut lo, mut hi) = (0.0, stokes);
                for _ in 0..100 {
                    let mid = 0.5 * (lo + hi);
                    if mid * (1.0 + 0.15 * (mid * d / nu).powf(0.687)) < stokes {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                lo
            }
        };
        // A box tall enough that half the particles reach the floor in 400 steps.
        let duration = 100.0;
        let height = 2.0 * vs * duration + d;
        let mut scene = Scene::new(Geometry::Room { size: [10.0 * height, 10.0 * height, height] });
        let settings = RunSettings::new(duration / 400.0, duration);
        scene.drag = drag;
        let n = 20_000;
        let result = run(&scene, &settings, &mono(n, d)).unwrap();
        let deposited = result.balance().deposited[0];
        assert_eq!(result.balance().deposited.iter().sum::<usize>(), deposited, "only the floor collects");
        // Injected uniformly over the height left free by the radius: C0 = n / (A (H - d)).
        let v_d = deposited as f64 * (height - d) / (n as f64 * duration);
        let p = deposited as f64 / n as f64;
        let sigma = vs * (p * (1.0 - p) / n as f64).sqrt() / p;
        let band = 4.0 * sigma + (2e-3 + MEAN_FREE_PATH_TOLERANCE) * vs;
        println!("d {d:e} {drag:?}: v_d {v_d:.4e} against {vs:.4e} by hand, band {band:.1e}");
        assert!((v_d - vs).abs() < band, "d {d} {drag:?}: v_d {v_d} vs {vs} (sigma {sigma})");
    }
}

/// Brownian motion alone: the mean-square displacement per axis is `2 D t` within 2 %.
#[test]
fn brownian_mean_square_displacement_is_2dt() {
    let d = 0.1e-6;
    let aero = hinds_by_hand(d, 1000.0);
    let mut scene = Scene::new(Geometry::Room { size: [1.0; 3] });
    let settings = RunSettings::new(0.1, 10.0);
    scene.gravity = [0.0; 3];
    scene.brownian = true;
    let injection = mono(40_000, d).within([0.49; 3], [0.51; 3]);
    let result = run(&scene, &settings, &injection).unwrap();
    assert_eq!(result.balance().airborne, 40_000);
    let tau = aero.relaxation_time;
    let expected = 2.0 * aero.diffusivity * (10.0 - tau * (1.0 - (-10.0 / tau).exp()));
    for axis in 0..3 {
        let msd = result.records.iter().map(|r| (r.position[axis] - r.start[axis]).powi(2)).sum::<f64>() / 40_000.0;
        println!("axis {axis}: {msd:.4e} against {expected:.4e} by hand");
        assert!((msd / expected - 1.0).abs() < 0.02, "axis {axis}: {msd} against {expected}");
    }
}

/// Brownian diffusion with settling onto a floor from still air: the deposits follow the exact
/// solution of the advection-diffusion equation over an absorbing plane within 5 %.
#[test]
fn diffusion_onto_a_floor_follows_the_exact_solution() {
    let d = 0.05e-6;
    let aero = hinds_by_hand(d, 1000.0);
    let (duration, height) = (100.0, 0.01);
    let mut scene = Scene::new(Geometry::Room { size: [1.0, 1.0, height] });
    let settings = RunSettings::new(0.02, duration);
    scene.brownian = true;
    // Only the floor matters: the ceiling is as far as the diffusion length allows.
    let n = 40_000;
    let result = run(&scene, &settings, &mono(n, d).within([0.0; 3], [1.0, 1.0, height / 2.0])).unwrap();
    let deposited = result.balance().deposited[0] as f64;
    // Cumulative flux: integrate J/C0 over time (midpoint rule on a fine grid; J ~ t^-1/2 at 0).
    let steps = 200_000;
    let h = duration / steps as f64;
    let cumulative: f64 =
        (0..steps).map(|i| settling_diffusion_flux(aero.settling, aero.diffusivity, (i as f64 + 0.5) * h) * h).sum();
    let expected = cumulative * n as f64 / (height / 2.0);
    assert!((deposited / expected - 1.0).abs() < 0.05, "{deposited} deposits against {expected}");
}

/// The share of 10 000 tracers within 10 wall units of either wall of a turbulent channel
/// (reflecting walls, 300 wall units high) after 5000 steps of 0.2 wall time units, over its
/// uniform value, with the near-wall model `near_wall`, the well-mixed drift on or off, and the
/// step `scheme`.
fn channel_tracer_share(near_wall: NearWall, drift_correction: bool, scheme: Scheme) -> f64 {
    let air = Air::standard();
    let u_star = 0.3;
    let unit = air.kinematic_viscosity() / u_star;
    let height = 300.0 * unit;
    let dt = 0.2 * unit / u_star;
    let mut scene =
        Scene::new(Geometry::Channel { length: 0.1, width: 0.05, height }).with_walls(WallBehaviour::Reflect);
    let mut settings = RunSettings::new(dt, 1000.0 * dt * 5.0);
    scene.gravity = [0.0; 3];
    scene.flow = Flow::TurbulentChannel { friction_velocity: u_star };
    scene.near_wall = near_wall;
    scene.drift_correction = drift_correction;
    settings.scheme = scheme;
    let tracers = run(&scene, &settings, &mono(10_000, 1e-9)).unwrap();
    assert_eq!(tracers.balance().airborne, 10_000);
    let near = tracers.records.iter().filter(|r| r.position[2] < 10.0 * unit || r.position[2] > height - 10.0 * unit);
    near.count() as f64 / tracers.records.len() as f64 / (20.0 / 300.0)
}

/// The dispersion model's drift keeps tracers well mixed in a turbulent channel: the share of
/// tracers within 10 wall units of a wall stays what it was. Without the drift they pile up in
/// the quiet layer at the wall, which the same check catches.
#[test]
fn tracers_stay_well_mixed_only_with_the_drift_correction() {
    let share = channel_tracer_share(NearWall::Gaussian, true, Scheme::Exponential);
    assert!((share - 1.0).abs() < 0.15, "with drift: {share} of uniform");
    let share = channel_tracer_share(NearWall::Gaussian, false, Scheme::Exponential);
    assert!(share > 1.5, "without drift the wall layer should collect tracers: {share} of uniform");
}

/// The same with the intermittent near-wall model: its drift for the heavy-tailed
/// distribution keeps the tracers well mixed too, and without it they pile up at the wall.
#[test]
fn tracers_stay_well_mixed_with_the_intermittent_model() {
    let share = channel_tracer_share(NearWall::Intermittent, true, Scheme::Exponential);
    assert!((share - 1.0).abs() < 0.15, "with drift: {share} of uniform");
    let share = channel_tracer_share(NearWall::Intermittent, false, Scheme::Exponential);
    assert!(share > 1.5, "without drift the wall layer should collect tracers: {share} of uniform");
    // Only a channel has the model's profiles.
    let mut room = Scene::new(Geometry::Room { size: [1.0; 3] });
    let room_settings = RunSettings::new(0.01, 1.0);
    room.flow = Flow::indoor_room();
    room.near_wall = NearWall::Intermittent;
    let err = run(&room, &room_settings, &mono(10, 1e-6)).unwrap_err();
    assert!(err.to_string().contains("near_wall"), "{err}");
}

/// The midpoint step keeps the channel's tracers well mixed too, under either near-wall model
/// (1.01 of uniform with the Gaussian one, 0.99 with the intermittent one; 4 % is one
/// standard error of the share).
#[test]
fn the_midpoint_step_keeps_channel_tracers_well_mixed_under_either_near_wall_model() {
    for near_wall in [NearWall::Gaussian, NearWall::Intermittent] {
        let share = channel_tracer_share(near_wall, true, Scheme::Midpoint);
        assert!((share - 1.0).abs() < 0.15, "{near_wall:?}: {share} of uniform");
    }
}

fn busy_room() -> (Scene, RunSettings, Injection) {
    let mut scene = Scene::new(Geometry::Room { size: [0.5, 0.4, 0.3] });
    let settings = RunSettings::new(0.01, 20.0);
    scene.flow = Flow::indoor_room();
    scene.brownian = true;
    scene.drag = Drag::SchillerNaumann;
    let law = WallLaw::preset("dunn1995-stainless").unwrap();
    scene.walls[0] = WallBehaviour::Law { law, size: Some(SizeDependence::new(8.6e-6, 1.51).unwrap()) };
    scene.walls[3] = WallBehaviour::Reflect;
    let injection = Injection::new(3000, SizeDistribution::LogNormal { median: 2e-6, geometric_sd: 2.5 }, 2000.0);
    (scene, settings, injection)
}

/// Airborne + deposited + escaped = injected, exactly, in every run; masses to rounding.
#[test]
fn mass_is_conserved() {
    let (scene, settings, injection) = busy_room();
    let result = run(&scene, &settings, &injection).unwrap();
    let b = result.balance();
    assert_eq!(b.airborne + b.deposited.iter().sum::<usize>() + b.escaped, b.injected);
    assert_eq!(b.injected, 3000);
    let mass = b.airborne_mass + b.deposited_mass.iter().sum::<f64>() + b.escaped_mass;
    assert!((mass / b.injected_mass - 1.0).abs() < 1e-12);
    assert!(b.deposited.iter().sum::<usize>() > 0 && b.airborne > 0);
    // The tallies agree with the records: every deposit was a capture.
    for (w, t) in result.tallies.iter().enumerate() {
        assert_eq!((t.captures + t.resting) as usize, b.deposited[w], "wall {w}");
        assert_eq!(t.contacts, t.captures + t.rebounds, "wall {w}: no escapes here");
    }
    assert_eq!(result.tallies[3].captures, 0, "the mirror deposits nothing");
    assert!(result.records.iter().all(|r| r.position.iter().all(|c| c.is_finite())));
}

/// With ventilation too: injected = airborne + deposited + escaped + exhausted, exactly; and
/// ventilation leaves a closed room's random numbers alone (the particles it does not exhaust
/// end where they did without it).
#[test]
fn mass_is_conserved_with_ventilation() {
    let (mut scene, settings, injection) = busy_room();
    scene.air_exchange = 0.02;
    let result = run(&scene, &settings, &injection).unwrap();
    let b = result.balance();
    assert_eq!(b.airborne + b.deposited.iter().sum::<usize>() + b.escaped + b.exhausted, b.injected);
    let mass = b.airborne_mass + b.deposited_mass.iter().sum::<f64>() + b.escaped_mass + b.exhausted_mass;
    assert!((mass / b.injected_mass - 1.0).abs() < 1e-12);
    // About 1 - exp(-0.02 * 20) = 33 % exhausted, less what deposits first.
    assert!(b.exhausted > 600 && b.deposited.iter().sum::<usize>() > 0 && b.airborne > 0, "{b:?}");
    scene.air_exchange = 0.0;
    let closed = run(&scene, &settings, &injection).unwrap();
    for (open, closed) in result.records.iter().zip(&closed.records) {
        if open.fate != Fate::Exhausted {
            assert_eq!(open, closed);
        } else {
            assert!(open.time <= closed.time);
        }
    }
}

/// Ventilation alone (mirror walls, still air): the airborne share after `t` is `exp(-a t)`,
/// within 4 binomial standard errors at five times, and particles leave at the ends of steps.
#[test]
fn ventilation_alone_decays_at_the_exchange_rate() {
    let a = 0.01;
    let mut scene = Scene::new(Geometry::Room { size: [4.0, 3.0, 2.5] }).with_walls(WallBehaviour::Reflect);
    let settings = RunSettings::new(2.0, 250.0);
    scene.gravity = [0.0; 3];
    scene.air_exchange = a;
    let n = 20_000;
    let result = run(&scene, &settings, &mono(n, 1e-6)).unwrap();
    for t in [10.0, 50.0, 100.0, 180.0, 250.0] {
        // Exhausted at `t` or before, or still in the air.
        let still = result.records.iter().filter(|r| r.fate == Fate::Airborne || r.time > t + 1e-9).count();
        let still = still as f64 / n as f64;
        let expected = (-a * t).exp();
        let se = (expected * (1.0 - expected) / n as f64).sqrt();
        assert!((still - expected).abs() < 4.0 * se, "t = {t}: {still} against {expected}");
    }
    let b = result.balance();
    assert_eq!(b.airborne + b.exhausted, n);
    for r in result.records.iter().filter(|r| r.fate == Fate::Exhausted) {
        assert!((r.time / 2.0 - (r.time / 2.0).round()).abs() < 1e-12 && r.time > 0.0, "{r:?}");
    }
}

/// A run carried on to more particles is the run of them all, particle for particle, with
/// and without excursions; and the same wall tallies.
#[test]
fn a_run_carried_on_is_the_run_of_all_its_particles() {
    let (scene, settings, injection) = busy_room();
    let whole = run(&scene, &settings, &injection).unwrap();
    let first = run(&scene, &settings, &Injection { count: 1100, ..injection }).unwrap();
    let more = depo_tracker::run_more(&scene, &settings, &injection, first).unwrap();
    assert_eq!(more.records, whole.records);
    assert_eq!(more.particles, whole.particles);
    for (a, b) in more.tallies.iter().zip(&whole.tallies) {
        assert_eq!((a.contacts, a.captures, a.rebounds, a.resting), (b.contacts, b.captures, b.rebounds, b.resting));
    }
    let mut split = settings.clone();
    split.average_from = 5.0;
    split.excursions = Some(depo_tracker::Excursions::in_wall_units(0.01, 1.5e-5, 0.05, 2.0, 2000.0));
    let small = Injection { count: 300, ..injection };
    let whole = run(&scene, &split, &small).unwrap();
    let first = run(&scene, &split, &Injection { count: 100, ..small }).unwrap();
    let more = depo_tracker::run_more(&scene, &split, &small, first).unwrap();
    assert_eq!(more.particles, whole.particles);
    assert!(more.particles.iter().any(|p| p.excursions > 0));
    assert_eq!(
        depo_tracker::run_more(&scene, &split, &Injection { count: 50, ..small }, more).unwrap_err().field,
        "count"
    );
}

/// The same seed gives the same run, bit for bit, on one thread and on two.
#[test]
fn results_do_not_depend_on_the_thread_count() {
    let (scene, settings, injection) = busy_room();
    let pool = |n| rayon::ThreadPoolBuilder::new().num_threads(n).build().unwrap();
    let one = pool(1).install(|| run(&scene, &settings, &injection).unwrap());
    let two = pool(2).install(|| run(&scene, &settings, &injection).unwrap());
    assert_eq!(one, two);
    let mut other = settings.clone();
    other.seed += 1;
    assert_ne!(run(&scene, &other, &injection).unwrap().records, one.records, "another seed, another run");
    assert!(one.records.iter().any(|r| matches!(r.fate, Fate::Deposited(_))));
}

/// Bad scenes are errors naming the field.
#[test]
fn scene_errors_name_the_field() {
    let mut scene = Scene::new(Geometry::Room { size: [1.0; 3] });
    let mut settings = RunSettings::new(0.01, 1.0);
    let particles = mono(10, 1e-6);
    scene.lift = true;
    assert_eq!(run(&scene, &settings, &particles).unwrap_err().field, "lift");
    scene.lift = false;
    settings.dt = 0.0;
    assert_eq!(run(&scene, &settings, &particles).unwrap_err().field, "dt");
    settings.dt = 0.01;
    scene.flow = Flow::TurbulentChannel { friction_velocity: 0.3 };
    assert_eq!(run(&scene, &settings, &particles).unwrap_err().field, "flow");
    scene.flow = Flow::Still;
    assert_eq!(run(&scene, &settings, &mono(10, 0.6)).unwrap_err().field, "particles.diameter");
    // A diameter in the wrong unit (1 for 1 um) in a room big enough for it: an error, not a
    // run of a 1 m ball.
    let big = Scene::new(Geometry::Room { size: [4.0, 3.0, 2.5] });
    let big_settings = RunSettings::new(0.01, 1.0);
    let err = run(&big, &big_settings, &mono(10, 1.0)).unwrap_err();
    assert_eq!(err.field, "particles.diameter");
    assert!(err.to_string().contains("at most 1 mm"), "{err}");
    assert!(run(&big, &big_settings, &mono(10, 1e-3)).is_ok());
    assert_eq!(run(&scene, &settings, &mono(0, 1e-6)).unwrap_err().field, "particles.count");
    let err = run(&scene, &settings, &mono(10, 1e-6).with_velocity([f64::NAN, 0.0, 0.0])).unwrap_err();
    assert_eq!(err.field, "particles.velocity");
    assert!(err.to_string().contains("must be finite"));
}

/// Lognormal injection: the sizes have the asked count median and geometric standard deviation.
#[test]
fn lognormal_sizes_have_their_median_and_spread() {
    let scene = Scene::new(Geometry::Room { size: [1.0; 3] });
    let settings = RunSettings::new(0.01, 0.0);
    let injection = Injection::new(20_000, SizeDistribution::LogNormal { median: 1e-6, geometric_sd: 2.0 }, 1000.0);
    let result = run(&scene, &settings, &injection).unwrap();
    let mut logs: Vec<f64> = result.records.iter().map(|r| r.diameter.ln()).collect();
    logs.sort_by(f64::total_cmp);
    let median = logs[logs.len() / 2].exp();
    let mean = logs.iter().sum::<f64>() / logs.len() as f64;
    let gsd = (logs.iter().map(|l| (l - mean).powi(2)).sum::<f64>() / (logs.len() - 1) as f64).sqrt().exp();
    assert!((median / 1e-6 - 1.0).abs() < 0.03, "median {median}");
    assert!((gsd / 2.0 - 1.0).abs() < 0.02, "gsd {gsd}");
    assert!(result.records.iter().all(|r| r.diameter >= 1e-6 / 32.0 && r.diameter <= 32e-6));
}

/// Several contacts in one step: a heavy particle crossing a 2 mm gap between mirrors about five
/// times per step ends where the unfolded straight path, folded back into the gap, puts it.
#[test]
fn several_contacts_per_step_follow_the_folded_path() {
    let (gap, d) = (2e-3, 100e-6);
    let r = d / 2.0;
    let mut scene = Scene::new(Geometry::Room { size: [gap, 1.0, 1.0] }).with_walls(WallBehaviour::Reflect);
    let settings = RunSettings::new(0.01, 0.1);
    scene.gravity = [0.0; 3];
    // Dense enough that drag barely slows it: tau ~ 3e4 s.
    let injection =
        Injection::new(50, SizeDistribution::Monodisperse { diameter: d }, 1e9).with_velocity([1.0, 0.0, 0.0]);
    let result = run(&scene, &settings, &injection).unwrap();
    let tau = hinds_by_hand(d, 1e9).relaxation_time;
    let travelled = tau * (1.0 - (-0.1 / tau).exp());
    let width = gap - 2.0 * r;
    for rec in &result.records {
        assert_eq!(rec.fate, Fate::Airborne);
        let unfolded = (rec.start[0] - r + travelled).rem_euclid(2.0 * width);
        let folded = if unfolded > width { 2.0 * width - unfolded } else { unfolded };
        assert!((rec.position[0] - (r + folded)).abs() < 1e-9, "{} against {}", rec.position[0], r + folded);
    }
    // About 0.1 m / 1.9 mm = 52 reflections per particle.
    let contacts = result.tallies[2].contacts + result.tallies[3].contacts;
    assert!((contacts as f64 / 50.0 - travelled / width).abs() < 1.0, "{contacts}");
}

/// The dispersion model keeps tracers well mixed in a room too, where the step is short against
/// the turbulence's gradients: between mirrors, the share of tracers within 2 cm of the walls
/// across each axis stays uniform within 10 % (the drift of each component scaled with its
/// damping along the other walls: unscaled, 0.71 of uniform along x) (at 0.01 s; at the
/// default 0.05 s, a million tracers stay within 3-5 % of uniform there, see
/// `MAX_STEP_GRADIENT`). A step too long for the gradients (a core of 0.5 m/s
/// blended over 0.25 m, `dt` = 0.05 s, which left 1.6 times uniform there) is refused.
#[test]
fn tracers_stay_well_mixed_in_a_room_and_long_steps_are_refused() {
    let mut scene = Scene::new(Geometry::Room { size: [4.0, 3.0, 2.5] }).with_walls(WallBehaviour::Reflect);
    let mut settings = RunSettings::new(0.01, 300.0);
    scene.gravity = [0.0; 3];
    scene.flow = Flow::indoor_room();
    let n = 20_000;
    let result = run(&scene, &settings, &mono(n, 1e-9)).unwrap();
    let band = 0.02;
    // Along each axis: the walls across it (and, through the tangential damping, the others).
    for (axis, length) in [4.0, 3.0, 2.5].into_iter().enumerate() {
        let near = result.records.iter().filter(|r| r.position[axis] < band || r.position[axis] > length - band).count()
            as f64;
        let expected = n as f64 * 2.0 * band / length;
        assert!((near / expected - 1.0).abs() < 0.1, "axis {axis}: {near} within {band} m against {expected}");
    }
    scene.flow = Flow::TurbulentRoom { friction_velocity: 0.01, core_rms: 0.5, core_time: 2.0, blend_length: 0.25 };
    settings.dt = 0.05;
    let err = run(&scene, &settings, &mono(10, 1e-9)).unwrap_err();
    assert_eq!(err.field, "dt");
    assert!(err.to_string().contains("too long for the turbulence"));
}

/// The midpoint scheme, which reads the turbulence half a step on, keeps tracers well mixed
/// where the default step, which reads it at the step's start, does not: between mirrors in a
/// room whose core turbulence (0.5 m/s, blended into the near-wall layer over 0.25 m) makes
/// `dt |d sigma/dy|` 0.05 at `dt = 0.025 s`, the largest the default step accepts, the share of
/// tracers within 0.1 m of floor and ceiling after 100 s is within 10 % of uniform with the
/// midpoint step and over 15 % above it with the default (here 0.96 and 1.24, each +- 3.5 %;
/// over 300 s with 20000 tracers 1.03 and 1.31). At twice the step the default is refused and
/// the midpoint accepted.
#[test]
fn the_midpoint_step_keeps_tracers_well_mixed_where_the_default_does_not() {
    let share = |scheme: Scheme, dt: f64| {
        let mut scene = Scene::new(Geometry::Room { size: [4.0, 3.0, 2.5] }).with_walls(WallBehaviour::Reflect);
        let mut settings = RunSettings::new(dt, 100.0);
        scene.gravity = [0.0; 3];
        scene.flow = Flow::TurbulentRoom { friction_velocity: 0.01, core_rms: 0.5, core_time: 2.0, blend_length: 0.25 };
        settings.scheme = scheme;
        let n = 10_000;
        let result = run(&scene, &settings, &mono(n, 1e-9))?;
        let band = 0.1;
        let near = result.records.iter().filter(|r| r.position[2] < band || r.position[2] > 2.5 - band).count();
        Ok::<f64, depo_tracker::SceneError>(near as f64 / (n as f64 * 2.0 * band / 2.5))
    };
    let midpoint = share(Scheme::Midpoint, 0.025).unwrap();
    assert!((midpoint - 1.0).abs() < 0.1, "midpoint: {midpoint} of uniform");
    let start = share(Scheme::Exponential, 0.025).unwrap();
    assert!(start > 1.15, "default step: {start} of uniform");
    assert_eq!(share(Scheme::Exponential, 0.05).unwrap_err().field, "dt");
    assert!(share(Scheme::Midpoint, 0.05).is_ok());
}

/// Contacts are found at step ends, so a Brownian excursion to the wall and back within one
/// step would be missed; the continuity correction (`CONTINUITY_CORRECTION`) takes contacts
/// that much before the wall. The most diffusive particles of the room, 0.01 um (`sqrt(2 D dt)`
/// = 73 um per step at the room's 0.05 s), released within 3 mm of a floor, deposit as the
/// exact solution of the diffusion equation has them within 3 % (about two standard errors)
/// at 0.05 s and at a ten times longer step (both 1.0 % low; without the correction 5.9 % low
/// at 0.05 s).
#[test]
fn brownian_contacts_between_step_ends_are_not_missed() {
    let d = 0.01e-6;
    let aero = hinds_by_hand(d, 1000.0);
    let (duration, layer) = (10.0, 3e-3);
    let n = 20_000;
    let deposited = |dt: f64| {
        let mut scene = Scene::new(Geometry::Room { size: [1.0, 1.0, 0.1] });
        let settings = RunSettings::new(dt, duration);
        scene.brownian = true;
        let result = run(&scene, &settings, &mono(n, d).within([0.0; 3], [1.0, 1.0, layer])).unwrap();
        result.balance().deposited[0] as f64
    };
    // Exact: the cumulative flux of the diffusion-settling solution times the initial
    // concentration (the far ceiling plays no part: sqrt(2 D t) is 1 mm).
    let steps = 200_000;
    let h = duration / steps as f64;
    let cumulative: f64 =
        (0..steps).map(|i| settling_diffusion_flux(aero.settling, aero.diffusivity, (i as f64 + 0.5) * h) * h).sum();
    let expected = cumulative * n as f64 / (layer - d / 2.0);
    let at_room_step = deposited(0.05);
    assert!((at_room_step / expected - 1.0).abs() < 0.03, "dt 0.05 s: {at_room_step} against {expected}");
    let long = deposited(0.5);
    assert!((long / expected - 1.0).abs() < 0.03, "dt 0.5 s: {long} against {expected}");
}
