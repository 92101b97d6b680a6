//! Criterion benches of the wall-law batch kernel, each timed interleaved with a copy kernel
//! that moves the same bytes (the memory ceiling), on a 2-thread pool.
//!
//! Every timed iteration runs the copy kernel and the law kernel back to back on the same
//! arrays, waking the pool first; criterion reports the law kernel, and each group ends with a
//! line giving the law kernel's rate as a fraction of the interleaved copy kernel's.
//! `cargo bench --bench wall_kernel`; `DEPO_BENCH_THREADS` sets the thread count.

use std::time::Duration;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use depo::bench::{standard_scenarios, timed, Precision, Scenario, Workload};
use depo::wall_model::Real;

const SIZES: [usize; 3] = [10_000, 1_000_000, 10_000_000];

fn pool() -> rayon::ThreadPool {
    let threads = std::env::var("DEPO_BENCH_THREADS").ok().and_then(|v| v.parse().ok()).unwrap_or(2);
    rayon::ThreadPoolBuilder::new().num_threads(threads).build().expect("thread pool")
}

fn bench_scenario<T: Real>(c: &mut Criterion, pool: &rayon::ThreadPool, template: Scenario) {
    let mut group = c.benchmark_group(template.label());
    group.sample_size(10).warm_up_time(Duration::from_millis(500)).measurement_time(Duration::from_secs(2));
    for n in SIZES {
        let scenario = Scenario { n, ..template };
        let law = scenario.law();
        let pristine = Workload::<T>::for_scenario(&scenario, 7);
        let mut work = Workload::<T>::for_scenario(&scenario, 7);
        let (mut law_time, mut copy_time) = (Duration::ZERO, Duration::ZERO);
        group.throughput(Throughput::Elements(n as u64));
        group.bench_function(BenchmarkId::from_parameter(n), |b| {
            b.iter_custom(|iters| {
                let mut total = Duration::ZERO;
                for _ in 0..iters {
                    work.restore(&pristine);
                    copy_time += timed(pool, || work.copy_kernel());
                    work.restore(&pristine);
                    let t = timed(pool, || work.law_kernel(&law, scenario.tally));
                    law_time += t;
                    total += t;
                }
                total
            })
        });
        if law_time > Duration::ZERO {
            println!(
                "{} N={n}: {:.2} of the interleaved copy-kernel ceiling",
                scenario.label(),
                copy_time.as_secs_f64() / law_time.as_secs_f64()
            );
        }
    }
    group.finish();
}

fn kernels(c: &mut Criterion) {
    let pool = pool();
    for scenario in standard_scenarios(0) {
        match scenario.precision {
            Precision::F64 => bench_scenario::<f64>(c, &pool, scenario),
            Precision::F32 => bench_scenario::<f32>(c, &pool, scenario),
        }
    }
}

criterion_group!(benches, kernels);
criterion_main!(benches);
