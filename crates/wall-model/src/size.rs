//! Capture velocity against particle size (paper Fig. 8), for polydisperse clouds.
//!
//! ```text
//! vc(d) = vc_ref (d / d_ref)^(-alpha)
//! ```
//!
//! with `vc_ref` the law's capture velocity at the reference diameter `d_ref` (m). The paper's
//! three simulation rows (35, 70, 140 um) give `alpha = 1.51` ([`FIG8_EXPONENT`]); the JKR
//! theory of Johnson & Pollock (1994) gives `vc ~ r^(-5/6)` ([`JKR_EXPONENT`]). Only `vc`
//! scales: `k` and `kappa` keep the law's values (the same rows show `kappa` falling as about
//! `d^-1.69`; where that matters, use one law per size class).
//!
//! A host computes each particle's capture velocity once (particles keep their size) and hands
//! it to the kernel with [`crate::Impacts::with_capture_velocity`].

use crate::params::ParamError;

/// `alpha` of the power law fitted across the paper's simulation rows (Fig. 8).
pub const FIG8_EXPONENT: f64 = 1.51;
/// `alpha` of the JKR theory, `vc ~ r^(-5/6)`.
pub const JKR_EXPONENT: f64 = 5.0 / 6.0;

/// How the capture velocity scales with particle diameter.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SizeDependence {
    reference_diameter: f64,
    exponent: f64,
}

impl SizeDependence {
    /// `vc ~ d^(-exponent)`, anchored at `reference_diameter` (m, finite and positive);
    /// `exponent` must be finite.
    pub fn new(reference_diameter: f64, exponent: f64) -> Result<Self, ParamError> {
        if !(reference_diameter.is_finite() && reference_diameter > 0.0) {
            return Err(ParamError {
                field: "reference_diameter",
                value: reference_diameter,
                requirement: "must be finite and positive",
            });
        }
        if !exponent.is_finite() {
            return Err(ParamError { field: "exponent", value: exponent, requirement: "must be finite" });
        }
        Ok(Self { reference_diameter, exponent })
    }

    /// The reference diameter, m.
    #[must_use]
    pub fn reference_diameter(&self) -> f64 {
        self.reference_diameter
    }

    /// The exponent `alpha`.
    #[must_use]
    pub fn exponent(&self) -> f64 {
        self.exponent
    }

    /// `vc(d) = vc_ref (d / d_ref)^(-alpha)` for a diameter `d` (m). A non-positive or
    /// non-finite `d` gives NaN, which the kernel flags as an invalid particle.
    #[must_use]
    pub fn capture_velocity(&self, vc_ref: f64, diameter: f64) -> f64 {
        if diameter.is_finite() && diameter > 0.0 {
            vc_ref * (diameter / self.reference_diameter).powf(-self.exponent)
        } else {
            f64::NAN
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::presets::preset;

    #[test]
    fn fig8_power_law_reproduces_the_paper_s_simulation_rows() {
        let at_70 = preset("sim-70um").unwrap().params.vc;
        let size = SizeDependence::new(70e-6, FIG8_EXPONENT).unwrap();
        // 0.074 * 2^1.51 = 0.2108 (Table 1: 0.212); 0.074 * 2^-1.51 = 0.0260 (Table 1: 0.026).
        assert!((size.capture_velocity(at_70, 35e-6) - 0.2108).abs() < 5e-4);
        assert!((size.capture_velocity(at_70, 35e-6) - preset("sim-35um").unwrap().params.vc).abs() < 2e-3);
        assert!((size.capture_velocity(at_70, 140e-6) - preset("sim-140um").unwrap().params.vc).abs() < 1e-3);
        assert_eq!(size.capture_velocity(at_70, 70e-6), at_70);
        let jkr = SizeDependence::new(70e-6, JKR_EXPONENT).unwrap();
        assert!((jkr.capture_velocity(1.0, 140e-6) - 2f64.powf(-5.0 / 6.0)).abs() < 1e-15);
    }

    #[test]
    fn bad_sizes() {
        assert_eq!(SizeDependence::new(0.0, 1.0).unwrap_err().field, "reference_diameter");
        assert_eq!(SizeDependence::new(1e-5, f64::NAN).unwrap_err().field, "exponent");
        let size = SizeDependence::new(1e-5, 1.0).unwrap();
        assert!(size.capture_velocity(0.1, 0.0).is_nan() && size.capture_velocity(0.1, f64::INFINITY).is_nan());
    }
}
