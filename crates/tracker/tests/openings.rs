//! Supply and exhaust openings (`depo_tracker::openings`): particles leave through the
//! exhaust, at the exchange rate `Q / V` in a well-mixed room, and the mass balance stays
//! exact.

use depo_tracker::{
    run, Drag, Fate, Flow, Furnishing, Geometry, Injection, Opening, Record, RunSettings, Scene, SizeDistribution,
    WallBehaviour,
};
use depo_wall_model::WallLaw;

mod common;
use common::{check_records, inside_a_box};

/// A 1 m room between mirrors, stirred hard (core 0.3 m/s, 1 s; eddy diffusivity 0.09 m^2/s,
/// mixing it in about a second; near-wall layers 3 cm and 10 cm thin at `u* = 3 cm/s`),
/// without gravity, with a supply and an exhaust of `q` (m^3/s) at the two ends of the
/// ceiling, 0.2 m square each.
fn stirred_room(q: f64) -> Scene {
    let mut scene = Scene::new(Geometry::Room { size: [1.0; 3] }).with_walls(WallBehaviour::Reflect);
    scene.flow = Flow::TurbulentRoom { friction_velocity: 0.03, core_rms: 0.3, core_time: 1.0, blend_length: 0.1 };
    scene.gravity = [0.0; 3];
    scene.openings =
        vec![Opening::supply(1, [0.2, 0.5], [0.2, 0.2], q), Opening::exhaust(1, [0.8, 0.5], [0.2, 0.2], q)];
    scene
}

/// The stirred room's run: 600 s of 10 ms steps, averaged from 60 s on.
fn stirred_settings() -> RunSettings {
    RunSettings { average_from: 60.0, ..RunSettings::new(0.01, 600.0) }
}

/// Tracers between mirrors in a well-mixed room leave through the exhaust alone, and the
/// airborne number decays at the exchange rate `Q / V` (here 0.0025 1/s, 9 air changes an
/// hour, so that the run is short), within three standard errors of the decay fit (2.4 %):
/// so neither `2 Q / V` nor no exhaust would pass (here 1.048 +- 0.024 times `Q / V`). The
/// room is well mixed to a few per cent (the damping of the fluctuations along its walls,
/// within 13 cm of each, keeps it from doing better); with the supply high on one wall and
/// the exhaust low on the opposite one the exhaust sees older air (it displaces the room's
/// air towards the exhaust). A room stirred less is mixed less (see `depo_tracker::openings`
/// and docs/tracker.md).
#[test]
fn the_airborne_number_decays_at_the_exchange_rate() {
    let q = 0.0025;
    let scene = stirred_room(q);
    let rate = q / 1.0; // Q / V, 1/s
    assert_eq!(scene.exchange_rate(), rate);
    let injection = Injection::new(4000, SizeDistribution::Monodisperse { diameter: 0.1e-6 }, 1000.0);
    let result = run(&scene, &stirred_settings(), &injection).unwrap();
    let b = result.balance();
    assert_eq!(b.deposited.iter().sum::<usize>() + b.escaped, 0, "{b:?}");
    assert_eq!(b.airborne + b.exhausted, 4000);
    let fit = result.decay_fit(&result.decay_curve(40), rate).expect("a fit");
    let (k, error) = (fit.total.value, fit.total.error);
    assert!(error > 0.0 && error < 0.03 * rate, "{fit:?}");
    assert!((k - rate).abs() < 3.0 * error, "decay rate {k} +- {error} against Q / V = {rate}");
    assert!((k - 2.0 * rate).abs() > 10.0 * error && k > 10.0 * error);
    // Every exhausted tracer left at the exhaust, at the ceiling.
    let exhaust = scene.openings[1];
    for r in result.records.iter().filter(|r| r.fate == Fate::Exhausted) {
        assert!(exhaust.holds(r.position) && (1.0 - r.position[2]) < 1e-6, "{r:?}");
    }
}

