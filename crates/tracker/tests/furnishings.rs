//! Furnishings: boxes inside a room whose faces are surfaces (`depo_tracker::furnishing`).

use depo_tracker::{
    run, Drag, Fate, Flow, Furnishing, Geometry, Injection, Orientation, Record, RunSettings, Scene, SizeDistribution,
    WallBehaviour,
};
use depo_wall_model::WallLaw;

mod common;
use common::{check_records, inside_a_box};

fn mono(count: usize, diameter: f64) -> Injection {
    Injection::new(count, SizeDistribution::Monodisperse { diameter }, 1000.0)
}

/// A small turbulent, ventilated room with a table (a wall law on its faces) and a shelf
/// (mirrors), Brownian motion and finite-Reynolds drag; 20 s of 10 ms steps.
fn furnished_room() -> (Scene, RunSettings, Injection) {
    let mut scene = Scene::new(Geometry::Room { size: [0.5, 0.4, 0.3] });
    scene.flow = Flow::indoor_room();
    scene.brownian = true;
    scene.drag = Drag::SchillerNaumann;
    scene.air_exchange = 0.02;
    let law = WallLaw::preset("dunn1995-stainless").unwrap();
    scene.furnishings = vec![
        Furnishing::new([0.1, 0.1, 0.05], [0.3, 0.25, 0.12])
            .named("table")
            .with_faces(WallBehaviour::Law { law, size: None }),
        Furnishing::new([0.35, 0.05, 0.02], [0.45, 0.35, 0.2]).with_faces(WallBehaviour::Reflect),
    ];
    scene.furnishings[0].faces[0] = WallBehaviour::Sink;
    let injection = Injection::new(3000, SizeDistribution::LogNormal { median: 3e-6, geometric_sd: 2.5 }, 2000.0);
    (scene, RunSettings::new(0.01, 20.0), injection)
}

