//! The random forcing: each particle's own random streams, and the standard normal variates
//! that Brownian motion and turbulent dispersion draw from them, made in blocks.
//!
//! A particle's numbers come from its id and the scene's seed alone ([`particle_rng`]), so a
//! run gives the same result on any number of threads.
//!
//! A turbulent Brownian step needs nine normal variates, and drawing them one call at a time
//! (rand_distr's `StandardNormal`, which does not inline) took a large share of the step. Here
//! they are made a block at a time by the ziggurat method of Marsaglia & Tsang (2000), laid
//! out so that the common case vectorises:
//!
//! - four xoshiro256++ streams (Blackman & Vigna 2021) run side by side, one per vector lane;
//! - each 64-bit word makes one attempt: 10 bits pick one of 1024 layers `i`, 52 other bits a
//!   uniform `u` in `[-1, 1)`, and `x = u x_i` is accepted when `|x| < x_{i+1}` (all but a
//!   fraction of a per cent of attempts), with no branch;
//! - the attempts that fall outside their layer's core finish afterwards, one by one, on a
//!   fifth (scalar) stream, exactly as the ziggurat prescribes (the wedge test, the tail, and
//!   fresh attempts until one is accepted);
//! - where the processor has AVX2 the first attempts are written in its intrinsics, the same
//!   arithmetic on the same bits (tested bit for bit against the plain version).
//!
//! The ziggurat is exact for any number of layers; more layers only make the core of each
//! layer a larger part of it, and so leave fewer attempts to the slow path, whose branches
//! mispredict and whose wedge test calls `exp`: 1024 layers rather than rand_distr's 256, for
//! an 8 KB table of edges (the shares and the speed-up are in docs/performance-log.md, "Moved
//! from the README: the tracker's speed, step by step").
//!
//! Every attempt uses fresh bits and every slot ends with exactly one accepted sample, so the
//! variates are independent standard normals: the block layout changes which bits make which
//! variate, not their distribution (tested against the normal distribution function).

use std::sync::LazyLock;

use rand::distr::Open01;
use rand::rngs::Xoshiro256PlusPlus;
use rand::{Rng, RngExt, SeedableRng};

/// Vector lanes: independent xoshiro256++ streams advanced together.
const LANES: usize = 4;
/// Ziggurat layers (a power of two: the layer is the low bits of a random word).
const LAYERS: usize = 1024;
/// Where the tail starts, `x_1 = R`: the root that makes 1024 layers of equal area close at
/// `x_1024 = 0` (solved to 40 digits; Marsaglia & Tsang's 256 layers have `R = 3.6541...`).
const TAIL: f64 = 4.038_849_846_109_505;
/// The area of each layer (and of the base layer with its tail) under `exp(-x^2/2)`,
/// `A = R f(R) + sqrt(pi/2) erfc(R / sqrt 2)`.
const LAYER_AREA: f64 = 0.001_226_324_646_353_088;

/// A random stream per particle, seeded from the scene's seed and the particle's id only.
pub(crate) fn particle_rng(seed: u64, id: u64) -> Xoshiro256PlusPlus {
    Xoshiro256PlusPlus::seed_from_u64(splitmix(seed ^ splitmix(id.wrapping_add(0x5851_f42d_4c95_7f2d))))
}

/// The random stream of copy number `copy` (from 1) of particle `id` under importance
/// splitting: independent of the particle's own stream and of its other copies'.
pub(crate) fn branch_rng(seed: u64, id: u64, copy: u64) -> Xoshiro256PlusPlus {
    particle_rng(seed ^ splitmix(copy ^ 0x2545_f491_4f6c_dd1d), id)
}

