"""The GIL is released while the law runs, and the thread setting changes no result."""

import threading
import time

import numpy as np

import depo


def batch(n, seed):
    rng = np.random.default_rng(seed)
    return [rng.normal(0.0, 0.5, n), rng.normal(0.0, 0.5, n), -np.abs(rng.normal(0.0, 1.0, n))]


def test_two_threads_apply_batches_at_the_same_time():
    """While one thread is inside a long apply, another completes applies of its own. Were the
    GIL held, the second could not run a line of Python in the middle of the first's call."""
    law = depo.WallLaw(12.5, 12.5, 0.065, 0.065, p=1.3, q=0.7, vc=0.074, mu=0.3)
    depo.set_num_threads(1)  # the long call on its own thread only
    try:
        n = 1 << 20
        while True:
            big = batch(n, 1)
            t0 = time.perf_counter()
            law.apply(*big)
            if time.perf_counter() - t0 > 0.25 or n >= 1 << 25:
                break
            n *= 2
        done, stop = [], threading.Event()

        def other():
            small = batch(1000, 2)
            while not stop.is_set():
                law.apply(*small)
                done.append(time.perf_counter())

        worker = threading.Thread(target=other)
        worker.start()
        while not done:
            time.sleep(0.001)
        big = batch(n, 3)
        t0 = time.perf_counter()
        law.apply(*big)
        t1 = time.perf_counter()
        stop.set()
        worker.join()
    finally:
        depo.set_num_threads(0)
    margin = 0.2 * (t1 - t0)
    inside = [t for t in done if t0 + margin < t < t1 - margin]
    assert len(inside) >= 3, f"{len(inside)} small applies finished within the middle of a {t1 - t0:.3f} s call"


def test_every_thread_setting_gives_the_same_bits():
    law = depo.WallLaw.preset("li1997-sio2")
    n = depo.PARALLEL_MIN * 3 + 17
    results = []
    try:
        for threads in [0, 1, 2, 3]:
            depo.set_num_threads(threads)
            v = batch(n, 5)
            tally = depo.Tally()
            outcome = law.apply(*v, tally=tally)
            results.append((b"".join(c.tobytes() for c in v), outcome.tobytes(), tally.to_dict()))
    finally:
        depo.set_num_threads(0)
    assert all(r == results[0] for r in results)
