//! Deposition correlations and models to compare runs with. Each takes the particle's
//! Schmidt number `Sc = nu / D` and, for channels, its dimensionless relaxation time
//! `tau+ = tau u*^2 / nu`; deposition velocities are made dimensionless as `V+ = v_d / u*`.

use std::f64::consts::PI;

use crate::model::air::{Aerodynamics, Air};

/// Lai & Nazaroff (2000), *Modeling indoor particle deposition from turbulent flow onto smooth
/// surfaces*, J. Aerosol Sci. 31: the deposition velocities (m/s) onto an upward-facing
/// surface (floor), a downward-facing one (ceiling) and a vertical wall of a room with
/// near-wall friction velocity `u*`.
///
/// ```text
/// v_floor   = v_s / (1 - exp(-v_s I / u*))
/// v_ceiling = v_s / (exp(v_s I / u*) - 1)
/// v_wall    = u* / I
/// I = 3.64 Sc^(2/3) (a - b) + 39
/// a = 1/2 ln[(10.92 Sc^(-1/3) + 4.3)^3 / (1/Sc + 0.0609)] + sqrt(3) atan[(8.6 - 10.92 Sc^(-1/3)) / (sqrt(3) 10.92 Sc^(-1/3))]
/// b = 1/2 ln[(10.92 Sc^(-1/3) + r+)^3 / (1/Sc + 7.669e-4 r+^3)] + sqrt(3) atan[(2 r+ - 10.92 Sc^(-1/3)) / (sqrt(3) 10.92 Sc^(-1/3))]
/// ```
///
/// with `r+ = r u* / nu` the particle radius in wall units. The model carries particles by
/// Brownian and turbulent diffusion and gravity only: no inertia (no turbophoresis or
/// impaction), which is why it misses the rise of vertical-wall deposition with size above
/// about 1 um that their 2005 measurements show.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LaiNazaroff {
    /// Onto an upward-facing surface, m/s.
    pub floor: f64,
    /// Onto a downward-facing surface, m/s.
    pub ceiling: f64,
    /// Onto a vertical surface, m/s.
    pub wall: f64,
}

/// The integral `I` of [`LaiNazaroff`] for Schmidt number `sc` and radius `r_plus` in wall units.
#[must_use]
pub fn lai_nazaroff_integral(sc: f64, r_plus: f64) -> f64 {
    let a0 = 10.92 * sc.powf(-1.0 / 3.0);
    let s3 = 3f64.sqrt();
    let a = 0.5 * ((a0 + 4.3).powi(3) / (1.0 / sc + 0.0609)).ln() + s3 * ((8.6 - a0) / (s3 * a0)).atan();
    let b = 0.5 * ((a0 + r_plus).powi(3) / (1.0 / sc + 7.669e-4 * r_plus.powi(3))).ln()
        + s3 * ((2.0 * r_plus - a0) / (s3 * a0)).atan();
    3.64 * sc.powf(2.0 / 3.0) * (a - b) + 39.0
}

impl LaiNazaroff {
    /// For a particle of `diameter` (m) and `density` (kg/m^3) in `air` under `gravity` (m/s^2)
    /// with friction velocity `friction_velocity` (m/s).
    #[must_use]
    pub fn new(diameter: f64, density: f64, air: &Air, gravity: f64, friction_velocity: f64) -> Self {
        let aero = Aerodynamics::new(diameter, density, air, gravity);
        let nu = air.kinematic_viscosity();
        let sc = nu / aero.diffusivity;
        let r_plus = 0.5 * diameter * friction_velocity / nu;
        Self::from_integral(lai_nazaroff_integral(sc, r_plus), aero.settling_speed, friction_velocity)
    }

    /// From the integral `I`, settling speed `v_s` and friction velocity `u*` (m/s).
    #[must_use]
    pub fn from_integral(integral: f64, settling: f64, friction_velocity: f64) -> Self {
        let wall = friction_velocity / integral;
        let x = settling * integral / friction_velocity;
        if x < 1e-12 {
            return Self { floor: wall, ceiling: wall, wall };
        }
        // v_s / (1 - e^-x) and v_s e^-x / (1 - e^-x), written with exp_m1 for small x.
        let one_minus = -(-x).exp_m1();
        Self { floor: settling / one_minus, ceiling: settling * (-x).exp() / one_minus, wall }
    }

