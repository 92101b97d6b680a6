//! Running a scene, and what a run tells: counts and mass per wall, deposition velocities,
//! loss-rate coefficients, deposition maps.
//!
//! Particles are independent (one-way coupling), so each is tracked through the whole run in
//! one go, with its own random stream; rayon spreads fixed chunks of particles over the cores
//! and the chunks' tallies are summed in chunk order. The same seed therefore gives the same
//! run, bit for bit, on any number of threads.
//!
//! ## Deposition velocity
//! `v_d = J / C`: the deposits on a set of walls per unit area and time over a window, divided by
//! the mean airborne concentration over that window. Here `C` is the number of airborne
//! particles integrated over the window (particle-seconds, [`Run::exposure`]) over the window
//! length and the volume: the well-mixed definition a room's or a channel's loss rate uses.
//! Its standard error is taken as Poisson, `v_d / sqrt(N)` for `N` deposits.

use rayon::prelude::*;

use crate::geometry::{Orientation, Wall};
use crate::scene::{Injection, Scene, SceneError};
use crate::track::{track, Fate, Prepared, Record, WallTally};

/// Particles per chunk of work (fixed, so the sums do not depend on the thread count).
const CHUNK: usize = 256;

/// Tracks `injection` through `scene` on the current rayon pool.
pub fn run(scene: &Scene, injection: &Injection) -> Result<Run, SceneError> {
    scene.validate(injection)?;
    let prepared = Prepared::new(scene, injection);
    let wall_count = prepared.walls.len();
    let chunks: Vec<(Vec<Record>, Vec<WallTally>)> = (0..injection.count.div_ceil(CHUNK))
        .into_par_iter()
        .map(|c| {
            let mut tally = vec![WallTally::default(); wall_count];
            let ids = c * CHUNK..((c + 1) * CHUNK).min(injection.count);
            let records = track(&prepared, ids, &mut tally);
            (records, tally)
        })
        .collect();
    let mut records = Vec::with_capacity(injection.count);
    let mut tallies = vec![WallTally::default(); wall_count];
    for (r, t) in chunks {
        records.extend(r);
        for (sum, x) in tallies.iter_mut().zip(t) {
            *sum += x;
        }
    }
    let duration = prepared.steps as f64 * scene.dt;
    Ok(Run { records, tallies, walls: prepared.walls, volume: scene.geometry.volume(), duration })
}

/// A value with its standard error.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Estimate {
    /// The value.
    pub value: f64,
    /// Its standard error.
    pub error: f64,
    /// The number of events it rests on.
    pub events: usize,
}

/// Where the injected particles are at the end: the mass balance of a run.
#[derive(Clone, Debug, PartialEq)]
pub struct Balance {
    /// Injected particles.
    pub injected: usize,
    /// Still airborne.
    pub airborne: usize,
    /// Deposited, per wall.
    pub deposited: Vec<usize>,
    /// Escaped.
    pub escaped: usize,
    /// Masses (kg): injected, airborne, per wall, escaped.
    pub injected_mass: f64,
    /// Airborne mass, kg.
    pub airborne_mass: f64,
    /// Deposited mass per wall, kg.
    pub deposited_mass: Vec<f64>,
    /// Escaped mass, kg.
    pub escaped_mass: f64,
}

/// The outcome of a run.
#[derive(Clone, Debug, PartialEq)]
pub struct Run {
    /// One record per particle, in injection order.
    pub records: Vec<Record>,
    /// Impact statistics per wall.
    pub tallies: Vec<WallTally>,
    /// The walls, in id order.
    pub walls: Vec<Wall>,
    /// Domain volume, m^3.
    pub volume: f64,
    /// Simulated time, s.
    pub duration: f64,
}

impl Run {
    /// Particle-steps tracked (the unit of tracking cost).
    #[must_use]
    pub fn particle_steps(&self) -> u64 {
        self.records.iter().map(|r| r.steps).sum()
    }

