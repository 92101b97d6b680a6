//! The carrier gas and what it does to one particle: slip correction, drag relaxation time,
//! settling velocity and Brownian diffusivity. Plain functions of plain numbers, SI units.
//!
//! References: Hinds, *Aerosol Technology* (2nd ed., 1999), Eqs. 3.18-3.21 (slip), 3.7 and
//! 3.29 (relaxation and settling), 7.23 (Stokes-Einstein); Schiller & Naumann (1933) for drag
//! at finite particle Reynolds number.

/// Boltzmann's constant, J/K.
pub const BOLTZMANN: f64 = 1.380_649e-23;
/// Standard gravity, m/s^2.
pub const STANDARD_GRAVITY: f64 = 9.806_65;
/// Mean free path of air at the reference state of Allen & Raabe's slip constants, 0.0673 um
/// at 296.15 K and 101.325 kPa (Allen & Raabe 1985; Hinds 1999, Sec. 3.3).
const REFERENCE_MEAN_FREE_PATH: f64 = 0.0673e-6;
const REFERENCE_TEMPERATURE: f64 = 296.15;
const REFERENCE_PRESSURE: f64 = 101_325.0;
/// Sutherland's constant of air, K.
const SUTHERLAND: f64 = 110.4;

/// The carrier gas. [`Air::standard`] is dry air at 20 C and one atmosphere.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Air {
    /// Temperature, K.
    pub temperature: f64,
    /// Pressure, Pa.
    pub pressure: f64,
    /// Density, kg/m^3.
    pub density: f64,
    /// Dynamic viscosity, Pa s.
    pub viscosity: f64,
}

impl Default for Air {
    fn default() -> Self {
        Self::standard()
    }
}

impl Air {
    /// Dry air at 293.15 K and 101325 Pa: density 1.204 kg/m^3, viscosity 1.81e-5 Pa s.
    #[must_use]
    pub fn standard() -> Self {
        Self { temperature: 293.15, pressure: 101_325.0, density: 1.204, viscosity: 1.81e-5 }
    }

    /// Kinematic viscosity `nu = mu / rho_air`, m^2/s.
    #[must_use]
    pub fn kinematic_viscosity(&self) -> f64 {
        self.viscosity / self.density
    }

    /// Mean free path of air, m: the value aerosol practice pairs with Allen & Raabe's slip
    /// constants, 0.0673 um at 296.15 K and 101.325 kPa, carried to this temperature and
    /// pressure by Willeke's (1976) Sutherland form (as in Hinds 1999, Ch. 2),
    /// `lambda = lambda_r (p_r / p) (T / T_r) (1 + S / T_r) / (1 + S / T)`, `S = 110.4 K`:
    /// 0.0664 um for standard air (20 C). Kinetic theory with the viscosity gives 0.065 um,
    /// which would make slip and diffusivity 1-1.4 % low at 0.1 um and below.
    #[must_use]
    pub fn mean_free_path(&self) -> f64 {
        let t = self.temperature;
        REFERENCE_MEAN_FREE_PATH
            * (REFERENCE_PRESSURE / self.pressure)
            * (t / REFERENCE_TEMPERATURE)
            * (1.0 + SUTHERLAND / REFERENCE_TEMPERATURE)
            / (1.0 + SUTHERLAND / t)
    }
}

/// Cunningham slip correction (Hinds Eq. 3.20, Allen & Raabe's constants):
/// `Cc = 1 + (lambda / d) (2.34 + 1.05 exp(-0.39 d / lambda))` for a diameter `d` (m).
#[must_use]
pub fn slip_correction(diameter: f64, mean_free_path: f64) -> f64 {
    let kn = mean_free_path / diameter;
    1.0 + kn * (2.34 + 1.05 * (-0.39 / kn).exp())
}

/// Drag relaxation time in the Stokes regime, `tau = rho_p d^2 Cc / (18 mu)`, s.
#[must_use]
pub fn relaxation_time(diameter: f64, particle_density: f64, slip: f64, air: &Air) -> f64 {
    particle_density * diameter * diameter * slip / (18.0 * air.viscosity)
}

/// Stokes-Einstein diffusivity with slip, `D = k T Cc / (3 pi mu d)`, m^2/s.
#[must_use]
pub fn diffusivity(diameter: f64, slip: f64, air: &Air) -> f64 {
    BOLTZMANN * air.temperature * slip / (3.0 * std::f64::consts::PI * air.viscosity * diameter)
}

/// Schiller-Naumann drag factor `f = 1 + 0.15 Re_p^0.687` (valid for `Re_p < 800`) by which
/// drag exceeds Stokes drag at particle Reynolds number `Re_p = |u - v| d / nu`; the
/// relaxation time becomes `tau / f`.
#[must_use]
pub fn schiller_naumann(reynolds: f64) -> f64 {
    1.0 + 0.15 * reynolds.powf(0.687)
}

/// What a particle of one size and density needs for transport in `air`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aerodynamics {
    /// Diameter, m.
    pub diameter: f64,
    /// Mass, kg.
    pub mass: f64,
    /// Slip correction `Cc`.
    pub slip: f64,
    /// Stokes relaxation time `tau`, s.
    pub relaxation_time: f64,
    /// Terminal settling speed under `gravity` with buoyancy, `tau g (1 - rho_air / rho_p)`, m/s
    /// (Stokes regime; see [`Aerodynamics::settling_speed_finite_reynolds`] beyond it).
    pub settling_speed: f64,
    /// Brownian diffusivity `D`, m^2/s.
    pub diffusivity: f64,
}