    /// Loss-rate coefficient of a box room, `beta = (v_floor A_floor + v_ceiling A_ceiling +
    /// v_wall A_walls) / V`, 1/s.
    #[must_use]
    pub fn loss_rate(&self, size: [f64; 3]) -> f64 {
        let [lx, ly, lz] = size;
        let horizontal = lx * ly;
        let vertical = 2.0 * (lx + ly) * lz;
        (self.floor * horizontal + self.ceiling * horizontal + self.wall * vertical) / (lx * ly * lz)
    }
}

/// Hussein, Smolík, Kerminen & Kulmala (2012), *Modeling dry deposition of aerosol particles
/// onto rough surfaces*, Aerosol Sci. Technol. 46:44-59, on a smooth surface: the dimensionless
/// deposition velocity `V+ = v_d / u*` of an Eulerian drift-flux model with Brownian and
/// turbulent diffusion, settling and turbophoresis, for Schmidt number `schmidt`, relaxation
/// time `tau_plus = tau u*^2 / nu`, radius `r_plus = r u* / nu` and settling speed
/// `settling_plus = v_s / u*` in wall units, onto a surface `facing` up (1, a floor), sideways
/// (0, a vertical wall) or down (-1, a ceiling).
///
/// The flux `J` towards the wall is constant across the layer `r+ < y+ < 100`:
///
/// ```text
/// J+ = D+ dC/dy+ + (facing v_s+ + tau+ d(v_p+^2)/dy+) C,   C(r+) = 0
/// V+ = J+ / C(100) = 1 / ∫_{r+}^{100} exp(F(y+) - F(100)) / D+ dy+
/// F(y+) = ∫_{r+}^{y+} (facing v_s+ + tau+ d(v_p+^2)/dy+) / D+ dy+
/// D+ = 1/Sc + x nu_t+,   x = tau_L+ / (tau_L+ + tau+),   tau_L+ = nu_t+ / v_y+^2
/// v_p+^2 = v_y+^2 / (1 + (tau+/tau_L+)^(1/2) + (tau+/tau_L+)^(3/2))
/// v_y+ = 0.005 y+^2 / (1 + 0.002923 y+^2.128)
/// nu_t+ = (y+/11.15)^3 (y+ < 3),  (y+/11.4)^2 - 0.049774 (y+ < 52.108),  0.4 y+
/// ```
///
/// The equations and every constant are as the model's author wrote them in its Fortran
/// form, routine `DEPOFROUGH` of the aerosol model MAFOR v2 (github.com/mafor2/mafor,
/// `src/GDE/gde_deposition.f90`; the paper itself could not be read): the wall-normal rms
/// `v_y+` is Guha's (1997) fit "after Zhao and Wu (2006a)", the eddy viscosity Lai &
/// Nazaroff's (2000) with Johansen's (1991) `0.4 y+` beyond `y+ = 52.108`, the reference
/// concentration that at `y+ = 100` (its `Ymax`), the deposition plane the particle's
/// radius (a smooth surface: roughness `F+ = 0`) and the settling term's sign by
/// orientation (`i_surface`). Two readings of that routine are made here: the turbophoretic
/// drift is `-tau d(v_p^2)/dy` as its equation (3) states, where the routine takes its
/// magnitude (the two differ only beyond `y+` 56, where `v_y` falls; by less than 0.1 % in
/// the cases of docs/validation.md), and of the two particle intensities it carries (the
/// `x v_y^2` of its comments and the form above) the one it computes. The integrals are
/// taken on a logarithmic grid of [`HUSSEIN_CELLS`] cells (the routine's own grid has 450).
///
/// Where `tau+` is small (a room's `u*` of about 1 cm/s and particles up to 10 um) the drift
/// hardly acts where the transfer is limited, within a few wall units of the wall, and the
/// model gives Lai & Nazaroff's (2000) diffusion within a few per cent (docs/validation.md).
#[must_use]
pub fn hussein(schmidt: f64, tau_plus: f64, r_plus: f64, settling_plus: f64, facing: f64) -> f64 {
    let n = HUSSEIN_CELLS;
    let (u0, u1) = (r_plus.ln(), HUSSEIN_TOP.ln());
    let h = (u1 - u0) / n as f64;
    let y = |k: usize| (u0 + h * k as f64).exp();
    let wall_normal_sq = |y: f64| {
        let v = 0.005 * y * y / (1.0 + 0.002923 * y.powf(2.128));
        v * v
    };
    let eddy_viscosity = |y: f64| {
        if y < 3.0 {
            (y / 11.15).powi(3)
        } else if y < 52.108 {
            (y / 11.4).powi(2) - 0.049_774
        } else {
            0.4 * y
        }
    };
    // The particle's intensity and diffusivity at `y`.
    let particle = |y: f64| {
        let (vy2, nut) = (wall_normal_sq(y), eddy_viscosity(y));
        let tau_l = nut / vy2;
        let r = tau_plus / tau_l;
        let vp2 = vy2 / (1.0 + r.sqrt() + r * r.sqrt());
        (vp2, 1.0 / schmidt + tau_l / (tau_l + tau_plus) * nut)
    };
    // F at the grid's nodes, then the integral, each cell taken at its (geometric) middle.
    let mut f = Vec::with_capacity(n + 1);
    f.push(0.0);
    let (mut vp2_low, mut y_low) = (particle(y(0)).0, y(0));
    for k in 0..n {
        let y_high = y(k + 1);
        let (vp2_high, _) = particle(y_high);
        let (_, d) = particle((y_low * y_high).sqrt());
        let step = (facing * settling_plus * (y_high - y_low) + tau_plus * (vp2_high - vp2_low)) / d;
        f.push(f[k] + step);
        (vp2_low, y_low) = (vp2_high, y_high);
    }
    let top = f[n];
    let integral: f64 = (0..n)
        .map(|k| {
            let (a, b) = (y(k), y(k + 1));
            let (_, d) = particle((a * b).sqrt());
            (0.5 * (f[k] + f[k + 1]) - top).exp() / d * (b - a)
        })
        .sum();
    1.0 / integral
}

