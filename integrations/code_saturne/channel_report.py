#!/usr/bin/env python3
"""The channel case's report: Code_Saturne's deposition velocity V+ = v_d / u* for each
tau+, with its deposition model (Guingo & Minier 2008), without it, and with depo's
deposition wall function, beside Wood (1981).

    channel_report.py FLOW_RUN OUT_CSV TRANSIENT_S PARTICLE_RUN...

reads the flow stage's channel_flow.csv and each particle stage's channel_counts.csv (the
airborne particles of each class after every step). Over the window after TRANSIENT_S
seconds to the end of the run,

    v_d = (N_dep / (A T)) / (N_air_mean / V),   V+ = v_d / u*,

with N_dep the particles of the class deposited in the window (the fall of its airborne
count), N_air_mean its mean airborne count over the window (trapezoidal in time), A the
area of both walls and V the channel's volume: the mean airborne concentration of the whole
channel, as depo's channel study defines v_d. The standard error is Poisson's, V+ / sqrt(N_dep).
u* is the friction velocity the driving pressure gradient imposes (-dp/dx = rho u*^2 / H,
which the developed flow's walls carry whole). Wood's V+ = 0.057 Sc^(-2/3) + 4.5e-4 tau+^2
(at most 0.13) takes Sc = nu / D with D = k T / (3 pi mu d), the Brownian diffusivity of
Code_Saturne's particles (no slip correction, like their relaxation time).

The wall function deposits the particles of the wall cells at the rate v_wf / layer, with
v_wf what depo's Wood gives at the walls' wall-function friction velocity (the counts file's
head): its V+ should be v_wf / u* times the wall cells' concentration over the mean, C_w / C
(counted over the window). The report prints that expectation and the ratio of V+ to it, with
the Poisson error of the deposits combined with the standard error of C_w / C (from the
spread of its values over ten blocks of the window).
"""
import csv
import math
import sys

BOLTZMANN = 1.380649e-23
# channel.h: standard air, 1000 kg/m^3 particles.
RHO, MU, TEMPERATURE = 1.204, 1.81e-5, 293.15
NU = MU / RHO


def read_counts(path):
    meta, rows, header = {}, [], None
    with open(path) as f:
        for line in f:
            line = line.strip()
            if line.startswith("# stage"):
                meta["model"] = line.split()[2].rstrip(",")
                meta["particles"] = int(line.split(",")[1].split()[0])
                meta["dt"] = float(line.split("step ")[1].split()[0])
                meta["ustar_model"] = float(line.split()[-2])
            elif line.startswith("# wall area"):
                meta["area"] = float(line.split()[3])
                meta["volume"] = float(line.split()[6].rstrip(","))
                meta["near_volume"] = float(line.split()[11])
            elif line.startswith("# diameters"):
                meta["diameters"] = [float(x) for x in line.split()[2:]]
            elif line.startswith("# wall function v_d"):
                meta["wall_function_vd"] = [float(x) for x in line.split()[4:]]
            elif header is None:
                header = line.split(",")
            else:
                rows.append([float(x) for x in line.split(",")])
    classes = [float(h.split("_")[1]) for h in header if h.startswith("airborne_")]
    return meta, header, rows, classes


def wood(tau_plus, diameter):
    diffusivity = BOLTZMANN * TEMPERATURE / (3.0 * math.pi * MU * diameter)
    sc = NU / diffusivity
    return min(0.057 * sc ** (-2.0 / 3.0) + 4.5e-4 * tau_plus ** 2, 0.13)


def measure(path, ustar, transient):
    meta, header, rows, classes = read_counts(path)
    dt = meta["dt"]
    # The state at the start of the window: the row of the last step at or before it.
    start = max(i for i, r in enumerate(rows) if r[1] <= transient + 1e-12)
    window = rows[start:]
    span = window[-1][1] - window[0][1]
    lost = sum(r[-1] for r in rows)
    out = []
    for c, tau_plus in enumerate(classes):
        col = header.index("airborne_%g" % tau_plus)
        n = [r[col] for r in window]
        if n[0] == 0:
            continue  # a class not injected
        deposits = int(n[0] - n[-1])
        particle_time = sum(0.5 * (a + b) * dt for a, b in zip(n[:-1], n[1:]))
        v_d = deposits * meta["volume"] / (meta["area"] * particle_time)
        v_plus = v_d / ustar
        # The same over each half of the window: a drift between them is a transient left.
        half = len(n) // 2
        halves = []
        for m in (n[: half + 1], n[half:]):
            t = sum(0.5 * (a + b) * dt for a, b in zip(m[:-1], m[1:]))
            halves.append((m[0] - m[-1]) * meta["volume"] / (meta["area"] * t) / ustar)
        # Free flight from the wall cells: particles crossing a plane at the wall with the
        # wall cells' concentration and mean |v_z| give the flux c_near <|v_z|> / 2.
        near = sum(r[header.index("near_%g" % tau_plus)] for r in window[1:])
        abs_vz = sum(r[header.index("abs_vz_%g" % tau_plus)] for r in window[1:])
        airborne = sum(n[1:])
        concentration_ratio = (near / meta["near_volume"]) / (airborne / meta["volume"])
        free_flight = concentration_ratio * 0.5 * abs_vz / near / ustar if near else float("nan")
        # C_w / C over ten blocks of the window: the standard error of its mean.
        near_col, blocks = header.index("near_%g" % tau_plus), []
        size = (len(window) - 1) // 10
        for b in range(10):
            rows_b = window[1 + b * size: 1 + (b + 1) * size]
            near_b = sum(r[near_col] for r in rows_b)
            air_b = sum(r[col] for r in rows_b)
            blocks.append((near_b / meta["near_volume"]) / (air_b / meta["volume"]))
        mean_b = sum(blocks) / len(blocks)
        ratio_error = math.sqrt(sum((x - mean_b) ** 2 for x in blocks) / (len(blocks) - 1) / len(blocks))
        d = meta["diameters"][c]
        expected = expected_error = expected_deposits = float("nan")
        if "wall_function_vd" in meta:
            expected = meta["wall_function_vd"][c] / ustar * concentration_ratio
            expected_error = expected * ratio_error / concentration_ratio
            # The deposits the wall function should give in the window: what V+ = expected means.
            expected_deposits = expected * ustar * meta["area"] * particle_time / meta["volume"]
        out.append({
            "tau_plus": tau_plus,
            "diameter_m": d,
            "model": meta["model"],
            "v_plus": v_plus,
            "v_plus_error": v_plus / math.sqrt(deposits) if deposits > 0 else float("nan"),
            "deposits": deposits,
            "wood": wood(tau_plus, d),
            "ustar_m_s": ustar,
            "particles": meta["particles"],
            "airborne_end": int(n[-1]),
            "halves": halves,
            "near_ratio": concentration_ratio,
            "near_ratio_error": ratio_error,
            "free_flight": free_flight,
            "expected": expected,
            "expected_error": expected_error,
            "expected_deposits": expected_deposits,
        })
    return out, meta, span, lost


