#!/usr/bin/python3
"""Peers for the work-precision study: the same Floquet exponents computed the way
most users would in Python, timed the same way (median of repeated runs, CPU and wall), with
the error measured against the same kind of reference, and compared with ltp's fastest method
at the same accuracy from OUT_DIR/work_precision.csv.

  /usr/bin/python3 benchmarks/peers/work_precision_scipy.py OUT_DIR

Peers: SciPy solve_ivp (RK45, DOP853, Radau, LSODA) on Phi' = A(t) Phi over one period, then
numpy eigvals -> log(rho)/T ("monodromy"); NumPy dense Hill matrix + numpy.linalg.eig with the
central-block-weight selection ("dense Hill"). Scenes: mathieu (a=1.5, q=0.5, c=0.05), meissner
(a=2, b=0.5, c=0.05; solve_ivp restarted at the jumps, as ltp does), stiff (tests/data/stiff.yaml).
References: closed form for meissner and stiff; for mathieu the monodromy peers are measured
against the dense Hill peer at N = 40 and vice versa (different methods; they agree to ~1e-15).
Writes OUT_DIR/peers.csv and OUT_DIR/peers.md. The PFRF step-sine peer: pfrf_stepsine_scipy.py.
"""
import csv
import math
import os
import sys

try:
    import numpy as np
    from scipy.integrate import solve_ivp
    from scipy.linalg import expm
    from peer_common import study_rows, timed, write_markdown
except ImportError as e:  # the study runs without peers
    print(f"work_precision_scipy: skipped ({e}); apt-get install python3-scipy", file=sys.stderr)
    sys.exit(0)

PI = math.pi


def mathieu():
    a, q, c = 1.5, 0.5, 0.05
    def A(t):
        return np.array([[0.0, 1.0], [-(a - 2 * q * math.cos(2 * t)), -c]])
    # Fourier blocks for Hill: A_0, A_{+1} = A_{-1}
    A0 = np.array([[0, 1], [-a, -c]], dtype=complex)
    A1 = np.array([[0, 0], [q, 0]], dtype=complex)
    return dict(name="mathieu", A=A, T=PI, n=2, breaks=[], fourier={0: A0, 1: A1, -1: A1})


def meissner():
    a, b, c = 2.0, 0.5, 0.05
    def A(t):
        s = 1.0 if math.cos(t) >= 0 else -1.0
        return np.array([[0.0, 1.0], [-(a + b * s), -c]])
    def E(k, tau):
        return expm(np.array([[0, 1], [-k, -c]]) * tau)
    phi = E(a + b, PI / 2) @ E(a - b, PI) @ E(a + b, PI / 2)
    ref = np.log(np.linalg.eigvals(phi).astype(complex)) / (2 * PI)
    return dict(name="meissner", A=A, T=2 * PI, n=2, breaks=[PI / 2, 3 * PI / 2], ref=ref)


def stiff():
    d = -800.0
    def A(t):
        return np.array([[d + 100 * math.cos(t), 5 * math.sin(t), 1.0],
                         [0.0, 150 + 10 * math.cos(t), 2 * math.cos(t)],
                         [0.0, 0.0, -3 + math.sin(t)]])
    return dict(name="stiff", A=A, T=2 * PI, n=3, breaks=[], ref=np.array([-800, 150, -3], dtype=complex))


def exponent_error(got, ref, omega):
    got = list(got)
    if len(got) < len(ref) or not all(np.isfinite(g) for g in got):
        return math.inf
    pairs = sorted((math.hypot((r - g).real, math.remainder((r - g).imag, omega)), i, j)
                   for i, r in enumerate(ref) for j, g in enumerate(got))
    ui, uj, worst, m = set(), set(), 0.0, 0
    for d, i, j in pairs:
        if i in ui or j in uj:
            continue
        ui.add(i)
        uj.add(j)
        worst = max(worst, d)
        m += 1
        if m == len(ref):
            break
    return worst


def monodromy_exponents(sc, method, rtol):
    n, T = sc["n"], sc["T"]
    A = sc["A"]
    def f(t, y):
        return (A(t) @ y.reshape(n, n)).ravel()
    edges = [0.0] + list(sc["breaks"]) + [T]
    y = np.eye(n).ravel()
    for t0, t1 in zip(edges[:-1], edges[1:]):
        try:
            with np.errstate(all="ignore"):
                sol = solve_ivp(f, (t0, t1), y, method=method, rtol=rtol, atol=rtol * 1e-3)
        except (ValueError, np.linalg.LinAlgError):  # overflow: the stiff scene's e^{942}
            return None
        if not sol.success or not np.all(np.isfinite(sol.y[:, -1])):
            return None
        y = sol.y[:, -1]
    with np.errstate(all="ignore"):
        rho = np.linalg.eigvals(y.reshape(n, n)).astype(complex)
        return np.log(rho) / T


