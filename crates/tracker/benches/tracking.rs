//! Tracking throughput in particle-steps per second on the current rayon pool (all cores),
//! for the two scenes the tracker's speed goals name: drag and gravity in a box with the wall
//! law on every wall, and the same with turbulent dispersion and Brownian motion; and that
//! turbulent scene again with the midpoint scheme (its predictor reusing the last read, one
//! particle at a time), which the room study uses at twice the step of the default scheme.
//!
//! `cargo bench -p depo-tracker --bench tracking`; criterion's "thrpt" is particle-steps/s.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use depo_tracker::{run, Flow, Geometry, Injection, RunSettings, Scene, Scheme, SizeDistribution, WallBehaviour};
use depo_wall_model::WallLaw;

fn scene(turbulent: bool) -> Scene {
    let law = WallLaw::preset("dunn1995-stainless").unwrap();
    let mut scene =
        Scene::new(Geometry::Room { size: [4.0, 3.0, 2.5] }).with_walls(WallBehaviour::Law { law, size: None });
    if turbulent {
        scene.flow = Flow::indoor_room();
        scene.brownian = true;
    }
    scene
}

fn tracking(c: &mut Criterion) {
    let injection = Injection::new(50_000, SizeDistribution::Monodisperse { diameter: 5e-6 }, 1000.0);
    let mut group = c.benchmark_group("tracking");
    group.sample_size(10);
    for (name, turbulent, scheme) in [
        ("drag+gravity+wall-law", false, Scheme::Exponential),
        ("+turbulence+brownian", true, Scheme::Exponential),
        ("+turbulence+brownian, midpoint", true, Scheme::Midpoint),
    ] {
        let scene = scene(turbulent);
        let settings = RunSettings { scheme, ..RunSettings::new(0.01, 2.0) };
        let steps = run(&scene, &settings, &injection).unwrap().particle_steps();
        group.throughput(Throughput::Elements(steps));
        group.bench_with_input(BenchmarkId::new(name, injection.count), &scene, |b, scene| {
            b.iter(|| run(scene, &settings, &injection).unwrap())
        });
    }
    group.finish();
}

criterion_group!(benches, tracking);
criterion_main!(benches);