def main(flow_run, out_csv, transient, *runs):
    with open(flow_run + "/channel_flow.csv") as f:
        flow = next(csv.DictReader(f))
    ustar = float(flow["ustar_imposed"])
    print("flow: u* = %.3f m/s imposed (wall functions' u* %.3f m/s), bulk %.2f m/s, centre %.2f m/s, "
          "first cell centre at y+ %.1f, Re_tau %.0f"
          % (ustar, float(flow["ustar_wall_functions"]), float(flow["bulk_velocity"]),
             float(flow["centre_velocity"]), float(flow["first_cell_yplus"]), ustar * 0.024 / NU))
    results = []
    for run in runs:
        rows, meta, span, lost = measure(run + "/channel_counts.csv", ustar, transient)
        print("%s: %d particles per class, window %.3f-%.3f s, %d lost by the tracking, "
              "u* seen by the deposition model %.3f m/s"
              % (meta["model"], meta["particles"], transient, transient + span, lost, meta["ustar_model"]))
        results += rows
    fields = ["tau_plus", "diameter_m", "model", "v_plus", "v_plus_error", "deposits", "wood",
              "ustar_m_s", "particles", "near_ratio", "near_ratio_error", "expected", "expected_error"]
    with open(out_csv, "w") as f:
        f.write(",".join(fields) + "\n")
        for r in results:
            line = "%g,%.4e,%s,%.4e,%.2e,%d,%.3e,%.3f,%d,%.4f,%.4f" % tuple(r[k] for k in fields[:11])
            if math.isnan(r["expected"]):
                line += ",,"
            else:
                line += ",%.4e,%.2e" % (r["expected"], r["expected_error"])
            f.write(line + "\n")
    print("%6s %9s %14s %10s %8s %8s %9s %9s | %19s %8s %9s"
          % ("tau+", "d (um)", "model", "V+", "error", "deposits", "Wood", "V+/Wood",
             "V+ by window halves", "c1/c", "free V+"))
    for r in results:
        print("%6g %9.2f %14s %10.3e %7.1f%% %8d %9.2e %9.3g | %9.3e %9.3e %8.3f %9.3e"
              % (r["tau_plus"], r["diameter_m"] * 1e6, r["model"], r["v_plus"],
                 100 * r["v_plus_error"] / r["v_plus"] if r["deposits"] else float("nan"),
                 r["deposits"], r["wood"], r["v_plus"] / r["wood"], r["halves"][0], r["halves"][1],
                 r["near_ratio"], r["free_flight"]))
    print("c1/c: the wall cells' mean concentration over the channel's; free V+: c1/c <|v_z|> / (2 u*),"
          " the one-way flux of the wall cells' particles through a plane")
    checks = [r for r in results if not math.isnan(r["expected"])]
    if checks:
        print("\nthe wall function: V+ against v_wf / u* x C_w / C (v_wf: depo's Wood at the walls' "
              "wall-function u*)")
        print("%6s %10s %8s %8s %15s %10s %9s %17s" % ("tau+", "V+", "error", "deposits", "C_w/C", "expected",
                                                        "deposits", "V+/expected"))
        for r in checks:
            ratio = r["v_plus"] / r["expected"]
            rel = math.sqrt(1.0 / max(r["deposits"], 1) + (r["near_ratio_error"] / r["near_ratio"]) ** 2)
            print("%6g %10.3e %7.1f%% %8d %7.3f +- %.3f %10.3e %9.1f %8.3f +- %.3f"
                  % (r["tau_plus"], r["v_plus"], 100 * r["v_plus_error"] / r["v_plus"] if r["deposits"] else float("nan"),
                     r["deposits"], r["near_ratio"], r["near_ratio_error"], r["expected"],
                     r["expected_deposits"], ratio, ratio * rel))
        print("expected deposits: the wall function's v_wf C_w over the window, in particles")
    print("wrote", out_csv)


if __name__ == "__main__":
    if len(sys.argv) < 5:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2], float(sys.argv[3]), *sys.argv[4:])
