//! An intermittent near-wall model of the wall-normal fluid velocity in a channel: the
//! normalised Langevin model of [`flow`](crate::flow) with its Gaussian replaced by the
//! heavy-tailed distribution that direct numerical simulation finds near a wall.
//!
//! Close to a wall the wall-normal velocity is quiet most of the time and violent in rare
//! sweeps and ejections: its flatness `F = <v^4> / <v^2>^2` is 27 at the wall, 12 at
//! `y+ = 5` and 5 at `y+ = 20`, against 3 for a Gaussian (Moser, Kim & Mansour 1999, *Phys.
//! Fluids* 11:943, channel at `Re_tau = 178`, profiles file `chan180.flat`; [`FLATNESS`]).
//! A Gaussian random walk with the right variance misses those rare strong events, and with
//! them the inertial particles they throw at the wall (the diffusion-impaction regime).
//!
//! Here the normalised fluctuation `zeta` (the fluid velocity seen is `sigma(y) zeta`, as in
//! the Gaussian model, with the same Kallio & Reeks `sigma` and `T_L`) has at each distance
//! the Student-t distribution of unit variance with `nu(y) = 4 + 6 / (F(y) - 3)` degrees of
//! freedom, the t whose flatness is `F(y)`:
//!
//! ```text
//! P(zeta; y) = K (1 + zeta^2 / (nu - 2))^(-(nu + 1)/2),  K = Gamma((nu+1)/2) / (Gamma(nu/2) sqrt(pi (nu - 2)))
//! ```
//!
//! It is a diffusion with that distribution and the Gaussian model's exponential
//! autocorrelation `exp(-t / T_L)`: for the linear drift `-zeta / T_L` the diffusion
//! coefficient that keeps `P` is `2 G / (P T_L)`, `G = -int_-inf^zeta u P du` (Bibby,
//! Skovgaard & Sorensen 2005, *Bernoulli* 11:191), here `b^2 = 2 S / T_L` with the spread
//! `S = (nu - 2 + zeta^2) / (nu - 1)`, whose mean is 1: the Gaussian model's `2 / T_L`, the
//! same mean dissipation. Strong events decay at the same rate `1 / T_L` as weak ones, so the
//! tails come from the distribution alone, not from long-lived extremes. For the
//! inhomogeneity, Thomson's (1987) well-mixed condition for tracers (`dy = sigma zeta dt`)
//! gives the drift `A P = d(sigma G)/dy` away from the wall:
//!
//! ```text
//! d zeta = (-zeta / T_L + A) dt + sqrt(2 S / T_L) dW
//! A = sigma' S + sigma nu' S [D(nu) - ln(q)/2 + (nu - 1) zeta^2 / (2 (nu - 2)^2 q)],
//! q = 1 + zeta^2 / (nu - 2),  D(nu) = d/dnu ln(K (nu - 2) / (nu - 1))
//! ```
//!
//! Where `S = 1` and `nu' = 0` (the Gaussian limit, `nu -> infinity` at constant `nu`) the
//! drift is the Gaussian model's `A = sigma'` (tested at constant `nu`). Each step is the
//! Gaussian model's exact Ornstein-Uhlenbeck step with `S` and `A` frozen at its start,
//! `zeta decay + A T_L (1 - decay) + sqrt(S (1 - decay^2)) normal`, `decay = exp(-dt / T_L)`;
//! a particle starts from the Gaussian, which relaxes to the t within a few `T_L`, inside
//! the transient the studies leave out.
//!
//! What is stepped along a particle's path is a choice ([`SeenVelocity`]): the normalised
//! `zeta`, as above, or the fluid velocity `u' = sigma zeta` itself, whose drift for a fluid
//! element is Thomson's `sigma (A + sigma' zeta^2)`. The two are one model for tracers; for a
//! particle that outruns its fluid, the normalised form shrinks the fluid velocity seen with
//! `sigma` as the particle moves, the fluid form lets it change over the Lagrangian time only.
//! In the channel the fluid form deposited 2-22 times more at `tau+` 0.3-3, within about a
//! factor of 2 of the band of the correlations there; its step is not yet bounded near the
//! wall, so these figures are provisional (docs/validation.md).
//!
//! Only the wall-normal component is intermittent: it alone carries particles to the wall.
//! The Student-t is this model's choice of family: the heavy-tailed distribution fixed by the
//! variance and flatness alone, with no further constant.

