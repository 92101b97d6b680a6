//! [`WallLaw`]: validated constants plus the per-scene choices, with the scalar and batch
//! entry points.

use glam::DVec3;

use crate::batch::{Impacts, Tally};
use crate::impact::{resolve, CaptureMode, ImpactResult};
use crate::kernel::{self, Setup};
use crate::law::{self, Coefficients, LawConstants};
use crate::params::{LawParams, ParamError};
use crate::power::{with_powers, Exponents, PowerMode};
use crate::presets::{self, UnknownPreset};
use crate::real::Real;

/// The Brach & Dunn wall law with validated constants, ready to apply.
///
/// ```
/// use depo_wall_model::{WallLaw, Impacts, Normals, Outcome, Tally};
///
/// let law = WallLaw::preset("li1997-sio2").unwrap();
/// let e = law.coefficients(1.0).overall; // e at |vn| = 1 m/s
/// assert!((e - 0.7319907).abs() < 1e-6);
///
/// // Two particles hitting the floor (normal +z), in the host's own arrays.
/// let (mut vx, mut vy, mut vz) = (vec![0.1, 0.0], vec![0.0, 0.0], vec![-1.0, -0.01]);
/// let mut outcome = vec![Outcome::default(); 2];
/// let batch = Impacts::new([&mut vx, &mut vy, &mut vz], Normals::Uniform([0.0, 0.0, 1.0]), &mut outcome).unwrap();
/// let mut tally = Tally::default();
/// law.apply(batch, Some(&mut tally));
/// assert_eq!(outcome, [Outcome::REBOUND, Outcome::CAPTURED]);
/// assert!((vz[0] - e).abs() < 1e-12 && vz[1] == 0.0);
/// assert_eq!((tally.rebound, tally.captured), (1, 1));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WallLaw {
    params: LawParams,
    capture: CaptureMode,
    power: PowerMode,
    constants: LawConstants<f64>,
}

impl WallLaw {
    /// A law with these constants; the error names the first field out of range.
    pub fn new(params: LawParams) -> Result<Self, ParamError> {
        params.validate()?;
        Ok(Self {
            params,
            capture: CaptureMode::default(),
            power: PowerMode::default(),
            constants: LawConstants::new(&params),
        })
    }

    /// The law of a Table 1 row by id (see [`crate::presets`]); friction `mu = 0`.
    pub fn preset(id: &str) -> Result<Self, UnknownPreset> {
        let preset = presets::preset(id).ok_or_else(|| UnknownPreset(id.to_string()))?;
        Ok(Self::new(preset.params).expect("presets are valid"))
    }

    /// Chooses what happens to captured particles (default [`CaptureMode::Deposit`]).
    #[must_use]
    pub fn with_capture_mode(self, capture: CaptureMode) -> Self {
        Self { capture, ..self }
    }

    /// Chooses how general exponents are evaluated (default [`PowerMode::Fast`]).
    #[must_use]
    pub fn with_power_mode(self, power: PowerMode) -> Self {
        Self { power, ..self }
    }

    /// The constants.
    #[must_use]
    pub fn params(&self) -> &LawParams {
        &self.params
    }

    /// What happens to captured particles.
    #[must_use]
    pub fn capture_mode(&self) -> CaptureMode {
        self.capture
    }

    /// How general exponents are evaluated.
    #[must_use]
    pub fn power_mode(&self) -> PowerMode {
        self.power
    }

    /// Which exponent case the kernels take.
    #[must_use]
    pub fn exponents(&self) -> Exponents {
        Exponents::of(self.params.p, self.params.q)
    }

    /// `R`, `rho`, `e` and capture at normal speed `|vn|` (m/s; the sign of `vn` is ignored).
    /// `vn = 0` is a touching contact, captured when `vc > 0` and otherwise given `e` of the
    /// limit `|vn| -> 0`.
    #[must_use]
    pub fn coefficients(&self, vn: f64) -> Coefficients<f64> {
        let c = &self.constants;
        with_powers!(self.exponents(), self.power, (c.p, c.q), |p, q| law::coefficients(c, p, q, vn.abs()))
    }

