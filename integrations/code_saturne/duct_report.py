#!/usr/bin/env python3
"""The duct case's report: where the particles of each size went, with Code_Saturne's own
deposition (every wall contact deposits) and with depo's law (rebound or capture).

    duct_report.py SINK_RUN DEPO_RUN OUT_DIR

reads each run's duct_census.csv (and depo's depo_impacts.csv for the rebounds), prints a
table, and writes OUT_DIR/duct.csv and the figure OUT_DIR/duct.svg. The fractions are of the
particles injected per size (8000); their standard errors are binomial, sqrt(f (1 - f) / N).
"""
import csv
import math
import os
import sys

WALLS = ["floor", "ceiling", "sides"]


def census(run):
    with open(os.path.join(run, "duct_census.csv")) as f:
        return {float(r["diameter"]): r for r in csv.DictReader(f)}


def rebounds(run):
    """Rebounds per (zone name, diameter) from the contacts depo recorded."""
    names = {}
    with open(os.path.join(run, "listing")) as f:
        for line in f:
            if line.startswith('depo: zone "'):
                name = line.split('"')[1]
                names[int(line.split("(id ")[1].split(")")[0])] = name
    counts = {}
    with open(os.path.join(run, "depo_impacts.csv")) as f:
        for r in csv.DictReader(f):
            if r["outcome"] == "0":
                key = (names[int(r["zone"])], round(float(r["diameter"]) * 1e6))
                counts[key] = counts.get(key, 0) + 1
    return counts


def main(sink_run, depo_run, out):
    sink, depo, bounced = census(sink_run), census(depo_run), rebounds(depo_run)
    rows = []
    for d in sorted(sink):
        for walls, c in (("sink", sink[d]), ("depo", depo[d])):
            n = int(c["injected"])
            for place in WALLS + ["airborne", "outlet"]:
                f = int(c[place]) / n
                rebound = bounced.get((place, round(d * 1e6)), 0) if walls == "depo" else 0
                rows.append((d * 1e6, walls, place, int(c[place]), f, math.sqrt(f * (1 - f) / n), rebound))
    with open(os.path.join(out, "duct.csv"), "w") as f:
        f.write("diameter_um,walls,where,count,fraction,error,rebounds\n")
        for r in rows:
            f.write("%g,%s,%s,%d,%.5f,%.5f,%d\n" % r)
    print("%8s %5s %9s %7s %18s %9s" % ("d (um)", "walls", "where", "count", "fraction", "rebounds"))
    for d, walls, place, count, frac, err, reb in rows:
        print("%8g %5s %9s %7d %9.4f +- %.4f %9d" % (d, walls, place, count, frac, err, reb))
    svg(rows, os.path.join(out, "duct.svg"))
    print("wrote", os.path.join(out, "duct.csv"), "and", os.path.join(out, "duct.svg"))


def svg(rows, path):
    """Grouped bars: per size, the fraction deposited on each wall and leaving, both wall models."""
    places = WALLS + ["outlet"]
    sizes = sorted({r[0] for r in rows})
    value = {(r[0], r[1], r[2]): (r[4], r[5]) for r in rows}
    colours = {"sink": "#888888", "depo": "#1f77b4"}
    w, h, left, bottom, top = 760, 360, 60, 60, 30
    group = (w - left - 20) / (len(sizes) * len(places))
    bar = group / 3
    y = lambda f: h - bottom - f * (h - bottom - top)
    out = ['<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d" font-family="sans-serif" font-size="11">' % (w, h)]
    out.append('<text x="%d" y="18" font-size="13">Duct, 1 m/s: fate of the particles (Code_Saturne sink walls vs depo li1997-sio2)</text>' % left)
    for k in range(6):
        f = k / 5
        out.append('<line x1="%d" x2="%d" y1="%.1f" y2="%.1f" stroke="#ddd"/>' % (left, w - 20, y(f), y(f)))
        out.append('<text x="%d" y="%.1f" text-anchor="end">%.1f</text>' % (left - 4, y(f) + 4, f))
    out.append('<text x="14" y="%d" transform="rotate(-90 14 %d)">fraction of the injected</text>' % (h // 2, h // 2))
    for i, d in enumerate(sizes):
        for j, place in enumerate(places):
            x0 = left + (i * len(places) + j) * group
            for k, walls in enumerate(("sink", "depo")):
                f, e = value[(d, walls, place)]
                x = x0 + (k + 0.5) * bar
                out.append('<rect x="%.1f" y="%.1f" width="%.1f" height="%.1f" fill="%s"/>' % (x, y(f), bar, y(0) - y(f), colours[walls]))
                out.append('<line x1="%.1f" x2="%.1f" y1="%.1f" y2="%.1f" stroke="black"/>' % (x + bar / 2, x + bar / 2, y(min(1, f + 2 * e)), y(max(0, f - 2 * e))))
            out.append('<text x="%.1f" y="%d" text-anchor="middle">%s</text>' % (x0 + group / 2, h - bottom + 14, place))
        out.append('<text x="%.1f" y="%d" text-anchor="middle" font-weight="bold">%g um</text>' % (left + (i + 0.5) * len(places) * group, h - bottom + 32, d))
    for k, walls in enumerate(("sink", "depo")):
        label = "Code_Saturne deposition (sink)" if walls == "sink" else "depo (rebound or capture)"
        out.append('<rect x="%d" y="%d" width="10" height="10" fill="%s"/><text x="%d" y="%d">%s</text>' % (left + 250 * k, h - 14, colours[walls], left + 250 * k + 14, h - 5, label))
    out.append('<text x="%d" y="%d">bars: 2 standard errors</text>' % (left + 520, h - 5))
    out.append("</svg>")
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    main(*sys.argv[1:])