use crate::flow::{lagrangian_time, profile_at, wall_normal_rms};
use crate::scene::SeenVelocity;

/// Flatness of the wall-normal velocity, `F(v)`, against `y+`: Moser, Kim & Mansour (1999),
/// channel at `Re_tau = 178.12`, the half-channel profile `chan180.flat` (wall to centre).
pub const FLATNESS: [(f64, f64); 64] = [
    (5.3648e-02, 26.972),
    (2.1456e-01, 26.212),
    (4.8263e-01, 24.992),
    (8.5771e-01, 23.385),
    (1.3396e+00, 21.498),
    (1.9279e+00, 19.467),
    (2.6224e+00, 17.443),
    (3.4226e+00, 15.559),
    (4.3280e+00, 13.885),
    (5.3381e+00, 12.411),
    (6.4523e+00, 11.095),
    (7.6700e+00, 9.9225),
    (8.9902e+00, 8.8956),
    (1.0412e+01, 8.0073),
    (1.1936e+01, 7.2420),
    (1.3559e+01, 6.5832),
    (1.5281e+01, 6.0160),
    (1.7102e+01, 5.5268),
    (1.9019e+01, 5.1059),
    (2.1033e+01, 4.7455),
    (2.3141e+01, 4.4413),
    (2.5342e+01, 4.1900),
    (2.7635e+01, 3.9869),
    (3.0019e+01, 3.8239),
    (3.2492e+01, 3.6929),
    (3.5053e+01, 3.5871),
    (3.7701e+01, 3.5022),
    (4.0432e+01, 3.4372),
    (4.3247e+01, 3.3886),
    (4.6143e+01, 3.3521),
    (4.9118e+01, 3.3249),
    (5.2171e+01, 3.3071),
    (5.5300e+01, 3.2995),
    (5.8503e+01, 3.3024),
    (6.1778e+01, 3.3159),
    (6.5123e+01, 3.3367),
    (6.8536e+01, 3.3618),
    (7.2016e+01, 3.3916),
    (7.5559e+01, 3.4271),
    (7.9164e+01, 3.4672),
    (8.2828e+01, 3.5118),
    (8.6550e+01, 3.5581),
    (9.0327e+01, 3.6042),
    (9.4157e+01, 3.6493),
    (9.8037e+01, 3.6924),
    (1.0197e+02, 3.7348),
    (1.0594e+02, 3.7785),
    (1.0996e+02, 3.8259),
    (1.1402e+02, 3.8724),
    (1.1812e+02, 3.9098),
    (1.2225e+02, 3.9350),
    (1.2642e+02, 3.9497),
    (1.3062e+02, 3.9564),
    (1.3484e+02, 3.9571),
    (1.3910e+02, 3.9530),
    (1.4337e+02, 3.9471),
    (1.4767e+02, 3.9396),
    (1.5199e+02, 3.9314),
    (1.5632e+02, 3.9280),
    (1.6066e+02, 3.9265),
    (1.6502e+02, 3.9254),
    (1.6938e+02, 3.9244),
    (1.7375e+02, 3.9230),
    (1.7812e+02, 3.9224),
];

/// `F(v)` at `y+`, linear between the [`FLATNESS`] points and held at the ends.
#[must_use]
pub fn flatness(y_plus: f64) -> f64 {
    profile_at(&FLATNESS, y_plus)
}

/// Degrees of freedom of the Student-t with flatness `f > 3`: `nu = 4 + 6 / (f - 3)`.
#[must_use]
pub fn degrees_of_freedom(f: f64) -> f64 {
    4.0 + 6.0 / (f - 3.0)
}

/// `ln(K (nu - 2) / (nu - 1))` of the unit-variance t with `nu` degrees of freedom.
fn ln_k(nu: f64) -> f64 {
    libm::lgamma(0.5 * (nu + 1.0)) - libm::lgamma(0.5 * nu) - 0.5 * (std::f64::consts::PI * (nu - 2.0)).ln()
        + ((nu - 2.0) / (nu - 1.0)).ln()
}

