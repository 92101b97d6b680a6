//! # depo-tracker
//!
//! Lagrangian particle transport in rooms and channels, with the Brach & Dunn wall law of
//! [`depo_wall_model`] at every wall contact, and the deposition statistics that building
//! air-quality and aerosol studies ask for.
//!
//! ## Layers
//!
//! The crate is in five layers, each a folder; a module imports only from its own layer and
//! those below it (`tests/layers.rs` checks it, and that no modules import each other round a
//! cycle):
//!
//! - [`model`]: what is simulated. The domain ([`Geometry`]: a room or a plane channel), the
//!   [`Air`] and one particle in it, the mean [`Flow`] as a scene states it, [`Furnishing`]s,
//!   [`Opening`]s and the potential flow between them, what each surface does
//!   ([`WallBehaviour`], [`WallFunction`]), the [`Injection`], and the [`Scene`] that holds
//!   them, validated once in [`Scene::validate`]; beside the scene, how a run is estimated,
//!   [`RunSettings`] (time step, [`Scheme`], duration, seed, averaging window, near-wall
//!   [`Excursions`]).
//! - [`physics`]: the physics of one particle: turbulence profiles and the dispersion model
//!   tabulated once per run (Gaussian near-wall statistics), the intermittent near-wall model,
//!   the deposition correlations and the wall function on them, random streams.
//! - tracking (internal): one particle through a run: the step, its wall contacts, its
//!   [`Fate`]; near-wall excursions and the wall function's layer; four particles side by side.
//! - [`estimation`]: all particles across cores, reproducibly, and the [`Run`]'s statistics
//!   (mass balance, deposition velocity and loss rate with their standard errors, deposition
//!   maps); the excursions' calibration and allocation; decay fits; the integrators'
//!   convergence.
//! - [`studies`]: the room and channel studies beside their correlations, size
//!   distributions, filtration, the steady state, the variance reduction's efficiency, and
//!   measurements to compare with.
//!
//! A scene, its run settings and an injection go down to the tracking layer through [`run()`]; a study calls
//! [`run()`] per particle size and reads the [`Run`]s it returns. The modules' paths from before
//! the layers (`depo_tracker::scene`, `depo_tracker::flow`, `depo_tracker::studies`, ...) are
//! kept as aliases. docs/ARCHITECTURE.md draws the data flow.
//!
//! SI units throughout; `z` is up in a room and wall-normal in a channel.
//!
//! ```
//! use depo_tracker::{run, Geometry, Injection, RunSettings, Scene, SizeDistribution};
//!
//! // 10 um particles settling in still air onto the floor of a 1 m box, for 10 s.
//! let scene = Scene::new(Geometry::Room { size: [1.0, 1.0, 1.0] });
//! let settings = RunSettings::new(0.01, 10.0);
//! let particles = Injection::new(2000, SizeDistribution::Monodisperse { diameter: 10e-6 }, 1000.0);
//! let result = run(&scene, &settings, &particles).unwrap();
//! let balance = result.balance();
//! assert_eq!(balance.airborne + balance.deposited.iter().sum::<usize>() + balance.escaped, 2000);
//! // Settling at 3 mm/s clears about 3 cm of the 1 m height in 10 s.
//! assert!(balance.deposited[0] > 30 && balance.deposited[0] < 90);
//! ```

pub mod estimation;
pub mod model;
pub mod physics;
pub mod studies;
mod tracking;

// The modules' paths before the layers, kept for code and documents that name them.

/// The gas and one particle in it: [`model::air`].
pub mod air {
    pub use crate::model::air::*;
}
/// Near-wall excursions: [`model::excursions`], calibrated by [`estimation::excursions`].
pub mod excursions {
    pub use crate::model::excursions::*;
}
/// The mean flow ([`model::flow`]), the turbulence profiles ([`physics::profiles`]) and the
/// tabulated dispersion model ([`physics::turbulence`]).
pub mod flow {
    pub use crate::model::flow::*;
    pub use crate::physics::profiles::*;
}
/// The whole setup of a run: [`model::scene`], with [`model::walls`]' behaviours and
/// [`model::error`]'s error.
pub mod scene {
    pub use crate::model::error::*;
    pub use crate::model::scene::*;
    pub use crate::model::settings::*;
    pub use crate::model::walls::WallBehaviour;
}
/// The deposition wall function: its settings ([`model::walls`]) and physics
/// ([`physics::wall_function`]).
pub mod wall_function {
    pub use crate::model::walls::{Correlation, WallFunction};
    pub use crate::physics::wall_function::*;
}
/// Openings ([`model::openings`]) and the potential flow between them
/// ([`model::potential_flow`]).
pub mod openings {
    pub use crate::model::openings::*;
    pub use crate::model::potential_flow::*;
}
pub use estimation::{allocation, convergence, decay, maps, run};
pub use model::{furnishing, geometry};
pub use physics::{correlations, intermittency};
/// Size distributions ([`studies::distribution`]) and their mass through a room
/// ([`studies::mass_balance`]).
pub mod distribution {
    pub use crate::studies::distribution::*;
    pub use crate::studies::mass_balance::*;
}
pub use studies::{efficiency, filtration, measurements, steady};

pub use air::{Aerodynamics, Air};
pub use decay::{log_linear_fit, Comparison, DecayCurve, DecayFit, LogLinear};
pub use excursions::{Excursions, Splitting, Sweeps};
pub use flow::Flow;
pub use furnishing::Furnishing;
pub use geometry::{Geometry, Orientation, Wall};
pub use openings::{Opening, OpeningKind};
pub use run::{binomial_error, delta_error, run, run_more, Balance, Cancel, Estimate, Run};
pub use scene::{Drag, Injection, NearWall, RunSettings, Scene, SceneError, Scheme, SizeDistribution, WallBehaviour};
pub use tracking::{
    Fate, Landed, ParticleTally, Record, WallTally, CONTINUITY_CORRECTION, MAX_CONTACTS, NEAR_FLOOR_SHARE,
};
pub use wall_function::{Correlation, WallFunction};