    /// Material restitution `R(|vn|)`, Eq. (8).
    #[must_use]
    pub fn restitution(&self, vn: f64) -> f64 {
        self.coefficients(vn).restitution
    }

    /// Adhesion coefficient `rho(|vn|)`, Eq. (9), with the capture rule (1 when captured).
    #[must_use]
    pub fn adhesion(&self, vn: f64) -> f64 {
        self.coefficients(vn).adhesion
    }

    /// Overall restitution `e(|vn|) = R (1 - rho)`, Eq. (2), with the capture rule.
    #[must_use]
    pub fn overall_restitution(&self, vn: f64) -> f64 {
        self.coefficients(vn).overall
    }

    /// One impact in 3-D: velocity `v` (m/s) against a wall with unit normal `normal` (into the
    /// fluid), with spin `(w, radius)` (rad/s, m) when the scene tracks it. The same code as the
    /// batch kernel. For `vn >= 0` the result is meaningless (not an impact): check
    /// `normal_velocity < 0` first, as the batch kernel does. Its coefficients are
    /// [`WallLaw::coefficients`]' at `|vn|`, bit for bit.
    #[must_use]
    pub fn impact(&self, v: DVec3, spin: Option<(DVec3, f64)>, normal: DVec3) -> ImpactResult<f64> {
        let c = &self.constants;
        let friction = c.mu > 0.0;
        let (v, n) = (v.to_array(), normal.to_array());
        with_powers!(self.exponents(), self.power, (c.p, c.q), |p, q| match (spin, friction) {
            (Some((w, r)), true) => resolve::<f64, _, _, true, true>(c, p, q, self.capture, v, w.to_array(), r, n),
            (Some((w, r)), false) => resolve::<f64, _, _, true, false>(c, p, q, self.capture, v, w.to_array(), r, n),
            (None, true) => resolve::<f64, _, _, false, true>(c, p, q, self.capture, v, [0.0; 3], 1.0, n),
            (None, false) => resolve::<f64, _, _, false, false>(c, p, q, self.capture, v, [0.0; 3], 1.0, n),
        })
    }

    /// [`WallLaw::impact`] for a particle with its own capture velocity `vc` (m/s), e.g. from its
    /// diameter with [`crate::SizeDependence`]; the other constants are the law's. Particle
    /// trackers that call the law once per wall contact use this for polydisperse clouds.
    #[must_use]
    pub fn impact_with_capture_velocity(&self, v: DVec3, normal: DVec3, vc: f64) -> ImpactResult<f64> {
        let c = &self.constants.with_capture_velocity(vc);
        let (v, n) = (v.to_array(), normal.to_array());
        with_powers!(self.exponents(), self.power, (c.p, c.q), |p, q| if c.mu > 0.0 {
            resolve::<f64, _, _, false, true>(c, p, q, self.capture, v, [0.0; 3], 1.0, n)
        } else {
            resolve::<f64, _, _, false, false>(c, p, q, self.capture, v, [0.0; 3], 1.0, n)
        })
    }

    /// Applies the law to every particle of a batch, in place, and adds its counts and energy
    /// losses to `tally` when given.
    ///
    /// Large batches run on the current rayon thread pool: to cap the threads (a host solver
    /// with its own OpenMP or MPI layout), call this inside `pool.install(..)` of a pool with
    /// the threads you allow. Batches below 65536 particles run on the calling thread.
    pub fn apply<T: Real>(&self, batch: Impacts<'_, T>, tally: Option<&mut Tally>) {
        self.apply_on(batch, tally, true);
    }

