#!/usr/bin/env python3
"""Top surface of a ddafit VTK snapshot against a ground profile CSV.

Usage: surface_after.py SNAPSHOT.vtk GROUND.csv OUT.csv [x_min x_max step]

Writes OUT.csv (x, simulated top of the moving blocks, ground profile, difference) and
prints the mean and RMS difference over the x range where blocks exist. The simulated
top is the highest point of any free block's outline in each x column (the VTK's
`fixed` cell field tells free from fixed blocks). Standard library only.
"""
import csv
import math
import sys


def read_vtk(path):
    with open(path) as f:
        tokens = f.read().split("\n")
    points, polygons, fixed = [], [], []
    i = 0
    while i < len(tokens):
        line = tokens[i].split()
        if line[:1] == ["POINTS"]:
            for k in range(int(line[1])):
                x, y, _ = tokens[i + 1 + k].split()
                points.append((float(x), float(y)))
            i += int(line[1])
        elif line[:1] == ["POLYGONS"]:
            for k in range(int(line[1])):
                ids = [int(v) for v in tokens[i + 1 + k].split()[1:]]
                polygons.append([points[v] for v in ids])
            i += int(line[1])
        elif line[:2] == ["SCALARS", "fixed"]:
            fixed = [int(tokens[i + 2 + k]) for k in range(len(polygons))]
            i += 1 + len(polygons)
        i += 1
    return [p for p, f in zip(polygons, fixed) if not f]


def read_profile(path):
    rows = [r for r in csv.reader(l for l in open(path) if not l.startswith("#"))]
    return [(float(x), float(z)) for x, z in rows[1:]]


def interpolate(profile, x):
    for (x0, z0), (x1, z1) in zip(profile, profile[1:]):
        if x0 <= x <= x1:
            return z0 + (z1 - z0) * (x - x0) / (x1 - x0) if x1 > x0 else max(z0, z1)
    return float("nan")


def top_of(polygons, x):
    best = -math.inf
    for poly in polygons:
        n = len(poly)
        for k in range(n):
            (xa, ya), (xb, yb) = poly[k], poly[(k + 1) % n]
            if min(xa, xb) <= x <= max(xa, xb):
                y = max(ya, yb) if xa == xb else ya + (yb - ya) * (x - xa) / (xb - xa)
                best = max(best, y)
    return best


def main():
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    blocks = read_vtk(sys.argv[1])
    profile = read_profile(sys.argv[2])
    x_min = float(sys.argv[4]) if len(sys.argv) > 4 else min(x for p in blocks for x, _ in p)
    x_max = float(sys.argv[5]) if len(sys.argv) > 5 else max(x for p in blocks for x, _ in p)
    step = float(sys.argv[6]) if len(sys.argv) > 6 else 10.0
    diffs = []
    with open(sys.argv[3], "w") as out:
        out.write("x,simulated_top,ground,difference\n")
        x = x_min
        while x <= x_max:
            top, ground = top_of(blocks, x), interpolate(profile, x)
            if top > -math.inf and not math.isnan(ground):
                diffs.append(top - ground)
                out.write(f"{x:.1f},{top:.2f},{ground:.2f},{top - ground:.2f}\n")
            x += step
    mean = sum(diffs) / len(diffs)
    rms = math.sqrt(sum(d * d for d in diffs) / len(diffs))
    print(f"{len(diffs)} columns from x = {x_min:.0f} to {x_max:.0f} m: mean difference {mean:+.1f} m, "
          f"RMS {rms:.1f} m, largest {max(diffs, key=abs):+.1f} m")


if __name__ == "__main__":
    main()
