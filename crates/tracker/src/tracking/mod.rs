//! One subject, hence one file over 700 lines: one particle's loop, its step and its injection (contacts, fluid and lanes are modules of their own).
//!
//! One particle through a whole run: the step (drag relaxation, gravity, Brownian motion,
//! turbulent dispersion), the wall contacts within a step, and the particle's fate.
//!
//! One subject, kept whole though long: the one-particle step and the types every tracking
//! loop shares; the loop's variants are the submodules.
//!
//! ## The step
//! Over a step `dt` the fluid velocity seen, `u_f = U(x) + sigma(x) zeta`, is frozen at its
//! start. With drag relaxation time `tau` and settling velocity `v_s = tau g (1 - rho/rho_p)`
//! the particle relaxes to `v_inf = u_f + v_s`. The [`Scheme::Exponential`] step is the exact
//! solution of `dv/dt = (v_inf - v) / tau`:
//!
//! ```text
//! v(t) = v_inf + (v0 - v_inf) exp(-t / tau)
//! x(t) = x0 + v_inf t + (v0 - v_inf) tau (1 - exp(-t / tau))
//! ```
//!
//! exact for any `dt / tau` (a tracer, `tau -> 0`, moves with `u_f`). Brownian motion adds the
//! exact Ornstein-Uhlenbeck increments of velocity and position over the step (Chandrasekhar
//! 1943): with `h = dt / tau` and thermal variance `kT/m`,
//!
//! ```text
//! var v = kT/m (1 - e^-2h),  var x = kT/m tau^2 (2h - 3 + 4 e^-h - e^-2h),
//! cov(x, v) = kT/m tau (1 - e^-h)^2
//! ```
//!
//! so the mean-square displacement is `2 D t` with `D = kT tau / m`, the Stokes-Einstein value.
//! [`Scheme::Euler`] is forward Euler (Euler-Maruyama with Brownian motion), for comparison.
//! [`Scheme::Midpoint`] is the exponential step with `u_f` (and the step of `zeta`) read not
//! at `x0` but where `x(dt/2)` of the formula above puts the particle for the `u_f` at `x0`:
//! a predictor that makes the step second order in the turbulence's gradients. In a room the
//! predictor's `u_f` is the mean flow plus `g sigma zeta` with the current `zeta` and the
//! scale `g sigma` where the last step read the turbulence (half a step back): that moves the
//! predicted point by `O(dt^2)` (with Brownian motion, also by `O(dt^(3/2))` of zero mean),
//! which keeps the step second order, and saves a second read of the turbulence's profiles
//! per step ([`Flyer::half_step_position`]; the openings' mean flow is still read at the
//! start).
//!
//! ## Wall contacts
//! When a step ends with the sphere through a wall plane (centre closer than its radius), the
//! contact time is found on the step's own trajectory by bisection, the particle is moved
//! there, and the wall acts: a sink deposits it, a reflecting wall mirrors it, the Brach & Dunn
//! law rebounds or captures it (see `WallBehaviour`). A rebounding particle flies on for the
//! rest of the step, with as many contacts as it meets (a particle still bouncing after
//! [`MAX_CONTACTS`] contacts in one step has come to rest on the wall and is deposited there).
//! The Brownian increments are spread evenly over the step up to the first contact; what is left
//! of them after a rebound is dropped. The normal velocity handed to the law is the inward
//! normal speed on the trajectory at contact (with Brownian motion its sign is taken as inward:
//! the trajectory did cross the plane).

//!
//! ## Particle-major, not step-major
//! Particles do not interact (one-way coupling), so each is carried through the whole run
//! before the next starts: its position, velocity and fluctuation stay in registers (or in
//! L1) from the first step to the last, and memory sees only its record at the end. A
//! step-major loop over all particles would stream their state through memory every step
//! instead. Turbulent scenes carry four particles at a time side by side (`run_lanes`): a
//! structure-of-arrays of four, not of the whole population, so that the four overlap their
//! table look-ups and share vector instructions. Scenes with constant forcing (uniform flow,
//! no turbulence or Brownian motion) take the same lanes and fly them freely between contacts
//! (`fly_freely`), a loop of a dozen vector operations per step. (What was tried instead and
//! not kept is in docs/performance-log.md.)
//!
//! ## Parts
//! The tracking layer: it may use the physics ([`crate::physics`]) and the model
//! ([`crate::model`]), nothing above them. //! This module holds what a particle is ([`Record`], its constants, injection) and the
//! one-particle loop (`run_particle`); `fluid` gives the fluid velocity a particle sees,
//! `contacts` the wall contacts within a step, and `lanes` the same loop for four particles
//! side by side.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

use depo_wall_model::energy::EnergyLoss;
use glam::DVec3;
use rand::{Rng, RngExt};
use rand_distr::{Distribution, LogNormal};

use crate::model::air::{schiller_naumann, Aerodynamics};
use crate::model::error::SceneError;
use crate::model::excursions::Excursions;
use crate::model::flow::Flow;
use crate::model::furnishing::{Clearance, Furnishing};
use crate::model::geometry::Wall;
use crate::model::openings::{Opening, OpeningKind, CELLS_ALONG_LONGEST};
use crate::model::potential_flow::{FlowCell, PotentialFlow};
use crate::model::scene::{Drag, Injection, NearWall, Scene, SizeDistribution};
use crate::model::settings::{RunSettings, Scheme};
use crate::model::walls::WallBehaviour;
use crate::model::walls::WallFunction;
use crate::physics::intermittency::Intermittent;
use crate::physics::noise::{particle_rng, Normals};
use crate::physics::turbulence::FlowField;

mod contacts;
mod excursions;
mod fluid;
mod lanes;
mod wall_function;

pub use excursions::{Landed, ParticleTally};

use contacts::{contacts, inside, wrap, AfterContacts, Flight};
use fluid::{
    fluid_velocity, fluid_velocity_and_fluctuation, furnished_fluid_velocity, intermittent_fluid_velocity, saffman_lift,
};
use lanes::run_lanes;
pub(crate) use wall_function::track_wall_function;

/// The most `dt |d sigma / dy|` may be with the default scheme: the step reads the
/// turbulence at its start, first order in this product, and beyond it tracers drift far from
/// well mixed near steep rms gradients (figures in docs/validation.md, "The time step").
pub const MAX_STEP_GRADIENT: f64 = 0.05;

