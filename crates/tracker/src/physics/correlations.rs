//! Deposition correlations and models to compare runs with. Each takes the particle's
//! Schmidt number `Sc = nu / D` and, for channels, its dimensionless relaxation time
//! `tau+ = tau u*^2 / nu`; deposition velocities are made dimensionless as `V+ = v_d / u*`.

use std::f64::consts::PI;

use crate::model::air::{Aerodynamics, Air};

/// Lai & Nazaroff (2000), *Modeling indoor particle deposition from turbulent flow onto smooth
/// surfaces*, J. Aerosol Sci. 31: the deposition velocities (m/s) onto an upward-facing
/// surface (floor), a downward-facing one (ceiling) and a vertical wall of a room with
/// near-wall friction velocity `u*`.
///
/// ```text
/// v_floor   = v_s / (1 - exp(-v_s I / u*))
/// v_ceiling = v_s / (exp(v_s I / u*) - 1)
/// v_wall    = u* / I
/// I = 3.64 Sc^(2/3) (a - b) + 39
/// a = 1/2 ln[(10.92 Sc^(-1/3) + 4.3)^3 / (1/Sc + 0.0609)] + sqrt(3) atan[(8.6 - 10.92 Sc^(-1/3)) / (sqrt(3) 10.92 Sc^(-1/3))]
/// b = 1/2 ln[(10.92 Sc^(-1/3) + r+)^3 / (1/Sc + 7.669e-4 r+^3)] + sqrt(3) atan[(2 r+ - 10.92 Sc^(-1/3)) / (sqrt(3) 10.92 Sc^(-1/3))]
/// ```
///
/// with `r+ = r u* / nu` the particle radius in wall units. The model carries particles by
/// Brownian and turbulent diffusion and gravity only: no inertia (no turbophoresis or
/// impaction), which is why it misses the rise of vertical-wall deposition with size above
/// about 1 um that their 2005 measurements show.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LaiNazaroff {
    /// Onto an upward-facing surface, m/s.
    pub floor: f64,
    /// Onto a downward-facing surface, m/s.
    pub ceiling: f64,
    /// Onto a vertical surface, m/s.
    pub wall: f64,
}

/// The integral `I` of [`LaiNazaroff`] for Schmidt number `sc` and radius `r_plus` in wall units.
#[must_use]
pub fn lai_nazaroff_integral(sc: f64, r_plus: f64) -> f64 {
    let a0 = 10.92 * sc.powf(-1.0 / 3.0);
    let s3 = 3f64.sqrt();
    let a = 0.5 * ((a0 + 4.3).powi(3) / (1.0 / sc + 0.0609)).ln() + s3 * ((8.6 - a0) / (s3 * a0)).atan();
    let b = 0.5 * ((a0 + r_plus).powi(3) / (1.0 / sc + 7.669e-4 * r_plus.powi(3))).ln()
        + s3 * ((2.0 * r_plus - a0) / (s3 * a0)).atan();
    3.64 * sc.powf(2.0 / 3.0) * (a - b) + 39.0
}

impl LaiNazaroff {
    /// For a particle of `diameter` (m) and `density` (kg/m^3) in `air` under `gravity` (m/s^2)
    /// with friction velocity `friction_velocity` (m/s).
    #[must_use]
    pub fn new(diameter: f64, density: f64, air: &Air, gravity: f64, friction_velocity: f64) -> Self {
        let aero = Aerodynamics::new(diameter, density, air, gravity);
        let nu = air.kinematic_viscosity();
        let sc = nu / aero.diffusivity;
        let r_plus = 0.5 * diameter * friction_velocity / nu;
        Self::from_integral(lai_nazaroff_integral(sc, r_plus), aero.settling_speed, friction_velocity)
    }

    /// From the integral `I`, settling speed `v_s` and friction velocity `u*` (m/s).
    #[must_use]
    pub fn from_integral(integral: f64, settling: f64, friction_velocity: f64) -> Self {
        let wall = friction_velocity / integral;
        let x = settling * integral / friction_velocity;
        if x < 1e-12 {
            return Self { floor: wall, ceiling: wall, wall };
        }
        // v_s / (1 - e^-x) and v_s e^-x / (1 - e^-x), written with exp_m1 for small x.
        let one_minus = -(-x).exp_m1();
        Self { floor: settling / one_minus, ceiling: settling * (-x).exp() / one_minus, wall }
    }

