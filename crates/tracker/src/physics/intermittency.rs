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
//! The drift grows like `zeta^2` (through `S`), faster than the decay `-zeta / T_L` shrinks
//! `zeta`: along a tracer's path the tracer soon leaves the region that feeds the growth, but
//! a particle that does not follow its fluid can stay, and there the deterministic part
//! blows up in finite time (an outward `zeta` of 30 held at `y+ = 2`, or a wall-ward 10 at
//! `y+ = 20`, reached infinity within 100 wall time units) — the unstable modes Yee & Wilson
//! (2007, *Boundary-Layer Meteorol.* 122:243) found in Lagrangian stochastic models whose
//! drift is nonlinear in the velocity. As they do, the step keeps the nonlinear part from
//! overtaking the linear one: the drift is evaluated with `zeta` held within bounds,
//! tabulated per node and per side, the largest `|zeta|` up to which the drift's change from
//! `A(0)` neither grows `|zeta|` faster than half the decay, `|zeta| / (2 T_L)`, nor shrinks it
//! by more than half in a step (the half leaves the decay the upper hand at the bound, so a
//! particle held still relaxes to the drift's balance). The bounds lie in the far tails: the
//! tightest 3.2-5 wall-ward at `y+` 10-50 and 3.7-4.2 outward at `y+` 65-103, outward 5-17
//! at `y+` 0.5-10, wall-ward 7.6 at the centre, tens to thousands elsewhere (a channel of
//! `Re_tau = 150`, `dt+ = 0.2`); at most 0.27 % of the local t lies beyond
//! them (tested), and tracers stay well mixed (tested). Within them the drift is Thomson's.
//!
//! What is stepped along a particle's path is the normalised `zeta`, so that the fluid
//! velocity a particle sees follows the local statistics wherever the particle goes. Stepping
//! the fluid velocity itself with Thomson's drift for it was tried and withdrawn: that drift,
//! `sigma (A + sigma' zeta^2)`, is quadratic in the fluid velocity and right only along a
//! fluid element's path; along the path of a particle that does not follow its fluid nothing
//! balances it, and the fluid velocity seen runs away (`docs/validation.md`). The test
//! `a_particle_held_still_sees_a_bounded_fluid_velocity` guards this.
//!
//! Only the wall-normal component is intermittent: it alone carries particles to the wall.
//! The Student-t is this model's choice of family: the heavy-tailed distribution fixed by the
//! variance and flatness alone, with no further constant.

use crate::physics::profiles::{lagrangian_time, profile_at, wall_normal_rms};

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
    /// `sqrt(nu - 2)` and `sqrt(1 / (nu - 1))`: the spread's root as `hypot(sqrt(nu - 2),
    /// zeta) sqrt(1 / (nu - 1))`, finite for any finite `zeta`.
    root_nu_m2: f64,
    root_inv_nu_m1: f64,
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
    /// The bounds on wall-ward and outward `zeta` (both positive) within which the drift is
    /// evaluated (see the module doc).
    zeta_max: [f64; 2],
}

impl Node {
    /// The well-mixed drift `A` (1/s) away from the wall at `zeta`.
    #[inline(always)]
    fn drift(&self, zeta: f64) -> f64 {
        let z2 = zeta * zeta;
        let q = 1.0 + z2 / self.nu_m2;
        let spread = (self.nu_m2 + z2) * self.inv_nu_m1;
        let shape = self.d_ln_k - 0.5 * q.ln() + 0.5 * z2 / (self.inv_nu_m1 * self.nu_m2 * self.nu_m2 * q);
        spread * (self.slope + self.sigma * self.dnu * shape)
    }

    /// The largest `zeta` of the sign of `side` (up to 1e4 in size) up to which the drift's
    /// change from `A(0)` neither grows `|zeta|` faster than half the decay, `|zeta| / (2
    /// T_L)`, nor shrinks it by more than half over a step; on a geometric grid of 5 % steps
    /// from 0.01. `lagrangian` is `T_L` in s.
    fn drift_bound(&self, side: f64, lagrangian: f64) -> f64 {
        let at_rest = self.drift(0.0);
        let within = |z: f64| {
            let growth = (self.drift(side * z) - at_rest) * side;
            growth <= z / (2.0 * lagrangian) && -growth * self.drift_time <= 0.5 * z
        };
        let mut z: f64 = 0.01;
        while z < 1e4 && within(z) {
            z *= 1.05;
        }
        z / 1.05
    }
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
}

