//! The oblique rigid-body impact of a sphere on a wall (paper Eqs. 3-7, in 3-D vector form).
//!
//! With `n` the unit wall normal into the fluid, `vn = v . n < 0` for an impact,
//! `v_t = v - vn n` and the contact-point slip `s = v_t - r (w x n)`:
//!
//! ```text
//! Pn/m = -(1 + e) vn                                            normal impulse per unit mass
//! Pt/m = -min( 2/7 |s|, mu (1 + e) |vn| ) s/|s|                 (0 when |s| = 0)
//! Vn   = -e vn                                                   (3)
//! V_t  = v_t + Pt/m                                              (4)
//! W    = w - 5/(2 r) n x (Pt/m)                                  (5)
//! ```
//!
//! The first branch of the `min` is rolling at separation (Eq. 6: `mu0 = 2 eta / (7 (1 + e))`
//! with `eta = |s| / |vn|`, Eq. 7), after which the slip `V_t - r (W x n)` is zero; the second
//! is sliding throughout the contact with `mu = mu_f`. In the paper's 2-D frame (`n = +y`,
//! `t = +x`, clockwise spin) `omega_paper = -w_z`, and these equations are its Eqs. (3)-(7).
//!
//! A captured impact has `e = 0`. By default ([`CaptureMode::Deposit`]) the particle is then
//! deposited: velocity and spin are set to zero and its remaining kinetic energy is booked as
//! deposited. [`CaptureMode::KeepOnWall`] keeps the tangential velocity and spin after the
//! impulse (`Vn = 0`), for hosts that let captured particles migrate along the wall.
//!
//! Scenes that do not track spin take `w = 0` and discard `W` (`SPIN = false`); scenes with
//! `mu = 0` have no tangential impulse (`FRICTION = false`). Both skip the corresponding work.

use crate::law::{self, Coefficients, LawConstants, Powers};
use crate::power::Power;
use crate::real::{select, Real};

/// What happens to a captured particle's tangential motion.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum CaptureMode {
    /// Deposited where it hit: velocity and spin become zero. The default.
    #[default]
    Deposit,
    /// Kept on the wall with `Vn = 0`, its tangential velocity and spin after the impact's
    /// friction impulse left as they are (the paper's remark that an obliquely captured
    /// particle may migrate along the surface).
    KeepOnWall,
}

/// The state after one impact, and how it came about. Velocities in m/s, spins in rad/s.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ImpactResult<T> {
    /// Velocity after the impact (zero when deposited).
    pub velocity: [T; 3],
    /// Spin after the impact (zero when deposited).
    pub spin: [T; 3],
    /// Normal velocity `vn = v . n` before the impact; an impact has `vn < 0`.
    pub normal_velocity: T,
    /// The law's coefficients at `|vn|`.
    pub coefficients: Coefficients<T>,
    /// Slip speed `|s|` of the contact point before the impact.
    pub slip: T,
    /// Magnitude of the tangential impulse per unit mass `|Pt|/m`, m/s.
    pub tangential_impulse: T,
    /// True when friction was enough to stop the slip (rolling at separation).
    pub rolling: bool,
    /// Kinetic energy per unit mass carried onto the wall by a deposited particle (J/kg).
    pub deposited_energy: T,
}

