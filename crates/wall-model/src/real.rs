//! The floating-point types the kernels run on: `f64` and `f32`.
//!
//! [`Real`] is the small set of operations the physics needs, so that every formula is
//! written once and compiled for both precisions. It also carries the two halves of the
//! vectorisable power function of [`crate::power`]: a base-2 logarithm and exponential
//! built from bit manipulation and short polynomials, with no table look-ups and no
//! branches, so that the compiler can vectorise loops that call them.

use core::fmt::Debug;
use core::ops::{Add, AddAssign, Div, Mul, Neg, Sub};

/// A floating-point type the wall law runs on (`f64` or `f32`).
pub trait Real:
    Copy
    + Send
    + Sync
    + Debug
    + Default
    + PartialOrd
    + Add<Output = Self>
    + AddAssign
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + bytemuck::Pod
    + 'static
{
    const ZERO: Self;
    const ONE: Self;
    const HALF: Self;
    const INFINITY: Self;
    /// A large value whose square is still finite: the law clamps its denominators here so
    /// that no product of two of them overflows (1e150 for `f64`, 1e18 for `f32`).
    const BIG: Self;

    /// Rounds an `f64` to this type.
    fn from_f64(x: f64) -> Self;
    /// Widens this value to `f64` (exact).
    fn to_f64(self) -> f64;
    #[must_use]
    fn abs(self) -> Self;
    #[must_use]
    fn sqrt(self) -> Self;
    /// The smaller of two values; a NaN argument yields the other one.
    #[must_use]
    fn min(self, other: Self) -> Self;
    /// The larger of two values; a NaN argument yields the other one.
    #[must_use]
    fn max(self, other: Self) -> Self;
    /// `self^y` from the platform's libm (correctly rounded or nearly so; not vectorisable).
    #[must_use]
    fn powf(self, y: Self) -> Self;
    /// True for every value but NaN and the infinities.
    fn is_finite(self) -> bool;
    /// `self * a + b` with one rounding (a fused multiply-add): one instruction on a CPU with
    /// FMA (the kernels' AVX2 and AVX-512 builds), a call to libm's `fma` otherwise. Being
    /// correctly rounded, it gives the same bits on every path.
    #[must_use]
    fn mul_add(self, a: Self, b: Self) -> Self;
    /// `log2(x)` for finite `x > 0` (subnormals included), relative error below
    /// [`Real::POW_TOLERANCE`] / 4 away from `x = 1` and absolute error below that near it.
    /// Values outside that domain give unspecified (but not trapping) results. It is
    /// [`Real::log2_reduce`] then [`Real::log2_series`].
    #[inline(always)]
    #[must_use]
    fn fast_log2(self) -> Self {
        let (exponent, z) = self.log2_reduce();
        Self::log2_series(exponent, z)
    }
    /// The first half of [`Real::fast_log2`]: `x = 2^e m` with `m` in `[sqrt(1/2), sqrt(2))`,
    /// returned as `(e, z)` with `z = (m - 1)/(m + 1)`, the half with the division.
    #[must_use]
    fn log2_reduce(self) -> (Self, Self);
    /// The second half of [`Real::fast_log2`]: `log2 x = e + 2 atanh(z) / ln 2`, a polynomial.
    #[must_use]
    fn log2_series(exponent: Self, z: Self) -> Self;
    /// `2^t`, relative error below [`Real::POW_TOLERANCE`] / 4; results that would be
    /// subnormal flush to zero, and results above `2^(MAX_EXP - 1/2)` (about 1.3e308 for
    /// `f64`, 2.4e38 for `f32`) become infinity, as do `2^-inf = 0` and `2^inf = inf`.
    #[must_use]
    fn fast_exp2(self) -> Self;
    /// The stated bound on the relative error of [`crate::power::fast_pow`] for
    /// `|y log2(x)| <= 64` (checked by the tests): 1e-12 for `f64`, 5e-6 for `f32`. In `f32`
    /// the bound is set by rounding, not by the polynomials: `log2 x` and `y log2 x` are each
    /// rounded to 24 bits, which alone allows about 4.3e-6 at `|y log2 x| = 64`.
    const POW_TOLERANCE: f64;
    /// `self`, a whole number from 0 to 255, as a byte: the low byte of the mantissa of
    /// `self + 2^52` (`2^23` in `f32`). An add and a narrowing, where `as u8` would clamp
    /// first; other values give an unspecified byte.
    fn small_int_to_byte(self) -> u8;
}

