"""A sweep of room studies on Dask: air-change rate x furnishing x size distribution.

Each task is one room study (depo.room) of one combination, with its own fixed seed, so the
results do not depend on which worker runs a task nor in what order the tasks finish: the
sweep gives the same results, bit for bit, as the serial loop (--check runs both and compares).

    python examples/python/sweep_dask.py                        # a LocalCluster on this machine
    python examples/python/sweep_dask.py --workers 2 --check    # ... and the serial loop, compared
    python examples/python/sweep_dask.py --scheduler tcp://HOST:8786   # a running cluster
    python examples/python/sweep_dask.py --slurm 4              # 4 SLURM jobs (dask-jobqueue)
    python examples/python/sweep_dask.py --size full            # the whole sweep (see below)

By default the sweep is small (2 x 2 x 2 tasks, each 4 bins per density of 100 particles over
600 s); --size full runs 4 air-change rates x 2 furnishings x 3 distributions, 8 bins of 400
particles over 1800 s; --size tiny is the tests' (2 bins of 16 particles over 120 s).
Every worker needs the depo package (pip install ./python) and runs one task per thread;
depo.set_num_threads(1) inside each task keeps a task on its worker's thread, so that the
cluster's threads, not depo's, share the cores. docs/python.md says what a task costs.

Requires dask[distributed]; dask-jobqueue for --slurm; pandas for --csv.
"""

import argparse
import itertools
import json
import sys
import time

import depo

# The sweep's axes. The room is 4 m x 3 m x 2.5 m; a furnished one holds a sofa, a table and a
# bookcase (as the Thatcher et al. 2002 chamber); the distributions are by mass, in the room's
# air at the start, released once and followed for `duration` seconds.
AIR_CHANGES_PER_HOUR = [0.2, 0.5, 1.0, 2.0]
FURNISHINGS = {
    "bare": [],
    "furnished": [
        {"name": "sofa", "low": [0.15, 0.15, 0.10], "high": [1.95, 0.95, 0.55]},
        {"name": "table", "low": [0.90, 1.40, 0.70], "high": [1.90, 2.20, 0.75]},
        {"name": "bookcase", "low": [2.00, 1.20, 0.10], "high": [2.35, 2.10, 1.85]},
    ],
}
DISTRIBUTIONS = {
    # Urban background: an accumulation mode and a coarse mode (as examples/room-pm.toml).
    "urban": [
        {"mass_median": 0.3e-6, "geometric_sd": 2.0, "mass_concentration": 15e-9, "density": 1500.0},
        {"mass_median": 6e-6, "geometric_sd": 2.2, "mass_concentration": 10e-9, "density": 2500.0},
    ],
    # Combustion (candles, cooking): fine particles only.
    "combustion": [{"count_median": 0.08e-6, "geometric_sd": 1.8, "mass_concentration": 30e-9, "density": 1200.0}],
    # Resuspended dust: coarse.
    "dust": [{"mass_median": 8e-6, "geometric_sd": 2.0, "mass_concentration": 40e-9, "density": 2500.0}],
}


def scene(air_changes, furnishing, distribution, size="small"):
    """The room scene (a dict of the scene file's keys) of one combination."""
    particles = {"modes": DISTRIBUTIONS[distribution]}
    if size == "full":
        particles.update(bins=8, count=400, target_error=0.0)
        duration = 1800.0
    elif size == "small":
        particles.update(bins=4, count=100, target_error=0.0)
        duration = 600.0
    else:  # "tiny", for the tests
        particles.update(bins=2, count=16, target_error=0.0)
        duration = 120.0
    return {
        "room": {"size": [4.0, 3.0, 2.5]},
        "particles": particles,
        "ventilation": {"air_changes_per_hour": air_changes},
        "furnishings": FURNISHINGS[furnishing],
        "run": {"duration": duration, "dt": 0.1},
    }


def tasks(size="small"):
    """The sweep: (key, scene, seed) per combination, the seed fixed by the combination's
    place in the sweep, so that any order of running gives the same results. `size` is
    "full" (every axis, the study's particle counts), "small" or "tiny" (2 x 2 x 2)."""
    if size == "full":
        axes = (AIR_CHANGES_PER_HOUR, list(FURNISHINGS), list(DISTRIBUTIONS))
    else:
        axes = ([0.5, 2.0], list(FURNISHINGS), ["urban", "dust"])
    combos = itertools.product(*axes)
    return [((a, f, d), scene(a, f, d, size), 1000 + i) for i, (a, f, d) in enumerate(combos)]


