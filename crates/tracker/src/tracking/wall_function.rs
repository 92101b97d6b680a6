//! One particle through a run with a deposition wall function ([`crate::wall_function`]).
//!
//! The particle is stepped as in any run, with the wall function's walls reflecting (the
//! layer, not the wall plane, deposits). After each step, for each such wall whose layer the
//! particle is in (not over an opening), it arrives at the wall with the layer's probability
//! `P`; a sink deposits it, a wall law decides with its velocity turned towards the wall.
//!
//! ## The estimate
//! The run's deposition velocities do not count the particle's own deposit, a rare event
//! for small `V+` (one deposit in 10^4 particles at `tau+ = 0.1` in the default channel),
//! but its expected value: each step in the layer within the averaging window adds `P`
//! (times whether the wall law would capture the particle as it stands) to the wall's
//! deposits, for as long as the particle is in the air. The expectation of that sum is the
//! chance of a deposit within the window, so the estimate is unbiased, and it rests on
//! every step spent in the layer rather than on the few that end in a deposit (a
//! conditional expectation: never a larger variance). The particle's record keeps its own
//! sampled fate, for the mass balance, the decay curves and the maps.

use depo_wall_model::energy::{energy_loss, EnergyLoss};
use glam::DVec3;
use rand::RngExt;

use super::contacts::in_joules;
use super::{Fate, Flyer, Needs, ParticleTally, Prepared, Record, Step, WallTally};
use crate::model::air::Aerodynamics;
use crate::model::walls::WallBehaviour;
use crate::physics::noise::particle_rng;
use crate::physics::wall_function::{deposition_probability, deposition_velocity_cached};

/// Salt of the stream that draws a particle's arrivals at the walls.
const ARRIVAL_SALT: u64 = 0x9e37_79b9_7f4a_7c15;

/// Tracks particles `ids` with the scene's wall function, adding their wall contacts (the
/// layer's arrivals and the furnishings' contacts) to `tally`: their records and tallies.
pub(crate) fn track_wall_function(
    p: &Prepared<'_>,
    ids: std::ops::Range<usize>,
    tally: &mut [WallTally],
) -> (Vec<Record>, Vec<ParticleTally>) {
    let Needs { brown, turb, finite_re, euler, lift } = Needs::of(p);
    // The wall function's walls reflect in the step: those contacts are the model's, not the
    // walls', and are not counted (the furnishings' are).
    let mut stepped = vec![WallTally::default(); tally.len()];
    // The walls' chances for the last particle's size (a run's particles mostly share one).
    let mut chances = Chances::default();
    let out = {
        let stepped = &mut stepped;
        let tally = &mut *tally;
        macro_rules! dispatch {
        ([$($done:literal)*] []) => {
            ids.map(|id| run_with_wall_function::<$($done),*>(p, id as u64, stepped, tally, &mut chances)).unzip()
        };
        ([$($done:literal)*] [$flag:expr $(, $rest:expr)*]) => {
            if $flag { dispatch!([$($done)* true] [$($rest),*]) } else { dispatch!([$($done)* false] [$($rest),*]) }
        };
    }
        dispatch!([] [brown, turb, finite_re, euler, lift])
    };
    let layered = p.wall_function.as_ref().map_or(&[][..], |wf| &wf.walls[..]);
    for (id, t) in stepped.into_iter().enumerate() {
        if !layered.iter().any(|(wall, _)| wall.id == id) {
            tally[id] += t;
        }
    }
    out
}

/// Each wall's chance of an arrival over a step in its layer, for the particle size it was
/// last computed for; a correlation such as [`crate::correlations::hussein`] integrates
/// across the layer, too slow to repeat for every particle, and its velocity is also kept
/// per thread across chunks, sizes and walls of one orientation
/// ([`deposition_velocity_cached`]).
#[derive(Default)]
struct Chances {
    /// The diameter (m) and mass (kg) they are for.
    size: Option<(f64, f64)>,
    chance: Vec<f64>,
}

impl Chances {
    fn for_particle(&mut self, p: &Prepared<'_>, aero: &Aerodynamics) -> &[f64] {
        let wf = p.wall_function.as_ref().expect("a scene with a wall function");
        if self.size != Some((aero.diameter, aero.mass)) {
            self.chance = wf
                .walls
                .iter()
                .map(|(wall, _)| {
                    let orientation = wall.orientation();
                    let correlation = wf.function.correlation_for(orientation);
                    let v_d =
                        deposition_velocity_cached(correlation, aero, &p.scene.air, wf.friction_velocity, orientation);
                    deposition_probability(v_d, wf.layer, p.settings.dt)
                })
                .collect();
            self.size = Some((aero.diameter, aero.mass));
        }
        &self.chance
    }
}

