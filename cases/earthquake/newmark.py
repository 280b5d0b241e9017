#!/usr/bin/env python3
"""Newmark's rigid sliding block on a plane of dip ALPHA (deg, dipping towards +x) and
friction angle PHI (deg) under a horizontal ground record (CSV time,ax,ay in m/s^2): the
displacement relative to the ground, down the plane, at the end of the record and after.
Standard library only; a check for docs/earthquakes.md, independent of ddafit.
    python3 newmark.py synthetic.csv 20 30 [SCALE]
"""
import csv, math, sys

path, alpha, phi = sys.argv[1], math.radians(float(sys.argv[2])), math.radians(float(sys.argv[3]))
scale = float(sys.argv[4]) if len(sys.argv) > 4 else 1.0
times, ax = [], []
with open(path) as f:
    for row in csv.reader(line for line in f if not line.startswith("#")):
        if row[0] == "time":
            continue
        times.append(float(row[0]))
        ax.append(scale * float(row[1]))

def ground(t):  # linear between samples, zero outside the record
    if t <= times[0] or t >= times[-1]:
        return 0.0
    k = int((t - times[0]) / (times[1] - times[0]))
    s = (t - times[k]) / (times[k + 1] - times[k])
    return ax[k] + s * (ax[k + 1] - ax[k])

g, mu, dt = 9.81, math.tan(phi), 1e-4
v = u = t = 0.0
while t < times[-1] + 2.0:
    e = -ground(t + 0.5 * dt)  # a unit mass feels (-a_x, -g) in the ground's frame
    drive = e * math.cos(alpha) + g * math.sin(alpha)
    normal = g * math.cos(alpha) - e * math.sin(alpha)
    if v == 0.0:
        acc = drive - math.copysign(mu * normal, drive) if abs(drive) > mu * normal else 0.0
    else:
        acc = drive - math.copysign(mu * normal, v)
    nv = v + acc * dt
    if v != 0.0 and nv * v < 0.0:
        u += 0.5 * v * (-v / acc)
        v = 0.0
    else:
        u += 0.5 * (v + nv) * dt
        v = nv
    t += dt
print(f"yield acceleration g tan(phi - alpha) = {g * math.tan(phi - alpha):.3f} m/s^2; "
      f"Newmark displacement down the plane = {u:.4f} m")