    /// Loss-rate coefficient of a box room, `beta = (v_floor A_floor + v_ceiling A_ceiling +
    /// v_wall A_walls) / V`, 1/s.
    #[must_use]
    pub fn loss_rate(&self, size: [f64; 3]) -> f64 {
        let [lx, ly, lz] = size;
        let horizontal = lx * ly;
        let vertical = 2.0 * (lx + ly) * lz;
        (self.floor * horizontal + self.ceiling * horizontal + self.wall * vertical) / (lx * ly * lz)
    }
}

/// Wood (1981), *A simple method for the calculation of turbulent deposition to smooth and
/// rough surfaces*, J. Aerosol Sci. 12: `V+ = 0.057 Sc^(-2/3) + 4.5e-4 tau+^2`, at most 0.13
/// (the inertia-moderated plateau).
#[must_use]
pub fn wood(tau_plus: f64, schmidt: f64) -> f64 {
    (0.057 * schmidt.powf(-2.0 / 3.0) + 4.5e-4 * tau_plus * tau_plus).min(0.13)
}

/// Papavergos & Hedley (1984), *Particle deposition behaviour from turbulent flows*, Chem. Eng.
/// Res. Des. 62: `V+ = 0.065 Sc^(-2/3)` (`tau+ < 0.2`), `3.5e-4 tau+^2` (`0.2 <= tau+ <= 20`),
/// `0.18` (`tau+ > 20`).
#[must_use]
pub fn papavergos_hedley(tau_plus: f64, schmidt: f64) -> f64 {
    if tau_plus < 0.2 {
        0.065 * schmidt.powf(-2.0 / 3.0)
    } else if tau_plus <= 20.0 {
        3.5e-4 * tau_plus * tau_plus
    } else {
        0.18
    }
}

/// How far `value` lies outside the band between two correlations `a` and `b` (say Wood's and
/// Papavergos & Hedley's `V+` at one `tau+`): 1 within it, `value / min(a, b)` below it and
/// `value / max(a, b)` above it. The two correlations were fitted to overlapping compilations
/// of the same measurements, so their spread is a floor on how well any one point is known;
/// a model within a factor 2 of the band (a result in `[0.5, 2]`) agrees with them.
pub fn band_factor(value: f64, a: f64, b: f64) -> f64 {
    let (low, high) = (a.min(b), a.max(b));
    if value >= low && value <= high {
        1.0
    } else if value < low {
        value / low
    } else {
        // Above the band, or NaN (which passes through).
        value / high
    }
}