def run_task(key, scene, seed):
    """One task: the room study of `scene`; returns (key, the study's dict, seconds)."""
    import depo  # on the worker

    depo.set_num_threads(1)  # one task per worker thread: the cluster shares the cores
    result = depo.room(scene, seed=seed)
    return key, result.to_dict(), result.seconds


def serial(sweep):
    """The serial loop: each task in turn, here."""
    return {key: run_task(key, s, seed)[1:] for key, s, seed in sweep}


def on_dask(client, sweep):
    """Each task as a future on the cluster, gathered as they finish (in any order)."""
    from distributed import as_completed

    futures = [client.submit(run_task, key, s, seed, pure=False) for key, s, seed in sweep]
    results = {}
    for future in as_completed(futures):
        key, report, seconds = future.result()
        results[key] = (report, seconds)
    return results


def summary(results):
    """One row per task: where the distribution's mass went by the end, and its loss rate."""
    rows = []
    for (a, f, d), (report, seconds) in sorted(results.items()):
        split = report["distribution"]["all"]
        beta = split["beta_per_hour"]
        rows.append(
            {
                "air_changes_per_hour": a,
                "furnishing": f,
                "distribution": d,
                "deposited": split["floor"]["value"] + split["ceiling"]["value"] + split["walls"]["value"]
                + split["furnishings"]["value"],
                "exhausted": split["exhausted"]["value"],
                "airborne": split["airborne"]["value"],
                "beta_per_hour": None if beta is None else beta["value"],
                "seconds": seconds,
            }
        )
    return rows


def client_for(args):
    """A Dask client: a running scheduler, SLURM jobs, or a LocalCluster."""
    from distributed import Client, LocalCluster

    if args.scheduler:
        return Client(args.scheduler), None
    if args.slurm:
        from dask_jobqueue import SLURMCluster

        cluster = SLURMCluster(cores=args.threads, processes=1, memory="4GB", walltime="01:00:00")
        cluster.scale(jobs=args.slurm)
        return Client(cluster), cluster
    cluster = LocalCluster(n_workers=args.workers, threads_per_worker=args.threads, processes=True)
    return Client(cluster), cluster


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--scheduler", help="address of a running Dask scheduler (tcp://HOST:8786)")
    p.add_argument("--slurm", type=int, metavar="JOBS", help="start this many SLURM jobs (dask-jobqueue)")
    p.add_argument("--workers", type=int, default=2, help="LocalCluster workers (default 2)")
    p.add_argument("--threads", type=int, default=1, help="threads per worker (default 1)")
    p.add_argument("--size", choices=["tiny", "small", "full"], default="small",
                   help="tiny (tests), small (default: 2 x 2 x 2 tasks, 4 bins of 100 particles, 600 s) "
                   "or full (4 x 2 x 3 tasks, 8 bins of 400 particles, 1800 s)")
    p.add_argument("--check", action="store_true", help="also run the serial loop and compare, bit for bit")
    p.add_argument("--json", help="write every task's study (the command's JSON) to this file")
    p.add_argument("--csv", help="write the summary to this CSV file (pandas)")
    args = p.parse_args(argv)

    sweep = tasks(args.size)
    client, cluster = client_for(args)
    try:
        start = time.perf_counter()
        results = on_dask(client, sweep)
        wall = time.perf_counter() - start
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
    rows = summary(results)
    task_seconds = [r["seconds"] for r in rows]
    print(f"{len(rows)} tasks in {wall:.1f} s on the cluster; each task {min(task_seconds):.2f}-"
          f"{max(task_seconds):.2f} s of study (sum {sum(task_seconds):.1f} s)")
    print("deposited, exhausted, airborne: kg of the distribution's mass in the room at the end")
    print(f"{'ach':>5} {'furnishing':>10} {'distribution':>12} {'deposited':>9} {'exhausted':>9} {'airborne':>8} {'beta/h':>8}")
    for r in rows:
        beta = "-" if r["beta_per_hour"] is None else f"{r['beta_per_hour']:.3f}"
        print(f"{r['air_changes_per_hour']:5.2f} {r['furnishing']:>10} {r['distribution']:>12} "
              f"{r['deposited']:9.3g} {r['exhausted']:9.3g} {r['airborne']:8.3g} {beta:>8}")
    if args.json:
        with open(args.json, "w") as f:
            json.dump([{"key": list(k), "study": v[0]} for k, v in sorted(results.items())], f)
    if args.csv:
        import pandas as pd

        pd.DataFrame(rows).to_csv(args.csv, index=False)
    if args.check:
        alone = serial(sweep)
        same = all(alone[k][0] == results[k][0] for k in alone)
        print("serial loop: " + ("the same results, bit for bit" if same else "DIFFERENT results"))
        return 0 if same else 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
