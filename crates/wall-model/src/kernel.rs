//! The batch kernel: one flat, branch-free loop per scene variant, chosen once per batch.
//!
//! A variant is the exponent pair (see [`crate::power::Exponents`]), where the normals come
//! from, and four switches fixed for the whole batch: spin tracked, friction (`mu > 0`), a
//! capture velocity per particle, tally wanted. The normals are one per particle, one for the
//! batch, or one for the batch along a coordinate axis: the walls of rooms and channels, whose
//! loop ([`AxisNormal`]) skips the products with the normal's zero components and runs about
//! 1.4 times as fast in cache. Each combination is its own monomorphised loop, so a scene pays only for
//! what it uses, and each loop is compiled for AVX-512, AVX2+FMA and baseline x86-64, picked
//! at run time (`multiversion`). The loop body calls [`crate::impact::resolve_with_powers`],
//! which the scalar API's [`crate::impact::resolve`] calls too, so batch and scalar results
//! agree bit for bit (on an axis wall, up to the sign of zeros, with energies summed in the
//! rotated order). The power of a general exponent (not 1 or 1/2) is evaluated first, a block
//! of particles at a time, in passes of its own: the bases, then the division of its `log2`,
//! the polynomial of its `log2`, and its `exp2` (see [`crate::power::Power::STAGED`]). In
//! cache that takes a sixth to 30 % off those loops' time.
//! No fast-math and no implicit FMA contraction: the fused multiply-adds the code asks for
//! (`mul_add`) are correctly rounded on every build (libm's `fma` where the CPU has none,
//! slowly), so the three instruction sets give identical results too by construction (the
//! tests run whichever build the machine selects).
//!
//! Above [`PARALLEL_MIN`] particles the batch is halved recursively down to [`LEAF`]-sized
//! pieces run by rayon on the current thread pool. The halving and the order in which tallies
//! are added depend only on the batch length, so results, tallies included, are identical
//! for any number of threads.

use multiversion::multiversion;

use crate::batch::{Impacts, Normals, Outcome, SpinArrays, Tally, UNIT_SQUARED_MAX, UNIT_SQUARED_MIN};
use crate::energy::{energy_loss, EnergyLoss};
use crate::impact::{resolve_with_powers, AxisNormal, CaptureMode, Frame};
use crate::law::{self, LawConstants, Powers};
use crate::power::{with_powers, Exponents, Power, PowerMode};
use crate::real::{select, Real};

/// Batches shorter than this run on the calling thread in one piece (no thread overhead).
pub const PARALLEL_MIN: usize = 1 << 16;
/// The size of the pieces a large batch is cut into for the threads.
pub const LEAF: usize = 1 << 14;
/// The most threads a pool of depo's may be asked for (the C ABI's `depo_set_num_threads`,
/// the command line's `--threads`): beyond any machine's cores, a larger pool only takes
/// minutes to start and to wake.
pub const MAX_THREADS: usize = 1024;
/// Independent accumulators of the tally's energy sums (keeps them vectorisable).
const LANES: usize = 8;
/// Particles per block where a sweep works a block at a time: general exponents' powers are
/// evaluated for a block in passes of their own, and a tally stores a block's energy losses
/// before it sums them. For the powers (then in two passes each), in cache on a Zen 3 core,
/// blocks of 512 took 6-10 % less time than blocks of 256, blocks of 1024 no less again, and
/// blocks of 64 more than no passes at all.
///
/// The rows of a block live on the stack and are zeroed on every call: 16 KiB in `f64` for
/// the staged powers, as much again for a tally. On a Zen 3 core a call with one impact
/// (`f64`, friction, axis wall) took 77 ns, 300 ns with a tally, and 310 ns with a general
/// `q`; from about 4096 impacts on, the zeroing is lost in the work. Rows on the heap sized
/// to the batch took the small calls to 117 and 128 ns, but made the tally loops of large
/// batches 7-12 % slower (most likely because the compiler can no longer tell that the rows
/// and the particle arrays do not overlap), so they were not kept. Hosts with many small
/// batches do better to gather them into one call.
const BLOCK: usize = 512;

