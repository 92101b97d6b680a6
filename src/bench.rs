//! Throughput of the wall-law kernel against this machine's memory ceiling.
//!
//! Memory bandwidth on shared machines swings by up to 2x between runs, so an absolute rate
//! says little. Each measurement here therefore times, interleaved in the same run, the law
//! kernel and a *copy kernel* that reads and writes exactly the same arrays (velocity, spin
//! and radius when tracked, the outcome bytes) with trivial arithmetic, split across the same
//! threads in the same pieces. The figure that holds from run to run is the ratio of the two.
//!
//! Before every timed call the pool's threads are woken with a broadcast, so a timing never
//! includes thread wake-up.

use std::time::{Duration, Instant};

use depo_wall_model::{Impacts, LawParams, Normals, Outcome, PowerMode, Real, Tally, WallLaw};
use multiversion::multiversion;
use rand::rngs::StdRng;
use rand::{RngExt, SeedableRng};
use rayon::prelude::*;
use rayon::ThreadPool;

use crate::wall_model::kernel::LEAF;

/// Working precision of a benchmark.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Precision {
    F64,
    F32,
}

/// The wall of a benchmark, and how the kernel is given its normal.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Wall {
    /// The floor, normal `+z`, one for the batch: the loop for walls along a coordinate axis,
    /// as in rooms and channels.
    Axis,
    /// The normal `(0.6, 0, 0.8)`, one for the batch: the general loop.
    Tilted,
    /// The same tilted wall with its normal stored once per particle, as a host solver passes
    /// the normals of the faces its particles hit: three more arrays to read, and each normal
    /// checked for unit length.
    PerParticle,
}

/// One kernel configuration to time.
#[derive(Clone, Copy, Debug)]
pub struct Scenario {
    pub precision: Precision,
    /// Exponents `(p, q)`.
    pub exponents: (f64, f64),
    pub power: PowerMode,
    pub spin: bool,
    /// Friction on (`mu = 0.3`) or off (`mu = 0`, the kernel without the tangential impulse).
    pub friction: bool,
    /// Whether a tally (counts and energy) is kept.
    pub tally: bool,
    /// The wall the impacts hit, and how its normal is given.
    pub wall: Wall,
    /// Number of impacts per call.
    pub n: usize,
}

impl Scenario {
    /// A short label such as `f64 p=1 q=0.5 spin`.
    #[must_use]
    pub fn label(&self) -> String {
        let exp = |x: f64| format!("{x}");
        let power = match (self.exponents, self.power) {
            ((1.0 | 0.5, 1.0 | 0.5), _) => "",
            (_, PowerMode::Fast) => " fast-pow",
            (_, PowerMode::Exact) => " libm-pow",
        };
        format!(
            "{} p={} q={}{}{}",
            match self.precision {
                Precision::F64 => "f64",
                Precision::F32 => "f32",
            },
            exp(self.exponents.0),
            exp(self.exponents.1),
            power,
            if self.spin { " spin" } else { "" }
        ) + if self.friction { "" } else { " mu=0" }
            + if self.tally { " tally" } else { "" }
            + match self.wall {
                Wall::Axis => "",
                Wall::Tilted => " tilted",
                Wall::PerParticle => " normals",
            }
    }

    /// Whether this kernel computes exactly what [`error_against_reference`] compares it with:
    /// the f64 kernel with libm's pow, or an f64 kernel with exponents of 1 and 1/2, which take
    /// no pow in either mode. Its error is then zero by construction, not a measurement.
    #[must_use]
    pub fn is_reference(&self) -> bool {
        let plain = |x: f64| x == 1.0 || x == 0.5;
        self.precision == Precision::F64
            && (self.power == PowerMode::Exact || (plain(self.exponents.0) && plain(self.exponents.1)))
    }