/// SplitMix64's finaliser: a bijective mix of 64 bits.
fn splitmix(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// The unnormalised normal density `exp(-x^2/2)`.
fn density(x: f64) -> f64 {
    (-0.5 * x * x).exp()
}

/// The ziggurat: layer edges `x_i` (`x_0 = A / f(R)` for the base layer, `x_1 = R`, ...,
/// `x_1024 = 0`) and the density there, `f_i = f(x_i)`.
struct Ziggurat {
    x: [f64; LAYERS + 1],
    f: [f64; LAYERS + 1],
}

static ZIGGURAT: LazyLock<Ziggurat> = LazyLock::new(|| {
    // Each layer has area A: x_{i+1} = f^-1(A / x_i + f(x_i)).
    let mut x = [0.0; LAYERS + 1];
    x[0] = LAYER_AREA / density(TAIL);
    x[1] = TAIL;
    for i in 2..LAYERS {
        x[i] = (-2.0 * (LAYER_AREA / x[i - 1] + density(x[i - 1])).ln()).sqrt();
    }
    Ziggurat { x, f: x.map(density) }
});

/// Four xoshiro256++ generators in structure-of-arrays form: `s[k][lane]` is word `k` of a
/// lane's state, so one step of all four is a handful of vector instructions.
#[derive(Clone, Debug)]
struct Xoshiro4 {
    s: [[u64; LANES]; 4],
}

impl Xoshiro4 {
    /// Four streams with states drawn from `seeder`.
    fn from_rng(seeder: &mut impl Rng) -> Self {
        let mut s = [[0u64; LANES]; 4];
        for lane in 0..LANES {
            // An all-zero state would stay zero; 256 random bits are never all zero in practice,
            // but the rule costs nothing.
            while (0..4).all(|k| s[k][lane] == 0) {
                for word in &mut s {
                    word[lane] = seeder.next_u64();
                }
            }
        }
        Self { s }
    }

    /// The next word of each stream. `rotation` must be [`Rotation::opaque`]'s.
    #[inline(always)]
    fn next(&mut self, rotation: Rotation) -> [u64; LANES] {
        let [s0, s1, s2, s3] = &mut self.s;
        let mut out = [0; LANES];
        for l in 0..LANES {
            out[l] = s0[l].wrapping_add(s3[l]).rotate_left(23).wrapping_add(s0[l]);
            let t = s1[l] << 17;
            s2[l] ^= s0[l];
            s3[l] ^= s1[l];
            s1[l] ^= s2[l];
            s0[l] ^= s3[l];
            s2[l] ^= t;
            s3[l] = (s3[l] << rotation.left) | (s3[l] >> rotation.right);
        }
        out
    }
}

/// The rotation of xoshiro256++'s last state word by 45 bits, as a left and a right shift
/// whose amounts the optimiser cannot see.
///
/// Neither SSE2 nor AVX2 has a 64-bit vector rotate. For a rotation it recognises (a constant
/// amount, or `rotate_left`) LLVM moved the four lanes out to general registers, rotated them
/// one by one and moved them back, a good part of the block's time (docs/performance-log.md).
/// Two shifts by unknown amounts and an `or` stay in
/// the vector register. The result is the same. (Where the processor has AVX2 the first
/// attempts are [`first_attempts_avx2`], whose shifts by constants stay vector shifts.)
#[derive(Clone, Copy, Debug)]
struct Rotation {
    left: u32,
    right: u32,
}

impl Rotation {
    fn opaque() -> Self {
        let (left, right) = std::hint::black_box((45, 64 - 45));
        Self { left, right }
    }
}

/// One ziggurat attempt from 64 random bits: the layer (bits 0-9), the uniform in `[-1, 1)`
/// (bits 12-63) and the candidate `x`, and whether it lies in the layer's core (accepted
/// without more work).
#[inline(always)]
fn attempt(z: &Ziggurat, bits: u64) -> (usize, f64, bool) {
    let i = (bits as usize) & (LAYERS - 1);
    // 52 bits as the mantissa of a number in [2, 4), shifted to [-1, 1).
    let u = f64::from_bits((bits >> 12) | 0x4000_0000_0000_0000) - 3.0;
    let x = u * z.x[i];
    (i, x, x.abs() < z.x[i + 1])
}

/// The most variates one [`Normals::fill`] call makes: 64 chunks of four, so that one bit of
/// a `u64` per chunk can mark the attempts left to finish.
pub(crate) const MAX_BLOCK: usize = LANES * 64;

/// A particle's standard normal variates.
#[derive(Clone, Debug)]
pub(crate) struct Normals {
    lanes: Xoshiro4,
    /// The stream that finishes the attempts outside their layer's core.
    finish: Xoshiro256PlusPlus,
}

impl Normals {
    /// Streams seeded from `seeder` (a particle's own stream).
    pub(crate) fn from_rng(seeder: &mut Xoshiro256PlusPlus) -> Self {
        let lanes = Xoshiro4::from_rng(seeder);
        let finish = Xoshiro256PlusPlus::seed_from_u64(seeder.next_u64());
        Self { lanes, finish }
    }

    /// Fills `out` with independent standard normal variates. Its length must be a multiple
    /// of four and at most [`MAX_BLOCK`].
    pub(crate) fn fill(&mut self, out: &mut [f64]) {
        assert!(out.len() % LANES == 0 && out.len() <= MAX_BLOCK, "block of {} variates", out.len());
        let z = &*ZIGGURAT;
        let rejected = first_attempts(&mut self.lanes, z, out);
        for (lane, mut chunks) in rejected.into_iter().enumerate() {
            while chunks != 0 {
                let slot = chunks.trailing_zeros() as usize * LANES + lane;
                out[slot] = finish(&mut self.finish, z, out[slot].to_bits());
                chunks &= chunks - 1;
            }
        }
    }
}

/// The first attempt for every slot of `out`: accepted values are stored as they are, the
/// others as their attempt's 64 bits (read back with `to_bits` to finish them). Returns, per
/// lane, a bit for each chunk of four slots whose attempt in that lane was not accepted.
/// [`first_attempts_avx2`] where the processor has AVX2, [`first_attempts_portable`] elsewhere.
fn first_attempts(lanes: &mut Xoshiro4, z: &Ziggurat, out: &mut [f64]) -> [u64; LANES] {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        // SAFETY: the processor has AVX2.
        return unsafe { first_attempts_avx2(lanes, z, out) };
    }
    first_attempts_portable(lanes, z, out)
}

