//! The capture velocity from material properties, for when there is no impact data.
//!
//! Each theory is an energy balance in closed form: a particle sticks when the kinetic energy
//! it brings to the wall is no more than what the contact dissipates or binds. The result is a
//! capture velocity `vc` (m/s) for [`crate::LawParams::vc`], or one per particle for
//! [`crate::Impacts::with_capture_velocity`]. `k` and `kappa` still need data or the contact
//! simulator of [`crate::contact`]; theory gives only the threshold.
//!
//! ## Elastic adhesive spheres: Johnson & Pollock (1994), Thornton & Ning (1998)
//!
//! In the JKR theory (Johnson, Kendall & Roberts 1971) a sphere of radius `R` on a flat wall,
//! with effective modulus `E*` and work of adhesion `w`, has, for a contact radius `a`,
//!
//! ```text
//! overlap  delta(a) = a^2 / R - sqrt(2 pi w a / E*)
//! force    F(a)     = 4 E* a^3 / (3 R) - sqrt(8 pi w E* a^3)        (compressive positive)
//! ```
//!
//! An impact follows this curve both ways, but not over the same range: coming in, the contact
//! snaps on at `delta = 0`; going out, a neck holds the sphere down to the least overlap
//! `delta_c = -3/4 (pi^2 w^2 R / E*^2)^(1/3)` (where `d delta / d a = 0` and `F = -5/6 pi w R`)
//! before it breaks. The work done against the neck between `delta = 0` and `delta_c` is lost.
//! Integrating `F d delta` along the curve in closed form gives
//!
//! ```text
//! W_L = C_W (w^5 R^4 / E*^2)^(1/3),   C_W = (2 pi)^(5/3) (3/10 + 2^(-8/3) / 5) = 7.0922
//! ```
//!
//! Thornton & Ning (1998, Powder Technology 99, 154) take this loss as the whole of an elastic
//! impact's dissipation and set `m vc^2 / 2 = W_L` with `m = 4/3 pi R^3 rho`:
//!
//! ```text
//! vc = C_v (w^5 / (rho^3 E*^2 R^5))^(1/6),   C_v = sqrt(3 C_W / (2 pi)) = 1.8402
//! ```
//!
//! the `vc ~ R^(-5/6)` law that Johnson & Pollock (1994, J. Adhesion Sci. Technol. 8, 1323)
//! derived for elastic adhesive impacts and that the paper's Fig. 8 compares with. Both
//! constants are derived here from the JKR curve and checked against a numerical integration of
//! it in the tests ([`jkr_energy_loss`], [`jkr_capture_velocity`]). Johnson & Pollock also let
//! the surface energy on detachment exceed that on attachment (adhesion hysteresis, as the
//! paper recalls under Fig. 8), which adds loss on the loading-unloading cycle; with one `w`
//! (give the detachment value) this `vc` is the lower estimate in that respect.
//!
//! Valid when: the contact is JKR-like (Tabor's parameter above about 5, [`tabor_parameter`];
//! small, stiff particles with weak adhesion are DMT-like and stick less); the impact stays
//! elastic (`vc` below the yield velocity of [`yield_velocity`]: a plastic impact dissipates
//! more and captures faster particles); the surfaces are smooth on the scale of the contact
//! radius (roughness lowers `w` by orders of magnitude, so `w` is best taken from pull-off
//! measurements on the same surfaces); and no material damping (the paper's `R < 1` at high
//! speed is not in this theory).
//!
//! ## A rigid sphere in a van der Waals well: Dahneke (1971)
//!
//! Dahneke (1971, J. Colloid Interface Sci. 37, 342) treats the particle as rigid, the wall's
//! attraction as a potential well of depth `E0` (J), and the contact's losses as a restitution
//! coefficient `e0` that would hold without adhesion. The particle arrives at contact with
//! `m v^2 / 2 + E0`, leaves it with `e0^2` of that, and escapes if what is left exceeds `E0`:
//!
//! ```text
//! vc = sqrt(2 E0 / m) sqrt(1 - e0^2) / e0
//! ```
//!
//! With the well of a smooth sphere at contact separation `z0` (about 0.4 nm) from a plane,
//! `E0 = A R / (6 z0)` for the Hamaker constant `A` (J) ([`hamaker_well_depth`]), `vc ~ R^-1`.
//! Valid when: the particle does not deform (stiff, small `w R / (E* z0^2)`), `e0` does not
//! depend on speed, and `z0` and `A` are known; `vc` is very sensitive to `z0` (as `z0^-1/2`).
//!
//! All inputs are SI and must be finite and positive (`e0` in `(0, 1]`); the functions are
//! plain formulas and do not check them: callers that read them from users validate there
//! (as `depo capture-velocity` does, naming the flag).

