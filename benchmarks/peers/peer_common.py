"""Shared by the SciPy peers of the work-precision study: timing by the same rule as ltp's
(median of repeated runs, CPU and wall) and writing a markdown table to OUT_DIR and stderr."""
import csv
import os
import sys
import time

import numpy as np


def timed(fn, repeats=5, budget=0.25, min_repeats=1):
    """Median CPU (time.process_time) and wall time of up to `repeats` runs of fn(); stops once
    `budget` seconds of wall time are spent and at least `min_repeats` runs are done, or after
    3 × budget in any case. Returns (last result, cpu_s, wall_s, runs)."""
    cpu, wall, out = [], [], None
    while len(cpu) < repeats:
        c0, w0 = time.process_time(), time.perf_counter()
        out = fn()
        cpu.append(time.process_time() - c0)
        wall.append(time.perf_counter() - w0)
        if sum(wall) > budget and len(cpu) >= min_repeats:
            break
        if sum(wall) > 3 * budget:
            break
    return out, float(np.median(cpu)), float(np.median(wall)), len(cpu)


def write_markdown(out_dir, name, lines):
    """OUT_DIR/name and stderr."""
    with open(os.path.join(out_dir, name), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines), file=sys.stderr)


def study_rows(out_dir, panel):
    """ltp's successful rows of one panel of OUT_DIR/work_precision.csv (csv.DictReader rows;
    empty when the study has not written it)."""
    path = os.path.join(out_dir, "work_precision.csv")
    if not os.path.exists(path):
        return []
    with open(path) as f:
        return [r for r in csv.DictReader(f) if r["panel"] == panel and r["ok"] == "1"]