/// Injected = airborne + deposited per surface (walls and faces) + escaped + exhausted, exactly,
/// with deposits on both the room's walls and the table's faces; the tallies agree with the
/// records; no particle starts or ends inside a box; the mirror shelf deposits nothing.
///
/// The balance counts the records by fate, so it holds by construction; what could fail is
/// checked besides ([`check_records`]): one record per particle, none escaped, each surface's
/// deposits as tallied at the contact, deposits on their surfaces, airborne particles in the
/// air. And the uniform exhaust: a particle leaves at the end of the step its exhaust time
/// falls in, which the closed room (the same run without ventilation, the same random
/// numbers otherwise) shows: every particle not exhausted ends as it did there, every
/// exhausted one leaves at the end of a step before it would have deposited or the run
/// ended there; and of the particles still airborne at the end of the closed run, the share
/// exhausted is `1 - exp(-a T)` within 4 binomial standard errors (the exhaust times are
/// exponential, and drawn apart from the motion).
#[test]
fn mass_balance_is_exact_with_furnishings_and_ventilation() {
    let (scene, settings, injection) = furnished_room();
    let result = run(&scene, &settings, &injection).unwrap();
    check_records(&scene, &injection, &result);
    let b = result.balance();
    assert_eq!(result.walls.len(), 6 + 12);
    assert_eq!(b.deposited.len(), 18);
    assert_eq!(b.airborne + b.deposited.iter().sum::<usize>() + b.escaped + b.exhausted, b.injected);
    assert_eq!(b.injected, 3000);
    let mass = b.airborne_mass + b.deposited_mass.iter().sum::<f64>() + b.escaped_mass + b.exhausted_mass;
    assert!((mass / b.injected_mass - 1.0).abs() < 1e-12);
    let on_table: usize = result.furnishing_faces(0).iter().map(|&w| b.deposited[w]).sum();
    let on_walls: usize = b.deposited[..6].iter().sum();
    assert!(on_table > 0 && on_walls > 0 && b.exhausted > 0 && b.airborne > 0, "{b:?}");
    assert!(b.deposited[6 + 1] > 0, "the table top collects settling particles: {:?}", &b.deposited[6..12]);
    for (w, t) in result.tallies.iter().enumerate() {
        assert_eq!((t.captures + t.resting) as usize, b.deposited[w], "surface {w}");
        assert_eq!(t.contacts, t.captures + t.rebounds, "surface {w}: no escapes here");
    }
    // Particles settling onto the mirror shelf's top come to rest there (still bouncing after
    // `MAX_CONTACTS` contacts in one step), as on a mirror floor; nothing is captured.
    let shelf = result.furnishing_faces(1);
    assert!(shelf
        .iter()
        .all(|&w| result.tallies[w].captures == 0 && b.deposited[w] == result.tallies[w].resting as usize));
    assert!(shelf.iter().map(|&w| result.tallies[w].rebounds).sum::<u64>() > 0, "the shelf is hit");
    for r in &result.records {
        assert!(!inside_a_box(&scene, r), "{r:?}");
        let start = Record { position: r.start, ..*r };
        assert!(!inside_a_box(&scene, &start), "{r:?}");
        if let Fate::Deposited(w) = r.fate {
            // A deposit touches its surface.
            let wall = result.walls[w];
            let gap = (r.position[wall.axis] - wall.position).abs();
            assert!((gap - 0.5 * r.diameter).abs() < 1e-12, "{r:?} on {wall:?}");
        }
    }
    // The air's volume is the room's less the boxes'.
    let volume = 0.5 * 0.4 * 0.3 - 0.2 * 0.15 * 0.07 - 0.1 * 0.3 * 0.18;
    assert!((result.volume - volume).abs() < 1e-15);
    assert!((scene.free_volume() - volume).abs() < 1e-15);
    let area = 2.0 * (0.5 * 0.4 + 0.5 * 0.3 + 0.4 * 0.3)
        + 2.0 * (0.2 * 0.15 + 0.2 * 0.07 + 0.15 * 0.07)
        + 2.0 * (0.1 * 0.3 + 0.1 * 0.18 + 0.3 * 0.18);
    assert!((result.surface_to_volume() - area / volume).abs() < 1e-9 * area / volume);
    assert!((scene.surface_to_volume() - area / volume).abs() < 1e-9 * area / volume);
    assert_eq!(scene.surface_name(7), "table.top");
    assert_eq!(scene.surface_name(14), "box2.x0");
    assert_eq!(scene.surface_name(0), "floor");
    // The table top faces up with the floor, but the room's floor figures keep to the room.
    assert_eq!(result.surfaces_facing(Orientation::Floor), vec![0, 7, 13]);
    assert_eq!(result.walls_facing(Orientation::Floor), vec![0]);
    // The uniform exhaust against the closed room.
    let closed = run(&Scene { air_exchange: 0.0, ..scene.clone() }, &settings, &injection).unwrap();
    assert_eq!(closed.balance().exhausted, 0);
    let (mut stayed, mut left) = (0usize, 0usize);
    for (open, closed) in result.records.iter().zip(&closed.records) {
        assert_eq!(open.start, closed.start);
        if open.fate == Fate::Exhausted {
            assert!(open.time == open.steps as f64 * settings.dt && open.steps < closed.steps, "{open:?} {closed:?}");
        } else {
            assert_eq!(open, closed);
        }
        if closed.fate == Fate::Airborne {
            stayed += 1;
            left += usize::from(open.fate == Fate::Exhausted);
        }
    }
    let expected = 1.0 - (-scene.air_exchange * result.duration).exp();
    let share = left as f64 / stayed as f64;
    let se = depo_tracker::binomial_error(expected, stayed);
    assert!(stayed > 1000 && (share - expected).abs() < 4.0 * se, "{left} of {stayed} exhausted, {expected} expected");
}

/// The same seed gives the same furnished run on one thread and on two.
#[test]
fn furnished_runs_do_not_depend_on_the_thread_count() {
    let (scene, settings, injection) = furnished_room();
    let injection = Injection { count: 600, ..injection };
    let on = |threads| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        pool.install(|| run(&scene, &settings, &injection).unwrap())
    };
    let (one, two) = (on(1), on(2));
    assert_eq!(one.records, two.records);
    assert_eq!(one.particles, two.particles);
}