/// What the step needs at one distance, in SI units.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct Node {
    /// `sigma`, m/s.
    sigma: f64,
    /// `d sigma / dy`, 1/s.
    slope: f64,
    /// `nu - 2`.
    nu_m2: f64,
    /// `1 / (nu - 1)`.
    inv_nu_m1: f64,
    /// `d nu / dy`, 1/m.
    dnu: f64,
    /// `D(nu)`.
    d_ln_k: f64,
    /// `exp(-dt / T_L)`.
    decay: f64,
    /// `sqrt(1 - decay^2)`.
    noise: f64,
    /// `T_L (1 - decay)`, s: what the drift adds over a step per unit drift.
    drift_time: f64,
}

/// Spacing of the table in wall units: up to a half-height of 328 wall units; beyond, the
/// table has [`MAX_NODES`] nodes and its spacing grows (0.6 wall units at 10^4), coarser near
/// the wall than the Gaussian model's table.
const SPACING_PLUS: f64 = 0.02;
/// At most this many nodes.
const MAX_NODES: usize = 16_384;

/// The intermittent model of one channel's wall-normal velocity, tabulated against the
/// distance to the nearer wall (`y+` from half a spacing to the centre), read at the cell's
/// lower node.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Intermittent {
    nodes: Vec<Node>,
    /// Nodes per metre.
    inv_dy: f64,
    /// The distance of node 0, m.
    y0: f64,
    /// Whether the step carries the fluid velocity rather than the normalised one
    /// ([`SeenVelocity::Fluid`]): it then adds the path term of [`Self::step`], and the
    /// tracker renormalises `zeta` to `sigma` where the particle moves.
    pub(crate) fluid_form: bool,
}

impl Intermittent {
    /// For a channel of half-height `half` (m), friction velocity `u*` (m/s) and kinematic
    /// viscosity `nu` (m^2/s), and a step `dt` (s), stepping what `form` names; `drift =
    /// false` drops the well-mixed drift (for comparison only).
    #[must_use]
    pub fn channel(
        half: f64,
        friction_velocity: f64,
        viscosity: f64,
        dt: f64,
        drift: bool,
        form: SeenVelocity,
    ) -> Self {
        let plus = friction_velocity / viscosity; // wall units per metre
        let time = viscosity / (friction_velocity * friction_velocity); // s per wall time unit
        let half_plus = half * plus;
        let spacing = SPACING_PLUS.max(half_plus / (MAX_NODES - 1) as f64);
        let count = (half_plus / spacing).ceil() as usize + 1;
        let y0 = 0.5 * spacing;
        let nu = |y: f64| degrees_of_freedom(flatness(y));
        let nodes = (0..count)
            .map(|i| {
                let y = y0 + i as f64 * spacing;
                let h = 0.25 * spacing;
                let per_metre = plus / (2.0 * h);
                let n = nu(y);
                let eps = 1e-6 * n;
                let on = if drift { 1.0 } else { 0.0 };
                Node {
                    sigma: friction_velocity * wall_normal_rms(y),
                    slope: on * friction_velocity * (wall_normal_rms(y + h) - wall_normal_rms(y - h)) * per_metre,
                    nu_m2: n - 2.0,
                    inv_nu_m1: 1.0 / (n - 1.0),
                    dnu: on * (nu(y + h) - nu(y - h)) * per_metre,
                    d_ln_k: (ln_k(n + eps) - ln_k(n - eps)) / (2.0 * eps),
                    decay: (-dt / (time * lagrangian_time(y))).exp(),
                    noise: (-(-2.0 * dt / (time * lagrangian_time(y))).exp_m1()).sqrt(),
                    drift_time: -(time * lagrangian_time(y)) * (-dt / (time * lagrangian_time(y))).exp_m1(),
                }
            })
            .collect();
        Self { nodes, inv_dy: plus / spacing, y0: y0 / plus, fluid_form: form == SeenVelocity::Fluid }
    }

    fn node(&self, distance: f64) -> &Node {
        let i = ((distance - self.y0) * self.inv_dy).max(0.0) as usize;
        &self.nodes[i.min(self.nodes.len() - 1)]
    }