/// Branch-free choice between two values; the kernels use it so that loops vectorise.
#[inline(always)]
#[must_use]
pub fn select<T: Copy>(condition: bool, if_true: T, if_false: T) -> T {
    if condition {
        if_true
    } else {
        if_false
    }
}

/// Evaluates `c[0] + c[1] x + c[2] x^2 + ...` by Estrin's scheme: pairs `c[i] + c[i+1] x`
/// combined with `x^2`, then `x^4`, ... A tree of depth `log2(N)` instead of Horner's chain of
/// `N` dependent multiply-adds, so a vectorised loop is not held up by latency. Every loop's
/// trip count follows from `N`, so the whole evaluation unrolls into registers.
#[inline(always)]
fn polynomial<T: Real, const N: usize>(x: T, c: &[f64; N]) -> T {
    let mut terms = c.map(T::from_f64);
    let mut power = x;
    let mut stride = 1;
    while stride < N {
        let mut i = 0;
        while i + stride < N {
            terms[i] = terms[i + stride].mul_add(power, terms[i]);
            i += 2 * stride;
        }
        power = power * power;
        stride *= 2;
    }
    terms[0]
}

// The polynomials below interpolate their function at Chebyshev nodes of the range (nearly
// the minimax polynomial, and with fewer terms than the Taylor series for the same error),
// with the constant term held at exactly 1 so that `log2(1) = 0` and `2^0 = 1` exactly. The
// stated errors are the polynomials' own, before rounding; `crates/wall-model/tools/series.py`
// computes the coefficients and errors (in 50-digit arithmetic).

/// `ln(m) / (2 z) = atanh(z) / z` in powers of `u = z^2`, where `z = (m - 1)/(m + 1)` and `m`
/// is in `[sqrt(1/2), sqrt(2))`, so `u < 0.02944`: relative error 6.9e-16 (the Taylor series
/// `1 + u/3 + u^2/5 + ...` needs 8 terms for 3e-14).
const ATANH_F64: [f64; 7] = [
    1.0,
    0.3333333333333104,
    0.20000000005603252,
    0.1428571206916208,
    0.11111431140054358,
    0.09070096901432996,
    0.08310908576429464,
];
/// As [`ATANH_F64`], 4 terms for `f32`: relative error 2.7e-9.
const ATANH_F32: [f64; 4] = [1.0, 0.3333334251978793, 0.1999439028301099, 0.14789974695986394];
/// `e^g` for `|g| <= ln(2)/2`: relative error 3.7e-14 (the Taylor series gives 6e-15
/// with 12 terms, 2e-13 with 11).
const EXP_F64: [f64; 10] = [
    1.0,
    1.0,
    0.49999999999797934,
    0.16666666666648303,
    0.041666666890957,
    0.008333333353717156,
    0.0013888821677630362,
    0.0001984120875699232,
    2.4876164022625967e-05,
    2.7625102005388108e-06,
];
/// As [`EXP_F64`], 6 terms for `f32`: relative error 2.0e-7, below the rounding of the
/// `f32` arguments it is applied to.
const EXP_F32: [f64; 6] = [1.0, 1.0, 0.4999937213862548, 0.1666657702559799, 0.04187564445233737, 0.008363173074513711];

/// `z = (m - 1)/(m + 1)`, shared by both precisions.
#[inline(always)]
fn atanh_argument<T: Real>(mantissa: T) -> T {
    (mantissa - T::ONE) / (mantissa + T::ONE)
}

/// `log2(x) = e + ln(m)/ln(2) = e + 2 atanh(z)/ln(2)` with `x = m 2^e`, shared by both
/// precisions.
#[inline(always)]
fn log2_from_parts<T: Real, const N: usize>(exponent: T, z: T, series: &[f64; N]) -> T {
    let series = polynomial(z * z, series);
    (z * series).mul_add(T::from_f64(2.0 * core::f64::consts::LOG2_E), exponent)
}

impl Real for f64 {
    const ZERO: Self = 0.0;
    const ONE: Self = 1.0;
    const HALF: Self = 0.5;
    const INFINITY: Self = f64::INFINITY;
    const BIG: Self = 1e150;
    const POW_TOLERANCE: f64 = 1e-12;
    #[inline(always)]
    fn small_int_to_byte(self) -> u8 {
        (self + 4_503_599_627_370_496.0).to_bits() as u8
    }