/// [`MAX_STEP_GRADIENT`] for [`Scheme::Midpoint`](crate::model::settings::Scheme::Midpoint),
/// which reads the profiles half a step on (second order) and keeps tracers well mixed up to
/// twice the default's limit (docs/validation.md, "The time step").
pub const MAX_STEP_GRADIENT_MIDPOINT: f64 = 0.1;

/// Contacts allowed in one step before a bouncing particle counts as resting on the wall.
pub const MAX_CONTACTS: usize = 32;
/// Steps whose normal variates are made in one block (a multiple of four variates for any
/// scene).
const STEPS_PER_BLOCK: usize = 16;

/// Steps between two looks at [`Prepared::stop`] in a particle's loop. A cancelled run then
/// stops within this many steps of the particles in hand (milliseconds), not when they have
/// been tracked through the whole run, which for slowly depositing particles in a long run
/// takes seconds per particle. One relaxed atomic load per so many steps costs nothing
/// measurable.
pub(crate) const STOP_CHECK_STEPS: usize = 1024;
/// Bisection steps for a contact time (to well below 1e-12 of the step).
const BISECTIONS: usize = 48;

/// What became of a particle by the end of the run.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Fate {
    /// Still in the air.
    Airborne,
    /// Deposited on the surface with this id: a wall, or a furnishing's face
    /// ([`Scene::surfaces`]).
    Deposited(usize),
    /// Lost to the statistics: a non-finite state or a contact the wall law flagged invalid.
    Escaped,
    /// Taken out of the room by ventilation: by the uniform exhaust ([`Scene::air_exchange`]),
    /// or through an exhaust opening ([`Scene::openings`]).
    Exhausted,
}

/// One particle's history in brief.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Record {
    /// Its fate.
    pub fate: Fate,
    /// When it was deposited or escaped; the end of the run for an airborne particle, s.
    pub time: f64,
    /// Where it was injected, m.
    pub start: [f64; 3],
    /// Where it was deposited, or where it is at the end of the run, m.
    pub position: [f64; 3],
    /// Diameter, m.
    pub diameter: f64,
    /// Mass, kg.
    pub mass: f64,
    /// Steps it was tracked for.
    pub steps: u64,
    /// Airborne time it spent near the floor, in the lowest [`NEAR_FLOOR_SHARE`] of the
    /// domain's height (at the ends of its steps), s: with `time`, how much of its life in the
    /// air was there (a steady source's near-floor concentration, [`crate::steady`]).
    pub near_floor: f64,
}

/// The share of the domain's height, from its floor (`z = 0`), whose airborne time a
/// [`Record`] keeps apart: a tenth, 0.25 m in a room 2.5 m high.
pub const NEAR_FLOOR_SHARE: f64 = 0.1;

/// A wall's impact statistics.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct WallTally {
    /// Contacts with the wall.
    pub contacts: u64,
    /// Contacts that ended in a rebound (or reflection).
    pub rebounds: u64,
    /// Contacts that ended in deposition (the sink, or the law's capture).
    pub captures: u64,
    /// Particles deposited because they were still bouncing after [`MAX_CONTACTS`] contacts
    /// in one step (at rest on the wall; not counted as captures).
    pub resting: u64,
    /// Energy lost at the wall by mechanism, J (the wall law's budget times particle mass).
    pub energy: EnergyLoss<f64>,
}

impl std::ops::AddAssign for WallTally {
    fn add_assign(&mut self, o: Self) {
        self.contacts += o.contacts;
        self.rebounds += o.rebounds;
        self.captures += o.captures;
        self.resting += o.resting;
        self.energy += o.energy;
    }
}

/// The scene prepared for tracking: tabulated flow, walls, per-run constants.
pub(crate) struct Prepared<'a> {
    pub scene: &'a Scene,
    /// How the run is estimated: its step, scheme, seed, window, excursions.
    pub settings: &'a RunSettings,
    pub injection: &'a Injection,
    pub field: FlowField,
    /// The domain's walls (the planes the contact search checks one by one).
    pub walls: Vec<Wall>,
    /// Every surface, walls and then furnishing faces, in id order (the tallies' order).
    pub surfaces: Vec<Wall>,
    /// Each surface's behaviour, in id order.
    pub behaviours: Vec<WallBehaviour>,
    /// The furnishings (empty in most scenes, which then take no furnished path).
    pub boxes: &'a [Furnishing],
    /// The potential flow between the room's openings ([`crate::openings`]), added to the
    /// mean flow; `None` without openings (most scenes, which then take no such path).
    pub mean_flow: Option<Arc<PotentialFlow>>,
    /// The exhaust openings: a particle that reaches a wall within one leaves the room.
    pub exhausts: Vec<Opening>,
    pub size: [f64; 3],
    pub walled: [bool; 3],
    /// Per axis, the walls' coordinates (`0` and the size), infinite along periodic axes.
    pub lower: [f64; 3],
    pub upper: [f64; 3],
    /// True when some axis is periodic.
    pub periodic: bool,
    pub steps: usize,
    /// The averaging window `[average_from, end of the run]`, s.
    pub window: [f64; 2],
    /// Whether each step takes the turbulence half a step on ([`Scheme::Midpoint`] in a
    /// turbulent scene).
    pub midpoint: bool,
    /// Whether the midpoint scheme's predictor takes the fluctuation's scale from the last
    /// step's read ([`Flyer::half_step_position`]): in a room (no mean profile, no
    /// correlated components, no intermittent model).
    pub reuse_scale: bool,
    /// The step this preparation is for, s: the scene's, or its excursions' coarse step.
    pub dt: f64,
    /// The scene prepared for the excursions' coarse steps ([`Excursions::coarse_factor`]
    /// above 1, in a scene without furnishings or openings); `None` otherwise.
    ///
    /// [`Excursions::coarse_factor`]: crate::Excursions::coarse_factor
    pub coarse: Option<Box<Prepared<'a>>>,
    /// The scene's wall function, prepared; `None` without one.
    pub wall_function: Option<LayerWalls>,
    /// The top of the near-floor layer whose airborne time a record keeps, m
    /// ([`NEAR_FLOOR_SHARE`] of the height).
    pub near_floor: f64,
    /// Set when the run is to stop early (its caller cancelled it): each particle loop looks
    /// at it every [`STOP_CHECK_STEPS`] steps ([`Prepared::stopped_at`]) and ends at once,
    /// leaving its particles' records incomplete, for the run to discard. `None`: never.
    pub stop: Option<Arc<AtomicBool>>,
}