/// Still air: particles released above a table settle onto its top at the Stokes settling
/// velocity with Cunningham's slip correction, computed here by hand, within 4 standard
/// errors: the deposition velocity `J / C0` onto the top face.
#[test]
fn settling_onto_a_table_top_deposits_at_the_settling_velocity() {
    // Standard air: 20 C, 1.81e-5 Pa s, 1.204 kg/m^3; mean free path 0.066432 um (the
    // aerosol reference 0.0673 um at 23 C carried to 20 C by Sutherland's law; Hinds: 0.066).
    let (mu, rho_air, lambda, g): (f64, f64, f64, f64) = (1.81e-5, 1.204, 0.066_432e-6, 9.806_65);
    for d in [3e-6, 10e-6] {
        let rho_p = 1000.0;
        // Hinds (1999) Eq. 3.20.
        let kn = lambda / d;
        let slip = 1.0 + kn * (2.34 + 1.05 * (-0.39 / kn).exp());
        let vs = (rho_p - rho_air) * g * d * d * slip / (18.0 * mu);
        let duration = 100.0;
        let h = 2.0 * vs * duration;
        let (top, low) = (0.4, [0.3, 0.3, 0.3]);
        let mut scene = Scene::new(Geometry::Room { size: [1.0, 1.0, top + 3.0 * h] });
        let settings = RunSettings::new(duration / 400.0, duration);
        scene.furnishings = vec![Furnishing::new(low, [0.7, 0.7, top])];
        let n = 20_000;
        // Over the table's top, up to `h` above it; the first `r` is inside the grown box and
        // never drawn: the release is uniform over a height `h - r`.
        let injection = mono(n, d).within([0.3, 0.3, top], [0.7, 0.7, top + h]);
        let result = run(&scene, &settings, &injection).unwrap();
        let b = result.balance();
        let deposited = b.deposited[6 + 1];
        assert_eq!(b.deposited.iter().sum::<usize>(), deposited, "only the top collects");
        assert!(result.records.iter().all(|r| r.start[2] >= top + 0.5 * d));
        let v_d = deposited as f64 * (h - 0.5 * d) / (n as f64 * duration);
        let p = deposited as f64 / n as f64;
        let sigma = vs * (p * (1.0 - p) / n as f64).sqrt() / p;
        assert!((v_d - vs).abs() < 4.0 * sigma + 2e-3 * vs, "d {d}: v_d {v_d} against {vs} (sigma {sigma})");
    }
}

/// Tracers between mirrors, with a mirror box in the room, stay well mixed: after 60 s the
/// share within 5 cm of the box's faces (about 550 of 10000 tracers) stays uniform within
/// 10 % and the share within 2 cm of the floor within 15 % (0.98 and 0.95) with the
/// dispersion model's drift; without it the floor's share is 2.2 times uniform (the drift is
/// what keeps them mixed, at the box's faces as at the walls). Tangential factors taken from
/// the distance to the nearest surface, box faces included, jump at the edges of a box's
/// shadow, and left the floor's share at 0.80.
#[test]
fn a_reflecting_box_leaves_tracers_well_mixed() {
    let mut scene = Scene::new(Geometry::Room { size: [1.0, 1.0, 1.0] }).with_walls(WallBehaviour::Reflect);
    let settings = RunSettings::new(0.01, 60.0);
    scene.gravity = [0.0; 3];
    scene.flow = Flow::indoor_room();
    let (low, high) = ([0.3, 0.3, 0.3], [0.7, 0.7, 0.6]);
    scene.furnishings = vec![Furnishing::new(low, high).with_faces(WallBehaviour::Reflect)];
    let n = 10_000;
    let band = 0.05;
    let shell = Furnishing::new(low.map(|l| l - band), high.map(|h| h + band));
    let expected = n as f64 * (shell.volume() - scene.furnishings[0].volume()) / scene.free_volume();
    // Within 2 cm of the room's floor (below the box).
    let floor_expected = n as f64 * 0.02 / scene.free_volume();
    let shares = |scene: &Scene| {
        let result = run(scene, &settings, &mono(n, 1e-9)).unwrap();
        assert_eq!(result.balance().airborne, n);
        let count =
            |near: &dyn Fn(&[f64; 3]) -> bool| result.records.iter().filter(|r| near(&r.position)).count() as f64;
        (count(&|x| shell.holds(*x, 0.0)) / expected, count(&|x| x[2] < 0.02) / floor_expected)
    };
    let (mixed, floor) = shares(&scene);
    assert!((mixed - 1.0).abs() < 0.1, "{mixed} times uniform within {band} m of the box");
    assert!((floor - 1.0).abs() < 0.15, "{floor} times uniform within 2 cm of the floor");
    // Without the drift the layers collect the tracers, most where the turbulence falls
    // fastest: within 2 cm of the room's floor.
    scene.drift_correction = false;
    let (_, drifting) = shares(&scene);
    assert!(drifting > 1.5, "without the drift the tracers should gather at the floor: {drifting}");
}

