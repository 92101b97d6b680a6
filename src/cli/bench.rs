//! `depo bench`: the wall-law kernels' throughput against a copy kernel moving the same bytes
//! (timed interleaved), and each kernel's error against the f64 libm-pow kernel; with
//! `--integrators`, the tracker's integrators' run time against error over the step size; with
//! `--studies`, the studies' variance reduction against plain tracking, run time against
//! statistical error.

use std::path::PathBuf;

use clap::Args;
use depo::bench::{error_against_reference, measure, standard_scenarios};
use depo::tracker::convergence::{integrator_convergence, relaxation_time};
use depo::tracker::efficiency::{compare_methods, MethodRun, TimeTo, CASES, MIN_EVENTS};
use depo::tracker::studies::TARGET_ERROR;
use depo::tracker::Scheme;
use depo::wall_model::kernel::MAX_THREADS;
use serde::Serialize;

use super::{check_memory, print_csv_rows, progress_bar, Error, Format};
use depo::plot::{self, Series};
use depo::report::Measured;

#[derive(Args, Debug)]
pub struct BenchArgs {
    /// Impacts per kernel call.
    #[arg(long, default_value_t = 10_000_000, allow_negative_numbers = true)]
    n: usize,
    /// Threads, at most 1024 (as the C ABI's `depo_set_num_threads`).
    #[arg(long, default_value_t = 2, allow_negative_numbers = true)]
    threads: usize,
    /// Interleaved rounds per kernel (medians are reported).
    #[arg(long, default_value_t = 5, allow_negative_numbers = true)]
    reps: usize,
    /// Only the kernels whose label contains this text.
    #[arg(long, default_value = "")]
    filter: String,
    /// Output format.
    #[arg(long, value_enum, default_value_t)]
    format: Format,
    /// Also draw throughput (fraction of the ceiling) against error into this SVG file.
    #[arg(long)]
    plot: Option<PathBuf>,
    /// The tracker's integrators instead: run time against error over the step size.
    #[arg(long)]
    integrators: bool,
    /// The studies' variance reduction against plain tracking instead: each run's time to a
    /// 5 % relative standard error, timed side by side.
    #[arg(long, conflicts_with = "integrators")]
    studies: bool,
    /// With --studies: particles per run as a multiple of the studies' first ones (1000 per
    /// room size; 4000 plain and 1000 with excursions per tau+).
    #[arg(long, default_value_t = 1.0, requires = "studies", allow_negative_numbers = true)]
    scale: f64,
}

/// One kernel's figures; the JSON keys are stable.
#[derive(Serialize)]
struct Row {
    kernel: String,
    impacts_per_second: f64,
    ceiling_impacts_per_second: f64,
    fraction_of_ceiling: f64,
    gigabytes_per_second: f64,
    /// The largest error against the reference; 0 for a reference kernel itself.
    max_error: f64,
    /// Whether this kernel is its own reference (the f64 kernel with libm's pow, or one with
    /// exponents 1 and 1/2, which take no pow): its error is zero by construction.
    reference: bool,
}

