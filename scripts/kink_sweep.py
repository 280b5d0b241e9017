#!/usr/bin/env python3
"""A slider crossing a kink of the ground, the ground built three ways: the black-box sweep behind
docs/theory.md §3, "Joints of the fixed ground, and cut ends" (model revision 2026-12-06.24).

Random cases (seeded): an upper face of 20, 30 or 40 deg bending by -30 to +10 deg at the kink K
(concave when the lower face is gentler), friction 10-20 deg, a slider 0.1-30 m long (0.3 or 0.6 as
high) starting 0.2-3 lengths before K (a thousandth of its length above the face) from rest or at
3-25 m/s, fixed blocks jointed every 0.37, 1.3 or 3.1 slider lengths, steps of 1, 5 and 10 ms; both
solvers. A case whose ground blocks the generator cannot make simple (deep blocks jointed closely
under a convex kink) is refused by ddafit (exit 2) and printed as FAILED. Each case runs on
  whole     the ground as one concave polygon,
  jointed   fixed blocks, one of them ending at K (the joint at K along the bisector of the faces),
  spanning  the same, the block over K spanning from the joint before it to the joint after it,
and prints the jointed and spanning grounds' final positions of the slider's centre off the whole
ground's, as shares of its travel there; '<<<' marks more than 1 %. With --free the third ground is
  free      the jointed blocks free (not fixed), on a fixed bed two lengths deep that holds them
            (60 deg on their joints and bed),
a jointed slide's surface rather than its bed; --solvers picks the solvers. With --steps the face is
straight and has a step at K of -5 to +20 % of the slider's length (negative: up) instead. The three are one ground, so
anything more is a ghost of the joints or cuts. Runs two at a time; not a timing.

    python3 scripts/kink_sweep.py --ddafit build/apps/ddafit/ddafit --seed 1 --cases 16 --out /tmp/kinks
    python3 scripts/kink_sweep.py --ddafit build/apps/ddafit/ddafit --seed 5 --cases 16 --steps --out /tmp/steps
    python3 scripts/kink_sweep.py --ddafit build/apps/ddafit/ddafit --seed 1 --cases 16 --free --solvers substep \
        --out /tmp/free
"""
import argparse
import csv
import json
import math
import os
import random
import subprocess
from concurrent.futures import ThreadPoolExecutor

G = 9.81


def unit(dip):
    a = math.radians(dip)
    return (math.cos(a), -math.sin(a))


def up(t):
    return (-t[1], t[0])


def add(p, q, s=1.0):
    return (p[0] + s * q[0], p[1] + s * q[1])


def scene(c):
    t1, t2 = unit(c["a1"]), unit(c["a2"])
    n1, n2 = up(t1), up(t2)
    length, depth, spacing = c["L"], c["L"], c["spacing"] * c["L"]
    upper, lower = c["D"] + 3 * length, c["run"]
    bis = (n1[0] + n2[0], n1[1] + n2[1])
    norm = math.hypot(*bis)
    bis = (bis[0] / norm, bis[1] / norm)
    kb = add((0.0, 0.0), bis, -depth / (bis[0] * n1[0] + bis[1] * n1[1]))
    # The joints' tops and bases, from the top of the upper face to the foot of the lower one.
    cuts = {upper - k * spacing for k in range(int(upper / spacing) + 1) if upper - k * spacing > 1e-9}
    cuts = sorted(cuts | {upper})
    top = [add((0.0, 0.0), t1, -x) for x in reversed(cuts)] + [(0.0, 0.0)]
    base = [add(p, n1, -depth) for p in top[:-1]] + [kb]
    k_joint = len(top) - 1
    lower_start = add((0.0, 0.0), n1, -c["h"] * length)  # --steps: below K (a step down) or above it
    for x in sorted({k * spacing for k in range(1, int(lower / spacing) + 1)} | {lower}):
        top.append(add(lower_start, t2, x))
        base.append(add(top[-1], n2, -depth))
    r = lambda p: [round(p[0], 9), round(p[1], 9)]

    def piece(i, j):  # the ground from joint i to joint j, counter-clockwise; a step's riser at K
        tops = list(top[i:j + 1])
        if c["h"] != 0.0 and i <= k_joint <= j:
            if i == k_joint:
                tops[0] = lower_start
            elif j != k_joint:
                tops.insert(k_joint - i + 1, lower_start)
        return [r(p) for p in base[i:j + 1]] + [r(p) for p in reversed(tops)]
    blocks = []
    if c["ground"] == "free":  # --free: the jointed blocks free on a fixed bed, 2 lengths deep, held at 60 deg
        bed = [r(p) for p in base] + [r(add(p, (0.0, -2.0 * length))) for p in reversed(base)]
        blocks.append({"name": "bed", "group": "bed", "material": "rock", "fixed": True, "polygon": bed})
    if c["ground"] == "whole":
        blocks.append({"name": "ground", "group": "base", "material": "rock", "fixed": True,
                       "polygon": piece(0, len(top) - 1)})
    else:
        i = 0
        while i < len(top) - 1:
            j = i + 2 if c["ground"] == "spanning" and i == k_joint - 1 else i + 1
            blocks.append({"name": f"ground_{i}", "group": "base", "material": "rock", "fixed": c["ground"] != "free",
                           "polygon": piece(i, j)})
            i = j
    # In flight a thousandth of its length above the face: resting on a face it cannot stand on,
    # the slider would slide through the quiet start by as much as its steps allow, differently on
    # each ground (docs/verification.md), and the grounds would be compared from different starts.
    front = add(add((0.0, 0.0), t1, -c["D"]), n1, 1e-3 * length)
    rear = add(front, t1, -length)
    height = c["aspect"] * length
    blocks.append({"name": "slider", "group": "slider", "material": "rock",
                   "polygon": [r(rear), r(front), r(add(front, n1, height)), r(add(rear, n1, height))],
                   "velocity": [c["v0"] * t1[0], c["v0"] * t1[1]]})
    centre = add(add(rear, t1, 0.5 * length), n1, 0.5 * height)
    s = {"gravity": [0, -G], "time": {"duration": c["T"], "step": c["dt"], "integrator": c["solver"]},
         "materials": {"rock": {"density": 2500, "young_modulus": 5e9, "poisson_ratio": 0.25}},
         "interfaces": {"basal": {"friction_angle": c["phi"]}}, "blocks": blocks,
         "contacts": [{"between": ["base", "slider"], "interface": "basal"}],
         "measure": [{"name": "P", "at": r(centre)}], "output": {"interval": c["T"] / 8}}
    if c["ground"] == "free":  # the free blocks' joints and bed hold them
        s["interfaces"]["bed"] = {"friction_angle": 60}
        s["default_interface"] = "bed"
    return s