    /// [`WallLaw::apply`] entirely on the calling thread, whatever the batch size: for a host
    /// that runs its own threads (OpenMP, one MPI rank per core) and wants depo never to start
    /// or wake one. Results and tally are those of [`WallLaw::apply`], bit for bit.
    pub fn apply_on_calling_thread<T: Real>(&self, batch: Impacts<'_, T>, tally: Option<&mut Tally>) {
        self.apply_on(batch, tally, false);
    }

    fn apply_on<T: Real>(&self, batch: Impacts<'_, T>, tally: Option<&mut Tally>, parallel: bool) {
        let setup = Setup {
            constants: LawConstants::<T>::new(&self.params),
            exponents: self.exponents(),
            power: self.power,
            capture: self.capture,
        };
        let want_tally = tally.is_some();
        let result = kernel::apply(&setup, batch, want_tally, parallel);
        if let Some(tally) = tally {
            *tally += result;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn own_capture_velocity_matches_the_law_at_its_own_vc_and_moves_the_threshold() {
        let law = WallLaw::preset("dunn1995-stainless").unwrap().with_capture_mode(CaptureMode::Deposit);
        let (v, n) = (DVec3::new(0.3, 0.0, -0.8), DVec3::Z);
        let own = law.impact_with_capture_velocity(v, n, law.params().vc);
        assert_eq!(own, law.impact(v, None, n));
        assert!(own.velocity[2] > 0.0, "0.8 m/s is above this law's vc and rebounds");
        let sticky = law.impact_with_capture_velocity(v, n, 1.0);
        assert_eq!(sticky.velocity, [0.0; 3], "below a 1 m/s capture velocity the particle deposits");
    }

    #[test]
    fn an_impact_s_coefficients_are_the_curve_s_bit_for_bit() {
        for (mu, p, q) in [(0.0, 1.0, 0.5), (0.3, 1.0, 0.5), (0.3, 1.0, 1.0), (0.5, 1.3, 0.7)] {
            let law = WallLaw::new(LawParams {
                p,
                q,
                ..LawParams::symmetric(12.5, 0.065, 0.074, 1.0, 0.5).with_friction(mu)
            })
            .unwrap();
            for speed in [1e-3, 0.074, 0.0741, 0.3, 1.0, 7.5, 1e3] {
                for (tangential, spin) in [(0.0, None), (0.4, None), (0.4, Some((DVec3::new(0.0, 3e3, 0.0), 5e-5)))] {
                    let v = DVec3::new(tangential, -0.2 * tangential, -speed);
                    let res = law.impact(v, spin, DVec3::Z);
                    assert_eq!(res.coefficients, law.coefficients(speed), "mu {mu} p {p} q {q} |vn| {speed}");
                }
            }
        }
    }

    /// Every exponent case, the paper's and the mixed ones, evaluated with the fast power
    /// agrees with libm's `powf` (the exact mode) to the fast power's tolerance: each case
    /// hands the right exponent to the right formula.
    #[test]
    fn every_exponent_case_agrees_with_libm() {
        let pairs = [(1.0, 1.0), (1.0, 0.5), (0.5, 1.0), (0.5, 0.5), (1.0, 0.7), (1.0, 2.5), (1.3, 0.7), (0.7, 1.0)];
        for (p, q) in pairs {
            let fast = WallLaw::new(LawParams::symmetric(12.5, 0.065, 0.074, p, q)).unwrap();
            let exact = fast.with_power_mode(PowerMode::Exact);
            for speed in [0.08, 0.3, 1.0, 4.0, 20.0] {
                let (got, want) = (fast.coefficients(speed), exact.coefficients(speed));
                for (g, w) in [(got.restitution, want.restitution), (got.adhesion, want.adhesion)] {
                    assert!((g - w).abs() <= 1e-11 * w, "p {p} q {q} |vn| {speed}: {g} vs {w}");
                }
                assert!((got.overall - want.overall).abs() <= 1e-11, "p {p} q {q} |vn| {speed}");
            }
        }
    }
}