/// Everything about a law that the kernel needs, fixed for one batch.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Setup<T> {
    pub(crate) constants: LawConstants<T>,
    pub(crate) exponents: Exponents,
    pub(crate) power: PowerMode,
    pub(crate) capture: CaptureMode,
}

/// Applies the law to a whole batch, returning its tally (all zero unless `want_tally`).
/// With `parallel` false a large batch is cut into the same pieces, run one after the other on
/// the calling thread and summed in the same order: the same results, and no thread is woken.
pub(crate) fn apply<T: Real>(setup: &Setup<T>, batch: Impacts<'_, T>, want_tally: bool, parallel: bool) -> Tally {
    if batch.len() < PARALLEL_MIN {
        run_piece(setup, batch, want_tally)
    } else {
        split(setup, batch, want_tally, parallel)
    }
}

fn split<T: Real>(setup: &Setup<T>, batch: Impacts<'_, T>, want_tally: bool, parallel: bool) -> Tally {
    if batch.len() <= LEAF {
        return run_piece(setup, batch, want_tally);
    }
    // Cut on a 64-particle boundary so that pieces start on cache-line boundaries.
    let mid = (batch.len() / 2).next_multiple_of(64);
    let (first, second) = batch.split_at(mid);
    let halves = (|| split(setup, first, want_tally, parallel), || split(setup, second, want_tally, parallel));
    let (mut tally, rest) = if parallel { rayon::join(halves.0, halves.1) } else { (halves.0(), halves.1()) };
    tally += rest;
    tally
}

/// Expands `$body` once for each combination of the named booleans, each bound to a `const`.
macro_rules! with_const_bools {
    ($body:expr;) => { $body };
    ($body:expr; $value:expr => $name:ident $(, $rest_value:expr => $rest_name:ident)*) => {
        if $value {
            const $name: bool = true;
            with_const_bools!($body; $($rest_value => $rest_name),*)
        } else {
            const $name: bool = false;
            with_const_bools!($body; $($rest_value => $rest_name),*)
        }
    };
}

/// Where each particle's wall normal comes from, and whether it is a valid one.
trait NormalSource<T: Real>: Copy {
    type Frame: Frame<T>;
    /// Particle `i`'s normal, and false when it is not of unit length within 1e-4.
    fn at(&self, i: usize) -> (Self::Frame, bool);
}

/// One normal for the whole batch (validated when the batch was made).
#[derive(Clone, Copy)]
struct Uniform<F>(F);

impl<T: Real, F: Frame<T>> NormalSource<T> for Uniform<F> {
    type Frame = F;
    #[inline(always)]
    fn at(&self, _: usize) -> (F, bool) {
        (self.0, true)
    }
}

/// One normal per particle, checked for unit length as it is read.
#[derive(Clone, Copy)]
struct PerParticle<'a, T> {
    n: [&'a [T]; 3],
    unit_squared: (T, T),
}

impl<T: Real> NormalSource<T> for PerParticle<'_, T> {
    type Frame = [T; 3];
    #[inline(always)]
    fn at(&self, i: usize) -> ([T; 3], bool) {
        let n = [self.n[0][i], self.n[1][i], self.n[2][i]];
        let nn = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
        (n, (nn >= self.unit_squared.0) & (nn <= self.unit_squared.1))
    }
}

/// `Some((axis, sign))` when `n` is exactly `sign` times a coordinate axis.
fn axis_of<T: Real>(n: [T; 3]) -> Option<(usize, T)> {
    let axis = n.iter().position(|c| c.abs() == T::ONE)?;
    let others_zero = (1..3).all(|k| n[(axis + k) % 3] == T::ZERO);
    others_zero.then_some((axis, n[axis]))
}