/// Furnishings are checked: inside the room, not overlapping, leaving free air to inject
/// into.
#[test]
fn furnishing_errors_name_the_field() {
    let base = Scene::new(Geometry::Room { size: [2.0, 2.0, 2.0] });
    let settings = RunSettings::new(0.01, 1.0);
    let run = |scene: &Scene, injection: &Injection| run(scene, &settings, injection);
    let injection = mono(10, 1e-6);
    let with = |boxes: Vec<Furnishing>| Scene { furnishings: boxes, ..base.clone() };
    let err = run(&with(vec![Furnishing::new([0.0, 0.5, 0.5], [1.0, 1.0, 1.0])]), &injection).unwrap_err();
    assert_eq!(err.field, "furnishings[0].low");
    let err = run(&with(vec![Furnishing::new([0.5, 0.5, 0.5], [1.0, 2.5, 1.0])]), &injection).unwrap_err();
    assert_eq!(err.field, "furnishings[0].high");
    let err = run(&with(vec![Furnishing::new([0.5, 0.5, 0.5], [0.4, 1.0, 1.0])]), &injection).unwrap_err();
    assert_eq!(err.field, "furnishings[0].high");
    let overlapping = vec![Furnishing::new([0.5; 3], [1.0; 3]), Furnishing::new([0.9; 3], [1.5; 3])];
    let err = run(&with(overlapping), &injection).unwrap_err();
    assert_eq!(err.field, "furnishings[1].low");
    let touching = vec![Furnishing::new([0.5; 3], [1.0; 3]), Furnishing::new([1.0, 0.5, 0.5], [1.5, 1.0, 1.0])];
    assert!(run(&with(touching), &injection).is_ok());
    let boxed = with(vec![Furnishing::new([0.5; 3], [1.0; 3])]);
    let err = run(&boxed, &injection.within([0.6; 3], [0.9; 3])).unwrap_err();
    assert_eq!(err.field, "particles.region");
    let err = run(&boxed, &injection.within([0.7; 3], [0.7; 3])).unwrap_err();
    assert_eq!(err.field, "particles.region");
    let mut channel = boxed.clone();
    channel.geometry = Geometry::Channel { length: 2.0, width: 2.0, height: 2.0 };
    channel.walls.truncate(2);
    assert_eq!(run(&channel, &injection).unwrap_err().field, "furnishings");
}

/// The near-wall turbulence forms at a box's faces as at the room's walls: ultrafine
/// particles (Brownian and turbulent diffusion through the same near-wall layer) deposit onto
/// a box's vertical faces at the deposition velocity of the room's vertical walls, within 3
/// standard errors; onto its top as onto the floor. Were the faces' distances left out of
/// the turbulence, the core's fluctuations would reach the faces and deposit there tens of
/// times faster.
#[test]
fn box_faces_take_the_walls_deposition_velocity() {
    let mut scene = Scene::new(Geometry::Room { size: [1.0, 1.0, 1.0] });
    scene.flow = Flow::indoor_room();
    scene.brownian = true;
    let settings = RunSettings { average_from: 60.0, ..RunSettings::new(0.05, 600.0) };
    scene.furnishings = vec![Furnishing::new([0.3, 0.3, 0.3], [0.7, 0.7, 0.7])];
    let result = run(&scene, &settings, &mono(4000, 0.01e-6)).unwrap();
    let walls = result.walls_facing(Orientation::Wall);
    let sides: Vec<usize> = result.furnishing_faces(0)[2..].to_vec();
    let (room, boxed) = (result.deposition_velocity(&walls), result.deposition_velocity(&sides));
    let combined = room.error.hypot(boxed.error);
    assert!(room.events > 100 && boxed.events > 20, "{room:?} {boxed:?}");
    assert!((room.value - boxed.value).abs() < 3.0 * combined, "walls {room:?}, box sides {boxed:?}");
    let (floor, top) = (result.deposition_velocity(&[0]), result.deposition_velocity(&[7]));
    assert!((floor.value - top.value).abs() < 3.0 * floor.error.hypot(top.error), "floor {floor:?}, top {top:?}");
}

/// Near-wall excursions start at a box's faces as at the walls (their gap is to the nearest
/// wall or box), and their estimate is unbiased there too: ultrafine particles' deposition
/// velocity onto a box's faces, and the loss rate, agree with plain tracking's within 3
/// combined standard errors, with excursions' deposits on every face of the box.
#[test]
fn excursions_agree_with_plain_tracking_at_a_box() {
    excursions_agree_with_plain_tracking_in_a_box_room([1.0; 4]);
}

