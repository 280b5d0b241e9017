#!/usr/bin/env python3
"""Stacks and slender blocks on steep faces at short time steps: the sweeps behind docs/theory.md,
Known limits (o). Two classes, from rest, 1 s each, E = 5 GPa, rho = 2700 kg/m^3, nu = 0.25:

  plates  a square block of side 2 or 20 m on a free plate three times its length and 0.02, 0.2 or 1
          of it thick, on a fixed face of 25-40 deg; the face holds the plate (tan(phi) = tan(alpha) /
          0.88 or 0.97) or lets it slide (/ 1.15), the joint between block and plate as strong or
          stronger (/ 0.88, / 0.6); steps given as shares of the block's L / c (L its side).
  slabs   a lone slab 6 or 60 m long, L / H of 1-150, on a fixed face, held (/ 0.88) or sliding
          (/ 1.15); steps in seconds.

A run passes if it completes and, held, its first measure point moves less than 1e-4 of the block's
length, or, sliding, it is within 1 % of seed Eq. 4 with the face's friction. Prints each failing
run and the count per class. Runs two at a time (`--jobs`); not a timing.

    python3 scripts/short_step_sweep.py --ddafit build/apps/ddafit/ddafit --class plates \
        --integrators implicit substep --shares 0.05 0.2
    python3 scripts/short_step_sweep.py --ddafit build/apps/ddafit/ddafit --class slabs --lengths 60 \
        --steps 1e-4 5e-4 1e-3 5e-3 --slopes 20 35
"""
import argparse
import csv
import itertools
import math
import os
import subprocess
import tempfile
from concurrent.futures import ThreadPoolExecutor

E, RHO, G = 5e9, 2700.0, 9.81


def frame(slope):
    a = math.radians(slope)
    along, up = (math.cos(a), -math.sin(a)), (math.sin(a), math.cos(a))
    return lambda s, h: (s * along[0] + h * up[0], s * along[1] + h * up[1])


def poly(points):
    return "[" + ", ".join("[%.12g, %.12g]" % p for p in points) + "]"


def box(at, s, h, length, height):
    return [at(s, h), at(s + length, h), at(s + length, h + height), at(s, h + height)]


def friction(slope, ratio):
    return math.degrees(math.atan(math.tan(math.radians(slope)) / ratio))


def header(step, integrator):
    return (f"gravity: [0, -9.81]\ntime: {{duration: 1.0, step: {step:.12g}, integrator: {integrator}}}\n"
            f"materials:\n  rock: {{density: {RHO}, young_modulus: {E}, poisson_ratio: 0.25}}\n"
            "output: {interval: 0.05}\n")


def plate_scene(side, thickness, slope, face_ratio, joint_ratio, share, integrator):
    at = frame(slope)
    t = thickness * side
    step = share * side / math.sqrt(E / RHO)
    return header(step, integrator) + f"""interfaces:
  face: {{friction_angle: {friction(slope, face_ratio):.12g}}}
  joint: {{friction_angle: {friction(slope, joint_ratio):.12g}}}
default_interface: joint
contacts:
  - {{between: [base, plate], interface: face}}
blocks:
  - {{name: base, material: rock, fixed: true, polygon: {poly([at(0, 0), at(0, -side), at(6 * side, -side), at(6 * side, 0)])}}}
  - {{name: plate, material: rock, polygon: {poly(box(at, 0.5 * side, 0, 3 * side, t))}}}
  - {{name: block, material: rock, polygon: {poly(box(at, side, t, side, side))}}}
measure:
  - {{name: centre, at: [{at(1.5 * side, t + 0.5 * side)[0]:.12g}, {at(1.5 * side, t + 0.5 * side)[1]:.12g}]}}
"""