    #[inline(always)]
    fn from_f64(x: f64) -> Self {
        x
    }
    #[inline(always)]
    fn to_f64(self) -> f64 {
        self
    }
    #[inline(always)]
    fn abs(self) -> Self {
        f64::abs(self)
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        f64::sqrt(self)
    }
    #[inline(always)]
    fn min(self, other: Self) -> Self {
        f64::min(self, other)
    }
    #[inline(always)]
    fn max(self, other: Self) -> Self {
        f64::max(self, other)
    }
    #[inline(always)]
    fn powf(self, y: Self) -> Self {
        f64::powf(self, y)
    }
    #[inline(always)]
    fn is_finite(self) -> bool {
        f64::is_finite(self)
    }
    #[inline(always)]
    fn mul_add(self, a: Self, b: Self) -> Self {
        f64::mul_add(self, a, b)
    }

    #[inline(always)]
    fn log2_reduce(self) -> (Self, Self) {
        // Subnormals are scaled into the normal range first.
        let subnormal = self < f64::MIN_POSITIVE;
        let x = select(subnormal, self * f64::from_bits(0x4350_0000_0000_0000), self); // 2^54
        let bits = x.to_bits();
        let mut mantissa = f64::from_bits((bits & 0x000f_ffff_ffff_ffff) | 0x3ff0_0000_0000_0000);
        let above = mantissa > core::f64::consts::SQRT_2;
        mantissa = select(above, mantissa * 0.5, mantissa);
        let biased = (bits >> 52) + above as u64;
        // Integer to float without a (non-vectorisable) 64-bit conversion: 2^52 + k - 2^52.
        let exponent = f64::from_bits(biased | 0x4330_0000_0000_0000)
            - (4_503_599_627_370_496.0 + 1023.0)
            - select(subnormal, 54.0, 0.0);
        (exponent, atanh_argument(mantissa))
    }

    #[inline(always)]
    fn log2_series(exponent: Self, z: Self) -> Self {
        log2_from_parts(exponent, z, &ATANH_F64)
    }

    #[inline(always)]
    fn fast_exp2(self) -> Self {
        let t = self.clamp(-1023.0, 1024.0);
        let n = (t + 0.5).floor(); // in [-1023, 1024]
        let g = (t - n) * core::f64::consts::LN_2; // |g| <= ln(2)/2
        let poly = polynomial(g, &EXP_F64);
        // 2^n built in the exponent field: (n + 1023) read off the mantissa of 2^52 + n + 1023.
        let biased = (n + (4_503_599_627_370_496.0 + 1023.0)).to_bits() & 0x7ff;
        let scale = f64::from_bits(biased << 52);
        select(self < -1022.0, 0.0, poly * scale)
    }
}

impl Real for f32 {
    const ZERO: Self = 0.0;
    const ONE: Self = 1.0;
    const HALF: Self = 0.5;
    const INFINITY: Self = f32::INFINITY;
    const BIG: Self = 1e18;
    const POW_TOLERANCE: f64 = 5e-6;
    #[inline(always)]
    fn small_int_to_byte(self) -> u8 {
        (self + 8_388_608.0).to_bits() as u8
    }

    #[inline(always)]
    fn from_f64(x: f64) -> Self {
        x as f32
    }
    #[inline(always)]
    fn to_f64(self) -> f64 {
        self as f64
    }
    #[inline(always)]
    fn abs(self) -> Self {
        f32::abs(self)
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        f32::sqrt(self)
    }
    #[inline(always)]
    fn min(self, other: Self) -> Self {
        f32::min(self, other)
    }
    #[inline(always)]
    fn max(self, other: Self) -> Self {
        f32::max(self, other)
    }
    #[inline(always)]
    fn powf(self, y: Self) -> Self {
        f32::powf(self, y)
    }
    #[inline(always)]
    fn is_finite(self) -> bool {
        f32::is_finite(self)
    }
    #[inline(always)]
    fn mul_add(self, a: Self, b: Self) -> Self {
        f32::mul_add(self, a, b)
    }

    #[inline(always)]
    fn log2_reduce(self) -> (Self, Self) {
        let subnormal = self < f32::MIN_POSITIVE;
        let x = select(subnormal, self * f32::from_bits(0x4b80_0000), self); // 2^24
        let bits = x.to_bits();
        let mut mantissa = f32::from_bits((bits & 0x007f_ffff) | 0x3f80_0000);
        let above = mantissa > core::f32::consts::SQRT_2;
        mantissa = select(above, mantissa * 0.5, mantissa);
        let biased = (bits >> 23) + above as u32;
        let exponent = f32::from_bits(biased | 0x4b00_0000) - (8_388_608.0 + 127.0) - select(subnormal, 24.0, 0.0);
        (exponent, atanh_argument(mantissa))
    }

