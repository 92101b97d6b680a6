//! What a surface does with a particle that reaches it: a sink, a mirror, the Brach & Dunn
//! wall law, or (on a domain's walls) a deposition wall function whose deposition velocity
//! comes from a correlation. The physics of the wall function is
//! [`crate::physics::wall_function`]; the contacts that apply a behaviour are in the tracking
//! layer.

use depo_wall_model::{SizeDependence, WallLaw};

use crate::model::air::Air;
use crate::model::geometry::Orientation;

/// What a wall does with a particle that touches it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum WallBehaviour {
    /// Every contact deposits: the perfect sink that deposition-velocity theories assume.
    Sink,
    /// Specular reflection, fluid fluctuation mirrored too: a symmetry plane (and the way to
    /// check that tracers stay well mixed).
    Reflect,
    /// The Brach & Dunn law decides: rebound or capture. With `size`, each particle's capture
    /// velocity follows its diameter ([`SizeDependence`], anchored at the law's own `vc`).
    /// Spin is not tracked by the tracker; friction acts through the law's `mu`.
    Law { law: WallLaw, size: Option<SizeDependence> },
}

/// The correlation a wall function takes the deposition velocity from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Correlation {
    /// Wood (1981), `V+ = 0.057 Sc^(-2/3) + 4.5e-4 tau+^2` (at most 0.13): fully developed
    /// duct and channel flow, every surface alike (gravity not included).
    Wood,
    /// Papavergos & Hedley (1984): `0.065 Sc^(-2/3)`, `3.5e-4 tau+^2`, `0.18` by regime; as
    /// [`Correlation::Wood`].
    PapavergosHedley,
    /// Lai & Nazaroff (2000): a room's floor, ceiling and walls by orientation, with settling
    /// (Brownian and turbulent diffusion and gravity; no inertia).
    LaiNazaroff,
    /// Hussein, Smolík, Kerminen & Kulmala (2012): floor, ceiling and walls by orientation,
    /// with settling and turbophoresis besides Brownian and turbulent diffusion
    /// ([`crate::correlations::hussein`]).
    Hussein,
}

impl Correlation {
    /// Every correlation with its name as scene files and the command write it.
    pub const NAMED: [(&'static str, Correlation); 4] = [
        ("wood", Correlation::Wood),
        ("papavergos-hedley", Correlation::PapavergosHedley),
        ("lai-nazaroff", Correlation::LaiNazaroff),
        ("hussein", Correlation::Hussein),
    ];

    /// Its name (`wood`, `papavergos-hedley`, `lai-nazaroff`, `hussein`).
    #[must_use]
    pub fn name(self) -> &'static str {
        Self::NAMED.iter().find(|(_, c)| *c == self).map_or("", |(n, _)| n)
    }
}

/// A deposition wall function on a scene's walls (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WallFunction {
    /// Where the deposition velocity comes from.
    pub correlation: Correlation,
    /// Where it comes from on vertical surfaces, if not from `correlation`.
    pub vertical: Option<Correlation>,
    /// The layer's thickness `y_w` in wall units, `y_w u* / nu` (30 by default: the bottom
    /// of the logarithmic layer, where wall-function meshes put their first cell).
    pub layer_plus: f64,
}

impl WallFunction {
    /// The default layer, in wall units.
    pub const LAYER_PLUS: f64 = 30.0;

    /// `correlation` over a layer of [`WallFunction::LAYER_PLUS`].
    #[must_use]
    pub fn new(correlation: Correlation) -> Self {
        Self { correlation, vertical: None, layer_plus: Self::LAYER_PLUS }
    }

    /// The correlation for a surface facing `orientation`.
    #[must_use]
    pub fn correlation_for(&self, orientation: Orientation) -> Correlation {
        match (orientation, self.vertical) {
            (Orientation::Wall, Some(vertical)) => vertical,
            _ => self.correlation,
        }
    }

    /// The layer's thickness, m, for friction velocity `u*` (m/s) in `air`.
    #[must_use]
    pub fn layer(&self, air: &Air, friction_velocity: f64) -> f64 {
        self.layer_plus * air.kinematic_viscosity() / friction_velocity
    }
}
