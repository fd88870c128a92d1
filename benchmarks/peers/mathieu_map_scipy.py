#!/usr/bin/env python3
"""Peer for benchmarks/chart_benchmark: the Mathieu stability map written the usual way in
Python -- the monodromy matrix of y'' + c y' + (a - 2q cos 2t) y = 0 over one period (pi) with
SciPy's solve_ivp (DOP853, rtol 1e-10, atol 1e-13, both fundamental solutions at once), then
numpy.linalg.eigvals -- over an evenly spread subset of the 401 x 401 grid
a in [-2, 10], q in [0, 8].

Two ways, as a numerical analyst would write them: `loop` (one solve_ivp per point) and
`vectorised` (the whole 401 x 401 map, ten q-rows -- 4010 points -- per solve_ivp: the state
holds both fundamental solutions of every point of the block, the right-hand side is numpy
arithmetic on whole arrays, the step control follows the block's hardest point, and the
eigenvalues of all 2 x 2 monodromies come from one call; per_point_s is over the whole map, the
results are those of the subset, for the comparison).

Usage: mathieu_map_scipy.py POINTS [C] [loop|vectorised]   -> one JSON object on stdout:
  {"points": n, "seconds": wall, "per_point_s": wall/n, "cpu_per_point_s": cpu/n,
   "results": [[a, q, max_log_abs_rho], ...]}
Needs Debian's python3-numpy and python3-scipy (exit code 3 with a message if absent).
"""
import json
import math
import sys
import time

try:
    import numpy as np
    from scipy.integrate import solve_ivp
except ImportError as e:  # the benchmark skips the peer with this message
    print(f"peer skipped: {e} (apt-get install python3-numpy python3-scipy)", file=sys.stderr)
    sys.exit(3)


def max_log_multiplier(a, q, c):
    def rhs(t, y):
        k = a - 2.0 * q * math.cos(2.0 * t)
        # y = [x1, v1, x2, v2]: two fundamental solutions
        return [y[1], -c * y[1] - k * y[0], y[3], -c * y[3] - k * y[2]]

    sol = solve_ivp(rhs, (0.0, math.pi), [1.0, 0.0, 0.0, 1.0], method="DOP853",
                    rtol=1e-10, atol=1e-13)
    y = sol.y[:, -1]
    phi = np.array([[y[0], y[2]], [y[1], y[3]]])
    return float(np.max(np.log(np.abs(np.linalg.eigvals(phi)))))


def max_log_multipliers_vectorised(a, q, c):
    p = len(a)

    def rhs(t, y):
        x1, v1, x2, v2 = y.reshape(4, p)
        k = a - 2.0 * q * math.cos(2.0 * t)
        return np.concatenate([v1, -c * v1 - k * x1, v2, -c * v2 - k * x2])

    y0 = np.concatenate([np.ones(p), np.zeros(p), np.zeros(p), np.ones(p)])
    sol = solve_ivp(rhs, (0.0, math.pi), y0, method="DOP853", rtol=1e-10, atol=1e-13,
                    t_eval=[math.pi])
    x1, v1, x2, v2 = sol.y[:, -1].reshape(4, p)
    phi = np.stack([np.stack([x1, x2], axis=-1), np.stack([v1, v2], axis=-1)], axis=-2)
    return np.max(np.log(np.abs(np.linalg.eigvals(phi))), axis=-1)


def main():
    count = int(sys.argv[1]) if len(sys.argv) > 1 else 400
    c = float(sys.argv[2]) if len(sys.argv) > 2 else 0.02
    mode = sys.argv[3] if len(sys.argv) > 3 else "loop"
    if mode not in ("loop", "vectorised"):
        print(f"unknown mode '{mode}' (loop | vectorised)", file=sys.stderr)
        sys.exit(2)
    total = 401 * 401
    stride = max(1, total // count)
    indices = list(range(0, total, stride))[:count]
    a = [-2.0 + 0.03 * (index % 401) for index in indices]
    q = [0.02 * (index // 401) for index in indices]
    start, cpu_start = time.perf_counter(), time.process_time()
    if mode == "loop":
        results = [[ai, qi, max_log_multiplier(ai, qi, c)] for ai, qi in zip(a, q)]
        points = len(indices)
    else:
        grid_a = -2.0 + 0.03 * np.arange(401)
        values = np.empty(total)
        rows = 10
        for first in range(0, 401, rows):
            qs = 0.02 * np.arange(first, min(first + rows, 401))
            block_a = np.tile(grid_a, len(qs))
            block_q = np.repeat(qs, 401)
            values[first * 401:first * 401 + block_a.size] = max_log_multipliers_vectorised(
                block_a, block_q, c)
        results = [[ai, qi, float(values[index])] for ai, qi, index in zip(a, q, indices)]
        points = total
    wall, cpu = time.perf_counter() - start, time.process_time() - cpu_start
    print(json.dumps({"points": points, "seconds": wall, "per_point_s": wall / points,
                      "cpu_per_point_s": cpu / points, "results": results}))


if __name__ == "__main__":
    main()
