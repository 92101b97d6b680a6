//! A scene: geometry, air, flow, forces and walls, and the particles injected into it; how a
//! run of it is estimated (time step, duration, seed, excursions) is a
//! [`RunSettings`](crate::model::settings::RunSettings) beside it. Everything is checked
//! once, in [`Scene::validate`] and [`RunSettings::validate`](crate::model::settings::RunSettings::validate);
//! the hot loop trusts it.

use crate::model::air::{Air, STANDARD_GRAVITY};
use crate::model::error::SceneError;
use crate::model::flow::Flow;
use crate::model::furnishing::{free_volume, Furnishing, FACE_NAMES, ROOM_SURFACES};
use crate::model::geometry::{Geometry, Wall};
use crate::model::openings::{self, Opening};
use crate::model::walls::WallBehaviour;
use crate::model::walls::WallFunction;

/// The drag law.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Drag {
    /// Stokes drag with the Cunningham slip correction. The default.
    #[default]
    Stokes,
    /// Stokes drag times the Schiller-Naumann factor `1 + 0.15 Re_p^0.687`, evaluated at the
    /// start of each step (costs a `powf` and a few `exp` per particle-step).
    SchillerNaumann,
}

/// The statistics of the wall-normal fluid velocity near a channel's walls.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum NearWall {
    /// Gaussian at every distance: the normalised Langevin model on the Kallio & Reeks
    /// profiles (see [`crate::flow`]). The default.
    #[default]
    Gaussian,
    /// Heavy-tailed, with the flatness direct numerical simulation finds near a wall (27 at
    /// the wall), and the same variance and Lagrangian time (see [`crate::intermittency`]).
    /// Channels only.
    Intermittent,
}

/// Particle sizes at injection.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SizeDistribution {
    /// One diameter, m.
    Monodisperse { diameter: f64 },
    /// Lognormal number distribution with count median diameter `median` (m) and geometric
    /// standard deviation `geometric_sd` (>= 1).
    LogNormal { median: f64, geometric_sd: f64 },
}

/// The particles put into a scene at `t = 0`: uniformly over the domain (or `region`), at the
/// local mean-flow velocity plus their settling velocity (plus a thermal velocity with Brownian
/// motion and a fluctuation drawn from the stationary distribution in turbulence).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Injection {
    /// Number of particles.
    pub count: usize,
    /// Their sizes.
    pub size: SizeDistribution,
    /// Particle material density, kg/m^3.
    pub density: f64,
    /// A box `(low, high)` corners in m, inside the domain; `None` for the whole domain.
    pub region: Option<([f64; 3], [f64; 3])>,
    /// The initial velocity (m/s) of every particle; `None` for the local mean flow plus the
    /// settling velocity.
    pub velocity: Option<[f64; 3]>,
}

impl Injection {
    /// `count` particles of `size` and `density` (kg/m^3) over the whole domain, at the local
    /// flow velocity plus their settling velocity.
    #[must_use]
    pub fn new(count: usize, size: SizeDistribution, density: f64) -> Self {
        Self { count, size, density, region: None, velocity: None }
    }

    /// Only within the box with corners `low` and `high` (m).
    #[must_use]
    pub fn within(self, low: [f64; 3], high: [f64; 3]) -> Self {
        Self { region: Some((low, high)), ..self }
    }

    /// All starting with `velocity` (m/s).
    #[must_use]
    pub fn with_velocity(self, velocity: [f64; 3]) -> Self {
        Self { velocity: Some(velocity), ..self }
    }
}

