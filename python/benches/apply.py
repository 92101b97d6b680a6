"""What the Python call costs: law.apply against the Rust batch on the same data, same run.

    pip install ./python          # an optimised wheel (release profile)
    python python/benches/apply.py

For each case the same arrays go through `law.apply` (numpy arrays in, outcome array out) and
through `WallLaw::apply` called directly in Rust (`depo._depo._bench_apply`, timed in Rust),
alternating, on fresh copies each repeat (copies not timed); the Rust side writes its
outcomes into one array allocated before timing, as `law.apply(..., out=)` does, while a plain
`law.apply` allocates a new one per call. Prints a Markdown table of the
medians: the Python call's extra time as a share of the Rust batch's for 1e6 impacts, and per
call in microseconds for 10 impacts.
"""

import argparse
import os
import platform
import statistics
import time

import numpy as np

import depo
from depo import _depo


def impacts(n, seed=1):
    rng = np.random.default_rng(seed)
    v = rng.normal(0.0, 0.5, size=(3, n))
    v[2] = -np.abs(v[2]) - 0.05
    return [np.ascontiguousarray(c) for c in v]


def python_seconds(law, v, calls, out):
    x = [c.copy() for c in v]
    out = np.zeros(len(v[0]), dtype=np.uint8) if out else None
    start = time.perf_counter()
    for _ in range(calls):
        law.apply(*x, out=out)
    return time.perf_counter() - start


def case(law, n, calls, repeats, out=False):
    v = impacts(n)
    python_seconds(law, v, calls, out)  # warm up: pages, thread pool
    _depo._bench_apply(law, *v, 1, calls)
    py, rs = [], []
    for _ in range(repeats):
        py.append(python_seconds(law, v, calls, out))
        rs.append(_depo._bench_apply(law, *v, 1, calls)[0])
    return statistics.median(py), statistics.median(rs)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=21)
    args = parser.parse_args()
    laws = {
        "li1997-sio2 (q = 1/2)": depo.WallLaw.preset("li1997-sio2"),
        "p = 1.3, q = 0.7, mu = 0.3": depo.WallLaw(12.5, 12.5, 0.065, 0.065, p=1.3, q=0.7, vc=0.074, mu=0.3),
    }
    print(f"depo {depo.__version__} from {depo._depo.__file__}")
    print(f"Python {platform.python_version()}, numpy {np.__version__}, "
          f"{os.cpu_count()} cores, median of {args.repeats} alternating repeats")
    print()
    print("| law | threads | impacts x calls | Rust batch | law.apply | Python adds |")
    print("|---|---|---|---|---|---|")
    for name, law in laws.items():
        for threads in [0, 1]:
            depo.set_num_threads(threads)
            shown = "all cores" if threads == 0 else "1"
            for out in [False, True]:
                py, rs = case(law, 1_000_000, 1, args.repeats, out)
                call = "1e6 x 1, out=" if out else "1e6 x 1"
                print(f"| {name} | {shown} | {call} | {rs * 1e3:.2f} ms | {py * 1e3:.2f} ms | "
                      f"{100 * (py - rs) / rs:+.1f} % |")
        depo.set_num_threads(0)
        calls = 20_000
        py, rs = case(law, 10, calls, args.repeats)
        print(f"| {name} | caller | 10 x {calls} | {rs / calls * 1e6:.3f} us/call | {py / calls * 1e6:.3f} us/call | "
              f"{(py - rs) / calls * 1e6:+.2f} us/call |")


if __name__ == "__main__":
    main()
