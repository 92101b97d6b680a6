//! # depo-tracker
//!
//! Lagrangian particle transport in rooms and channels, with the Brach & Dunn wall law of
//! [`depo_wall_model`] at every wall contact, and the deposition statistics that building
//! air-quality and aerosol studies ask for.
//!
//! How the parts fit:
//!
//! - [`air`]: the gas and one particle in it: slip correction, relaxation time, settling,
//!   Brownian diffusivity, finite-Reynolds drag.
//! - [`geometry`]: a room (six walls) or a plane channel (two walls, periodic along and across).
//! - [`flow`]: mean flow (still, uniform, Poiseuille, Reichardt's turbulent profile) and the
//!   near-wall stochastic dispersion model, tabulated once per run.
//! - [`intermittency`]: the alternative near-wall model of a channel's wall-normal velocity,
//!   heavy-tailed with the flatness of channel DNS.
//! - [`furnishing`]: solid boxes inside a room (tables, shelves), each face a surface with
//!   its own wall behaviour and tally.
//! - [`openings`]: supply and exhaust openings on a room's walls, and the potential flow
//!   between them that carries air and particles from the supply to the exhaust.
//! - [`scene`]: a whole run's setup: walls (sink, mirror or wall law), forces, integrator, time
//!   step, injection; validated once.
//! - `noise` (internal): each particle's random streams and its standard normal variates,
//!   made a block of steps at a time by a vectorised ziggurat.
//! - `track` (internal): one particle through the run: the exponential integrator, the
//!   particle's [`Fate`]; in it `fluid` (the fluid velocity a particle sees), `contacts` (the
//!   wall contacts within a step) and `lanes` (four particles side by side).
//! - [`run`](mod@run): all particles across cores, reproducibly, and the [`Run`]'s statistics:
//!   mass balance, deposition velocity and loss rate with their standard errors, deposition
//!   maps.
//! - [`decay`]: the airborne share after a release over time, and the loss rate fitted from
//!   it as decay experiments fit theirs.
//! - [`excursions`]: near-wall excursions, the variance reduction for rare deposition: an
//!   unbiased estimate of the steady deposition rate from split copies of the particles that
//!   enter a near-wall layer (in `track` as `excursions`).
//! - [`allocation`]: how many excursions a study starts per class of crossing (floor,
//!   ceiling, walls, furnishings), fewer where its figures have room to spare.
//! - [`convergence`]: run time against error of the integrators over the step size.
//! - [`efficiency`]: run time against statistical error of the studies' variance reduction,
//!   beside the plain tracking it replaces.
//! - [`studies`]: the room and channel studies, runs beside their correlations.
//! - [`steady`]: the steady state under a continuous source (indoor emission or
//!   infiltration), read off a release followed from its start.
//! - [`distribution`]: size distributions (lognormal modes by number or mass, measured size
//!   classes) through a room study: the mass deposited per surface, exhausted and airborne,
//!   for all of it and for PM2.5 and PM10.
//! - [`wall_function`]: deposition where the near-wall layer is not resolved: a particle in
//!   a layer over the wall deposits with the probability a correlation's deposition velocity
//!   gives (for the tracker's rooms and channels, and for host solvers through the C ABI).
//! - [`correlations`]: what to compare with: Lai & Nazaroff (2000) for rooms, Wood (1981) and
//!   Papavergos & Hedley (1984) for channels.
//! - [`measurements`]: measured deposition beside them: Sippola & Nazaroff's (2004) duct
//!   side walls.
//!
//! SI units throughout; `z` is up in a room and wall-normal in a channel.
//!
//! ```
//! use depo_tracker::{run, Geometry, Injection, Scene, SizeDistribution};
//!
//! // 10 um particles settling in still air onto the floor of a 1 m box, for 10 s.
//! let scene = Scene::new(Geometry::Room { size: [1.0, 1.0, 1.0] }, 0.01, 10.0);
//! let particles = Injection::new(2000, SizeDistribution::Monodisperse { diameter: 10e-6 }, 1000.0);
//! let result = run(&scene, &particles).unwrap();
//! let balance = result.balance();
//! assert_eq!(balance.airborne + balance.deposited.iter().sum::<usize>() + balance.escaped, 2000);
//! // Settling at 3 mm/s clears about 3 cm of the 1 m height in 10 s.
//! assert!(balance.deposited[0] > 30 && balance.deposited[0] < 90);
//! ```

pub mod air;
pub mod allocation;
pub mod convergence;
pub mod correlations;
pub mod decay;
pub mod distribution;
pub mod efficiency;
pub mod excursions;
pub mod filtration;
pub mod flow;
pub mod furnishing;
pub mod geometry;
pub mod intermittency;
pub mod measurements;
mod noise;
pub mod openings;
pub mod run;
pub mod scene;
pub mod steady;
pub mod studies;
mod track;
pub mod wall_function;

pub use air::{Aerodynamics, Air};
pub use decay::{log_linear_fit, Comparison, DecayCurve, DecayFit, LogLinear};
pub use excursions::{Excursions, Splitting, Sweeps};
pub use flow::Flow;
pub use furnishing::Furnishing;
pub use geometry::{Geometry, Orientation, Wall};
pub use openings::{Opening, OpeningKind};
pub use run::{binomial_error, delta_error, run, run_more, Balance, Estimate, Run};
pub use scene::{Drag, Injection, NearWall, Scene, SceneError, Scheme, SizeDistribution, WallBehaviour};
pub use track::{Fate, ParticleTally, Record, WallTally, CONTINUITY_CORRECTION, MAX_CONTACTS};
pub use wall_function::{Correlation, WallFunction};