/// What is simulated, but its particles (see [`Injection`]) and how the run is estimated
/// (see [`RunSettings`](crate::model::settings::RunSettings)).
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    /// The domain.
    pub geometry: Geometry,
    /// The carrier gas.
    pub air: Air,
    /// Gravity, m/s^2 (a room's is `[0, 0, -9.807]`; zero turns settling off).
    pub gravity: [f64; 3],
    /// Mean flow and turbulence.
    pub flow: Flow,
    /// Brownian motion on or off.
    pub brownian: bool,
    /// The drag law.
    pub drag: Drag,
    /// Saffman's shear lift from the mean flow's shear (channel flows with a mean profile only;
    /// off by default).
    pub lift: bool,
    /// The near-wall statistics of a channel's wall-normal velocity.
    pub near_wall: NearWall,
    /// A deposition wall function on the domain's walls (see [`crate::wall_function`]): a
    /// particle within its layer deposits with the probability its correlation gives, and
    /// the walls themselves reflect; `None` (the default) resolves deposition at the walls.
    /// Furnishings' faces and mirror walls keep their own behaviour.
    pub wall_function: Option<WallFunction>,
    /// One behaviour per wall, in the order of [`Geometry::walls`].
    pub walls: Vec<WallBehaviour>,
    /// Keep the well-mixed drift of the dispersion model (on by default; off only to show what
    /// it is for).
    pub drift_correction: bool,
    /// Air-exchange rate `a`, 1/s (air changes per hour / 3600; 0, the default, for a closed
    /// room). Ventilation takes air from the well-mixed room: each airborne particle is
    /// exhausted at a rate `a`, wherever it is, so that without deposition the airborne
    /// number falls as `exp(-a t)`, exactly at the ends of steps (see [`mod@crate::run`]).
    /// Must be 0 with [`Scene::openings`], whose flows set the exchange rate
    /// ([`Scene::exchange_rate`]).
    pub air_exchange: f64,
    /// Supply and exhaust openings on a room's walls (see [`crate::openings`]); none by
    /// default. With openings, air comes in through the supply openings and leaves, with the
    /// particles it carries there, through the exhaust openings, in a potential flow between
    /// them; the uniform exhaust of [`Scene::air_exchange`] is then off.
    pub openings: Vec<Opening>,
    /// Solid boxes inside a room, each face a surface of its own (see [`crate::furnishing`]);
    /// none by default. They may not overlap and must lie strictly inside the room.
    pub furnishings: Vec<Furnishing>,
}

impl Scene {
    /// A scene with standard air, gravity along `-z` and every wall a perfect sink; still air,
    /// no Brownian motion, Stokes drag.
    #[must_use]
    pub fn new(geometry: Geometry) -> Self {
        let walls = vec![WallBehaviour::Sink; geometry.walls().len()];
        Self {
            geometry,
            air: Air::standard(),
            gravity: [0.0, 0.0, -STANDARD_GRAVITY],
            flow: Flow::Still,
            brownian: false,
            drag: Drag::Stokes,
            lift: false,
            near_wall: NearWall::Gaussian,
            wall_function: None,
            walls,
            drift_correction: true,
            air_exchange: 0.0,
            openings: Vec::new(),
            furnishings: Vec::new(),
        }
    }

    /// Every surface: the domain's walls in id order, then each furnishing's faces
    /// ([`crate::furnishing`]), so that a surface's id is its index.
    #[must_use]
    pub fn surfaces(&self) -> Vec<Wall> {
        let mut surfaces = self.geometry.walls();
        for (k, f) in self.furnishings.iter().enumerate() {
            surfaces.extend(f.faces(k));
        }
        surfaces
    }

    /// Each surface's behaviour, in the order of [`Scene::surfaces`].
    #[must_use]
    pub fn surface_behaviours(&self) -> Vec<WallBehaviour> {
        let mut behaviours = self.walls.clone();
        for f in &self.furnishings {
            behaviours.extend(f.faces);
        }
        behaviours
    }

    /// A surface's name: a wall's (`floor`, `x0`; see [`Wall::name`]) or a furnishing face's
    /// (`table.top`, `box2.x1`).
    #[must_use]
    pub fn surface_name(&self, id: usize) -> String {
        if id < ROOM_SURFACES || self.furnishings.is_empty() {
            let walls = self.geometry.walls();
            return walls.get(id).map_or_else(|| format!("surface{id}"), |w| w.name(&self.geometry).to_string());
        }
        let (k, f) = ((id - ROOM_SURFACES) / 6, (id - ROOM_SURFACES) % 6);
        match self.furnishings.get(k) {
            Some(box_) => format!("{}.{}", box_.label(k), FACE_NAMES[f]),
            None => format!("surface{id}"),
        }
    }

    /// The air's volume: the domain's less the furnishings', m^3.
    #[must_use]
    pub fn free_volume(&self) -> f64 {
        free_volume(self.geometry.size(), &self.furnishings)
    }

    /// The air-exchange rate, 1/s: the exhaust openings' total flow over the air's volume
    /// with [`Scene::openings`], [`Scene::air_exchange`] without them.
    #[must_use]
    pub fn exchange_rate(&self) -> f64 {
        if self.openings.is_empty() {
            self.air_exchange
        } else {
            openings::exhaust_flow(&self.openings) / self.free_volume()
        }
    }

    /// All surfaces' area (walls and furnishing faces) over the free air volume, 1/m.
    #[must_use]
    pub fn surface_to_volume(&self) -> f64 {
        self.surfaces().iter().map(|w| w.area).sum::<f64>() / self.free_volume()
    }

    /// Sets every wall to `behaviour`.
    #[must_use]
    pub fn with_walls(mut self, behaviour: WallBehaviour) -> Self {
        self.walls = vec![behaviour; self.geometry.walls().len()];
        self
    }

