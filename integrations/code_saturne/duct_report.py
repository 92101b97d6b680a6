#!/usr/bin/env python3
"""The duct case's report: where the particles of each size went, with Code_Saturne's own
deposition walls (every wall contact deposits), with depo's law (rebound or capture) and, given
the model run, with Code_Saturne's deposition model (Guingo & Minier 2008); and, given the
wall-function run, its deposits against the correlation's prediction.

    duct_report.py SINK_RUN DEPO_RUN [WALL_FUNCTION_RUN [MODEL_RUN]] OUT_DIR

reads each run's duct_census.csv (and depo's depo_impacts.csv for the rebounds), prints a
table, and writes OUT_DIR/duct.csv and the figure OUT_DIR/duct.svg. The fractions are of the
particles injected per size (8000); their standard errors are binomial, sqrt(f (1 - f) / N).

With WALL_FUNCTION_RUN, its duct_wall_function.csv gives per size the deposits, the number
the correlation's flux predicts from the particles the wall cells held at each step (the sum
of their chances, with its binomial variance), and per wall the mean u*, the correlation's
v_d there and the wall cells' concentration over the duct's. The table sets beside them the
well-mixed prediction for the duct, 1 - exp(-(sum over walls of v_d x perimeter) L / Q) with
the duct's L = 2 m, perimeter 0.2 m per wall (0.4 m for the two sides) and Q = 0.04 m^3/s,
and Code_Saturne's sink walls' deposited fraction, and with MODEL_RUN its deposition model's;
written to OUT_DIR/duct_wall_function.csv, and the figure gains a second panel: the deposited
fraction per size beside both predictions, the sink walls' and the model's.

    duct_report.py --figure DUCT_CSV WALL_FUNCTION_CSV OUT_SVG

draws the figure alone from the two CSV files a report wrote: the ones stored beside this
script (duct.csv, duct_wall_function.csv) redraw docs/figures/code-saturne-duct.svg without
running the case.
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


def main(sink_run, depo_run, out, model_run=None):
    sink, depo, bounced = census(sink_run), census(depo_run), rebounds(depo_run)
    model = census(model_run) if model_run else None
    rows = []
    for d in sorted(sink):
        runs = [("sink", sink[d]), ("depo", depo[d])] + ([("model", model[d])] if model else [])
        for walls, c in runs:
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
    print("wrote", os.path.join(out, "duct.csv"))


def read_csv(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def figure(duct_csv, wall_function_csv, path):
    """The figure, from the report's CSV files (the stored ones redraw it without a run): the
    fate of the particles with each kind of wall and, given the wall-function CSV, a second
    panel with its deposited fraction beside the correlation's predictions and Code_Saturne's
    sink walls and deposition model."""
    rows = [(float(r["diameter_um"]), r["walls"], r["where"], int(r["count"]), float(r["fraction"]),
             float(r["error"]), int(r["rebounds"])) for r in read_csv(duct_csv)]
    w, h = 760, 360
    out = fates(rows, w, h)
    if wall_function_csv is not None:
        panel_h = 360
        out += ['<g transform="translate(0 %d)">' % h] + wall_function_panel(read_csv(wall_function_csv), w, panel_h) + ["</g>"]
        h += panel_h
    head = '<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d" font-family="sans-serif" font-size="11">' % (w, h)
    with open(path, "w") as f:
        f.write("\n".join([head] + out + ["</svg>"]) + "\n")
    print("wrote", path)


# The kinds of wall of the fates' panel: their colours and legends, in the order drawn.
FATE_WALLS = [
    ("sink", "#888888", "Code_Saturne sink walls"),
    ("depo", "#1f77b4", "depo (rebound or capture)"),
    ("model", "#2ca02c", "Code_Saturne deposition model"),
]


def fates(rows, w, h):
    """Grouped bars: per size, the fraction deposited on each wall and leaving, each kind of
    wall the CSV holds."""
    places = WALLS + ["outlet"]
    sizes = sorted({r[0] for r in rows})
    value = {(r[0], r[1], r[2]): (r[4], r[5]) for r in rows}
    kinds = [k for k in FATE_WALLS if any(r[1] == k[0] for r in rows)]
    left, bottom, top = 60, 60, 30
    group = (w - left - 20) / (len(sizes) * len(places))
    bar = group / (len(kinds) + 1)
    y = lambda f: h - bottom - f * (h - bottom - top)
    out = []
    out.append('<text x="%d" y="18" font-size="13">Duct, 1 m/s: fate of the particles, per kind of wall</text>' % left)
    out.append('<text x="%d" y="18" text-anchor="end">bars: 2 standard errors</text>' % (w - 20))
    for k in range(6):
        f = k / 5
        out.append('<line x1="%d" x2="%d" y1="%.1f" y2="%.1f" stroke="#ddd"/>' % (left, w - 20, y(f), y(f)))
        out.append('<text x="%d" y="%.1f" text-anchor="end">%.1f</text>' % (left - 4, y(f) + 4, f))
    out.append('<text x="14" y="%d" transform="rotate(-90 14 %d)">fraction of the injected</text>' % (h // 2, h // 2))
    for i, d in enumerate(sizes):
        for j, place in enumerate(places):
            x0 = left + (i * len(places) + j) * group
            for k, (walls, colour, _) in enumerate(kinds):
                f, e = value[(d, walls, place)]
                x = x0 + (k + 0.5) * bar
                out.append('<rect x="%.1f" y="%.1f" width="%.1f" height="%.1f" fill="%s"/>' % (x, y(f), bar, y(0) - y(f), colour))
                out.append('<line x1="%.1f" x2="%.1f" y1="%.1f" y2="%.1f" stroke="black"/>' % (x + bar / 2, x + bar / 2, y(min(1, f + 2 * e)), y(max(0, f - 2 * e))))
            out.append('<text x="%.1f" y="%d" text-anchor="middle">%s</text>' % (x0 + group / 2, h - bottom + 14, place))
        out.append('<text x="%.1f" y="%d" text-anchor="middle" font-weight="bold">%g um</text>' % (left + (i + 0.5) * len(places) * group, h - bottom + 32, d))
    x = left
    for walls, colour, label in kinds:
        out.append('<rect x="%d" y="%d" width="10" height="10" fill="%s"/><text x="%d" y="%d">%s</text>' % (x, h - 14, colour, x + 14, h - 5, label))
        x += 14 + int(6 * len(label)) + 24
    return out


def wall_function_panel(rows, w, h):
    """Per size, on a log scale: the wall function's deposited fraction (all walls), the
    fraction the correlation's flux predicts from the wall cells' particles, the well-mixed
    duct's prediction, Code_Saturne's sink walls and, where the CSV has them, its deposition
    model on the same mesh; 2 binomial standard errors on each count."""
    model = "model_fraction" in rows[0]
    left, bottom, top = 60, 106 if model else 76, 34
    lo, hi = 0.01, 1.3
    y = lambda f: h - bottom - math.log10(max(lo, min(hi, f)) / lo) / math.log10(hi / lo) * (h - bottom - top)
    group = (w - left - 20) / len(rows)
    out = ['<text x="%d" y="20" font-size="13">Duct: deposited fraction (all walls) against Lai &amp; Nazaroff\'s (2000) prediction</text>' % left]
    for f in (0.01, 0.02, 0.05, 0.1, 0.2, 0.5, 1):
        major = f in (0.01, 0.1, 1)
        out.append('<line x1="%d" x2="%d" y1="%.1f" y2="%.1f" stroke="%s"/>' % (left, w - 20, y(f), y(f), "#bbb" if major else "#eee"))
        out.append('<text x="%d" y="%.1f" text-anchor="end">%g</text>' % (left - 4, y(f) + 4, f))
    out.append('<text x="14" y="%d" transform="rotate(-90 14 %d)">fraction deposited</text>' % ((h - bottom + top) // 2 + 40, (h - bottom + top) // 2 + 40))
    series = [  # (label, colour, marker, fraction column, error column)
        ("depo's wall function", "#d62728", "dot", "fraction", None),
        ("predicted from the wall cells", "black", "square", "predicted_wall_cells", "predicted_error"),
        ("well-mixed prediction", "black", "dash", "predicted_well_mixed", ""),
        ("Code_Saturne sink walls", "#888888", "diamond", "sink_fraction", None),
    ]
    if model:
        series.append(("Code_Saturne deposition model", "#2ca02c", "triangle", "model_fraction", None))
    step = group / (len(series) + 1)
    for i, r in enumerate(rows):
        n = int(r["injected"])
        x0 = left + i * group
        for k, (label, colour, marker, col, err_col) in enumerate(series):
            f = float(r[col])
            if err_col is None:
                e = math.sqrt(max(0.0, f * (1 - f)) / n)
            else:
                e = float(r[err_col]) if err_col else 0.0
            x = x0 + (k + 1) * step
            if e > 0:
                out.append('<line x1="%.1f" x2="%.1f" y1="%.1f" y2="%.1f" stroke="%s"/>' % (x, x, y(f + 2 * e), y(f - 2 * e), colour))
                for yy in (y(f + 2 * e), y(f - 2 * e)):
                    out.append('<line x1="%.1f" x2="%.1f" y1="%.1f" y2="%.1f" stroke="%s"/>' % (x - 4, x + 4, yy, yy, colour))
            out.append(mark(marker, x, y(f), colour))
        mixed = float(r["predicted_well_mixed"])
        out.append('<text x="%.1f" y="%d" text-anchor="middle" font-weight="bold">%g um</text>' % (x0 + group / 2, h - bottom + 16, float(r["diameter_um"])))
        out.append('<text x="%.1f" y="%d" text-anchor="middle" fill="%s">z = %s, %.2f x well-mixed</text>' % (
            x0 + group / 2, h - bottom + 30, series[0][1], r["z"].replace("-", "&#8722;"), float(r["fraction"]) / mixed))
        if model:
            out.append('<text x="%.1f" y="%d" text-anchor="middle" fill="%s">model: %.2f x well-mixed</text>' % (
                x0 + group / 2, h - bottom + 44, series[-1][1], float(r["model_fraction"]) / mixed))
    out.append('<text x="%d" y="%d">z: the wall function\'s deposits minus the prediction from the wall cells, in its errors; bars: 2 binomial standard errors</text>' % (left, h - 39 if model else h - 24))
    x, line = left, h - 20 if model else h - 5
    for label, colour, marker, _, _ in series:
        width = 14 + 6 * len(label) + 20
        if x + width > w - 20:
            x, line = left, line + 15
        out.append(mark(marker, x + 5, line - 4, colour) + '<text x="%d" y="%d">%s</text>' % (x + 14, line, label))
        x += width
    return out


def mark(marker, x, y, colour):
    if marker == "dot":
        return '<circle cx="%.1f" cy="%.1f" r="4" fill="%s"/>' % (x, y, colour)
    if marker == "square":
        return '<rect x="%.1f" y="%.1f" width="8" height="8" fill="none" stroke="%s" stroke-width="1.5"/>' % (x - 4, y - 4, colour)
    if marker == "dash":
        return '<line x1="%.1f" x2="%.1f" y1="%.1f" y2="%.1f" stroke="%s" stroke-width="2.5"/>' % (x - 6, x + 6, y, y, colour)
    if marker == "triangle":
        return '<path d="M %.1f %.1f l 5 9 l -10 0 z" fill="%s"/>' % (x, y - 5, colour)
    return '<path d="M %.1f %.1f l 5 5 l -5 5 l -5 -5 z" fill="%s"/>' % (x, y - 5, colour)


# The duct: length (m), each wall's share of the perimeter (m), the air's flow rate (m^3/s).
LENGTH, PERIMETER, FLOW = 2.0, {"floor": 0.2, "ceiling": 0.2, "sides": 0.4}, 0.2 * 0.2 * 1.0


def wall_function(sink_run, wf_run, out, model_run=None):
    sink = census(sink_run)
    model = census(model_run) if model_run else None
    rows = []
    with open(os.path.join(wf_run, "duct_wall_function.csv")) as f:
        for r in csv.DictReader(f):
            d, n = float(r["diameter"]), int(r["injected"])
            dep, exp, var = int(r["deposited"]), float(r["expected"]), float(r["expected_variance"])
            loss = sum(float(r[w + "_vd"]) * PERIMETER[w] for w in WALLS) * LENGTH / FLOW
            mixed = 1.0 - math.exp(-loss)
            deposited = lambda c: sum(int(c[w]) for w in WALLS) / int(c["injected"])
            z = (dep - exp) / math.sqrt(var) if var > 0 else float("nan")
            rows.append((d * 1e6, n, dep, dep / n, exp / n, math.sqrt(var) / n, z, mixed,
                         float(r["floor_near_ratio"]), float(r["floor_ustar"]), deposited(sink[d]))
                        + ((deposited(model[d]),) if model else ()))
    with open(os.path.join(out, "duct_wall_function.csv"), "w") as f:
        f.write("diameter_um,injected,deposited,fraction,predicted_wall_cells,predicted_error,"
                "z,predicted_well_mixed,floor_near_ratio,floor_ustar,sink_fraction"
                + (",model_fraction\n" if model else "\n"))
        for r in rows:
            f.write("%g,%d,%d,%.5f,%.5f,%.5f,%.2f,%.5f,%.3f,%.5f,%.5f" % r[:11]
                    + (",%.5f\n" % r[11] if model else "\n"))
    print("\nwall function (lai-nazaroff): deposited fraction against the correlation's prediction")
    print("%8s %8s %18s %18s %6s %11s %9s %10s%s" % ("d (um)", "deposits", "fraction", "from wall cells",
                                                   "z", "well-mixed", "C_w/C fl", "CS sink",
                                                   " %18s" % "CS model" if model else ""))
    for r in rows:
        d, n, dep, frac, pred, err, z, mixed, near, ustar, sink_f = r[:11]
        line = "%8g %8d %9.4f +- %.4f %9.4f +- %.4f %6.2f %11.4f %9.3f %10.4f" % (
            d, dep, frac, math.sqrt(frac * (1 - frac) / n), pred, err, z, mixed, near, sink_f)
        if model:
            line += " %9.4f +- %.4f" % (r[11], math.sqrt(r[11] * (1 - r[11]) / n))
        print(line)
    print("u* (area-weighted mean of the floor's ustar): %.4f m/s" % rows[0][9])
    print("wrote", os.path.join(out, "duct_wall_function.csv"))


if __name__ == "__main__":
    args = sys.argv[1:]
    if len(args) == 4 and args[0] == "--figure":
        figure(*args[1:])
    elif len(args) == 3:
        main(*args)
        figure(os.path.join(args[2], "duct.csv"), None, os.path.join(args[2], "duct.svg"))
    elif len(args) in (4, 5):
        sink_run, depo_run, wf_run, out = args[0], args[1], args[2], args[-1]
        model_run = args[3] if len(args) == 5 else None
        main(sink_run, depo_run, out, model_run)
        wall_function(sink_run, wf_run, out, model_run)
        figure(*(os.path.join(out, name) for name in ("duct.csv", "duct_wall_function.csv", "duct.svg")))
    else:
        sys.exit(__doc__)
