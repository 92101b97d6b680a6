//! The tracker snippet of `docs/tracker.md`, runnable: `cargo run --release --example room_from_rust`.

use depo::tracker::{run, Flow, Geometry, Injection, RunSettings, Scene, SizeDistribution, WallBehaviour};
use depo::wall_model::WallLaw;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut scene = Scene::new(Geometry::Room { size: [4.0, 3.0, 2.5] });
    scene.flow = Flow::indoor_room();
    scene.brownian = true;
    scene.walls[0] = WallBehaviour::Law { law: WallLaw::preset("dunn1995-copper")?, size: None }; // the floor
    let particles = Injection::new(10_000, SizeDistribution::LogNormal { median: 1e-6, geometric_sd: 2.0 }, 1500.0);
    let mut settings = RunSettings::new(0.05, 600.0); // dt, duration (s)
    settings.average_from = 60.0; // averages over [60 s, 600 s]
    let result = run(&scene, &settings, &particles)?; // on the current rayon pool
    let floor = result.deposition_velocity(&[0]); // v_d onto the floor, m/s
    let beta = result.loss_rate(); // 1/s
    let curve = result.decay_curve(40); // N(t)/N(0) at 41 times from the release
    let fitted = result.decay_fit(&curve, scene.air_exchange); // the decay experiment's beta
    let balance = result.balance();
    println!(
        "floor v_d {:.2e} +- {:.1e} m/s ({} deposits), beta {:.3} 1/h, {} of {} particles airborne after {} s",
        floor.value,
        floor.error,
        floor.events,
        beta.value * 3600.0,
        balance.airborne,
        balance.injected,
        result.duration
    );
    if let Some(fit) = fitted {
        println!(
            "beta fitted to the decay over {:?} s: {:.3} +- {:.3} 1/h",
            fit.window,
            fit.beta.value * 3600.0,
            fit.beta.error * 3600.0
        );
    }
    Ok(())
}
