//! Structure-of-arrays batches of impacts, their per-particle outcomes, and tallies.
//!
//! A batch borrows the host's arrays: three velocity components, optionally three spin
//! components with the radii, and either one wall normal for the whole batch or one per
//! particle. Nothing is copied; the kernel updates velocity and spin in place and writes one
//! [`Outcome`] per particle. Lengths and the batch normal are checked when the batch is made;
//! per-particle values are checked by the kernel, which flags bad particles
//! [`Outcome::INVALID`] and leaves them untouched.

use core::fmt;

use crate::energy::EnergyLoss;
use crate::real::Real;

/// What happened to one particle, as a byte (the values of the C API's `DEPO_*` codes).
#[repr(transparent)]
#[derive(Clone, Copy, PartialEq, Eq, Hash, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct Outcome(pub u8);

impl Outcome {
    /// It hit the wall and rebounded: velocity (and spin) updated.
    pub const REBOUND: Self = Self(0);
    /// It hit the wall and was captured: deposited (velocity and spin zero) or kept on the
    /// wall with zero normal velocity, per [`crate::CaptureMode`].
    pub const CAPTURED: Self = Self(1);
    /// Not an impact (`vn >= 0`): untouched.
    pub const SKIPPED: Self = Self(2);
    /// Non-finite velocity, spin or per-particle capture velocity, a radius that is not finite
    /// or below `1 / Real::BIG` (1e-150 m in `f64`, 1e-18 m in `f32`: the spin change goes
    /// as `1 / r`), or a per-particle normal that is not finite or not of unit length within
    /// 1e-4: untouched.
    pub const INVALID: Self = Self(3);

    /// A lower-case name for reports.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::REBOUND => "rebound",
            Self::CAPTURED => "captured",
            Self::SKIPPED => "skipped",
            Self::INVALID => "invalid",
            _ => "unknown",
        }
    }
}

impl fmt::Debug for Outcome {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "Outcome::{}", self.name())
    }
}

/// Squared-length bounds of a normal "of unit length within 1e-4": `(1 -+ 1e-4)^2`.
pub(crate) const UNIT_SQUARED_MIN: f64 = (1.0 - 1e-4) * (1.0 - 1e-4);
pub(crate) const UNIT_SQUARED_MAX: f64 = (1.0 + 1e-4) * (1.0 + 1e-4);

/// Wall normals of a batch, unit vectors pointing from the wall into the fluid.
#[derive(Clone, Copy, Debug)]
pub enum Normals<'a, T> {
    /// One normal for every particle (a single wall patch).
    Uniform([T; 3]),
    /// One normal per particle, as three component arrays.
    PerParticle([&'a [T]; 3]),
}

/// Spin arrays (rad/s, updated in place) with the radii they need (m).
#[derive(Debug)]
pub(crate) struct SpinArrays<'a, T> {
    pub(crate) w: [&'a mut [T]; 3],
    pub(crate) radius: &'a [T],
}

/// A batch of wall contacts in structure-of-arrays layout, borrowed from the caller.
#[derive(Debug)]
pub struct Impacts<'a, T> {
    pub(crate) velocity: [&'a mut [T]; 3],
    pub(crate) spin: Option<SpinArrays<'a, T>>,
    pub(crate) normals: Normals<'a, T>,
    /// Per-particle capture velocity (m/s), replacing the law's `vc` (see [`crate::size`]).
    pub(crate) capture_velocity: Option<&'a [T]>,
    pub(crate) outcome: &'a mut [Outcome],
}

/// A batch whose arrays do not fit together.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum BatchError {
    /// An array's length differs from the velocity arrays'.
    LengthMismatch { field: &'static str, expected: usize, found: usize },
    /// The batch normal is not finite or not of unit length within 1e-4.
    NormalNotUnit { length: f64 },
}

impl fmt::Display for BatchError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::LengthMismatch { field, expected, found } => {
                write!(f, "batch array {field} has {found} elements, expected {expected}")
            }
            Self::NormalNotUnit { length } => {
                write!(f, "batch normal has length {length}, not 1 within 1e-4")
            }
        }
    }
}