/// The outer edge of [`hussein`]'s layer, where its reference concentration is taken, in
/// wall units (`Ymax` of the model's routine).
pub const HUSSEIN_TOP: f64 = 100.0;

/// The cells of [`hussein`]'s logarithmic grid from the particle's radius to
/// [`HUSSEIN_TOP`].
pub const HUSSEIN_CELLS: usize = 4000;

/// Wood (1981), *A simple method for the calculation of turbulent deposition to smooth and
/// rough surfaces*, J. Aerosol Sci. 12: `V+ = 0.057 Sc^(-2/3) + 4.5e-4 tau+^2`, at most 0.13
/// (the inertia-moderated plateau).
#[must_use]
pub fn wood(tau_plus: f64, schmidt: f64) -> f64 {
    (0.057 * schmidt.powf(-2.0 / 3.0) + 4.5e-4 * tau_plus * tau_plus).min(0.13)
}

/// Papavergos & Hedley (1984), *Particle deposition behaviour from turbulent flows*, Chem. Eng.
/// Res. Des. 62: `V+ = 0.065 Sc^(-2/3)` (`tau+ < 0.2`), `3.5e-4 tau+^2` (`0.2 <= tau+ <= 20`),
/// `0.18` (`tau+ > 20`).
#[must_use]
pub fn papavergos_hedley(tau_plus: f64, schmidt: f64) -> f64 {
    if tau_plus < 0.2 {
        0.065 * schmidt.powf(-2.0 / 3.0)
    } else if tau_plus <= 20.0 {
        3.5e-4 * tau_plus * tau_plus
    } else {
        0.18
    }
}

