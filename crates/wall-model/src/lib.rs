//! # depo-wall-model
//!
//! The rebound/capture law of Brach & Dunn (1998) for Lagrangian particles hitting a wall,
//! for one impact or for millions at a time on a host solver's own arrays.
//!
//! How the parts fit, from the physics up:
//!
//! - [`params`]: the constants `k1, k2, kappa1, kappa2, p, q, vc, mu` and their validation;
//!   [`presets`]: the paper's Table 1 by id.
//! - [`law`]: material restitution `R` (Eq. 8), adhesion `rho` (Eq. 9), overall restitution
//!   `e = R (1 - rho)` (Eq. 2) and the capture rule, as plain functions of `|vn|`.
//! - [`impact`]: the 3-D oblique impact (Eqs. 3-7): friction, sliding or rolling, spin, and what
//!   happens to a captured particle ([`CaptureMode`]).
//! - [`energy`]: where each impact's energy goes (Eqs. 1, 14).
//! - [`size`]: the capture velocity against particle diameter (Fig. 8), for polydisperse
//!   batches that carry one capture velocity per particle.
//! - [`fit`]: measured `(|vn|, e)` data to the law's constants by nonlinear least squares, with
//!   uncertainties and a warning when `vc` is an extrapolation; [`tilt`]: what a misaligned or
//!   rough surface does to measured restitution (Fig. 6), and rough per-particle normals;
//!   [`contact`]: a time-integrated sphere-wall impact (Hertz, damping, adhesion) that makes
//!   `e(vn)` curves and capture velocities where there is no data; [`theory`]: the capture
//!   velocity in closed form from material properties (JKR after Johnson & Pollock and
//!   Thornton & Ning; a van der Waals well after Dahneke), with where each holds.
//! - [`batch`]: structure-of-arrays batches borrowed from the host, per-particle
//!   [`Outcome`]s and the [`Tally`]; [`kernel`] is the loop over a batch, one monomorphised,
//!   vectorised variant per scene, run across cores with rayon.
//! - [`power`] and [`real`]: the exponents and the two precisions (`f64`, `f32`) the formulas
//!   are written for once.
//!
//! [`WallLaw`] ties them together: a validated law with [`WallLaw::coefficients`] for curves,
//! [`WallLaw::impact`] for one particle and [`WallLaw::apply`] for a batch. All quantities are
//! SI: m/s, rad/s, m, J/kg. The physics contract, with the conventions the paper leaves open,
//! is the project's `docs/MODEL.md`; every choice beyond it is documented where it is made.
//!
//! ## Moving a case over from another CFD code
//!
//! - **OpenFOAM** (`StandardWallInteraction`, `rebound`/`stick`/`escape` with constant `e` and
//!   `mu`): its `e` is a constant normal restitution and its `mu` a tangential restitution
//!   factor (`V_t = (1 - mu) v_t`), not a friction coefficient. A constant `e` with no capture
//!   is this law with `vc <= 0`, `kappa1 -> 0` and `R = e`; depo's `e` instead depends on `|vn|`
//!   and reaches zero at `vc`. OpenFOAM's tangential factor `mu_OF` corresponds to a rolling
//!   or sliding impulse here: a rolling impact without spin keeps `V_t = 5/7 v_t`
//!   (`mu_OF = 2/7`); a sliding one removes `mu (1 + e) |vn|` of tangential speed.
//! - **Fluent** (DPM `reflect` with normal and tangential coefficients of restitution `e_n`,
//!   `e_t`, polynomial in impact angle): `e_n` is `e` here as a function of `|vn|` instead of
//!   angle; `e_t` follows from the impulses (`1 - j/|v_t|`). Fluent's `trap` is capture with
//!   [`CaptureMode::Deposit`] for every impact; depo decides it per impact from `vc`.

pub mod batch;
pub mod contact;
pub mod energy;
pub mod fit;
pub mod impact;
pub mod kernel;
pub mod law;
pub mod params;
pub mod power;
pub mod presets;
pub mod real;
pub mod size;
pub mod theory;
pub mod tilt;
mod wall_law;

pub use batch::{BatchError, Impacts, Normals, Outcome, Tally};
pub use energy::EnergyLoss;
pub use impact::{CaptureMode, ImpactResult};
pub use law::Coefficients;
pub use params::{LawParams, ParamError};
pub use power::{Exponents, PowerMode};
pub use presets::{Preset, UnknownPreset, PRESETS};
pub use real::Real;
pub use size::SizeDependence;
pub use wall_law::WallLaw;