    /// The law used: the li1997-sio2 constants with the scenario's exponents and friction 0.3
    /// (or none).
    #[must_use]
    pub fn law(&self) -> WallLaw {
        let (p, q) = self.exponents;
        let mu = if self.friction { 0.3 } else { 0.0 };
        WallLaw::new(LawParams { p, q, ..LawParams::symmetric(12.5, 0.065, 0.074, 1.0, 0.5).with_friction(mu) })
            .expect("valid benchmark law")
            .with_power_mode(self.power)
    }
}

/// The timing of one scenario.
#[derive(Clone, Debug)]
pub struct Measurement {
    pub scenario: Scenario,
    /// Median time of one law-kernel call.
    pub kernel: Duration,
    /// Median time of one copy-kernel call on the same arrays.
    pub ceiling: Duration,
    /// Median over the rounds of the ratio of each round's copy-kernel time to the law-kernel
    /// time right after it: see [`Measurement::fraction`].
    pub paired_fraction: f64,
}

impl Measurement {
    /// Impacts per second of the law kernel.
    #[must_use]
    pub fn rate(&self) -> f64 {
        self.scenario.n as f64 / self.kernel.as_secs_f64()
    }
    /// Impacts per second of the copy kernel.
    #[must_use]
    pub fn ceiling_rate(&self) -> f64 {
        self.scenario.n as f64 / self.ceiling.as_secs_f64()
    }
    /// The kernel's rate as a fraction of the copy kernel's. Each round's law-kernel time is
    /// set against the copy-kernel time measured just before it, and the median of those
    /// ratios is taken: bandwidth drifts within a run, and a ratio of two separate medians can
    /// pair a fast moment of one with a slow moment of the other.
    #[must_use]
    pub fn fraction(&self) -> f64 {
        self.paired_fraction
    }
    /// Bytes the kernel moves per impact (read plus written).
    #[must_use]
    pub fn bytes_per_impact(&self) -> usize {
        let size = match self.scenario.precision {
            Precision::F64 => 8,
            Precision::F32 => 4,
        };
        let arrays = if self.scenario.spin { 6 * 2 + 1 } else { 3 * 2 };
        let normals = if self.scenario.wall == Wall::PerParticle { 3 } else { 0 };
        (arrays + normals) * size + 1
    }
}

/// Structure-of-arrays particle state owned by a benchmark: random impacts on a floor
/// (normal +z) or a tilted wall (its normal given once, or once per particle), normal speeds
/// log-uniform over 0.01..10 m/s (both sides of the law's `vc`), tangential speeds up to
/// 1 m/s, spins up to 1e4 rad/s, radii 10..100 um.
pub struct Workload<T> {
    /// Velocity components, m/s.
    pub v: [Vec<T>; 3],
    /// Spin components, rad/s (empty without spin).
    pub w: [Vec<T>; 3],
    /// Radii, m (empty without spin).
    pub radius: Vec<T>,
    /// One outcome per particle.
    pub outcome: Vec<Outcome>,
    /// The wall normal of the whole batch.
    pub normal: [T; 3],
    /// The wall normal once per particle, three components (empty unless the scenario's wall
    /// is [`Wall::PerParticle`]).
    pub normals: [Vec<T>; 3],
}

impl<T: Real> Workload<T> {
    /// `n` random impacts from `seed`, with spin arrays when `spin`.
    #[must_use]
    pub fn random(n: usize, spin: bool, seed: u64) -> Self {
        let mut rng = StdRng::seed_from_u64(seed);
        let mut column =
            |f: &mut dyn FnMut(&mut StdRng) -> f64| (0..n).map(|_| T::from_f64(f(&mut rng))).collect::<Vec<T>>();
        let vx = column(&mut |r| r.random_range(-1.0..1.0));
        let vy = column(&mut |r| r.random_range(-1.0..1.0));
        // Normal speeds log-uniform over 0.01..10 m/s: both sides of vc = 0.074.
        let vz = column(&mut |r| -(10f64).powf(r.random_range(-2.0..1.0)));
        let m = if spin { n } else { 0 };
        let mut spin_column =
            |f: &mut dyn FnMut(&mut StdRng) -> f64| (0..m).map(|_| T::from_f64(f(&mut rng))).collect::<Vec<T>>();
        let w = [
            spin_column(&mut |r| r.random_range(-1e4..1e4)),
            spin_column(&mut |r| r.random_range(-1e4..1e4)),
            spin_column(&mut |r| r.random_range(-1e4..1e4)),
        ];
        let radius = spin_column(&mut |r| r.random_range(1e-5..1e-4));
        Self {
            v: [vx, vy, vz],
            w,
            radius,
            outcome: vec![Outcome::default(); n],
            normal: [T::ZERO, T::ZERO, T::ONE],
            normals: Default::default(),
        }
    }