use core::f64::consts::PI;

/// `C_W` of [`jkr_energy_loss`]: `(2 pi)^(5/3) (3/10 + 2^(-8/3) / 5)`.
pub const JKR_LOSS_COEFFICIENT: f64 = 7.092_195_971_863_958;
/// `C_v` of [`jkr_capture_velocity`]: `sqrt(3 C_W / (2 pi))`.
pub const JKR_VELOCITY_COEFFICIENT: f64 = 1.840_183_180_799_056_5;
/// A typical separation at contact `z0` for van der Waals adhesion, 0.4 nm.
pub const CONTACT_SEPARATION: f64 = 4e-10;

/// Effective modulus `E*` (Pa) of two elastic bodies:
/// `1 / E* = (1 - nu1^2) / E1 + (1 - nu2^2) / E2`, from Young's moduli `E` (Pa) and Poisson
/// ratios `nu`. A rigid wall is `E2 = f64::INFINITY`.
#[must_use]
pub fn effective_modulus(particle_modulus: f64, particle_poisson: f64, wall_modulus: f64, wall_poisson: f64) -> f64 {
    1.0 / ((1.0 - particle_poisson * particle_poisson) / particle_modulus
        + (1.0 - wall_poisson * wall_poisson) / wall_modulus)
}

/// Mass (kg) of a sphere of radius `radius` (m) and density `density` (kg/m^3).
#[must_use]
pub fn sphere_mass(radius: f64, density: f64) -> f64 {
    4.0 / 3.0 * PI * radius.powi(3) * density
}

/// Energy (J) an elastic adhesive impact loses to the JKR neck:
/// `W_L = C_W (w^5 R^4 / E*^2)^(1/3)`, for radius `R` (m), effective modulus `E*` (Pa) and work
/// of adhesion `w` (J/m^2). See the module doc for the derivation.
#[must_use]
pub fn jkr_energy_loss(radius: f64, effective_modulus: f64, work_of_adhesion: f64) -> f64 {
    // (w^5 R^4 / E*^2)^(1/3) written as w (w^2 (R^2 / E*)^2)^(1/3), so that w^5 and R^4 are
    // never formed on their own (tested finite from R = 1e-12 m, E* = 1e3 Pa up).
    let w = work_of_adhesion;
    JKR_LOSS_COEFFICIENT * w * (w * w * (radius * radius / effective_modulus).powi(2)).cbrt()
}

/// Capture velocity (m/s) of an elastic adhesive sphere after Thornton & Ning (1998):
/// `vc = C_v (w^5 / (rho^3 E*^2 R^5))^(1/6)`, radius `R` (m), density `rho` (kg/m^3), effective
/// modulus `E*` (Pa), work of adhesion `w` (J/m^2). `vc ~ R^(-5/6)` (Johnson & Pollock 1994).
#[must_use]
pub fn jkr_capture_velocity(radius: f64, density: f64, effective_modulus: f64, work_of_adhesion: f64) -> f64 {
    let w = work_of_adhesion;
    // (w^5 / (rho^3 E*^2 R^5))^(1/6) as products of sixth roots, so no power overflows.
    let root = |x: f64| x.sqrt().cbrt();
    JKR_VELOCITY_COEFFICIENT * root(w / radius).powi(5) / (density.sqrt() * effective_modulus.cbrt())
}

