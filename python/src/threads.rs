//! Where large batches run: `depo.set_num_threads`, with the C ABI's meaning
//! (`depo_set_num_threads` in crates/capi).

use std::sync::{Arc, RwLock};

use depo_wall_model::kernel::{MAX_THREADS, PARALLEL_MIN};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

/// Where depo runs large batches.
enum Threads {
    /// rayon's global pool.
    Global,
    /// The calling thread: no thread is started or woken.
    Caller,
    /// A pool of depo's own, of the capped size.
    Pool(Arc<rayon::ThreadPool>),
}

static THREADS: RwLock<Threads> = RwLock::new(Threads::Global);

/// Sets how many threads depo runs a large batch on (PARALLEL_MIN = 65536 particles or more);
/// smaller batches always run on the calling thread, in one piece.
///
/// - 0 (the default): one thread per core (or RAYON_NUM_THREADS), started at the first large
///   batch and kept until the process exits.
/// - 1: the calling thread only: depo never starts or wakes a thread (for a program that runs
///   its own threads or processes, one per core, e.g. Dask workers or multiprocessing).
/// - 2 to MAX_THREADS (1024): a pool of that many threads of depo's own, started by this call
///   and ended when a later call replaces it.
///
/// A study (depo.room, depo.channel) runs its particles likewise: on one thread per core (0),
/// on a single thread (1), or on the pool of n (it always runs beside the calling thread, which
/// watches for Ctrl-C).
///
/// The setting is process-wide. Results are identical, bit for bit, for every setting. A value
/// above MAX_THREADS or below 0 is a ValueError and changes nothing.
#[pyfunction]
#[pyo3(signature = (n))]
pub fn set_num_threads(n: i64) -> PyResult<()> {
    let setting = match usize::try_from(n) {
        Ok(0) => Threads::Global,
        Ok(1) => Threads::Caller,
        Ok(threads @ 2..=MAX_THREADS) => {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .thread_name(|i| format!("depo-{i}"))
                .build()
                .map_err(|e| PyValueError::new_err(format!("cannot start {threads} threads: {e}")))?;
            Threads::Pool(Arc::new(pool))
        }
        _ => {
            return Err(PyValueError::new_err(format!(
                "threads = {n} is outside 0..={MAX_THREADS} (MAX_THREADS = {MAX_THREADS})"
            )))
        }
    };
    *THREADS.write().unwrap_or_else(|e| e.into_inner()) = setting;
    Ok(())
}

/// Runs work on `n` particles where [`set_num_threads`] says: `work(parallel)` on the calling
/// thread unless `n` reaches `PARALLEL_MIN` and a pool is allowed; with `parallel` false the work
/// must keep every piece on the calling thread.
pub fn run_batch<R: Send>(n: usize, work: impl FnOnce(bool) -> R + Send) -> R {
    if n < PARALLEL_MIN {
        return work(false);
    }
    let pool = match &*THREADS.read().unwrap_or_else(|e| e.into_inner()) {
        Threads::Global => None,
        Threads::Caller => return work(false),
        Threads::Pool(pool) => Some(Arc::clone(pool)),
    };
    match pool {
        Some(pool) => pool.install(|| work(true)),
        None => work(true),
    }
}

/// Runs a study (`work`, on the thread that calls this) where [`set_num_threads`] says: its
/// particles on rayon's global pool (0), on one thread (1: a pool of one, started for the study
/// and ended with it), or on depo's own pool (2 and more). Results are the same bits for every
/// setting.
pub fn run_study<R: Send>(work: impl FnOnce() -> R + Send) -> R {
    let pool = match &*THREADS.read().unwrap_or_else(|e| e.into_inner()) {
        Threads::Global => None,
        Threads::Caller => rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .thread_name(|_| "depo-study-1".into())
            .build()
            .ok()
            .map(Arc::new),
        Threads::Pool(pool) => Some(Arc::clone(pool)),
    };
    match pool {
        Some(pool) => pool.install(work),
        None => work(),
    }
}
