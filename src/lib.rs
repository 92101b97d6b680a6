//! # depo
//!
//! A particle-deposition engine for CFD: the Brach & Dunn (1998) rebound/capture law applied
//! to Lagrangian particles at walls. This crate is the facade over the workspace:
//!
//! - [`wall_model`]: the law, 3-D impacts and structure-of-arrays batches.
//! - [`tracker`]: particle transport in rooms and channels with the law at every wall contact.
//! - [`bench`](mod@bench): kernel throughput as a fraction of a copy kernel moving the same bytes.
// Inlined, so that `cargo doc -p depo --no-deps` documents both crates as modules of the
// facade and the links above resolve without the crates' own pages.
#[doc(inline)]
pub use depo_tracker as tracker;
#[doc(inline)]
pub use depo_wall_model as wall_model;

pub mod bench;
