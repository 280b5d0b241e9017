#!/usr/bin/env python3
"""Collects the runs of run_peer.sh and prints a markdown table.

usage: peer_report.py RUN_ROOT [STAND_MM]

RUN_ROOT holds one folder per run, each with a file `meta` (key=value lines written by
run_peer.sh: program, wall, blocks_asked, solver, threads, repeat, rc, folder) and the
program's own outputs:
  ntdda : output/pushblock.html ("Total: X", "Total number of open-close iterations was N"),
          output/pushblock_data.m (step, springstiff, delta_t, OC_count, KE, Istress, OC_cuts),
          output/pushblock_meas.m (step, t, dt, x, y, distance from start, vx, vy, |v|),
          stderr.txt ("nBlocks=N after ddacut", "pipeline_test: PASSED"), time.txt (/usr/bin/time %e)
  ddafit: summary.json (status, run.*, profile_seconds.settle, points."1".*), history.csv,
          import.txt ("wrote ...: N blocks"), time.txt
Only the standard library; reads small files only.
"""
import json
import math
import os
import re
import statistics
import sys


def read(path):
    try:
        with open(path, "r", errors="replace") as f:
            return f.read()
    except OSError:
        return None


def meta_of(folder):
    m = {}
    text = read(os.path.join(folder, "meta"))
    if text is None:
        return None
    for line in text.splitlines():
        if "=" in line:
            k, v = line.split("=", 1)
            m[k.strip()] = v.strip()
    return m


def time_of(folder):
    """Wall seconds from /usr/bin/time -f %e -o time.txt (last numeric line)."""
    text = read(os.path.join(folder, "time.txt"))
    if not text:
        return None
    for line in reversed(text.strip().splitlines()):
        try:
            return float(line.strip())
        except ValueError:
            continue
    return None


def matlab_rows(text, start_marker, ncols):
    """Numeric rows after the line containing start_marker, up to ']'."""
    rows = []
    if text is None:
        return rows
    i = text.find(start_marker)
    if i < 0:
        return rows
    for line in text[i + len(start_marker):].splitlines():
        s = line.replace("\x00", "").strip()
        if not s:
            continue
        if s.startswith("]"):
            break
        parts = s.split()
        if len(parts) != ncols:
            continue
        try:
            rows.append([float(p) for p in parts])
        except ValueError:
            continue
    return rows


def ntdda_result(folder, m):
    r = {"program": "ntdda", "solver": "ntdda (DDA, LU/penalty, OC limit 8)", "threads": "1"}
    stderr = read(os.path.join(folder, "stderr.txt")) or ""
    html = read(os.path.join(folder, "output", "pushblock.html"))
    data = read(os.path.join(folder, "output", "pushblock_data.m"))
    meas = read(os.path.join(folder, "output", "pushblock_meas.m"))
    mb = re.search(r"nBlocks=(\d+) after ddacut", stderr)
    r["blocks"] = int(mb.group(1)) if mb else None
    r["time_wall"] = time_of(folder)
    rc = int(m.get("rc", "-1"))
    passed = "pipeline_test: PASSED" in stderr
    r["status"] = "completed" if (rc == 0 and passed) else ("TIMEOUT" if rc == 124 else "FAILED rc=%d" % rc)
    r["run_seconds"] = None
    r["oc_total"] = None
    if html:
        mt = re.search(r"<li>Total:\s*([0-9.eE+-]+)</li>", html)
        if mt:
            r["run_seconds"] = float(mt.group(1))
        mo = re.search(r"Total number of open-close iterations was\s+(-?\d+)\s+over\s+(\d+)", html)
        if mo:
            r["oc_total"] = int(mo.group(1))
        checks = {
            "Auto time step: 0": "Autotimestep not off",
            "Auto penalty: 0": "Autopenalty not off",
            "Max time step: 0.001000": "Maxtimestep not 0.001",
        }
        r["warnings"] = [w for k, w in checks.items() if k not in html]
        mp = re.search(r"Penalty value:\s*([0-9.eE+-]+)", html)
        r["penalty"] = float(mp.group(1)) if mp else None
    else:
        r["warnings"] = ["no output/pushblock.html"]
    rows = matlab_rows(data, "runtime = [", 7)
    steps = [row for row in rows if row[0] >= 1]
    r["steps"] = len(steps) if steps else None
    r["oc_data_sum"] = int(sum(row[3] for row in steps)) if steps else None
    r["redos"] = int(sum(row[6] for row in steps)) if steps else None
    r["simulated"] = sum(row[2] for row in steps) if steps else None
    mrows = matlab_rows(meas, "measpoint1=[", 9)
    if mrows:
        r["moved_end_mm"] = 1000.0 * mrows[-1][5]
        r["moved_max_mm"] = 1000.0 * max(row[5] for row in mrows)
        r["moved_end_xy_mm"] = None
        if r["simulated"] is None:
            r["simulated"] = mrows[-1][1]
    else:
        r["moved_end_mm"] = r["moved_max_mm"] = None
    r["settle"] = None
    return r