/// Impact speed (m/s) at which a Hertzian impact first reaches the limiting contact pressure
/// `p_y` (Pa): `v_y = (pi^2 / sqrt(40)) sqrt(p_y^5 / (E*^4 rho)) = 1.5605 sqrt(p_y^5 / (E*^4
/// rho))`, independent of size. From Hertz's largest overlap
/// `delta = (15 m v^2 / (16 E* sqrt(R)))^(2/5)` and largest pressure
/// `p0 = (2 E* / pi) sqrt(delta / R)`. Plastic flow starts at `p0 = 1.6 Y` for a yield stress
/// `Y` (Johnson, Contact Mechanics, 1985); [`jkr_capture_velocity`] holds only below `v_y`.
#[must_use]
pub fn yield_velocity(density: f64, effective_modulus: f64, limiting_pressure: f64) -> f64 {
    let ratio = limiting_pressure / effective_modulus;
    PI * PI / 40f64.sqrt() * (ratio.powi(4) * limiting_pressure / density).sqrt()
}

/// Tabor's parameter above which a contact is JKR-like and [`jkr_capture_velocity`] applies.
pub const JKR_TABOR_MIN: f64 = 5.0;
/// Tabor's parameter below which a contact is DMT-like (stiff, small particles).
pub const DMT_TABOR_MAX: f64 = 0.1;

/// Tabor's parameter `mu = (R w^2 / (E*^2 z0^3))^(1/3)`: the neck's height over the range of
/// the surface forces. JKR-like above [`JKR_TABOR_MIN`], DMT-like below [`DMT_TABOR_MAX`].
#[must_use]
pub fn tabor_parameter(radius: f64, effective_modulus: f64, work_of_adhesion: f64, separation: f64) -> f64 {
    (radius * (work_of_adhesion / effective_modulus).powi(2)).cbrt() / separation
}

/// Depth (J) of the van der Waals well of a smooth rigid sphere of radius `R` (m) touching a
/// plane at separation `z0` (m): `E0 = A R / (6 z0)` for Hamaker constant `A` (J), `z0 << R`.
#[must_use]
pub fn hamaker_well_depth(hamaker: f64, radius: f64, separation: f64) -> f64 {
    hamaker * radius / (6.0 * separation)
}