pub fn run(args: &BenchArgs) -> Result<(), Error> {
    if !(1..=MAX_THREADS).contains(&args.threads) {
        return Err(format!("--threads {} must be from 1 to {MAX_THREADS}", args.threads));
    }
    if args.studies {
        return studies(args);
    }
    if let Some(path) = &args.plot {
        plot::check_writable(path)?;
    }
    if args.integrators {
        return integrators(args);
    }
    if args.n < 1000 || args.reps == 0 {
        return Err("--n must be at least 1000, --reps at least 1".into());
    }
    // Two copies (pristine and working) of velocity, spin, radius, normals and outcome in f64.
    check_memory(&format!("--n {}", args.n), args.n as u64, 2 * 81)?;
    let pool = rayon::ThreadPoolBuilder::new().num_threads(args.threads).build().map_err(|e| e.to_string())?;
    let scenarios: Vec<_> =
        standard_scenarios(args.n).into_iter().filter(|s| s.label().contains(&args.filter)).collect();
    if scenarios.is_empty() {
        return Err(format!("--filter '{}' matches no kernel", args.filter));
    }
    let progress = progress_bar(scenarios.len(), "kernels")?;
    let mut rows = Vec::new();
    for scenario in scenarios {
        progress.set_message(scenario.label());
        let m = measure(scenario, &pool, args.reps);
        rows.push(Row {
            kernel: scenario.label(),
            impacts_per_second: m.rate(),
            ceiling_impacts_per_second: m.ceiling_rate(),
            fraction_of_ceiling: m.fraction(),
            gigabytes_per_second: m.rate() * m.bytes_per_impact() as f64 / 1e9,
            max_error: error_against_reference(scenario, args.n.min(200_000)),
            reference: scenario.is_reference(),
        });
        progress.inc(1);
    }
    progress.finish_and_clear();
    match args.format {
        Format::Json => out!("{}", serde_json::to_string_pretty(&rows).map_err(|e| e.to_string())?),
        Format::Csv => print_csv_rows(&rows)?,
        Format::Table => {
            out!("N = {}, {} threads, median of {} interleaved rounds", args.n, args.threads, args.reps);
            out!(
                "{:<30} {:>11} {:>11} {:>9} {:>7} {:>10}",
                "kernel",
                "Mimpacts/s",
                "ceiling",
                "fraction",
                "GB/s",
                "max error"
            );
            for r in &rows {
                out!(
                    "{:<30} {:>11.0} {:>11.0} {:>9.2} {:>7.1} {:>10}",
                    r.kernel,
                    r.impacts_per_second / 1e6,
                    r.ceiling_impacts_per_second / 1e6,
                    r.fraction_of_ceiling,
                    r.gigabytes_per_second,
                    if r.reference { "reference".to_string() } else { format!("{:.1e}", r.max_error) }
                );
            }
            if rows.iter().any(|r| r.reference) {
                out!(
                    "max error: the largest |V - V_ref| / |v| against the f64 libm-pow kernel of the same setup; \
                     reference: that kernel, or one computing the same (exponents 1 and 1/2 take no pow), error 0 by \
                     construction."
                );
            }
        }
    }
    if let Some(path) = &args.plot {
        // Speed against error: each kernel a point, named beside it; one series per precision
        // and power function. The reference kernels have no error to put on the log axis: they
        // are drawn at its floor, in a series of their own whose legend entry says so.
        let reference = format!("f64 reference kernels: error 0 by construction, drawn at {EXACT_AT:.0e}");
        let names = [reference.as_str(), "f64, fast pow", "f32, exponents 1 and 1/2", "f32, general exponents"];
        // Which of `names` a kernel's series is.
        let group = |r: &Row| match (r.kernel.starts_with("f32"), r.reference, r.kernel.contains("pow")) {
            (false, true, _) => 0,
            (false, false, _) => 1,
            (true, _, false) => 2,
            (true, _, true) => 3,
        };
        let series: Vec<Series> = names
            .iter()
            .enumerate()
            .map(|(k, &name)| {
                let own: Vec<&Row> = rows.iter().filter(|r| group(r) == k).collect();
                let precision = if k < 2 { "f64" } else { "f32" };
                Series::markers(name, own.iter().map(|r| (r.max_error.max(EXACT_AT), r.fraction_of_ceiling)).collect())
                    .with_labels(own.iter().map(|r| short_label(&r.kernel, precision)).collect())
                    .color(k)
            })
            .filter(|s| !s.points.is_empty())
            .collect();
        plot_points(path, &series)?;
    }
    Ok(())
}

/// Where the kernels figure draws the reference kernels' error of 0 (below any rounding error
/// of an f64 result); their legend entry names it.
const EXACT_AT: f64 = 1e-17;

/// A kernel's label beside its point: without the precision its series names.
fn short_label(kernel: &str, precision: &str) -> String {
    kernel.strip_prefix(precision).unwrap_or(kernel).trim_start_matches([' ', ',', '-', '_']).to_string()
}

fn plot_points(path: &std::path::Path, series: &[Series]) -> Result<(), Error> {
    plot::lines(
        path,
        "Kernel speed against error",
        "max error vs f64 libm-pow kernel",
        "fraction of copy ceiling",
        series,
        true,
    )?;
    eprintln!("wrote {}", path.display());
    Ok(())
}

