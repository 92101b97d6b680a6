//! Powers `x^p` for the exponents of Eqs. (8) and (9), chosen once per batch.
//!
//! The paper's fits use `p = 1` and `q` in `{1, 1/2}`; those take a plain value or a square
//! root. Any other exponent takes either [`Fast`], a vectorisable `2^(y log2 x)` with a stated
//! relative error ([`Real::POW_TOLERANCE`]: 1e-12 for `f64`, 5e-6 for `f32`), or [`Exact`],
//! the platform's libm `powf`, which does not vectorise: a batch of ten million impacts with
//! it took about four times as long on two Zen 3 cores. [`PowerMode`] picks between the two;
//! the default is [`PowerMode::Fast`], whose error is orders of magnitude below the scatter
//! of any measured `e(vn)`.
//!
//! Each power is written as three stages ([`Power`]) so that the batch kernel can run a block
//! of particles through one stage at a time; a scalar call runs the three in a row.

use crate::real::{select, Real};

/// How a general (not 1, not 1/2) exponent is evaluated.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum PowerMode {
    /// The vectorisable `2^(y log2 x)` of [`fast_pow`].
    #[default]
    Fast,
    /// The platform's libm `powf`.
    Exact,
}

/// A power `x -> x^y` for `x >= 0`, with the exponent fixed for a whole batch.
///
/// A power is evaluated in three stages, [`Power::start`], [`Power::middle`] and
/// [`Power::finish`]; [`Power::pow`] is the three in a row, and no implementation overrides
/// it. The batch kernel evaluates a [`Power::STAGED`] power stage by stage, each stage in a
/// pass of its own over a block of particles, and so gets the same bits as a scalar call.
pub trait Power<T: Real>: Copy + Send + Sync {
    /// True when the batch kernel evaluates this power in passes of its own before the
    /// impacts: a long chain of dependent operations vectorises better cut into short ones,
    /// and a loop that calls libm's `powf` does not vectorise at all.
    const STAGED: bool;
    /// The first stage: two numbers for the second. By default `x` passed on as it is.
    #[inline(always)]
    fn start(self, x: T) -> [T; 2] {
        [x, T::ZERO]
    }
    /// The second stage. By default the first number passed on as it is.
    #[inline(always)]
    fn middle(self, state: [T; 2]) -> T {
        state[0]
    }
    /// The last stage: `finish(middle(start(x))) = x^y`.
    fn finish(self, t: T) -> T;
    /// `x^y` for `x >= 0`; `0^y = 0` and `inf^y = inf` for `y > 0`.
    #[inline(always)]
    fn pow(self, x: T) -> T {
        self.finish(self.middle(self.start(x)))
    }
}

/// The exponent 1: `x^1 = x`, no work at all.
#[derive(Clone, Copy, Debug)]
pub struct One;

/// The exponent 1/2: one square root.
#[derive(Clone, Copy, Debug)]
pub struct Half;

/// A general positive exponent, by [`fast_pow`]: the two halves of `log2` (the division, then
/// a polynomial), then `exp2`.
#[derive(Clone, Copy, Debug)]
pub struct Fast<T>(pub T);

/// A general positive exponent, by libm's `powf`.
#[derive(Clone, Copy, Debug)]
pub struct Exact<T>(pub T);

impl<T: Real> Power<T> for One {
    const STAGED: bool = false;
    #[inline(always)]
    fn finish(self, t: T) -> T {
        t
    }
}

impl<T: Real> Power<T> for Half {
    const STAGED: bool = false;
    #[inline(always)]
    fn finish(self, t: T) -> T {
        t.sqrt()
    }
}

impl<T: Real> Power<T> for Fast<T> {
    const STAGED: bool = true;
    /// `log2 x` reduced to `(e, z)` ([`Real::log2_reduce`]), with `0^y = 0` and
    /// `inf^y = inf` carried as `e = -inf` and `e = +inf`.
    #[inline(always)]
    fn start(self, x: T) -> [T; 2] {
        let (exponent, z) = x.log2_reduce();
        let exponent = select(x == T::INFINITY, T::INFINITY, exponent);
        [select(x == T::ZERO, -T::INFINITY, exponent), z]
    }
    /// `y log2 x`, the exponent of 2.
    #[inline(always)]
    fn middle(self, [exponent, z]: [T; 2]) -> T {
        self.0 * T::log2_series(exponent, z)
    }
    /// `2^(y log2 x)` ([`Real::fast_exp2`] maps `-inf` to 0 and `+inf` to infinity).
    #[inline(always)]
    fn finish(self, t: T) -> T {
        t.fast_exp2()
    }
}

impl<T: Real> Power<T> for Exact<T> {
    const STAGED: bool = true;
    #[inline(always)]
    fn finish(self, t: T) -> T {
        t.powf(self.0)
    }
}

