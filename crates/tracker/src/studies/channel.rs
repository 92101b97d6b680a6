//! The channel study: one run per `tau+` in a turbulent channel, beside Wood (1981) and
//! Papavergos & Hedley (1984) (see [`super::study`] for what both studies share).

use crate::estimation::run::{run, run_more, Estimate, Run};
use crate::model::air::Air;
use crate::model::error::SceneError;
use crate::model::excursions::Sweeps;
use crate::model::flow::Flow;
use crate::model::geometry::Geometry;
use crate::model::scene::{Injection, Scene, SizeDistribution};
use crate::model::settings::RunSettings;
use crate::physics::correlations::{diameter_for_tau_plus, papavergos_hedley, schmidt, wood};
use crate::tracking::WallTally;

use crate::studies::study::*;

/// The longest a channel study follows an excursion, in wall time units (`nu / u*^2`). Below
/// `tau+ = 3` particles hover in the viscous sublayer, where the turbulence has all but
/// vanished and Brownian motion at `Sc ~ 1e6` crosses the last wall unit slowly: given up
/// much sooner, the weight left hovering outweighs the weight deposited and `V+` comes out
/// low. After 1e5 next to none is left to give up, so the estimate has no truncation bias
/// left to speak of; the printed share given up says so for each run. (Measurements in
/// docs/performance-log.md, "Channel excursions followed to 10^5 wall time units".)
pub const CHANNEL_LONGEST_EXCURSION: f64 = 1e5;

/// The innermost splitting level of a channel study's excursions, in wall units (from the
/// particle's surface): levels halve from 15 wall units down to 0.23. Below `tau+ = 3` the
/// branches spend most of their steps within one wall unit of the wall, hovering for
/// hundreds to thousands of wall time units, so each split below a few tenths of a wall unit
/// multiplies the costliest branches; one level further out splits too little. The
/// efficiencies of each choice are in docs/performance-log.md ("The channel study: splitting
/// levels that stop at 0.23 wall units").
pub const CHANNEL_INNERMOST_LEVEL: f64 = 0.2;

/// The channel study catches strong sweeps on their way to the near-wall layer
/// ([`Excursions::sweeps`](crate::model::excursions::Excursions::sweeps)) from this `tau+` on:
/// where a strong sweep's wall-ward speed (a few `u*`) times the particle's relaxation time carries
/// it across the sublayer's few wall units. At `tau+` 0.1-1, where Brownian motion and the
/// turbulence within the sublayer carry the particles the last part of the way, sweeps cost
/// more than the error they save, so they stay off there (docs/performance-log.md).
pub const CHANNEL_SWEEPS_FROM: f64 = 3.0;

/// The sweeps the channel study catches: the fluid's wall-ward `zeta` above 3 (0.13 % of the
/// time in a Gaussian) until it falls below 2, ten excursions per such entry, and then one
/// per crossing of the layer (not the three the studies start elsewhere): the most efficient
/// of the settings compared at `tau+ = 3` (`1 / (relative error^2 time)`; the table is in
/// docs/performance-log.md, "The channel at `tau+ = 3`").
pub const CHANNEL_SWEEPS: Sweeps = Sweeps { enter: 3.0, leave: 2.0, sampling: 10.0 };

/// The coarse steps of a channel study's excursions below [`CHANNEL_SWEEPS_FROM`]
/// ([`Excursions::coarse_factor`](crate::model::excursions::Excursions::coarse_factor)): four times
/// the study's step (0.8 wall time units), with the midpoint scheme, wherever they cannot reach a
/// wall (the wall-normal rms' steepest slope, about 0.04 `u*` per wall unit, times 0.8 is below the
/// gradient limit, so that limit does not bind here). Four keeps `V+` within the errors of the
/// study's step while taking well under its time; eight drifts high. The midpoint scheme is
/// what makes coarse steps safe: the default scheme's first-order error in the sublayer grows
/// with the step. From `tau+ = 3`, where sweeps carry the particles to the wall rather than
/// hovering, they are off: faster there, but no more efficient. (Measurements in
/// docs/performance-log.md, "The channel below `tau+ = 3`".)
pub const CHANNEL_COARSE_FACTOR: u32 = 4;

