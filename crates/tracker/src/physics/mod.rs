//! The physics of one particle in the model's air: the near-wall turbulence profiles, the
//! stochastic dispersion model tabulated once per run (Gaussian near-wall statistics), the
//! intermittent near-wall model, the deposition-velocity correlations and the wall function
//! built on them, and each particle's random streams.
//!
//! May use the model layer ([`crate::model`]); nothing above it.

pub mod correlations;
pub mod intermittency;
pub(crate) mod noise;
pub mod profiles;
pub mod turbulence;
pub mod wall_function;
