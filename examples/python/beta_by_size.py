"""Deposition loss rate against particle size in two rooms, beside Lai & Nazaroff's model.

The same 4 m x 3 m x 2.5 m room twice, both ventilated by infiltration (0.5 air changes per
hour, 80 % of outdoor particles getting in): bare, and furnished with a sofa, a table and a
bookcase. For each particle size depo tracks particles released into the room's air and
reports beta, the rate at which deposition onto every surface takes them out of the air (1/h),
with its standard error. Lai & Nazaroff's (2000) model gives beta for the bare room's floor,
ceiling and walls at the same friction velocity; the study's result carries it per size. The
figure shows beta against size (top) and its ratio to the model's (bottom), error bars one
standard error; the table printed gives the same numbers.

    python examples/python/beta_by_size.py                  # writes beta_by_size.png
    python examples/python/beta_by_size.py --out fig.png --count 200

Requires matplotlib (pip install matplotlib).
"""

import argparse

import matplotlib

matplotlib.use("Agg")  # files only, no window
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import depo  # noqa: E402

DIAMETERS_M = [0.01e-6, 0.03e-6, 0.1e-6, 0.3e-6, 1e-6, 3e-6, 10e-6]

INFILTRATION = {"air_changes_per_hour": 0.5, "penetration": 0.8}
FURNITURE = [
    {"name": "sofa", "low": [0.15, 0.15, 0.10], "high": [1.95, 0.95, 0.55]},
    {"name": "table", "low": [0.90, 1.40, 0.70], "high": [1.90, 2.20, 0.75]},
    {"name": "bookcase", "low": [2.00, 1.20, 0.10], "high": [2.35, 2.10, 1.85]},
]


def room(furnished, count, duration_s):
    """The room as a scene: the keys of a scene file (examples/room.toml), SI units."""
    return {
        "room": {"size": [4.0, 3.0, 2.5]},
        "flow": {"friction_velocity": 0.01},
        "particles": {"diameters": DIAMETERS_M, "count": count, "target_error": 0.0},
        "ventilation": INFILTRATION,
        "furnishings": FURNITURE if furnished else [],
        "run": {"duration": duration_s},
    }


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--out", default="beta_by_size.png", help="the figure (PNG)")
    p.add_argument("--count", type=int, default=400, help="particles per size (default 400)")
    p.add_argument("--duration", type=float, default=1800.0, help="seconds followed (default 1800)")
    p.add_argument("--seed", type=int, default=1)
    args = p.parse_args(argv)

    rooms = {}
    for label, furnished in [("bare, infiltration", False), ("furnished, infiltration", True)]:
        rooms[label] = depo.room(room(furnished, args.count, args.duration), seed=args.seed)
        print(f"{label}: {rooms[label].seconds:.1f} s")

    bare = rooms["bare, infiltration"]
    model = np.array([s["lai_nazaroff"]["beta_per_hour"] for s in bare.sizes])

    fig, (ax, ratio) = plt.subplots(2, 1, sharex=True, figsize=(6.4, 6.4), height_ratios=(3, 2))
    ax.plot(bare.diameters_um, model, "k.-", label="Lai & Nazaroff (2000), bare room")
    ratio.axhline(1.0, color="k", lw=1)
    for (label, r), shift, marker in zip(rooms.items(), (0.93, 1.07), ("o", "s")):
        beta, error = r.beta_per_hour, r.beta_error_per_hour
        seen = beta > 0  # a size with no deposit has beta 0, off a log axis
        # A bar that would reach below zero runs to the axis' foot (consistent with zero).
        low = np.minimum(error, beta * 0.999)
        style = dict(fmt=marker, ms=4, capsize=3, elinewidth=1.2)
        ax.errorbar(r.diameters_um[seen] * shift, beta[seen], yerr=[low[seen], error[seen]],
                    label=f"depo, {label} (+- 1 s.e.)", **style)
        ratio.errorbar(r.diameters_um * shift, beta / model, yerr=error / model, **style)
        print(f"{label}: d (um), beta (1/h), s.e., Lai & Nazaroff")
        for d, b, e, m in zip(r.diameters_um, beta, error, model):
            print(f"  {d:7.2f} {b:9.4f} {e:8.4f} {m:9.4f}")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_ylabel(r"deposition loss rate $\beta$ (1/h)")
    ax.set_title(f"A 4 m x 3 m x 2.5 m room, u* = 0.01 m/s, {args.count} particles per size")
    ax.legend(fontsize="small")
    ratio.set_xlabel(r"particle diameter ($\mu$m)")
    ratio.set_ylabel(r"$\beta$ / Lai & Nazaroff's")
    for a in (ax, ratio):
        a.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(args.out, dpi=120)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
