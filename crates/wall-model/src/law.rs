//! The coefficients of the law: material restitution `R` (Eq. 8), adhesion `rho` (Eq. 9),
//! overall restitution `e = R (1 - rho)` (Eq. 2) and the capture rule.
//!
//! All speeds are `speed = |vn| > 0`, the magnitude of the normal velocity of an impact, in m/s.
//! The formulas are evaluated in a non-dimensional form that cannot overflow:
//!
//! ```text
//! R   = k1^p / (k2^p + |vn|^p)            = 1 / A,  A = (k2/k1)^p + (|vn|/k1)^p        (8)
//! rho = kappa1^q / (kappa2^q + |u|^q)     = 1 / B,  B = (kappa2/kappa1)^q + (|u|/kappa1)^q  (9)
//! u   = |vn| - vc
//! e   = R (1 - rho)                       = (B - 1) / (A B)                               (2)
//! ```
//!
//! `A` is clamped to `[1, BIG]` and `B` to `[0, BIG]` ([`Real::BIG`]: 1e150 in `f64`, 1e18 in
//! `f32`), so `R <= 1` (a wall never adds energy, even when `k1 > k2`), `A B` never overflows,
//! and `e` costs one division. The clamp at `BIG` changes `R` and `rho` only where they are below
//! `1/BIG` anyway.
//!
//! **Capture rule** (docs/MODEL.md): an impact is captured when `vc > 0` and `|vn| <= vc`, or
//! whenever the law gives `e <= 0` (possible when `kappa1 > kappa2`, where `rho` exceeds 1).
//! The paper's `|vn - vc|` with `vn < 0` never reaches `rho = 1`; its intent, capture where
//! `|vn| = vc` (Eq. 14), is `u = |vn| - vc`. A captured impact reports `rho = 1` and `e = 0`.

use crate::params::LawParams;
use crate::power::Power;
use crate::real::{select, Real};

/// The law's constants in the working precision, precomputed once per batch.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LawConstants<T> {
    /// `(k2/k1)^p`.
    pub k_ratio: T,
    /// `1/k1`, in s/m.
    pub inv_k1: T,
    /// `(kappa2/kappa1)^q`.
    pub kappa_ratio: T,
    /// `1/kappa1`, in s/m.
    pub inv_kappa1: T,
    /// Capture velocity `vc`, m/s.
    pub vc: T,
    /// `max(vc, 0)`: impacts with `|vn|` at or below this are captured.
    pub capture_speed: T,
    /// Friction coefficient.
    pub mu: T,
    /// Exponent of Eq. (8).
    pub p: T,
    /// Exponent of Eq. (9).
    pub q: T,
}

impl<T: Real> LawConstants<T> {
    /// Precomputes the constants (in `f64`, then rounded to `T`). `params` must be valid.
    #[must_use]
    pub fn new(params: &LawParams) -> Self {
        let LawParams { k1, k2, kappa1, kappa2, p, q, vc, mu } = *params;
        Self {
            k_ratio: T::from_f64((k2 / k1).powf(p)),
            inv_k1: T::from_f64(1.0 / k1),
            kappa_ratio: T::from_f64((kappa2 / kappa1).powf(q)),
            inv_kappa1: T::from_f64(1.0 / kappa1),
            vc: T::ZERO,
            capture_speed: T::ZERO,
            mu: T::from_f64(mu),
            p: T::from_f64(p),
            q: T::from_f64(q),
        }
        .with_capture_velocity(T::from_f64(vc))
    }

    /// The same constants with capture velocity `vc` (m/s): a particle's own, in a
    /// polydisperse batch (see [`crate::size`]).
    #[inline(always)]
    #[must_use]
    pub fn with_capture_velocity(self, vc: T) -> Self {
        Self { vc, capture_speed: vc.max(T::ZERO), ..self }
    }
}

/// The coefficients of one impact.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Coefficients<T> {
    /// Material restitution `R`, Eq. (8), in `(0, 1]`.
    pub restitution: T,
    /// Adhesion coefficient `rho`, Eq. (9), in `(0, 1]`; exactly 1 when captured.
    pub adhesion: T,
    /// Overall restitution `e = -Vn/vn = R (1 - rho)`, Eq. (2); exactly 0 when captured.
    pub overall: T,
    /// The capture rule's verdict.
    pub captured: bool,
}

/// The bases of the law's two powers at `speed = |vn|`: `|vn|/k1` of Eq. (8) and `|u|/kappa1`
/// of Eq. (9), with `u = |vn| - vc`.
#[inline(always)]
#[must_use]
pub fn power_bases<T: Real>(c: &LawConstants<T>, speed: T) -> [T; 2] {
    [speed * c.inv_k1, (speed - c.vc).abs() * c.inv_kappa1]
}