    /// Checks the scene and the injection; the error names the first offending field.
    pub fn validate(&self, injection: &Injection) -> Result<(), SceneError> {
        let size = self.geometry.size();
        for (name, l) in ["size.x", "size.y", "size.z"].iter().zip(size) {
            positive(name, l)?;
        }
        positive("air.temperature", self.air.temperature)?;
        positive("air.pressure", self.air.pressure)?;
        positive("air.density", self.air.density)?;
        positive("air.viscosity", self.air.viscosity)?;
        for g in self.gravity {
            finite("gravity", g)?;
        }
        if !(self.air_exchange.is_finite() && self.air_exchange >= 0.0) {
            return Err(SceneError::new("air_exchange", self.air_exchange, "must be finite and not negative"));
        }
        openings::validate(&self.openings, &self.geometry)?;
        if !self.openings.is_empty() && self.air_exchange != 0.0 {
            return Err(SceneError::new(
                "air_exchange",
                self.air_exchange,
                "must be 0 with openings: their exhaust flow sets the exchange rate",
            ));
        }
        if self.walls.len() != self.geometry.walls().len() {
            return Err(SceneError::new("walls", self.walls.len() as f64, "must give one behaviour per wall"));
        }
        let channel = matches!(self.geometry, Geometry::Channel { .. });
        match self.flow {
            Flow::Still => {}
            Flow::Uniform { velocity } => {
                for v in velocity {
                    finite("flow.velocity", v)?;
                }
            }
            Flow::Poiseuille { max_speed } => {
                finite("flow.max_speed", max_speed)?;
                if !channel {
                    return Err(SceneError::new("flow", max_speed, "Poiseuille flow needs a channel"));
                }
            }
            Flow::TurbulentChannel { friction_velocity } => {
                positive("flow.friction_velocity", friction_velocity)?;
                if !channel {
                    return Err(SceneError::new("flow", friction_velocity, "a turbulent channel flow needs a channel"));
                }
            }
            Flow::TurbulentRoom { friction_velocity, core_rms, core_time, blend_length } => {
                positive("flow.friction_velocity", friction_velocity)?;
                positive("flow.core_rms", core_rms)?;
                positive("flow.core_time", core_time)?;
                positive("flow.blend_length", blend_length)?;
            }
        }
        if self.lift && !matches!(self.flow, Flow::Poiseuille { .. } | Flow::TurbulentChannel { .. }) {
            return Err(SceneError::new(
                "lift",
                1.0,
                "needs a channel flow with a mean shear (Poiseuille or turbulent)",
            ));
        }
        if self.near_wall == NearWall::Intermittent && !matches!(self.flow, Flow::TurbulentChannel { .. }) {
            return Err(SceneError::new("near_wall", 1.0, "\"intermittent\" needs a turbulent channel flow"));
        }
        if let Some(wf) = &self.wall_function {
            self.validate_wall_function(wf)?;
        }
        if injection.count == 0 {
            return Err(SceneError::new("particles.count", 0.0, "must be at least 1"));
        }
        positive("particles.density", injection.density)?;
        let largest = match injection.size {
            SizeDistribution::Monodisperse { diameter } => {
                positive("particles.diameter", diameter)?;
                diameter
            }
            SizeDistribution::LogNormal { median, geometric_sd } => {
                positive("particles.median", median)?;
                if !(geometric_sd.is_finite() && geometric_sd >= 1.0) {
                    return Err(SceneError::new("particles.geometric_sd", geometric_sd, "must be finite and >= 1"));
                }
                // Sizes are drawn up to 5 geometric standard deviations out.
                median * geometric_sd.powi(5)
            }
        };
        if largest > LARGEST_PARTICLE {
            return Err(SceneError::new(
                "particles.diameter",
                largest,
                "must be at most 1 mm, an airborne particle (Schiller-Naumann's drag holds to Re_p ~ 800)",
            ));
        }
        let smallest = size.iter().copied().fold(f64::INFINITY, f64::min);
        if largest >= 0.5 * smallest {
            return Err(SceneError::new("particles.diameter", largest, "must be smaller than half the domain"));
        }
        if let Some(v) = injection.velocity {
            for c in v {
                finite("particles.velocity", c)?;
            }
        }
        if let Some((lo, hi)) = injection.region {
            for a in 0..3 {
                if !(lo[a].is_finite() && hi[a].is_finite() && 0.0 <= lo[a] && lo[a] <= hi[a] && hi[a] <= size[a]) {
                    return Err(SceneError::new("particles.region", lo[a], "must be a box inside the domain"));
                }
            }
        }
        self.validate_furnishings(injection, largest)?;
        openings::validate_clearance(&self.openings, &self.furnishings, size)
    }

