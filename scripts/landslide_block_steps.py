#!/usr/bin/env python3
"""Sliders of landslide size from rest against seed Eq. 4, at time steps given as shares of each
slider's elastic period L/c (L = sqrt(area), c = sqrt(E / rho)): the sweep behind the short-step
numbers of docs/theory.md, Known limits (a), and docs/verification.md, "Stability map".

Sliders 10 x 2.5, 30 x 8, 90 x 24 and 200 x 50 m; faces 40/25, 35/33 and 28/18 deg (slope/friction);
on one fixed block and across joints every third of the slider; E = 5 GPa, rho = 2700 kg/m^3;
1.5 s, an output at every step, the scene's default controls. Prints each run's worst relative
error of the displacement along the face where it has moved 1 cm, and per share the worst of all.

    python3 scripts/landslide_block_steps.py --ddafit build/apps/ddafit/ddafit --shares 0.005 0.01
"""
import argparse
import csv
import json
import math
import os
import subprocess
import tempfile

SLIDERS = [(10.0, 2.5), (30.0, 8.0), (90.0, 24.0), (200.0, 50.0)]
FACES = [(40.0, 25.0), (35.0, 33.0), (28.0, 18.0)]
E, RHO, G = 5e9, 2700.0, 9.81


def scene(length, height, slope, friction, joint, integrator, step, penalty_factor=None):
    a = math.radians(slope)
    along, up = (math.cos(a), -math.sin(a)), (math.sin(a), math.cos(a))
    at = lambda s, h: (s * along[0] + h * up[0], s * along[1] + h * up[1])
    rear = 0.2 * length
    accel = G * (math.sin(a) - math.cos(a) * math.tan(math.radians(friction)))
    plane = rear + length + 0.5 * max(accel, 1.0) * 1.5 ** 2 + 0.2 * length
    cuts = [0.0] if joint is None else [0.0] + [0.37 * joint + j * joint for j in range(int(plane / joint) + 1)]
    if joint is None:
        cuts.append(plane)
    pt = lambda p: "[%r, %r]" % p
    lines = ["gravity: [0, -9.81]",
             "time: {duration: 1.5, step: %r, integrator: %s}" % (step, integrator),
             "materials:", "  rock: {density: %r, young_modulus: %r, poisson_ratio: 0.25}" % (RHO, E),
             "interfaces:", "  face: {friction_angle: %r}" % friction, "blocks:"]
    for j in range(len(cuts) - 1):
        s0, s1 = cuts[j], cuts[j + 1]
        corners = [at(s0, 0), at(s0, -0.2 * length), at(s1, -0.2 * length), at(s1, 0)]
        lines.append("  - {name: base_%d, group: base, material: rock, fixed: true, polygon: [%s]}"
                     % (j, ", ".join(pt(c) for c in corners)))
    slider = [at(rear, 0), at(rear + length, 0), at(rear + length, height), at(rear, height)]
    lines.append("  - {name: slider, material: rock, polygon: [%s]}" % ", ".join(pt(c) for c in slider))
    lines += ["default_interface: face", "measure:",
              "  - {name: centre, at: %s}" % pt(at(rear + 0.5 * length, 0.5 * height)),
              "output: {interval: %r}" % step]
    if penalty_factor is not None:
        lines.append("control: {penalty_factor: %r}" % penalty_factor)
    return "\n".join(lines) + "\n", accel, along


def worst_error(out, accel, along):
    worst = 0.0
    with open(os.path.join(out, "history.csv")) as f:
        for row in csv.DictReader(f):
            t = float(row["time"])
            exact = 0.5 * accel * t * t
            if exact < 0.01:
                continue
            moved = float(row["ux"]) * along[0] + float(row["uy"]) * along[1]
            worst = max(worst, abs(moved - exact) / exact)
    return worst


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--ddafit", default="build/apps/ddafit/ddafit")
    parser.add_argument("--integrator", default="implicit", choices=["implicit", "substep"])
    parser.add_argument("--penalty-factor", type=float, default=None,
                        help="control.penalty_factor (p / E); the default penalty if not given")
    parser.add_argument("--shares", type=float, nargs="+", default=[0.005, 0.007, 0.01, 0.05, 0.2, 0.7])
    args = parser.parse_args()
    c = math.sqrt(E / RHO)
    with tempfile.TemporaryDirectory() as tmp:
        for share in args.shares:
            worst, worst_case, failed = 0.0, "", 0
            for length, height in SLIDERS:
                step = share * math.sqrt(length * height) / c
                for slope, friction in FACES:
                    for joint in (None, length / 3.0):
                        text, accel, along = scene(length, height, slope, friction, joint, args.integrator, step,
                                                   args.penalty_factor)
                        path, out = os.path.join(tmp, "scene.yaml"), os.path.join(tmp, "out")
                        with open(path, "w") as f:
                            f.write(text)
                        subprocess.run([args.ddafit, "simulate", path, "--out", out, "--quiet"],
                                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
                        status = json.load(open(os.path.join(out, "summary.json")))["status"]
                        case = "%g x %g m, %g/%g deg, %s" % (length, height, slope, friction,
                                                            "one block" if joint is None else "jointed")
                        if status != "completed":
                            failed += 1
                            print("%g L/c  %s: %s" % (share, case, status))
                            continue
                        error = worst_error(out, accel, along)
                        print("%g L/c  %s: %.3g off seed Eq. 4" % (share, case, error))
                        if error > worst:
                            worst, worst_case = error, case
            print("== %g L/c: worst %.3g (%s), %d of 24 failed" % (share, worst, worst_case, failed))


if __name__ == "__main__":
    main()