    /// The normalised wall-normal fluctuation `zeta` one step later, at `distance` (m) from
    /// the nearer wall, `sign` the sign of `d(distance)/dz`, driven by the standard normal
    /// `normal`: the Gaussian model's exact step for frozen coefficients, `zeta decay + A T_L
    /// (1 - decay) + sqrt(S (1 - decay^2)) normal`, with the spread `S` and the drift `A` at
    /// the step's start.
    ///
    /// With [`SeenVelocity::Fluid`] the step carries the fluid velocity `u' = sigma zeta`
    /// rather than `zeta`: `zeta` here is `u' / sigma(distance)`, and the step adds the part of
    /// Thomson's (1987) drift for `u'` that the normalised form leaves to the path,
    /// `sigma' zeta^2` (for a fluid element `d(sigma zeta) = sigma d zeta + zeta sigma' dy`,
    /// `dy = sigma zeta dt`); the caller then divides by `sigma` where the particle has moved. For a tracer the two cancel to first order, and the two forms agree.
    #[inline]
    #[must_use]
    pub fn step(&self, distance: f64, sign: f64, zeta: f64, normal: f64) -> f64 {
        let n = self.node(distance);
        let z2 = zeta * zeta;
        let q = 1.0 + z2 / n.nu_m2;
        let spread = (n.nu_m2 + z2) * n.inv_nu_m1;
        let shape = n.d_ln_k - 0.5 * q.ln() + 0.5 * z2 / (n.inv_nu_m1 * n.nu_m2 * n.nu_m2 * q);
        let drift = spread * (n.slope + n.sigma * n.dnu * shape);
        let path = if self.fluid_form {
            // Outward `w = sign zeta` grows as `dw/dt = sigma' w^2`, over the step's drift time
            // `r / sigma'`: exact (`w / (1 + r |w|)`) where the term shrinks `|w|`, at most
            // doubling it where it grows it, Euler's `r w^2` for small `|r w|`.
            let w = sign * zeta;
            let r = n.slope * n.drift_time;
            sign * (r * w * w / (1.0 + (r * w).abs()))
        } else {
            0.0
        };
        zeta * n.decay + sign * drift * n.drift_time + path + spread.sqrt() * n.noise * normal
    }

    /// The well-mixed drift `A` away from the wall at `distance` for `zeta` (for tests).
    #[cfg(test)]
    fn well_mixed_drift(&self, distance: f64, zeta: f64) -> f64 {
        let n = self.node(distance);
        (self.step(distance, 1.0, zeta, 0.0) - zeta * n.decay) / n.drift_time
    }
}

#[cfg(test)]
mod tests {
    use rand_distr::{Distribution, StandardNormal};

    use super::*;

    #[test]
    fn flatness_follows_the_dns_profile_and_gives_the_t_with_that_flatness() {
        assert_eq!(flatness(0.0), 26.972);
        assert!((flatness(5.0) - (13.885 + (12.411 - 13.885) * (5.0 - 4.3280) / (5.3381 - 4.3280))).abs() < 1e-12);
        assert_eq!(flatness(500.0), 3.9224);
        // The t with nu degrees of freedom has flatness 3 + 6 / (nu - 4).
        for f in [3.3, 5.0, 27.0] {
            let nu = degrees_of_freedom(f);
            assert!((3.0 + 6.0 / (nu - 4.0) - f).abs() < 1e-12);
        }
    }

