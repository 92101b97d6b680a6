//! A cancelled run stops within a second however long each of its particles' runs would be:
//! the particles in hand look at the token as they step, not only between chunks of
//! particles. One scene per particle loop: one particle at a time, four side by side, with
//! near-wall excursions, with a wall function.

use std::time::{Duration, Instant};

use depo_tracker::studies::RoomStudy;
use depo_tracker::{
    run, Cancel, Correlation, Excursions, Injection, RunSettings, Scene, Scheme, SizeDistribution, WallBehaviour,
    WallFunction,
};

/// The default room's turbulence and Brownian motion for `duration` s, its walls mirrors so
/// that every particle stays in the air to the end: each particle's run costs its steps,
/// whatever its fate would have been.
fn endless_room(duration: f64) -> (Scene, RunSettings) {
    let RoomStudy { mut scene, mut settings, .. } = RoomStudy::default();
    scene.walls = vec![WallBehaviour::Reflect; scene.walls.len()];
    settings.duration = duration;
    settings.average_from = 0.0;
    (scene, settings)
}

/// The scenes, one per particle loop, by name.
fn scenes(duration: f64) -> Vec<(&'static str, (Scene, RunSettings))> {
    let one_at_a_time = endless_room(duration); // the midpoint scheme: one particle at a time
    let mut side_by_side = endless_room(duration);
    side_by_side.1.scheme = Scheme::Exponential;
    side_by_side.1.dt = 0.05; // the default scheme's longest step in this turbulence
    let mut excursions = endless_room(duration);
    let nu = excursions.0.air.kinematic_viscosity();
    excursions.1.excursions = Some(Excursions::in_wall_units(0.01, nu, 0.05, 2.0, 4000.0));
    let mut wall_function = endless_room(duration);
    wall_function.0.wall_function = Some(WallFunction::new(Correlation::LaiNazaroff));
    vec![
        ("one particle at a time", one_at_a_time),
        ("four side by side", side_by_side),
        ("excursions", excursions),
        ("wall function", wall_function),
    ]
}

/// `count` particles of 0.2 um (the mirrors keep any size in the air).
fn injection(count: usize) -> Injection {
    Injection::new(count, SizeDistribution::Monodisperse { diameter: 0.2e-6 }, 1000.0)
}

/// A 1000-hour run of 16 particles (one chunk of 8 per core on two cores) cancelled after
/// 0.2 s ends within a second of the cancel with the cancelled error. Its premise, checked
/// first: a chunk, tracked to its end, would take several seconds (a particle's cost per
/// step from one particle's runs over a hundredth and a two-hundredth of the time, the
/// preparation they share left out), so that stopping only between chunks would fail.
#[test]
fn a_cancelled_run_of_long_particle_runs_stops_within_a_second() {
    const DURATION: f64 = 3.6e6;
    let timed = |(scene, settings): &(Scene, RunSettings)| {
        let start = Instant::now();
        let one = run(scene, settings, &injection(1)).unwrap();
        assert_eq!(one.records[0].steps as f64, (settings.duration / settings.dt).round(), "not airborne to the end");
        start.elapsed().as_secs_f64()
    };
    let [half, short, long] = [200.0, 100.0, 1.0].map(|share| scenes(DURATION / share));
    for (((name, half), (_, short)), (_, long)) in half.into_iter().zip(short).zip(long) {
        let chunk = 8.0 * (timed(&short) - timed(&half)) * 200.0;
        assert!(chunk > 4.0, "{name}: a chunk would take {chunk:.1} s, too little to tell");

        let cancel = Cancel::new();
        let (result, stopped) = std::thread::scope(|s| {
            let asked = s.spawn(|| {
                std::thread::sleep(Duration::from_millis(200));
                cancel.cancel();
                Instant::now()
            });
            let result = cancel.watch(|| run(&long.0, &long.1, &injection(16)));
            let done = Instant::now();
            (result, done - asked.join().unwrap())
        });
        let error = result.expect_err("the run was cancelled");
        assert!(error.is_cancelled(), "{name}: {error}");
        assert!(
            stopped < Duration::from_secs(1),
            "{name}: stopped {stopped:?} after the cancel (a chunk: {chunk:.1} s)"
        );
        println!("{name}: stopped {:.3} s after the cancel; a chunk would take {chunk:.1} s", stopped.as_secs_f64());
    }
}