/// A channel study: one run per `tau+` in a turbulent channel.
#[derive(Clone, Debug, PartialEq)]
pub struct ChannelStudy {
    /// The channel, its air, flow (a [`Flow::TurbulentChannel`]) and walls.
    pub scene: Scene,
    /// How each `tau+` is run: time step, scheme, duration and seed. The study sets the
    /// averaging window from `transient`, and below `excursions_below` the excursions.
    pub settings: RunSettings,
    /// Dimensionless relaxation times `tau+ = tau u*^2 / nu`.
    pub tau_plus: Vec<f64>,
    /// Particles per `tau+`.
    pub count: usize,
    /// Particle density, kg/m^3.
    pub density: f64,
    /// Share of the run left out of the averages, in `[0, 1)`.
    pub transient: f64,
    /// Count deposits by near-wall excursions below this `tau+` (10 by default: above it
    /// deposition is frequent and plain tracking resolves it faster).
    pub excursions_below: f64,
    /// Particles per `tau+` where excursions count the deposits (each costs far more than a
    /// plainly tracked one).
    pub excursion_count: usize,
    /// The relative standard error to resolve each `V+` to. When the first particles (`count`
    /// or `excursion_count`) leave it less resolved, as many more are run (and pooled with
    /// them) as its error, falling as `1 / sqrt(n)`, says it needs, times [`TARGET_MARGIN`],
    /// provided that is at most `max_factor` times the first particles, and once more the
    /// same way if the pooled error is still above the target; a `tau+` that would need more
    /// keeps what it ran, and its printed error says how far it is. `None`: the
    /// first particles, whatever the errors.
    pub target_error: Option<f64>,
    /// The most particles per `tau+` with `target_error`, as a multiple of its first ones.
    pub max_factor: f64,
}

impl Default for ChannelStudy {
    /// A channel of `Re_tau = 150` (`u* = 0.3 m/s`, height 15 mm in standard air), no gravity
    /// (the correlations are for vertical flows), Brownian motion, absorbing walls, particles
    /// of 1000 kg/m^3, steps of 0.2 and runs of 3000 wall time units, averages over the second
    /// half; 1000 particles per `tau+` with excursions (below 10) and 4000 without, and up to
    /// eight times as many where `V+` needs them for a 5 % error (in up to two rounds).
    fn default() -> Self {
        let air = Air::standard();
        let u_star = 0.3;
        let unit = air.kinematic_viscosity() / u_star;
        let time = unit / u_star;
        let mut scene =
            Scene::new(Geometry::Channel { length: 1000.0 * unit, width: 300.0 * unit, height: 300.0 * unit });
        scene.gravity = [0.0; 3];
        scene.flow = Flow::TurbulentChannel { friction_velocity: u_star };
        scene.brownian = true;
        Self {
            scene,
            settings: RunSettings::new(0.2 * time, 3000.0 * time),
            tau_plus: vec![0.1, 0.3, 1.0, 3.0, 10.0, 30.0, 100.0],
            count: 4000,
            density: 1000.0,
            transient: 0.5,
            excursions_below: 10.0,
            excursion_count: 1000,
            target_error: Some(TARGET_ERROR),
            max_factor: 8.0,
        }
    }
}

/// One `tau+` of a channel study.
#[derive(Clone, Debug, PartialEq)]
pub struct ChannelPoint {
    /// `tau+`.
    pub tau_plus: f64,
    /// The particle diameter giving it, m.
    pub diameter: f64,
    /// Schmidt number `nu / D`.
    pub schmidt: f64,
    /// Dimensionless deposition velocity `V+ = v_d / u*`.
    pub v_plus: Estimate,
    /// Wood (1981) at this `tau+` and `Sc`.
    pub wood: f64,
    /// Papavergos & Hedley (1984).
    pub papavergos_hedley: f64,
    /// Particle-steps the run took (of the tracked particles; excursions not included).
    pub particle_steps: u64,
    /// Particles run (more than the first ones where [`ChannelStudy::target_error`] needed
    /// them).
    pub particles: usize,
    /// Whether deposits were counted by near-wall excursions, and if so the share of their
    /// weight given up at their longest duration ([`Run::truncated_share`](crate::Run::truncated_share)).
    pub excursions: Option<f64>,
    /// Wall-clock time of the excursions' pilot calibration, s (0 without excursions): a
    /// cost fixed per run, which does not grow with the particles run.
    pub calibration_seconds: f64,
    /// Whether the excursions also caught strong sweeps before the layer
    /// ([`Excursions::sweeps`](crate::model::excursions::Excursions::sweeps); from [`CHANNEL_SWEEPS_FROM`]).
    pub sweeps: bool,
    /// The wall-law tallies summed over both walls.
    pub tally: WallTally,
    /// With a wall function: the concentration in its layers over the mean, `C_w / C`, which
    /// the deposition velocity is proportional to (1 where the layers hold the bulk
    /// concentration the correlation is defined against; [`crate::wall_function`]).
    pub layer_concentration: Option<Estimate>,
}

