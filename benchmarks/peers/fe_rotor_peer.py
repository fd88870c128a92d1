#!/usr/bin/env python3
"""Peer for benchmarks/model_size_benchmark: the finite-element rotor of tests/python/fe_rotor.py
(SI units, 8 (elements + 1) states), its largest Floquet exponent at tolerance 1e-10 either
  ltp    ltp.System.from_second_order + ltp.floquet (defaults: balanced states, the error
         estimate `auto` picks — Taylor series' order-p product here —, mode shapes), or
  scipy  what one writes without ltp: solve_ivp DOP853 (rtol 1e-10, atol 1e-13) of the n x n
         matrix ODE Phi' = A(t) Phi over one period, vectorised numpy right-hand side, then
         numpy.linalg.eigvals of the monodromy (no estimate, no mode shapes).
Each in its own process (importing ltp makes OpenBLAS single-threaded for the process; SciPy
keeps its threads).

Usage: fe_rotor_peer.py ELEMENTS ltp|scipy -> one JSON object on stdout:
  {"states": n, "wall_s": ..., "cpu_s": ..., "max_real": ..., "estimate": ... | null}
Exit 3 with a message when numpy/scipy (or the ltp module) is missing.
"""
import json
import os
import sys
import time

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, "..", "..", "tests", "python"))
try:
    import numpy as np
    from fe_rotor import fe_rotor
except ImportError as e:
    print(f"peer skipped: {e} (apt-get install python3-numpy python3-scipy)", file=sys.stderr)
    sys.exit(3)


def main():
    elements, which = int(sys.argv[1]), sys.argv[2]
    period, M, D, K = fe_rotor(elements)
    wall, cpu = time.perf_counter(), time.process_time()
    estimate = None
    if which == "ltp":
        try:
            import ltp
        except ImportError as e:
            print(f"peer skipped: {e} (PYTHONPATH=build/python)", file=sys.stderr)
            sys.exit(3)
        import warnings
        with warnings.catch_warnings():  # the long-work announcement is not the output
            warnings.simplefilter("ignore", UserWarning)
            r = ltp.floquet(ltp.System.from_second_order(period, M=M, K=K, D=D), tol=1e-10)
        n, max_real, estimate = r.states, r.max_real_exponent, r.error_estimate
    else:
        from scipy.integrate import solve_ivp
        q = M.shape[0]
        n = 2 * q
        minv = np.linalg.inv(M)
        a0 = np.zeros((n, n))
        a0[:q, q:] = np.eye(q)
        a0[q:, :q] = -minv @ K[1].real
        a0[q:, q:] = -minv @ D
        ac, as_ = np.zeros((n, n)), np.zeros((n, n))
        ac[q:, :q] = -minv @ (2 * K[2].real)
        as_[q:, :q] = -minv @ (-2 * K[2].imag)
        w = 2 * np.pi / period

        def rhs(t, y):
            return ((a0 + ac * np.cos(w * t) + as_ * np.sin(w * t)) @ y.reshape(n, n)).ravel()

        sol = solve_ivp(rhs, (0, period), np.eye(n).ravel(), method="DOP853", rtol=1e-10,
                        atol=1e-13)
        rho = np.linalg.eigvals(sol.y[:, -1].reshape(n, n))
        max_real = float(np.log(np.abs(rho)).max() / period)
    print(json.dumps({"states": n, "wall_s": time.perf_counter() - wall,
                      "cpu_s": time.process_time() - cpu, "max_real": max_real,
                      "estimate": estimate}))


main()