/// [`first_attempts`] in plain Rust, branch-free so that it vectorises.
fn first_attempts_portable(lanes: &mut Xoshiro4, z: &Ziggurat, out: &mut [f64]) -> [u64; LANES] {
    let mut rejected = [0u64; LANES];
    let rotation = Rotation::opaque();
    for (c, chunk) in out.chunks_exact_mut(LANES).enumerate() {
        let bits = lanes.next(rotation);
        for l in 0..LANES {
            let (_, x, core) = attempt(z, bits[l]);
            chunk[l] = if core { x } else { f64::from_bits(bits[l]) };
            rejected[l] |= u64::from(!core) << c;
        }
    }
    rejected
}

/// [`first_attempts`] in AVX2: the same arithmetic on the same bits as
/// [`first_attempts_portable`], so the same variates (tested). What the compiler made of that
/// for AVX2 moved each lane's pair of layer edges into place with more index extractions and
/// shuffles than the two loads, two inserts and two unpacks here. The rejected attempts are
/// marked with a bit per chunk that doubles each chunk, rather than a shift by the chunk's
/// index, which takes fewer instructions (counts in docs/performance-log.md).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn first_attempts_avx2(lanes: &mut Xoshiro4, z: &Ziggurat, out: &mut [f64]) -> [u64; LANES] {
    use std::arch::x86_64::*;
    // SAFETY: each word holds four u64s.
    let load = |word: &[u64; LANES]| unsafe { _mm256_loadu_si256(word.as_ptr().cast()) };
    let [mut s0, mut s1, mut s2, mut s3] = [0, 1, 2, 3].map(|k| load(&lanes.s[k]));
    let layer_mask = _mm256_set1_epi64x((LAYERS - 1) as i64);
    let exponent = _mm256_set1_epi64x(0x4000_0000_0000_0000);
    let magnitude = _mm256_castsi256_pd(_mm256_set1_epi64x(i64::MAX));
    // Bit `c` of each lane, for chunk `c` (doubled after each chunk).
    let mut chunk_bit = _mm256_set1_epi64x(1);
    let mut rejected = _mm256_setzero_si256();
    let edges = z.x.as_ptr();
    for chunk in out.chunks_exact_mut(LANES) {
        // xoshiro256++ on the four lanes, as `Xoshiro4::next`.
        let sum = _mm256_add_epi64(s0, s3);
        let bits = _mm256_add_epi64(_mm256_or_si256(_mm256_slli_epi64::<23>(sum), _mm256_srli_epi64::<41>(sum)), s0);
        let t = _mm256_slli_epi64::<17>(s1);
        s2 = _mm256_xor_si256(s2, s0);
        s3 = _mm256_xor_si256(s3, s1);
        s1 = _mm256_xor_si256(s1, s2);
        s0 = _mm256_xor_si256(s0, s3);
        s2 = _mm256_xor_si256(s2, t);
        s3 = _mm256_or_si256(_mm256_slli_epi64::<45>(s3), _mm256_srli_epi64::<19>(s3));
        // `attempt` on the four lanes.
        let i = _mm256_and_si256(bits, layer_mask);
        let (low, high) = (_mm256_castsi256_si128(i), _mm256_extracti128_si256::<1>(i));
        let layer = [
            _mm_cvtsi128_si64(low),
            _mm_extract_epi64::<1>(low),
            _mm_cvtsi128_si64(high),
            _mm_extract_epi64::<1>(high),
        ];
        // SAFETY: `layer < LAYERS`, so `x[layer]` and `x[layer + 1]` are in the table.
        let pair = layer.map(|k| unsafe { _mm_loadu_pd(edges.add(k as usize)) });
        let (even, odd) = (
            _mm256_insertf128_pd::<1>(_mm256_castpd128_pd256(pair[0]), pair[2]),
            _mm256_insertf128_pd::<1>(_mm256_castpd128_pd256(pair[1]), pair[3]),
        );
        let (edge, next_edge) = (_mm256_unpacklo_pd(even, odd), _mm256_unpackhi_pd(even, odd));
        let u = _mm256_sub_pd(
            _mm256_castsi256_pd(_mm256_or_si256(_mm256_srli_epi64::<12>(bits), exponent)),
            _mm256_set1_pd(3.0),
        );
        let x = _mm256_mul_pd(u, edge);
        let core = _mm256_cmp_pd::<_CMP_LT_OQ>(_mm256_and_pd(x, magnitude), next_edge);
        // SAFETY: `chunk` holds four f64s.
        unsafe { _mm256_storeu_pd(chunk.as_mut_ptr(), _mm256_blendv_pd(_mm256_castsi256_pd(bits), x, core)) };
        rejected = _mm256_or_si256(rejected, _mm256_andnot_si256(_mm256_castpd_si256(core), chunk_bit));
        chunk_bit = _mm256_add_epi64(chunk_bit, chunk_bit);
    }
    let mut words = [[0u64; LANES]; 5];
    for (word, v) in words.iter_mut().zip([s0, s1, s2, s3, rejected]) {
        // SAFETY: `word` holds four u64s.
        unsafe { _mm256_storeu_si256(word.as_mut_ptr().cast(), v) };
    }
    lanes.s = [words[0], words[1], words[2], words[3]];
    words[4]
}