/// A wall function prepared for a run ([`crate::wall_function`]).
pub(crate) struct LayerWalls {
    /// The scene's wall function (its correlation by orientation).
    pub function: WallFunction,
    /// The layer's thickness, m.
    pub layer: f64,
    /// The flow's friction velocity, m/s.
    pub friction_velocity: f64,
    /// The walls it acts on (every domain wall but the mirrors), each with the behaviour
    /// that decides what arrives there; in [`Prepared::behaviours`] they reflect.
    pub walls: Vec<(Wall, WallBehaviour)>,
}

impl<'a> Prepared<'a> {
    /// The scene prepared for `injection`.
    ///
    /// # Errors
    ///
    /// Where the mean flow between the openings cannot be solved ([`PotentialFlow::new`]).
    pub fn new(scene: &'a Scene, settings: &'a RunSettings, injection: &'a Injection) -> Result<Self, SceneError> {
        let mut prepared = Self::stepping(scene, settings, injection, settings.dt)?;
        let factor = settings.excursions.as_ref().map_or(1, |e| e.coarse_factor);
        if factor > 1 && prepared.boxes.is_empty() && prepared.mean_flow.is_none() {
            let mut coarse = Self::stepping(scene, settings, injection, settings.dt * f64::from(factor))?;
            // Second order in `dt |d sigma/dy|`, whatever the scene's scheme.
            coarse.midpoint = coarse.field.turbulence.is_some();
            prepared.coarse = Some(Box::new(coarse));
        }
        Ok(prepared)
    }

    /// The scene prepared for steps of `dt`.
    fn stepping(
        scene: &'a Scene,
        settings: &'a RunSettings,
        injection: &'a Injection,
        dt: f64,
    ) -> Result<Self, SceneError> {
        let size = scene.geometry.size();
        let nu = scene.air.kinematic_viscosity();
        let walled = scene.geometry.walled();
        let mut field = FlowField::new(&scene.flow, size, nu, dt, scene.drift_correction);
        if let (NearWall::Intermittent, Flow::TurbulentChannel { friction_velocity }) = (scene.near_wall, scene.flow) {
            field.intermittent =
                Some(Intermittent::channel(0.5 * size[2], friction_velocity, nu, dt, scene.drift_correction));
        }
        let midpoint = settings.scheme == Scheme::Midpoint && field.turbulence.is_some();
        let mut behaviours = scene.surface_behaviours();
        let wall_function = match (scene.wall_function, scene.flow.friction_velocity()) {
            (Some(wf), Some(u_star)) => {
                let walls: Vec<(Wall, WallBehaviour)> = scene
                    .geometry
                    .walls()
                    .into_iter()
                    .zip(scene.walls.iter().copied())
                    .filter(|(_, b)| *b != WallBehaviour::Reflect)
                    .collect();
                for (wall, _) in &walls {
                    behaviours[wall.id] = WallBehaviour::Reflect;
                }
                Some(LayerWalls { function: wf, layer: wf.layer(&scene.air, u_star), friction_velocity: u_star, walls })
            }
            _ => None,
        };
        let reuse_scale =
            midpoint && field.profile.is_none() && field.stress_coupling.is_none() && field.intermittent.is_none();
        Ok(Self {
            scene,
            settings,
            injection,
            field,
            walls: scene.geometry.walls(),
            surfaces: scene.surfaces(),
            behaviours,
            boxes: &scene.furnishings,
            mean_flow: if scene.openings.is_empty() {
                None
            } else {
                Some(PotentialFlow::shared(size, &scene.openings, &scene.furnishings, CELLS_ALONG_LONGEST)?)
            },
            exhausts: scene.openings.iter().filter(|o| o.kind == OpeningKind::Exhaust).copied().collect(),
            size,
            walled,
            lower: walled.map(|w| if w { 0.0 } else { f64::NEG_INFINITY }),
            upper: std::array::from_fn(|a| if walled[a] { size[a] } else { f64::INFINITY }),
            periodic: walled.contains(&false),
            steps: settings.steps(),
            window: [settings.average_from, settings.steps() as f64 * settings.dt],
            midpoint,
            reuse_scale,
            dt,
            coarse: None,
            wall_function,
            near_floor: NEAR_FLOOR_SHARE * size[2],
            stop: None,
        })
    }

    /// Whether a particle loop at step `n` is to end early: [`Prepared::stop`] is set, looked
    /// at on every [`STOP_CHECK_STEPS`]-th step only.
    #[inline(always)]
    pub fn stopped_at(&self, n: usize) -> bool {
        n % STOP_CHECK_STEPS == 0 && self.stop.as_ref().is_some_and(|s| s.load(Ordering::Relaxed))
    }
}

/// The per-particle constants of a run.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Body {
    aero: Aerodynamics,
    radius: f64,
    /// The centre's distance from a wall plane at which the particle counts as touching it,
    /// m: the radius, plus with Brownian motion the continuity correction for contacts missed
    /// between step ends, `0.5826 sx` (see [`CONTINUITY_CORRECTION`]).
    contact: f64,
    /// Gravity with buoyancy, `g (1 - rho/rho_p)`, m/s^2.
    gravity: DVec3,
    /// Drag relaxation time, s.
    tau: f64,
    /// Settling velocity vector `tau g (1 - rho/rho_p)`, m/s.
    settling: DVec3,
    /// `exp(-dt / tau)`.
    decay: f64,
    /// `tau (1 - exp(-dt / tau))`, s.
    relax: f64,
    /// `tau (1 - exp(-dt / (2 tau)))`, s: the midpoint predictor's relaxation over half a step.
    half_relax: f64,
    /// Brownian step: `x = sx a`, `v = cxv a + sv b` for standard normals `a, b`.
    brownian: [f64; 3],
    /// Thermal velocity variance per axis `kT/m`, m^2/s^2.
    thermal_variance: f64,
}