/// `x^y = 2^(y log2 x)` for `x >= 0` and `y > 0`, without branches or table look-ups.
///
/// The relative error is below [`Real::POW_TOLERANCE`] while `|y log2 x| <= 64`; beyond that
/// it grows like `|y log2 x|` machine epsilons (the rounding of the product itself).
/// `0^y = 0`, `inf^y = inf`; results below the smallest normal number flush to zero.
#[inline(always)]
#[must_use]
pub fn fast_pow<T: Real>(x: T, y: T) -> T {
    Fast(y).pow(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn worst_error<T: Real>(exponents: &[f64]) -> f64 {
        let mut worst = 0.0f64;
        for &y in exponents {
            let mut lx = -30.0f64;
            while lx < 30.0 {
                let x = T::from_f64(lx.exp2());
                let yt = T::from_f64(y);
                if (yt.to_f64() * x.to_f64().log2()).abs() <= 64.0 {
                    let exact = x.to_f64().powf(yt.to_f64());
                    let got = fast_pow(x, yt).to_f64();
                    worst = worst.max(((got - exact) / exact).abs());
                }
                lx += 0.00731;
            }
        }
        worst
    }

    #[test]
    fn fast_pow_meets_its_stated_tolerance() {
        let exponents = [0.3, 0.5, 0.77, 1.0, 1.5, 2.0, 3.3, 7.0, 13.5, 20.0];
        let e64 = worst_error::<f64>(&exponents);
        let e32 = worst_error::<f32>(&exponents);
        assert!(e64 < f64::POW_TOLERANCE, "f64 fast_pow error {e64:e}");
        assert!(e32 < f32::POW_TOLERANCE, "f32 fast_pow error {e32:e}");
    }

    #[test]
    fn fast_pow_edges() {
        assert_eq!(fast_pow(0.0f64, 2.5), 0.0);
        assert_eq!(fast_pow(f64::INFINITY, 0.5), f64::INFINITY);
        assert_eq!(fast_pow(1e300f64, 20.0), f64::INFINITY);
        assert_eq!(fast_pow(1e-300f64, 20.0), 0.0);
        let tiny = 1e-310f64; // subnormal
        let rel = (fast_pow(tiny, 0.5) - tiny.sqrt()).abs() / tiny.sqrt();
        assert!(rel < 1e-12, "subnormal base: {rel:e}");
        assert_eq!(fast_pow(0.0f32, 2.5), 0.0);
        assert_eq!(fast_pow(f32::INFINITY, 3.0), f32::INFINITY);
    }

    #[test]
    fn each_exponent_pair_has_its_case() {
        assert_eq!(Exponents::of(1.0, 1.0), Exponents::OneOne);
        assert_eq!(Exponents::of(1.0, 0.5), Exponents::OneHalf);
        assert_eq!(Exponents::of(0.5, 1.0), Exponents::HalfOne);
        assert_eq!(Exponents::of(0.5, 0.5), Exponents::HalfHalf);
        assert_eq!(Exponents::of(1.0, 0.7), Exponents::OneGeneral);
        assert_eq!(Exponents::of(0.7, 1.0), Exponents::General);
        assert_eq!(Exponents::of(1.3, 0.7), Exponents::General);
    }

    #[test]
    fn one_and_half_are_exact() {
        assert_eq!(<One as Power<f64>>::pow(One, 3.7), 3.7);
        assert_eq!(<Half as Power<f64>>::pow(Half, 2.25), 1.5);
    }
}

/// The exponent pair `(p, q)` as the kernels see it: the paper's cases get loops with no
/// power function at all; anything else is [`Exponents::General`], evaluated per
/// [`PowerMode`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Exponents {
    /// `p = 1`, `q = 1` (Eq. 13).
    OneOne,
    /// `p = 1`, `q = 1/2`.
    OneHalf,
    /// `p = 1/2`, `q = 1`.
    HalfOne,
    /// `p = 1/2`, `q = 1/2`.
    HalfHalf,
    /// `p = 1` (as in all the paper's fits) with any other `q`: only `q` takes a power.
    OneGeneral,
    /// Any other pair.
    General,
}

impl Exponents {
    /// Classifies a pair of (validated) exponents.
    #[must_use]
    pub fn of(p: f64, q: f64) -> Self {
        match (p, q) {
            (1.0, 1.0) => Self::OneOne,
            (1.0, 0.5) => Self::OneHalf,
            (0.5, 1.0) => Self::HalfOne,
            (0.5, 0.5) => Self::HalfHalf,
            (1.0, _) => Self::OneGeneral,
            _ => Self::General,
        }
    }
}

/// Runs `$body` with `$p` and `$q` bound to the [`Power`] types for an exponent pair, so that
/// the body is compiled once per case and the choice is made once, outside any loop.
macro_rules! with_powers {
    ($exponents:expr, $mode:expr, ($p_value:expr, $q_value:expr), |$p:ident, $q:ident| $body:expr) => {{
        use $crate::power::{Exact, Exponents, Fast, Half, One, PowerMode};
        match ($exponents, $mode) {
            (Exponents::OneOne, _) => {
                let ($p, $q) = (One, One);
                $body
            }
            (Exponents::OneHalf, _) => {
                let ($p, $q) = (One, Half);
                $body
            }
            (Exponents::HalfOne, _) => {
                let ($p, $q) = (Half, One);
                $body
            }
            (Exponents::HalfHalf, _) => {
                let ($p, $q) = (Half, Half);
                $body
            }
            (Exponents::OneGeneral, PowerMode::Fast) => {
                let ($p, $q) = (One, Fast($q_value));
                $body
            }
            (Exponents::General, PowerMode::Fast) => {
                let ($p, $q) = (Fast($p_value), Fast($q_value));
                $body
            }
            // libm's `powf(x, 1)` is `x`: one loop serves every pair.
            (Exponents::General | Exponents::OneGeneral, PowerMode::Exact) => {
                let ($p, $q) = (Exact($p_value), Exact($q_value));
                $body
            }
        }
    }};
}
pub(crate) use with_powers;