/// A small turbulent room with a table (a wall law on its faces) and a shelf (mirrors), an
/// exhaust low on one wall and two supplies, Brownian motion and finite-Reynolds drag.
/// 20 s of 10 ms steps.
fn furnished_room() -> (Scene, RunSettings, Injection) {
    let mut scene = Scene::new(Geometry::Room { size: [0.5, 0.4, 0.3] });
    scene.flow = Flow::indoor_room();
    scene.brownian = true;
    scene.drag = Drag::SchillerNaumann;
    let law = WallLaw::preset("dunn1995-stainless").unwrap();
    scene.walls[0] = WallBehaviour::Law { law, size: None };
    scene.furnishings = vec![
        Furnishing::new([0.1, 0.1, 0.05], [0.3, 0.25, 0.12])
            .named("table")
            .with_faces(WallBehaviour::Law { law, size: None }),
        Furnishing::new([0.35, 0.05, 0.02], [0.45, 0.35, 0.2]).with_faces(WallBehaviour::Reflect),
    ];
    // 0.02 m^3/s (20 air changes a minute in 0.06 m^3): plenty of exhaust in 20 s.
    scene.openings = vec![
        Opening::exhaust(3, [0.2, 0.08], [0.1, 0.06], 0.002),
        Opening::supply(1, [0.1, 0.1], [0.08, 0.08], 0.0012),
        Opening::supply(4, [0.25, 0.2], [0.1, 0.05], 0.0008),
    ];
    let injection = Injection::new(3000, SizeDistribution::LogNormal { median: 3e-6, geometric_sd: 2.5 }, 2000.0);
    (scene, RunSettings::new(0.01, 20.0), injection)
}

/// Injected = airborne + deposited per surface (walls and faces) + exhausted + escaped,
/// exactly, with deposits on the walls and the table and particles exhausted; the exhausted
/// left within the exhaust; no exhaust counts as a wall contact.
///
/// The balance counts the records by fate, so it holds by construction; what could fail is
/// checked besides ([`check_records`]): one record per particle, none escaped, each surface's
/// deposits as tallied at the contact, deposits on their surfaces, airborne particles in the
/// air, exhausted ones at the exhaust. And no particle starts or ends inside a box.
#[test]
fn mass_balance_is_exact_with_openings_and_furnishings() {
    let (scene, settings, injection) = furnished_room();
    let result = run(&scene, &settings, &injection).unwrap();
    check_records(&scene, &injection, &result);
    assert!(result.records.iter().all(|r| !inside_a_box(&scene, &Record { position: r.start, ..*r })));
    let b = result.balance();
    assert_eq!(b.airborne + b.deposited.iter().sum::<usize>() + b.escaped + b.exhausted, b.injected);
    assert_eq!(b.injected, 3000);
    let mass = b.airborne_mass + b.deposited_mass.iter().sum::<f64>() + b.escaped_mass + b.exhausted_mass;
    assert!((mass / b.injected_mass - 1.0).abs() < 1e-12);
    let on_table: usize = result.furnishing_faces(0).iter().map(|&w| b.deposited[w]).sum();
    let on_walls: usize = b.deposited[..6].iter().sum();
    assert!(on_table > 0 && on_walls > 0 && b.exhausted > 100 && b.airborne > 0, "{b:?}");
    for (w, t) in result.tallies.iter().enumerate() {
        assert_eq!((t.captures + t.resting) as usize, b.deposited[w], "surface {w}");
        assert_eq!(t.contacts, t.captures + t.rebounds, "surface {w}");
    }
    let exhaust = scene.openings[0];
    for r in result.records.iter().filter(|r| r.fate == Fate::Exhausted) {
        // At the x1 wall (its centre within its contact distance, a few radii), in the opening.
        assert!(exhaust.holds(r.position) && 0.5 - r.position[0] < 1e-3, "{r:?}");
        assert!(r.time > 0.0 && r.time <= 20.0);
    }
}

/// The same seed gives the same run with openings on one thread and on two.
#[test]
fn runs_with_openings_do_not_depend_on_the_thread_count() {
    let (scene, settings, injection) = furnished_room();
    let injection = Injection { count: 600, ..injection };
    let on = |threads| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        pool.install(|| run(&scene, &settings, &injection).unwrap())
    };
    let (one, two) = (on(1), on(2));
    assert_eq!(one.records, two.records);
}

