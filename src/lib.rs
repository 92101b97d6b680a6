//! # depo
//!
//! A particle-deposition engine for CFD: the Brach & Dunn (1998) rebound/capture law applied
//! to Lagrangian particles at walls. This crate is the facade over the workspace:
//!
//! - [`wall_model`]: the law, 3-D impacts and structure-of-arrays batches.
//! - [`tracker`]: particle transport in rooms and channels with the law at every wall contact.
//! - [`bench`](mod@bench): kernel throughput as a fraction of a copy kernel moving the same bytes.
//! - [`scene_file`]: scene files (TOML; a file, a string or a parsed table) read into the
//!   tracker's room and channel studies, every error one line naming the key.
//! - [`report`]: the room and channel studies run once into a result ([`report::room::study`],
//!   [`report::channel::study`]), and that result rendered as a text table, JSON, CSV and SVG
//!   figures ([`plot`]), each renderer in its own module.
//!
//! How the parts fit: a scene is read ([`scene_file`]), the study runs once and reports its
//! progress to a [`report::Progress`], and the renderers read the one result it gives. The
//! `depo` command (`src/cli/`) parses its arguments with clap, calls these and prints what
//! they render; `depo room --format json` prints [`report::room::json::to_json`], so another
//! binding that calls the same functions with the same scene and seed gives the same JSON.
//! Imports only go down: the command uses the reports, a renderer its study's result, the
//! results the scene reader and the tracker; none the other way.
// Inlined, so that `cargo doc -p depo --no-deps` documents both crates as modules of the
// facade and the links above resolve without the crates' own pages.
#[doc(inline)]
pub use depo_tracker as tracker;
#[doc(inline)]
pub use depo_wall_model as wall_model;

pub mod bench;
pub mod csv_input;
mod error;
pub mod plot;
pub mod report;
pub mod scene_file;
pub mod text;

pub use error::Error;