    #[inline(always)]
    fn log2_series(exponent: Self, z: Self) -> Self {
        log2_from_parts(exponent, z, &ATANH_F32)
    }

    #[inline(always)]
    fn fast_exp2(self) -> Self {
        let t = self.clamp(-127.0, 128.0);
        let n = (t + 0.5).floor();
        let g = (t - n) * core::f32::consts::LN_2;
        let poly = polynomial(g, &EXP_F32);
        let biased = (n + (8_388_608.0 + 127.0)).to_bits() & 0xff;
        let scale = f32::from_bits(biased << 23);
        select(self < -126.0, 0.0, poly * scale)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn small_whole_numbers_become_their_bytes() {
        for k in 0..=255u8 {
            assert_eq!(f64::from(k).small_int_to_byte(), k);
            assert_eq!(f32::from(k).small_int_to_byte(), k);
        }
    }

    fn rel(a: f64, b: f64) -> f64 {
        if a == b {
            0.0
        } else {
            ((a - b) / b).abs()
        }
    }

    #[test]
    fn log2_matches_libm_over_the_normal_and_subnormal_range() {
        let mut worst = 0.0f64;
        for k in -1070..1023 {
            for frac in
                [1.0, 1.1, 1.25, 0.99999 * core::f64::consts::SQRT_2, 1.00001 * core::f64::consts::SQRT_2, 1.5, 1.9999]
            {
                let x = frac * 2f64.powi(k);
                let err = (x.fast_log2() - x.log2()).abs() / x.log2().abs().max(1.0);
                worst = worst.max(err);
            }
        }
        assert!(worst < f64::POW_TOLERANCE / 4.0, "worst log2 error {worst:e}");
    }

    #[test]
    fn the_constant_terms_make_log2_of_one_and_exp2_of_zero_exact() {
        assert_eq!(1.0f64.fast_log2(), 0.0);
        assert_eq!(0.0f64.fast_exp2(), 1.0);
        assert_eq!(1.0f32.fast_log2(), 0.0);
        assert_eq!(0.0f32.fast_exp2(), 1.0);
        assert_eq!(crate::power::fast_pow(1.0f64, 1.3), 1.0);
        assert_eq!(crate::power::fast_pow(1.0f32, 0.7), 1.0);
    }

    #[test]
    fn exp2_matches_libm_and_flushes_at_the_ends() {
        let mut worst = 0.0f64;
        let mut t = -1022.0;
        while t < 1023.4 {
            worst = worst.max(rel(t.fast_exp2(), t.exp2()));
            t += 0.137;
        }
        assert!(worst < f64::POW_TOLERANCE / 4.0, "worst exp2 error {worst:e}");
        assert_eq!((-1100.0f64).fast_exp2(), 0.0);
        assert_eq!(2000.0f64.fast_exp2(), f64::INFINITY);
        assert_eq!(1023.6f64.fast_exp2(), f64::INFINITY); // the documented edge
        assert_eq!((-200.0f32).fast_exp2(), 0.0);
        assert_eq!(200.0f32.fast_exp2(), f32::INFINITY);
        assert_eq!(f64::NEG_INFINITY.fast_exp2(), 0.0);
        assert_eq!(f64::INFINITY.fast_exp2(), f64::INFINITY);
        assert_eq!(f32::NEG_INFINITY.fast_exp2(), 0.0);
        assert_eq!(f32::INFINITY.fast_exp2(), f32::INFINITY);
    }

    #[test]
    fn f32_log2_and_exp2_are_accurate_to_a_few_ulp() {
        let mut worst_log = 0.0f64;
        let mut worst_exp = 0.0f64;
        for k in -140..127 {
            for frac in [1.0f32, 1.2, 1.41, 1.5, 1.99] {
                let x = frac * 2f32.powi(k);
                if x == 0.0 {
                    continue;
                }
                let exact = (x as f64).log2();
                worst_log = worst_log.max((x.fast_log2() as f64 - exact).abs() / exact.abs().max(1.0));
            }
        }
        let mut t = -126.0f32;
        while t < 127.4 {
            worst_exp = worst_exp.max(rel(t.fast_exp2() as f64, (t as f64).exp2()));
            t += 0.0917;
        }
        assert!(worst_log < f32::POW_TOLERANCE / 4.0, "worst f32 log2 error {worst_log:e}");
        assert!(worst_exp < f32::POW_TOLERANCE / 4.0, "worst f32 exp2 error {worst_exp:e}");
    }
}
