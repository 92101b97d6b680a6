//! Where an impact's kinetic energy goes (paper Eqs. 1 and 14), per unit particle mass.
//!
//! With `T_n = vn^2 / 2` the normal kinetic energy per unit mass (J/kg):
//!
//! ```text
//! material loss  = T_n (1 - R^2)
//! adhesion loss  = T_n R^2 rho (2 - rho)      (= |W_A|/m, Eq. 1 solved for W_A)
//! normal loss    = T_n (1 - e^2)              = material + adhesion
//! friction loss  = j (|s| - 7/4 j)            the drop in tangential + rotational energy
//! deposition     = what a deposited particle still carried (tangential + rotational)
//! ```
//!
//! `j = |Pt|/m` is the tangential impulse per unit mass and `|s|` the slip speed before the
//! impact; since `j <= 2/7 |s|` the friction loss is never negative (rolling: `|s|^2 / 7`).
//! A captured impact has `e = 0`: its adhesion loss is `T_n R^2`, which at `|vn| = vc` is
//! Eq. (14), `|W_A^c| / (m vc^2 / 2) = R(vc)^2`.
//!
//! A scene that does not track spin discards the spin an impact gives (`5/4 j^2` per unit
//! mass): that energy is neither a loss of the wall law nor in the particle afterwards.

use core::ops::{Add, AddAssign};

use crate::impact::ImpactResult;
use crate::real::{select, Real};

/// Energy lost per mechanism, in J/kg for one impact, or summed over impacts in a tally.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct EnergyLoss<T> {
    /// Material dissipation, `T_n (1 - R^2)`.
    pub material: T,
    /// Adhesion dissipation, `T_n R^2 rho (2 - rho)`.
    pub adhesion: T,
    /// Friction dissipation in the contact.
    pub friction: T,
    /// Kinetic energy taken onto the wall by deposited particles.
    pub deposition: T,
}

impl<T: Real> EnergyLoss<T> {
    /// The sum of all mechanisms.
    #[must_use]
    pub fn total(&self) -> T {
        self.material + self.adhesion + self.friction + self.deposition
    }

    /// The same figures in `f64`.
    #[must_use]
    pub fn to_f64(&self) -> EnergyLoss<f64> {
        EnergyLoss {
            material: self.material.to_f64(),
            adhesion: self.adhesion.to_f64(),
            friction: self.friction.to_f64(),
            deposition: self.deposition.to_f64(),
        }
    }
}

impl<T: Real> Add for EnergyLoss<T> {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        Self {
            material: self.material + o.material,
            adhesion: self.adhesion + o.adhesion,
            friction: self.friction + o.friction,
            deposition: self.deposition + o.deposition,
        }
    }
}

impl<T: Real> AddAssign for EnergyLoss<T> {
    fn add_assign(&mut self, o: Self) {
        *self = *self + o;
    }
}

/// The energy budget of one impact, per unit mass. Written so that no finite input gives NaN
/// (`T_n` may overflow to infinity for `|vn|` above 1e154 m/s; the products are ordered so that
/// it is never multiplied by zero).
#[inline(always)]
#[must_use]
pub fn energy_loss<T: Real>(impact: &ImpactResult<T>) -> EnergyLoss<T> {
    let speed = -impact.normal_velocity;
    let c = impact.coefficients;
    let r = c.restitution;
    let rho = c.adhesion;
    let adhesion_share = select(c.captured, T::ONE, rho * (T::from_f64(2.0) - rho));
    let sr = speed * r;
    let j = impact.tangential_impulse;
    EnergyLoss {
        material: T::HALF * speed * (speed * (T::ONE - r * r)),
        adhesion: T::HALF * sr * (sr * adhesion_share),
        friction: j * (impact.slip - T::from_f64(1.75) * j),
        deposition: impact.deposited_energy,
    }
}

/// Eq. (14): the work of adhesion at capture per unit mass, `|W_A^c|/m = R(vc)^2 vc^2 / 2`
/// (J/kg), given `R(vc)`.
#[must_use]
pub fn capture_work_of_adhesion(vc: f64, restitution_at_vc: f64) -> f64 {
    0.5 * vc * vc * restitution_at_vc * restitution_at_vc
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::impact::{kinetic_energy, resolve, CaptureMode};
    use crate::law::LawConstants;
    use crate::params::LawParams;
    use crate::power::{Half, One};

    #[test]
    fn budget_closes_on_hand_computed_impacts() {
        let c = LawConstants::<f64>::new(&LawParams::symmetric(12.5, 0.065, 0.074, 1.0, 0.5).with_friction(0.3));
        for (v, w) in [
            ([0.5, -1.0, 0.2], [0.0, 0.0, 0.0]),
            ([0.1, -2.0, -0.4], [100.0, -3e3, 5e2]),
            ([0.3, -0.05, 0.0], [0.0, 1e3, 0.0]),
        ] {
            let r = 1e-4;
            let n = [0.0, 1.0, 0.0];
            let res = resolve::<f64, One, Half, true, true>(&c, One, Half, CaptureMode::Deposit, v, w, r, n);
            let loss = energy_loss(&res);
            let direct = kinetic_energy(v, w, r) - kinetic_energy(res.velocity, res.spin, r);
            assert!((loss.total() - direct).abs() <= 1e-13 * kinetic_energy(v, w, r), "{loss:?} vs {direct}");
            assert!(loss.material >= 0.0 && loss.adhesion >= 0.0 && loss.friction >= 0.0);
        }
    }

    #[test]
    fn normal_loss_is_one_minus_e_squared() {
        // li1997 at 1 m/s, normal: T_n = 0.5; e = 0.731990683 -> loss 0.5 (1 - e^2) = 0.232095.
        let c = LawConstants::<f64>::new(&LawParams::symmetric(12.5, 0.065, 0.074, 1.0, 0.5));
        let res = resolve::<f64, One, Half, false, false>(
            &c,
            One,
            Half,
            CaptureMode::Deposit,
            [0.0, -1.0, 0.0],
            [0.0; 3],
            1.0,
            [0.0, 1.0, 0.0],
        );
        let loss = energy_loss(&res);
        assert!((loss.material + loss.adhesion - 0.5 * (1.0 - 0.731_990_683f64.powi(2))).abs() < 1e-9);
        assert!((loss.material - 0.5 * (1.0 - (12.5f64 / 13.5).powi(2))).abs() < 1e-15);
    }

    #[test]
    fn eq14_at_capture() {
        // At |vn| = vc the adhesion loss per unit mass over vc^2/2 is R(vc)^2.
        let vc = 0.074;
        let c = LawConstants::<f64>::new(&LawParams::symmetric(12.5, 0.065, vc, 1.0, 0.5));
        let res = resolve::<f64, One, Half, false, false>(
            &c,
            One,
            Half,
            CaptureMode::Deposit,
            [0.0, -vc, 0.0],
            [0.0; 3],
            1.0,
            [0.0, 1.0, 0.0],
        );
        let rc = 12.5 / (12.5 + vc);
        assert!(res.coefficients.captured);
        assert!((energy_loss(&res).adhesion - capture_work_of_adhesion(vc, rc)).abs() < 1e-16);
        assert!((capture_work_of_adhesion(vc, rc) / (0.5 * vc * vc) - rc * rc).abs() < 1e-15);
    }
}