    #[test]
    fn drift_is_the_gaussian_models_where_the_spread_is_one() {
        // Beyond the DNS profile (y+ > 178) nu is constant, 4 + 6 / 0.9224 = 10.505, and
        // A = sigma' (nu - 2 + zeta^2) / (nu - 1): sigma', the Gaussian model's drift, at
        // zeta = +-1, and less or more than it for weaker or stronger fluctuations. Worked in
        // wall units (u* = 1 m/s, nu_air = 1 m^2/s), sigma' by central differences.
        let model = Intermittent::channel(300.0, 1.0, 1.0, 0.2, true, SeenVelocity::Normalised);
        let y = 250.01; // a node: 0.01 + 0.02 * 12500
        let h = 1e-4;
        let slope = (wall_normal_rms(y + h) - wall_normal_rms(y - h)) / (2.0 * h);
        let nu = 4.0 + 6.0 / (3.9224 - 3.0);
        for zeta in [-1.0, 1.0, 0.0, 3.0] {
            let by_hand = slope * (nu - 2.0 + zeta * zeta) / (nu - 1.0);
            let drift = model.well_mixed_drift(y, zeta);
            assert!((drift - by_hand).abs() < 1e-6 * slope.abs(), "zeta {zeta}: {drift} against {by_hand}");
        }
        assert!((model.well_mixed_drift(y, 1.0) / slope - 1.0).abs() < 1e-6);
    }

