//! A deposition wall function: deposition where the near-wall layer is not resolved.
//!
//! A host CFD code meshed with wall functions (first cell at `y+` 30-50, as nearly all
//! building and duct CFD is meshed) does not resolve the viscous sublayer through which
//! particles reach a wall, and depo's own resolved near-wall model misses the
//! diffusion-impaction regime (`tau+` 0.3-3, docs/validation.md). What engineering practice
//! does there is what this module does: the transfer across the near-wall layer is taken from
//! a validated correlation, the bulk transport from the simulation.
//!
//! ## The deposition probability
//! A particle whose centre lies within `y_w` of a wall (the *layer*: a wall-function mesh's
//! wall cell) deposits at a constant rate `k` while it is there. The layer then deposits a
//! flux `J = k ∫_0^y_w C(y) dy = k y_w C_w`, with `C_w` the layer's mean concentration. A
//! correlation gives `J = v_d C` against a reference concentration `C`: the bulk (mean)
//! concentration of a channel for Wood (1981) and Papavergos & Hedley (1984), the well-mixed
//! core's for Lai & Nazaroff (2000). So
//!
//! ```text
//! k = v_d / y_w,     P(dt) = 1 - exp(-v_d dt / y_w)
//! ```
//!
//! the second the chance that a particle in the layer throughout a step `dt` deposits within
//! it (the Poisson process at rate `k`, exact for any `dt`; its first order `v_d dt / y_w`
//! would exceed 1 for long steps). The flux is then `v_d C_w`: the correlation's wherever
//! the layer's concentration is the reference one. The simulated bulk transport must keep it
//! so: tracers are uniform up to a reflecting wall under the well-mixed dispersion model (the
//! wall reflects in this mode, so that nothing deposits twice), and inertial particles keep
//! their bulk concentration in the layer to the extent the transport does; depo's channel
//! study prints `C_w / C` beside each `V+`.
//!
//! ## What arrives at a wall with a wall law
//! Where the surface has a Brach & Dunn law, the correlation says that a particle arrives,
//! not how; the law then decides between rebound and capture with the velocity the particle
//! has in the layer, its wall-normal component turned towards the wall (a free flight from
//! the layer to the wall). In depo's tracker that velocity carries the particle's thermal
//! (Brownian) velocity, which dominates in the diffusion regime, and its drag-relaxed
//! velocity with the fluid's fluctuation and settling, which dominates in the inertial one.
//! The deposited flux is then `v_d C` times the law's capture share of the arrivals.
//!
//! ## References
//! - Wood, N. B. (1981), *A simple method for the calculation of turbulent deposition to
//!   smooth and rough surfaces*, J. Aerosol Sci. 12:275-290.
//! - Papavergos, P. G. & Hedley, A. B. (1984), *Particle deposition behaviour from turbulent
//!   flows*, Chem. Eng. Res. Des. 62:275-295.
//! - Lai, A. C. K. & Nazaroff, W. W. (2000), *Modeling indoor particle deposition from
//!   turbulent flow onto smooth surfaces*, J. Aerosol Sci. 31:463-476.

use crate::model::air::{Aerodynamics, Air};
use crate::model::geometry::Orientation;
use crate::model::walls::Correlation;
use crate::physics::correlations::{hussein, papavergos_hedley, wood, LaiNazaroff};

/// The deposition velocity (m/s) that `correlation` gives onto a smooth surface facing
/// `orientation`, for a particle `aero` (settling speed under the scene's gravity) in `air`
/// with friction velocity `u*` (m/s).
#[must_use]
pub fn deposition_velocity(
    correlation: Correlation,
    aero: &Aerodynamics,
    air: &Air,
    friction_velocity: f64,
    orientation: Orientation,
) -> f64 {
    let nu = air.kinematic_viscosity();
    let schmidt = nu / aero.diffusivity;
    let tau_plus = aero.relaxation_time * friction_velocity * friction_velocity / nu;
    match correlation {
        Correlation::Wood => wood(tau_plus, schmidt) * friction_velocity,
        Correlation::PapavergosHedley => papavergos_hedley(tau_plus, schmidt) * friction_velocity,
        Correlation::LaiNazaroff => {
            let r_plus = 0.5 * aero.diameter * friction_velocity / nu;
            let integral = crate::physics::correlations::lai_nazaroff_integral(schmidt, r_plus);
            let ln = LaiNazaroff::from_integral(integral, aero.settling_speed, friction_velocity);
            match orientation {
                Orientation::Floor => ln.floor,
                Orientation::Ceiling => ln.ceiling,
                Orientation::Wall => ln.wall,
            }
        }
        Correlation::Hussein => {
            let r_plus = 0.5 * aero.diameter * friction_velocity / nu;
            let facing = match orientation {
                Orientation::Floor => 1.0,
                Orientation::Wall => 0.0,
                Orientation::Ceiling => -1.0,
            };
            hussein(schmidt, tau_plus, r_plus, aero.settling_speed / friction_velocity, facing) * friction_velocity
        }
    }
}

