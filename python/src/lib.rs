//! # depo._depo: depo for Python
//!
//! The native module under the `depo` package (`python/depo/__init__.py` re-exports it). It
//! binds the Rust crates directly, never through the C ABI: `law` the wall law on numpy
//! arrays (`WallLaw`, `Tally`), `arrays` how numpy arrays are borrowed (contiguous ones without
//! a copy, strided views gathered and scattered back), `jobs` the `depo` command's other jobs
//! (`fit`, `capture_velocity`, `presets`), `studies` the room and channel studies (watched
//! for Ctrl-C), `threads` where large batches and studies run, `bench` the Rust side of the
//! Python benchmark.
//!
//! Conventions: SI units throughout; a bad value is a `ValueError` whose message is the one-line
//! message of the C ABI or the command, naming the parameter; a wrong array type or dtype is a
//! `TypeError`; the GIL is released while the law runs. The outcome codes and capture modes
//! are the C header's (`depo.h`).

use pyo3::prelude::*;

mod arrays;
mod bench;
mod jobs;
mod law;
mod studies;
mod threads;

/// The module `depo._depo`.
#[pymodule]
fn _depo(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("REBOUND", depo_wall_model::Outcome::REBOUND.0)?;
    m.add("CAPTURED", depo_wall_model::Outcome::CAPTURED.0)?;
    m.add("SKIPPED", depo_wall_model::Outcome::SKIPPED.0)?;
    m.add("INVALID", depo_wall_model::Outcome::INVALID.0)?;
    m.add("CAPTURE_DEPOSIT", law::CAPTURE_DEPOSIT)?;
    m.add("CAPTURE_KEEP_ON_WALL", law::CAPTURE_KEEP_ON_WALL)?;
    m.add("PARALLEL_MIN", depo_wall_model::kernel::PARALLEL_MIN)?;
    m.add("MAX_THREADS", depo_wall_model::kernel::MAX_THREADS)?;
    m.add_class::<law::PyWallLaw>()?;
    m.add_class::<law::PyTally>()?;
    m.add_function(wrap_pyfunction!(jobs::presets, m)?)?;
    m.add_function(wrap_pyfunction!(jobs::fit, m)?)?;
    m.add_function(wrap_pyfunction!(jobs::capture_velocity, m)?)?;
    m.add_function(wrap_pyfunction!(threads::set_num_threads, m)?)?;
    m.add_function(wrap_pyfunction!(studies::_room, m)?)?;
    m.add_function(wrap_pyfunction!(studies::_channel, m)?)?;
    m.add_function(wrap_pyfunction!(bench::_bench_apply, m)?)?;
    Ok(())
}