    /// Counts and masses: airborne + deposited + escaped = injected, exactly.
    #[must_use]
    pub fn balance(&self) -> Balance {
        let mut b = Balance {
            injected: self.records.len(),
            airborne: 0,
            deposited: vec![0; self.walls.len()],
            escaped: 0,
            injected_mass: 0.0,
            airborne_mass: 0.0,
            deposited_mass: vec![0.0; self.walls.len()],
            escaped_mass: 0.0,
        };
        for r in &self.records {
            b.injected_mass += r.mass;
            match r.fate {
                Fate::Airborne => {
                    b.airborne += 1;
                    b.airborne_mass += r.mass;
                }
                Fate::Deposited(w) => {
                    b.deposited[w] += 1;
                    b.deposited_mass[w] += r.mass;
                }
                Fate::Escaped => {
                    b.escaped += 1;
                    b.escaped_mass += r.mass;
                }
            }
        }
        b
    }

    /// Airborne particle-seconds within `[from, to]` (s).
    #[must_use]
    pub fn exposure(&self, from: f64, to: f64) -> f64 {
        self.records.iter().map(|r| (r.time.min(to) - from).max(0.0)).sum()
    }

    /// Deposits on `walls` within `[from, to]`.
    #[must_use]
    pub fn deposits(&self, walls: &[usize], from: f64, to: f64) -> usize {
        self.records
            .iter()
            .filter(|r| matches!(r.fate, Fate::Deposited(w) if walls.contains(&w)) && r.time >= from && r.time <= to)
            .count()
    }

    /// The walls of one orientation.
    #[must_use]
    pub fn walls_facing(&self, orientation: Orientation) -> Vec<usize> {
        self.walls.iter().filter(|w| w.orientation() == orientation).map(|w| w.id).collect()
    }

    /// Deposition velocity onto `walls` over `[from, to]` (m/s; see the module docs).
    #[must_use]
    pub fn deposition_velocity(&self, walls: &[usize], from: f64, to: f64) -> Estimate {
        let n = self.deposits(walls, from, to);
        let area: f64 = walls.iter().map(|&w| self.walls[w].area).sum();
        let concentration_time = self.exposure(from, to) / self.volume;
        let value = if concentration_time > 0.0 && area > 0.0 { n as f64 / (area * concentration_time) } else { 0.0 };
        Estimate { value, error: value / (n.max(1) as f64).sqrt(), events: n }
    }

    /// Loss-rate coefficient `beta = sum(v_d A) / V` over `[from, to]`, 1/s: the first-order rate
    /// at which deposition removes airborne particles.
    #[must_use]
    pub fn loss_rate(&self, from: f64, to: f64) -> Estimate {
        let all: Vec<usize> = (0..self.walls.len()).collect();
        let n = self.deposits(&all, from, to);
        let exposure = self.exposure(from, to);
        let value = if exposure > 0.0 { n as f64 / exposure } else { 0.0 };
        Estimate { value, error: value / (n.max(1) as f64).sqrt(), events: n }
    }

    /// Deposition map of one wall: counts on a `bins[0] x bins[1]` grid over its two
    /// in-plane axes (in the order x, y, z without the wall's own axis), row-major.
    #[must_use]
    pub fn deposition_map(&self, wall: usize, size: [f64; 3], bins: [usize; 2]) -> Vec<u32> {
        let axis = self.walls[wall].axis;
        let (a, b) = match axis {
            0 => (1, 2),
            1 => (0, 2),
            _ => (0, 1),
        };
        let mut map = vec![0u32; bins[0] * bins[1]];
        for r in self.records.iter().filter(|r| r.fate == Fate::Deposited(wall)) {
            let i = ((r.position[a] / size[a] * bins[0] as f64) as usize).min(bins[0] - 1);
            let j = ((r.position[b] / size[b] * bins[1] as f64) as usize).min(bins[1] - 1);
            map[i * bins[1] + j] += 1;
        }
        map
    }
}
