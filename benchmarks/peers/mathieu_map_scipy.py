#!/usr/bin/env python3
"""Peer for benchmarks/chart_benchmark: the Mathieu stability map written the usual way in
Python -- the monodromy matrix of y'' + c y' + (a - 2q cos 2t) y = 0 over one period (pi) with
SciPy's solve_ivp (DOP853, rtol 1e-10, atol 1e-13, both fundamental solutions at once), then
numpy.linalg.eigvals -- over an evenly spread subset of the 401 x 401 grid
a in [-2, 10], q in [0, 8].

Usage: mathieu_map_scipy.py POINTS [C]   -> one JSON object on stdout:
  {"points": n, "seconds": wall, "per_point_s": wall/n, "results": [[a, q, max_log_abs_rho], ...]}
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


def main():
    count = int(sys.argv[1]) if len(sys.argv) > 1 else 400
    c = float(sys.argv[2]) if len(sys.argv) > 2 else 0.02
    total = 401 * 401
    stride = max(1, total // count)
    indices = list(range(0, total, stride))[:count]
    start = time.perf_counter()
    results = []
    for index in indices:
        a = -2.0 + 0.03 * (index % 401)
        q = 0.02 * (index // 401)
        results.append([a, q, max_log_multiplier(a, q, c)])
    wall = time.perf_counter() - start
    print(json.dumps({"points": len(indices), "seconds": wall, "per_point_s": wall / len(indices),
                      "results": results}))


if __name__ == "__main__":
    main()
