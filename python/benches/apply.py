"""What the Python call costs: law.apply against the Rust batch on the same data, same run.

    pip install ./python          # an optimised wheel (release profile)
    python python/benches/apply.py [--repeats 21]

For each case the same arrays go through `law.apply` (numpy arrays in, outcome array out) and
through `WallLaw::apply` called directly in Rust (`depo._depo._bench_apply`, timed in Rust),
in pairs, one of each, on fresh copies each repeat (copies not timed), which side goes first
alternating from pair to pair so that a change in the machine's speed falls on both; the Rust
side writes its outcomes into one array allocated before timing, as `law.apply(..., out=)`
does, while a plain `law.apply` allocates a new one per call. Prints a Markdown table: the
medians of each side, and over the pairs the median and quartiles of the ratio
`law.apply / Rust` for 1e6 impacts, and of the extra time per call in microseconds for 10
impacts. On a shared machine the quartiles say how far one pair can be trusted.
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
    """Seconds of `calls` calls on `n` impacts, per pair: (Python's, Rust's)."""
    v = impacts(n)
    python_seconds(law, v, calls, out)  # warm up: pages, thread pool
    _depo._bench_apply(law, *v, 1, calls)
    py, rs = [], []
    for i in range(repeats):
        if i % 2 == 0:
            py.append(python_seconds(law, v, calls, out))
            rs.append(_depo._bench_apply(law, *v, 1, calls)[0])
        else:
            rs.append(_depo._bench_apply(law, *v, 1, calls)[0])
            py.append(python_seconds(law, v, calls, out))
    return py, rs


def spread(values, fmt):
    """The median and, in brackets, the quartiles of `values`, each formatted by `fmt`."""
    q1, median, q3 = statistics.quantiles(values, n=4, method="inclusive")
    return f"{fmt(median)} [{fmt(q1)}, {fmt(q3)}]"


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
    print("| law | threads | impacts x calls | Rust batch | law.apply | law.apply / Rust, median [quartiles] |")
    print("|---|---|---|---|---|---|")
    for name, law in laws.items():
        for threads in [0, 1]:
            depo.set_num_threads(threads)
            shown = "all cores" if threads == 0 else "1"
            for out in [False, True]:
                py, rs = case(law, 1_000_000, 1, args.repeats, out)
                call = "1e6 x 1, out=" if out else "1e6 x 1"
                ratios = [p / r for p, r in zip(py, rs)]
                print(f"| {name} | {shown} | {call} | {statistics.median(rs) * 1e3:.2f} ms | "
                      f"{statistics.median(py) * 1e3:.2f} ms | {spread(ratios, lambda x: f'{x:.3f}')} |")
        depo.set_num_threads(0)
        calls = 20_000
        py, rs = case(law, 10, calls, args.repeats)
        extra = [(p - r) / calls * 1e6 for p, r in zip(py, rs)]
        print(f"| {name} | caller | 10 x {calls} | {statistics.median(rs) / calls * 1e6:.3f} us/call | "
              f"{statistics.median(py) / calls * 1e6:.3f} us/call | "
              f"{spread(extra, lambda x: f'{x:+.2f}')} us a call more |")

if __name__ == "__main__":
    main()
