//! Studies: the room and channel studies (runs of the estimation layer per particle size,
//! beside their correlations), size distributions through a room, filtration and ventilation,
//! the steady state under a continuous source, the efficiency of the variance reduction, and
//! the measurements the studies are compared with.
//!
//! The top layer: it may use every layer below ([`crate::estimation`], the tracking layer,
//! [`crate::physics`], [`crate::model`]).

pub mod channel;
pub mod distribution;
pub mod efficiency;
pub mod filtration;
pub mod mass_balance;
pub mod measurements;
pub mod room;
pub mod steady;
pub mod study;

// The room and channel studies at the layer's own path, where they were before the layers.
pub use channel::*;
pub use room::*;
pub use study::*;
