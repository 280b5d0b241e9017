#!/usr/bin/env python3
"""Writes the synthetic ground motion of docs/earthquakes.md, as CSV and as PEER .AT2.

A 1.5 Hz sine under a sin^2 envelope, peak 0.35 g, over 8 s, sampled every 0.01 s: a
short strong-motion pulse train, not a real earthquake. Run from this folder:
    python3 make_record.py
"""
import math

G = 9.80665  # m/s^2 per g
STEP, DURATION, PEAK, FREQUENCY = 0.01, 8.0, 0.35, 1.5
n = int(round(DURATION / STEP)) + 1
accel = [PEAK * math.sin(math.pi * k / (n - 1)) ** 2 * math.sin(2 * math.pi * FREQUENCY * k * STEP) for k in range(n)]

with open("synthetic.csv", "w") as out:
    out.write("# synthetic record for docs/earthquakes.md (make_record.py): ground acceleration, m/s^2\n")
    out.write("time,ax,ay\n")
    for k, a in enumerate(accel):
        out.write(f"{k * STEP:.2f},{a * G:.6f},0\n")

with open("synthetic.AT2", "w") as out:
    out.write("PEER NGA STRONG MOTION DATABASE RECORD\n")
    out.write("synthetic 1.5 Hz pulse train, peak 0.35 g (ddafit cases/earthquake/make_record.py)\n")
    out.write("ACCELERATION TIME SERIES IN UNITS OF G\n")
    out.write(f"NPTS= {n:6d}, DT= {STEP:.4f} SEC\n")
    for k in range(0, n, 5):
        out.write("".join(f"{a:15.7E}" for a in accel[k:k + 5]) + "\n")
