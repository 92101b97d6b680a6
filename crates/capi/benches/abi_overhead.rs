//! What the C ABI adds to the kernel: `depo_apply_f64` against `WallLaw::apply` on the same
//! 1e6-impact batch (f64, tally on), timed interleaved, on the current thread pool; and the
//! time per call of small batches (10 and 2000 impacts) with no thread cap, `depo_set_num_threads(1)`
//! and a cap of 2, which must all run on the calling thread at the same cost.
//!
//! The C entry points are compiled into this bench from the crate's source (the library itself
//! is built only as cdylib/staticlib) and called exactly as C calls them.
//! `cargo bench -p depo-capi --bench abi_overhead`

#[allow(dead_code, unused_imports)]
#[path = "../src/lib.rs"]
mod capi;

use std::time::{Duration, Instant};

use capi::{
    depo_apply_f64, depo_apply_strided_f64, depo_law_free, depo_law_preset, depo_set_num_threads, DepoImpactsF64,
    DepoStrides, DepoTally, DepoWallLaw, DEPO_OK,
};
use criterion::{criterion_group, criterion_main, BatchSize, Criterion, Throughput};
use depo_wall_model::{Impacts, Normals, Outcome, Tally, WallLaw};

const N: usize = 1_000_000;

struct Data {
    v: [Vec<f64>; 3],
    outcome: Vec<u8>,
}

impl Data {
    fn new() -> Self {
        let col = |f: &dyn Fn(usize) -> f64| (0..N).map(f).collect::<Vec<f64>>();
        Self {
            v: [
                col(&|i| ((i * 7919) % 1013) as f64 / 1013.0 - 0.5),
                col(&|i| ((i * 104_729) % 997) as f64 / 997.0 - 0.5),
                col(&|i| -0.01 - ((i * 31) % 1009) as f64 / 100.0),
            ],
            outcome: vec![0; N],
        }
    }
}

fn through_rust(law: &WallLaw, d: &mut Data, pristine: &Data) -> Duration {
    for k in 0..3 {
        d.v[k].copy_from_slice(&pristine.v[k]);
    }
    let [vx, vy, vz] = &mut d.v;
    let outcome: &mut [Outcome] = bytemuck_cast(&mut d.outcome);
    let start = Instant::now();
    let batch = Impacts::new([vx, vy, vz], Normals::Uniform([0.0, 0.0, 1.0]), outcome).unwrap();
    let mut tally = Tally::default();
    law.apply(batch, Some(&mut tally));
    let elapsed = start.elapsed();
    std::hint::black_box(tally);
    elapsed
}

fn through_c(law: *const DepoWallLaw, d: &mut Data, pristine: &Data) -> Duration {
    for k in 0..3 {
        d.v[k].copy_from_slice(&pristine.v[k]);
    }
    let [vx, vy, vz] = &mut d.v;
    let start = Instant::now();
    let mut batch = DepoImpactsF64 {
        n: N,
        vx: vx.as_mut_ptr(),
        vy: vy.as_mut_ptr(),
        vz: vz.as_mut_ptr(),
        wx: std::ptr::null_mut(),
        wy: std::ptr::null_mut(),
        wz: std::ptr::null_mut(),
        radius: std::ptr::null(),
        nx: std::ptr::null(),
        ny: std::ptr::null(),
        nz: std::ptr::null(),
        normal: [0.0, 0.0, 1.0],
        outcome: d.outcome.as_mut_ptr(),
    };
    let mut tally = DepoTally::default();
    let status = unsafe { depo_apply_f64(law, &mut batch, &mut tally) };
    let elapsed = start.elapsed();
    assert_eq!(status, DEPO_OK);
    std::hint::black_box(tally);
    elapsed
}

fn bytemuck_cast(bytes: &mut [u8]) -> &mut [Outcome] {
    // SAFETY: Outcome is a transparent u8 newtype; every byte value is a valid Outcome.
    unsafe { std::slice::from_raw_parts_mut(bytes.as_mut_ptr().cast(), bytes.len()) }
}

fn overhead(c: &mut Criterion) {
    let law = WallLaw::preset("sim-70um").unwrap();
    let mut c_law: *mut DepoWallLaw = std::ptr::null_mut();
    assert_eq!(unsafe { depo_law_preset(c"sim-70um".as_ptr(), &mut c_law) }, DEPO_OK);
    let pristine = Data::new();
    let mut data = Data::new();
    let (mut rust_total, mut c_total) = (Duration::ZERO, Duration::ZERO);

    let mut group = c.benchmark_group("abi 1e6 f64 tally");
    group.sample_size(20).throughput(Throughput::Elements(N as u64));
    group.bench_function("rust WallLaw::apply", |b| {
        b.iter_custom(|iters| {
            let mut total = Duration::ZERO;
            for _ in 0..iters {
                total += through_rust(&law, &mut data, &pristine);
                c_total += through_c(c_law, &mut data, &pristine);
            }
            rust_total += total;
            total
        })
    });
    group.bench_function("C depo_apply_f64", |b| {
        b.iter_custom(|iters| {
            let mut total = Duration::ZERO;
            for _ in 0..iters {
                rust_total += through_rust(&law, &mut data, &pristine);
                total += through_c(c_law, &mut data, &pristine);
            }
            c_total += total;
            total
        })
    });
    group.finish();
    println!(
        "C ABI overhead on a 1e6-impact batch, interleaved: {:+.1} % of the Rust call's time",
        100.0 * (c_total.as_secs_f64() / rust_total.as_secs_f64() - 1.0)
    );
    unsafe { depo_law_free(c_law) };
}

