//! Invariants over random scenes: every particle is accounted for, nothing becomes NaN, airborne
//! (and exhausted) particles stay inside the domain and deposited ones sit on the wall that
//! took them.

use depo_tracker::{
    run, Drag, Fate, Flow, Geometry, Injection, RunSettings, Scene, Scheme, SizeDistribution, WallBehaviour,
};
use depo_wall_model::{SizeDependence, WallLaw};
use proptest::prelude::*;

fn scene_strategy() -> impl Strategy<Value = (Scene, RunSettings, Injection)> {
    (
        (0.05f64..3.0, 0.05f64..3.0, 0.02f64..3.0),
        any::<bool>(),
        0usize..4,
        (-8.0f64..-4.3, 500.0f64..8000.0),
        (any::<bool>(), any::<bool>(), any::<bool>()),
        (0usize..3, -5.0f64..-0.5),
        (any::<u64>(), prop_oneof![Just(0.0), 0.0f64..2.0]),
    )
        .prop_map(
            |(
                size,
                channel,
                flow,
                (log_d, density),
                (brownian, finite_re, euler),
                (walls, log_dt),
                (seed, exchange),
            )| {
                let geometry = if channel {
                    Geometry::Channel { length: size.0, width: size.1, height: size.2 }
                } else {
                    Geometry::Room { size: [size.0, size.1, size.2] }
                };
                let mut scene = Scene::new(geometry);
                let mut settings = RunSettings::new(10f64.powf(log_dt), 40.0 * 10f64.powf(log_dt));
                scene.flow = match (channel, flow) {
                    (_, 0) => Flow::Still,
                    (true, 1) => Flow::Poiseuille { max_speed: 2.0 },
                    (true, _) => Flow::TurbulentChannel { friction_velocity: 0.3 },
                    (false, 1) => Flow::Uniform { velocity: [0.3, -0.2, 0.1] },
                    (false, _) => Flow::indoor_room(),
                };
                scene.brownian = brownian;
                scene.drag = if finite_re { Drag::SchillerNaumann } else { Drag::Stokes };
                settings.scheme = if euler { Scheme::Euler } else { Scheme::Exponential };
                scene.lift = channel && flow >= 1;
                let law = WallLaw::preset("li1997-sio2").unwrap();
                scene = scene.with_walls(match walls {
                    0 => WallBehaviour::Sink,
                    1 => WallBehaviour::Reflect,
                    _ => WallBehaviour::Law { law, size: Some(SizeDependence::new(70e-6, 1.51).unwrap()) },
                });
                settings.seed = seed;
                // Up to two air changes over the run.
                scene.air_exchange = exchange / settings.duration;
                let d = 10f64.powf(log_d);
                (scene, settings, Injection::new(24, SizeDistribution::Monodisperse { diameter: d }, density))
            },
        )
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    #[test]
    fn every_particle_is_accounted_for_and_stays_in_the_domain((scene, settings, injection) in scene_strategy()) {
        let result = match run(&scene, &settings, &injection) {
            // A step too long for the turbulence's gradients is refused (tested elsewhere).
            Err(e) if e.field == "dt" => return Ok(()),
            other => other.unwrap(),
        };
        let b = result.balance();
        prop_assert_eq!(b.airborne + b.deposited.iter().sum::<usize>() + b.escaped + b.exhausted, injection.count);
        let size = scene.geometry.size();
        let walled = scene.geometry.walled();
        for r in &result.records {
            let radius = 0.5 * r.diameter;
            prop_assert!(r.position.iter().all(|c| c.is_finite()), "{:?}", r);
            prop_assert!(r.time.is_finite() && r.time >= 0.0 && r.time <= result.duration + 1e-12);
            match r.fate {
                Fate::Airborne | Fate::Exhausted => {
                    for a in 0..3 {
                        let slack = 1e-9 * size[a];
                        if walled[a] {
                            prop_assert!(r.position[a] >= radius - slack && r.position[a] <= size[a] - radius + slack, "{:?}", r);
                        } else {
                            prop_assert!(r.position[a] >= 0.0 && r.position[a] <= size[a], "{:?}", r);
                        }
                    }
                }
                Fate::Deposited(w) => {
                    let wall = result.walls[w];
                    let plane = if wall.upper { wall.position - radius } else { wall.position + radius };
                    prop_assert!((r.position[wall.axis] - plane).abs() <= 1e-9 * size[wall.axis], "{:?} on {:?}", r, wall);
                }
                Fate::Escaped => {}
            }
        }
        // Only an unstable Euler step may lose particles to non-finite states.
        if settings.scheme == Scheme::Exponential {
            prop_assert_eq!(b.escaped, 0);
        }
    }
}

/// Extreme but valid inputs: nanometre and millimetre particles, time steps from 1e-14 s to
/// 10 s, light and heavy materials, in still air, a turbulent room and a turbulent channel, with
/// Brownian motion: no NaN, no escapes, every particle accounted for.
#[test]
fn extreme_scenes_stay_finite() {
    for &(d, dt, density) in
        // The fourth: dt / tau below 1e-16, where exp(-dt / tau) rounds to exactly 1.
        &[
            (1e-9, 1e-7, 1.0),
            (1e-9, 10.0, 1e5),
            (1e-3, 1e-7, 1e5),
            (1e-3, 1e-14, 1e5),
            (1e-3, 10.0, 1.0),
            (3e-8, 0.5, 2000.0),
        ]
    {
        for flow in [Flow::Still, Flow::indoor_room(), Flow::TurbulentChannel { friction_velocity: 0.5 }] {
            let channel = matches!(flow, Flow::TurbulentChannel { .. });
            let geometry = if channel {
                Geometry::Channel { length: 0.1, width: 0.1, height: 0.02 }
            } else {
                Geometry::Room { size: [0.5, 0.5, 0.5] }
            };
            let law = WallLaw::preset("dunn1995-copper").unwrap();
            let mut scene = Scene::new(geometry).with_walls(WallBehaviour::Law { law, size: None });
            scene.flow = flow;
            scene.brownian = true;
            let injection = Injection::new(40, SizeDistribution::Monodisperse { diameter: d }, density);
            let result = match run(&scene, &RunSettings::new(dt, 20.0 * dt), &injection) {
                // Steps too long for the turbulence's gradients are refused, and only those.
                Err(e) if e.field == "dt" && flow != Flow::Still && dt >= 0.5 => continue,
                other => other.unwrap(),
            };
            let b = result.balance();
            assert_eq!(b.airborne + b.deposited.iter().sum::<usize>(), 40, "d {d} dt {dt} rho {density} {flow:?}");
            assert_eq!(b.escaped, 0, "d {d} dt {dt} rho {density} {flow:?}");
            assert!(result.records.iter().all(|r| r.position.iter().all(|c| c.is_finite())));
            assert!(result.tallies.iter().all(|t| t.energy.total().is_finite()));
        }
    }
}