/// Capture velocity (m/s) of a rigid particle of mass `m` (kg) in a well of depth `E0` (J) with
/// restitution `e0` without adhesion, after Dahneke (1971):
/// `vc = sqrt(2 E0 / m) sqrt(1 - e0^2) / e0`. `e0 = 1` gives 0 (nothing is captured by speed);
/// `e0 -> 0` gives an unbounded `vc` (everything sticks).
#[must_use]
pub fn dahneke_capture_velocity(mass: f64, well_depth: f64, restitution: f64) -> f64 {
    (2.0 * well_depth / mass).sqrt() * (1.0 - restitution * restitution).sqrt() / restitution
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64, rel: f64) -> bool {
        (a - b).abs() <= rel * b.abs()
    }

    /// The JKR curve with `w = R = E* = 1`, parameterised by the contact radius.
    fn overlap(a: f64) -> f64 {
        a * a - (2.0 * PI * a).sqrt()
    }
    fn force(a: f64) -> f64 {
        4.0 / 3.0 * a.powi(3) - (8.0 * PI * a.powi(3)).sqrt()
    }

    #[test]
    fn loss_coefficient_is_the_jkr_neck_integrated_numerically() {
        // From the least overlap (d delta / d a = 0) up to delta = 0, trapezoids in a.
        let a_sep = ((2.0 * PI).sqrt() / 4.0).powf(2.0 / 3.0);
        let a_zero = (2.0 * PI).cbrt();
        assert!(overlap(a_zero).abs() < 1e-12);
        let n = 200_000;
        let mut work = 0.0;
        for i in 0..n {
            let (a0, a1) =
                (a_sep + (a_zero - a_sep) * i as f64 / n as f64, a_sep + (a_zero - a_sep) * (i + 1) as f64 / n as f64);
            work -= 0.5 * (force(a0) + force(a1)) * (overlap(a1) - overlap(a0));
        }
        assert!(close(work, JKR_LOSS_COEFFICIENT, 1e-9), "{work}");
        let closed = (2.0 * PI).powf(5.0 / 3.0) * (0.3 + 2f64.powf(-8.0 / 3.0) / 5.0);
        assert!(close(closed, JKR_LOSS_COEFFICIENT, 1e-15));
        // The neck breaks at F = -5/6 pi w R and delta_c = -3/4 (pi^2)^(1/3).
        assert!(close(force(a_sep), -5.0 / 6.0 * PI, 1e-12));
        assert!(close(overlap(a_sep), -0.75 * (PI * PI).cbrt(), 1e-12));
    }

    #[test]
    fn velocity_coefficient_converts_the_loss_into_kinetic_energy() {
        assert!(close((3.0 * JKR_LOSS_COEFFICIENT / (2.0 * PI)).sqrt(), JKR_VELOCITY_COEFFICIENT, 1e-15));
        let (r, rho, e, w) = (3e-6, 2500.0, 5e10, 0.04);
        let vc = jkr_capture_velocity(r, rho, e, w);
        let kinetic = 0.5 * sphere_mass(r, rho) * vc * vc;
        assert!(close(kinetic, jkr_energy_loss(r, e, w), 1e-12));
    }

    #[test]
    fn jkr_capture_velocity_by_hand() {
        // w = 0.1, R = 1 um, E* = 10 GPa, rho = 1000:
        // w^5 / (rho^3 E*^2 R^5) = 1e-5 / (1e9 1e20 1e-30) = 1e-4; 1.8402 * 1e-4^(1/6) = 0.39646.
        let vc = jkr_capture_velocity(1e-6, 1000.0, 1e10, 0.1);
        assert!(close(vc, JKR_VELOCITY_COEFFICIENT * 1e-4f64.powf(1.0 / 6.0), 1e-12));
        assert!(close(vc, 0.396_46, 1e-4), "{vc}");
        // W_L = C_W (w^5 R^4 / E*^2)^(1/3) = C_W (1e-5 1e-24 / 1e20)^(1/3) = C_W 1e-49^(1/3).
        assert!(close(jkr_energy_loss(1e-6, 1e10, 0.1), JKR_LOSS_COEFFICIENT * 1e-49f64.cbrt(), 1e-12));
    }

    #[test]
    fn jkr_capture_velocity_scales_as_the_minus_five_sixth_power_of_size() {
        let at = |r: f64| jkr_capture_velocity(r, 2000.0, 3e10, 0.05);
        for r in [1e-8, 1e-6, 1e-4] {
            assert!(close(at(2.0 * r) / at(r), 2f64.powf(-5.0 / 6.0), 1e-12));
        }
        // and as w^(5/6), rho^(-1/2), E*^(-1/3)
        let base = jkr_capture_velocity(1e-6, 2000.0, 3e10, 0.05);
        assert!(close(jkr_capture_velocity(1e-6, 2000.0, 3e10, 0.1) / base, 2f64.powf(5.0 / 6.0), 1e-12));
        assert!(close(jkr_capture_velocity(1e-6, 8000.0, 3e10, 0.05) / base, 0.5, 1e-12));
        assert!(close(jkr_capture_velocity(1e-6, 2000.0, 24e10, 0.05) / base, 0.5, 1e-12));
    }

    #[test]
    fn extreme_inputs_stay_finite() {
        for r in [1e-12, 1e-9, 1e-3, 1.0] {
            for e in [1e3, 1e9, 1e13] {
                for w in [1e-6, 1e-2, 10.0] {
                    let vc = jkr_capture_velocity(r, 1e4, e, w);
                    let loss = jkr_energy_loss(r, e, w);
                    assert!(vc.is_finite() && vc > 0.0 && loss.is_finite() && loss > 0.0, "{r} {e} {w}");
                }
            }
        }
    }

    #[test]
    fn yield_velocity_is_where_hertz_pressure_reaches_the_limit() {
        let (rho, e, p_y) = (7800.0, 1.1e11, 1.5e9);
        let v = yield_velocity(rho, e, p_y);
        for r in [1e-6, 1e-3] {
            let m = sphere_mass(r, rho);
            let delta = (15.0 * m * v * v / (16.0 * e * r.sqrt())).powf(0.4);
            let p0 = 2.0 * e / PI * (delta / r).sqrt();
            assert!(close(p0, p_y, 1e-12), "{p0}");
        }
        assert!(close(PI * PI / 40f64.sqrt(), 1.5605, 1e-4));
    }

    #[test]
    fn effective_modulus_and_tabor_parameter_by_hand() {
        // Two steels: E* = E / (2 (1 - nu^2)) = 200e9 / 1.82.
        assert!(close(effective_modulus(200e9, 0.3, 200e9, 0.3), 200e9 / 1.82, 1e-12));
        // A rigid wall leaves the particle's plane-strain modulus.
        assert!(close(effective_modulus(70e9, 0.2, f64::INFINITY, 0.3), 70e9 / 0.96, 1e-12));
        // R w^2 / E*^2 = 1e-6 * 1e-2 / 1e20 = 1e-28, cube root 4.6416e-10, over 4e-10: 1.1604.
        assert!(close(tabor_parameter(1e-6, 1e10, 0.1, 4e-10), 1e-28f64.cbrt() / 4e-10, 1e-12));
    }

    #[test]
    fn dahneke_capture_velocity_by_hand_and_by_energy() {
        // A = 1e-19 J, R = 1 um, z0 = 0.4 nm: E0 = 1e-25 / 2.4e-9 = 4.1667e-17 J.
        let well = hamaker_well_depth(1e-19, 1e-6, 4e-10);
        assert!(close(well, 1e-25 / 2.4e-9, 1e-12));
        let m = sphere_mass(1e-6, 1000.0);
        let e0 = 0.8;
        let vc = dahneke_capture_velocity(m, well, e0);
        assert!(close(vc, (2.0 * well / m).sqrt() * 0.6 / 0.8, 1e-12));
        // At vc the particle leaves the contact with exactly the well depth.
        let leaving = e0 * e0 * (0.5 * m * vc * vc + well);
        assert!(close(leaving, well, 1e-12));
        assert_eq!(dahneke_capture_velocity(m, well, 1.0), 0.0);
        assert!(dahneke_capture_velocity(m, well, 1e-3) > 100.0 * vc);
    }

    #[test]
    fn the_contact_simulator_captures_near_the_jkr_velocity() {
        // The simulator's linear neck dissipates F_po delta_c / 2 = pi^(5/3) (w^5 R^4 / E*^2)^(1/3)
        // where JKR's dissipates C_W (...)^(1/3), so without damping its capture velocity is
        // sqrt(pi^(5/3) / C_W) = 0.975 of the theory's, at every radius.
        let expected = (PI.powf(5.0 / 3.0) / JKR_LOSS_COEFFICIENT).sqrt();
        for radius in [0.5e-6, 5e-6] {
            let model = crate::contact::ContactModel {
                radius,
                density: 2000.0,
                effective_modulus: 2e10,
                damping_time: 0.0,
                work_of_adhesion: 0.05,
            };
            let theory = jkr_capture_velocity(radius, 2000.0, 2e10, 0.05);
            let simulated = model.capture_velocity(0.2 * theory, 5.0 * theory).expect("bracket holds");
            assert!(close(simulated / theory, expected, 5e-3), "{radius}: {}", simulated / theory);
        }
    }
}
