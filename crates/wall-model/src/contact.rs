//! Impact dynamics in time: one sphere against a flat wall, in the spirit of Brach & Dunn
//! (1995). It makes `e(vn)` curves where there is no impact data, for [`crate::fit`] to turn into
//! the law's constants, and capture velocity against radius (paper Figs. 7, 8).
//!
//! The normal overlap `delta` (m, positive in contact) obeys `m delta'' = F_adhesion - F_elastic
//! - F_damping`, with
//!
//! ```text
//! F_elastic = k delta^(3/2),            k = 4/3 E* sqrt(R)        (Hertz)
//! F_damping = 3/2 A k sqrt(delta) delta'                          (Kuwabara & Kono 1987)
//! F_adhesion = F_po = 2 pi w R          in contact                (DMT pull-off force)
//!            = F_po (1 + delta/delta_c)  for -delta_c < delta < 0 after contact (the neck)
//! delta_c = (pi^2 w^2 R / E*^2)^(1/3)                             (the JKR length scale)
//! ```
//!
//! `E*` is the effective modulus (`1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2`), `A` the
//! viscoelastic damping time (s), `w` the work of adhesion (J/m^2), `m = 4/3 pi R^3 rho`.
//! The adhesion force does no net work until the neck stretches: the neck's hysteresis,
//! `F_po delta_c / 2`, is what adhesion dissipates. With `A = 0` that makes the capture
//! velocity scale as `R^(-5/6)`, the JKR law of Johnson & Pollock (1994) (tested). This is a
//! simple model of our own for producing curves, not the paper's simulation: its constants
//! (`A`, `w`, the form of the neck) are inputs, not predictions.
//!
//! Integration: velocity Verlet from first contact at speed `v` until the sphere leaves the neck
//! (rebound, `e = -delta'/v`) or turns back towards the wall while still attached (captured),
//! with a step of 1/4000 of Hertz's elastic contact time.

use crate::fit::Sample;

/// The contact's constants, SI units.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactModel {
    /// Sphere radius `R`, m.
    pub radius: f64,
    /// Sphere density, kg/m^3.
    pub density: f64,
    /// Effective modulus `E*`, Pa.
    pub effective_modulus: f64,
    /// Kuwabara-Kono damping time `A`, s (0: elastic).
    pub damping_time: f64,
    /// Work of adhesion `w`, J/m^2 (0: no adhesion).
    pub work_of_adhesion: f64,
}

/// The outcome of one simulated normal impact.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SimulatedImpact {
    /// `e = -V/v`; 0 when captured.
    pub restitution: f64,
    /// True when the sphere could not leave the wall.
    pub captured: bool,
    /// Time from first contact to separation (or to capture), s.
    pub contact_time: f64,
    /// Largest overlap, m.
    pub max_overlap: f64,
}

impl ContactModel {
    fn mass(&self) -> f64 {
        crate::theory::sphere_mass(self.radius, self.density)
    }

    fn stiffness(&self) -> f64 {
        4.0 / 3.0 * self.effective_modulus * self.radius.sqrt()
    }

    /// Pull-off force `2 pi w R`, N.
    #[must_use]
    pub fn pull_off_force(&self) -> f64 {
        2.0 * core::f64::consts::PI * self.work_of_adhesion * self.radius
    }

    /// Neck length `delta_c = (pi^2 w^2 R / E*^2)^(1/3)`, m.
    #[must_use]
    pub fn neck_length(&self) -> f64 {
        let pi = core::f64::consts::PI;
        (pi * pi * self.work_of_adhesion.powi(2) * self.radius / self.effective_modulus.powi(2)).cbrt()
    }

    /// Hertz's elastic contact time at impact speed `speed` (m/s):
    /// `2.868 (m^2 / (R E*^2 v))^(1/5)`.
    #[must_use]
    pub fn hertz_contact_time(&self, speed: f64) -> f64 {
        2.868 * (self.mass().powi(2) / (self.radius * self.effective_modulus.powi(2) * speed.abs())).powf(0.2)
    }

    /// One normal impact at speed `speed` (m/s, > 0).
    #[must_use]
    pub fn simulate(&self, speed: f64) -> SimulatedImpact {
        let v0 = speed.abs();
        let m = self.mass();
        let k = self.stiffness();
        let f_po = self.pull_off_force();
        let neck = self.neck_length();
        let dt = self.hertz_contact_time(v0) / 4000.0;
        let force = |delta: f64, rate: f64, separating: bool| -> f64 {
            if delta > 0.0 {
                let root = delta.sqrt();
                f_po - k * delta * root - 1.5 * self.damping_time * k * root * rate
            } else if separating && delta > -neck {
                f_po * (1.0 + delta / neck)
            } else {
                0.0
            }
        };
        let (mut delta, mut rate, mut t, mut max_overlap) = (0.0f64, v0, 0.0f64, 0.0f64);
        let mut separating = false;
        let mut accel = force(delta, rate, separating) / m;
        // Generous cap: an impact lasts a few contact times; a captured sphere oscillates.
        for _ in 0..400_000 {
            delta += rate * dt + 0.5 * accel * dt * dt;
            let half = rate + 0.5 * accel * dt;
            let next = force(delta, half, separating) / m;
            rate = half + 0.5 * next * dt;
            accel = next;
            t += dt;
            max_overlap = max_overlap.max(delta);
            if rate < 0.0 {
                separating = true;
            }
            if separating && rate >= 0.0 {
                return SimulatedImpact { restitution: 0.0, captured: true, contact_time: t, max_overlap };
            }
            if separating && delta <= -neck && delta <= 0.0 {
                return SimulatedImpact { restitution: -rate / v0, captured: false, contact_time: t, max_overlap };
            }
        }
        SimulatedImpact { restitution: 0.0, captured: true, contact_time: t, max_overlap }
    }