impl Intermittent {
    /// For a channel of half-height `half` (m), friction velocity `u*` (m/s) and kinematic
    /// viscosity `nu` (m^2/s), and a step `dt` (s); `drift = false` drops the well-mixed
    /// drift (for comparison only).
    #[must_use]
    pub fn channel(half: f64, friction_velocity: f64, viscosity: f64, dt: f64, drift: bool) -> Self {
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
                let lagrangian = time * lagrangian_time(y);
                let mut node = Node {
                    sigma: friction_velocity * wall_normal_rms(y),
                    slope: on * friction_velocity * (wall_normal_rms(y + h) - wall_normal_rms(y - h)) * per_metre,
                    nu_m2: n - 2.0,
                    inv_nu_m1: 1.0 / (n - 1.0),
                    root_nu_m2: (n - 2.0).sqrt(),
                    root_inv_nu_m1: (1.0 / (n - 1.0)).sqrt(),
                    dnu: on * (nu(y + h) - nu(y - h)) * per_metre,
                    d_ln_k: (ln_k(n + eps) - ln_k(n - eps)) / (2.0 * eps),
                    decay: (-dt / lagrangian).exp(),
                    noise: (-(-2.0 * dt / lagrangian).exp_m1()).sqrt(),
                    drift_time: -lagrangian * (-dt / lagrangian).exp_m1(),
                    zeta_max: [f64::INFINITY; 2],
                };
                node.zeta_max = [node.drift_bound(-1.0, lagrangian), node.drift_bound(1.0, lagrangian)];
                node
            })
            .collect();
        Self { nodes, inv_dy: plus / spacing, y0: y0 / plus }
    }

    fn node(&self, distance: f64) -> &Node {
        let i = ((distance - self.y0) * self.inv_dy).max(0.0) as usize;
        &self.nodes[i.min(self.nodes.len() - 1)]
    }

    /// The normalised wall-normal fluctuation `zeta` one step later, at `distance` (m) from
    /// the nearer wall, `sign` the sign of `d(distance)/dz`, driven by the standard normal
    /// `normal`: the Gaussian model's exact step for frozen coefficients, `zeta decay + A T_L
    /// (1 - decay) + sqrt(S (1 - decay^2)) normal`, with the spread `S` and the drift `A` at
    /// the step's start, `A` evaluated with `zeta` held within the node's bounds.
    #[inline]
    #[must_use]
    pub fn step(&self, distance: f64, sign: f64, zeta: f64, normal: f64) -> f64 {
        let n = self.node(distance);
        let root_spread = n.root_nu_m2.hypot(zeta) * n.root_inv_nu_m1;
        // `sign * zeta` is outward; the bounds are on it.
        let drift = n.drift(sign * (sign * zeta).clamp(-n.zeta_max[0], n.zeta_max[1]));
        zeta * n.decay + sign * drift * n.drift_time + root_spread * n.noise * normal
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
        let model = Intermittent::channel(300.0, 1.0, 1.0, 0.2, true);
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
    fn a_particle_held_still_sees_a_bounded_fluid_velocity() {
        // A particle far heavier than its fluid barely moves while the fluid velocity it sees
        // changes: held at one distance, with the noise off, `zeta` must settle to the drift's
        // balance `A T_L` (a few tenths) from any start, wall-ward or outward, within 600 wall
        // time units (12 T_L at y+ = 100). Without the drift's bound an outward 30 at y+ = 2
        // and a wall-ward 10 at y+ = 20 blew up to NaN. The withdrawn fluid-velocity form
        // added Thomson's path term `sigma' zeta^2` per unit time, a fluid element's, which
        // nothing balances off a fluid element's path: from `zeta = 3` at `y+ = 2` it runs
        // away even with the bound (checked below with the term added by hand).
        let model = Intermittent::channel(150.0, 1.0, 1.0, 0.2, true);
        for y in [0.5, 2.0, 5.0, 10.0, 20.0, 50.0, 100.0] {
            for start in [-100.0, -30.0, -10.0, -3.0, -1.0, 1.0, 3.0, 10.0, 30.0, 100.0] {
                let mut zeta: f64 = start;
                let mut largest: f64 = 0.0;
                for _ in 0..3000 {
                    zeta = model.step(y, 1.0, zeta, 0.0);
                    largest = largest.max(zeta.abs());
                }
                assert!(zeta.abs() < 1.0, "y+ {y}, from {start}: zeta {zeta}");
                assert!(largest <= start.abs(), "y+ {y}, from {start}: reached {largest}");
            }
            // Finite from any finite start, with or without noise.
            for zeta in [-1e300, 1e300] {
                assert!(model.step(y, 1.0, zeta, 0.0).is_finite() && model.step(y, -1.0, zeta, 3.0).is_finite());
            }
        }
        let (y, h) = (2.0, 1e-3);
        let slope = (wall_normal_rms(y + h) - wall_normal_rms(y - h)) / (2.0 * h);
        let drift_time = -10.0 * (-0.2f64 / 10.0).exp_m1(); // T_L+ = 10 below y+ = 5
        let mut zeta: f64 = 3.0;
        for _ in 0..500 {
            zeta = model.step(y, 1.0, zeta, 0.0) + slope * zeta * zeta * drift_time;
            if zeta.abs() > 1e6 {
                break;
            }
        }
        assert!(zeta.abs() > 1e6, "with the fluid element's path term: {zeta}");
    }

    #[test]
    fn the_drift_bound_leaves_the_body_of_the_distribution_alone() {
        // The share of the local t beyond the drift's bounds, by quadrature of its density
        // (u = bound + e^s - 1): the bound changes the drift only in the far tails.
        let model = Intermittent::channel(150.0, 1.0, 1.0, 0.2, true);
        let tail = |bound: f64, nu: f64| {
            let k = (libm::lgamma(0.5 * (nu + 1.0)) - libm::lgamma(0.5 * nu)).exp()
                / (std::f64::consts::PI * (nu - 2.0)).sqrt();
            let f = |s: f64| {
                let u = bound + s.exp_m1();
                k * (1.0 + u * u / (nu - 2.0)).powf(-0.5 * (nu + 1.0)) * s.exp()
            };
            let (h, n) = (4e-3, 3_000); // to u = bound + 1.6e5
            (1..n).map(|i| f(f64::from(i) * h)).sum::<f64>() * h + 0.5 * h * (f(0.0) + f(f64::from(n) * h))
        };
        let mut largest: f64 = 0.0;
        for k in (0..7500).step_by(7) {
            let y = 0.01 + 0.02 * f64::from(k); // every seventh node, wall to centre
            let nu = degrees_of_freedom(flatness(y));
            let [wall_ward, outward] = model.node(y).zeta_max;
            largest = largest.max(tail(wall_ward, nu)).max(tail(outward, nu));
        }
        assert!(largest < 5e-3, "{largest}"); // 2.7e-3 over every node
    }

    #[test]
    fn drift_matches_the_formula_worked_by_hand() {
        // At y+ = 2 (between the DNS points 1.9279 and 2.6224), zeta = 2, in wall units:
        // A = sigma' S + sigma nu' S [D - ln(q)/2 + (nu - 1) zeta^2 / (2 (nu - 2)^2 q)], the
        // derivatives by central differences of the functions as written here.
        let model = Intermittent::channel(150.0, 1.0, 1.0, 0.2, true);
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
        let model = Intermittent::channel(150.0, 1.0, 1.0, 0.2, true);
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
            // Within the drift's bounds (wall-ward 3.2 at y+ = 30, the tightest here).
            for zeta in [-3.0, -1.0, 0.0, 1.5, 6.0] {
                let [wall_ward, outward] = model.node(y).zeta_max;
                assert!(-zeta <= wall_ward && zeta <= outward, "y+ {y}: {zeta} beyond {wall_ward}, {outward}");
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
        let model = Intermittent::channel(150.0, 1.0, 1.0, 0.2, true);
        let y = 15.0;
        let (mut w, mut m2, mut m4) = (0.0, 0.0, 0.0);
        let mut rng = crate::physics::noise::particle_rng(1, 0);
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
