#!/usr/bin/env python3
"""Writes cases/walls/brick_wall_1621.yaml: a running-bond wall of 36 courses x 45 bricks
(2 m x 1 m) on a fixed floor, 1620 bricks + floor = 1621 blocks. Run from the repository root."""
COURSES, PER_COURSE, LENGTH, HEIGHT = 36, 45, 2.0, 1.0
lines = [
    "# A running-bond brick wall, 36 courses x 45 bricks of 2 m x 1 m on a fixed floor: 1621 blocks.",
    "# Must stand still (the top moves < 1 cm in 1 s). The many-contact benchmark of the two",
    "# solvers (docs/performance.md); written by scripts/make_brick_wall.py.",
    "gravity: [0, -9.81]",
    "time: {duration: 1, step: 0.005}",
    "materials:",
    "  brick: {density: 2500, young_modulus: 5.0e9, poisson_ratio: 0.25}",
    "interfaces:",
    "  joint: {friction_angle: 35}",
    "blocks:",
    f"  - {{name: floor, material: brick, fixed: true, polygon: [[-2, -1], [{PER_COURSE * LENGTH + 2}, -1], "
    f"[{PER_COURSE * LENGTH + 2}, 0], [-2, 0]]}}",
]
for c in range(COURSES):
    shift = 0.5 * LENGTH if c % 2 else 0.0
    y0, y1 = c * HEIGHT, (c + 1) * HEIGHT
    for k in range(PER_COURSE):
        x0 = shift + k * LENGTH
        x1 = x0 + LENGTH
        lines.append(f"  - {{name: brick_{c}_{k}, material: brick, polygon: [[{x0:g}, {y0:g}], [{x1:g}, {y0:g}], "
                     f"[{x1:g}, {y1:g}], [{x0:g}, {y1:g}]]}}")
top_x = (0.5 * LENGTH if (COURSES - 1) % 2 else 0.0) + (PER_COURSE // 2) * LENGTH + 0.5 * LENGTH
lines += [
    "default_interface: joint",
    "measure:",
    f"  - {{name: top, at: [{top_x:g}, {COURSES * HEIGHT - 0.5 * HEIGHT:g}]}}",
    f"  - {{name: middle, at: [{top_x:g}, {COURSES * HEIGHT / 2 - 0.5 * HEIGHT:g}]}}",
    "output: {interval: 0.05}",
    "rest_speed: 0.01",
]
with open("cases/walls/brick_wall_1621.yaml", "w") as out:
    out.write("\n".join(lines) + "\n")
