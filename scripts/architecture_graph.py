#!/usr/bin/env python3
"""Draws docs/architecture.svg from the code: one node per source folder, an arrow from a
folder to each folder whose headers it includes (the number of include lines on the arrow),
boxed by the CMake library the folder builds. The files at forward/'s top are split in three
by their place: simulate() above both solvers, the run record between the solvers and the
contact code, and the plain data (scene, block system, geometry) at the bottom. A node above
includes only nodes below: an arrow pointing up would be a layer reaching into the one
above it.

    python3 scripts/architecture_graph.py     # needs graphviz's `dot` (scripts/install-deps.sh)
"""
import collections, os, re, subprocess, sys

ROOT = os.path.normpath(os.path.join(os.path.dirname(__file__), ".."))
FOLDERS = ["apps/ddafit", "batch", "inverse", "verify", "forward/io", "forward/analysis", "forward",
           "forward/step", "forward/substep", "forward/common", "forward/contact", "forward/mesh"]
# Files of forward/'s top level that are not plain data: (node, file stems).
SPLIT = [("forward: simulate()", ("forward/simulation",)), ("forward: run record", ("forward/run_record",))]
DATA = "forward: scene, blocks, geometry"
LIBRARY = {"apps/ddafit": "ddafit (the command line)", "batch": "ddafit_batch", "inverse": "ddafit_inverse",
           "verify": "ddafit_verify", "forward/io": "ddafit_io", "forward/mesh": "ddafit_mesh"}
INCLUDE = re.compile(r'^#include "([^"]+)"', re.M)


def node_of(path):
    """The node of `path` (a repository path): its deepest listed folder, or a SPLIT part."""
    for node, stems in SPLIT:
        if os.path.splitext(path)[0] in stems:
            return node
    best = None
    for f in FOLDERS:
        if path.startswith(f + "/") and "/" not in path[len(f) + 1:] and (best is None or len(f) > len(best)):
            best = f
    return DATA if best == "forward" else best


edges = collections.Counter()
for folder in FOLDERS:
    for name in os.listdir(os.path.join(ROOT, folder)):
        if not name.endswith((".cpp", ".hpp")):
            continue
        with open(os.path.join(ROOT, folder, name), encoding="utf-8") as f:
            here = node_of(os.path.join(folder, name))
            for target in INCLUDE.findall(f.read()):
                to = node_of(target)
                if to and to != here:
                    edges[(here, to)] += 1

lines = ['digraph ddafit {', '  rankdir = TB; nodesep = 0.35; ranksep = 0.45;',
         '  node [shape = box, style = "rounded,filled", fillcolor = "#f4f4f4", fontname = "Helvetica", fontsize = 11];',
         '  edge [color = "#555555", fontname = "Helvetica", fontsize = 9];']
forward_lib = [n for n, _ in SPLIT] + [f for f in FOLDERS if f not in LIBRARY and f != "forward"] + [DATA]
for k, (title, members) in enumerate([(LIBRARY[f], [f]) for f in LIBRARY] + [("ddafit_forward", forward_lib)]):
    lines.append(f'  subgraph cluster_{k} {{ label = "{title}"; fontname = "Helvetica"; fontsize = 10; color = "#999999";')
    lines += [f'    "{m}";' for m in members]
    lines.append("  }")
for (a, b), n in sorted(edges.items()):
    lines.append(f'  "{a}" -> "{b}" [label = "{n}"];')
lines.append("}")
out = os.path.join(ROOT, "docs", "architecture.svg")
subprocess.run(["dot", "-Tsvg", "-o", out], input="\n".join(lines).encode(), check=True)
print(f"wrote {os.path.relpath(out, ROOT)}: {len(FOLDERS)} folders, {len(edges)} arrows")