    /// The same impacts against the wall with normal `(0.6, 0, 0.8)`: velocities and spins
    /// rotated about `y` by the angle that takes `+z` to that normal.
    #[must_use]
    pub fn tilted(mut self) -> Self {
        let (c, s) = (T::from_f64(0.8), T::from_f64(0.6));
        let rotate = |[x, _, z]: &mut [Vec<T>; 3]| {
            for (x, z) in x.iter_mut().zip(z.iter_mut()) {
                (*x, *z) = (c * *x + s * *z, c * *z - s * *x);
            }
        };
        rotate(&mut self.v);
        rotate(&mut self.w);
        self.normal = [s, T::ZERO, c];
        self
    }

    /// The workload of `scenario`: [`Workload::random`], tilted if the scenario says so, with
    /// the tilted normal copied to every particle for [`Wall::PerParticle`].
    #[must_use]
    pub fn for_scenario(scenario: &Scenario, seed: u64) -> Self {
        let work = Self::random(scenario.n, scenario.spin, seed);
        match scenario.wall {
            Wall::Axis => work,
            Wall::Tilted => work.tilted(),
            Wall::PerParticle => {
                let mut work = work.tilted();
                work.normals = work.normal.map(|c| vec![c; scenario.n]);
                work
            }
        }
    }

    /// Copies the particle state back from `pristine` (untimed, between timed calls).
    pub fn restore(&mut self, pristine: &Self) {
        for k in 0..3 {
            self.v[k].copy_from_slice(&pristine.v[k]);
            self.w[k].copy_from_slice(&pristine.w[k]);
        }
    }

    /// Applies `law` to the whole workload, with a tally when `tally`.
    pub fn law_kernel(&mut self, law: &WallLaw, tally: bool) {
        let [vx, vy, vz] = &mut self.v;
        let normals = if self.normals[0].is_empty() {
            Normals::Uniform(self.normal)
        } else {
            let [nx, ny, nz] = &self.normals;
            Normals::PerParticle([nx, ny, nz])
        };
        let batch = Impacts::new([vx, vy, vz], normals, &mut self.outcome).expect("consistent arrays");
        let batch = if self.radius.is_empty() {
            batch
        } else {
            let [wx, wy, wz] = &mut self.w;
            batch.with_spin([wx, wy, wz], &self.radius).expect("consistent arrays")
        };
        let mut sums = Tally::default();
        law.apply(batch, tally.then_some(&mut sums));
        std::hint::black_box(sums);
    }

    /// Reads and writes the same arrays as the law kernel, in the same pieces, with trivial
    /// arithmetic: the memory ceiling.
    pub fn copy_kernel(&mut self) {
        let [vx, vy, vz] = &mut self.v;
        let [wx, wy, wz] = &mut self.w;
        let [nx, ny, nz] = &self.normals;
        let outcome: &mut [u8] = bytemuck::cast_slice_mut(&mut self.outcome);
        let normals = |k: usize| (!nx.is_empty()).then(|| [&nx[k..], &ny[k..], &nz[k..]]);
        if self.radius.is_empty() {
            vx.par_chunks_mut(LEAF)
                .zip(vy.par_chunks_mut(LEAF))
                .zip(vz.par_chunks_mut(LEAF))
                .zip(outcome.par_chunks_mut(LEAF))
                .enumerate()
                .for_each(|(k, (((a, b), c), o))| copy_piece([a, b, c], None, normals(k * LEAF), o));
        } else {
            let radius = &self.radius;
            vx.par_chunks_mut(LEAF)
                .zip(vy.par_chunks_mut(LEAF))
                .zip(vz.par_chunks_mut(LEAF))
                .zip(wx.par_chunks_mut(LEAF).zip(wy.par_chunks_mut(LEAF)).zip(wz.par_chunks_mut(LEAF)))
                .zip(radius.par_chunks(LEAF).zip(outcome.par_chunks_mut(LEAF)))
                .enumerate()
                .for_each(|(k, ((((a, b), c), ((d, e), f)), (r, o)))| {
                    copy_piece([a, b, c], Some(([d, e, f], r)), normals(k * LEAF), o)
                });
        }
    }
}