/// Picks the variant for this piece and runs its loop. A uniform normal along a coordinate
/// axis (the walls of rooms and channels) takes the loop of [`AxisNormal`], with the arrays
/// rotated so that the wall's axis comes third.
fn run_piece<T: Real>(setup: &Setup<T>, mut batch: Impacts<'_, T>, want_tally: bool) -> Tally {
    match batch.normals {
        Normals::PerParticle(n) => {
            let unit_squared = (T::from_f64(UNIT_SQUARED_MIN), T::from_f64(UNIT_SQUARED_MAX));
            run_with(setup, &mut batch, PerParticle { n, unit_squared }, want_tally)
        }
        Normals::Uniform(n) => match axis_of(n) {
            Some((axis, sign)) => {
                batch.rotate_axes((axis + 1) % 3);
                run_with(setup, &mut batch, Uniform(AxisNormal { sign }), want_tally)
            }
            None => run_with(setup, &mut batch, Uniform(n), want_tally),
        },
    }
}

fn run_with<T: Real, S: NormalSource<T>>(
    setup: &Setup<T>,
    batch: &mut Impacts<'_, T>,
    normals: S,
    want_tally: bool,
) -> Tally {
    let c = &setup.constants;
    let spin = batch.spin.is_some();
    let friction = c.mu > T::ZERO;
    let per_particle_vc = batch.capture_velocity.is_some();
    with_powers!(setup.exponents, setup.power, (c.p, c.q), |p, q| {
        with_const_bools!(
            sweep::<T, _, _, S, SPIN, FRICTION, PER_VC, TALLY>(c, p, q, setup.capture, batch, normals);
            spin => SPIN, friction => FRICTION, per_particle_vc => PER_VC, want_tally => TALLY
        )
    })
}

/// True when all are finite: `x - x` is 0 for finite `x` and NaN otherwise, and the sum of
/// such terms is 0 only when all are (adds run on other pipes than compares).
#[inline(always)]
#[allow(clippy::eq_op)] // `x - x` is the point: NaN exactly when `x` is not finite.
fn all_finite<T: Real, const N: usize>(x: [T; N]) -> bool {
    let mut sum = x[0] - x[0];
    for y in &x[1..] {
        sum += *y - *y;
    }
    sum == T::ZERO
}

// The outcome codes rise with precedence (invalid over skipped over captured over rebound),
// so the kernel picks a particle's code as the largest of its candidates.
const _: () = assert!(
    Outcome::REBOUND.0 < Outcome::CAPTURED.0
        && Outcome::CAPTURED.0 < Outcome::SKIPPED.0
        && Outcome::SKIPPED.0 < Outcome::INVALID.0
);

/// A staged power over a block, one pass per stage, each pass a short chain that vectorises
/// alone: `values` holds the bases on entry and the powers on return; `aside` holds the first
/// stage's second number until the second stage.
#[inline(always)]
fn power_in_passes<T: Real, P: Power<T>>(p: P, values: &mut [T], aside: &mut [T]) {
    for (value, other) in values.iter_mut().zip(aside.iter_mut()) {
        [*value, *other] = p.start(*value);
    }
    for (value, other) in values.iter_mut().zip(aside.iter()) {
        *value = p.middle([*value, *other]);
    }
    for value in values.iter_mut() {
        *value = p.finish(*value);
    }
}

/// The loop over one piece of a batch, for one variant.
#[multiversion(targets("x86_64+avx512f+avx512vl+avx512dq+avx512bw", "x86_64+avx2+fma"))]
fn sweep<
    T: Real,
    P: Power<T>,
    Q: Power<T>,
    S: NormalSource<T>,
    const SPIN: bool,
    const FRICTION: bool,
    const PER_VC: bool,
    const TALLY: bool,