impl Aerodynamics {
    /// For a sphere of `diameter` (m) and `particle_density` (kg/m^3) in `air` under `gravity`
    /// (m/s^2, magnitude).
    #[must_use]
    pub fn new(diameter: f64, particle_density: f64, air: &Air, gravity: f64) -> Self {
        let slip = slip_correction(diameter, air.mean_free_path());
        let tau = relaxation_time(diameter, particle_density, slip, air);
        let mass = depo_wall_model::theory::sphere_mass(0.5 * diameter, particle_density);
        Self {
            diameter,
            mass,
            slip,
            relaxation_time: tau,
            settling_speed: tau * gravity * (1.0 - air.density / particle_density),
            diffusivity: diffusivity(diameter, slip, air),
        }
    }

    /// Settling speed with Schiller-Naumann drag, solved by fixed-point iteration of
    /// `vs = vs_stokes / f(Re_p(vs))`; equal to the Stokes value for `Re_p << 1`.
    #[must_use]
    pub fn settling_speed_finite_reynolds(&self, air: &Air) -> f64 {
        let nu = air.kinematic_viscosity();
        let mut vs = self.settling_speed;
        for _ in 0..100 {
            let next = self.settling_speed / schiller_naumann(vs.abs() * self.diameter / nu);
            // Averaging damps the oscillation of the plain iteration at larger Re_p.
            let next = 0.5 * (vs + next);
            if (next - vs).abs() <= 1e-12 * vs.abs() {
                return next;
            }
            vs = next;
        }
        vs
    }

    /// Thermal velocity variance per axis, `k T / m`, m^2/s^2.
    #[must_use]
    pub fn thermal_variance(&self, air: &Air) -> f64 {
        BOLTZMANN * air.temperature / self.mass
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64, rel: f64) -> bool {
        (a - b).abs() <= rel * b.abs()
    }

    #[test]
    fn mean_free_path_of_standard_air_is_the_aerosol_value() {
        // At the reference state itself, 0.0673 um; at 20 C by hand:
        // 0.0673 (293.15 / 296.15) (1 + 110.4 / 296.15) / (1 + 110.4 / 293.15) = 0.066432 um,
        // within Hinds' 0.066 um at 20 C.
        let reference = Air { temperature: 296.15, ..Air::standard() };
        assert!(close(reference.mean_free_path(), 0.0673e-6, 1e-12));
        let lambda = Air::standard().mean_free_path();
        assert!(close(lambda, 0.066_432e-6, 1e-4), "{lambda}");
        // Inversely proportional to pressure.
        let half = Air { pressure: 0.5 * 101_325.0, ..Air::standard() };
        assert!(close(half.mean_free_path(), 2.0 * lambda, 1e-12));
    }

    #[test]
    fn slip_correction_matches_hinds_table() {
        // By hand from Eq. 3.20 with lambda = 0.066 um: 0.01 um: 1 + 6.6 (2.34 + 1.05 e^-0.0591)
        // = 22.98; 0.1 um: 1 + 0.66 (2.34 + 1.05 e^-0.591) = 2.928. Hinds Table A.6: Cc(1 um) =
        // 1.164, Cc(10 um) = 1.016.
        let lambda = 0.066e-6;
        for (d, cc) in [(0.01e-6, 22.98), (0.1e-6, 2.928), (1e-6, 1.164), (10e-6, 1.016)] {
            assert!(close(slip_correction(d, lambda), cc, 0.01), "d {d}: {}", slip_correction(d, lambda));
        }
    }

    #[test]
    fn settling_and_diffusivity_match_hand_values() {
        // 1 um, unit density, standard air: tau = 1000 (1e-6)^2 Cc / (18 * 1.81e-5).
        let air = Air::standard();
        let a = Aerodynamics::new(1e-6, 1000.0, &air, STANDARD_GRAVITY);
        let tau = 1000.0 * 1e-12 * a.slip / (18.0 * 1.81e-5);
        assert!(close(a.relaxation_time, tau, 1e-12));
        // Hinds Table A.6: settling velocity 3.5e-5 m/s, D = 2.7e-11 m^2/s at 1 um.
        assert!(close(a.settling_speed, 3.5e-5, 0.02), "{}", a.settling_speed);
        assert!(close(a.diffusivity, 2.7e-11, 0.03), "{}", a.diffusivity);
        // 0.1 um: D = 6.8e-10 m^2/s (Hinds).
        let b = Aerodynamics::new(0.1e-6, 1000.0, &air, STANDARD_GRAVITY);
        assert!(close(b.diffusivity, 6.8e-10, 0.03), "{}", b.diffusivity);
        // Einstein: D = k T tau / m.
        assert!(close(b.diffusivity, b.thermal_variance(&air) * b.relaxation_time, 1e-12));
    }

    #[test]
    fn finite_reynolds_settling_is_slower_for_large_particles_only() {
        let air = Air::standard();
        let small = Aerodynamics::new(5e-6, 1000.0, &air, STANDARD_GRAVITY);
        assert!(close(small.settling_speed_finite_reynolds(&air), small.settling_speed, 1e-3));
        // 100 um water drop: Stokes gives 0.30 m/s, measured about 0.25 m/s (Re_p ~ 1.7).
        let large = Aerodynamics::new(100e-6, 1000.0, &air, STANDARD_GRAVITY);
        let vs = large.settling_speed_finite_reynolds(&air);
        assert!(vs < 0.9 * large.settling_speed && vs > 0.22 && vs < 0.28, "{vs}");
        let re = vs * 100e-6 / air.kinematic_viscosity();
        assert!(close(vs * schiller_naumann(re), large.settling_speed, 1e-9));
    }
}