def slab_scene(length, aspect, slope, face_ratio, step, integrator):
    at = frame(slope)
    h = length / aspect
    c = at(0.7 * length, 0.5 * h)
    return header(step, integrator) + f"""interfaces:
  face: {{friction_angle: {friction(slope, face_ratio):.12g}}}
default_interface: face
blocks:
  - {{name: base, material: rock, fixed: true, polygon: {poly([at(0, 0), at(0, -length), at(3 * length, -length), at(3 * length, 0)])}}}
  - {{name: slab, material: rock, polygon: {poly(box(at, 0.2 * length, 0, length, h))}}}
measure:
  - {{name: centre, at: [{c[0]:.12g}, {c[1]:.12g}]}}
"""


def judge(ddafit, text, slope, face_ratio, length, folder):
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, "scene.yaml"), "w") as f:
        f.write(text)
    run = subprocess.run([ddafit, "simulate", os.path.join(folder, "scene.yaml"), "--out", folder, "--quiet",
                          "--threads", "1"], capture_output=True, text=True)
    if run.returncode != 0:
        return False, "exit %d: %s" % (run.returncode, run.stderr.strip()[:160])
    with open(os.path.join(folder, "history.csv")) as f:
        last = list(csv.DictReader(f))[-1]
    t, u = float(last["time"]), math.hypot(float(last["ux"]), float(last["uy"]))
    a = math.radians(slope)
    expected = max(0.0, 0.5 * G * (math.sin(a) - math.cos(a) * math.tan(a) / face_ratio) * t * t)
    if expected > 0.0:
        error = abs(u - expected) / expected
        return error < 0.01, "%.3g of seed Eq. 4" % error
    return u / length < 1e-4, "moved %.3g of its length" % (u / length)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--ddafit", default="build/apps/ddafit/ddafit")
    p.add_argument("--class", dest="kind", choices=["plates", "slabs"], default="plates")
    p.add_argument("--integrators", nargs="+", default=["implicit", "substep"])
    p.add_argument("--slopes", nargs="+", type=float, default=None)
    p.add_argument("--shares", nargs="+", type=float, default=[0.05, 0.2], help="plates: step / (L/c)")
    p.add_argument("--steps", nargs="+", type=float, default=[1e-4, 5e-4, 1e-3, 5e-3], help="slabs: step, s")
    p.add_argument("--lengths", nargs="+", type=float, default=[6.0, 60.0], help="slabs: length, m")
    p.add_argument("--aspects", nargs="+", type=float, default=[150, 40, 15, 5, 1], help="slabs: L / H")
    p.add_argument("--jobs", type=int, default=2)
    args = p.parse_args()
    work = tempfile.mkdtemp(prefix="short_steps_")
    cases = []
    if args.kind == "plates":
        for integ, slope, fr, jr, side, th, share in itertools.product(
                args.integrators, args.slopes or [25, 30, 35, 40], [0.88, 0.97, 1.15], [0.88, 0.6], [2.0, 20.0],
                [0.02, 0.2, 1.0], args.shares):
            label = f"{integ} plate: {side} m block, plate {th} of it, {slope} deg, face {fr}, joint {jr}, {share} L/c"
            cases.append((integ, label, plate_scene(side, th, slope, fr, jr, share, integ), slope, fr, side))
    else:
        for integ, length, aspect, slope, fr, step in itertools.product(
                args.integrators, args.lengths, args.aspects, args.slopes or [20, 35], [1.15, 0.88], args.steps):
            label = f"{integ} slab: {length} m, L/H {aspect}, {slope} deg, face {fr}, step {step} s"
            cases.append((integ, label, slab_scene(length, aspect, slope, fr, step, integ), slope, fr, length))

    def one(k):
        integ, label, text, slope, fr, length = cases[k]
        return (integ, label) + judge(args.ddafit, text, slope, fr, length, os.path.join(work, str(k)))

    with ThreadPoolExecutor(args.jobs) as pool:
        results = list(pool.map(one, range(len(cases))))
    for integ in args.integrators:
        mine = [r for r in results if r[0] == integ]
        for _, label, ok, what in mine:
            if not ok:
                print("off:", label, "-", what)
        print(f"{integ}: {sum(not r[2] for r in mine)} of {len(mine)} runs off their bound")


if __name__ == "__main__":
    main()