/// What arriving at a wall does to a particle with velocity `v`: captured (deposited), or
/// rebounding with a new velocity; and the wall's tally of it when `count` (the contact,
/// its outcome and the energy lost).
fn arrive(
    behaviour: WallBehaviour,
    normal: DVec3,
    v: DVec3,
    diameter: f64,
    mass: f64,
    count: Option<&mut WallTally>,
) -> Option<DVec3> {
    // A free flight from the layer to the wall: the normal component towards it.
    let vn = v.dot(normal);
    let v = v - normal * (vn + vn.abs());
    let (outcome, loss) = match behaviour {
        WallBehaviour::Law { .. } if v.dot(normal) >= 0.0 => (None, EnergyLoss::default()), // touching at rest
        WallBehaviour::Law { law, size } => {
            let vc = size.map_or(law.params().vc, |s| s.capture_velocity(law.params().vc, diameter));
            let result = law.impact_with_capture_velocity(v, normal, vc);
            let rebound = DVec3::from_array(result.velocity);
            let kept = !result.coefficients.captured && rebound.is_finite();
            (kept.then_some(rebound), energy_loss(&result))
        }
        // A sink (mirrors never take the wall function).
        _ => (None, EnergyLoss { deposition: 0.5 * v.length_squared(), ..EnergyLoss::default() }),
    };
    if let Some(w) = count {
        w.contacts += 1;
        if outcome.is_some() {
            w.rebounds += 1;
        } else {
            w.captures += 1;
        }
        w.energy += in_joules(loss, mass);
    }
    outcome
}

fn run_with_wall_function<
    const BROWN: bool,
    const TURB: bool,
    const FINITE_RE: bool,
    const EULER: bool,
    const LIFT: bool,
>(
    p: &Prepared<'_>,
    id: u64,
    stepped: &mut [WallTally],
    tally: &mut [WallTally],
    chances: &mut Chances,
) -> (Record, ParticleTally) {
    let wf = p.wall_function.as_ref().expect("a scene with a wall function");
    let dt = p.settings.dt;
    let window = p.window;
    let mut flyer = Flyer::inject(p, id, TURB, BROWN);
    let aero = flyer.base.aero;
    // Each wall's chance of an arrival over a step in its layer (0 for walls it skips).
    let chance = chances.for_particle(p, &aero);
    let mut arrivals = particle_rng(p.settings.seed ^ ARRIVAL_SALT, id);
    let mut expected = [0.0; 6];
    let mut steps_in_layer = [0u32; 6];
    let mut layer_time = 0.0;
    let mut ended: Option<Record> = None;
    'steps: for n in 0..flyer.end {
        if p.stopped_at(n) {
            break; // an incomplete record, which the stopped run discards
        }
        if let Step::Left(fate, t, at) = flyer.step::<BROWN, TURB, FINITE_RE, EULER, LIFT>(p, n, stepped) {
            ended = Some(flyer.record(fate, n as f64 * dt + t, at, n as u64 + 1));
            break;
        }
        let t = (n + 1) as f64 * dt;
        let counted = t >= window[0] && t <= window[1];
        let mut in_layer = false;
        for ((wall, behaviour), &chance) in wf.walls.iter().zip(chance) {
            let x = flyer.x;
            if (x[wall.axis] - wall.position).abs() >= wf.layer
                || p.scene.openings.iter().any(|o| o.wall == wall.id && o.holds(x.to_array()))
            {
                continue;
            }
            if counted && !in_layer {
                // The step's airborne time in the layer (a deposit below ends it in the layer).
                layer_time += dt;
            }
            in_layer = true;
            let normal = DVec3::from_array(wall.normal());
            if counted {
                let captured = arrive(*behaviour, normal, flyer.v, aero.diameter, aero.mass, None).is_none();
                if captured {
                    expected[wall.id] += chance;
                    steps_in_layer[wall.id] += 1;
                }
            }
            if arrivals.random::<f64>() < chance {
                let w = &mut tally[wall.id];
                match arrive(*behaviour, normal, flyer.v, aero.diameter, aero.mass, Some(w)) {
                    Some(rebound) => flyer.v = rebound,
                    None => {
                        let mut at = x;
                        at[wall.axis] = wall.position + if wall.upper { -flyer.body.radius } else { flyer.body.radius };
                        ended = Some(flyer.record(Fate::Deposited(wall.id), t, at, n as u64 + 1));
                        break 'steps;
                    }
                }
            }
        }
    }
    let record = ended.unwrap_or_else(|| flyer.finish(p));
    let mut particle = ParticleTally::of(&record, window);
    // The expected deposits on the wall function's walls replace the particle's own there.
    for (wall, _) in &wf.walls {
        particle.deposited[wall.id] = expected[wall.id];
        particle.events[wall.id] = steps_in_layer[wall.id];
        particle.landed.retain(|l| l.surface as usize != wall.id);
    }
    particle.layer_exposure = layer_time;
    (record, particle)
}