/// The continuity correction of an absorbing barrier watched only at step ends: a Brownian
/// path that ends a step on the near side of a barrier may have touched it within the step,
/// and watching at step ends only is, to leading order, watching a barrier moved away by
/// `beta sx`, with `sx` the step's standard deviation and `beta = -zeta(1/2) / sqrt(2 pi) =
/// 0.5826` (Broadie, Glasserman & Kou 1997, Math. Finance 7:325; Siegmund 1985). So contacts
/// are taken `beta sx` before the wall. Brownian deposition of 0.01 um particles released near
/// a floor at the room's step (0.05 s, `sx` = 73 um) was 6 % below the exact solution without
/// it (tested). The paths it assumes are Brownian over a step (`dt >> tau`, as for every
/// particle where the correction is not negligible); for smoother ones it overcorrects by a
/// part of `sx`, which is then small.
pub const CONTINUITY_CORRECTION: f64 = 0.582_597_157_939_010_7;

/// `(sx, cxv, sv)` of the exact Brownian step for `h = dt / tau` and thermal variance `kt_m`.
fn brownian_coefficients(h: f64, tau: f64, kt_m: f64) -> [f64; 3] {
    if !(h.is_finite() && tau > 0.0) {
        // Over-damped limit: position only, variance 2 D dt = 2 kT/m tau dt.
        let sx = (2.0 * kt_m * tau * tau * h).sqrt();
        return [sx, 0.0, kt_m.sqrt()];
    }
    let one_minus = -(-h).exp_m1();
    // 2h - 3 + 4 e^-h - e^-2h, by its series (to h^7) where the formula cancels.
    let shape = if h < 0.05 {
        h * h * h * (2.0 / 3.0 - h * (0.5 - h * (7.0 / 30.0 - h * (1.0 / 12.0 - h * 31.0 / 1260.0))))
    } else {
        2.0 * h - 3.0 + 4.0 * (-h).exp() - (-2.0 * h).exp()
    };
    let var_x = kt_m * tau * tau * shape;
    let var_v = kt_m * one_minus * (2.0 - one_minus);
    let cov = kt_m * tau * one_minus * one_minus;
    let sx = var_x.sqrt();
    let cxv = if sx > 0.0 { cov / sx } else { 0.0 };
    let sv = (var_v - cxv * cxv).max(0.0).sqrt();
    [sx, cxv, sv]
}

impl Body {
    fn new(p: &Prepared<'_>, diameter: f64) -> Self {
        let scene = p.scene;
        let g = DVec3::from_array(scene.gravity);
        let aero = Aerodynamics::new(diameter, p.injection.density, &scene.air, g.length());
        let buoyancy = 1.0 - scene.air.density / p.injection.density;
        let kt = aero.thermal_variance(&scene.air);
        let mut body = Self {
            aero,
            radius: 0.5 * diameter,
            contact: 0.5 * diameter,
            gravity: g * buoyancy,
            tau: 0.0,
            settling: DVec3::ZERO,
            decay: 0.0,
            relax: 0.0,
            half_relax: 0.0,
            brownian: [0.0; 3],
            thermal_variance: kt,
        };
        body.relax_in(aero.relaxation_time, p.dt);
        if scene.brownian && p.settings.scheme != Scheme::Euler {
            body.contact += CONTINUITY_CORRECTION * body.brownian[0];
        }
        body
    }

    /// Sets the relaxation time to `tau` (s) and what follows from it for steps of `dt`.
    #[inline(always)]
    fn relax_in(&mut self, tau: f64, dt: f64) {
        let h = dt / tau;
        self.tau = tau;
        self.settling = self.gravity * tau;
        self.decay = (-h).exp();
        self.relax = tau * -(-h).exp_m1();
        self.half_relax = tau * (1.0 - self.decay.sqrt());
        self.brownian = brownian_coefficients(h, tau, self.thermal_variance);
    }
}

/// The exact Brownian increments of position and velocity over a step along one axis,
/// `(sx a, cxv a + sv b)`, from the standard normals `a, b` and `[sx, cxv, sv]` of
/// [`brownian_coefficients`].
#[inline(always)]
fn brownian_increment([sx, cxv, sv]: [f64; 3], a: f64, b: f64) -> (f64, f64) {
    (sx * a, cxv * a + sv * b)
}

/// One component of the exact drag relaxation over a step (the module's equations): from
/// `x0, v0` towards `v_inf`, with `(dt, exp(-dt/tau), tau (1 - exp(-dt/tau)))` and the
/// Brownian increments `bx, bv`. Returns the position and velocity at the step's end.
#[inline(always)]
fn relaxed(x0: f64, v0: f64, v_inf: f64, (dt, decay, relax): (f64, f64, f64), bx: f64, bv: f64) -> (f64, f64) {
    let dv = v0 - v_inf;
    (x0 + v_inf * dt + dv * relax + bx, v_inf + dv * decay + bv)
}

/// Distance to the nearer wall across `axis` and the sign of `d(distance)/d(coordinate)`.
#[inline(always)]
fn wall_distance(c: f64, length: f64) -> (f64, f64) {
    let upper = length - c;
    let lower = c <= upper;
    (if lower { c } else { upper }, if lower { 1.0 } else { -1.0 })
}

/// The particle's state between steps.
#[derive(Clone, Copy, Debug)]
pub(crate) struct State {
    x: DVec3,
    v: DVec3,
    zeta: [f64; 3],
}

/// What a scene's step needs, each a const generic of the particle loops.
#[derive(Clone, Copy)]
struct Needs {
    brown: bool,
    turb: bool,
    finite_re: bool,
    euler: bool,
    lift: bool,
}

impl Needs {
    fn of(p: &Prepared<'_>) -> Self {
        let scene = p.scene;
        Self {
            brown: scene.brownian,
            turb: p.field.turbulence.is_some(),
            finite_re: scene.drag == Drag::SchillerNaumann,
            euler: p.settings.scheme == Scheme::Euler,
            lift: scene.lift && p.field.profile.is_some(),
        }
    }
}