/// Openings are checked where a run starts: the uniform exhaust with them, a channel,
/// unbalanced flows, an opening off its wall.
#[test]
fn scenes_with_bad_openings_are_refused() {
    let injection = Injection::new(10, SizeDistribution::Monodisperse { diameter: 1e-6 }, 1000.0);
    let run = |scene: &Scene, injection: &Injection| run(scene, &stirred_settings(), injection);
    let mut scene = stirred_room(0.0025);
    scene.air_exchange = 0.001;
    assert_eq!(run(&scene, &injection).unwrap_err().field, "air_exchange");
    let mut scene = stirred_room(0.0025);
    scene.openings[0].flow = 0.003;
    assert_eq!(run(&scene, &injection).unwrap_err().field, "openings");
    let mut scene = stirred_room(0.0025);
    scene.openings[1].center = [0.95, 0.5];
    assert_eq!(run(&scene, &injection).unwrap_err().field, "openings[1].center");
    let mut scene = stirred_room(0.0025);
    scene.geometry = Geometry::Channel { length: 1.0, width: 1.0, height: 1.0 };
    scene.walls.truncate(2);
    assert_eq!(run(&scene, &injection).unwrap_err().field, "openings");
}

/// A plate 15 cm under the exhaust of the stirred room: the mean flow goes round it to the
/// exhaust rather than through it, so its underside, which the flow heads for, takes
/// particles by the turbulence's diffusion, as its top does, not at the mean flow's speed
/// through the plate's footprint (`Q / A`, 2.1 cm/s here), with which a flow that ignored
/// the plate drove 0.1 um particles into it: the 95 % bound on the underside's deposition
/// velocity stays below 2 % of `Q / A`.
#[test]
fn the_mean_flow_goes_round_a_plate_under_the_exhaust() {
    let q = 0.0025;
    let mut scene = stirred_room(q);
    let settings = RunSettings { duration: 120.0, average_from: 20.0, ..stirred_settings() };
    scene.furnishings = vec![Furnishing::new([0.65, 0.3, 0.8], [0.95, 0.7, 0.85]).named("plate")];
    let injection = Injection::new(2000, SizeDistribution::Monodisperse { diameter: 0.1e-6 }, 1000.0);
    let result = run(&scene, &settings, &injection).unwrap();
    let faces = result.furnishing_faces(0);
    let bottom = result.deposition_velocity(&faces[..1]);
    let through = q / (0.3 * 0.4);
    // With the flow through the plate: 6.6e-3 +- 0.6e-3 m/s (129 deposits), 0.32 Q / A.
    assert!(bottom.upper_bound < 0.02 * through, "underside {bottom:?} against Q / A = {through}");
}

/// A particle beside an exhaust whose step read the opening's face velocity (half a step on,
/// with the midpoint scheme) leaves through the exhaust rather than depositing just past its
/// edge. In a 1 m room of indoor turbulence with sink walls, a supply and an exhaust of
/// 0.2 m square (face velocity 0.1 m/s) on opposite walls, none of the exhaust wall's
/// deposits lies within 5 mm outside the exhaust's edge; counted as deposits, such particles
/// lined the edges in proportion to the step (109 of the wall's 112 deposits here).
#[test]
fn no_deposits_line_the_exhaust_s_edges() {
    let q = 0.004;
    let mut scene = Scene::new(Geometry::Room { size: [1.0; 3] });
    scene.flow = Flow::indoor_room();
    scene.brownian = true;
    let settings = RunSettings { scheme: depo_tracker::Scheme::Midpoint, ..RunSettings::new(0.1, 600.0) };
    scene.openings =
        vec![Opening::supply(2, [0.5, 0.7], [0.2, 0.2], q), Opening::exhaust(3, [0.5, 0.3], [0.2, 0.2], q)];
    let injection = Injection::new(4000, SizeDistribution::Monodisperse { diameter: 0.3e-6 }, 1000.0);
    let result = run(&scene, &settings, &injection).unwrap();
    let exhaust = scene.openings[1];
    let [[y0, y1], [z0, z1]] = exhaust.bounds();
    let on_wall: Vec<[f64; 3]> =
        result.records.iter().filter(|r| r.fate == Fate::Deposited(3)).map(|r| r.position).collect();
    let near = |p: &[f64; 3]| {
        let outside = (y0 - p[1]).max(p[1] - y1).max(z0 - p[2]).max(p[2] - z1);
        (0.0..5e-3).contains(&outside)
    };
    let lining = on_wall.iter().filter(|p| near(p)).count();
    assert!(result.balance().exhausted > 100, "{:?}", result.balance());
    assert!(!on_wall.is_empty(), "the exhaust's wall takes deposits elsewhere: {:?}", result.balance());
    assert_eq!(lining, 0, "{lining} of the exhaust wall's {} deposits line the exhaust's edges", on_wall.len());
}