impl ChannelStudy {
    /// Runs every `tau+`; `progress` is told after each.
    pub fn run(&self, mut progress: impl FnMut(usize)) -> Result<Vec<ChannelPoint>, SceneError> {
        let u_star = self.scene.flow.friction_velocity().unwrap_or(1.0);
        let air = &self.scene.air;
        let mut points = Vec::new();
        for (i, &tp) in self.tau_plus.iter().enumerate() {
            let d = diameter_for_tau_plus(tp, self.density, air, u_star).ok_or_else(|| {
                SceneError::new("particles.tau_plus", tp, "needs a particle diameter outside 0.1 nm to 1 cm here")
            })?;
            // A wall function counts expected deposits itself: no excursions.
            let excursions = tp < self.excursions_below && self.scene.wall_function.is_none();
            let count = if excursions { self.excursion_count } else { self.count };
            let injection = Injection::new(count, SizeDistribution::Monodisperse { diameter: d }, self.density);
            let scene = &self.scene;
            let mut settings = self.settings.clone();
            settings.average_from = self.transient * settings.steps() as f64 * settings.dt;
            let mut calibration_seconds = 0.0;
            if excursions {
                // Factors up to 4 (larger ones made the deep branches, which live long in
                // the Brownian sublayer, too many: 3-5 times the run time for the same error).
                let pilot = (count / PILOT.0).max(1);
                let sweeps = (tp >= CHANNEL_SWEEPS_FROM).then_some(CHANNEL_SWEEPS);
                let (inner, longest) = (CHANNEL_INNERMOST_LEVEL, CHANNEL_LONGEST_EXCURSION);
                // Without sweeps the branches hover in the viscous sublayer: coarse steps there.
                let coarse = if sweeps.is_some() { 1 } else { CHANNEL_COARSE_FACTOR };
                (settings, _, calibration_seconds) =
                    with_excursions(scene, settings, &injection, pilot, inner, (longest, longest), 4, sweeps, coarse)?;
            }
            let all_walls = |r: &Run| r.deposition_velocity(&(0..r.walls.len()).collect::<Vec<_>>());
            let mut result = run(scene, &settings, &injection)?;
            if let Some(target) = self.target_error {
                // Two rounds: the second where the pooled estimate still misses the target (an
                // error that rests on rare events is itself rough from the first particles).
                let mut have = count;
                for round in 0..2 {
                    let e = all_walls(&result);
                    if round > 0 && resolved(&e, target) {
                        break;
                    }
                    let needed = particles_for(&e, have, target);
                    if needed <= have || needed as f64 > self.max_factor * count as f64 {
                        break;
                    }
                    result = run_more(scene, &settings, &Injection { count: needed, ..injection }, result)?;
                    have = needed;
                }
            }
            let v = all_walls(&result);
            let sc = schmidt(d, air);
            let layer_concentration = scene.wall_function.map(|wf| {
                let layer = wf.layer(air, u_star);
                result.layer_concentration(result.walls.iter().map(|w| w.area * layer).sum())
            });
            points.push(ChannelPoint {
                tau_plus: tp,
                diameter: d,
                schmidt: sc,
                v_plus: Estimate {
                    value: v.value / u_star,
                    error: v.error / u_star,
                    events: v.events,
                    upper_bound: v.upper_bound / u_star,
                },
                wood: wood(tp, sc),
                papavergos_hedley: papavergos_hedley(tp, sc),
                particle_steps: result.particle_steps(),
                particles: result.records.len(),
                excursions: settings.excursions.as_ref().map(|_| result.truncated_share()),
                calibration_seconds,
                sweeps: settings.excursions.as_ref().is_some_and(|e| e.sweeps.is_some()),
                tally: total(&result.tallies),
                layer_concentration,
            });
            progress(i + 1);
        }
        Ok(points)
    }
}