/// Tracks particles `ids` through the run, adding their wall contacts to `tally`.
pub(crate) fn track(p: &Prepared<'_>, ids: std::ops::Range<usize>, tally: &mut [WallTally]) -> Vec<Record> {
    let Needs { brown, turb, finite_re, euler, lift } = Needs::of(p);
    // One monomorphised loop per combination of what the scene needs, chosen once for all the
    // particles: each flag becomes a const generic, and the loop carries no code for a force
    // left out. Turbulent scenes with the common options step particles side by side.
    // (Lanes pay where there are look-ups to overlap, or where the forcing is constant and they
    // fly freely; a scene with Brownian motion alone, or a laminar profile, runs faster one
    // particle at a time.)
    // Furnished scenes and scenes with openings take the one-particle loop: its contact search
    // and turbulence know the boxes, and its fluid velocity the openings' mean flow; the
    // lanes' free-flight bounds and table look-ups do not.
    let free = !(brown || turb) && p.field.profile.is_none();
    // So does the intermittent near-wall model, whose wall-normal step the lanes do not have.
    let plain = p.boxes.is_empty() && p.mean_flow.is_none() && p.field.intermittent.is_none();
    if (turb || free) && !(finite_re || euler || lift || p.midpoint) && plain {
        return match (turb, brown) {
            (true, true) => run_lanes::<true, true>(p, ids, tally),
            (true, false) => run_lanes::<false, true>(p, ids, tally),
            (false, _) => run_lanes::<false, false>(p, ids, tally), // `free`: no Brownian motion
        };
    }
    macro_rules! dispatch {
        ([$($done:literal)*] []) => { ids.map(|id| run_particle::<$($done),*>(p, id as u64, tally)).collect() };
        ([$($done:literal)*] [$flag:expr $(, $rest:expr)*]) => {
            if $flag { dispatch!([$($done)* true] [$($rest),*]) } else { dispatch!([$($done)* false] [$($rest),*]) }
        };
    }
    dispatch!([] [brown, turb, finite_re, euler, lift])
}

/// Tracks particles `ids` with near-wall `excursions`, adding their wall contacts (not their
/// excursions') to `tally`: their records and tallies.
pub(crate) fn track_excursions(
    p: &Prepared<'_>,
    excursions: &Excursions,
    ids: std::ops::Range<usize>,
    tally: &mut [WallTally],
) -> (Vec<Record>, Vec<ParticleTally>) {
    let Needs { brown, turb, finite_re, euler, lift } = Needs::of(p);
    macro_rules! dispatch {
        ([$($done:literal)*] []) => {
            ids.map(|id| excursions::run_with_excursions::<$($done),*>(p, excursions, id as u64, tally)).unzip()
        };
        ([$($done:literal)*] [$flag:expr $(, $rest:expr)*]) => {
            if $flag { dispatch!([$($done)* true] [$($rest),*]) } else { dispatch!([$($done)* false] [$($rest),*]) }
        };
    }
    dispatch!([] [brown, turb, finite_re, euler, lift])
}

fn sample_diameter(size: SizeDistribution, rng: &mut impl Rng) -> f64 {
    match size {
        SizeDistribution::Monodisperse { diameter } => diameter,
        SizeDistribution::LogNormal { median, geometric_sd } => {
            // Clamped to 5 geometric standard deviations, as Scene::validate assumes.
            let spread = geometric_sd.powi(5);
            let d: f64 = LogNormal::new(median.ln(), geometric_sd.ln()).expect("validated").sample(rng);
            d.clamp(median / spread, median * spread)
        }
    }
}

/// A particle as injected: its constants, where and how it starts, and its random streams.
struct Injected {
    body: Body,
    start: [f64; 3],
    x: [f64; 3],
    v: [f64; 3],
    zeta: [f64; 3],
    normals: Normals,
    /// Steps it is tracked for: the run's, or fewer when ventilation exhausts it earlier.
    end: usize,
}

/// The steps particle `id` stays in the air before ventilation exhausts it, at most the run's
/// `steps`: `ceil(E / dt)` for an exponential time `E` of rate `a = air_exchange`, drawn from a
/// stream of its own (so that the particle's other random numbers are those of a closed room).
/// The particle leaves at the end of that step: the chance to be still in the air after `n`
/// steps is `exp(-a n dt)`, exactly.
fn exhaust_steps(p: &Prepared<'_>, id: u64) -> usize {
    let a = p.scene.air_exchange;
    if a <= 0.0 {
        return p.steps;
    }
    let u: f64 = particle_rng(p.settings.seed ^ EXHAUST_SALT, id).random();
    // `1 - u` in (0, 1]: a finite time.
    let steps = (-(1.0 - u).ln() / (a * p.settings.dt)).ceil();
    if steps < p.steps as f64 {
        (steps as usize).max(1)
    } else {
        p.steps
    }
}

/// The most positions drawn for one particle before its injection gives up (see `inject`).
const MAX_INJECTION_DRAWS: usize = 10_000;

/// Salt of the stream that draws a particle's exhaust time.
const EXHAUST_SALT: u64 = 0x3c6e_f372_fe94_f82b;

/// Particle `id` at `t = 0`: size, position, velocity (and fluctuation) from its own stream.
fn inject(p: &Prepared<'_>, id: u64, turb: bool, brown: bool) -> Injected {
    let mut rng = particle_rng(p.settings.seed, id);
    let diameter = sample_diameter(p.injection.size, &mut rng);
    let body = Body::new(p, diameter);
    let r = body.radius;
    let (lo, hi) = p.injection.region.unwrap_or(([0.0; 3], p.size));
    let mut start = [0.0; 3];
    // Uniform over the free air: a position inside a furnishing (grown by the radius) is drawn
    // again, from the particle's own stream (so a scene without furnishings draws once).
    // `Scene::validate` leaves at least 1 % of the region free: 10^4 draws all fail with a
    // chance below 1e-43.
    for attempt in 0.. {
        for a in 0..3 {
            let (l, h) = if p.walled[a] { (lo[a].max(r), hi[a].min(p.size[a] - r)) } else { (lo[a], hi[a]) };
            start[a] = if h > l { rng.random_range(l..h) } else { 0.5 * (l + h) };
        }
        if !p.boxes.iter().any(|b| b.holds(start, r)) {
            break;
        }
        assert!(attempt < MAX_INJECTION_DRAWS, "no free air found to inject particle {id} into");
    }
    let x = DVec3::from_array(start);
    let mut normals = Normals::from_rng(&mut rng);
    let mut z = [0.0; 8];
    if turb || brown {
        normals.fill(&mut z);
    }
    let mut zeta = [0.0; 3];
    if turb {
        zeta = [z[0], z[1], z[2]];
    }
    let mut uf = if p.boxes.is_empty() {
        fluid_velocity::<true>(&p.field, p.size, x, &zeta)
    } else {
        furnished_fluid_velocity(&p.field, p.size, p.boxes, x, &mut zeta, None).0
    };
    if let Some(mean) = &p.mean_flow {
        uf += DVec3::from_array(mean.velocity(start));
    }
    let mut v = match p.injection.velocity {
        Some(v) => DVec3::from_array(v),
        None => uf + body.settling,
    };
    if brown {
        let sd = body.thermal_variance.sqrt();
        v += DVec3::new(z[3], z[4], z[5]) * sd;
    }
    Injected { body, start, x: start, v: v.to_array(), zeta, normals, end: exhaust_steps(p, id) }
}