/// The law's two powers at one speed: `(|vn|/k1)^p` and `(|u|/kappa1)^q`. Everything else in
/// the law is a few additions and one division; the batch kernel evaluates general exponents'
/// powers in passes of their own and hands them in.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Powers<T> {
    /// `(|vn|/k1)^p`, Eq. (8).
    pub material: T,
    /// `(|u|/kappa1)^q`, Eq. (9).
    pub adhesion: T,
}

/// The law's two powers at `speed = |vn|`.
#[inline(always)]
#[must_use]
pub fn powers<T: Real, P: Power<T>, Q: Power<T>>(c: &LawConstants<T>, p: P, q: Q, speed: T) -> Powers<T> {
    let [material, adhesion] = power_bases(c, speed);
    Powers { material: p.pow(material), adhesion: q.pow(adhesion) }
}

/// `A` of Eq. (8) from its power: `R = 1/A`, clamped to `[1, BIG]`.
#[inline(always)]
fn material_denominator_of<T: Real>(c: &LawConstants<T>, power: T) -> T {
    (c.k_ratio + power).max(T::ONE).min(T::BIG)
}

/// `B` of Eq. (9) from its power: `rho = 1/B`, clamped to `[0, BIG]`.
#[inline(always)]
fn adhesion_denominator_of<T: Real>(c: &LawConstants<T>, power: T) -> T {
    (c.kappa_ratio + power).min(T::BIG)
}

/// `A` of Eq. (8): `R = 1/A`, clamped to `[1, BIG]`.
#[inline(always)]
#[must_use]
pub fn material_denominator<T: Real, P: Power<T>>(c: &LawConstants<T>, p: P, speed: T) -> T {
    material_denominator_of(c, p.pow(power_bases(c, speed)[0]))
}

/// `B` of Eq. (9): `rho = 1/B`, clamped to `[0, BIG]`.
#[inline(always)]
#[must_use]
pub fn adhesion_denominator<T: Real, Q: Power<T>>(c: &LawConstants<T>, q: Q, speed: T) -> T {
    adhesion_denominator_of(c, q.pow(power_bases(c, speed)[1]))
}

/// Material restitution `R(|vn|)`, Eq. (8), capped at 1.
#[inline(always)]
#[must_use]
pub fn material_restitution<T: Real, P: Power<T>>(c: &LawConstants<T>, p: P, speed: T) -> T {
    T::ONE / material_denominator(c, p, speed)
}

/// Adhesion coefficient `rho(|vn|)` of Eq. (9) as the formula gives it, capped at 1
/// (without the capture rule, which [`coefficients`] applies).
#[inline(always)]
#[must_use]
pub fn adhesion<T: Real, Q: Power<T>>(c: &LawConstants<T>, q: Q, speed: T) -> T {
    (T::ONE / adhesion_denominator(c, q, speed)).min(T::ONE)
}

/// `R (1 - rho)` of Eq. (2) as the formulas give it, before the capture rule: may be `<= 0`.
#[inline(always)]
#[must_use]
pub fn restitution_formula<T: Real, P: Power<T>, Q: Power<T>>(c: &LawConstants<T>, p: P, q: Q, speed: T) -> T {
    formula_from_denominators(material_denominator(c, p, speed), adhesion_denominator(c, q, speed))
}

/// Eq. (2) from the denominators: `e = R (1 - rho) = (B - 1) / (A B)`.
#[inline(always)]
fn formula_from_denominators<T: Real>(a: T, b: T) -> T {
    (b - T::ONE) / (a * b)
}

/// The capture rule: `|vn| <= vc` (with `vc > 0`), or a formula restitution `e <= 0`, decided
/// from `B` (the `adhesion_denominator`) without the division: `e = (B - 1) / (A B)` with
/// `A >= 1` and `B >= 0` has the sign of `B - 1` (and is `-inf` for `B = 0`), so `e <= 0`
/// exactly when `B <= 1`. The kernel's outcome flag then does not wait for the division.
#[inline(always)]
#[must_use]
pub fn is_captured<T: Real>(c: &LawConstants<T>, speed: T, adhesion_denominator: T) -> bool {
    (speed <= c.capture_speed) | (adhesion_denominator <= T::ONE)
}

/// All coefficients of an impact of normal speed `|vn| > 0`, with the capture rule applied.
#[inline(always)]
#[must_use]
pub fn coefficients<T: Real, P: Power<T>, Q: Power<T>>(c: &LawConstants<T>, p: P, q: Q, speed: T) -> Coefficients<T> {
    coefficients_from_powers(c, speed, powers(c, p, q, speed))
}