impl std::error::Error for BatchError {}

fn check_len(field: &'static str, expected: usize, found: usize) -> Result<(), BatchError> {
    if expected == found {
        Ok(())
    } else {
        Err(BatchError::LengthMismatch { field, expected, found })
    }
}

impl<'a, T: Real> Impacts<'a, T> {
    /// Rotates the velocity and spin components left by `mid` (a cyclic rotation of the
    /// axes, which keeps cross products): after it, component `k` is the old `(k + mid) % 3`.
    pub(crate) fn rotate_axes(&mut self, mid: usize) {
        self.velocity.rotate_left(mid);
        if let Some(spin) = &mut self.spin {
            spin.w.rotate_left(mid);
        }
    }

    /// A batch without spin. All arrays must have the same length; a uniform normal must be
    /// of unit length within 1e-4.
    pub fn new(
        velocity: [&'a mut [T]; 3],
        normals: Normals<'a, T>,
        outcome: &'a mut [Outcome],
    ) -> Result<Self, BatchError> {
        let n = velocity[0].len();
        check_len("vy", n, velocity[1].len())?;
        check_len("vz", n, velocity[2].len())?;
        check_len("outcome", n, outcome.len())?;
        match normals {
            Normals::Uniform(normal) => {
                let length_sq = normal.iter().map(|c| c.to_f64() * c.to_f64()).sum::<f64>();
                if !(UNIT_SQUARED_MIN..=UNIT_SQUARED_MAX).contains(&length_sq) {
                    return Err(BatchError::NormalNotUnit { length: length_sq.sqrt() });
                }
            }
            Normals::PerParticle([nx, ny, nz]) => {
                check_len("nx", n, nx.len())?;
                check_len("ny", n, ny.len())?;
                check_len("nz", n, nz.len())?;
            }
        }
        Ok(Self { velocity, spin: None, normals, capture_velocity: None, outcome })
    }

    /// Tracks spin too: `spin` in rad/s is updated in place, `radius` (m) is read.
    pub fn with_spin(mut self, spin: [&'a mut [T]; 3], radius: &'a [T]) -> Result<Self, BatchError> {
        let n = self.len();
        check_len("wx", n, spin[0].len())?;
        check_len("wy", n, spin[1].len())?;
        check_len("wz", n, spin[2].len())?;
        check_len("radius", n, radius.len())?;
        self.spin = Some(SpinArrays { w: spin, radius });
        Ok(self)
    }

    /// Gives each particle its own capture velocity `vc` (m/s), in place of the law's: a
    /// polydisperse cloud, with `vc` from each particle's diameter ([`crate::SizeDependence`]).
    /// A non-finite value flags that particle invalid.
    pub fn with_capture_velocity(mut self, capture_velocity: &'a [T]) -> Result<Self, BatchError> {
        check_len("capture_velocity", self.len(), capture_velocity.len())?;
        self.capture_velocity = Some(capture_velocity);
        Ok(self)
    }

    /// Number of particles.
    #[must_use]
    pub fn len(&self) -> usize {
        self.outcome.len()
    }

    /// True for an empty batch.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.outcome.is_empty()
    }

    /// Whether spin is tracked.
    #[must_use]
    pub fn tracks_spin(&self) -> bool {
        self.spin.is_some()
    }

    /// Splits into particles `[0, mid)` and `[mid, len)`, for the threads.
    pub(crate) fn split_at(self, mid: usize) -> (Self, Self) {
        let [vx, vy, vz] = self.velocity;
        let (vx0, vx1) = vx.split_at_mut(mid);
        let (vy0, vy1) = vy.split_at_mut(mid);
        let (vz0, vz1) = vz.split_at_mut(mid);
        let (spin0, spin1) = match self.spin {
            None => (None, None),
            Some(SpinArrays { w: [wx, wy, wz], radius }) => {
                let (wx0, wx1) = wx.split_at_mut(mid);
                let (wy0, wy1) = wy.split_at_mut(mid);
                let (wz0, wz1) = wz.split_at_mut(mid);
                let (r0, r1) = radius.split_at(mid);
                (
                    Some(SpinArrays { w: [wx0, wy0, wz0], radius: r0 }),
                    Some(SpinArrays { w: [wx1, wy1, wz1], radius: r1 }),
                )
            }
        };
        let (normals0, normals1) = match self.normals {
            Normals::Uniform(n) => (Normals::Uniform(n), Normals::Uniform(n)),
            Normals::PerParticle([nx, ny, nz]) => {
                let (nx0, nx1) = nx.split_at(mid);
                let (ny0, ny1) = ny.split_at(mid);
                let (nz0, nz1) = nz.split_at(mid);
                (Normals::PerParticle([nx0, ny0, nz0]), Normals::PerParticle([nx1, ny1, nz1]))
            }
        };
        let (vc0, vc1) = match self.capture_velocity {
            None => (None, None),
            Some(vc) => {
                let (a, b) = vc.split_at(mid);
                (Some(a), Some(b))
            }
        };
        let (o0, o1) = self.outcome.split_at_mut(mid);
        (
            Self { velocity: [vx0, vy0, vz0], spin: spin0, normals: normals0, capture_velocity: vc0, outcome: o0 },
            Self { velocity: [vx1, vy1, vz1], spin: spin1, normals: normals1, capture_velocity: vc1, outcome: o1 },
        )
    }
}

/// Counts of each outcome and the energy lost by each mechanism over one or more batches.
///
/// Energies are sums over impacts of the loss per unit particle mass (J/kg, see
/// [`crate::energy`]): for a batch of equal particles multiply by the particle mass.
/// Tallies add with `+=`, e.g. across calls or MPI ranks.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Tally {
    pub rebound: u64,
    pub captured: u64,
    pub skipped: u64,
    pub invalid: u64,
    pub energy: EnergyLoss<f64>,
}

