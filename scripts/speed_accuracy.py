#!/usr/bin/env python3
"""Tabulates the runs of scripts/speed_accuracy.sh: error against wall time.

Incline: the worst relative error of the downslope displacement (where it is >= 1 cm)
against seed Eq. 5 integrated with a fine fixed step. Vajont: the relative change of
point 1's maximum lateral displacement and peak lateral velocity from the section's
finest substep run (time.step 0.0025 s, 8 substeps)."""
import csv
import json
import math
import os
import sys

out = sys.argv[1]
runs = os.path.join(out, "runs")
G, ALPHA, PHI, I_DEG, DC = 9.81, math.atan(0.5), 25.0, 5.0, 0.01 * 2.23


def exact_incline(times):
    """Seed Eq. 5: a(d) = g (sin a - cos a tan(phi_p - i min(d/dc, 1))), by RK4 at 1e-5 s."""
    def acc(d):
        phi = math.radians(PHI - I_DEG * min(d / DC, 1.0))
        return G * (math.sin(ALPHA) - math.cos(ALPHA) * math.tan(phi))
    result, t, d, v, h = {}, 0.0, 0.0, 0.0, 1e-5
    for target in sorted(times):
        while t < target - 1e-12:
            step = min(h, target - t)
            k1v, k1d = acc(d), v
            k2v, k2d = acc(d + 0.5 * step * k1d), v + 0.5 * step * k1v
            k3v, k3d = acc(d + 0.5 * step * k2d), v + 0.5 * step * k2v
            k4v, k4d = acc(d + step * k3d), v + step * k3v
            d += step * (k1d + 2 * k2d + 2 * k3d + k4d) / 6
            v += step * (k1v + 2 * k2v + 2 * k3v + k4v) / 6
            t += step
        result[target] = d
    return result


def load(name):
    path = os.path.join(runs, name, "summary.json")
    if not os.path.exists(path):
        return None
    with open(path) as f:
        return json.load(f)


along = (2 / math.sqrt(5), -1 / math.sqrt(5))
with open(os.path.join(out, "incline.csv"), "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(["solver", "time_step", "substeps", "wall_seconds", "displacement_error", "status"])
    for name in sorted(os.listdir(runs)):
        if not name.startswith("incline_"):
            continue
        s = load(name)
        parts = name.split("_")
        solver, dt = parts[1], float(parts[2])
        substeps = int(parts[3]) if solver == "substep" else 0
        if s is None or s["status"] != "completed":
            w.writerow([solver, dt, substeps, "", "", "failed"])
            continue
        rows = list(csv.DictReader(open(os.path.join(runs, name, "history.csv"))))
        times = [float(r["time"]) for r in rows]
        exact = exact_incline(times)
        worst = 0.0
        for r, t in zip(rows, times):
            d = float(r["ux"]) * along[0] + float(r["uy"]) * along[1]
            if exact[t] >= 0.01:
                worst = max(worst, abs(d - exact[t]) / exact[t])
        w.writerow([solver, dt, substeps, s["run"]["wall_seconds"], worst, "completed"])

with open(os.path.join(out, "vajont.csv"), "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(["block_size", "solver", "time_step", "substeps", "wall_seconds", "runout", "peak_velocity",
                "runout_error", "velocity_error", "worst_penetration_ratio", "status"])
    sizes = sorted({n.split("_")[1] for n in os.listdir(runs) if n.startswith("vajont_")}, key=float, reverse=True)
    for size in sizes:
        ref = load(f"vajont_{size}_substep_0.0025_8")
        if ref is None or ref["status"] != "completed":
            continue
        r1 = ref["points"]["1"]
        for name in sorted(n for n in os.listdir(runs) if n.startswith(f"vajont_{size}_")):
            s = load(name)
            parts = name.split("_")
            solver, dt = parts[2], float(parts[3])
            substeps = int(parts[4]) if solver == "substep" else 0
            if s is None:
                continue
            p = s["points"]["1"]
            ok = s["status"] == "completed"
            w.writerow([size, solver, dt, substeps, s["run"]["wall_seconds"], p["max_lateral_displacement"],
                        p["peak_lateral_velocity"],
                        abs(p["max_lateral_displacement"] / r1["max_lateral_displacement"] - 1) if ok else "",
                        abs(p["peak_lateral_velocity"] / r1["peak_lateral_velocity"] - 1) if ok else "",
                        s.get("solver", {}).get("worst_penetration_ratio", ""), s["status"]])
