//! The model: what is simulated. The domain (a room or a plane channel), the air and a
//! particle in it, the mean flow and turbulence as a scene states them, furnishings, supply
//! and exhaust openings with the potential flow between them, what each surface does with a
//! particle, the injection, and the [`Scene`] that holds them, validated in one place
//! ([`Scene::validate`]); beside the scene, how a run of it is estimated ([`RunSettings`]:
//! time step, scheme, duration, seed, averaging window, the near-wall excursions asked for),
//! validated against it ([`RunSettings::validate`]).
//!
//! The bottom layer: it uses no other layer of the crate (only the wall law of
//! [`depo_wall_model`]). Every layer above reads it.
//!
//! [`Scene`]: scene::Scene
//! [`Scene::validate`]: scene::Scene::validate
//! [`RunSettings`]: settings::RunSettings
//! [`RunSettings::validate`]: settings::RunSettings::validate

pub mod air;
pub mod error;
pub mod excursions;
pub mod flow;
pub mod furnishing;
pub mod geometry;
pub mod openings;
pub mod potential_flow;
pub mod scene;
pub mod settings;
pub mod walls;