/// The particle diameter (m) of density `density` with dimensionless relaxation time `tau_plus`
/// in a flow of friction velocity `u*` (slip included, found by bisection), or `None` when no
/// diameter between 0.1 nm and 1 cm gives it (say, `tau+ = 10` at `u* = 1e-4 m/s` would need
/// a particle larger than 1 cm).
#[must_use]
pub fn diameter_for_tau_plus(tau_plus: f64, density: f64, air: &Air, friction_velocity: f64) -> Option<f64> {
    let nu = air.kinematic_viscosity();
    let tau = tau_plus * nu / (friction_velocity * friction_velocity);
    let relaxation = |d: f64| Aerodynamics::new(d, density, air, 0.0).relaxation_time;
    let (mut lo, mut hi) = (1e-10_f64, 1e-2_f64);
    if !(tau.is_finite() && relaxation(lo) <= tau && tau <= relaxation(hi)) {
        return None;
    }
    for _ in 0..200 {
        let mid = (lo * hi).sqrt();
        if relaxation(mid) < tau {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Some((lo * hi).sqrt())
}

/// Schmidt number `nu / D` of a particle.
#[must_use]
pub fn schmidt(diameter: f64, air: &Air) -> f64 {
    // D depends on size only, not on density.
    let slip = crate::model::air::slip_correction(diameter, air.mean_free_path());
    air.kinematic_viscosity() / crate::model::air::diffusivity(diameter, slip, air)
}

/// The still-air Brownian deposition flux onto a floor with settling, from a uniform initial
/// concentration, as a deposition velocity at time `t` (s): the exact solution of the
/// advection-diffusion equation over a perfectly absorbing plane,
/// `J/C0 = v_s/2 [1 + erf(v_s sqrt(t) / (2 sqrt(D)))] + sqrt(D / (pi t)) exp(-v_s^2 t / (4 D))`.
#[must_use]
pub fn settling_diffusion_flux(settling: f64, diffusivity: f64, t: f64) -> f64 {
    let z = settling * t.sqrt() / (2.0 * diffusivity.sqrt());
    0.5 * settling * (1.0 + libm::erf(z)) + (diffusivity / (PI * t)).sqrt() * (-z * z).exp()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn band_factor_is_one_within_and_the_ratio_to_the_nearer_edge_outside() {
        // tau+ = 1: Wood 4.5e-4, Papavergos & Hedley 3.5e-4.
        assert_eq!(band_factor(4e-4, 4.5e-4, 3.5e-4), 1.0);
        assert!((band_factor(7e-5, 4.5e-4, 3.5e-4) - 0.2).abs() < 1e-12);
        assert!((band_factor(1.35e-3, 3.5e-4, 4.5e-4) - 3.0).abs() < 1e-12);
        // On an edge, within; a NaN is not reported within.
        assert_eq!(band_factor(3.5e-4, 4.5e-4, 3.5e-4), 1.0);
        assert!(band_factor(f64::NAN, 4.5e-4, 3.5e-4).is_nan());
    }

    #[test]
    fn lai_nazaroff_integral_matches_hand_values() {
        // Evaluated independently of this code from the formula above.
        assert!((lai_nazaroff_integral(1000.0, 0.01) / 1_314.923_307_742_62 - 1.0).abs() < 1e-10);
        assert!((lai_nazaroff_integral(1e5, 0.05) / 23_473.929_525_906_453 - 1.0).abs() < 1e-10);
    }

    #[test]
    fn lai_nazaroff_orders_surfaces_and_has_the_settling_limits() {
        let ln = LaiNazaroff::from_integral(23_473.929_525_906_453, 1e-4, 0.01);
        assert!((ln.wall - 4.260_045_165_835_457_7e-7).abs() < 1e-18);
        assert!((ln.floor - 1e-4).abs() < 1e-12, "strong settling: floor takes v_s");
        assert!(ln.ceiling < 1e-100);
        let small = LaiNazaroff::from_integral(1000.0, 1e-9, 0.01);
        assert!(small.floor > small.wall && small.wall > small.ceiling);
        assert!((small.floor - small.ceiling - 1e-9).abs() < 1e-15, "floor - ceiling = v_s exactly");
        // A real particle: 1 um, unit density, u* = 1 cm/s.
        let one = LaiNazaroff::new(1e-6, 1000.0, &Air::standard(), 9.80665, 0.01);
        assert!(one.floor > 3e-5 && one.floor < 4e-5, "{}", one.floor);
        assert!(one.wall < 1e-5 && one.wall > 1e-7, "{}", one.wall);
        let beta = one.loss_rate([4.0, 4.0, 2.5]);
        assert!((beta - (one.floor + one.ceiling) / 2.5 - one.wall * 2.0 * 8.0 / 16.0).abs() < 1e-15);
    }

    #[test]
    fn channel_correlations_have_their_regimes() {
        assert!((wood(0.0, 1000.0) - 0.057 * 1e-2).abs() < 1e-15);
        assert!((wood(10.0, 1e6) - (0.057e-4 + 0.045)).abs() < 1e-12);
        assert_eq!(wood(100.0, 1e6), 0.13);
        assert_eq!(papavergos_hedley(100.0, 1e6), 0.18);
        assert!((papavergos_hedley(10.0, 1e6) - 0.035).abs() < 1e-15);
        assert!((papavergos_hedley(0.1, 1000.0) - 0.065e-2).abs() < 1e-15);
    }

    #[test]
    fn tau_plus_inverts() {
        let air = Air::standard();
        let d = diameter_for_tau_plus(10.0, 1000.0, &air, 0.3).unwrap();
        let tau = Aerodynamics::new(d, 1000.0, &air, 0.0).relaxation_time;
        let tp = tau * 0.09 / air.kinematic_viscosity();
        assert!((tp / 10.0 - 1.0).abs() < 1e-9, "{tp}");
        // tau+ = 10 at u* = 1e-4 m/s would take a particle larger than 1 cm.
        assert_eq!(diameter_for_tau_plus(10.0, 1000.0, &air, 1e-4), None);
    }

    #[test]
    fn settling_diffusion_flux_has_its_limits() {
        // Pure diffusion: sqrt(D / (pi t)); pure settling at long times: v_s.
        assert!((settling_diffusion_flux(0.0, 1e-9, 10.0) - (1e-9 / (PI * 10.0)).sqrt()).abs() < 1e-18);
        assert!((settling_diffusion_flux(1e-3, 1e-12, 100.0) - 1e-3).abs() < 1e-9);
    }
}
