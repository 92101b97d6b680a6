//! One particle through a whole run: the step (drag relaxation, gravity, Brownian motion,
//! turbulent dispersion), the wall contacts within a step, and the particle's fate.
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
//! (`fly_freely`), a loop of a dozen vector operations per step. (An earlier eight-lane
//! structure-of-arrays variant, with a Box-Muller generator, measured slower and was not kept.)

use depo_wall_model::energy::{energy_loss, EnergyLoss};
use glam::DVec3;
use multiversion::multiversion;
use multiversion::target::target_cfg_f;
use rand::{Rng, RngExt};
use rand_distr::{Distribution, LogNormal};

use crate::air::{schiller_naumann, Aerodynamics};
#[cfg(doc)]
use crate::flow::Table;
use crate::flow::{Component, FlowField, Node};
use crate::geometry::Wall;
use crate::noise::{particle_rng, Normals};
use crate::scene::{Drag, Injection, Scene, Scheme, SizeDistribution, WallBehaviour};

/// Contacts allowed in one step before a bouncing particle counts as resting on the wall.
pub const MAX_CONTACTS: usize = 32;
/// Steps whose normal variates are made in one block (a multiple of four variates for any
/// scene).
const STEPS_PER_BLOCK: usize = 16;
/// Bisection steps for a contact time (to well below 1e-12 of the step).
const BISECTIONS: usize = 48;

/// What became of a particle by the end of the run.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Fate {
    /// Still in the air.
    Airborne,
    /// Deposited on the wall with this id.
    Deposited(usize),
    /// Lost to the statistics: a non-finite state or a contact the wall law flagged invalid.
    Escaped,
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
}

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
    pub injection: &'a Injection,
    pub field: FlowField,
    pub walls: Vec<Wall>,
    pub size: [f64; 3],
    pub walled: [bool; 3],
    /// Per axis, the walls' coordinates (`0` and the size), infinite along periodic axes.
    pub lower: [f64; 3],
    pub upper: [f64; 3],
    /// True when some axis is periodic.
    pub periodic: bool,
    pub steps: usize,
}

impl<'a> Prepared<'a> {
    pub fn new(scene: &'a Scene, injection: &'a Injection) -> Self {
        let size = scene.geometry.size();
        let nu = scene.air.kinematic_viscosity();
        let walled = scene.geometry.walled();
        Self {
            scene,
            injection,
            field: FlowField::new(&scene.flow, size, nu, scene.dt, scene.drift_correction),
            walls: scene.geometry.walls(),
            size,
            walled,
            lower: walled.map(|w| if w { 0.0 } else { f64::NEG_INFINITY }),
            upper: std::array::from_fn(|a| if walled[a] { size[a] } else { f64::INFINITY }),
            periodic: walled.contains(&false),
            steps: scene.steps(),
        }
    }
}

/// The per-particle constants of a run.
#[derive(Clone, Copy, Debug)]
struct Body {
    aero: Aerodynamics,
    radius: f64,
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
    /// Brownian step: `x = sx a`, `v = cxv a + sv b` for standard normals `a, b`.
    brownian: [f64; 3],
    /// Thermal velocity variance per axis `kT/m`, m^2/s^2.
    thermal_variance: f64,
}

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
            gravity: g * buoyancy,
            tau: 0.0,
            settling: DVec3::ZERO,
            decay: 0.0,
            relax: 0.0,
            brownian: [0.0; 3],
            thermal_variance: kt,
        };
        body.relax_in(aero.relaxation_time, scene.dt);
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
struct State {
    x: DVec3,
    v: DVec3,
    zeta: [f64; 3],
}

