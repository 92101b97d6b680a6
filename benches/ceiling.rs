//! Prints the wall-law kernel's throughput as a fraction of a copy kernel that moves the same
//! bytes, timed interleaved in the same run (see `depo::bench`), and each kernel's largest
//! deviation from the f64 libm-pow kernel relative to the incoming speed: run time against error.
//!
//! `cargo bench --bench ceiling` (2 threads, N = 1e7); `DEPO_BENCH_N`, `DEPO_BENCH_THREADS`
//! and `DEPO_BENCH_REPS` override the defaults; `DEPO_BENCH_FILTER` keeps the kernels whose label
//! contains it.

use depo::bench::{error_against_reference, measure, standard_scenarios};

fn env(name: &str, default: usize) -> usize {
    std::env::var(name).ok().and_then(|v| v.parse().ok()).unwrap_or(default)
}

fn main() {
    // `cargo bench` passes `--bench`; under `cargo test --benches` run a tiny size once.
    let testing = !std::env::args().any(|a| a == "--bench");
    let n = if testing { 1 << 17 } else { env("DEPO_BENCH_N", 10_000_000) };
    let threads = env("DEPO_BENCH_THREADS", 2);
    let reps = if testing { 1 } else { env("DEPO_BENCH_REPS", 9) };
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().expect("thread pool");
    println!("N = {n}, {threads} threads, median of {reps} interleaved rounds");
    println!(
        "{:<28} {:>12} {:>12} {:>9} {:>8} {:>12}",
        "kernel", "Mimpacts/s", "ceiling", "fraction", "GB/s", "max error"
    );
    let filter = std::env::var("DEPO_BENCH_FILTER").unwrap_or_default();
    for scenario in standard_scenarios(n).into_iter().filter(|s| s.label().contains(&filter)) {
        let m = measure(scenario, &pool, reps);
        let gbs = m.rate() * m.bytes_per_impact() as f64 / 1e9;
        let error = error_against_reference(scenario, if testing { 1000 } else { 200_000 });
        println!(
            "{:<28} {:>12.0} {:>12.0} {:>9.2} {:>8.1} {:>12.1e}",
            scenario.label(),
            m.rate() / 1e6,
            m.ceiling_rate() / 1e6,
            m.fraction(),
            gbs,
            error
        );
    }
}