def ddafit_result(folder, m):
    r = {"program": "ddafit", "solver": m.get("solver", "?"), "threads": m.get("threads", "?")}
    r["time_wall"] = time_of(folder)
    imp = read(m["import_log"]) if m.get("import_log") else None
    mb = re.search(r"wrote .*?: (\d+) blocks", imp or "")
    r["blocks"] = int(mb.group(1)) if mb else None
    text = read(os.path.join(folder, "summary.json"))
    rc = int(m.get("rc", "-1"))
    r["warnings"] = []
    s = None
    if text:
        try:
            s = json.loads(text)
        except ValueError:
            s = None
    if s is None:
        r["status"] = "TIMEOUT" if rc == 124 else "FAILED rc=%d (no summary.json)" % rc
        for k in ("run_seconds", "steps", "simulated", "oc_total", "settle", "moved_end_mm", "moved_max_mm"):
            r[k] = None
        return r
    run = s.get("run", {})
    r["status"] = s.get("status", "?") + ("" if rc == 0 else " rc=%d" % rc)
    if s.get("message"):
        r["warnings"].append(s["message"])
    r["warnings"] += s.get("warnings", [])
    r["run_seconds"] = run.get("wall_seconds")
    r["steps"] = run.get("steps")
    r["simulated"] = run.get("simulated_time")
    solver = s.get("solver", {})
    integ = solver.get("integrator")
    if integ and integ != r["solver"]:
        r["warnings"].append("solver.integrator is %s, asked %s" % (integ, r["solver"]))
    r["oc_total"] = run.get("open_close_iterations") if integ == "implicit" else None
    r["step_cuts"] = run.get("step_cuts")
    r["penalty_raises"] = run.get("penalty_raises")
    r["settle"] = s.get("profile_seconds", {}).get("settle")
    p = s.get("points", {}).get("1", {})
    r["moved_max_mm"] = 1000.0 * p["max_total_displacement"] if "max_total_displacement" in p else None
    # displacement from the point's given position (includes the settling at t = 0)
    r["moved_end_mm"] = None
    hist = read(os.path.join(folder, "history.csv"))
    at = m.get("measure_at")
    if hist and at:
        ax, ay = (float(v) for v in at.split(","))
        lines = [l.split(",") for l in hist.strip().splitlines()[1:] if l.strip()]
        lines = [l for l in lines if len(l) >= 6 and l[1] == "1"]
        if lines:
            x, y = float(lines[-1][2]), float(lines[-1][3])
            r["moved_end_mm"] = 1000.0 * math.hypot(x - ax, y - ay)
    return r


def fmt(x, nd=2):
    if x is None:
        return "–"
    if isinstance(x, int):
        return str(x)
    if abs(x) >= 100:
        return "%.0f" % x
    if abs(x) >= 10:
        return "%.1f" % x
    return ("%." + str(nd) + "f") % x


