//! The constants of the law and their validation.

use core::fmt;

/// The constants of the Brach & Dunn wall law (paper Eqs. 8 and 9), in SI units.
///
/// | field | meaning | unit | valid range |
/// |---|---|---|---|
/// | `k1`, `k2` | material restitution velocities of Eq. (8) | m/s | finite, `> 0` |
/// | `kappa1`, `kappa2` | adhesion velocities of Eq. (9) | m/s | finite, `> 0` |
/// | `p` | exponent of Eq. (8) | - | finite, `> 0` |
/// | `q` | exponent of Eq. (9) | - | finite, `> 0` |
/// | `vc` | capture velocity | m/s | finite; `<= 0` means the law never captures by speed |
/// | `mu` | Coulomb friction coefficient of the contact | - | finite, `>= 0` |
///
/// With `k1 = k2 = k` and `kappa1 = kappa2 = kappa` the law is the paper's Eq. (10); build that
/// case with [`LawParams::symmetric`]. `k1 > k2` is accepted, but the material restitution is
/// capped at 1 so that a wall never adds energy (see [`crate::law`]).
///
/// This is plain data with public fields (it mirrors the C struct `DepoLawParams`); it is
/// checked when a [`crate::WallLaw`] is made from it, or by [`LawParams::validate`].
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C)]
pub struct LawParams {
    pub k1: f64,
    pub k2: f64,
    pub kappa1: f64,
    pub kappa2: f64,
    pub p: f64,
    pub q: f64,
    pub vc: f64,
    pub mu: f64,
}

impl LawParams {
    /// The paper's Eq. (10) form: `k1 = k2 = k`, `kappa1 = kappa2 = kappa`, no friction.
    #[must_use]
    pub fn symmetric(k: f64, kappa: f64, vc: f64, p: f64, q: f64) -> Self {
        Self { k1: k, k2: k, kappa1: kappa, kappa2: kappa, p, q, vc, mu: 0.0 }
    }

    /// The same constants with friction coefficient `mu`.
    #[must_use]
    pub fn with_friction(self, mu: f64) -> Self {
        Self { mu, ..self }
    }

    /// Checks every field against the table above; the error names the first bad field.
    pub fn validate(&self) -> Result<(), ParamError> {
        let positive = [
            ("k1", self.k1),
            ("k2", self.k2),
            ("kappa1", self.kappa1),
            ("kappa2", self.kappa2),
            ("p", self.p),
            ("q", self.q),
        ];
        for (field, value) in positive {
            if !value.is_finite() {
                return Err(ParamError { field, value, requirement: "must be finite" });
            }
            if value <= 0.0 {
                return Err(ParamError { field, value, requirement: "must be positive" });
            }
        }
        if !self.vc.is_finite() {
            return Err(ParamError { field: "vc", value: self.vc, requirement: "must be finite" });
        }
        if !self.mu.is_finite() {
            return Err(ParamError { field: "mu", value: self.mu, requirement: "must be finite" });
        }
        if self.mu < 0.0 {
            return Err(ParamError { field: "mu", value: self.mu, requirement: "must not be negative" });
        }
        Ok(())
    }
}

/// A law constant out of its valid range.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ParamError {
    /// The field's name, as in [`LawParams`].
    pub field: &'static str,
    /// The rejected value.
    pub value: f64,
    /// What the field must satisfy.
    pub requirement: &'static str,
}

impl fmt::Display for ParamError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "invalid wall-law parameter {} = {}: {}", self.field, self.value, self.requirement)
    }
}

impl std::error::Error for ParamError {}

#[cfg(test)]
mod tests {
    use super::*;

    fn good() -> LawParams {
        LawParams::symmetric(12.5, 0.065, 0.074, 1.0, 0.5)
    }

    #[test]
    fn accepts_the_paper_s_constants_and_a_negative_capture_velocity() {
        assert_eq!(good().validate(), Ok(()));
        assert_eq!(LawParams { vc: -0.44, ..good() }.validate(), Ok(()));
        assert_eq!(good().with_friction(0.0).validate(), Ok(()));
    }

    #[test]
    fn rejects_each_bad_field_by_name() {
        let cases = [
            (LawParams { k1: 0.0, ..good() }, "k1", "must be positive"),
            (LawParams { k2: -1.0, ..good() }, "k2", "must be positive"),
            (LawParams { kappa1: f64::NAN, ..good() }, "kappa1", "must be finite"),
            (LawParams { kappa2: f64::INFINITY, ..good() }, "kappa2", "must be finite"),
            (LawParams { p: 0.0, ..good() }, "p", "must be positive"),
            (LawParams { q: -0.5, ..good() }, "q", "must be positive"),
            (LawParams { vc: f64::NEG_INFINITY, ..good() }, "vc", "must be finite"),
            (LawParams { mu: -0.1, ..good() }, "mu", "must not be negative"),
            (LawParams { mu: f64::NAN, ..good() }, "mu", "must be finite"),
        ];
        for (params, field, requirement) in cases {
            let err = params.validate().unwrap_err();
            assert_eq!((err.field, err.requirement), (field, requirement));
            assert!(err.to_string().contains(field));
        }
    }
}