/// Fewer or more excursions per crossing by the class of surface crossed (the floor's
/// halved, the ceiling's doubled, the walls' quartered, the box's halved), each weighing one
/// over its own sampling, keep the estimate unbiased; and the excursions' tallies by class of
/// crossing add up to the particle's deposits, with every class's excursions stepped.
#[test]
fn excursions_sampled_by_class_of_crossing_agree_with_plain_tracking() {
    let split = excursions_agree_with_plain_tracking_in_a_box_room([0.5, 2.0, 0.25, 0.5]);
    for p in &split.particles {
        let by_class: f64 = p.class_deposits.iter().flatten().sum();
        assert!((by_class - p.deposited_total()).abs() <= 1e-12 * p.deposited_total(), "{p:?}");
    }
    for c in 0..4 {
        assert!(split.particles.iter().any(|p| p.class_steps[c] > 0), "class {c}: no steps");
        assert!(
            split.particles.iter().any(|p| p.class_deposits[c][c] > 0.0),
            "class {c}: no deposit on its own surface"
        );
    }
}

/// The loss rate's per-particle influences (what the decay fit's comparison pairs with)
/// count a box's deposits as the loss rate does: they sum to zero and give its error, with
/// a good share of the deposits on the table's top.
#[test]
fn the_loss_rate_s_influences_count_the_furnishings() {
    let mut scene = Scene::new(Geometry::Room { size: [1.0, 1.0, 1.0] });
    scene.furnishings = vec![Furnishing::new([0.2, 0.2, 0.3], [0.8, 0.8, 0.4])];
    let result = run(&scene, &RunSettings::new(0.05, 60.0), &mono(2000, 10e-6)).unwrap();
    let on_top = result.balance().deposited[6 + 1];
    assert!(on_top > 100, "{on_top} on the top");
    let (influences, beta) = (result.loss_rate_influences().unwrap(), result.loss_rate());
    assert!(influences.iter().sum::<f64>().abs() < 1e-12 * beta.value);
    assert!((depo_tracker::delta_error(&influences) / beta.error - 1.0).abs() < 1e-12, "{beta:?}");
}

/// Plain tracking of ultrafine particles in a 1 m room around a box, against excursions with
/// `class_sampling` ([`depo_tracker::Excursions::class_sampling`]): the box's faces and the
/// loss rate within 3 combined standard errors. The excursions' run.
fn excursions_agree_with_plain_tracking_in_a_box_room(class_sampling: [f64; 4]) -> depo_tracker::Run {
    let mut scene = Scene::new(Geometry::Room { size: [1.0, 1.0, 1.0] });
    scene.flow = Flow::indoor_room();
    scene.brownian = true;
    let settings = RunSettings { average_from: 60.0, ..RunSettings::new(0.05, 600.0) };
    scene.furnishings = vec![Furnishing::new([0.3, 0.3, 0.3], [0.7, 0.7, 0.7])];
    let injection = mono(400, 0.01e-6);
    let plain = run(&scene, &settings, &Injection { count: 4000, ..injection }).unwrap();
    let mut split = settings.clone();
    split.seed += 1;
    let nu = scene.air.kinematic_viscosity();
    let excursions = depo_tracker::Excursions::in_wall_units(0.01, nu, 0.05, 3.0, 16_000.0);
    let calibrated = excursions.calibrated(&scene, &split, &injection, 100, 1, 8).unwrap().0;
    split.excursions = Some(depo_tracker::Excursions { class_sampling, ..calibrated });
    let split = run(&scene, &split, &injection).unwrap();
    let faces = plain.furnishing_faces(0);
    for f in &faces {
        assert!(split.particles.iter().any(|p| p.events_on(*f) > 0), "face {f}: no excursion deposit");
    }
    let z = |a: depo_tracker::Estimate, b: depo_tracker::Estimate| (a.value - b.value).abs() / a.error.hypot(b.error);
    let (a, b) = (plain.deposition_velocity(&faces), split.deposition_velocity(&faces));
    assert!(a.events >= 40 && b.error < 0.15 * b.value, "plain {a:?}, excursions {b:?}");
    assert!(z(a, b) < 3.0, "box faces: plain {a:?}, excursions {b:?}");
    let (a, b) = (plain.loss_rate(), split.loss_rate());
    assert!(z(a, b) < 3.0, "beta: plain {a:?}, excursions {b:?}");
    split
}