impl Tally {
    /// Particles counted, whatever their outcome.
    #[must_use]
    pub fn particles(&self) -> u64 {
        self.rebound + self.captured + self.skipped + self.invalid
    }
}

impl core::ops::AddAssign for Tally {
    fn add_assign(&mut self, o: Self) {
        self.rebound += o.rebound;
        self.captured += o.captured;
        self.skipped += o.skipped;
        self.invalid += o.invalid;
        self.energy += o.energy;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn constructor_checks_lengths_and_the_batch_normal() {
        let (mut a, mut b, mut c) = (vec![0.0f64; 3], vec![0.0; 3], vec![0.0; 2]);
        let mut out = vec![Outcome::default(); 3];
        let err = Impacts::new([&mut a, &mut b, &mut c], Normals::Uniform([0.0, 1.0, 0.0]), &mut out).unwrap_err();
        assert_eq!(err, BatchError::LengthMismatch { field: "vz", expected: 3, found: 2 });
        let mut c = vec![0.0; 3];
        let err = Impacts::new([&mut a, &mut b, &mut c], Normals::Uniform([0.0, 1.001, 0.0]), &mut out).unwrap_err();
        assert!(matches!(err, BatchError::NormalNotUnit { .. }));
        assert!(Impacts::new([&mut a, &mut b, &mut c], Normals::Uniform([0.0, f64::NAN, 0.0]), &mut out).is_err());
        let batch = Impacts::new([&mut a, &mut b, &mut c], Normals::Uniform([0.0, 1.00009, 0.0]), &mut out).unwrap();
        let (mut wx, mut wy, mut wz) = (vec![0.0; 3], vec![0.0; 3], vec![0.0; 3]);
        let radius = vec![1.0; 4];
        let err = batch.with_spin([&mut wx, &mut wy, &mut wz], &radius).unwrap_err();
        assert_eq!(err.to_string(), "batch array radius has 4 elements, expected 3");
    }

    #[test]
    fn outcome_codes_are_the_c_values() {
        assert_eq!([Outcome::REBOUND.0, Outcome::CAPTURED.0, Outcome::SKIPPED.0, Outcome::INVALID.0], [0, 1, 2, 3]);
        assert_eq!(format!("{:?}", Outcome::CAPTURED), "Outcome::captured");
    }
}