/// [`deposition_velocity`], kept per thread for Hussein et al.'s correlation, whose velocity
/// is an integral across the layer (about 0.8 ms, docs/performance-log.md): a run's chunks
/// of particles of one size, and the walls of one orientation, then integrate it once per
/// thread rather than once per wall and chunk. The key is the bits of every input the
/// velocity reads (correlation, orientation, the particle's diameter, diffusivity,
/// relaxation time and settling speed, the gas's density and viscosity, `u*`), so a hit
/// returns what the integral would; up to [`VELOCITY_CACHE_SIZE`] inputs, then it starts
/// again empty. The other correlations are computed each time (they cost less than a lookup).
#[must_use]
pub fn deposition_velocity_cached(
    correlation: Correlation,
    aero: &Aerodynamics,
    air: &Air,
    friction_velocity: f64,
    orientation: Orientation,
) -> f64 {
    if correlation != Correlation::Hussein {
        return deposition_velocity(correlation, aero, air, friction_velocity, orientation);
    }
    let key = [
        correlation as u64,
        orientation as u64,
        aero.diameter.to_bits(),
        aero.diffusivity.to_bits(),
        aero.relaxation_time.to_bits(),
        aero.settling_speed.to_bits(),
        air.density.to_bits(),
        air.viscosity.to_bits(),
        friction_velocity.to_bits(),
    ];
    VELOCITIES.with(|cache| {
        let mut cache = cache.borrow_mut();
        if let Some(&v) = cache.get(&key) {
            return v;
        }
        if cache.len() >= VELOCITY_CACHE_SIZE {
            cache.clear();
        }
        let v = deposition_velocity(correlation, aero, air, friction_velocity, orientation);
        cache.insert(key, v);
        v
    })
}

/// The most inputs [`deposition_velocity_cached`] keeps per thread (about 100 bytes each).
pub const VELOCITY_CACHE_SIZE: usize = 1 << 16;

thread_local! {
    static VELOCITIES: std::cell::RefCell<std::collections::HashMap<[u64; 9], f64>> =
        std::cell::RefCell::new(std::collections::HashMap::new());
}