/// One piece of the copy kernel: negates every velocity component (or, with a normal per
/// particle, subtracts it from the normal's component, so the normals are read), negates two
/// spin components and scales the third by the radius (so the radius is read), and writes the
/// outcome byte. Compiled for the same instruction sets as the law kernel (a baseline-only
/// build, 128-bit vectors, timed below the law kernel's AVX-512 build), with every slice cut
/// to one length so that the loop needs no bounds checks: the ceiling must be the fastest way
/// to move these bytes, or a law kernel could time above it.
#[multiversion(targets("x86_64+avx512f+avx512vl+avx512dq+avx512bw", "x86_64+avx2+fma"))]
fn copy_piece<T: Real>(
    v: [&mut [T]; 3],
    spin: Option<([&mut [T]; 3], &[T])>,
    normals: Option<[&[T]; 3]>,
    outcome: &mut [u8],
) {
    match (spin, normals) {
        (None, None) => copy_loop::<T, false, false>(v, [&mut [], &mut [], &mut []], &[], [&[]; 3], outcome),
        (None, Some(n)) => copy_loop::<T, false, true>(v, [&mut [], &mut [], &mut []], &[], n, outcome),
        (Some((w, r)), None) => copy_loop::<T, true, false>(v, w, r, [&[]; 3], outcome),
        (Some((w, r)), Some(n)) => copy_loop::<T, true, true>(v, w, r, n, outcome),
    }
}

/// The loop of [`copy_piece`] for one combination of spin arrays and per-particle normals.
#[inline(always)]
fn copy_loop<T: Real, const SPIN: bool, const NORMALS: bool>(
    v: [&mut [T]; 3],
    w: [&mut [T]; 3],
    radius: &[T],
    normals: [&[T]; 3],
    outcome: &mut [u8],
) {
    // Arrays a variant does not use are empty and stay so.
    let len = outcome.len();
    let [vx, vy, vz] = v;
    let (vx, vy, vz) = (&mut vx[..len], &mut vy[..len], &mut vz[..len]);
    let [wx, wy, wz] = w;
    let (wx, wy, wz, radius) =
        if SPIN { (&mut wx[..len], &mut wy[..len], &mut wz[..len], &radius[..len]) } else { (wx, wy, wz, radius) };
    let [nx, ny, nz] = normals;
    let (nx, ny, nz) = if NORMALS { (&nx[..len], &ny[..len], &nz[..len]) } else { (nx, ny, nz) };
    for i in 0..len {
        if NORMALS {
            vx[i] = nx[i] - vx[i];
            vy[i] = ny[i] - vy[i];
            vz[i] = nz[i] - vz[i];
        } else {
            vx[i] = -vx[i];
            vy[i] = -vy[i];
            vz[i] = -vz[i];
        }
        if SPIN {
            wx[i] = wx[i] * radius[i];
            wy[i] = -wy[i];
            wz[i] = -wz[i];
        }
        outcome[i] = 1;
    }
}

fn median(mut xs: Vec<Duration>) -> Duration {
    xs.sort();
    xs[xs.len() / 2]
}