/// Time per call of a small batch (below the parallel threshold) by thread cap: small batches
/// run on the calling thread whatever the cap, so the three must cost the same.
fn small_batches(c: &mut Criterion) {
    let mut law: *mut DepoWallLaw = std::ptr::null_mut();
    assert_eq!(unsafe { depo_law_preset(c"sim-70um".as_ptr(), &mut law) }, DEPO_OK);
    let pristine = Data::new();
    for n in [10, 2000] {
        let mut group = c.benchmark_group(format!("abi {n} f64 tally by thread cap"));
        group.throughput(Throughput::Elements(n as u64));
        for (cap, label) in [(0, "uncapped"), (1, "cap 1 (caller)"), (2, "cap 2")] {
            assert_eq!(depo_set_num_threads(cap), DEPO_OK);
            let fresh = || {
                ([pristine.v[0][..n].to_vec(), pristine.v[1][..n].to_vec(), pristine.v[2][..n].to_vec()], vec![0u8; n])
            };
            group.bench_function(label, |b| {
                b.iter_batched_ref(
                    fresh,
                    |(v, outcome)| {
                        let [vx, vy, vz] = v;
                        let mut batch = DepoImpactsF64 {
                            n,
                            vx: vx.as_mut_ptr(),
                            vy: vy.as_mut_ptr(),
                            vz: vz.as_mut_ptr(),
                            wx: std::ptr::null_mut(),
                            wy: std::ptr::null_mut(),
                            wz: std::ptr::null_mut(),
                            radius: std::ptr::null(),
                            nx: std::ptr::null(),
                            ny: std::ptr::null(),
                            nz: std::ptr::null(),
                            normal: [0.0, 0.0, 1.0],
                            outcome: outcome.as_mut_ptr(),
                        };
                        let mut tally = DepoTally::default();
                        let status = unsafe { depo_apply_f64(law, &mut batch, &mut tally) };
                        assert_eq!(status, DEPO_OK);
                        std::hint::black_box(tally)
                    },
                    BatchSize::SmallInput,
                )
            });
        }
        group.finish();
    }
    assert_eq!(depo_set_num_threads(0), DEPO_OK);
    unsafe { depo_law_free(law) };
}

/// The same 1e6 impacts kept as an array of structures (velocity and outcome of a particle
/// side by side, 32 bytes apart) through `depo_apply_strided_f64`, against contiguous arrays
/// through `depo_apply_f64`, interleaved: what gathering and scattering costs over the
/// kernel.
fn strided(c: &mut Criterion) {
    #[repr(C)]
    #[derive(Clone, Copy)]
    struct Parcel {
        v: [f64; 3],
        outcome: u8,
    }
    let mut law: *mut DepoWallLaw = std::ptr::null_mut();
    assert_eq!(unsafe { depo_law_preset(c"sim-70um".as_ptr(), &mut law) }, DEPO_OK);
    let pristine = Data::new();
    let mut data = Data::new();
    let aos: Vec<Parcel> =
        (0..N).map(|i| Parcel { v: [pristine.v[0][i], pristine.v[1][i], pristine.v[2][i]], outcome: 0 }).collect();
    let mut parcels = aos.clone();
    let size = std::mem::size_of::<Parcel>();
    let strides = DepoStrides { v: [size; 3], w: [0; 3], radius: 0, normals: [0; 3], outcome: size };
    let through_strided = |parcels: &mut Vec<Parcel>| {
        parcels.copy_from_slice(&aos);
        let base = parcels.as_mut_ptr().cast::<u8>();
        let start = Instant::now();
        let mut batch = DepoImpactsF64 {
            n: N,
            vx: base.cast(),
            vy: unsafe { base.add(8) }.cast(),
            vz: unsafe { base.add(16) }.cast(),
            wx: std::ptr::null_mut(),
            wy: std::ptr::null_mut(),
            wz: std::ptr::null_mut(),
            radius: std::ptr::null(),
            nx: std::ptr::null(),
            ny: std::ptr::null(),
            nz: std::ptr::null(),
            normal: [0.0, 0.0, 1.0],
            outcome: unsafe { base.add(24) },
        };
        let mut tally = DepoTally::default();
        let status = unsafe { depo_apply_strided_f64(law, &mut batch, &strides, &mut tally) };
        let elapsed = start.elapsed();
        assert_eq!(status, DEPO_OK);
        std::hint::black_box(tally);
        elapsed
    };
    let (mut contiguous_total, mut strided_total) = (Duration::ZERO, Duration::ZERO);
    let mut group = c.benchmark_group("abi 1e6 f64 tally, strided");
    group.sample_size(20).throughput(Throughput::Elements(N as u64));
    group.bench_function("C depo_apply_strided_f64 (array of structures)", |b| {
        b.iter_custom(|iters| {
            let mut total = Duration::ZERO;
            for _ in 0..iters {
                total += through_strided(&mut parcels);
                contiguous_total += through_c(law, &mut data, &pristine);
            }
            strided_total += total;
            total
        })
    });
    group.finish();
    println!(
        "strided (array of structures) over contiguous on a 1e6-impact batch, interleaved: {:.2} times the time",
        strided_total.as_secs_f64() / contiguous_total.as_secs_f64()
    );
    unsafe { depo_law_free(law) };
}

criterion_group!(benches, overhead, small_batches, strided);
criterion_main!(benches);