/// The chance that a particle in a near-wall layer of thickness `layer` (m) throughout a step
/// of `dt` (s) deposits within it, for deposition velocity `v_d` (m/s):
/// `1 - exp(-v_d dt / layer)` (module docs). 0 for `v_d = 0`, below 1 for any finite step.
#[inline]
#[must_use]
pub fn deposition_probability(deposition_velocity: f64, layer: f64, dt: f64) -> f64 {
    -(-deposition_velocity * dt / layer).exp_m1()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::walls::WallFunction;

    #[test]
    fn the_probability_is_the_poisson_chance_of_the_layer_s_rate() {
        // v_d = 1 mm/s over a 5 mm layer: k = 0.2 /s; over 0.1 s, 1 - e^-0.02.
        let p = deposition_probability(1e-3, 5e-3, 0.1);
        assert!((p - 0.019_801_326_693_244_71).abs() < 1e-15, "{p}");
        // Small k dt: k dt; long steps: towards 1, never above.
        assert!((deposition_probability(1e-9, 1e-2, 1e-3) / 1e-10 - 1.0).abs() < 1e-9);
        assert_eq!(deposition_probability(0.0, 1e-2, 1.0), 0.0);
        let long = deposition_probability(1.0, 1e-3, 1e3);
        assert!(long <= 1.0 && long > 0.999_999);
        // Two half steps deposit as one step does: 1 - (1 - p/2-step)^2.
        let half = deposition_probability(2e-3, 4e-3, 0.05);
        assert!((1.0 - (1.0 - half).powi(2) - deposition_probability(2e-3, 4e-3, 0.1)).abs() < 1e-15);
    }

    #[test]
    fn the_velocity_is_the_correlation_s_on_each_surface() {
        let air = Air::standard();
        let (u_star, nu) = (0.3, air.kinematic_viscosity());
        // A 5 um particle of 1000 kg/m^3, no gravity (a channel).
        let aero = Aerodynamics::new(5e-6, 1000.0, &air, 0.0);
        let tau_plus = aero.relaxation_time * u_star * u_star / nu;
        let sc = nu / aero.diffusivity;
        for orientation in [Orientation::Floor, Orientation::Wall, Orientation::Ceiling] {
            let v = deposition_velocity(Correlation::Wood, &aero, &air, u_star, orientation);
            let by_hand = (0.057 * sc.powf(-2.0 / 3.0) + 4.5e-4 * tau_plus * tau_plus).min(0.13) * u_star;
            assert!((v / by_hand - 1.0).abs() < 1e-12, "{v} {by_hand}");
            let v = deposition_velocity(Correlation::PapavergosHedley, &aero, &air, u_star, orientation);
            assert!((v / (3.5e-4 * tau_plus * tau_plus * u_star) - 1.0).abs() < 1e-12);
        }
        // Lai & Nazaroff with settling: floor above wall above ceiling, floor - ceiling = v_s.
        let settling = Aerodynamics::new(5e-6, 1000.0, &air, 9.80665);
        let ln = |o| deposition_velocity(Correlation::LaiNazaroff, &settling, &air, 0.01, o);
        let (floor, wall, ceiling) = (ln(Orientation::Floor), ln(Orientation::Wall), ln(Orientation::Ceiling));
        assert!(floor > wall && wall > ceiling, "{floor} {wall} {ceiling}");
        assert!((floor - ceiling - settling.settling_speed).abs() < 1e-12 * floor);
        let direct = LaiNazaroff::new(5e-6, 1000.0, &air, 9.80665, 0.01);
        assert!((wall / direct.wall - 1.0).abs() < 1e-12 && (floor / direct.floor - 1.0).abs() < 1e-12);
    }

    #[test]
    fn hussein_s_velocity_is_its_v_plus_by_orientation() {
        let air = Air::standard();
        let (u_star, nu) = (0.3, air.kinematic_viscosity());
        let aero = Aerodynamics::new(5e-6, 1000.0, &air, 9.80665);
        let (sc, tp) = (nu / aero.diffusivity, aero.relaxation_time * u_star * u_star / nu);
        let (rp, vs) = (2.5e-6 * u_star / nu, aero.settling_speed / u_star);
        for (orientation, facing) in [(Orientation::Floor, 1.0), (Orientation::Wall, 0.0), (Orientation::Ceiling, -1.0)]
        {
            let v = deposition_velocity(Correlation::Hussein, &aero, &air, u_star, orientation);
            let direct = crate::physics::correlations::hussein(sc, tp, rp, vs, facing) * u_star;
            assert!((v / direct - 1.0).abs() < 1e-12, "{orientation:?}: {v} {direct}");
        }
        // A wall function picks it for the vertical walls only, where it is named for them.
        let wf = WallFunction { vertical: Some(Correlation::Hussein), ..WallFunction::new(Correlation::LaiNazaroff) };
        assert_eq!(wf.correlation_for(Orientation::Wall), Correlation::Hussein);
        assert_eq!(wf.correlation_for(Orientation::Floor), Correlation::LaiNazaroff);
        assert_eq!(WallFunction::new(Correlation::Wood).correlation_for(Orientation::Wall), Correlation::Wood);
        assert_eq!(Correlation::Hussein.name(), "hussein");
    }

    #[test]
    fn the_cached_velocity_is_the_velocity_for_every_correlation_and_input() {
        let air = Air::standard();
        let correlations =
            [Correlation::Wood, Correlation::PapavergosHedley, Correlation::LaiNazaroff, Correlation::Hussein];
        // Twice over: the second pass answers Hussein et al.'s from the cache.
        for _ in 0..2 {
            for (d, rho, g, u) in [
                (5e-6, 1000.0, 9.80665, 0.3),
                (5e-6, 2500.0, 9.80665, 0.3),
                (5e-6, 1000.0, 0.0, 0.3),
                (2e-6, 1000.0, 9.80665, 0.01),
            ] {
                let aero = Aerodynamics::new(d, rho, &air, g);
                for c in correlations {
                    for o in [Orientation::Floor, Orientation::Wall, Orientation::Ceiling] {
                        let cached = deposition_velocity_cached(c, &aero, &air, u, o);
                        let direct = deposition_velocity(c, &aero, &air, u, o);
                        assert_eq!(cached.to_bits(), direct.to_bits(), "{c:?} {o:?} d {d} rho {rho} g {g} u* {u}");
                    }
                }
            }
        }
        // Another gas is another key.
        let thin = Air { density: 0.6, ..air };
        let aero = Aerodynamics::new(5e-6, 1000.0, &thin, 9.80665);
        let v = deposition_velocity_cached(Correlation::Hussein, &aero, &thin, 0.3, Orientation::Wall);
        assert_eq!(
            v.to_bits(),
            deposition_velocity(Correlation::Hussein, &aero, &thin, 0.3, Orientation::Wall).to_bits()
        );
    }

    #[test]
    fn the_layer_is_in_wall_units() {
        let air = Air::standard();
        let w = WallFunction::new(Correlation::Wood);
        assert!((w.layer(&air, 0.3) * 0.3 / air.kinematic_viscosity() - 30.0).abs() < 1e-12);
        assert_eq!(Correlation::PapavergosHedley.name(), "papavergos-hedley");
    }
}