/// What one step did to a particle in flight.
pub(crate) enum Step {
    /// Still in the air at the step's end.
    Airborne,
    /// Gone within the step: its fate, the time into the step (s) and where.
    Left(Fate, f64, DVec3),
}

/// One particle in flight: its constants, state and random streams, stepped by
/// [`Flyer::step`]. `run_particle` carries one through the whole run; near-wall excursions
/// (`excursions`) copy one where it enters the layer, and again where they split.
#[derive(Clone)]
pub(crate) struct Flyer {
    /// Its constants (with Schiller-Naumann drag, as at the current step).
    pub body: Body,
    /// Its constants in Stokes drag.
    pub base: Body,
    pub start: [f64; 3],
    pub x: DVec3,
    pub v: DVec3,
    pub zeta: [f64; 3],
    /// Steps it is tracked for ([`exhaust_steps`]).
    pub end: usize,
    draws: StepNormals,
    /// Saffman's lift per unit relative velocity and root shear rate, `(9.69/pi) sqrt(rho mu) /
    /// (rho_p d)`.
    lift_coefficient: f64,
    /// The cell of the openings' mean flow it was last in ([`PotentialFlow::velocity_in`]).
    flow_cell: FlowCell,
    /// Each fluctuating component's scale `g sigma` where the turbulence was last read, which
    /// the predictor reuses where the scene allows it ([`Prepared::reuse_scale`]); `None`
    /// before the first read, and where the read gives none (the intermittent model).
    scale: Option<[f64; 3]>,
    /// A ball clear of the furnishings, made anew at a step's start wherever the old one no
    /// longer keeps them beyond the turbulence read's reach: where it keeps them beyond every
    /// reach a step asks about, the step skips them.
    pub clearance: Clearance,
    /// Airborne time so far in the near-floor layer ([`Record::near_floor`]), s.
    pub near_floor: f64,
}

impl Flyer {
    /// Particle `id` as injected.
    pub fn inject(p: &Prepared<'_>, id: u64, turb: bool, brown: bool) -> Self {
        let Injected { body, start, x, v, zeta, normals, end } = inject(p, id, turb, brown);
        let air = &p.scene.air;
        let lift_coefficient = 9.69 / std::f64::consts::PI * (air.density * air.viscosity).sqrt()
            / (p.injection.density * body.aero.diameter);
        Self {
            body,
            base: body,
            start,
            x: DVec3::from_array(x),
            v: DVec3::from_array(v),
            zeta,
            end,
            draws: StepNormals::new(normals),
            lift_coefficient,
            flow_cell: FlowCell::NONE,
            scale: None,
            clearance: Clearance::NONE,
            near_floor: 0.0,
        }
    }

    /// The same particle with fresh random streams from `normals`, from step `n` on.
    pub fn with_streams(&self, normals: Normals, n: usize, per_step: usize) -> Self {
        Self { draws: StepNormals::starting_at(normals, n, per_step), ..self.clone() }
    }

    /// The record of a particle still in the air after its [`Flyer::end`] steps: exhausted then,
    /// or airborne at the end of the run.
    pub fn finish(&self, p: &Prepared<'_>) -> Record {
        let fate = if self.end < p.steps { Fate::Exhausted } else { Fate::Airborne };
        self.record(fate, self.end as f64 * p.settings.dt, self.x, self.end as u64)
    }

    /// The record of this particle's end.
    pub fn record(&self, fate: Fate, time: f64, at: DVec3, steps: u64) -> Record {
        Record {
            fate,
            time,
            start: self.start,
            position: at.to_array(),
            diameter: self.body.aero.diameter,
            mass: self.body.aero.mass,
            steps,
            near_floor: self.near_floor,
        }
    }

    /// Where the particle would be half a step on from `x` with velocity `v`, flying towards
    /// the fluid velocity seen at `x` (its fluctuation as it stands) plus its settling: the
    /// exponential scheme's exact flight for that constant target, without Brownian motion
    /// or lift; `x` itself where that leaves the fluid. [`Scheme::Midpoint`]'s predictor. Where
    /// the scene reuses the scale ([`Prepared::reuse_scale`]) the fluctuation is `g sigma` of
    /// the last read times the current `zeta`, without reading the profiles at `x`.
    fn half_step_position(&mut self, p: &Prepared<'_>, x: DVec3, v: DVec3) -> DVec3 {
        let field = &p.field;
        let mut u0 = match self.scale.filter(|_| p.reuse_scale) {
            Some(scale) => DVec3::from_array(field.uniform) + DVec3::from_array(scale) * DVec3::from_array(self.zeta),
            None if p.boxes.is_empty() => fluid_velocity::<true>(field, p.size, x, &self.zeta),
            None => {
                let mut zeta = self.zeta;
                let boxes = self.clearance.near(p.boxes, x.to_array(), field.turbulence_flat_from);
                furnished_fluid_velocity(field, p.size, boxes, x, &mut zeta, None).0
            }
        };
        if let Some(mean) = &p.mean_flow {
            u0 += DVec3::from_array(mean.velocity_in(x.to_array(), &mut self.flow_cell));
        }
        let target = u0 + self.body.settling;
        // Over h = dt / 2: x + target h + (v - target) tau (1 - exp(-h / tau)).
        let h = 0.5 * p.dt;
        let half = x + target * h + (v - target) * self.body.half_relax;
        // A box grown by `contact` along each axis reaches `sqrt(3) contact` at its corners.
        let reach = 2.0 * self.body.contact;
        if inside(half, self.body.contact, p, self.clearance.near(p.boxes, half.to_array(), reach)) {
            half
        } else {
            x
        }
    }