/// One integrator at one step size; the JSON keys are stable.
#[derive(Serialize)]
struct IntegratorRow {
    scheme: &'static str,
    dt_over_tau: f64,
    seconds: f64,
    particle_steps: u64,
    relative_error: Option<f64>,
    observed_order: Option<f64>,
}

fn integrators(args: &BenchArgs) -> Result<(), Error> {
    let pool = rayon::ThreadPoolBuilder::new().num_threads(args.threads).build().map_err(|e| e.to_string())?;
    let ratios = [0.01, 0.03, 0.1, 0.3, 1.0, 3.0, 10.0];
    let progress = progress_bar(2 * ratios.len(), "runs")?;
    let runs = pool.install(|| integrator_convergence(&ratios, 2000, |done| progress.set_position(done as u64)));
    progress.finish_and_clear();
    let rows: Vec<IntegratorRow> = runs
        .into_iter()
        .map(|r| IntegratorRow {
            scheme: match r.scheme {
                Scheme::Exponential => "exponential",
                Scheme::Euler => "euler",
                Scheme::Midpoint => "midpoint",
            },
            dt_over_tau: r.dt_over_tau,
            seconds: r.seconds,
            particle_steps: r.particle_steps,
            relative_error: r.error.is_finite().then_some(r.error),
            observed_order: r.order,
        })
        .collect();
    let show = |x: Option<f64>, precision: usize| x.map_or("unstable".to_string(), |v| format!("{v:.precision$e}"));
    match args.format {
        Format::Json => out!("{}", serde_json::to_string_pretty(&rows).map_err(|e| e.to_string())?),
        Format::Csv => print_csv_rows(&rows)?,
        Format::Table => {
            out!(
                "Particles settling across a Poiseuille channel from rest (tau = {:.2} ms), {} threads;",
                relaxation_time() * 1e3,
                args.threads
            );
            out!("error: RMS position error after 0.1 s against dt = tau/1000, relative to the distance travelled.");
            out!(
                "{:<12} {:>8} {:>10} {:>13} {:>10} {:>6}",
                "scheme",
                "dt/tau",
                "run (ms)",
                "particle-steps",
                "error",
                "order"
            );
            for r in &rows {
                out!(
                    "{:<12} {:>8.2} {:>10.2} {:>13} {:>10} {:>6}",
                    r.scheme,
                    r.dt_over_tau,
                    r.seconds * 1e3,
                    r.particle_steps,
                    show(r.relative_error, 2),
                    r.observed_order.map_or("-".to_string(), |o| format!("{o:.2}"))
                );
            }
        }
    }
    if let Some(path) = &args.plot {
        let series: Vec<Series> = ["exponential", "euler"]
            .iter()
            .map(|scheme| {
                let runs: Vec<&IntegratorRow> = rows.iter().filter(|r| r.scheme == *scheme).collect();
                let points: Vec<(f64, f64)> =
                    runs.iter().filter_map(|r| r.relative_error.map(|e| (r.seconds * 1e3, e))).collect();
                // An unstable step has no error to draw: say so rather than leave it out unseen.
                let unstable = runs.len() - points.len();
                let name = match unstable {
                    0 => (*scheme).to_string(),
                    1 => format!("{scheme} (1 unstable step size not shown)"),
                    n => format!("{scheme} ({n} unstable step sizes not shown)"),
                };
                // Each point's dt / tau beside it, in both series: the two schemes' points at one
                // step need not sit side by side.
                let labels = runs
                    .iter()
                    .filter(|r| r.relative_error.is_some())
                    .map(|r| format!("dt/tau {:.2}", r.dt_over_tau))
                    .collect();
                Series::markers(name, points).with_labels(labels)
            })
            .collect();
        plot::log_log(
            path,
            "Integrators: run time against error",
            "run time (ms)",
            "relative position error",
            &series,
        )?;
        eprintln!("wrote {}", path.display());
    }
    Ok(())
}

