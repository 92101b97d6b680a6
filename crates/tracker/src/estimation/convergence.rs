//! Run time against error for the integrators: how the step size trades speed for accuracy.
//!
//! The test problem has no exact solution under either scheme: particles settling across a
//! laminar Poiseuille channel (`U_max` = 1 m/s, height 10 mm), 30 um and 1000 kg/m^3
//! (`tau` = 2.8 ms, settling 2.7 cm/s), released in the upper half and tracked for 0.1 s, so the
//! streamwise velocity they relax to changes along their path; they start at rest, so the first
//! relaxation times are a transient the schemes resolve differently. The error is the RMS distance of
//! the final positions from a reference run of the exponential scheme at `dt = tau / 1000`,
//! relative to the RMS distance travelled. No walls are reached, no randomness is involved:
//! what differs is the integration alone. The observed order is the slope of `ln(error)`
//! against `ln(dt)` between neighbouring step sizes.

use std::time::Instant;

use crate::estimation::run::{run, Run};
use crate::model::air::{Aerodynamics, Air, STANDARD_GRAVITY};
use crate::model::flow::Flow;
use crate::model::geometry::Geometry;
use crate::model::scene::{Injection, Scene, SizeDistribution};
use crate::model::settings::{RunSettings, Scheme};

/// One scheme at one step size.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ConvergenceRow {
    /// The scheme.
    pub scheme: Scheme,
    /// `dt / tau`.
    pub dt_over_tau: f64,
    /// Wall-clock time of the run, s.
    pub seconds: f64,
    /// Particle-steps of the run.
    pub particle_steps: u64,
    /// RMS position error relative to the RMS displacement (non-finite once the scheme blows up).
    pub error: f64,
    /// Observed order against the previous (smaller) step size, where both errors are finite.
    pub order: Option<f64>,
}

const DIAMETER: f64 = 30e-6;
const DENSITY: f64 = 1000.0;
const DURATION: f64 = 0.1;

fn scene() -> Scene {
    let mut scene = Scene::new(Geometry::Channel { length: 100.0, width: 1.0, height: 0.01 });
    scene.flow = Flow::Poiseuille { max_speed: 1.0 };
    scene.gravity = [0.0, 0.0, -STANDARD_GRAVITY];
    scene
}

fn settings(dt: f64, scheme: Scheme) -> RunSettings {
    RunSettings { scheme, ..RunSettings::new(dt, DURATION) }
}

fn injection(count: usize) -> Injection {
    // Released at rest: the first relaxation times are the transient the schemes differ on.
    Injection::new(count, SizeDistribution::Monodisperse { diameter: DIAMETER }, DENSITY)
        .within([0.0, 0.0, 0.006], [1.0, 1.0, 0.009])
        .with_velocity([0.0; 3])
}

/// A step that divides the run into whole steps, near `dt` (s).
fn whole_steps(dt: f64) -> f64 {
    DURATION / (DURATION / dt).round().max(1.0)
}

/// The test problem's relaxation time, s.
#[must_use]
pub fn relaxation_time() -> f64 {
    Aerodynamics::new(DIAMETER, DENSITY, &Air::standard(), STANDARD_GRAVITY).relaxation_time
}

/// Runs both schemes at each `dt / tau` (ascending) with `count` particles; `progress` is
/// told the runs done after each (of twice the step sizes).
#[must_use]
pub fn integrator_convergence(
    dt_over_tau: &[f64],
    count: usize,
    mut progress: impl FnMut(usize),
) -> Vec<ConvergenceRow> {
    let tau = relaxation_time();
    let (scene, injection) = (scene(), injection(count));
    let reference =
        run(&scene, &settings(whole_steps(tau / 1000.0), Scheme::Exponential), &injection).expect("valid scene");
    let mut rows = Vec::new();
    for scheme in [Scheme::Exponential, Scheme::Euler] {
        let mut previous: Option<(f64, f64)> = None;
        for &ratio in dt_over_tau {
            let dt = whole_steps(ratio * tau);
            let ratio = dt / tau;
            let start = Instant::now();
            let result = run(&scene, &settings(dt, scheme), &injection).expect("valid scene");
            let seconds = start.elapsed().as_secs_f64();
            let error = relative_error(&result, &reference);
            let order = match previous {
                Some((e0, r0)) if e0.is_finite() && error.is_finite() && e0 > 0.0 && error > 0.0 => {
                    Some((error / e0).ln() / (ratio / r0).ln())
                }
                _ => None,
            };
            previous = Some((error, ratio));
            rows.push(ConvergenceRow {
                scheme,
                dt_over_tau: ratio,
                seconds,
                particle_steps: result.particle_steps(),
                error,
                order,
            });
            progress(rows.len());
        }
    }
    rows
}

fn relative_error(result: &Run, reference: &Run) -> f64 {
    let (mut err, mut travel) = (0.0, 0.0);
    for (a, b) in result.records.iter().zip(&reference.records) {
        for k in 0..3 {
            err += (a.position[k] - b.position[k]).powi(2);
            travel += (b.position[k] - b.start[k]).powi(2);
        }
    }
    if result.records.iter().any(|r| r.fate != crate::tracking::Fate::Airborne) {
        return f64::INFINITY;
    }
    (err / travel).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exponential_converges_at_first_order_and_stays_stable_where_euler_fails() {
        let mut told = Vec::new();
        let rows = integrator_convergence(&[0.03, 0.1, 0.3, 1.0, 3.0], 20, |done| told.push(done));
        assert_eq!(told, (1..=10).collect::<Vec<_>>(), "one call per run");
        let exp: Vec<_> = rows.iter().filter(|r| r.scheme == Scheme::Exponential).collect();
        let euler: Vec<_> = rows.iter().filter(|r| r.scheme == Scheme::Euler).collect();
        for r in &exp[1..3] {
            let order = r.order.unwrap();
            assert!((0.8..1.3).contains(&order), "exponential order {order} at dt/tau {}", r.dt_over_tau);
        }
        assert!(exp.iter().all(|r| r.error.is_finite() && r.error < 0.05), "{exp:?}");
        // Euler: first order too while dt < tau, far off (or blown up) beyond dt = 2 tau.
        let order = euler[1].order.unwrap();
        assert!((0.8..1.3).contains(&order), "euler order {order}");
        assert!(euler[4].error > 10.0 * exp[4].error, "{euler:?}");
        // At equal dt the exponential scheme is the more accurate.
        for (e, x) in euler.iter().zip(&exp) {
            assert!(x.error < e.error, "dt/tau {}: {} vs {}", x.dt_over_tau, x.error, e.error);
        }
    }
}
