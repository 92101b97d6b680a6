//! The Rust side of the Python benchmark (python/benches/apply.py): the same batch through the crate
//! directly, timed in Rust, so that the benchmark compares `law.apply` with it on the same
//! data in the same run.

use std::time::Instant;

use depo_wall_model::{Impacts, Normals, Outcome};
use numpy::PyReadonlyArray1;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

use crate::law::PyWallLaw;
use crate::threads::run_batch;

/// Times `calls` consecutive `WallLaw::apply` calls on a copy of (vx, vy, vz) with normal
/// (0, 0, 1), `repeats` times, with the GIL released and the threads of `set_num_threads`;
/// returns the seconds of each repeat. Copying the arrays is not timed. For benchmarks only.
#[pyfunction]
#[pyo3(signature = (law, vx, vy, vz, repeats, calls = 1))]
pub fn _bench_apply(
    py: Python<'_>,
    law: &PyWallLaw,
    vx: PyReadonlyArray1<'_, f64>,
    vy: PyReadonlyArray1<'_, f64>,
    vz: PyReadonlyArray1<'_, f64>,
    repeats: usize,
    calls: usize,
) -> PyResult<Vec<f64>> {
    let v = [vx.as_slice()?.to_vec(), vy.as_slice()?.to_vec(), vz.as_slice()?.to_vec()];
    let n = v[0].len();
    if v[1].len() != n || v[2].len() != n {
        return Err(PyValueError::new_err("vx, vy, vz must have one length"));
    }
    let law = law.law;
    Ok(py.detach(move || {
        let mut outcome = vec![Outcome::default(); n];
        let mut times = Vec::with_capacity(repeats);
        for _ in 0..repeats {
            let [mut x, mut y, mut z] = v.clone();
            let start = Instant::now();
            for _ in 0..calls {
                let batch = Impacts::new([&mut x, &mut y, &mut z], Normals::Uniform([0.0, 0.0, 1.0]), &mut outcome)
                    .expect("checked lengths and a unit normal");
                run_batch(n, |parallel| {
                    if parallel {
                        law.apply(batch, None);
                    } else {
                        law.apply_on_calling_thread(batch, None);
                    }
                });
            }
            times.push(start.elapsed().as_secs_f64());
            std::hint::black_box((&x, &y, &z, &outcome));
        }
        times
    }))
}