    /// Step `n` (from 0, in order) of the run: the fluid velocity seen, the drag relaxation,
    /// Brownian motion and the wall contacts within the step.
    #[inline(always)]
    pub fn step<const BROWN: bool, const TURB: bool, const FINITE_RE: bool, const EULER: bool, const LIFT: bool>(
        &mut self,
        p: &Prepared<'_>,
        n: usize,
        tally: &mut [WallTally],
    ) -> Step {
        let scene = p.scene;
        let field = &p.field;
        let dt = p.dt;
        let (brownian_start, per_step) = normals_per_step(TURB, BROWN, EULER);
        let (x, v) = (self.x, self.v);
        // A read skips the boxes beyond `turbulence_flat_from`: a ball that keeps them beyond
        // it about `x` likely keeps them so about where this step reads and ends, too.
        let reads = field.turbulence_flat_from;
        if !p.boxes.is_empty() && !self.clearance.keeps(x.to_array(), reads) {
            self.clearance = Clearance::around(x.to_array(), p.boxes);
        }
        // Where the flow is read: the start of the step, or half a step on (`Scheme::Midpoint`).
        let at = if TURB && p.midpoint { self.half_step_position(p, x, v) } else { x };
        let z = self.draws.step(n, per_step);
        let (mut uf, scale) = if !p.boxes.is_empty() {
            let normals = TURB.then(|| [z[0], z[1], z[2]]);
            let boxes = self.clearance.near(p.boxes, at.to_array(), reads);
            let (u, scale) = furnished_fluid_velocity(field, p.size, boxes, at, &mut self.zeta, normals);
            (u, Some(scale))
        } else if TURB {
            match &field.intermittent {
                None => {
                    let (u, scale) =
                        fluid_velocity_and_fluctuation(field, p.size, at, &mut self.zeta, [z[0], z[1], z[2]]);
                    (u, Some(scale))
                }
                Some(model) => {
                    (intermittent_fluid_velocity(field, model, p.size, at, &mut self.zeta, [z[0], z[1], z[2]]), None)
                }
            }
        } else {
            (fluid_velocity::<false>(field, p.size, x, &self.zeta), None)
        };
        self.scale = scale;
        if let Some(mean) = &p.mean_flow {
            uf += DVec3::from_array(mean.velocity_in(at.to_array(), &mut self.flow_cell));
        }
        let body = &mut self.body;
        if FINITE_RE {
            let nu = scene.air.kinematic_viscosity();
            let re = (uf - v).length() * body.aero.diameter / nu;
            body.relax_in(self.base.tau / schiller_naumann(re), dt);
        }
        let mut v_inf = uf + body.settling;
        if LIFT {
            v_inf.z += body.tau * saffman_lift(field, p.size, x, uf, v, self.lift_coefficient);
        }
        let (bx, bv) = if BROWN {
            let mut bx = DVec3::ZERO;
            let mut bv = DVec3::ZERO;
            let z = &z[brownian_start..];
            for a in 0..3 {
                if EULER {
                    // Euler-Maruyama: velocity kick of variance 2 kT/m dt/tau; position from v.
                    bv[a] = (2.0 * body.thermal_variance * dt / body.tau).sqrt() * z[a];
                } else {
                    (bx[a], bv[a]) = brownian_increment(body.brownian, z[2 * a], z[2 * a + 1]);
                }
            }
            (bx, bv)
        } else {
            (DVec3::ZERO, DVec3::ZERO)
        };
        let flight =
            Flight::<EULER> { x0: x, v0: v, v_inf, tau: body.tau, decay: body.decay, relax: body.relax, dt, bx, bv };
        let (x1, v1) = flight.end();
        if inside(x1, body.contact, p, self.clearance.near(p.boxes, x1.to_array(), 2.0 * body.contact)) {
            self.x = wrap(x1, p);
            self.v = v1;
            if !(self.x.is_finite() && self.v.is_finite()) {
                return Step::Left(Fate::Escaped, dt, self.x);
            }
            self.near_floor += if self.x.z < p.near_floor { dt } else { 0.0 };
            return Step::Airborne;
        }
        match contacts::<EULER>(p, body, flight, State { x, v, zeta: self.zeta }, at, tally) {
            AfterContacts::Airborne(s) => {
                (self.x, self.v, self.zeta) = (s.x, s.v, s.zeta);
                self.near_floor += if self.x.z < p.near_floor { dt } else { 0.0 };
                Step::Airborne
            }
            AfterContacts::Left(fate, t, at) => Step::Left(fate, t, at),
        }
    }
}

fn run_particle<const BROWN: bool, const TURB: bool, const FINITE_RE: bool, const EULER: bool, const LIFT: bool>(
    p: &Prepared<'_>,
    id: u64,
    tally: &mut [WallTally],
) -> Record {
    let dt = p.settings.dt;
    let mut flyer = Flyer::inject(p, id, TURB, BROWN);
    for n in 0..flyer.end {
        if p.stopped_at(n) {
            break; // an incomplete record, which the stopped run discards
        }
        if let Step::Left(fate, t, at) = flyer.step::<BROWN, TURB, FINITE_RE, EULER, LIFT>(p, n, tally) {
            return flyer.record(fate, n as f64 * dt + t, at, n as u64 + 1);
        }
    }
    flyer.finish(p)
}

/// Where a step's Brownian normals start among its variates, and how many it draws: three for
/// the fluctuations when turbulent, then two per axis for Brownian motion (one with Euler).
fn normals_per_step(turb: bool, brown: bool, euler: bool) -> (usize, usize) {
    let brownian_start = if turb { 3 } else { 0 };
    let brownian = match (brown, euler) {
        (false, _) => 0,
        (true, true) => 3,
        (true, false) => 6,
    };
    (brownian_start, brownian_start + brownian)
}

/// A particle's normal variates for its steps, made [`STEPS_PER_BLOCK`] steps at a time.
#[derive(Clone)]
struct StepNormals {
    normals: Normals,
    block: [f64; 9 * STEPS_PER_BLOCK],
}

impl StepNormals {
    fn new(normals: Normals) -> Self {
        Self { normals, block: [0.0; 9 * STEPS_PER_BLOCK] }
    }

    /// Streams for a particle that starts at step `n` (not necessarily a block's first): the
    /// block holding step `n` is made now, from `normals`.
    fn starting_at(mut normals: Normals, n: usize, per_step: usize) -> Self {
        let mut block = [0.0; 9 * STEPS_PER_BLOCK];
        if per_step > 0 && n % STEPS_PER_BLOCK != 0 {
            normals.fill(&mut block[..per_step * STEPS_PER_BLOCK]);
        }
        Self { normals, block }
    }