/// [`coefficients`] from the law's two [`Powers`] at `speed = |vn|`.
#[inline(always)]
#[must_use]
pub fn coefficients_from_powers<T: Real>(c: &LawConstants<T>, speed: T, powers: Powers<T>) -> Coefficients<T> {
    let a = material_denominator_of(c, powers.material);
    let b = adhesion_denominator_of(c, powers.adhesion);
    let captured = is_captured(c, speed, b);
    Coefficients {
        restitution: T::ONE / a,
        adhesion: select(captured, T::ONE, (T::ONE / b).min(T::ONE)),
        overall: select(captured, T::ZERO, formula_from_denominators(a, b)),
        captured,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::power::{Exact, Half, One};
    use crate::presets::PRESETS;

    fn constants(k: f64, kappa: f64, vc: f64, p: f64, q: f64) -> LawConstants<f64> {
        LawConstants::new(&LawParams::symmetric(k, kappa, vc, p, q))
    }

    /// Eq. (10) written out literally, as a reader of the paper would.
    fn eq10(k: f64, kappa: f64, vc: f64, p: f64, q: f64, speed: f64) -> f64 {
        let u: f64 = speed - vc;
        k.powf(p) / (k.powf(p) + speed.powf(p)) * (1.0 - kappa.powf(q) / (kappa.powf(q) + u.abs().powf(q)))
    }

    #[test]
    fn hand_computed_values_li1997() {
        // k = 12.5, kappa = 0.065, vc = 0.074, p = 1, q = 1/2, |vn| = 1 m/s, by hand:
        // R = 12.5/13.5 = 0.925925926; rho = sqrt(.065)/(sqrt(.065)+sqrt(.926))
        //   = 0.254950976/(0.254950976 + 0.962288937) = 0.209450062; e = 0.731990683
        let c = constants(12.5, 0.065, 0.074, 1.0, 0.5);
        let co = coefficients(&c, One, Half, 1.0);
        assert!((co.restitution - 0.925_925_926).abs() < 1e-9);
        assert!((co.adhesion - 0.209_450_062).abs() < 1e-9, "{}", co.adhesion);
        assert!((co.overall - 0.731_990_683).abs() < 1e-9);
        assert!(!co.captured);
    }

    #[test]
    fn hand_computed_values_dahneke_eq13() {
        // p = q = 1 (Eq. 13): e = k/(k+|vn|) * |u|/(kappa+|u|); |vn| = 2, u = 1.033:
        // e = 556.3/558.3 * 1.033/1.306 = 0.996417697 * 0.790964778 = 0.788131
        let c = constants(556.3, 0.273, 0.967, 1.0, 1.0);
        let e = coefficients(&c, One, One, 2.0).overall;
        assert!((e - 0.996_417_697 * 0.790_964_778).abs() < 1e-8, "{e}");
    }

    #[test]
    fn every_preset_matches_eq10_over_the_measured_range() {
        for preset in &PRESETS {
            let lp = preset.params;
            let c = LawConstants::<f64>::new(&lp);
            let mut speed = 0.01;
            while speed < 100.0 {
                let co = coefficients(&c, Exact(lp.p), Exact(lp.q), speed);
                let expected = if speed <= lp.vc { 0.0 } else { eq10(lp.k1, lp.kappa1, lp.vc, lp.p, lp.q, speed) };
                assert!(
                    (co.overall - expected).abs() < 1e-12,
                    "{} at {speed}: {} vs {expected}",
                    preset.id,
                    co.overall
                );
                let r = lp.k1 / (lp.k1 + speed);
                assert!((co.restitution - r).abs() < 1e-12);
                speed *= 1.07;
            }
        }
    }

    #[test]
    fn presets_reproduce_the_table_s_last_column() {
        for preset in PRESETS.iter().filter(|p| p.last_column.is_some()) {
            let lp = preset.params;
            let c = LawConstants::<f64>::new(&lp);
            let rc = material_restitution(&c, Exact(lp.p), lp.vc);
            let shown = if preset.last_column_is_squared { rc * rc } else { rc };
            // The column is printed to three digits; compare at that precision. (sim-35um:
            // R(vc)^2 = 0.96743 shows as 0.967 against a printed 0.966.)
            let shown = (shown * 1000.0).round() / 1000.0;
            let printed = preset.last_column.unwrap();
            assert!((shown - printed).abs() <= 0.001 + 1e-9, "{}: R(vc) = {rc}, table {printed}", preset.id);
        }
    }

    #[test]
    fn capture_rule_at_and_around_vc() {
        let c = constants(12.5, 0.065, 0.074, 1.0, 0.5);
        let vc = 0.074f64;
        assert!(coefficients(&c, One, Half, vc).captured);
        assert!(coefficients(&c, One, Half, vc.next_down()).captured);
        let above = coefficients(&c, One, Half, vc.next_up());
        assert!(!above.captured && above.overall > 0.0 && above.overall < 1e-6);
        // Far below vc the formula would rebound again; the rule overrides it.
        assert!(restitution_formula(&c, One, Half, 0.001) > 0.0);
        let below = coefficients(&c, One, Half, 0.001);
        assert!(below.captured && below.overall == 0.0 && below.adhesion == 1.0);
    }

    #[test]
    fn negative_vc_never_captures_by_speed_but_kappa1_above_kappa2_does() {
        let c = constants(51.7, 4.07, -0.44, 1.0, 1.0);
        assert!(!coefficients(&c, One, One, 1e-6).captured);
        let strong = LawConstants::<f64>::new(&LawParams {
            kappa1: 2.0,
            kappa2: 1.0,
            ..LawParams::symmetric(50.0, 1.0, -0.1, 1.0, 1.0)
        });
        // rho = 2/(1 + |vn| + 0.1) >= 1 for |vn| <= 0.9: captured by e <= 0.
        assert!(coefficients(&strong, One, One, 0.5).captured);
        assert!(!coefficients(&strong, One, One, 2.0).captured);
    }

    /// The capture rule, and the rule written with the divided formula's sign.
    fn rule_and_sign<T: Real>(lp: &LawParams, speed: T) -> (bool, bool) {
        let c = LawConstants::<T>::new(lp);
        let (p, q) = (Exact(T::from_f64(lp.p)), Exact(T::from_f64(lp.q)));
        let b = adhesion_denominator(&c, q, speed);
        let e = restitution_formula(&c, p, q, speed);
        (is_captured(&c, speed, b), (speed <= c.capture_speed) | (e <= T::ZERO))
    }

    proptest::proptest! {
        /// The capture rule reads `e <= 0` off `B <= 1`, before the division: it must agree
        /// with the sign of the divided formula, also where `B` is within rounding of 1.
        #[test]
        fn capture_from_the_denominator_is_the_sign_of_e(
            k1 in 1e-3f64..1e3, k2 in 1e-3f64..1e3, kappa1 in 1e-3f64..1e3, kappa2 in 1e-3f64..1e3,
            p in 0.2f64..4.0, q in 0.2f64..4.0, vc in -1.0f64..1.0, speed in 1e-6f64..1e3,
        ) {
            let lp = LawParams { k1, k2, kappa1, kappa2, p, q, vc, mu: 0.0 };
            let (rule, sign) = rule_and_sign::<f64>(&lp, speed);
            proptest::prop_assert_eq!(rule, sign);
            let (rule, sign) = rule_and_sign::<f32>(&lp, speed as f32);
            proptest::prop_assert_eq!(rule, sign);
            // The speed where B = (kappa2/kappa1)^q + (u/kappa1)^q = 1 (kappa2 < kappa1): e
            // changes sign there, and the two rules must round alike on both sides of it.
            let (lo, hi) = (kappa1.min(kappa2), kappa1.max(kappa2));
            let lp = LawParams { kappa1: hi, kappa2: lo, ..lp };
            let u = hi * (1.0 - (lo / hi).powf(q)).powf(1.0 / q);
            let at_one = vc.max(0.0) + u;
            for s in [at_one.next_down(), at_one, at_one.next_up()] {
                let (rule, sign) = rule_and_sign::<f64>(&lp, s);
                proptest::prop_assert_eq!(rule, sign, "at {}", s);
            }
        }
    }

    #[test]
    fn capture_when_the_adhesion_denominator_underflows_to_zero() {
        // (kappa2/kappa1)^q underflows to 0 and |u| = 0: B = 0, e = -1/0 = -inf, captured.
        let c = LawConstants::<f64>::new(&LawParams {
            kappa1: 1e6,
            kappa2: 1e-6,
            q: 30.0,
            ..LawParams::symmetric(10.0, 1.0, 0.5, 1.0, 1.0)
        });
        assert_eq!(c.kappa_ratio, 0.0);
        assert_eq!(adhesion_denominator(&c, Exact(30.0), 0.5), 0.0);
        assert!(restitution_formula(&c, One, Exact(30.0), 0.5) == f64::NEG_INFINITY);
        assert!(is_captured(&c, 0.5, 0.0));
    }

    #[test]
    fn restitution_is_capped_at_one_when_k1_exceeds_k2() {
        let c = LawConstants::<f64>::new(&LawParams { k1: 20.0, ..LawParams::symmetric(10.0, 0.1, 0.0, 1.0, 1.0) });
        assert_eq!(material_restitution(&c, One, 1.0), 1.0);
        assert!((material_restitution(&c, One, 30.0) - 20.0 / 40.0).abs() < 1e-15);
    }
}