def main():
    root = sys.argv[1]
    stand_mm = float(sys.argv[2]) if len(sys.argv) > 2 else 10.0
    runs = []
    for name in sorted(os.listdir(root)):
        folder = os.path.join(root, name)
        if not os.path.isdir(folder):
            continue
        m = meta_of(folder)
        if not m or "program" not in m:
            continue
        r = ntdda_result(folder, m) if m["program"] == "ntdda" else ddafit_result(folder, m)
        r["wall"] = m.get("wall", "?")
        r["blocks_asked"] = int(m.get("blocks_asked", "0"))
        r["repeat"] = m.get("repeat", "1")
        r["folder"] = folder
        runs.append(r)

    # group repeats: median of the timed seconds
    groups = {}
    for r in runs:
        groups.setdefault((r["blocks_asked"], r["program"] != "ntdda", r["solver"], r["threads"]), []).append(r)

    def med(rs, key):
        v = [r[key] for r in rs if r.get(key) is not None]
        return statistics.median(v) if v else None

    ntdda_rate = {}
    for key, rs in groups.items():
        if rs[0]["program"] == "ntdda":
            sec, sim = med(rs, "run_seconds"), med(rs, "simulated")
            if sec and sim:
                ntdda_rate[key[0]] = sec / sim

    print("| wall | blocks | program / solver | threads | steps | simulated (s) | run time (s) | of which settle (s) "
          "| wall, /usr/bin/time (s) | s per simulated s | open-close passes | ratio to ntdda | point moved, end / max (mm) "
          "| stands (< %g mm) | status |" % stand_mm)
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    notes = []
    for key in sorted(groups):
        rs = groups[key]
        r0 = rs[0]
        sec, sim = med(rs, "run_seconds"), med(rs, "simulated")
        rate = sec / sim if (sec is not None and sim) else None
        ref = ntdda_rate.get(key[0])
        ratio = rate / ref if (rate is not None and ref) else None
        if r0["program"] == "ntdda":
            label = "ntdda"
            steps = fmt(r0.get("steps"))
            if r0.get("redos"):
                steps += " (%d Δt cuts)" % r0["redos"]
            oc = fmt(r0.get("oc_total"))
            if r0.get("oc_data_sum") is not None:
                oc += " (data.m Σ %d)" % r0["oc_data_sum"]
        else:
            label = "ddafit %s" % r0["solver"]
            steps = fmt(r0.get("steps"))
            oc = fmt(r0.get("oc_total")) if r0["solver"] == "implicit" else "n/a"
            if r0.get("step_cuts"):
                steps += " (%d cuts)" % r0["step_cuts"]
        moved_end = med(rs, "moved_end_mm")
        moved_max = med(rs, "moved_max_mm")
        worst = max([v for v in (moved_end, moved_max) if v is not None], default=None)
        stands = "–" if worst is None else ("yes" if worst < stand_mm else "**NO**")
        statuses = sorted(set(r["status"] for r in rs))
        rep = "" if len(rs) == 1 else " (median of %d: %s)" % (
            len(rs), ", ".join(fmt(r.get("run_seconds")) for r in rs))
        print("| %s | %s | %s | %s | %s | %s | %s%s | %s | %s | %s | %s | %s | %s / %s | %s | %s |" % (
            r0["wall"], fmt(r0.get("blocks")), label, r0["threads"], steps, fmt(sim, 3), fmt(sec), rep,
            fmt(med(rs, "settle")), fmt(med(rs, "time_wall")), fmt(rate, 1), oc,
            fmt(ratio, 3), fmt(moved_end, 3), fmt(moved_max, 3), stands, "; ".join(statuses)))
        for r in rs:
            if r.get("blocks") is not None and r["blocks"] != r["blocks_asked"]:
                notes.append("%s: %s blocks, expected %d" % (r["folder"], r["blocks"], r["blocks_asked"]))
            for w in r.get("warnings", []):
                notes.append("%s: %s" % (r["folder"], w))
            if r["program"] == "ntdda" and r.get("penalty") is not None and abs(r["penalty"] - 2.5e8) > 1.0:
                notes.append("%s: ntdda penalty %g kN/m, expected 2.5e8 (50 x 5e6)" % (r["folder"], r["penalty"]))
    print()
    print("- run time: ntdda = `Total:` of output/pushblock.html (clock(): CPU seconds of its analysis loop, "
          "single-threaded, so = wall on an idle machine; excludes reading and cutting); ddafit = summary.json "
          "`run.wall_seconds` (the whole run, including the t = 0 settling / quiet start shown in the next column).")
    print("- s per simulated s = run time / simulated time; ratio to ntdda = that rate / ntdda's rate on the same wall "
          "(below 1: faster than ntdda).")
    print("- open-close passes: ntdda = \"Total number of open-close iterations\" of pushblock.html (every solve, also "
          "those of redone steps); in brackets the sum of the per-step OC_count column of pushblock_data.m (final "
          "attempt of each step only; the difference is the passes of steps that hit the limit of 8 and were redone, "
          "which ntdda does with the same Δt when Autotimestep is off). ddafit implicit = summary.json `run.open_close_iterations` (incl. redone "
          "attempts); the substep solver has none.")
    print("- point moved: measured point 1 (top course, x = W/2 + 0.3, y = H - 0.5). ntdda: distance from its start "
          "(pushblock_meas.m column 6), at the end / largest over the steps. ddafit: end = |position in the last "
          "history.csv row - the point's `at`| (includes the t = 0 settling), max = summary.json "
          "`points.\"1\".max_total_displacement` (measured from after settling).")
    print("- elastic settlement of the top under its own weight (plane strain, 1-D column): rho g H^2 / (2 E/(1-nu^2)) "
          "= %.2f mm (H = 20 m) and %.2f mm (H = 40 m); a run started without settling (ntdda) may overshoot to ~2x." % (
              2650 * 9.81 * 20 ** 2 / (2 * 5e9 / (1 - 0.25 ** 2)) * 1000,
              2650 * 9.81 * 40 ** 2 / (2 * 5e9 / (1 - 0.25 ** 2)) * 1000))
    if notes:
        print()
        print("Notes and warnings:")
        for n in notes:
            print("- " + n)


if __name__ == "__main__":
    main()