/// Times a closure on `pool` after waking every thread of the pool with a broadcast.
pub fn timed(pool: &ThreadPool, f: impl FnOnce() + Send) -> Duration {
    pool.broadcast(|_| ());
    pool.install(|| {
        let start = Instant::now();
        f();
        start.elapsed()
    })
}

fn measure_typed<T: Real>(scenario: Scenario, pool: &ThreadPool, reps: usize) -> Measurement {
    let law = scenario.law();
    let pristine = Workload::<T>::for_scenario(&scenario, 42);
    let mut state = Workload::<T>::for_scenario(&scenario, 42);
    let (mut kernel, mut ceiling, mut ratios) = (Vec::new(), Vec::new(), Vec::new());
    for rep in 0..reps + 1 {
        state.restore(&pristine);
        let c = timed(pool, || state.copy_kernel());
        state.restore(&pristine);
        let k = timed(pool, || state.law_kernel(&law, scenario.tally));
        if rep > 0 {
            // The first round warms caches and page tables.
            kernel.push(k);
            ceiling.push(c);
            ratios.push(c.as_secs_f64() / k.as_secs_f64());
        }
    }
    ratios.sort_by(f64::total_cmp);
    Measurement {
        scenario,
        kernel: median(kernel),
        ceiling: median(ceiling),
        paired_fraction: ratios[ratios.len() / 2],
    }
}

/// Times `scenario` on `pool`: `reps` interleaved rounds of copy kernel then law kernel,
/// the medians of each and the median of the per-round ratios.
#[must_use]
pub fn measure(scenario: Scenario, pool: &ThreadPool, reps: usize) -> Measurement {
    match scenario.precision {
        Precision::F64 => measure_typed::<f64>(scenario, pool, reps),
        Precision::F32 => measure_typed::<f32>(scenario, pool, reps),
    }
}

/// The scenarios of the speed table (`docs/speed.md`) at `n` impacts.
#[must_use]
pub fn standard_scenarios(n: usize) -> Vec<Scenario> {
    let mut out = Vec::new();
    for precision in [Precision::F64, Precision::F32] {
        for spin in [false, true] {
            for (exponents, power) in [
                ((1.0, 1.0), PowerMode::Fast),
                ((1.0, 0.5), PowerMode::Fast),
                ((1.0, 0.7), PowerMode::Fast),
                ((1.3, 0.7), PowerMode::Fast),
                ((1.3, 0.7), PowerMode::Exact),
            ] {
                out.push(Scenario {
                    precision,
                    exponents,
                    power,
                    spin,
                    friction: true,
                    tally: false,
                    wall: Wall::Axis,
                    n,
                });
            }
        }
    }
    for precision in [Precision::F64, Precision::F32] {
        for exponents in [(1.0, 1.0), (1.0, 0.5)] {
            let power = PowerMode::Fast;
            out.push(Scenario {
                precision,
                exponents,
                power,
                spin: false,
                friction: false,
                tally: false,
                wall: Wall::Axis,
                n,
            });
        }
    }
    for precision in [Precision::F64, Precision::F32] {
        let (exponents, power) = ((1.0, 0.5), PowerMode::Fast);
        out.push(Scenario {
            precision,
            exponents,
            power,
            spin: false,
            friction: true,
            tally: true,
            wall: Wall::Axis,
            n,
        });
    }
    // The general loop, for a wall that is not along a coordinate axis, its normal given once
    // for the batch or once per particle.
    for wall in [Wall::Tilted, Wall::PerParticle] {
        for spin in [false, true] {
            let (precision, exponents, power) = (Precision::F64, (1.0, 0.5), PowerMode::Fast);
            out.push(Scenario { precision, exponents, power, spin, friction: true, tally: false, wall, n });
        }
    }
    out
}