#[inline(always)]
fn dot<T: Real>(a: [T; 3], b: [T; 3]) -> T {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

#[inline(always)]
fn cross<T: Real>(a: [T; 3], b: [T; 3]) -> [T; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

#[inline(always)]
fn axpy<T: Real>(a: T, x: [T; 3], y: [T; 3]) -> [T; 3] {
    [a * x[0] + y[0], a * x[1] + y[1], a * x[2] + y[2]]
}

/// A vector in the wall's plane: three components in general, two when the wall is aligned
/// with the coordinate axes ([`AxisNormal`]).
pub trait Tangent<T: Real>: Copy {
    /// The zero vector.
    fn zero() -> Self;
    /// `a x + y`, each component one fused multiply-add.
    #[must_use]
    fn axpy(a: T, x: Self, y: Self) -> Self;
    /// The dot product, summed left to right. Without fused multiply-adds: a sum of two
    /// products then does not depend on their order, so a wall along an axis (two
    /// components, rotated) and the same wall as a general normal (three, one of them zero)
    /// agree bit for bit.
    fn dot(self, other: Self) -> T;
}

impl<T: Real, const N: usize> Tangent<T> for [T; N] {
    #[inline(always)]
    fn zero() -> Self {
        [T::ZERO; N]
    }
    #[inline(always)]
    fn axpy(a: T, x: Self, y: Self) -> Self {
        std::array::from_fn(|i| a.mul_add(x[i], y[i]))
    }
    #[inline(always)]
    fn dot(self, other: Self) -> T {
        let mut sum = self[0] * other[0];
        for i in 1..N {
            sum += self[i] * other[i];
        }
        sum
    }
}

/// The wall normal `n` as the impact formulas use it: everything they need of `n` is one of
/// these operations. A plain `[T; 3]` is any unit normal; [`AxisNormal`] is a wall aligned with
/// the coordinate axes, for which the products with the normal's zero components are not
/// computed at all (the batch kernel's cheaper loop for rooms and channels). Both give the
/// same results, up to the sign of components that are zero.
pub trait Frame<T: Real>: Copy {
    /// Vectors in the wall's plane.
    type Tangent: Tangent<T>;
    /// The normal part `vn n` of a velocity, in the form [`Frame::compose`] takes it.
    type NormalPart: Copy;
    /// Splits `v` into `vn = v . n`, the normal part `vn n` and the tangential part `v - vn n`.
    fn split(self, v: [T; 3]) -> (T, Self::NormalPart, Self::Tangent);
    /// `t + a vn n`: a velocity from a tangential part and a multiple of a normal part.
    fn compose(self, t: Self::Tangent, a: T, normal_part: Self::NormalPart) -> [T; 3];
    /// The contact point's slip `s = v_t - r (w x n)` (m/s) from the tangential velocity `v_t`,
    /// the spin `w` (rad/s) and the radius `r` (m).
    fn slip(self, v_t: Self::Tangent, w: [T; 3], radius: T) -> Self::Tangent;
    /// `W = w - 5/(2 r) (n x x)`: the spin `w` (rad/s) after a tangential impulse per unit mass
    /// `x` (m/s) on a sphere of radius `r` (m), Eq. (5).
    fn spin_after(self, w: [T; 3], radius: T, x: Self::Tangent) -> [T; 3];
}

/// `-5/2` of Eq. (5), `W = w - 5/(2 r) n x (Pt/m)`: the spin a tangential impulse gives a solid
/// sphere (`I = 2/5 m r^2`), times the radius.
const SPIN_KICK: f64 = -2.5;

/// Any unit normal.
impl<T: Real> Frame<T> for [T; 3] {
    type Tangent = [T; 3];
    type NormalPart = [T; 3];
    #[inline(always)]
    fn split(self, v: [T; 3]) -> (T, [T; 3], [T; 3]) {
        let vn = dot(v, self);
        let v_n = [vn * self[0], vn * self[1], vn * self[2]];
        (vn, v_n, [v[0] - v_n[0], v[1] - v_n[1], v[2] - v_n[2]])
    }
    #[inline(always)]
    fn compose(self, t: [T; 3], a: T, normal_part: [T; 3]) -> [T; 3] {
        axpy(a, normal_part, t)
    }
    #[inline(always)]
    fn slip(self, v_t: [T; 3], w: [T; 3], radius: T) -> [T; 3] {
        Tangent::axpy(-radius, cross(w, self), v_t)
    }
    #[inline(always)]
    fn spin_after(self, w: [T; 3], radius: T, x: [T; 3]) -> [T; 3] {
        axpy(T::from_f64(SPIN_KICK) / radius, cross(self, x), w)
    }
}

/// A wall normal along the third coordinate axis, `n = (0, 0, sign)` with `sign = +-1`.
/// Walls along the other axes use it too: the batch kernel rotates the velocity and spin
/// components cyclically so that the wall's axis comes third (a cyclic rotation keeps every
/// cross product).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AxisNormal<T> {
    /// `+1` or `-1`.
    pub sign: T,
}

impl<T: Real> Frame<T> for AxisNormal<T> {
    type Tangent = [T; 2];
    /// The third component of `vn n`, which is `v[2]` itself (`sign^2 = 1`).
    type NormalPart = T;
    #[inline(always)]
    fn split(self, v: [T; 3]) -> (T, T, [T; 2]) {
        (self.sign * v[2], v[2], [v[0], v[1]])
    }
    #[inline(always)]
    fn compose(self, t: [T; 2], a: T, normal_part: T) -> [T; 3] {
        [t[0], t[1], a * normal_part]
    }
    // The sign goes into the radius and into the constant -5/2 rather than into each
    // component: a product with +-1 is exact, so the results are the same bits as the general
    // normal's, with fewer multiplications.
    #[inline(always)]
    fn slip(self, v_t: [T; 2], w: [T; 3], radius: T) -> [T; 2] {
        // (w0, w1, w2) x (0, 0, s) = (s w1, -s w0, 0).
        let signed_radius = self.sign * radius;
        [(-signed_radius).mul_add(w[1], v_t[0]), signed_radius.mul_add(w[0], v_t[1])]
    }
    #[inline(always)]
    fn spin_after(self, w: [T; 3], radius: T, x: [T; 2]) -> [T; 3] {
        // (0, 0, s) x (x0, x1, 0) = (-s x1, s x0, 0).
        let a = (T::from_f64(SPIN_KICK) * self.sign) / radius;
        [-(a * x[1]) + w[0], a * x[0] + w[1], w[2]]
    }
}

/// Resolves one impact. `v`, `w` (rad/s), `radius` (m) and the unit normal `n` (a `[T; 3]`, or
/// an [`AxisNormal`]) are the state at contact; `w` and `radius` are ignored unless `SPIN`,
/// friction is skipped unless `FRICTION`.
/// Called for `vn >= 0` too (the batch kernel discards that result), it still returns finite
/// values for finite input.
#[inline(always)]
#[must_use]
#[allow(clippy::too_many_arguments)]
pub fn resolve<T: Real, P: Power<T>, Q: Power<T>, const SPIN: bool, const FRICTION: bool>(
    c: &LawConstants<T>,
    p: P,
    q: Q,
    mode: CaptureMode,
    v: [T; 3],
    w: [T; 3],
    radius: T,
    n: impl Frame<T>,
) -> ImpactResult<T> {
    let powers = law::powers(c, p, q, -n.split(v).0);
    resolve_with_powers::<T, SPIN, FRICTION>(c, powers, mode, v, w, radius, n)
}

/// [`resolve`] with the law's two powers at this impact's `|vn|` given, for the batch kernel,
/// which evaluates general exponents in passes of their own.
#[inline(always)]
#[must_use]
pub fn resolve_with_powers<T: Real, const SPIN: bool, const FRICTION: bool>(
    c: &LawConstants<T>,
    powers: Powers<T>,
    mode: CaptureMode,
    v: [T; 3],
    w: [T; 3],
    radius: T,
    n: impl Frame<T>,
) -> ImpactResult<T> {
    // The normal part `vn n` is shared by `v_t` and the rebound's `Vn n = -e vn n`, so that
    // after `e` only one multiply and one add remain on the way to the velocity.
    let (vn, v_n, v_t) = n.split(v);
    let speed = -vn;

    // Pt/m = -ratio s with ratio = min(2/7, mu |vn| / |s| (1 + e)): rolling, or sliding at the
    // friction limit. `mu |vn| / |s|` needs only the slip, so its division runs beside the
    // law's (for `e`) rather than after it: on a core where divisions and roots are quick but
    // slow to finish, two divisions side by side take less time than one shared division
    // that has to wait for the slip's square root. Zero slip makes the quotient infinite:
    // rolling with no impulse.
    let coefficients = law::coefficients_from_powers(c, speed, powers);
    let e = coefficients.overall;
    let (slip_vector, slip, ratio, j, rolling) = if FRICTION {
        let s = if SPIN { n.slip(v_t, w, radius) } else { v_t };
        let slip = s.dot(s).sqrt();
        let sliding_scale = c.mu * speed.abs();
        let per_slip = sliding_scale / slip;
        let two_sevenths = T::from_f64(2.0 / 7.0);
        let limit = select(slip > T::ZERO, per_slip, T::INFINITY) * (T::ONE + e);
        let rolling = two_sevenths <= limit;
        // |Pt|/m = min(2/7 |s|, mu (1 + e) |vn|), chosen rather than computed as ratio |s|
        // (NaN for an infinite slip).
        let j = select(rolling, two_sevenths * slip, sliding_scale * (T::ONE + e));
        (s, slip, two_sevenths.min(limit), j, rolling)
    } else {
        (Tangent::zero(), T::ZERO, T::ZERO, T::ZERO, false)
    };
    let impulse_t = Tangent::axpy(-ratio, slip_vector, Tangent::zero());

    let tangential = if FRICTION { Tangent::axpy(-ratio, slip_vector, v_t) } else { v_t };
    let mut velocity = n.compose(tangential, -e, v_n);
    let mut spin = if SPIN && FRICTION { n.spin_after(w, radius, impulse_t) } else { w };

    // The capture mode as a bound on the speed, so that `deposit` is a compare of floats:
    // combined with the batch-wide boolean itself, LLVM narrowed the lanes' mask to 32 bits
    // and widened it again (3-4 more instructions per four impacts in the AVX2 f64 friction
    // loops).
    let deposit_limit = select(mode == CaptureMode::Deposit, T::INFINITY, -T::INFINITY);
    let deposit = coefficients.captured & (speed <= deposit_limit);
    let rotational =
        if SPIN { T::from_f64(0.2) * radius * radius * dot(spin, spin) } else { T::from_f64(1.25) * j * j };
    let deposited_energy = select(deposit, T::HALF * tangential.dot(tangential) + rotational, T::ZERO);
    for i in 0..3 {
        velocity[i] = select(deposit, T::ZERO, velocity[i]);
        spin[i] = select(deposit, T::ZERO, spin[i]);
    }
    ImpactResult {
        velocity,
        spin,
        normal_velocity: vn,
        coefficients,
        slip,
        tangential_impulse: j,
        rolling,
        deposited_energy,
    }
}

/// Kinetic energy per unit mass of a solid sphere, `|v|^2/2 + r^2 |w|^2/5` (J/kg), with
/// `I = 2/5 m r^2`.
#[inline(always)]
#[must_use]
pub fn kinetic_energy<T: Real>(v: [T; 3], w: [T; 3], radius: T) -> T {
    T::HALF * dot(v, v) + T::from_f64(0.2) * radius * radius * dot(w, w)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::params::LawParams;
    use crate::power::{Half, One};

    fn law(mu: f64) -> LawConstants<f64> {
        LawConstants::new(&LawParams::symmetric(12.5, 0.065, 0.074, 1.0, 0.5).with_friction(mu))
    }

    /// The paper's 2-D Eqs. (3)-(7) with its clockwise spin `omega`, `n = +y`, `t = +x`.
    fn paper_2d(e: f64, mu_f: f64, vn: f64, vt: f64, omega: f64, r: f64) -> (f64, f64, f64) {
        let eta = (vt - r * omega) / vn; // Eq. 7
        let mu0 = 2.0 * eta / (7.0 * (1.0 + e)); // Eq. 6
                                                 // Rolling when |mu0| <= mu_f; sliding otherwise, with mu opposing the slip.
        let mu = if mu0.abs() <= mu_f { mu0 } else { mu_f * mu0.signum() };
        let vn_after = -e * vn; // Eq. 3
        let vt_after = vt - mu * (1.0 + e) * vn; // Eq. 4
        let omega_after = omega + 5.0 * mu / (2.0 * r) * (1.0 + e) * vn; // Eq. 5
        (vn_after, vt_after, omega_after)
    }

    #[test]
    fn reduces_to_the_paper_s_2d_equations_with_clockwise_spin() {
        let r = 35e-6;
        for &(mu_f, vt, omega) in
            &[(0.3, 0.4, 0.0), (0.05, 0.4, 1e4), (0.3, -0.2, -3e4), (0.8, 1.0, 2e4), (0.1, 0.0, 5e3)]
        {
            let c = law(mu_f);
            let vn = -0.9;
            let res = resolve::<f64, One, Half, true, true>(
                &c,
                One,
                Half,
                CaptureMode::Deposit,
                [vt, vn, 0.0],
                [0.0, 0.0, -omega],
                r,
                [0.0, 1.0, 0.0],
            );
            let e = res.coefficients.overall;
            let (vn_p, vt_p, omega_p) = paper_2d(e, mu_f, vn, vt, omega, r);
            assert!((res.velocity[1] - vn_p).abs() < 1e-12);
            assert!((res.velocity[0] - vt_p).abs() < 1e-12, "vt {} vs {vt_p}", res.velocity[0]);
            assert!(
                (-res.spin[2] - omega_p).abs() < 1e-6 * omega_p.abs().max(1.0),
                "omega {} vs {omega_p}",
                -res.spin[2]
            );
            assert_eq!(res.velocity[2], 0.0);
        }
    }

    #[test]
    fn hand_computed_oblique_rolling_impact() {
        // li1997 at vn = -1 m/s, vt = 0.5 m/s, no spin, mu = 0.5: e = 0.731990683 (law tests),
        // |s| = 0.5, rolling impulse 2/7 * 0.5 = 0.142857 < 0.5 * 1.731991 = 0.866: rolling.
        // V_t = 0.5 - 0.142857 = 0.357143 (= 5/7 vt); W_z = -5/(2r) (n x Pt)_z = -5/(7r) * 0.5.
        let r = 1e-5;
        let res = resolve::<f64, One, Half, true, true>(
            &law(0.5),
            One,
            Half,
            CaptureMode::Deposit,
            [0.5, -1.0, 0.0],
            [0.0; 3],
            r,
            [0.0, 1.0, 0.0],
        );
        assert!(res.rolling);
        assert!((res.velocity[0] - 2.5 / 7.0).abs() < 1e-15);
        assert!((res.velocity[1] - 0.731_990_683).abs() < 1e-9);
        assert!((res.spin[2] + 2.5 / (7.0 * r)).abs() < 1e-9 * 2.5 / (7.0 * r));
        // No slip after a rolling impact: V_t - r (W x n) = 0.
        let slip_after = res.velocity[0] - r * (res.spin[1] * 0.0 - res.spin[2] * 1.0);
        assert!(slip_after.abs() < 1e-15);
    }

    #[test]
    fn hand_computed_sliding_impact_and_capture() {
        // mu = 0.05: limit 0.05 * 1.731990683 = 0.0865995 < 0.142857: sliding, V_t = 0.4134005.
        let res = resolve::<f64, One, Half, false, true>(
            &law(0.05),
            One,
            Half,
            CaptureMode::Deposit,
            [0.5, -1.0, 0.0],
            [0.0; 3],
            1.0,
            [0.0, 1.0, 0.0],
        );
        assert!(!res.rolling);
        assert!((res.velocity[0] - 0.413_400_466).abs() < 1e-9);
        // Below vc: deposited with zero velocity, or kept on the wall with Vn = 0.
        let slow = [0.3, -0.05, 0.1];
        let dep = resolve::<f64, One, Half, false, true>(
            &law(0.05),
            One,
            Half,
            CaptureMode::Deposit,
            slow,
            [0.0; 3],
            1.0,
            [0.0, 1.0, 0.0],
        );
        assert!(dep.coefficients.captured);
        assert_eq!(dep.velocity, [0.0; 3]);
        let keep = resolve::<f64, One, Half, false, true>(
            &law(0.05),
            One,
            Half,
            CaptureMode::KeepOnWall,
            slow,
            [0.0; 3],
            1.0,
            [0.0, 1.0, 0.0],
        );
        assert_eq!(keep.velocity[1], 0.0);
        // Friction limit at capture: mu (1 + 0) |vn| = 0.0025 along -s.
        let vt = (0.3f64 * 0.3 + 0.1 * 0.1).sqrt();
        let scale = (vt - 0.0025) / vt;
        assert!((keep.velocity[0] - 0.3 * scale).abs() < 1e-15 && (keep.velocity[2] - 0.1 * scale).abs() < 1e-15);
    }

    #[test]
    fn huge_slips_slide_at_the_friction_limit_and_overflowing_ones_get_no_impulse() {
        let n = [0.0, 0.0, 1.0];
        let (w, r) = ([0.0, 0.0, 1e9], 1e-9);
        // Slips of 10 and 1e141 m/s slide with the friction limit's impulse j = mu (1 + e) |vn|
        // along -x, which kicks the spin by W_y = 5 j / (2 r).
        for v in [[1e141, 0.0, -1.0], [10.0, 0.0, -1.0]] {
            let res = resolve::<f64, One, Half, true, true>(&law(0.3), One, Half, CaptureMode::Deposit, v, w, r, n);
            let j = 0.3 * (1.0 + res.coefficients.overall);
            assert!(!res.rolling && (res.tangential_impulse - j).abs() < 1e-15, "{v:?}");
            assert!((res.spin[1] - 2.5 * j / r).abs() < 1e-12 * res.spin[1], "{:?}", res.spin);
        }
        // A slip whose square overflows (|s| = inf): no impulse, and nothing turns NaN.
        let v = [1e200, 0.0, -1.0];
        let res = resolve::<f64, One, Half, true, true>(&law(0.3), One, Half, CaptureMode::Deposit, v, w, r, n);
        assert!(!res.rolling);
        assert_eq!(res.velocity[0], 1e200);
        assert_eq!(res.spin, w);
    }

    /// The axis wall folds its sign into the radius and into -5/2 (products with +-1 are
    /// exact), so its slip and spin after an impulse are the general normal's bits. Values
    /// with many significant digits, so that a changed rounding would show.
    #[test]
    fn an_axis_wall_gives_the_general_normal_s_slip_and_spin_bit_for_bit() {
        use rand::{RngExt, SeedableRng};
        let mut rng = rand::rngs::StdRng::seed_from_u64(3);
        for sign in [1.0f64, -1.0] {
            let (axis, general) = (AxisNormal { sign }, [0.0, 0.0, sign]);
            for _ in 0..1000 {
                let mut draw = || rng.random_range(-1.0..1.0);
                let (v_t, w) = ([draw(), draw()], [draw() * 1e4, draw() * 1e4, draw() * 1e4]);
                let (radius, x) = (1e-5 * (1.5 + draw()), [draw(), draw()]);
                let slip = axis.slip(v_t, w, radius);
                let general_slip = general.slip([v_t[0], v_t[1], 0.0], w, radius);
                assert_eq!([slip[0], slip[1]], [general_slip[0], general_slip[1]], "slip, sign {sign}");
                assert_eq!(general_slip[2], 0.0);
                let spin = axis.spin_after(w, radius, x);
                assert_eq!(spin, general.spin_after(w, radius, [x[0], x[1], 0.0]), "spin, sign {sign}");
            }
        }
    }
}
