//! What moves the air of a scene: its mean flow and turbulence, as a scene states them. The
//! dispersion model that turns them into the velocity a particle sees is
//! [`crate::physics::turbulence`].

/// The mean flow and turbulence of a scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Flow {
    /// Still air.
    Still,
    /// A uniform velocity, m/s.
    Uniform { velocity: [f64; 3] },
    /// Laminar channel flow along `x`, `U = 4 U_max z (H - z) / H^2` (channel only).
    Poiseuille { max_speed: f64 },
    /// Fully developed turbulent channel flow with friction velocity `u*` (m/s): Reichardt's
    /// mean profile along `x` and the near-wall fluctuation model (channel only).
    TurbulentChannel { friction_velocity: f64 },
    /// A room with near-wall turbulence of friction velocity `u*` and a well-mixed core of
    /// fluctuation `core_rms` (m/s per component; `sqrt(2 k / 3)` for turbulent kinetic energy
    /// `k`) and Lagrangian time `core_time` (s), blended over `blend_length` (m).
    TurbulentRoom { friction_velocity: f64, core_rms: f64, core_time: f64, blend_length: f64 },
}

impl Flow {
    /// A typical indoor room: `u* = 1 cm/s`, core fluctuation 5 cm/s, core time 2 s, blended over
    /// 0.25 m (core eddy diffusivity `sigma^2 T = 5e-3 m^2/s`).
    #[must_use]
    pub fn indoor_room() -> Self {
        Flow::TurbulentRoom { friction_velocity: 0.01, core_rms: 0.05, core_time: 2.0, blend_length: 0.25 }
    }

    /// The friction velocity of a turbulent flow, m/s.
    #[must_use]
    pub fn friction_velocity(&self) -> Option<f64> {
        match *self {
            Flow::TurbulentChannel { friction_velocity } | Flow::TurbulentRoom { friction_velocity, .. } => {
                Some(friction_velocity)
            }
            _ => None,
        }
    }

    /// True when the flow has velocity fluctuations.
    #[must_use]
    pub fn is_turbulent(&self) -> bool {
        self.friction_velocity().is_some()
    }
}