def run(ddafit, out, c):
    folder = os.path.join(out, "_".join(f"{k}{v}" for k, v in sorted(c.items()) if k != "run"))
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, "scene.yaml"), "w") as f:
        json.dump(scene(c), f)  # JSON is YAML
    p = subprocess.run([ddafit, "simulate", os.path.join(folder, "scene.yaml"), "--out", folder, "--quiet",
                        "--threads", "1"], capture_output=True, text=True)
    if p.returncode != 0:
        return None, f"exit {p.returncode}: {(p.stderr or p.stdout).strip()[-200:]}"
    with open(os.path.join(folder, "history.csv")) as f:
        last = list(csv.DictReader(f))[-1]
    return (float(last["ux"]), float(last["uy"]), math.hypot(float(last["vx"]), float(last["vy"]))), ""


def cases(seed, count, steps, free=False, solvers=("implicit", "substep")):
    rng = random.Random(seed)
    for _ in range(count):
        a1 = rng.choice([20, 30, 40])
        a2 = max(a1 + rng.choice([-30, -20, -10, -5, 5, 10]), 0)
        if steps:  # a straight face with a step at K
            a2 = a1
        phi = rng.choice([10, 15]) if a2 < 15 else rng.choice([10, 15, 20])
        length, v0 = rng.choice([0.1, 1.0, 10.0, 30.0]), rng.choice([0.0, 3.0, 10.0, 25.0])
        c = dict(a1=a1, a2=a2, phi=phi, L=length, aspect=rng.choice([0.3, 0.6]), D=rng.choice([0.2, 1.0, 3.0]) * length,
                 v0=v0, spacing=rng.choice([0.37, 1.3, 3.1]), dt=rng.choice([0.001, 0.005, 0.01]))
        a = G * (math.sin(math.radians(a1)) - math.cos(math.radians(a1)) * math.tan(math.radians(phi)))
        reach = (-v0 + math.sqrt(v0 * v0 + 2 * a * c["D"])) / a if a > 0 else c["D"] / max(v0, 1e-9)
        c["T"] = round(reach + max(1.0, 0.5 * math.sqrt(length)), 3)
        c["run"] = (v0 + 10 * c["T"]) * c["T"] + 5 * length
        c["h"] = 0.0
        if steps:  # the step's height in slider lengths (> 0 down); the flush tolerance eta is 0.02 of them
            c["h"] = rng.choice([-0.05, -0.01, -0.002, 0.002, 0.01, 0.05, 0.2])
        for solver in solvers:
            yield [dict(c, solver=solver, ground=g) for g in ["whole", "jointed", "free" if free else "spanning"]]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--ddafit", default="build/apps/ddafit/ddafit")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--cases", type=int, default=16, help="cases, each on both solvers and three grounds")
    parser.add_argument("--out", default="kink-sweep")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--steps", action="store_true", help="a step at K on a straight face instead of a kink")
    parser.add_argument("--free", action="store_true",
                        help="the third ground is the jointed blocks free on a fixed bed, instead of spanning")
    parser.add_argument("--solvers", nargs="+", default=["implicit", "substep"])
    args = parser.parse_args()
    groups = list(cases(args.seed, args.cases, args.steps, args.free, args.solvers))
    flat = [c for g in groups for c in g]
    with ThreadPoolExecutor(args.jobs) as pool:
        results = list(pool.map(lambda c: run(args.ddafit, args.out, c), flat))
    flagged = 0
    for i, group in enumerate(groups):
        rr = results[3 * i:3 * i + 3]
        key = " ".join(f"{k}={v}" for k, v in group[0].items() if k not in ("ground", "run"))
        failed = [(c["ground"], e) for c, (r, e) in zip(group, rr) if r is None]
        if failed:
            print(key, "FAILED", failed, flush=True)
            continue
        whole = rr[0][0]
        travel = math.hypot(whole[0], whole[1])
        offs = [math.hypot(r[0][0] - whole[0], r[0][1] - whole[1]) / travel for r in rr[1:]]
        flagged += max(offs) > 0.01
        print(f"{key}: travel {travel:.4f} m, speeds {' '.join(f'{r[0][2]:.3f}' for r in rr)} m/s | jointed "
              f"{100 * offs[0]:.2f} %, {group[2]['ground']} {100 * offs[1]:.2f} % {'<<<' if max(offs) > 0.01 else ''}",
              flush=True)
    print(f"{len(groups)} cases, {flagged} more than 1 % apart")


if __name__ == "__main__":
    main()