/// Completes the ziggurat for an attempt `bits` that fell outside its layer's core: the tail
/// below the base layer, or the wedge test, and fresh attempts from `rng` until one is
/// accepted (rand_distr's `StandardNormal` does the same, one variate at a time).
#[cold]
fn finish(rng: &mut Xoshiro256PlusPlus, z: &Ziggurat, bits: u64) -> f64 {
    let (mut i, mut x, _) = attempt(z, bits);
    loop {
        if i == 0 {
            return tail(rng, x < 0.0);
        }
        if z.f[i + 1] + (z.f[i] - z.f[i + 1]) * rng.random::<f64>() < density(x) {
            return x;
        }
        let core;
        (i, x, core) = attempt(z, rng.next_u64());
        if core {
            return x;
        }
    }
}

/// A variate from the normal tail beyond `R` (Marsaglia 1964), negative when `negative`.
fn tail(rng: &mut Xoshiro256PlusPlus, negative: bool) -> f64 {
    loop {
        let a = rng.sample::<f64, _>(Open01).ln() / TAIL;
        let b = rng.sample::<f64, _>(Open01).ln();
        if -2.0 * b >= a * a {
            return if negative { a - TAIL } else { TAIL - a };
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The standard normal distribution function, from libm's `erfc`.
    fn phi(x: f64) -> f64 {
        0.5 * libm::erfc(-x / std::f64::consts::SQRT_2)
    }

    fn sample(seed: u64, blocks: usize, block: usize) -> Vec<f64> {
        let mut normals = Normals::from_rng(&mut particle_rng(seed, 0));
        let mut out = vec![0.0; blocks * block];
        for chunk in out.chunks_exact_mut(block) {
            normals.fill(chunk);
        }
        out
    }

    #[test]
    fn each_lane_is_xoshiro256plusplus() {
        let mut seeder = particle_rng(3, 4);
        let mut lanes = Xoshiro4::from_rng(&mut seeder);
        let mut reference: Vec<Xoshiro256PlusPlus> = (0..LANES)
            .map(|l| {
                let mut seed = [0u8; 32];
                for k in 0..4 {
                    seed[8 * k..8 * k + 8].copy_from_slice(&lanes.s[k][l].to_le_bytes());
                }
                Xoshiro256PlusPlus::from_seed(seed)
            })
            .collect();
        for _ in 0..100 {
            let words = lanes.next(Rotation::opaque());
            for (l, rng) in reference.iter_mut().enumerate() {
                assert_eq!(words[l], rng.next_u64());
            }
        }
    }

    #[test]
    fn avx2_first_attempts_are_the_portable_ones_bit_for_bit() {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            let z = &*ZIGGURAT;
            let mut seeder = particle_rng(5, 6);
            let mut portable = Xoshiro4::from_rng(&mut seeder);
            let mut vector = portable.clone();
            let mut rejections = 0;
            for len in [4, 8, 36, 144, MAX_BLOCK].into_iter().cycle().take(200) {
                let (mut a, mut b) = (vec![0.0; len], vec![0.0; len]);
                let ra = first_attempts_portable(&mut portable, z, &mut a);
                // SAFETY: the processor has AVX2.
                let rb = unsafe { first_attempts_avx2(&mut vector, z, &mut b) };
                assert_eq!(ra, rb);
                assert_eq!(
                    a.iter().map(|x| x.to_bits()).collect::<Vec<_>>(),
                    b.iter().map(|x| x.to_bits()).collect::<Vec<_>>()
                );
                assert_eq!(portable.s, vector.s);
                rejections += ra.iter().map(|r| r.count_ones()).sum::<u32>();
            }
            // Some attempts fell outside their layer's core (0.43 % of about 18000).
            assert!(rejections > 20, "{rejections}");
        }
    }

    #[test]
    fn the_ziggurat_has_layers_of_equal_area_that_close_at_zero() {
        let z = &*ZIGGURAT;
        // Edges and densities computed independently in 40-digit arithmetic.
        for (i, x, f) in [
            (0, 4.273_445_303_098_994_6, 0.000_108_239_155_169_781_74),
            (2, 3.856_002_654_983_262_4, 0.000_590_596_073_134_601_8),
            (512, 1.537_312_330_250_695_6, 0.306_767_667_781_384_3),
            (1023, 0.135_063_558_635_168_85, 0.990_920_388_454_552_6),
        ] {
            assert!((z.x[i] / x - 1.0).abs() < 1e-11, "x_{i} = {}", z.x[i]);
            assert!((z.f[i] / f - 1.0).abs() < 1e-11, "f_{i} = {}", z.f[i]);
        }
        assert_eq!(z.x[LAYERS], 0.0);
        // The base layer with its tail, every layer above it, and the top one (which the
        // recursion does not impose) all have the area A.
        let base = TAIL * density(TAIL) + (std::f64::consts::PI / 2.0).sqrt() * libm::erfc(TAIL / 2f64.sqrt());
        assert!((base / LAYER_AREA - 1.0).abs() < 1e-14, "{base}");
        for i in 1..LAYERS {
            let area = z.x[i] * (z.f[i + 1] - z.f[i]);
            assert!((area / LAYER_AREA - 1.0).abs() < 1e-9, "layer {i}: {area}");
        }
        // An attempt lands in its layer's core with probability mean(x_{i+1} / x_i).
        let core = (0..LAYERS).map(|i| z.x[i + 1] / z.x[i]).sum::<f64>() / LAYERS as f64;
        assert!((core - 0.995_723_4).abs() < 1e-7, "{core}");
    }

    #[test]
    fn variates_follow_the_standard_normal_distribution() {
        let n = 1 << 20;
        let mut z = sample(11, n / 72, 72);
        let n = z.len() as f64;
        let mean = z.iter().sum::<f64>() / n;
        let var = z.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / n;
        let kurt = z.iter().map(|x| (x - mean).powi(4)).sum::<f64>() / n / (var * var);
        assert!(mean.abs() < 5.0 / n.sqrt(), "mean {mean}");
        assert!((var - 1.0).abs() < 5.0 * (2.0 / n).sqrt(), "variance {var}");
        assert!((kurt - 3.0).abs() < 5.0 * (24.0 / n).sqrt(), "kurtosis {kurt}");
        // Kolmogorov-Smirnov against Phi: the 1 % critical value is 1.63 / sqrt(n).
        z.sort_by(f64::total_cmp);
        let d = z
            .iter()
            .enumerate()
            .map(|(i, &x)| {
                let p = phi(x);
                (p - i as f64 / n).abs().max(((i + 1) as f64 / n - p).abs())
            })
            .fold(0.0, f64::max);
        assert!(d < 1.63 / n.sqrt(), "KS distance {d}");
        // The tail beyond R (from the slow path only) at its expected rate, 2 (1 - Phi(R)).
        let beyond = z.iter().filter(|x| x.abs() > TAIL).count() as f64;
        let expected = 2.0 * (1.0 - phi(TAIL)) * n;
        assert!((beyond - expected).abs() < 5.0 * expected.sqrt(), "{beyond} beyond R, expected {expected}");
    }

    #[test]
    fn the_same_seed_gives_the_same_variates_and_blocks_do_not_matter_for_the_distribution() {
        assert_eq!(sample(1, 10, 72), sample(1, 10, 72));
        assert_ne!(sample(1, 10, 72), sample(2, 10, 72));
        let short = sample(9, 4096, 8);
        let mean = short.iter().sum::<f64>() / short.len() as f64;
        assert!(mean.abs() < 5.0 / (short.len() as f64).sqrt());
    }

    #[test]
    fn streams_are_reproducible_and_distinct() {
        let a: u64 = particle_rng(7, 0).random();
        let b: u64 = particle_rng(7, 1).random();
        let c: u64 = particle_rng(8, 0).random();
        assert!(a != b && a != c && b != c);
        assert_eq!(a, particle_rng(7, 0).random::<u64>());
    }
}