def hill_exponents(sc, N):
    n, T = sc["n"], sc["T"]
    w = 2 * PI / T
    F = sc["fourier"]
    size = (2 * N + 1) * n
    H = np.zeros((size, size), dtype=complex)
    for v in range(-N, N + 1):
        for u in range(-N, N + 1):
            blk = F.get(v - u)
            if blk is not None:
                H[(v + N) * n:(v + N + 1) * n, (u + N) * n:(u + N + 1) * n] = blk
        H[(v + N) * n:(v + N + 1) * n, (v + N) * n:(v + N + 1) * n] -= 1j * v * w * np.eye(n)
    vals, vecs = np.linalg.eig(H)
    central = np.sum(np.abs(vecs[N * n:(N + 1) * n, :]) ** 2, axis=0)
    return vals[np.argsort(-central)[:n]]


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "out/work-precision"
    os.makedirs(out, exist_ok=True)
    rows = []
    for sc in (mathieu(), meissner(), stiff()):
        omega = 2 * PI / sc["T"]
        if "fourier" in sc:
            ref_for_mono = hill_exponents(sc, 40)
            m = monodromy_exponents(sc, "DOP853", 1e-13)
            ref_for_hill = m
        else:
            ref_for_mono = ref_for_hill = sc["ref"]
        scale = max(1.0, max(abs(x) for x in ref_for_hill))
        for method in ("RK45", "DOP853", "Radau", "LSODA"):
            for k in range(6):
                rtol = 10.0 ** (-3 - 2 * k)
                if method in ("Radau", "LSODA") and rtol < 1e-11:
                    continue  # below what these reach in double precision per step
                if method == "RK45" and rtol < 1e-9:
                    continue  # 5th order at 1e-11: tens of thousands of Python-level steps
                e, cpu, wall, rep = timed(lambda: monodromy_exponents(sc, method, rtol), min_repeats=3)
                err = math.inf if e is None else exponent_error(e, ref_for_mono, omega)
                rows.append([sc["name"], "exponents", f"scipy {method}", "rtol", rtol, int(math.isfinite(err)),
                             err, err / scale, cpu, wall, rep])
                print(f"  peer {sc['name']} {method} rtol={rtol:g} err {err / scale:.3g} cpu {cpu:.3g} s",
                      file=sys.stderr)
                if wall > 2:
                    break
        if "fourier" in sc:
            for N in (2, 4, 8, 16, 32, 64):
                e, cpu, wall, rep = timed(lambda: hill_exponents(sc, N), min_repeats=3)
                err = exponent_error(e, ref_for_hill, omega)
                rows.append([sc["name"], "exponents", "numpy dense Hill", "harmonics", N, 1, err, err / scale,
                             cpu, wall, rep])
    with open(os.path.join(out, "peers.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["scene", "panel", "method", "knob_name", "knob", "ok", "error_abs", "error_rel", "cpu_s",
                    "wall_s", "repeats"])
        w.writerows(rows)
    # Side by side: cheapest run reaching each target, ltp vs peers (CPU time, same machine).
    ltp = [(r["scene"], r["method"], float(r["error_rel"]), float(r["cpu_s"]))
           for r in study_rows(out, "exponents")]
    lines = ["| scene | target error | fastest ltp method | CPU | fastest peer | CPU | peer / ltp |",
             "|---|---|---|---|---|---|---|"]
    for scene in ("mathieu", "meissner", "stiff"):
        for target in (1e-6, 1e-10):
            best_l = min(((c, m) for s, m, e, c in ltp if s == scene and e <= target), default=None)
            best_p = min(((r[8], r[2]) for r in rows if r[0] == scene and r[7] <= target), default=None)
            ratio = f"{best_p[0] / best_l[0]:.0f}×" if best_l and best_p and best_l[0] > 0 else "—"
            fmt = lambda b: (f"{b[1]}", f"{b[0] * 1e3:.3g} ms") if b else ("none reaches it", "—")
            lines.append(f"| {scene} | {target:g} | {fmt(best_l)[0]} | {fmt(best_l)[1]} | {fmt(best_p)[0]} | "
                         f"{fmt(best_p)[1]} | {ratio} |")
    write_markdown(out, "peers.md", lines)


if __name__ == "__main__":
    main()