    #[test]
    fn the_fluid_form_adds_thomsons_path_term_worked_by_hand() {
        // At the node y+ = 5.01 in wall units (u* = 1 m/s, nu_air = 1 m^2/s), dt = 0.2: the
        // fluid form's step less the normalised one is sign r w^2 / (1 + r |w|), w = sign zeta,
        // r = sigma' T_L (1 - exp(-dt / T_L)), T_L+ = 7.122 + 0.5731 y+ - 0.00129 y+^2 and
        // sigma' by central differences of the fit. A wall-ward w of -2 shrinks to
        // w / (1 + r |w|) over the path term alone; an outward one grows by less than w.
        let normalised = Intermittent::channel(150.0, 1.0, 1.0, 0.2, true, SeenVelocity::Normalised);
        let fluid = Intermittent::channel(150.0, 1.0, 1.0, 0.2, true, SeenVelocity::Fluid);
        let y: f64 = 5.01;
        let h = 0.005;
        let slope = (wall_normal_rms(y + h) - wall_normal_rms(y - h)) / (2.0 * h);
        let t = 7.122 + 0.5731 * y - 0.00129 * y * y;
        let r = slope * t * (1.0 - (-0.2 / t).exp());
        for (sign, zeta, normal) in [(1.0, -2.0, 0.0), (-1.0, 2.0, 0.7), (1.0, 3.0, -1.1), (-1.0, -0.5, 0.0)] {
            let w: f64 = sign * zeta;
            let by_hand = sign * r * w * w / (1.0 + r * w.abs());
            let added = fluid.step(y, sign, zeta, normal) - normalised.step(y, sign, zeta, normal);
            assert!((added - by_hand).abs() < 1e-3 * by_hand.abs(), "w {w}: {added} against {by_hand}");
            if w < 0.0 {
                assert!((w + sign * added - w / (1.0 + r * w.abs())).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn drift_matches_the_formula_worked_by_hand() {
        // At y+ = 2 (between the DNS points 1.9279 and 2.6224), zeta = 2, in wall units:
        // A = sigma' S + sigma nu' S [D - ln(q)/2 + (nu - 1) zeta^2 / (2 (nu - 2)^2 q)], the
        // derivatives by central differences of the functions as written here.
        let model = Intermittent::channel(150.0, 1.0, 1.0, 0.2, true, SeenVelocity::Normalised);
        let y = 0.01 + 0.02 * ((2.0f64 - 0.01) / 0.02).floor(); // the node below y+ = 2
        let nu_at = |y: f64| 4.0 + 6.0 / (19.467 + (17.443 - 19.467) * (y - 1.9279) / (2.6224 - 1.9279) - 3.0);
        let sigma_at = |y: f64| 0.0116 * y * y / (1.0 + 0.203 * y + 0.0014 * y.powf(2.421));
        let ln_k = |nu: f64| {
            libm::lgamma(0.5 * (nu + 1.0)) - libm::lgamma(0.5 * nu) - 0.5 * (std::f64::consts::PI * (nu - 2.0)).ln()
                + (nu - 2.0).ln()
                - (nu - 1.0).ln()
        };
        let h = 0.005;
        let (nu, sigma) = (nu_at(y), sigma_at(y));
        let dnu = (nu_at(y + h) - nu_at(y - h)) / (2.0 * h);
        let dsigma = (sigma_at(y + h) - sigma_at(y - h)) / (2.0 * h);
        let d = (ln_k(nu + 1e-5) - ln_k(nu - 1e-5)) / 2e-5;
        let zeta: f64 = 2.0;
        let q = 1.0 + zeta * zeta / (nu - 2.0);
        let s = (nu - 2.0 + zeta * zeta) / (nu - 1.0);
        let by_hand = dsigma * s
            + sigma * dnu * s * (d - 0.5 * q.ln() + (nu - 1.0) * zeta * zeta / (2.0 * (nu - 2.0).powi(2) * q));
        let drift = model.well_mixed_drift(2.0, zeta);
        assert!((drift / by_hand - 1.0).abs() < 1e-4, "{drift} against {by_hand}");
    }

    #[test]
    fn drift_meets_thomsons_condition_by_quadrature() {
        // Thomson's condition for tracers, dy = sigma zeta dt, with the stationary density
        // uniform in y times P(zeta; nu(y)): A P = d(sigma G)/dy, G = int_|zeta|^inf u P du.
        // Here G by quadrature of the t's density (independent of the code's closed form),
        // the y-derivative by central differences, in wall units (u* = 1 m/s, nu = 1 m^2/s).
        let model = Intermittent::channel(150.0, 1.0, 1.0, 0.2, true, SeenVelocity::Normalised);
        let nu_at = |y: f64| 4.0 + 6.0 / (flatness(y) - 3.0);
        let density = |u: f64, nu: f64| {
            let k = (libm::lgamma(0.5 * (nu + 1.0)) - libm::lgamma(0.5 * nu)).exp()
                / (std::f64::consts::PI * (nu - 2.0)).sqrt();
            k * (1.0 + u * u / (nu - 2.0)).powf(-0.5 * (nu + 1.0))
        };
        let g = |zeta: f64, nu: f64| {
            // Trapezoids on u = |zeta| + e^s - 1, s up to ln(2001): the tail beyond is < 1e-10.
            let (h, end) = (1e-3, 2001f64.ln());
            let f = |s: f64| {
                let u = zeta.abs() + s.exp_m1();
                u * density(u, nu) * s.exp()
            };
            let n = (end / h) as usize;
            (1..n).map(|i| f(i as f64 * h)).sum::<f64>() * h + 0.5 * h * (f(0.0) + f(n as f64 * h))
        };
        for k in [24, 99, 399, 1499] {
            let y = 0.01 + 0.02 * f64::from(k); // nodes at y+ 0.49, 1.99, 7.99, 29.99
            let h = 0.005;
            for zeta in [-4.0, -1.0, 0.0, 1.5, 6.0] {
                let flux = |y: f64| wall_normal_rms(y) * g(zeta, nu_at(y));
                let thomson = (flux(y + h) - flux(y - h)) / (2.0 * h) / density(zeta, nu_at(y));
                let drift = model.well_mixed_drift(y, zeta);
                assert!((drift / thomson - 1.0).abs() < 1e-3, "y+ {y}, zeta {zeta}: {drift} against {thomson}");
            }
        }
    }

    #[test]
    fn steps_keep_the_variance_and_grow_the_tails() {
        // The process at a fixed distance with the well-mixed drift removed (sign 0): its
        // stationary distribution is the unit-variance t with the flatness there (F = 27 at
        // y+ ~ 0.05 is beyond what a sample can show; at y+ = 15, F = 6.1).
        let model = Intermittent::channel(150.0, 1.0, 1.0, 0.2, true, SeenVelocity::Normalised);
        let y = 15.0;
        let (mut w, mut m2, mut m4) = (0.0, 0.0, 0.0);
        let mut rng = crate::noise::particle_rng(1, 0);
        let n = 2_000_000;
        for i in 0..n + 1000 {
            w = model.step(y, 0.0, w, StandardNormal.sample(&mut rng));
            if i >= 1000 {
                m2 += w * w;
                m4 += w * w * w * w;
            }
        }
        let (var, flat) = (m2 / n as f64, m4 / n as f64 / (m2 / n as f64).powi(2));
        assert!((var - 1.0).abs() < 0.1, "variance {var}");
        assert!(flat > 4.5 && flat < 8.0, "flatness {flat} against {}", flatness(y));
    }
}