/// How far `value` lies outside the band between two correlations `a` and `b` (say Wood's and
/// Papavergos & Hedley's `V+` at one `tau+`): 1 within it, `value / min(a, b)` below it and
/// `value / max(a, b)` above it. The two correlations were fitted to overlapping compilations
/// of the same measurements, so their spread is a floor on how well any one point is known;
/// a model within a factor 2 of the band (a result in `[0.5, 2]`) agrees with them.
pub fn band_factor(value: f64, a: f64, b: f64) -> f64 {
    let (low, high) = (a.min(b), a.max(b));
    if value >= low && value <= high {
        1.0
    } else if value < low {
        value / low
    } else {
        // Above the band, or NaN (which passes through).
        value / high
    }
}

/// The particle diameter (m) of density `density` with dimensionless relaxation time `tau_plus`
/// in a flow of friction velocity `u*` (slip included, found by bisection), or `None` when no
/// diameter between 0.1 nm and 1 cm gives it (say, `tau+ = 10` at `u* = 1e-4 m/s` would need
/// a particle larger than 1 cm).
#[must_use]
pub fn diameter_for_tau_plus(tau_plus: f64, density: f64, air: &Air, friction_velocity: f64) -> Option<f64> {
    let nu = air.kinematic_viscosity();
    let tau = tau_plus * nu / (friction_velocity * friction_velocity);
    let relaxation = |d: f64| Aerodynamics::new(d, density, air, 0.0).relaxation_time;
    let (mut lo, mut hi) = (1e-10_f64, 1e-2_f64);
    if !(tau.is_finite() && relaxation(lo) <= tau && tau <= relaxation(hi)) {
        return None;
    }
    for _ in 0..200 {
        let mid = (lo * hi).sqrt();
        if relaxation(mid) < tau {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Some((lo * hi).sqrt())
}

/// Schmidt number `nu / D` of a particle.
#[must_use]
pub fn schmidt(diameter: f64, air: &Air) -> f64 {
    // D depends on size only, not on density.
    let slip = crate::model::air::slip_correction(diameter, air.mean_free_path());
    air.kinematic_viscosity() / crate::model::air::diffusivity(diameter, slip, air)
}

/// The still-air Brownian deposition flux onto a floor with settling, from a uniform initial
/// concentration, as a deposition velocity at time `t` (s): the exact solution of the
/// advection-diffusion equation over a perfectly absorbing plane,
/// `J/C0 = v_s/2 [1 + erf(v_s sqrt(t) / (2 sqrt(D)))] + sqrt(D / (pi t)) exp(-v_s^2 t / (4 D))`.
#[must_use]
pub fn settling_diffusion_flux(settling: f64, diffusivity: f64, t: f64) -> f64 {
    let z = settling * t.sqrt() / (2.0 * diffusivity.sqrt());
    0.5 * settling * (1.0 + libm::erf(z)) + (diffusivity / (PI * t)).sqrt() * (-z * z).exp()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn band_factor_is_one_within_and_the_ratio_to_the_nearer_edge_outside() {
        // tau+ = 1: Wood 4.5e-4, Papavergos & Hedley 3.5e-4.
        assert_eq!(band_factor(4e-4, 4.5e-4, 3.5e-4), 1.0);
        assert!((band_factor(7e-5, 4.5e-4, 3.5e-4) - 0.2).abs() < 1e-12);
        assert!((band_factor(1.35e-3, 3.5e-4, 4.5e-4) - 3.0).abs() < 1e-12);
        // On an edge, within; a NaN is not reported within.
        assert_eq!(band_factor(3.5e-4, 4.5e-4, 3.5e-4), 1.0);
        assert!(band_factor(f64::NAN, 4.5e-4, 3.5e-4).is_nan());
    }

    #[test]
    fn lai_nazaroff_integral_matches_hand_values() {
        // Evaluated independently of this code from the formula above.
        assert!((lai_nazaroff_integral(1000.0, 0.01) / 1_314.923_307_742_62 - 1.0).abs() < 1e-10);
        assert!((lai_nazaroff_integral(1e5, 0.05) / 23_473.929_525_906_453 - 1.0).abs() < 1e-10);
    }

    #[test]
    fn lai_nazaroff_orders_surfaces_and_has_the_settling_limits() {
        let ln = LaiNazaroff::from_integral(23_473.929_525_906_453, 1e-4, 0.01);
        assert!((ln.wall - 4.260_045_165_835_457_7e-7).abs() < 1e-18);
        assert!((ln.floor - 1e-4).abs() < 1e-12, "strong settling: floor takes v_s");
        assert!(ln.ceiling < 1e-100);
        let small = LaiNazaroff::from_integral(1000.0, 1e-9, 0.01);
        assert!(small.floor > small.wall && small.wall > small.ceiling);
        assert!((small.floor - small.ceiling - 1e-9).abs() < 1e-15, "floor - ceiling = v_s exactly");
        // A real particle: 1 um, unit density, u* = 1 cm/s.
        let one = LaiNazaroff::new(1e-6, 1000.0, &Air::standard(), 9.80665, 0.01);
        assert!(one.floor > 3e-5 && one.floor < 4e-5, "{}", one.floor);
        assert!(one.wall < 1e-5 && one.wall > 1e-7, "{}", one.wall);
        let beta = one.loss_rate([4.0, 4.0, 2.5]);
        assert!((beta - (one.floor + one.ceiling) / 2.5 - one.wall * 2.0 * 8.0 / 16.0).abs() < 1e-15);
    }

    #[test]
    fn hussein_matches_an_independent_evaluation() {
        // Evaluated independently of this code from the equations in its docs: Simpson's rule
        // on 200000 logarithmic cells, the drift from the analytic derivative of v_p^2
        // (converged to 6e-7 or better against 400000 cells).
        let cases = [
            // (Sc, tau+, r+, v_s+, facing, V+): inertial onto a wall, floor and ceiling with
            // settling, a room's 1 um particle, the inertia-moderated regime.
            (1e6, 1.0, 0.3, 0.0, 0.0, 3.254_683_934_1e-4),
            (1e4, 0.01, 0.05, 0.01, 1.0, 1.007_118_730_8e-2),
            (1e4, 0.01, 0.05, 1e-4, -1.0, 1.302_176_173_6e-4),
            (1e4, 0.01, 0.05, 1e-4, 1.0, 2.312_650_986_1e-4),
            (2e5, 1e-3, 3e-3, 0.0, 0.0, 2.200_548_531_8e-5),
            (1e7, 10.0, 1.0, 0.0, 0.0, 7.232_717_646_3e-2),
        ];
        for (sc, tp, rp, vs, facing, expected) in cases {
            let v = hussein(sc, tp, rp, vs, facing);
            assert!((v / expected - 1.0).abs() < 2e-5, "Sc {sc} tau+ {tp}: {v} against {expected}");
        }
    }

    #[test]
    fn hussein_has_its_limits() {
        // With a constant drift w (no inertia) V+(w) = w / (1 - exp(-w Phi)), Phi = ∫ dy/D+,
        // so a floor takes exactly v_s+ more than a ceiling.
        let (sc, rp, vs) = (1e4, 0.05, 2e-4);
        let (up, down, side) =
            (hussein(sc, 0.0, rp, vs, 1.0), hussein(sc, 0.0, rp, vs, -1.0), hussein(sc, 0.0, rp, vs, 0.0));
        assert!(((up - down) / vs - 1.0).abs() < 1e-6, "{up} {down}");
        let phi = 1.0 / side;
        assert!((up / (vs / -(-vs * phi).exp_m1()) - 1.0).abs() < 1e-6);
        // Turbophoresis carries inertial particles: at tau+ = 10 a wall takes about 50 times
        // what diffusion alone gives the same Schmidt number (tau+ = 0), at 3 less.
        let diffusion = hussein(1e7, 0.0, 1.0, 0.0, 0.0);
        let (t3, t10) = (hussein(1e7, 3.0, 1.0, 0.0, 0.0), hussein(1e7, 10.0, 1.0, 0.0, 0.0));
        assert!(t10 > 20.0 * diffusion && t10 > t3 && t3 > diffusion, "{diffusion} {t3} {t10}");
        // The grid's error where the drift varies most: below 1e-5 of the converged value.
        let v = hussein(1e6, 1.0, 0.3, 0.0, 0.0);
        assert!((v / 3.254_683_934_1e-4 - 1.0).abs() < 1e-5, "{v}");
    }

    #[test]
    fn hussein_is_lai_and_nazaroff_s_diffusion_where_inertia_is_small() {
        // A room's 1 um particle at u* = 1 cm/s (tau+ 2e-5): the drift is negligible and the
        // model's eddy viscosity is Lai & Nazaroff's, its layer 100 wall units against 30.
        let air = Air::standard();
        let aero = Aerodynamics::new(1e-6, 1000.0, &air, 9.80665);
        let (u, nu) = (0.01, air.kinematic_viscosity());
        let (sc, rp) = (nu / aero.diffusivity, 0.5e-6 * u / nu);
        let tp = aero.relaxation_time * u * u / nu;
        let wall = hussein(sc, tp, rp, aero.settling_speed / u, 0.0) * u;
        let ln = LaiNazaroff::new(1e-6, 1000.0, &air, 9.80665, u);
        assert!((wall / ln.wall - 1.0).abs() < 0.05, "{wall} {}", ln.wall);
    }

    #[test]
    fn hussein_in_a_duct_falls_below_wood_where_inertia_starts_to_count() {
        // A duct's vertical wall at u* = 0.3 m/s, unit density (docs/tracker.md quotes these):
        // as other Eulerian turbophoresis models on Gaussian-statistics profiles, far below
        // Wood in the diffusion-impaction regime, near it on the inertia-moderated plateau.
        let air = Air::standard();
        let (u, nu) = (0.3, air.kinematic_viscosity());
        let mut ratios = Vec::new();
        for tp in [0.5, 2.0, 30.0] {
            let d = diameter_for_tau_plus(tp, 1000.0, &air, u).unwrap();
            let sc = schmidt(d, &air);
            let v = hussein(sc, tp, 0.5 * d * u / nu, 0.0, 0.0);
            ratios.push(v / wood(tp, sc));
            println!("tau+ {tp}: d {:.2} um, V+ {v:.3e}, Wood {:.3e}", d * 1e6, wood(tp, sc));
        }
        assert!(ratios[0] < 0.2 && ratios[1] < 0.1, "{ratios:?}");
        assert!(ratios[2] > 0.5 && ratios[2] < 2.0, "{ratios:?}");
    }

    #[test]
    fn channel_correlations_have_their_regimes() {
        assert!((wood(0.0, 1000.0) - 0.057 * 1e-2).abs() < 1e-15);
        assert!((wood(10.0, 1e6) - (0.057e-4 + 0.045)).abs() < 1e-12);
        assert_eq!(wood(100.0, 1e6), 0.13);
        assert_eq!(papavergos_hedley(100.0, 1e6), 0.18);
        assert!((papavergos_hedley(10.0, 1e6) - 0.035).abs() < 1e-15);
        assert!((papavergos_hedley(0.1, 1000.0) - 0.065e-2).abs() < 1e-15);
    }

    #[test]
    fn tau_plus_inverts() {
        let air = Air::standard();
        let d = diameter_for_tau_plus(10.0, 1000.0, &air, 0.3).unwrap();
        let tau = Aerodynamics::new(d, 1000.0, &air, 0.0).relaxation_time;
        let tp = tau * 0.09 / air.kinematic_viscosity();
        assert!((tp / 10.0 - 1.0).abs() < 1e-9, "{tp}");
        // tau+ = 10 at u* = 1e-4 m/s would take a particle larger than 1 cm.
        assert_eq!(diameter_for_tau_plus(10.0, 1000.0, &air, 1e-4), None);
    }

    #[test]
    fn settling_diffusion_flux_has_its_limits() {
        // Pure diffusion: sqrt(D / (pi t)); pure settling at long times: v_s.
        assert!((settling_diffusion_flux(0.0, 1e-9, 10.0) - (1e-9 / (PI * 10.0)).sqrt()).abs() < 1e-18);
        assert!((settling_diffusion_flux(1e-3, 1e-12, 100.0) - 1e-3).abs() < 1e-9);
    }
}