/// Tracks particles `ids` through the run, adding their wall contacts to `tally`.
pub(crate) fn track(p: &Prepared<'_>, ids: std::ops::Range<usize>, tally: &mut [WallTally]) -> Vec<Record> {
    let scene = p.scene;
    let brown = scene.brownian;
    let turb = p.field.turbulence.is_some();
    let finite_re = scene.drag == Drag::SchillerNaumann;
    let euler = scene.scheme == Scheme::Euler;
    let lift = scene.lift && p.field.profile.is_some();
    // One monomorphised loop per combination of what the scene needs, chosen once for all the
    // particles: each flag becomes a const generic, and the loop carries no code for a force
    // left out. Turbulent scenes with the common options step particles side by side.
    // (Lanes pay where there are look-ups to overlap, or where the forcing is constant and they
    // fly freely; a scene with Brownian motion alone, or a laminar profile, runs faster one
    // particle at a time.)
    let free = !(brown || turb) && p.field.profile.is_none();
    if (turb || free) && !(finite_re || euler || lift) {
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
}

/// Particle `id` at `t = 0`: size, position, velocity (and fluctuation) from its own stream.
fn inject(p: &Prepared<'_>, id: u64, turb: bool, brown: bool) -> Injected {
    let mut rng = particle_rng(p.scene.seed, id);
    let diameter = sample_diameter(p.injection.size, &mut rng);
    let body = Body::new(p, diameter);
    let r = body.radius;
    let (lo, hi) = p.injection.region.unwrap_or(([0.0; 3], p.size));
    let mut start = [0.0; 3];
    for a in 0..3 {
        let (l, h) = if p.walled[a] { (lo[a].max(r), hi[a].min(p.size[a] - r)) } else { (lo[a], hi[a]) };
        start[a] = if h > l { rng.random_range(l..h) } else { 0.5 * (l + h) };
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
    let mut v = match p.injection.velocity {
        Some(v) => DVec3::from_array(v),
        None => fluid_velocity::<true>(&p.field, p.size, x, &zeta) + body.settling,
    };
    if brown {
        let sd = body.thermal_variance.sqrt();
        v += DVec3::new(z[3], z[4], z[5]) * sd;
    }
    Injected { body, start, x: start, v: v.to_array(), zeta, normals }
}

fn run_particle<const BROWN: bool, const TURB: bool, const FINITE_RE: bool, const EULER: bool, const LIFT: bool>(
    p: &Prepared<'_>,
    id: u64,
    tally: &mut [WallTally],
) -> Record {
    let scene = p.scene;
    let field = &p.field;
    let dt = scene.dt;
    let nu = scene.air.kinematic_viscosity();
    let Injected { mut body, start, x, v, zeta, normals } = inject(p, id, TURB, BROWN);
    let (brownian_start, per_step) = normals_per_step(TURB, BROWN, EULER);
    let mut draws = StepNormals::new(normals);
    let (mut x, mut v, mut zeta) = (DVec3::from_array(x), DVec3::from_array(v), zeta);
    let diameter = body.aero.diameter;
    let r = body.radius;
    let base = body;
    // Saffman's lift per unit relative velocity and root shear rate, (9.69/pi) sqrt(rho mu) /
    // (rho_p d).
    let lift_coefficient = 9.69 / std::f64::consts::PI * (scene.air.density * scene.air.viscosity).sqrt()
        / (p.injection.density * diameter);

    let mass = body.aero.mass;
    let record = |fate: Fate, time: f64, x: DVec3, steps: u64| Record {
        fate,
        time,
        start,
        position: x.to_array(),
        diameter,
        mass,
        steps,
    };

    for n in 0..p.steps {
        let t0 = n as f64 * dt;
        let z = draws.step(n, per_step);
        let uf = if TURB {
            fluid_velocity_and_fluctuation(field, p.size, x, &mut zeta, [z[0], z[1], z[2]])
        } else {
            fluid_velocity::<false>(field, p.size, x, &zeta)
        };
        if FINITE_RE {
            let re = (uf - v).length() * diameter / nu;
            body.relax_in(base.tau / schiller_naumann(re), dt);
        }
        let mut v_inf = uf + body.settling;
        if LIFT {
            v_inf.z += body.tau * saffman_lift(field, p.size, x, uf, v, lift_coefficient);
        }
        let (bx, bv) = if BROWN {
            let mut bx = DVec3::ZERO;
            let mut bv = DVec3::ZERO;
            let z = &z[brownian_start..];
            for a in 0..3 {
                if EULER {
                    let za = z[a];
                    // Euler-Maruyama: velocity kick of variance 2 kT/m dt/tau; position from v.
                    bv[a] = (2.0 * body.thermal_variance * dt / body.tau).sqrt() * za;
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
        if inside(x1, r, p) {
            x = wrap(x1, p);
            v = v1;
            if !(x.is_finite() && v.is_finite()) {
                return record(Fate::Escaped, t0 + dt, x, n as u64 + 1);
            }
            continue;
        }
        match contacts::<EULER>(p, &body, flight, State { x, v, zeta }, tally) {
            AfterContacts::Airborne(s) => (x, v, zeta) = (s.x, s.v, s.zeta),
            AfterContacts::Left(fate, t, at) => return record(fate, t0 + t, at, n as u64 + 1),
        }
    }
    record(Fate::Airborne, p.steps as f64 * dt, x, p.steps as u64)
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
struct StepNormals {
    normals: Normals,
    block: [f64; 9 * STEPS_PER_BLOCK],
}

impl StepNormals {
    fn new(normals: Normals) -> Self {
        Self { normals, block: [0.0; 9 * STEPS_PER_BLOCK] }
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

/// Particles stepped side by side by [`run_lanes`].
const WIDTH: usize = 4;

/// A particle in one of [`run_lanes`]' lanes: what the step itself does not need.
struct Lane {
    id: u64,
    body: Body,
    start: [f64; 3],
    draws: StepNormals,
}

/// [`run_particle`] for turbulent scenes, and for scenes of constant forcing, with the
/// exponential scheme, Stokes drag and no lift, [`WIDTH`] particles at a time. Their states
/// sit side by side (one array per coordinate) and each part of the step runs for all lanes
/// before the next, so the compiler vectorises the arithmetic across lanes and the processor
/// overlaps the lanes' table look-ups, where one particle alone, each step waiting on the
/// last, leaves it idle (the turbulent Brownian bench scene: 34 -> 37.5 million
/// particle-steps/s on 2 cores). Where the processor has AVX2 the whole step before the walls
/// is [`step_lanes_avx2`] (its look-ups alone, [`Table::at4`] in AVX2, had taken the step from
/// 303 to 288 instructions per particle-step). Under constant forcing, whenever every lane
/// holds a particle they fly freely ([`fly_freely`]) up to the next step that needs more. (With Brownian motion
/// alone, or a laminar profile, there are no look-ups to overlap and no free flight, and one
/// particle at a time is faster: `track` does not send such scenes here.) A step that ends
/// for every lane in the air, without a contact or a wrap, is taken for all lanes at once
/// (13 % fewer instructions in the turbulent bench scene, about 3 % less time). Each
/// particle takes exactly the steps, random numbers and contacts it takes alone (a lane whose
/// particle is done takes the next one), so the records are identical to [`run_particle`]'s
/// (tested); only the order in which contacts add their energies to the tallies differs.
#[multiversion(targets("x86_64+avx2+fma"))]
fn run_lanes<const BROWN: bool, const TURB: bool>(
    p: &Prepared<'_>,
    ids: std::ops::Range<usize>,
    tally: &mut [WallTally],
) -> Vec<Record> {
    // True in the build of this function for processors with AVX2.
    const AVX2: bool = target_cfg_f!(all(target_arch = "x86_64", target_feature = "avx2"));
    lanes::<BROWN, TURB, AVX2>(p, ids, tally)
}

/// The body of [`run_lanes`], with its AVX2 parts on when `AVX2` (which the caller may set
/// only where the processor has AVX2). Inlined into each build of `run_lanes`; the tests also
/// run it with `AVX2` off, the path of processors without it.
#[inline(always)]
fn lanes<const BROWN: bool, const TURB: bool, const AVX2: bool>(
    p: &Prepared<'_>,
    ids: std::ops::Range<usize>,
    tally: &mut [WallTally],
) -> Vec<Record> {
    if p.steps == 0 {
        return ids.map(|id| run_particle::<BROWN, TURB, false, false, false>(p, id as u64, tally)).collect();
    }
    let dt = p.scene.dt;
    let field = &p.field;
    let first = ids.start;
    let mut records: Vec<Option<Record>> = vec![None; ids.len()];
    let mut next = ids.start;
    let (brownian_start, per_step) = normals_per_step(TURB, BROWN, false);

    let mut lanes: [Option<Lane>; WIDTH] = Default::default();
    let (mut x, mut v, mut zeta) = ([[0.0; WIDTH]; 3], [[0.0; WIDTH]; 3], [[0.0; WIDTH]; 3]);
    let mut settling = [[0.0; WIDTH]; 3];
    let (mut decay, mut relax, mut radius) = ([0.0; WIDTH], [0.0; WIDTH], [0.0; WIDTH]);
    let mut brownian = [[0.0; WIDTH]; 3];
    // Steps taken, and the box each lane's position must stay in for a step to end without a
    // contact and without being wrapped ([`free_bounds`]).
    let mut n = [0usize; WIDTH];
    let (mut lo, mut hi) = ([[0.0; WIDTH]; 3], [[0.0; WIDTH]; 3]);

    let record = |lane: &Lane, fate: Fate, time: f64, at: [f64; 3], steps: u64| Record {
        fate,
        time,
        start: lane.start,
        position: at,
        diameter: lane.body.aero.diameter,
        mass: lane.body.aero.mass,
        steps,
    };

    // Some lane is empty (and may take the next particle).
    let mut vacant = true;
    loop {
        // Empty lanes take the next particles.
        for l in (0..WIDTH).filter(|_| vacant) {
            if lanes[l].is_none() && next < ids.end {
                let id = next as u64;
                next += 1;
                let Injected { body, start, x: x0, v: v0, zeta: z0, normals } = inject(p, id, TURB, BROWN);
                for a in 0..3 {
                    (x[a][l], v[a][l], zeta[a][l], settling[a][l]) = (x0[a], v0[a], z0[a], body.settling[a]);
                    (lo[a][l], hi[a][l]) = free_bounds(p, a, body.radius);
                }
                (decay[l], relax[l], radius[l], n[l]) = (body.decay, body.relax, body.radius, 0);
                for (k, b) in body.brownian.into_iter().enumerate() {
                    brownian[k][l] = b;
                }
                lanes[l] = Some(Lane { id, body, start, draws: StepNormals::new(normals) });
            }
        }
        if vacant && lanes.iter().all(Option::is_none) {
            break;
        }
        vacant = lanes.iter().any(Option::is_none);

        if !(TURB || BROWN || vacant) && field.profile.is_none() {
            // Constant forcing: every lane flies freely until one is due for more than that.
            let left = n.iter().map(|&n| p.steps - 1 - n).min().unwrap_or(0);
            let mut v_inf = [[0.0; WIDTH]; 3];
            for a in 0..3 {
                for l in 0..WIDTH {
                    v_inf[a][l] = field.uniform[a] + settling[a][l];
                }
            }
            let taken = fly_freely::<AVX2>(&mut x, &mut v, FreeLanes { v_inf, decay, relax, lo, hi, dt }, left);
            for n in &mut n {
                *n += taken;
            }
        }

        // This step's normal variates, read where each lane's block holds them (copying them
        // into one array first cost more than the reads it saved).
        let mut z: [&[f64; 9]; WIDTH] = [&[0.0; 9]; WIDTH];
        for ((z, lane), &n) in z.iter_mut().zip(&mut lanes).zip(&n) {
            if let Some(lane) = lane {
                *z = lane.draws.step(n, per_step);
            }
        }

        // The step, for all lanes at once (an empty lane computes on stale values, unused).
        let constants = LaneConstants { settling: &settling, decay: &decay, relax: &relax, brownian: &brownian, dt };
        let step = (field, p.size, brownian_start);
        let Stepped { uf, x1, v1, bx, bv } = step_lanes::<BROWN, TURB, AVX2>(&x, &v, &mut zeta, &z, constants, step);

        // The common step, for all lanes at once: every lane holds a particle, and each step
        // ends inside its free box (no contact, nothing to wrap), with a finite velocity, before
        // the particle's last step. It is what the general path below does in that case.
        if !vacant {
            let mut plain = ends_free::<AVX2>(&x1, &v1, &lo, &hi);
            for &n in &n {
                plain &= n + 1 < p.steps;
            }
            if plain {
                (x, v) = (x1, v1);
                for n in &mut n {
                    *n += 1;
                }
                continue;
            }
        }

        let mut ok = [true; WIDTH];
        for l in 0..WIDTH {
            ok[l] = inside(DVec3::new(x1[0][l], x1[1][l], x1[2][l]), radius[l], p);
        }

        // What each particle does with its step.
        for l in 0..WIDTH {
            let Some(lane) = &mut lanes[l] else { continue };
            let taken = n[l];
            n[l] += 1;
            let t0 = taken as f64 * dt;
            let done = if ok[l] {
                let xw = wrap(DVec3::new(x1[0][l], x1[1][l], x1[2][l]), p);
                let vw = DVec3::new(v1[0][l], v1[1][l], v1[2][l]);
                for a in 0..3 {
                    (x[a][l], v[a][l]) = (xw[a], vw[a]);
                }
                if !(xw.is_finite() && vw.is_finite()) {
                    Some(record(lane, Fate::Escaped, t0 + dt, xw.to_array(), taken as u64 + 1))
                } else {
                    None
                }
            } else {
                let body = &lane.body;
                let flight = Flight::<false> {
                    x0: DVec3::new(x[0][l], x[1][l], x[2][l]),
                    v0: DVec3::new(v[0][l], v[1][l], v[2][l]),
                    v_inf: DVec3::new(uf[0][l], uf[1][l], uf[2][l]) + body.settling,
                    tau: body.tau,
                    decay: body.decay,
                    relax: body.relax,
                    dt,
                    bx: DVec3::new(bx[0][l], bx[1][l], bx[2][l]),
                    bv: DVec3::new(bv[0][l], bv[1][l], bv[2][l]),
                };
                let state = State { x: flight.x0, v: flight.v0, zeta: [zeta[0][l], zeta[1][l], zeta[2][l]] };
                match contacts::<false>(p, body, flight, state, tally) {
                    AfterContacts::Airborne(s) => {
                        for a in 0..3 {
                            (x[a][l], v[a][l], zeta[a][l]) = (s.x[a], s.v[a], s.zeta[a]);
                        }
                        None
                    }
                    AfterContacts::Left(fate, t, at) => {
                        Some(record(lane, fate, t0 + t, at.to_array(), taken as u64 + 1))
                    }
                }
            };
            let done = done.or_else(|| {
                (n[l] == p.steps).then(|| {
                    record(lane, Fate::Airborne, p.steps as f64 * dt, [x[0][l], x[1][l], x[2][l]], p.steps as u64)
                })
            });
            if let Some(rec) = done {
                records[lane.id as usize - first] = Some(rec);
                lanes[l] = None;
                vacant = true;
            }
        }
    }
    records.into_iter().map(|r| r.expect("every particle recorded")).collect()
}

/// The per-lane constants a step of [`run_lanes`] needs, side by side.
#[derive(Clone, Copy)]
struct LaneConstants<'a> {
    settling: &'a [[f64; WIDTH]; 3],
    decay: &'a [f64; WIDTH],
    relax: &'a [f64; WIDTH],
    brownian: &'a [[f64; WIDTH]; 3],
    dt: f64,
}

/// The scene's part of a step: the flow, the domain's size (m) and where the Brownian
/// variates start among a step's variates.
type StepScene<'a> = (&'a FlowField, [f64; 3], usize);

/// One step of [`run_lanes`]' four lanes, before any wall: the fluid velocity seen `uf`, the
/// position and velocity at the step's end, and the Brownian increments (for the contact
/// search of a lane that meets a wall). The lanes' `zeta` are advanced.
struct Stepped {
    uf: [[f64; WIDTH]; 3],
    x1: [[f64; WIDTH]; 3],
    v1: [[f64; WIDTH]; 3],
    bx: [[f64; WIDTH]; 3],
    bv: [[f64; WIDTH]; 3],
}

/// The step of [`run_lanes`] as [`run_particle`] takes it, lane by lane: [`fluid_velocity`],
/// [`fluctuation`] (four [`Table::at`]s through [`Table::at4`]), [`brownian_increment`] and
/// [`relaxed`]. With `AVX2` (set only where the processor has it) a turbulent scene's step is
/// [`step_lanes_avx2`].
#[inline(always)]
fn step_lanes<const BROWN: bool, const TURB: bool, const AVX2: bool>(
    x: &[[f64; WIDTH]; 3],
    v: &[[f64; WIDTH]; 3],
    zeta: &mut [[f64; WIDTH]; 3],
    z: &[&[f64; 9]; WIDTH],
    c: LaneConstants<'_>,
    scene: StepScene<'_>,
) -> Stepped {
    #[cfg(target_arch = "x86_64")]
    if AVX2 && TURB {
        // SAFETY: the caller sets `AVX2` only where the processor has AVX2.
        return unsafe { step_lanes_avx2::<BROWN>(x, v, zeta, z, c, scene) };
    }
    let (field, size, brownian_start) = scene;
    let LaneConstants { settling, decay, relax, brownian, dt } = c;
    let mut uf = [[0.0; WIDTH]; 3];
    for l in 0..WIDTH {
        let xl = DVec3::new(x[0][l], x[1][l], x[2][l]);
        let u = fluid_velocity::<false>(field, size, xl, &[0.0; 3]);
        for a in 0..3 {
            uf[a][l] = u[a];
        }
    }
    if let Some(turb) = field.turbulence.as_ref().filter(|_| TURB) {
        for (a, comp) in turb.iter().enumerate() {
            let (mut d, mut sign) = ([0.0; WIDTH], [0.0; WIDTH]);
            for l in 0..WIDTH {
                (d[l], sign[l]) = wall_distance(x[comp.axis][l], size[comp.axis]);
            }
            // (With AVX2 a turbulent step never gets here: it is `step_lanes_avx2`.)
            let nodes = comp.table.at4::<false>(d);
            for l in 0..WIDTH {
                let (du, next) = langevin_step(&nodes.lane(l), sign[l], zeta[a][l], z[l][a]);
                uf[a][l] += du;
                zeta[a][l] = next;
            }
        }
    }
    let (mut x1, mut v1) = ([[0.0; WIDTH]; 3], [[0.0; WIDTH]; 3]);
    let (mut bx, mut bv) = ([[0.0; WIDTH]; 3], [[0.0; WIDTH]; 3]);
    for a in 0..3 {
        for l in 0..WIDTH {
            if BROWN {
                let (za, zb) = (z[l][brownian_start + 2 * a], z[l][brownian_start + 2 * a + 1]);
                let coefficients = [brownian[0][l], brownian[1][l], brownian[2][l]];
                (bx[a][l], bv[a][l]) = brownian_increment(coefficients, za, zb);
            }
            let v_inf = uf[a][l] + settling[a][l];
            let relaxation = (dt, decay[l], relax[l]);
            (x1[a][l], v1[a][l]) = relaxed(x[a][l], v[a][l], v_inf, relaxation, bx[a][l], bv[a][l]);
        }
    }
    Stepped { uf, x1, v1, bx, bv }
}

/// [`step_lanes`] in AVX2 for turbulent scenes: the same operations in the same order on the
/// four lanes at once, so the same results bit for bit (the records of [`run_lanes`] are
/// tested identical to [`run_particle`]'s). The compiler's vectorisation of `step_lanes` mixed
/// 128- and 256-bit halves, gathered each variate lane by lane and kept the arrays on the
/// stack: 269 -> 240 instructions per particle-step in the turbulent Brownian room, and one
/// thread 1.08 times as fast (median of 8 alternating runs, 1.06-1.28).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn step_lanes_avx2<const BROWN: bool>(
    x: &[[f64; WIDTH]; 3],
    v: &[[f64; WIDTH]; 3],
    zeta: &mut [[f64; WIDTH]; 3],
    z: &[&[f64; 9]; WIDTH],
    c: LaneConstants<'_>,
    (field, size, brownian_start): StepScene<'_>,
) -> Stepped {
    use std::arch::x86_64::*;
    // SAFETY (both): each array holds four f64s.
    let load = |a: &[f64; WIDTH]| unsafe { _mm256_loadu_pd(a.as_ptr()) };
    let lanes = |v: __m256d| -> [f64; WIDTH] {
        let mut a = [0.0; WIDTH];
        unsafe { _mm256_storeu_pd(a.as_mut_ptr(), v) };
        a
    };
    let splat = |x: f64| _mm256_set1_pd(x);

    // The variates side by side: `normal[k]` is variate k of the four lanes (the first eight
    // by two 4 x 4 transposes, the ninth lane by lane).
    let mut normal = [_mm256_setzero_pd(); 9];
    for half in 0..if BROWN { 2 } else { 1 } {
        // SAFETY: each row holds nine f64s; these are its four from `4 * half`.
        let r = z.map(|row| unsafe { _mm256_loadu_pd(row.as_ptr().add(4 * half)) });
        let (t0, t1) = (_mm256_unpacklo_pd(r[0], r[1]), _mm256_unpackhi_pd(r[0], r[1]));
        let (t2, t3) = (_mm256_unpacklo_pd(r[2], r[3]), _mm256_unpackhi_pd(r[2], r[3]));
        normal[4 * half] = _mm256_permute2f128_pd::<0x20>(t0, t2);
        normal[4 * half + 1] = _mm256_permute2f128_pd::<0x20>(t1, t3);
        normal[4 * half + 2] = _mm256_permute2f128_pd::<0x31>(t0, t2);
        normal[4 * half + 3] = _mm256_permute2f128_pd::<0x31>(t1, t3);
    }
    if BROWN {
        normal[8] = _mm256_set_pd(z[3][8], z[2][8], z[1][8], z[0][8]);
    }

    // `wall_distance` of the lanes' coordinates along `axis`: the distance and the sign.
    let distance = |axis: usize| {
        let c = load(&x[axis]);
        let upper = _mm256_sub_pd(splat(size[axis]), c);
        let lower = _mm256_cmp_pd::<_CMP_LE_OQ>(c, upper);
        (_mm256_blendv_pd(upper, c, lower), _mm256_blendv_pd(splat(-1.0), splat(1.0), lower))
    };
    // `fluid_velocity` without turbulence: the uniform part, and the profile along `x`.
    let mut uf = field.uniform.map(splat);
    if let Some(profile) = &field.profile {
        let (d, _) = distance(2);
        uf[0] = _mm256_add_pd(uf[0], load(&profile.at4::<true>(lanes(d)).sigma));
    }
    // `fluctuation` of each component (`langevin_step`).
    for (a, comp) in field.turbulence.iter().flatten().enumerate() {
        let (d, sign) = distance(comp.axis);
        let node = comp.table.at4::<true>(lanes(d));
        let z0 = load(&zeta[a]);
        let du = _mm256_mul_pd(load(&node.sigma), z0);
        let drifted = _mm256_add_pd(_mm256_mul_pd(z0, load(&node.decay)), _mm256_mul_pd(sign, load(&node.drift)));
        zeta[a] = lanes(_mm256_add_pd(drifted, _mm256_mul_pd(load(&node.noise), normal[a])));
        uf[a] = _mm256_add_pd(uf[a], du);
    }
    // `brownian_increment` and `relaxed` along each axis.
    let [sx, cxv, sv] = c.brownian.map(|k| load(&k));
    let (dt, decay, relax) = (splat(c.dt), load(c.decay), load(c.relax));
    let mut out = Stepped {
        uf: [[0.0; WIDTH]; 3],
        x1: [[0.0; WIDTH]; 3],
        v1: [[0.0; WIDTH]; 3],
        bx: [[0.0; WIDTH]; 3],
        bv: [[0.0; WIDTH]; 3],
    };
    for a in 0..3 {
        let (bx, bv) = if BROWN {
            let (za, zb) = (normal[brownian_start + 2 * a], normal[brownian_start + 2 * a + 1]);
            (_mm256_mul_pd(sx, za), _mm256_add_pd(_mm256_mul_pd(cxv, za), _mm256_mul_pd(sv, zb)))
        } else {
            (_mm256_setzero_pd(), _mm256_setzero_pd())
        };
        let v_inf = _mm256_add_pd(uf[a], load(&c.settling[a]));
        let dv = _mm256_sub_pd(load(&v[a]), v_inf);
        let moved = _mm256_add_pd(_mm256_add_pd(load(&x[a]), _mm256_mul_pd(v_inf, dt)), _mm256_mul_pd(dv, relax));
        out.x1[a] = lanes(_mm256_add_pd(moved, bx));
        out.v1[a] = lanes(_mm256_add_pd(_mm256_add_pd(v_inf, _mm256_mul_pd(dv, decay)), bv));
        (out.uf[a], out.bx[a], out.bv[a]) = (lanes(uf[a]), lanes(bx), lanes(bv));
    }
    out
}

/// What [`fly_freely`] needs of its lanes: the constant velocity each relaxes to, the step's
/// constants, and the box each position must stay in for its step to be plain flight.
struct FreeLanes {
    v_inf: [[f64; WIDTH]; 3],
    decay: [f64; WIDTH],
    relax: [f64; WIDTH],
    lo: [[f64; WIDTH]; 3],
    hi: [[f64; WIDTH]; 3],
    dt: f64,
}

/// The coordinates along `axis` between which a sphere of radius `r` flies on without a
/// contact and without being wrapped: `[lower + r, upper - r]` across walls (the bounds of
/// [`inside`], rounded the same way) and `[0, size)` along a periodic axis (where [`wrap`]
/// leaves the coordinate as it is).
#[inline(always)]
fn free_bounds(p: &Prepared<'_>, axis: usize, r: f64) -> (f64, f64) {
    if p.walled[axis] {
        (p.lower[axis] + r, p.upper[axis] - r)
    } else {
        (0.0, f64::from_bits(p.size[axis].to_bits() - 1))
    }
}

/// Steps all lanes under constant forcing (no turbulence, no Brownian motion, uniform flow)
/// for at most `limit` steps, stopping before the first step after which some lane is outside
/// its [`FreeLanes`] box or not finite; returns the steps taken. Each step is [`relaxed`], as
/// in [`run_particle`], so the lanes end bit for bit where the general step would take them;
/// the loop keeps the lanes in registers and does nothing else (the drag-and-gravity bench
/// scene on 2 cores: 188 million particle-steps/s one particle at a time, 375 million here;
/// on one thread the AVX2 [`ends_free`] made it 1.6 times as fast again, median of six
/// alternating runs).
#[inline(always)]
fn fly_freely<const AVX2: bool>(
    x: &mut [[f64; WIDTH]; 3],
    v: &mut [[f64; WIDTH]; 3],
    c: FreeLanes,
    limit: usize,
) -> usize {
    let (mut xs, mut vs) = (*x, *v);
    let mut taken = 0;
    while taken < limit {
        let (mut x1, mut v1) = ([[0.0; WIDTH]; 3], [[0.0; WIDTH]; 3]);
        for a in 0..3 {
            for l in 0..WIDTH {
                (x1[a][l], v1[a][l]) =
                    relaxed(xs[a][l], vs[a][l], c.v_inf[a][l], (c.dt, c.decay[l], c.relax[l]), 0.0, 0.0);
            }
        }
        if !ends_free::<AVX2>(&x1, &v1, &c.lo, &c.hi) {
            break;
        }
        (xs, vs) = (x1, v1);
        taken += 1;
    }
    (*x, *v) = (xs, vs);
    taken
}

/// True when every lane's step ends inside its box `[lo, hi]` ([`free_bounds`]: no contact,
/// nothing to wrap) with a finite velocity. With `AVX2` (set only where the processor has
/// it) the twelve tests are ANDed as vector masks and read with one `movmsk`; the compiler
/// made about 45 instructions of packing out of the plain version.
#[inline(always)]
fn ends_free<const AVX2: bool>(
    x1: &[[f64; WIDTH]; 3],
    v1: &[[f64; WIDTH]; 3],
    lo: &[[f64; WIDTH]; 3],
    hi: &[[f64; WIDTH]; 3],
) -> bool {
    #[cfg(target_arch = "x86_64")]
    if AVX2 {
        // SAFETY: the caller sets `AVX2` only where the processor has AVX2.
        return unsafe { ends_free_avx2(x1, v1, lo, hi) };
    }
    let mut free = true;
    for a in 0..3 {
        for l in 0..WIDTH {
            free &= (x1[a][l] >= lo[a][l]) & (x1[a][l] <= hi[a][l]) & v1[a][l].is_finite();
        }
    }
    free
}

/// [`ends_free`] in AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn ends_free_avx2(
    x1: &[[f64; WIDTH]; 3],
    v1: &[[f64; WIDTH]; 3],
    lo: &[[f64; WIDTH]; 3],
    hi: &[[f64; WIDTH]; 3],
) -> bool {
    use std::arch::x86_64::*;
    // SAFETY: each row holds four f64s.
    let load = |row: &[f64; WIDTH]| unsafe { _mm256_loadu_pd(row.as_ptr()) };
    let magnitude = _mm256_castsi256_pd(_mm256_set1_epi64x(i64::MAX));
    let infinity = _mm256_set1_pd(f64::INFINITY);
    let mut free = _mm256_castsi256_pd(_mm256_set1_epi64x(-1));
    for a in 0..3 {
        let x = load(&x1[a]);
        // Ordered comparisons: false for NaN, as in the plain version.
        let inside =
            _mm256_and_pd(_mm256_cmp_pd::<_CMP_GE_OQ>(x, load(&lo[a])), _mm256_cmp_pd::<_CMP_LE_OQ>(x, load(&hi[a])));
        let finite = _mm256_cmp_pd::<_CMP_LT_OQ>(_mm256_and_pd(load(&v1[a]), magnitude), infinity);
        free = _mm256_and_pd(free, _mm256_and_pd(inside, finite));
    }
    _mm256_movemask_pd(free) == 0b1111
}

/// The mean flow plus the fluctuation `sigma zeta` at `x`.
#[inline(always)]
fn fluid_velocity<const TURB: bool>(field: &FlowField, size: [f64; 3], x: DVec3, zeta: &[f64; 3]) -> DVec3 {
    let mut u = DVec3::from_array(field.uniform);
    if let Some(profile) = &field.profile {
        u.x += profile.at(wall_distance(x.z, size[2]).0).sigma;
    }
    if TURB {
        if let Some(turb) = &field.turbulence {
            for (a, comp) in turb.iter().enumerate() {
                let (d, _) = wall_distance(x.to_array()[comp.axis], size[comp.axis]);
                u[a] += comp.table.at(d).sigma * zeta[a];
            }
        }
    }
    u
}

/// Saffman's (1965, erratum 1968) shear lift on a sphere in the mean shear `G = dU/dz` of a
/// channel, as an acceleration along `z` (m/s^2):
///
/// ```text
/// a_L = (9.69 / pi) sqrt(rho mu |G|) / (rho_p d) (u_x - v_x) sign(G)
/// ```
///
/// with `u_x - v_x` the streamwise slip of the particle against the fluid it sees: a particle
/// leading the fluid is pushed towards the slower fluid (the wall), a lagging one away from it.
/// Valid for `Re_G = |G| d^2 / nu << 1` and slip Reynolds numbers below `sqrt(Re_G)`; without
/// McLaughlin's (1993) wall correction it overstates the lift within a few diameters of the wall.
#[inline(always)]
fn saffman_lift(field: &FlowField, size: [f64; 3], x: DVec3, uf: DVec3, v: DVec3, coefficient: f64) -> f64 {
    let Some(profile) = &field.profile else { return 0.0 };
    let (d, sign) = wall_distance(x.z, size[2]);
    let shear = profile.at(d).slope * sign;
    coefficient * shear.abs().sqrt() * (uf.x - v.x) * shear.signum()
}

/// The fluid velocity seen at `x` (mean plus `sigma zeta`), and one exact Ornstein-Uhlenbeck
/// step of the normalised fluctuations `zeta` there driven by the standard normals `normals`,
/// from one table lookup per component.
#[inline(always)]
fn fluid_velocity_and_fluctuation(
    field: &FlowField,
    size: [f64; 3],
    x: DVec3,
    zeta: &mut [f64; 3],
    normals: [f64; 3],
) -> DVec3 {
    let mut u = fluid_velocity::<false>(field, size, x, zeta);
    if let Some(turb) = &field.turbulence {
        for (a, comp) in turb.iter().enumerate() {
            let (du, next) = fluctuation(comp, x.to_array()[comp.axis], size[comp.axis], zeta[a], normals[a]);
            u[a] += du;
            zeta[a] = next;
        }
    }
    u
}

/// One fluctuating component at coordinate `c` across a domain of `length` (m): the velocity
/// `sigma zeta` it adds to the fluid's, and `zeta` after one step ([`langevin_step`]).
#[inline(always)]
fn fluctuation(comp: &Component, c: f64, length: f64, zeta: f64, normal: f64) -> (f64, f64) {
    let (d, sign) = wall_distance(c, length);
    langevin_step(&comp.table.at(d), sign, zeta, normal)
}

/// The velocity `sigma zeta` a fluctuating component adds to the fluid's at `node` (with
/// `sign` the sign of `d(distance)/d(coordinate)`), and `zeta` after one exact
/// Ornstein-Uhlenbeck step (with the well-mixed drift where the table has one) driven by the
/// standard normal `normal`.
#[inline(always)]
fn langevin_step(node: &Node, sign: f64, zeta: f64, normal: f64) -> (f64, f64) {
    (node.sigma * zeta, zeta * node.decay + sign * node.drift + node.noise * normal)
}

/// The trajectory of one (part of a) step.
#[derive(Clone, Copy, Debug)]
struct Flight<const EULER: bool> {
    x0: DVec3,
    v0: DVec3,
    v_inf: DVec3,
    tau: f64,
    decay: f64,
    relax: f64,
    /// Length of the whole step this flight belongs to, s (the Brownian share is `t / dt`).
    dt: f64,
    bx: DVec3,
    bv: DVec3,
}

impl<const EULER: bool> Flight<EULER> {
    /// Position and velocity at the end of the full step.
    #[inline(always)]
    fn end(&self) -> (DVec3, DVec3) {
        if EULER {
            let x = self.x0 + self.v0 * self.dt + self.bx;
            let v = self.v0 + (self.v_inf - self.v0) * (self.dt / self.tau) + self.bv;
            (x, v)
        } else {
            let [x0, v0, v_inf, bx, bv] = [self.x0, self.v0, self.v_inf, self.bx, self.bv].map(|q| q.to_array());
            let axis = |a: usize| relaxed(x0[a], v0[a], v_inf[a], (self.dt, self.decay, self.relax), bx[a], bv[a]);
            let [(x, vx), (y, vy), (z, vz)] = [axis(0), axis(1), axis(2)];
            (DVec3::new(x, y, z), DVec3::new(vx, vy, vz))
        }
    }

    /// Position and velocity `t` (s, `0 < t <= dt`) into the flight.
    fn at(&self, t: f64) -> (DVec3, DVec3) {
        let share = t / self.dt;
        if EULER {
            let (_, v1) = self.end();
            (self.x0 + (self.v0 * self.dt + self.bx) * share, self.v0 + (v1 - self.v0) * share)
        } else {
            let e = (-t / self.tau).exp();
            let dv = self.v0 - self.v_inf;
            let relax = if self.tau > 0.0 { self.tau * -(-t / self.tau).exp_m1() } else { 0.0 };
            (self.x0 + self.v_inf * t + dv * relax + self.bx * share, self.v_inf + dv * e + self.bv * share)
        }
    }

    /// The same trajectory restarted at `x, v` for the remaining `left` seconds, without the
    /// Brownian increments.
    fn restart(&self, x: DVec3, v: DVec3, left: f64) -> Self {
        let (decay, relax) = if self.tau > 0.0 {
            let h = left / self.tau;
            ((-h).exp(), self.tau * -(-h).exp_m1())
        } else {
            (0.0, 0.0)
        };
        Self { x0: x, v0: v, decay, relax, dt: left, bx: DVec3::ZERO, bv: DVec3::ZERO, ..*self }
    }
}

#[inline(always)]
fn inside(x: DVec3, r: f64, p: &Prepared<'_>) -> bool {
    // Periodic axes have no bounds: `[-inf, inf]`.
    let mut ok = true;
    for ((x, lower), upper) in x.to_array().into_iter().zip(p.lower).zip(p.upper) {
        ok &= (x >= lower + r) & (x <= upper - r);
    }
    ok
}

#[inline(always)]
fn wrap(mut x: DVec3, p: &Prepared<'_>) -> DVec3 {
    if !p.periodic {
        return x;
    }
    for a in 0..3 {
        if !p.walled[a] {
            x[a] = x[a].rem_euclid(p.size[a]);
        }
    }
    x
}

/// How a step with wall contacts ended.
enum AfterContacts {
    /// Still in the air, in this state at the step's end.
    Airborne(State),
    /// Gone: its fate, the time into the step and where.
    Left(Fate, f64, DVec3),
}

/// Resolves the wall contacts of a step whose end lies through a wall.
#[cold]
fn contacts<const EULER: bool>(
    p: &Prepared<'_>,
    body: &Body,
    mut flight: Flight<EULER>,
    mut s: State,
    tally: &mut [WallTally],
) -> AfterContacts {
    let r = body.radius;
    let mut elapsed = 0.0;
    let (mut last_wall, mut last_x) = (0, s.x);
    for _ in 0..MAX_CONTACTS {
        let (x1, v1) = flight.end();
        if inside(x1, r, p) {
            s.x = wrap(x1, p);
            s.v = v1;
            return AfterContacts::Airborne(s);
        }
        if !x1.is_finite() {
            return AfterContacts::Left(Fate::Escaped, elapsed, s.x);
        }
        // The earliest plane crossed.
        let mut first: Option<(f64, &Wall)> = None;
        for wall in &p.walls {
            let plane = if wall.upper { wall.position - r } else { wall.position + r };
            let outside = |x: DVec3| if wall.upper { x[wall.axis] > plane } else { x[wall.axis] < plane };
            if !outside(x1) {
                continue;
            }
            let (mut lo, mut hi) = (0.0, flight.dt);
            for _ in 0..BISECTIONS {
                let mid = 0.5 * (lo + hi);
                if outside(flight.at(mid).0) {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            if first.is_none_or(|(t, _)| hi < t) {
                first = Some((hi, wall));
            }
        }
        let (t, wall) = first.expect("a step ending outside crossed a wall plane");
        let (mut x, mut v) = flight.at(t);
        x[wall.axis] = if wall.upper { wall.position - r } else { wall.position + r };
        let x = wrap(x, p);
        elapsed += t;
        (last_wall, last_x) = (wall.id, x);
        let n = DVec3::from_array(wall.normal());
        // The trajectory crossed the plane: its normal velocity points into the wall.
        let vn = v.dot(n);
        v -= n * (vn + vn.abs());
        let left = flight.dt - t;
        let w = &mut tally[wall.id];
        w.contacts += 1;
        match p.scene.walls[wall.id] {
            WallBehaviour::Sink => {
                w.captures += 1;
                w.energy.deposition += 0.5 * body.aero.mass * v.length_squared();
                return AfterContacts::Left(Fate::Deposited(wall.id), elapsed, x);
            }
            WallBehaviour::Reflect => {
                w.rebounds += 1;
                v -= 2.0 * n * v.dot(n);
                s.zeta[wall.axis] = -s.zeta[wall.axis];
                let mut v_inf = flight.v_inf;
                v_inf[wall.axis] = body.settling[wall.axis] - (v_inf[wall.axis] - body.settling[wall.axis]);
                flight = Flight { v_inf, ..flight.restart(x, v, left) };
            }
            WallBehaviour::Law { .. } if v.dot(n) >= 0.0 => {
                // Touching without closing in: resting contact.
                w.captures += 1;
                return AfterContacts::Left(Fate::Deposited(wall.id), elapsed, x);
            }
            WallBehaviour::Law { law, size } => {
                let vc = match size {
                    Some(size) => size.capture_velocity(law.params().vc, body.aero.diameter),
                    None => law.params().vc,
                };
                let result = law.impact_with_capture_velocity(v, n, vc);
                let loss = energy_loss(&result);
                let m = body.aero.mass;
                w.energy += EnergyLoss {
                    material: m * loss.material,
                    adhesion: m * loss.adhesion,
                    friction: m * loss.friction,
                    deposition: m * loss.deposition,
                };
                if !result.velocity.iter().all(|c| c.is_finite()) {
                    return AfterContacts::Left(Fate::Escaped, elapsed, x);
                }
                if result.coefficients.captured {
                    w.captures += 1;
                    return AfterContacts::Left(Fate::Deposited(wall.id), elapsed, x);
                }
                w.rebounds += 1;
                flight = flight.restart(x, DVec3::from_array(result.velocity), left);
            }
        }
    }
    // Still bouncing: at rest on the last wall it touched.
    tally[last_wall].resting += 1;
    AfterContacts::Left(Fate::Deposited(last_wall), elapsed, last_x)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::flow::Flow;
    use crate::geometry::Geometry;
    use depo_wall_model::WallLaw;

    /// `run_lanes` must give each particle exactly what `run_particle` gives it alone: same
    /// records bit for bit, same wall contacts.
    fn lanes_match_one_at_a_time<const BROWN: bool, const TURB: bool>(scene: &Scene, injection: &Injection) -> usize {
        let p = Prepared::new(scene, injection);
        let walls = p.walls.len();
        let (mut lane_tally, mut alone_tally) = (vec![WallTally::default(); walls], vec![WallTally::default(); walls]);
        let lanes = run_lanes::<BROWN, TURB>(&p, 0..injection.count, &mut lane_tally);
        let alone: Vec<Record> = (0..injection.count as u64)
            .map(|id| run_particle::<BROWN, TURB, false, false, false>(&p, id, &mut alone_tally))
            .collect();
        assert_eq!(lanes, alone);
        // The lanes as a processor without AVX2 runs them.
        let mut plain_tally = vec![WallTally::default(); walls];
        assert_eq!(super::lanes::<BROWN, TURB, false>(&p, 0..injection.count, &mut plain_tally), alone);
        for (a, b) in lane_tally.iter().zip(&alone_tally) {
            assert_eq!(
                (a.contacts, a.rebounds, a.captures, a.resting),
                (b.contacts, b.rebounds, b.captures, b.resting)
            );
            assert!((a.energy.material - b.energy.material).abs() <= 1e-12 * b.energy.material.abs());
        }
        let fates = |f: fn(&Fate) -> bool| lanes.iter().filter(|r| f(&r.fate)).count();
        let (deposited, airborne) =
            (fates(|f| matches!(f, Fate::Deposited(_))), fates(|f| matches!(f, Fate::Airborne)));
        let contacts: u64 = lane_tally.iter().map(|t| t.contacts).sum();
        assert!(contacts > 0 && airborne > 0, "{contacts} contacts, {airborne} airborne: both paths must be seen");
        deposited
    }

    #[test]
    fn lanes_give_each_particle_what_it_gets_alone() {
        // A small turbulent room whose walls rebound particles by the law (5 um particles
        // over 10 s: settling alone brings a quarter of them to the floor, where they bounce,
        // so the test does not depend on lucky random numbers), and a turbulent channel (periodic along and across) whose walls absorb
        // them. 37 particles, so that the lanes refill unevenly (as particles deposit) and the
        // last ones run part-empty.
        let law = WallLaw::preset("dunn1995-stainless").unwrap();
        let mut room = Scene::new(Geometry::Room { size: [0.05, 0.04, 0.03] }, 0.01, 10.0)
            .with_walls(WallBehaviour::Law { law, size: None });
        room.flow = Flow::TurbulentRoom { friction_velocity: 0.05, core_rms: 0.1, core_time: 0.5, blend_length: 0.01 };
        room.brownian = true;
        let settling = Injection::new(37, SizeDistribution::Monodisperse { diameter: 5e-6 }, 1000.0);
        lanes_match_one_at_a_time::<true, true>(&room, &settling);
        lanes_match_one_at_a_time::<false, true>(&room, &settling);

        let mut channel = Scene::new(Geometry::Channel { length: 0.05, width: 0.02, height: 0.01 }, 1e-4, 0.3);
        channel.flow = Flow::TurbulentChannel { friction_velocity: 0.3 };
        channel.brownian = true;
        channel.gravity = [0.0; 3];
        let particles = Injection::new(37, SizeDistribution::Monodisperse { diameter: 20e-6 }, 1000.0);
        assert!(lanes_match_one_at_a_time::<true, true>(&channel, &particles) > 0);
        assert!(lanes_match_one_at_a_time::<false, true>(&channel, &particles) > 0);
    }

    #[test]
    fn the_avx2_step_is_the_plain_step_bit_for_bit() {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            let size = [0.05, 0.04, 0.01];
            let room =
                Flow::TurbulentRoom { friction_velocity: 0.05, core_rms: 0.1, core_time: 0.5, blend_length: 0.01 };
            let channel = Flow::TurbulentChannel { friction_velocity: 0.3 };
            let mut rng = particle_rng(7, 8);
            for flow in [room, channel] {
                let field = FlowField::new(&flow, size, 1.5e-5, 1e-3, true);
                for _ in 0..2000 {
                    let mut lanes = |scale: f64| -> [[f64; WIDTH]; 3] {
                        std::array::from_fn(|_| std::array::from_fn(|_| scale * rng.random_range(-0.2..1.2)))
                    };
                    // Positions across the walls' layers and a little beyond the domain.
                    let x = [0, 1, 2].map(|a| lanes(size[a])[a]);
                    let (v, mut zeta, settling, brownian) = (lanes(0.1), lanes(2.0), lanes(1e-3), lanes(1e-4));
                    let (decay, relax) = (lanes(1.0)[0], lanes(1e-3)[0]);
                    let rows: [[f64; 9]; WIDTH] =
                        std::array::from_fn(|_| std::array::from_fn(|_| rng.random_range(-4.0..4.0)));
                    let z = [&rows[0], &rows[1], &rows[2], &rows[3]];
                    let c = LaneConstants {
                        settling: &settling,
                        decay: &decay,
                        relax: &relax,
                        brownian: &brownian,
                        dt: 1e-3,
                    };
                    let mut zeta2 = zeta;
                    let bits = |s: Stepped| [s.uf, s.x1, s.v1, s.bx, s.bv].map(|q| q.map(|r| r.map(f64::to_bits)));
                    for (brown, start) in [(true, 3), (false, 3)] {
                        let (plain, vector) = if brown {
                            let plain =
                                step_lanes::<true, true, false>(&x, &v, &mut zeta, &z, c, (&field, size, start));
                            // SAFETY: the processor has AVX2.
                            (plain, unsafe {
                                step_lanes_avx2::<true>(&x, &v, &mut zeta2, &z, c, (&field, size, start))
                            })
                        } else {
                            let plain =
                                step_lanes::<false, true, false>(&x, &v, &mut zeta, &z, c, (&field, size, start));
                            // SAFETY: the processor has AVX2.
                            (plain, unsafe {
                                step_lanes_avx2::<false>(&x, &v, &mut zeta2, &z, c, (&field, size, start))
                            })
                        };
                        assert_eq!(bits(plain), bits(vector), "{flow:?}");
                        assert_eq!(zeta.map(|r| r.map(f64::to_bits)), zeta2.map(|r| r.map(f64::to_bits)));
                    }
                }
            }
        }
    }

    #[test]
    fn the_free_step_test_is_the_same_in_avx2() {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            let (lo, hi) = ([[0.0, -1.0, 1e-9, 2.0]; 3], [[1.0, 0.0, 1.0, 2.0]; 3]);
            let specials = [0.0, -0.0, 1.0, -1.0, 1e-9, 2.0, 0.5, f64::from_bits(1), 1.0 + f64::EPSILON];
            let odd = [f64::NAN, f64::INFINITY, f64::NEG_INFINITY];
            let mut rng = particle_rng(1, 2);
            let (mut free, mut cases) = (0, 0);
            for _ in 0..20_000 {
                // Mostly inside each lane's box (its edges included), sometimes an edge case.
                let mut pick = |l: usize| -> f64 {
                    let r: f64 = rng.random();
                    if r < 0.003 {
                        odd[rng.random_range(0..3)]
                    } else if r < 0.05 {
                        specials[rng.random_range(0..specials.len())]
                    } else if r < 0.1 {
                        [lo[0][l], hi[0][l]][rng.random_range(0..2)]
                    } else {
                        lo[0][l] + (hi[0][l] - lo[0][l]) * rng.random::<f64>()
                    }
                };
                let x1: [[f64; WIDTH]; 3] = std::array::from_fn(|_| std::array::from_fn(&mut pick));
                let v1: [[f64; WIDTH]; 3] = std::array::from_fn(|_| std::array::from_fn(&mut pick));
                let expected = ends_free::<false>(&x1, &v1, &lo, &hi);
                // SAFETY: the processor has AVX2.
                assert_eq!(unsafe { ends_free_avx2(&x1, &v1, &lo, &hi) }, expected, "{x1:?} {v1:?}");
                free += usize::from(expected);
                cases += 1;
            }
            // Both answers occur often enough to be tested.
            assert!(free > 100 && cases - free > 100, "{free} of {cases}");
        }
    }

    #[test]
    fn lanes_without_turbulence_give_each_particle_what_it_gets_alone() {
        // Still air in a small room with rebounding walls, settling 30 um particles (most reach
        // the floor within the run, those injected high do not); and a uniform flow through a
        // channel, periodic along and across (so that particles wrap), whose floor absorbs them.
        let law = WallLaw::preset("dunn1995-stainless").unwrap();
        let room = Scene::new(Geometry::Room { size: [0.05, 0.04, 0.03] }, 0.01, 0.8)
            .with_walls(WallBehaviour::Law { law, size: None });
        let settling = Injection::new(37, SizeDistribution::Monodisperse { diameter: 30e-6 }, 1000.0);
        assert!(lanes_match_one_at_a_time::<false, false>(&room, &settling) > 0);

        let mut channel = Scene::new(Geometry::Channel { length: 0.05, width: 0.02, height: 0.01 }, 1e-3, 0.3);
        channel.flow = Flow::Uniform { velocity: [0.5, -0.2, 0.0] };
        assert!(lanes_match_one_at_a_time::<false, false>(&channel, &settling) > 0);
    }

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
    fn series_and_formula_agree_where_they_meet() {
        let h: f64 = 0.05;
        let series = h * h * h * (2.0 / 3.0 - h * (0.5 - h * (7.0 / 30.0 - h * (1.0 / 12.0 - h * 31.0 / 1260.0))));
        let formula = 2.0 * h - 3.0 + 4.0 * (-h).exp() - (-2.0 * h).exp();
        assert!((series / formula - 1.0).abs() < 1e-7, "{series} {formula}");
    }

    fn flight<const EULER: bool>(tau: f64, dt: f64) -> Flight<EULER> {
        let h = dt / tau;
        Flight {
            x0: DVec3::new(0.1, 0.2, 0.3),
            v0: DVec3::new(1.0, -2.0, 0.5),
            v_inf: DVec3::new(0.2, 0.0, -0.1),
            tau,
            decay: (-h).exp(),
            relax: tau * -(-h).exp_m1(),
            dt,
            bx: DVec3::ZERO,
            bv: DVec3::ZERO,
        }
    }

    #[test]
    fn exponential_flight_is_the_exact_drag_solution_and_composes() {
        for (tau, dt) in [(1e-3, 0.1), (0.5, 0.1), (10.0, 0.1), (0.0, 0.1)] {
            let f = flight::<false>(tau, dt);
            let (x, v) = f.end();
            let (xa, va) = f.at(dt);
            assert!((x - xa).length() < 1e-14 && (v - va).length() < 1e-14, "tau {tau}");
            // By hand: v(t) = v_inf + (v0 - v_inf) e^(-t/tau).
            let e = if tau > 0.0 { (-dt / tau).exp() } else { 0.0 };
            assert!((v - (f.v_inf + (f.v0 - f.v_inf) * e)).length() < 1e-14);
            // Stopping halfway and flying on from there ends at the same state.
            let (xm, vm) = f.at(0.4 * dt);
            let (x2, v2) = f.restart(xm, vm, 0.6 * dt).end();
            assert!((x2 - x).length() < 1e-13 && (v2 - v).length() < 1e-13, "tau {tau}: {x2} {x}");
            assert!(x.is_finite() && v.is_finite());
        }
        // Euler is first order: its end differs from the exact one by O(dt^2 / tau).
        let f = flight::<false>(0.5, 0.01);
        let (xe, _) = flight::<true>(0.5, 0.01).end();
        let leading = (f.v0 - f.v_inf).length() * 0.01 * 0.01 / (2.0 * 0.5);
        assert!(((xe - f.end().0).length() / leading - 1.0).abs() < 0.01);
    }

    #[test]
    fn saffman_lift_pushes_leading_particles_to_the_wall() {
        // Poiseuille flow, U_max = 1 m/s over H = 0.01 m: G = 4 U_max (H - 2z) / H^2.
        let field = FlowField::new(&crate::Flow::Poiseuille { max_speed: 1.0 }, [1.0, 1.0, 0.01], 1.5e-5, 1e-4, true);
        let size = [1.0, 1.0, 0.01];
        let x = DVec3::new(0.5, 0.5, 0.001);
        let shear: f64 = 4.0 * (0.01 - 0.002) / 1e-4; // 320 1/s
        let uf = DVec3::new(0.32, 0.0, 0.0);
        let lead = saffman_lift(&field, size, x, uf, DVec3::new(0.42, 0.0, 0.0), 2.0);
        // By hand: 2 * sqrt(320) * (0.32 - 0.42) * (+1) = -3.578 m/s^2 (towards the lower wall).
        assert!((lead - 2.0 * shear.sqrt() * -0.1).abs() < 0.02 * lead.abs(), "{lead}");
        let lag = saffman_lift(&field, size, x, uf, DVec3::new(0.22, 0.0, 0.0), 2.0);
        assert!(lag > 0.0 && (lag + lead).abs() < 1e-9);
        // Near the upper wall the shear changes sign, and so does the lift.
        let upper = saffman_lift(&field, size, DVec3::new(0.5, 0.5, 0.009), uf, DVec3::new(0.42, 0.0, 0.0), 2.0);
        assert!((upper + lead).abs() < 1e-9, "{upper} {lead}");
    }
}
