//! Estimation: running the particles of a scene across cores, reproducibly, and the
//! statistics of a run (mass balance, deposition velocities and loss rates with their standard
//! errors; deposition maps of their estimator, `maps`); the calibration of near-wall excursions and how a study allocates
//! them; decay curves and their fitted loss rates; the convergence of the integrators.
//!
//! May use the tracking layer, the physics and the model; nothing above them.

pub mod allocation;
pub mod convergence;
pub mod decay;
pub mod excursions;
pub mod maps;
pub mod run;
