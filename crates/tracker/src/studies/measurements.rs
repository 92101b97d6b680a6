//! Measured deposition to set runs beside: data, not models (the models are in
//! [`correlations`](crate::correlations)).
//!
//! Sippola & Nazaroff (2004), *Experiments measuring particle deposition from fully developed
//! turbulent flow in ventilation ducts*, Aerosol Sci. Technol. 38:914-925 (and Sippola's 2002
//! thesis, *Particle deposition in ventilation ducts*, UC Berkeley, doi:10.2172/810494):
//! monodisperse fluorescent particles in a horizontal galvanised-steel duct of 15 cm square
//! section, hydraulically smooth, at nominal air speeds of 2.2, 5.3 and 9.0 m/s; deposits
//! counted on panels of the floor, a side wall and the ceiling, where the flow is fully
//! developed. On the vertical side wall gravity acts along the surface, so its deposition is
//! the turbulent (diffusion and turbophoresis) part that channel correlations describe. The
//! sixteen steel-duct tests as tabulated, with each test's particle density, in the
//! validation suite of NIST's Fire Dynamics Simulator (FDS Validation Guide, "Sippola Aerosol
//! Deposition Experiments"); the lined (rough) duct is left out.
//!
//! The papers of Liu & Agarwal (1974) and the data Papavergos & Hedley (1984) compiled, on
//! which the channel correlations rest, could not be read for their numbers; these are the
//! measurements depo shows beside its channel study instead.

use crate::model::air::{Aerodynamics, Air};

/// One steel-duct test of Sippola & Nazaroff (2004): deposition onto the duct's side wall.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DuctWallDeposition {
    /// The test's number in the source.
    pub test: u8,
    /// Particle diameter, m.
    pub diameter: f64,
    /// Particle density, kg/m^3.
    pub density: f64,
    /// Friction velocity `u*` of the duct flow, m/s.
    pub friction_velocity: f64,
    /// Deposition velocity onto the side wall, m/s.
    pub deposition_velocity: f64,
    /// The same made dimensionless, `V+ = v_d / u*`, as the source gives it (two digits).
    pub v_plus: f64,
}

impl DuctWallDeposition {
    /// The particle's `tau+ = tau u*^2 / nu` in `air` (the source's air at 22-27 C is not
    /// given per test; at 20 C instead of 25 C `tau+` comes out about 5 % higher).
    #[must_use]
    pub fn tau_plus(&self, air: &Air) -> f64 {
        let tau = Aerodynamics::new(self.diameter, self.density, air, 0.0).relaxation_time;
        tau * self.friction_velocity * self.friction_velocity / air.kinematic_viscosity()
    }
}

const fn test(
    test: u8,
    diameter_um: f64,
    density: f64,
    friction_velocity: f64,
    deposition_velocity: f64,
    v_plus: f64,
) -> DuctWallDeposition {
    DuctWallDeposition { test, diameter: diameter_um * 1e-6, density, friction_velocity, deposition_velocity, v_plus }
}

/// Sippola & Nazaroff (2004), steel duct, side wall: tests 1-16 (see the module's doc).
pub const SIPPOLA_NAZAROFF_2004: [DuctWallDeposition; 16] = [
    test(1, 1.0, 1350.0, 0.12, 1.320e-6, 1.1e-5),
    test(2, 2.8, 1170.0, 0.12, 8.160e-6, 6.8e-5),
    test(3, 5.2, 1210.0, 0.12, 3.720e-5, 3.1e-4),
    test(4, 9.1, 1030.0, 0.13, 9.880e-5, 7.6e-4),
    test(5, 16.0, 950.0, 0.12, 2.040e-4, 1.7e-3),
    test(6, 1.0, 1350.0, 0.28, 6.160e-6, 2.2e-5),
    test(7, 1.0, 1350.0, 0.26, 6.500e-6, 2.5e-5),
    test(8, 3.1, 1170.0, 0.26, 1.300e-5, 5.0e-5),
    test(9, 5.2, 1210.0, 0.27, 9.450e-5, 3.5e-4),
    test(10, 9.8, 1030.0, 0.28, 2.800e-4, 1.0e-3),
    test(11, 16.0, 950.0, 0.28, 4.200e-3, 1.5e-2),
    test(12, 1.0, 1350.0, 0.45, 1.170e-5, 2.6e-5),
    test(13, 3.1, 1170.0, 0.42, 4.620e-5, 1.1e-4),
    test(14, 5.4, 1210.0, 0.44, 6.160e-4, 1.4e-3),
    test(15, 8.7, 1030.0, 0.46, 1.610e-3, 3.5e-3),
    test(16, 15.0, 950.0, 0.45, 1.080e-2, 2.4e-2),
];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_test_gives_v_plus_as_its_deposition_velocity_over_u_star() {
        // A check on the transcription: the two columns were typed separately.
        for t in SIPPOLA_NAZAROFF_2004 {
            let v_plus = t.deposition_velocity / t.friction_velocity;
            assert!((v_plus / t.v_plus - 1.0).abs() < 0.05, "test {}: {v_plus} against {}", t.test, t.v_plus);
        }
    }

    #[test]
    fn tau_plus_matches_a_hand_computation() {
        // Test 9: 5.2 um, 1210 kg/m^3, u* = 0.27 m/s in standard air (mu 1.81e-5 Pa s,
        // rho 1.204 kg/m^3, mean free path 0.0664 um): Cc = 1 + (0.0664/5.2)(2.34 + 1.05
        // exp(-0.39 * 5.2/0.0664)) = 1.029895; tau = 1210 (5.2e-6)^2 Cc / (18 * 1.81e-5)
        // = 1.03427e-4 s; tau+ = tau 0.27^2 / (1.81e-5/1.204) = 0.50154.
        let t = SIPPOLA_NAZAROFF_2004[8];
        assert_eq!(t.test, 9);
        let tau_plus = t.tau_plus(&Air::standard());
        assert!((tau_plus / 0.50154 - 1.0).abs() < 2e-3, "{tau_plus}");
    }
}