    /// The wall function's part of [`Scene::validate`].
    fn validate_wall_function(&self, wf: &WallFunction) -> Result<(), SceneError> {
        let Some(u_star) = self.flow.friction_velocity() else {
            return Err(SceneError::new(
                "wall_function",
                1.0,
                "needs a turbulent flow (its friction velocity sets the layer and the correlation)",
            ));
        };
        positive("wall_function.layer_plus", wf.layer_plus)?;
        let layer = wf.layer(&self.air, u_star);
        let size = self.geometry.size();
        let walled = self.geometry.walled();
        let narrowest = (0..3).filter(|&a| walled[a]).map(|a| size[a]).fold(f64::INFINITY, f64::min);
        if layer.is_nan() || layer >= 0.25 * narrowest {
            return Err(SceneError::new(
                "wall_function.layer_plus",
                wf.layer_plus,
                "must make the layer thinner than a quarter of the domain across its walls",
            ));
        }
        if self.near_wall == NearWall::Intermittent {
            return Err(SceneError::new("near_wall", 1.0, "must be \"gaussian\" with a wall function"));
        }
        Ok(())
    }

    /// The furnishings' part of [`Scene::validate`]; `largest` is the largest diameter
    /// injected (m).
    fn validate_furnishings(&self, injection: &Injection, largest: f64) -> Result<(), SceneError> {
        if self.furnishings.is_empty() {
            return Ok(());
        }
        let size = self.geometry.size();
        if !matches!(self.geometry, Geometry::Room { .. }) {
            return Err(SceneError::new("furnishings", self.furnishings.len() as f64, "need a room"));
        }
        for (k, f) in self.furnishings.iter().enumerate() {
            let field = |key: &str| format!("furnishings[{k}].{key}");
            for ((lo, hi), length) in f.low.into_iter().zip(f.high).zip(size) {
                if !(lo.is_finite() && lo > 0.0 && lo < length) {
                    return Err(SceneError {
                        field: field("low"),
                        value: lo,
                        requirement: "must lie strictly inside the room",
                    });
                }
                if !(hi.is_finite() && hi > lo && hi < length) {
                    return Err(SceneError {
                        field: field("high"),
                        value: hi,
                        requirement: "must lie strictly inside the room and above `low`",
                    });
                }
            }
            if let Some(other) = self.furnishings[..k].iter().position(|o| o.overlaps(f)) {
                return Err(SceneError {
                    field: field("low"),
                    value: other as f64,
                    requirement: "must not overlap another furnishing (the one at this index)",
                });
            }
        }
        // Particles are drawn uniformly over the free part of the injection region (see the
        // tracker's injection): it must be a good part of the region.
        let (lo, hi) = injection.region.unwrap_or(([0.0; 3], size));
        let region: f64 = (0..3).map(|a| (hi[a] - lo[a]).max(0.0)).product();
        let r = 0.5 * largest;
        let grown: f64 = self
            .furnishings
            .iter()
            .map(|f| Furnishing { low: f.low.map(|l| l - r), high: f.high.map(|h| h + r), ..f.clone() })
            .map(|f| f.shared_volume(lo, hi))
            .sum();
        let middle: [f64; 3] = std::array::from_fn(|a| 0.5 * (lo[a] + hi[a]));
        let blocked = if region > 0.0 {
            grown > (1.0 - MIN_FREE_SHARE) * region
        } else {
            self.furnishings.iter().any(|f| f.holds(middle, r))
        };
        if blocked {
            return Err(SceneError::new(
                "particles.region",
                grown / region,
                "is almost all inside furnishings: at least 1 % of it must be free air",
            ));
        }
        Ok(())
    }
}

/// The least share of the injection region left free by the furnishings.
const MIN_FREE_SHARE: f64 = 0.01;

fn finite(field: &str, v: f64) -> Result<(), SceneError> {
    if v.is_finite() {
        Ok(())
    } else {
        Err(SceneError::new(field, v, "must be finite"))
    }
}

fn positive(field: &str, v: f64) -> Result<(), SceneError> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(SceneError::new(field, v, "must be finite and positive"))
    }
}

/// The largest particle a scene takes, m: a 1 mm sphere of unit density falls at about 4 m/s
/// in air (particle Reynolds number about 270), within the range of Schiller & Naumann's drag
/// (to about 800; Clift, Grace & Weber 1978); a larger one is an object, not an aerosol, and a
/// diameter given in the wrong unit (1 for 1 um) is caught here rather than run.
pub const LARGEST_PARTICLE: f64 = 1e-3;