/// One method's run of one study case; the JSON keys are stable.
#[derive(Serialize)]
struct StudyRow {
    case: String,
    figure: &'static str,
    method: &'static str,
    value: f64,
    error: f64,
    events: usize,
    /// With no event, a 95 % upper bound on the value.
    upper_bound: Option<f64>,
    particles: usize,
    seconds: f64,
    relative_error: Option<f64>,
    /// The part of `seconds` fixed per run (the excursions' pilot calibration).
    fixed_seconds: f64,
    /// Seconds to the studies' relative standard error (5 %).
    seconds_to_target: Option<f64>,
    /// Whether that time was projected from the other method's value (too few events).
    projected: bool,
    /// On the reduced method's row: plain tracking's time to 5 % over this one's.
    speedup: Option<f64>,
}

fn studies(args: &BenchArgs) -> Result<(), Error> {
    if args.plot.is_some() {
        return Err("--plot draws the kernels and the integrators, not --studies".into());
    }
    if !(args.scale > 0.0 && args.scale <= 100.0) {
        return Err(format!("--scale {} is not in (0, 100]", args.scale));
    }
    let pool = rayon::ThreadPoolBuilder::new().num_threads(args.threads).build().map_err(|e| e.to_string())?;
    let progress = progress_bar(CASES, "cases")?;
    let cases = pool
        .install(|| compare_methods(args.scale, |done| progress.set_position(done as u64)))
        .map_err(|e| e.to_string())?;
    progress.finish_and_clear();
    let mut rows = Vec::new();
    for case in &cases {
        let [plain, reduced] = case.time_to(TARGET_ERROR);
        let row = |method: &'static str, run: &MethodRun, time: Option<TimeTo>, speedup: Option<f64>| StudyRow {
            case: case.name.clone(),
            figure: case.figure,
            method,
            value: run.estimate.value,
            error: run.estimate.error,
            events: run.estimate.events,
            upper_bound: (run.estimate.events == 0).then_some(run.estimate.upper_bound),
            particles: run.particles,
            seconds: run.seconds,
            fixed_seconds: run.fixed_seconds,
            relative_error: run.relative_error(),
            seconds_to_target: time.map(|t| t.seconds),
            projected: time.is_some_and(|t| t.projected),
            speedup,
        };
        rows.push(row("plain", &case.plain, plain, None));
        rows.push(row(case.method, &case.reduced, reduced, case.speedup(TARGET_ERROR)));
    }
    match args.format {
        Format::Json => out!("{}", serde_json::to_string_pretty(&rows).map_err(|e| e.to_string())?),
        Format::Csv => print_csv_rows(&rows)?,
        Format::Table => {
            out!(
                "The studies' variance reduction against plain tracking, each case run both ways in this run, {} threads;",
                args.threads
            );
            let target = format!("{} %", 100.0 * TARGET_ERROR);
            out!(
                "time to {target}: the run's pilot calibration plus the rest times (relative error / {target})^2, the error falling as 1/sqrt(particles)."
            );
            out!(
                "{:<20} {:<11} {:<25} {:>26} {:>9} {:>8} {:>7} {:>14} {:>8}",
                "case",
                "figure",
                "method",
                "value +- error [events]",
                "particles",
                "run (s)",
                "error",
                format!("to {target} (s)"),
                "speed-up"
            );
            for r in &rows {
                out!(
                    "{:<20} {:<11} {:<25} {:>26} {:>9} {:>8.1} {:>7} {:>14} {:>8}",
                    r.case,
                    r.figure,
                    r.method,
                    Measured { value: r.value, error: r.error, events: r.events, upper_bound: r.upper_bound }.cell(),
                    r.particles,
                    r.seconds,
                    r.relative_error.map_or("-".to_string(), |e| format!("{:.1} %", 100.0 * e)),
                    r.seconds_to_target
                        .map_or("-".to_string(), |t| format!("{t:.3e}{}", if r.projected { "*" } else { "" })),
                    r.speedup.map_or(String::new(), |s| format!("{s:.0}x"))
                );
            }
            out!(
                "* projected: with fewer than {MIN_EVENTS} deposits a run's own error says little; plain tracking's deposits as a Poisson count at the other method's value give it (- for a reduced run)."
            );
        }
    }
    Ok(())
}