>(
    c: &LawConstants<T>,
    p: P,
    q: Q,
    mode: CaptureMode,
    batch: &mut Impacts<'_, T>,
    normals: S,
) -> Tally {
    let len = batch.len();
    let Impacts { velocity, spin, capture_velocity, outcome, .. } = batch;
    let [vx, vy, vz] = velocity;
    // Re-slicing to `len` lets the compiler drop every bounds check in the loop.
    let (vx, vy, vz) = (&mut vx[..len], &mut vy[..len], &mut vz[..len]);
    let outcome: &mut [u8] = bytemuck::cast_slice_mut::<Outcome, u8>(&mut outcome[..len]);
    let (wx, wy, wz, radius): (&mut [T], &mut [T], &mut [T], &[T]) = match spin {
        Some(SpinArrays { w: [wx, wy, wz], radius }) if SPIN => {
            (&mut wx[..len], &mut wy[..len], &mut wz[..len], &radius[..len])
        }
        _ => (&mut [], &mut [], &mut [], &[]),
    };
    let vcs: &[T] = match capture_velocity {
        Some(vc) if PER_VC => &vc[..len],
        _ => &[],
    };

    // The law of particle `i`: the batch's, or with the particle's own capture velocity.
    let law_at = |i: usize| if PER_VC { c.with_capture_velocity(vcs[i]) } else { *c };

    // The piece is swept in blocks. General exponents' powers are evaluated first, for the
    // whole block: the bases in one pass, then each staged power one pass per stage (see
    // `Power::STAGED`). Such short passes keep more particles in flight than a loop in which
    // every impact waits for a long chain of polynomials.
    let mut powers = [[T::ZERO; BLOCK]; 4];
    let mut counts = [0u64; 4];
    let mut energy = [[0.0f64; LANES]; 4];
    let mut scratch = [[T::ZERO; BLOCK]; 4];
    // Without staged powers or a tally, one block is the whole piece: a flat loop.
    let block = if P::STAGED || Q::STAGED || TALLY { BLOCK } else { len };
    let mut base = 0;
    while base < len {
        let m = block.min(len - base);
        if P::STAGED || Q::STAGED {
            let [material, material_aside, adhesion, adhesion_aside] = &mut powers;
            #[allow(clippy::needless_range_loop)] // one index for the particle and two rows
            for j in 0..m {
                let i = base + j;
                let vn = normals.at(i).0.split([vx[i], vy[i], vz[i]]).0;
                [material[j], adhesion[j]] = law::power_bases(&law_at(i), -vn);
            }
            if P::STAGED {
                power_in_passes(p, &mut material[..m], &mut material_aside[..m]);
            }
            if Q::STAGED {
                power_in_passes(q, &mut adhesion[..m], &mut adhesion_aside[..m]);
            }
        }

        let mut particle = |j: usize| -> (u8, EnergyLoss<T>) {
            let i = base + j;
            let v = [vx[i], vy[i], vz[i]];
            let (n, unit_normal) = normals.at(i);
            let (w, r) = if SPIN { ([wx[i], wy[i], wz[i]], radius[i]) } else { ([T::ZERO; 3], T::ONE) };
            let law = law_at(i);
            let law_powers = if P::STAGED || Q::STAGED {
                // The block's staged powers; a power that is not staged from its base here.
                let material = if P::STAGED { powers[0][j] } else { p.pow(powers[0][j]) };
                let adhesion = if Q::STAGED { powers[2][j] } else { q.pow(powers[2][j]) };
                Powers { material, adhesion }
            } else {
                law::powers(&law, p, q, -n.split(v).0)
            };
            let res = resolve_with_powers::<T, SPIN, FRICTION>(&law, law_powers, mode, v, w, r, n);

            let mut valid = all_finite(v) & unit_normal;
            if SPIN {
                // The radius joins the finiteness sum: `r < inf` beside `r > 0` became an
                // integer range check (8 more instructions per four impacts, AVX2, f64). The
                // floor is `1 / BIG` rather than 0: the spin change goes as `1 / r`, which for a
                // subnormal radius overflowed to an infinite spin on a "rebound".
                valid &= all_finite([w[0], w[1], w[2], r]) & (r >= T::ONE / T::BIG);
            }
            if PER_VC {
                valid &= vcs[i].is_finite();
            }
            let impact = res.normal_velocity < T::ZERO;
            let update = valid & impact;
            // The outcome byte is stored before the velocities. Stored after them, LLVM turned
            // the first velocity store, `select(update, new, old)` of a value just loaded from
            // the same place, into a masked store (`vmaskmovpd`), which is slow on AMD cores:
            // in cache on a Zen 3 core the loops took 5-25 % longer with it. The code is chosen
            // among floats and narrowed to a byte once: chosen among bytes, LLVM narrowed each
            // of the three conditions first (in the f64 friction loop 19 of 86 instructions per
            // four impacts were packs, extracts and byte blends; then 7 of 81), and the f64
            // friction loops took 7-9 % longer in cache. The code is the largest of three
            // candidates (the codes rise with precedence): nested selects let LLVM move the
            // invalid case after the narrowing, as a byte blend on a narrowed mask. The
            // larger of two is written as a select, which is one `vmaxpd`; `f64::max` adds a
            // NaN check, and no candidate is NaN.
            let as_real = |o: Outcome| T::from_f64(f64::from(o.0));
            let larger = |a: T, b: T| select(a > b, a, b);
            let code = larger(
                larger(
                    select(res.coefficients.captured, as_real(Outcome::CAPTURED), as_real(Outcome::REBOUND)),
                    select(impact, T::ZERO, as_real(Outcome::SKIPPED)),
                ),
                select(valid, T::ZERO, as_real(Outcome::INVALID)),
            )
            .small_int_to_byte();
            outcome[i] = code;
            vx[i] = select(update, res.velocity[0], v[0]);
            vy[i] = select(update, res.velocity[1], v[1]);
            vz[i] = select(update, res.velocity[2], v[2]);
            if SPIN {
                wx[i] = select(update, res.spin[0], w[0]);
                wy[i] = select(update, res.spin[1], w[1]);
                wz[i] = select(update, res.spin[2], w[2]);
            }
            let loss = if TALLY {
                let l = energy_loss(&res);
                let keep = |x: T| select(update, x, T::ZERO);
                EnergyLoss {
                    material: keep(l.material),
                    adhesion: keep(l.adhesion),
                    friction: keep(l.friction),
                    deposition: keep(l.deposition),
                }
            } else {
                EnergyLoss::default()
            };
            (code, loss)
        };

        if !TALLY {
            for j in 0..m {
                particle(j);
            }
            base += m;
            continue;
        }

        // With a tally: the loop stays a plain vectorisable loop that stores each particle's
        // losses in a scratch block and counts outcomes with integer sums; each block is then
        // added up in LANES independent chains. The order depends only on the piece's length.
        // 32-bit counts within a block keep the loop's lanes as narrow as f32's.
        let mut block_counts = [0u32; 4];
        #[allow(clippy::needless_range_loop)] // one index for the particle and four scratch rows
        for j in 0..m {
            let (code, loss) = particle(j);
            for (k, count) in block_counts.iter_mut().enumerate() {
                *count += u32::from(code == k as u8);
            }
            scratch[0][j] = loss.material;
            scratch[1][j] = loss.adhesion;
            scratch[2][j] = loss.friction;
            scratch[3][j] = loss.deposition;
        }
        for (total, block) in counts.iter_mut().zip(block_counts) {
            *total += u64::from(block);
        }
        for (sums, block) in energy.iter_mut().zip(&scratch) {
            let chunks = block[..m].chunks_exact(LANES);
            let rest = chunks.remainder();
            for chunk in chunks {
                for lane in 0..LANES {
                    sums[lane] += chunk[lane].to_f64();
                }
            }
            for (lane, x) in rest.iter().enumerate() {
                sums[lane] += x.to_f64();
            }
        }
        base += m;
    }
    if !TALLY {
        return Tally::default();
    }
    let total = |sums: &[f64; LANES]| sums.iter().fold(0.0, |acc, x| acc + x);
    Tally {
        rebound: counts[0],
        captured: counts[1],
        skipped: counts[2],
        invalid: counts[3],
        energy: EnergyLoss {
            material: total(&energy[0]),
            adhesion: total(&energy[1]),
            friction: total(&energy[2]),
            deposition: total(&energy[3]),
        },
    }
}