    /// The variates of step `n`, its `per_step` ones first (steps taken in order from 0, the
    /// same `per_step` each time: a constant of the caller, which the compiler folds into the
    /// indexing). The view is always nine long, so that constant indices need no bounds
    /// check; past `per_step` it shows later steps' variates, or stale ones.
    #[inline(always)]
    fn step(&mut self, n: usize, per_step: usize) -> &[f64; 9] {
        if n % STEPS_PER_BLOCK == 0 && per_step > 0 {
            self.normals.fill(&mut self.block[..per_step * STEPS_PER_BLOCK]);
        }
        let at = (n % STEPS_PER_BLOCK) * per_step;
        self.block[at..at + 9].try_into().expect("nine variates within the block")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn brownian_step_has_the_ornstein_uhlenbeck_moments() {
        let (tau, kt) = (2.0, 3.0);
        for h in [1e-4, 0.01, 0.049, 0.051, 1.0, 30.0] {
            let [sx, cxv, sv] = brownian_coefficients(h, tau, kt);
            let e = (-h).exp();
            // The same shape written with expm1: it cancels to ~1e-16 / h^2 relative only.
            let var_x = kt * tau * tau * (2.0 * h + 4.0 * (-h).exp_m1() - (-2.0 * h).exp_m1());
            let var_v = kt * (1.0 - e * e);
            let cov = kt * tau * (1.0 - e) * (1.0 - e);
            let tol = if h < 0.05 { 1e-8 } else { 1e-10 };
            assert!((sx * sx - var_x).abs() <= tol * var_x.abs() + 1e-300, "h {h}");
            assert!((sx * cxv - cov).abs() <= 1e-10 * cov, "h {h}");
            assert!((cxv * cxv + sv * sv - var_v).abs() <= 1e-10 * var_v, "h {h}");
        }
        // Large h: position variance tends to 2 D dt with D = kT/m tau.
        let [sx, ..] = brownian_coefficients(1e6, tau, kt);
        assert!((sx * sx / (2.0 * kt * tau * tau * 1e6) - 1.0).abs() < 1e-5);
    }

    #[test]
    fn a_room_s_predictor_reuses_the_last_read_s_scale() {
        // With the scale read where the particle stands, the predictor that reuses it is the
        // fresh one (to rounding: `g sigma` is multiplied in another order): the scale is each
        // component's `g sigma` and nothing else. Near the floor and, furnished, a table's top,
        // where the profiles change.
        for furnished in [false, true] {
            let mut scene = Scene::new(crate::Geometry::Room { size: [4.0, 3.0, 2.5] });
            scene.flow = Flow::indoor_room();
            scene.brownian = true;
            let settings = RunSettings { scheme: Scheme::Midpoint, ..RunSettings::new(0.1, 10.0) };
            if furnished {
                scene.furnishings = vec![Furnishing::new([1.0, 1.0, 0.7], [2.0, 1.5, 0.75])];
            }
            let injection = Injection::new(10, SizeDistribution::Monodisperse { diameter: 1e-6 }, 1000.0);
            let p = Prepared::new(&scene, &settings, &injection).unwrap();
            assert!(p.reuse_scale);
            let mut tally = vec![WallTally::default(); p.surfaces.len()];
            let mut flyer = Flyer::inject(&p, 3, true, true);
            assert_eq!(flyer.scale, None);
            let _ = flyer.step::<true, true, false, false, false>(&p, 0, &mut tally);
            assert!(flyer.scale.is_some(), "a step keeps its read's scale");
            // The predictor takes it: with a zero scale it is the flight without turbulence.
            let (x, v) = (flyer.x, flyer.v);
            let kept = flyer.scale;
            flyer.scale = Some([0.0; 3]);
            let still = flyer.half_step_position(&p, x, v);
            flyer.zeta = [0.0; 3];
            flyer.scale = None;
            assert!((flyer.half_step_position(&p, x, v) - still).length() < 1e-15);
            flyer.scale = kept;
            for (x, zeta) in [([1.5, 1.2, 0.78], [0.7, -1.3, 0.4]), ([3.0, 2.9, 0.02], [-0.2, 0.9, -1.1])] {
                let x = DVec3::from_array(x);
                flyer.zeta = zeta;
                let v = DVec3::new(0.01, -0.02, 0.005);
                let (_, scale) = if furnished {
                    furnished_fluid_velocity(&p.field, p.size, p.boxes, x, &mut flyer.zeta.clone(), None)
                } else {
                    fluid_velocity_and_fluctuation(&p.field, p.size, x, &mut flyer.zeta.clone(), [0.0; 3])
                };
                flyer.scale = Some(scale);
                let reused = flyer.half_step_position(&p, x, v);
                flyer.scale = None;
                let fresh = flyer.half_step_position(&p, x, v);
                assert!((reused - fresh).length() < 1e-15, "{reused} {fresh}");
                assert!((fresh - x).length() > 1e-4, "the fluctuation moves it: {fresh} {x}");
            }
        }
        // A channel's predictor reads afresh (its mean profile and correlated components):
        // a scale planted in its flyer changes nothing.
        let mut channel = Scene::new(crate::Geometry::Channel { length: 0.1, width: 0.05, height: 0.02 });
        channel.flow = Flow::TurbulentChannel { friction_velocity: 0.5 };
        let settings = RunSettings { scheme: Scheme::Midpoint, ..RunSettings::new(1e-4, 0.01) };
        let injection = Injection::new(10, SizeDistribution::Monodisperse { diameter: 1e-6 }, 1000.0);
        let p = Prepared::new(&channel, &settings, &injection).unwrap();
        assert!(!p.reuse_scale);
        let mut flyer = Flyer::inject(&p, 3, true, false);
        let (x, v) = (flyer.x, flyer.v);
        let fresh = flyer.half_step_position(&p, x, v);
        flyer.scale = Some([0.0; 3]);
        assert_eq!(flyer.half_step_position(&p, x, v), fresh);
    }

    #[test]
    fn series_and_formula_agree_where_they_meet() {
        let h: f64 = 0.05;
        let series = h * h * h * (2.0 / 3.0 - h * (0.5 - h * (7.0 / 30.0 - h * (1.0 / 12.0 - h * 31.0 / 1260.0))));
        let formula = 2.0 * h - 3.0 + 4.0 * (-h).exp() - (-2.0 * h).exp();
        assert!((series / formula - 1.0).abs() < 1e-7, "{series} {formula}");
    }
}