/// The largest deviation of `scenario`'s results from the f64, libm-pow kernel on the same
/// `n` impacts, relative to each particle's incoming speed: `max |V - V_ref| / |v|`, with spin
/// converted to a contact-point speed `r |W - W_ref|`. The error half of "run time against error".
#[must_use]
pub fn error_against_reference(scenario: Scenario, n: usize) -> f64 {
    let reference_law = Scenario { precision: Precision::F64, power: PowerMode::Exact, ..scenario }.law();
    let scenario = Scenario { n, ..scenario };
    let mut reference = Workload::<f64>::for_scenario(&scenario, 11);
    let incoming = Workload::<f64>::for_scenario(&scenario, 11);
    reference.law_kernel(&reference_law, false);
    let law = scenario.law();
    let (v, w): ([Vec<f64>; 3], [Vec<f64>; 3]) = match scenario.precision {
        Precision::F64 => {
            let mut work = Workload::<f64>::for_scenario(&scenario, 11);
            work.law_kernel(&law, false);
            (work.v, work.w)
        }
        Precision::F32 => {
            let mut work = Workload::<f32>::for_scenario(&scenario, 11);
            work.law_kernel(&law, false);
            let widen = |c: &Vec<f32>| c.iter().map(|&x| f64::from(x)).collect::<Vec<f64>>();
            (work.v.each_ref().map(widen), work.w.each_ref().map(widen))
        }
    };
    let mut worst = 0.0f64;
    for i in 0..n {
        let speed = (0..3).map(|k| incoming.v[k][i].powi(2)).sum::<f64>().sqrt();
        let dv = (0..3).map(|k| (v[k][i] - reference.v[k][i]).powi(2)).sum::<f64>().sqrt();
        let dw = if scenario.spin {
            incoming.radius[i] * (0..3).map(|k| (w[k][i] - reference.w[k][i]).powi(2)).sum::<f64>().sqrt()
        } else {
            0.0
        };
        worst = worst.max((dv + dw) / speed);
    }
    worst
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The ceiling means something only if the copy kernel reads and writes every element of
    /// every array the law kernel touches, across piece boundaries and in both precisions.
    fn copy_kernel_touches_everything<T: Real>(spin: bool, per_particle_normals: bool) {
        let n = 3 * LEAF + 17;
        let workload = || {
            let mut work = Workload::<T>::random(n, spin, 5);
            if per_particle_normals {
                // A different value for every particle, so that a piece reading another
                // piece's normals would show.
                work.normals = [1.0, 2.0, 3.0].map(|c| (0..n).map(|i| T::from_f64(c + i as f64 / 1024.0)).collect());
            }
            work
        };
        let pristine = workload();
        let mut work = workload();
        work.copy_kernel();
        for k in 0..3 {
            let expected = |i: usize| {
                let x0 = pristine.v[k][i];
                if per_particle_normals {
                    pristine.normals[k][i] - x0
                } else {
                    -x0
                }
            };
            assert!(work.v[k].iter().enumerate().all(|(i, &x)| x == expected(i)), "velocity {k}");
        }
        if spin {
            let scaled = work.w[0].iter().zip(&pristine.w[0]).zip(&pristine.radius);
            assert!(scaled.into_iter().all(|((&x, &x0), &r)| x == x0 * r), "spin 0 scaled by the radius");
            for k in 1..3 {
                assert!(work.w[k].iter().zip(&pristine.w[k]).all(|(&x, &x0)| x == -x0), "spin {k}");
            }
        }
        assert!(bytemuck::cast_slice::<Outcome, u8>(&work.outcome).iter().all(|&o| o == 1));
    }

    #[test]
    fn the_copy_kernel_reads_and_writes_every_element() {
        for spin in [false, true] {
            for per_particle_normals in [false, true] {
                copy_kernel_touches_everything::<f64>(spin, per_particle_normals);
                copy_kernel_touches_everything::<f32>(spin, per_particle_normals);
            }
        }
    }

    /// The kernels the table calls the reference are those whose error is zero by
    /// construction, and only they: every other kernel differs from its reference.
    #[test]
    fn the_reference_kernels_are_exact_and_the_others_not() {
        for scenario in standard_scenarios(2000) {
            let error = error_against_reference(scenario, 2000);
            assert_eq!(scenario.is_reference(), error == 0.0, "{}: {error:e}", scenario.label());
        }
    }
}