/// A furnished, ventilated room study with excursions: per furnishing its faces' figures, the
/// release's exact balance with its part on the furnishings, and the surface-to-volume ratio.
#[test]
fn a_furnished_room_study_reports_each_furnishing() {
    let mut study = depo_tracker::studies::RoomStudy::default();
    study.scene.geometry = Geometry::Room { size: [1.5, 1.0, 1.0] };
    study.settings.duration = 120.0;
    study.scene.air_exchange = 2.0 / 3600.0;
    study.scene.furnishings = vec![Furnishing::new([0.2, 0.2, 0.4], [0.8, 0.8, 0.45]).named("table")];
    study.diameters = vec![5e-6];
    study.count = 300;
    study.target_error = None;
    let points = study.run(|_| {}).unwrap();
    let p = &points[0];
    assert!(p.excursions.is_some(), "counted by excursions");
    assert_eq!(p.furnishings.len(), 1);
    let table = &p.furnishings[0];
    assert_eq!(table.name, "table");
    assert!((table.area - 2.0 * (0.36 + 0.03 + 0.03)).abs() < 1e-12);
    assert!(table.faces[1].events > 0 && table.faces[1].value > 0.0, "the top collects: {table:?}");
    assert_eq!(table.deposited.0, table.face_deposited.iter().map(|f| f.0).sum::<usize>());
    let on_room: usize = p.deposited.iter().map(|d| d.0).sum();
    assert_eq!(on_room + table.deposited.0 + p.balance.exhausted + p.balance.airborne, p.balance.injected);
    let volume = 1.5 - 0.6 * 0.6 * 0.05;
    let area = 2.0 * (1.5 + 1.5 + 1.0) + table.area;
    assert!((p.surface_to_volume - area / volume).abs() < 1e-9);
    assert_eq!(p.maps.len(), 12);
    assert_eq!(p.maps[7].iter().sum::<u32>() as usize, table.face_deposited[1].0);
}

/// The air exchange alone removes particles from a furnished room whose every surface, the
/// room's walls and both boxes' faces, is a mirror: the airborne number decays at the
/// exchange rate `a` (the decay fit's rate within 3.5 of its standard errors, which are
/// below 5 % of `a`, so that neither no exhaust nor twice it would pass), nothing deposits
/// on any surface (by the records and by the surfaces' own tallies at contact, though the
/// particles do hit the boxes' faces), and every particle ends exhausted or airborne.
/// Ultrafine particles (Brownian motion takes them to the surfaces through the near-wall
/// layers) without gravity in indoor turbulence, so that none comes to rest on a mirror
/// floor.
#[test]
fn the_air_exchange_alone_empties_a_furnished_room_of_mirrors() {
    let a = 0.01;
    let mut scene = Scene::new(Geometry::Room { size: [1.0, 0.8, 0.6] }).with_walls(WallBehaviour::Reflect);
    let settings = RunSettings::new(0.05, 150.0);
    scene.gravity = [0.0; 3];
    scene.flow = Flow::indoor_room();
    scene.brownian = true;
    scene.air_exchange = a;
    scene.furnishings = vec![
        Furnishing::new([0.1, 0.1, 0.2], [0.5, 0.4, 0.25]).named("table").with_faces(WallBehaviour::Reflect),
        Furnishing::new([0.6, 0.5, 0.1], [0.9, 0.7, 0.5]).with_faces(WallBehaviour::Reflect),
    ];
    let n = 2000;
    let injection = mono(n, 0.01e-6);
    let result = run(&scene, &settings, &injection).unwrap();
    check_records(&scene, &injection, &result);
    let b = result.balance();
    assert_eq!(b.deposited.len(), 6 + 12);
    assert!(b.deposited.iter().all(|&d| d == 0), "{b:?}");
    for (w, t) in result.tallies.iter().enumerate() {
        assert!(t.captures == 0 && t.resting == 0 && t.rebounds == t.contacts, "surface {w}: {t:?}");
    }
    for k in 0..2 {
        let hits: u64 = result.furnishing_faces(k).iter().map(|&w| result.tallies[w].contacts).sum();
        assert!(hits > 0, "box {k} is hit");
    }
    assert!(result.records.iter().all(|r| matches!(r.fate, Fate::Exhausted | Fate::Airborne)));
    assert_eq!(b.airborne + b.exhausted, n);
    let fit = result.decay_fit(&result.decay_curve(30), a).expect("a fit");
    let (k, error) = (fit.total.value, fit.total.error);
    assert!(error > 0.0 && error < 0.05 * a, "{fit:?}");
    assert!((k - a).abs() < 3.5 * error, "decay rate {k} +- {error} against a = {a}");
}