    /// `e` at each speed (m/s), as samples for [`crate::fit::fit`].
    #[must_use]
    pub fn restitution_curve(&self, speeds: &[f64]) -> Vec<Sample> {
        speeds.iter().map(|&s| Sample { speed: s, restitution: self.simulate(s).restitution, weight: 1.0 }).collect()
    }

    /// The capture velocity (m/s): the largest speed that is captured, by bisection between
    /// `low` (captured) and `high` (rebounds) to a relative width of 1e-6. `None` if the bracket
    /// does not hold.
    #[must_use]
    pub fn capture_velocity(&self, low: f64, high: f64) -> Option<f64> {
        let (mut lo, mut hi) = (low, high);
        if !self.simulate(lo).captured || self.simulate(hi).captured {
            return None;
        }
        while hi - lo > 1e-6 * hi {
            let mid = 0.5 * (lo + hi);
            if self.simulate(mid).captured {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        Some(0.5 * (lo + hi))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fit::{fit, Exponents};

    /// 70 um stainless steel on SiO2-like glass: E* about 70 GPa.
    fn steel(radius: f64, damping_time: f64, work_of_adhesion: f64) -> ContactModel {
        ContactModel { radius, density: 7900.0, effective_modulus: 7.0e10, damping_time, work_of_adhesion }
    }

    #[test]
    fn elastic_impacts_conserve_energy_and_last_hertz_s_contact_time() {
        let model = steel(35e-6, 0.0, 0.0);
        for speed in [0.01, 0.3, 1.0, 10.0] {
            let r = model.simulate(speed);
            assert!(!r.captured);
            assert!((r.restitution - 1.0).abs() < 1e-6, "e = {} at {speed}", r.restitution);
            let hertz = model.hertz_contact_time(speed);
            assert!((r.contact_time / hertz - 1.0).abs() < 0.01, "{} vs {hertz}", r.contact_time);
        }
    }

    #[test]
    fn restitution_falls_with_damping_and_with_speed() {
        let speed = 1.0;
        let mut last = 1.0 + 1e-6; // the integrator's error on the elastic e = 1
        for a in [0.0, 1e-9, 3e-9, 1e-8] {
            let e = steel(35e-6, a, 0.0).simulate(speed).restitution;
            assert!(e < last, "A = {a}: e = {e}");
            last = e;
        }
        let damped = steel(35e-6, 3e-9, 0.0);
        assert!(damped.simulate(0.1).restitution > damped.simulate(1.0).restitution);
        assert!(damped.simulate(1.0).restitution > damped.simulate(10.0).restitution);
    }

    #[test]
    fn adhesion_alone_gives_the_jkr_five_sixths_law() {
        let w = 0.3;
        let small = steel(35e-6, 0.0, w).capture_velocity(1e-4, 10.0).unwrap();
        let large = steel(70e-6, 0.0, w).capture_velocity(1e-4, 10.0).unwrap();
        let ratio = large / small;
        eprintln!("capture velocity {small} m/s at 35 um, {large} m/s at 70 um: ratio {ratio}");
        assert!((ratio / 2f64.powf(-5.0 / 6.0) - 1.0).abs() < 0.02, "vc ratio {ratio}");
        // Below the capture velocity the sphere stays; above it rebounds with e from 0 upwards.
        let model = steel(35e-6, 0.0, w);
        assert!(model.simulate(0.9 * small).captured);
        let above = model.simulate(1.1 * small);
        assert!(!above.captured && above.restitution > 0.0 && above.restitution < 0.7);
    }

    #[test]
    fn simulated_curves_fit_the_law() {
        let model = steel(35e-6, 2e-9, 0.3);
        let vc = model.capture_velocity(1e-4, 10.0).unwrap();
        let speeds: Vec<f64> = (0..30).map(|i| 1.05 * vc * (100.0f64).powf(i as f64 / 29.0)).collect();
        let report = fit(&model.restitution_curve(&speeds), Exponents::Free { p: 1.0, q: 0.5 }).unwrap();
        eprintln!("simulated vc {vc}, fit {:?}, R^2 {}", report.params, report.fitting_index);
        assert!(report.fitting_index > 0.95, "R^2 {}", report.fitting_index);
        assert!((report.params.vc / vc - 1.0).abs() < 0.1, "fitted vc {} vs simulated {vc}", report.params.vc);
    }
}
