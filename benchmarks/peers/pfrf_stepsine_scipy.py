#!/usr/bin/python3
"""Step-sine peer for the partial FRFs of the work-precision study: H_z
computed the way the reference paper obtained its partial FRFs (eq. 47, a step-sine simulation
from rest), with SciPy's solve_ivp, timed the same way as ltp (CPU time, median of repeats, the
whole set of frequencies of a scene), with the error measured exactly like the study, and
compared with ltp's PFRF routes from OUT_DIR/work_precision.csv.

  /usr/bin/python3 benchmarks/peers/pfrf_stepsine_scipy.py OUT_DIR

Needs OUT_DIR/pfrf_reference.csv (written by work_precision_benchmark: ltp shooting at rkf78
1e-13, channel (0, 0), orders z = -2..2); only the scenes found there are run. Scenes: mathieu
(a=1.5, q=0.5, c=0.05, T = pi) and meissner (a=2, b=0.5, c=0.05, T = 2 pi; solve_ivp restarted
at the jumps pi/2, 3 pi/2, as ltp does). Peers: solve_ivp RK45 (rtol 1e-4, 1e-6) and DOP853
(rtol 1e-4, 1e-6, 1e-9, 1e-12), atol = rtol 1e-3 as in work_precision_scipy.py and in ltp's own
runs; settling matched to the tolerance (settle_tol = rtol). About 30 s on the project's 2-core machine.

Method, per excitation frequency w: u(t) = e^{jwt} = cos wt + j sin wt switched on at t = 0 with
the system at rest; the cos run and the sin run are one real system of 2n states (one solve_ivp
call, one step-size sequence for both). Integrate until the transient has decayed, then project
the output over M whole system periods:
  H_z(w) = 1/(M T) * integral_{t_s}^{t_s + M T} y(t) e^{-j(w + z Wp) t} dt,   Wp = 2 pi / T.
For the periodic steady state y(t) e^{-jwt} is T-periodic, so this is exact for whole periods.
Writes OUT_DIR/peers_pfrf.csv and OUT_DIR/peers_pfrf.md.
"""
import csv
import math
import os
import sys
import time

try:
    import numpy as np
    import scipy
    from scipy.integrate import solve_ivp
    from peer_common import study_rows, timed, write_markdown
except ImportError as e:  # the study runs without peers
    print(f"pfrf_stepsine_scipy: skipped ({e}); apt-get install python3-scipy", file=sys.stderr)
    sys.exit(0)

PI = math.pi
ORDERS = np.arange(-2, 3)  # z = -2..2, as kMinOrder/kMaxOrder in benchmarks/work_precision_benchmark.cc
COMPARABLE = 2.0  # (a) below: ltp's time route counts as "comparable" up to 2x the peer's error
RECORD_PERIODS = 4  # M: whole system periods projected (ltp's ShootingOptions::record_periods is 4 too)


# --- scenes (the study's parameters: benchmarks/work_precision_benchmark.cc; models:
#     models/src/builtin_scenes.cc). State x = (y, y'), input u on y'', output y. ---------------

def mathieu():
    a, q, c = 1.5, 0.5, 0.05
    # y'' + c y' + (a - 2q cos 2t) y = u; smooth, so no restarts.
    return dict(name="mathieu", T=PI, c=c, breaks=[], stiffness=lambda t: a - 2 * q * math.cos(2 * t),
                piecewise=False)


def meissner():
    a, b, c = 2.0, 0.5, 0.05
    # y'' + c y' + (a + b sign(cos t)) y = u; the stiffness jumps at pi/2 and 3 pi/2, so every
    # solve_ivp call covers one piece with the constant stiffness of that piece (evaluated at the
    # piece's midpoint, so the value at the jump itself never matters).
    return dict(name="meissner", T=2 * PI, c=c, breaks=[PI / 2, 3 * PI / 2],
                stiffness=lambda t: a + b * (1.0 if math.cos(t) > 0 else -1.0), piecewise=True)


def pieces(sc, t0, t1):
    """[t0, t1] cut at the scene's jumps (breaks repeat every period)."""
    T = sc["T"]
    cuts = [t0]
    k0 = math.floor(t0 / T)
    for k in range(k0, int(math.ceil(t1 / T)) + 1):
        for b in sc["breaks"]:
            t = k * T + b
            if t0 + 1e-12 * T < t < t1 - 1e-12 * T:
                cuts.append(t)
    cuts.append(t1)
    return list(zip(cuts[:-1], cuts[1:]))


def slowest_decay(sc):
    """max Re(lambda) over the Floquet exponents, from the monodromy matrix (DOP853 1e-13; not
    timed, as ltp's time route gets its Floquet result outside the timed region). For these
    damped 2x2 oscillators tr A = -c, so lambda_1 + lambda_2 = -c and, with complex-conjugate
    multipliers (both scenes sit outside the instability tongues), Re lambda = -c/2 exactly;
    the monodromy checks that rather than assuming it."""
    T, c = sc["T"], sc["c"]
    phi = np.eye(2)
    for t0, t1 in pieces(sc, 0.0, T):
        k = sc["stiffness"](0.5 * (t0 + t1)) if sc["piecewise"] else None
        def f(t, v, k=k):
            kk = k if k is not None else sc["stiffness"](t)
            m = v.reshape(2, 2)
            return np.array([m[1], -kk * m[0] - c * m[1]]).ravel()
        sol = solve_ivp(f, (t0, t1), phi.ravel(), method="DOP853", rtol=1e-13, atol=1e-16)
        phi = sol.y[:, -1].reshape(2, 2)
    rho = np.linalg.eigvals(phi).astype(complex)
    re = float(np.max(np.log(np.abs(rho)) / T))
    if abs(re + c / 2) > 1e-8:
        print(f"  {sc['name']}: max Re lambda = {re:.12g}, not -c/2 = {-c / 2:g}; using the monodromy's",
              file=sys.stderr)
    return re


def settle_periods(sc, decay, settle_tol):
    """Whole periods K with e^{decay K T} <= settle_tol (decay = max Re lambda < 0)."""
    return int(math.ceil(math.log(settle_tol) / decay / sc["T"]))


def step_sine(sc, w, method, rtol, K):
    """H_z(w), z = -2..2, by a step-sine simulation: K settling periods, then M = RECORD_PERIODS
    projected periods. Returns (H, rhs evaluations).

    The projection integrals are extra ODE states q_z' = y(t) e^{-j(w + z Wp) t} (real and
    imaginary parts), integrated by the same solve_ivp call over the recorded periods, rather
    than sampling the dense output and summing (trapezoid / FFT). Why: (1) the quadrature then
    has the method's own order and sits under the same error control, whereas solve_ivp's dense
    output is a lower-order interpolant (RK45: 4th order) that would cap the accuracy at tight
    tolerances; (2) meissner's y'' jumps at the breakpoints, so y(t) e^{-jwt} is only C^1 and a
    periodic trapezoid / FFT converges only algebraically (aliasing ~ S^-3), while the quadrature
    states are restarted exactly at the jumps with the rest of the state; (3) no sample-count
    knob to tune. The cost is 10 extra states over the M recorded periods only (the settling
    phase, by far the longest, integrates just the 4 states of the cos and sin runs)."""
    T, c = sc["T"], sc["c"]
    Wz = w + ORDERS * (2 * PI / T)  # response frequencies w + z Wp
    t_s, t_end = K * T, (K + RECORD_PERIODS) * T
    atol = rtol * 1e-3
    nfev = 0
    state = np.zeros(4)  # (y_cos, y_cos', y_sin, y_sin'): at rest when the sine is switched on
    h_last = None

    def make_rhs(k_const, record):
        stiff = sc["stiffness"]
        def f(t, s):
            k = k_const if k_const is not None else stiff(t)
            cw, sw = math.cos(w * t), math.sin(w * t)
            d = [s[1], -k * s[0] - c * s[1] + cw, s[3], -k * s[2] - c * s[3] + sw]
            if not record:
                return d
            p = (s[0] + 1j * s[2]) * np.exp(-1j * Wz * t)  # y = y_cos + j y_sin, times e^{-j W_z t}
            return np.concatenate((d, p.real, p.imag))
        return f

    for phase, (a, b) in (("settle", (0.0, t_s)), ("record", (t_s, t_end))):
        record = phase == "record"
        if record:
            state = np.concatenate((state, np.zeros(2 * len(ORDERS))))
        for t0, t1 in pieces(sc, a, b) if b > a else []:
            k = sc["stiffness"](0.5 * (t0 + t1)) if sc["piecewise"] else None
            # Restarts keep the last step size as the first step (as ltp's integrator does)
            # instead of paying solve_ivp's initial-step heuristic at every jump.
            first = min(h_last, t1 - t0) if h_last else None
            sol = solve_ivp(make_rhs(k, record), (t0, t1), state, method=method, rtol=rtol, atol=atol,
                            first_step=first)
            nfev += sol.nfev
            if not sol.success or not np.all(np.isfinite(sol.y[:, -1])):
                return None, nfev
            state = sol.y[:, -1]
            if len(sol.t) >= 2:  # the last step was cut to land on t1: take the larger of the last two
                h_last = max(np.diff(sol.t[-3:]))
    quad = state[4:4 + len(ORDERS)] + 1j * state[4 + len(ORDERS):]
    return quad / (RECORD_PERIODS * T), nfev


def all_frequencies(sc, fhz, method, rtol, K):
    out, nfev = [], 0
    for f in fhz:
        h, n = step_sine(sc, 2 * PI * f, method, rtol, K)
        nfev += n
        if h is None:
            return None, nfev
        out.append(h)
    return np.array(out), nfev


def read_reference(out):
    """OUT/pfrf_reference.csv -> {scene: (freqs_hz, H[f, z])}, z = -2..2."""
    path = os.path.join(out, "pfrf_reference.csv")
    ref = {}
    if not os.path.exists(path):
        return ref
    with open(path) as f:
        for r in csv.DictReader(f):
            ref.setdefault(r["scene"], {})[(float(r["freq_hz"]), int(r["order"]))] = complex(float(r["re"]),
                                                                                             float(r["im"]))
    res = {}
    for scene, d in ref.items():
        fhz = sorted({f for f, _ in d})
        H = np.array([[d[(f, int(z))] for z in ORDERS] for f in fhz])
        res[scene] = (fhz, H)
    return res


def frf_error(got, ref):
    """As FrfError in work_precision_benchmark.cc: max over frequencies and orders of |H - H_ref|,
    and (relative) the same divided by max |H_ref| over the scene's frequencies and orders."""
    if got is None or got.shape != ref.shape or not np.all(np.isfinite(got)):
        return math.inf, math.inf
    e = float(np.max(np.abs(got - ref)))
    return e, e / float(np.max(np.abs(ref)))


def read_ltp(out):
    """ltp's PFRF rows of OUT/work_precision.csv: (scene, method, knob_name, knob, error_rel, cpu_s)."""
    rows = [(r["scene"], r["method"], r["knob_name"], r["knob"], float(r["error_rel"]), float(r["cpu_s"]))
            for r in study_rows(out, "pfrf")]
    return rows


def cheapest(ltp, scene, err, methods=None):
    """Cheapest ltp row on `scene` (restricted to `methods`) at the same or better accuracy."""
    c = [r for r in ltp if r[0] == scene and r[4] <= err and (methods is None or r[1] in methods)]
    return min(c, key=lambda r: r[5]) if c else None


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "out/work-precision"
    os.makedirs(out, exist_ok=True)
    refs = read_reference(out)
    if not any(name in refs for name in ("mathieu", "meissner")):
        # Nothing to compare with: say so in the outputs too (no stale table from an older run).
        msg = (f"PFRF step-sine peer skipped: no mathieu or meissner rows in {out}/pfrf_reference.csv "
               "(written by work_precision_benchmark's study for its PFRF scenes).")
        with open(os.path.join(out, "peers_pfrf.md"), "w") as f:
            f.write(msg + "\n")
        open(os.path.join(out, "peers_pfrf.csv"), "w").close()
        print(msg, file=sys.stderr)
        return
    rows = []
    t_start = time.perf_counter()
    for sc in (mathieu(), meissner()):
        if sc["name"] not in refs:
            continue  # scene not in this study run
        fhz, H_ref = refs[sc["name"]]
        decay = slowest_decay(sc)
        for method in ("RK45", "DOP853"):
            # 1e-4: the accuracy of ltp's quick-mode time route (settle_tol 1e-4), so that (a) below
            # has a comparable point in --quick runs too; 1e-6 and 1e-9 match the full study's
            # settle_tol 1e-6 and 1e-9 rows; 1e-12 shows where the peer's accuracy ends.
            for rtol in (1e-4, 1e-6, 1e-9, 1e-12):
                if method == "RK45" and rtol < 1e-6:
                    continue  # DOP853 covers the tight end; RK45 at 1e-9 alone took 18 s of the budget
                # Settling matched to the tolerance: the transient is left at settle_tol of its
                # initial size, the same level as the integration error per unit solution (no
                # cond(Xi) factor as in ltp's SettlingTime). Measured with DOP853, separating the
                # two: the transient's leftover alone (rtol 1e-12) is ~1.5 settle_tol on mathieu
                # and ~0.15 settle_tol on meissner; the integration error alone (settle_tol
                # 1e-12) ~1.0 rtol and ~0.06 rtol. Same order, so neither is wasted.
                settle_tol = rtol
                K = settle_periods(sc, decay, settle_tol)
                (H, nfev), cpu, wall, rep = timed(lambda: all_frequencies(sc, fhz, method, rtol, K),
                                                  repeats=3, budget=1.5)
                err_abs, err_rel = frf_error(H, H_ref)
                rows.append(dict(scene=sc["name"], panel="pfrf", method=f"scipy {method} step-sine",
                                 knob_name="rtol", knob=rtol, ok=int(math.isfinite(err_rel)),
                                 error_abs=err_abs, error_rel=err_rel, cpu_s=cpu, wall_s=wall, repeats=rep,
                                 settle_tol=settle_tol, settle_periods=K, record_periods=RECORD_PERIODS,
                                 rhs_evals=nfev))
                print(f"  peer {sc['name']} pfrf {method} rtol={rtol:g} settle {K} periods err {err_rel:.3g} "
                      f"cpu {cpu:.3g} s ({rep} run{'s' if rep > 1 else ''}, {nfev} rhs evals)", file=sys.stderr)
    fields = ["scene", "panel", "method", "knob_name", "knob", "ok", "error_abs", "error_rel", "cpu_s", "wall_s",
              "repeats", "settle_tol", "settle_periods", "record_periods", "rhs_evals"]
    with open(os.path.join(out, "peers_pfrf.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields)
        w.writeheader()
        w.writerows(rows)

    # Side by side with ltp (CPU time, same machine), from OUT/work_precision.csv, panel "pfrf":
    # (a) ltp's own step-sine route "time (step-sine)", its cheapest run at comparable or better
    #     accuracy (error_rel <= COMPARABLE x the peer's: the two simulations' errors are both
    #     ~settle_tol, so a factor 2 either way is the same setting, not a different accuracy);
    # (b) ltp's cheapest PFRF row of any route (modal, htf, shooting, time, and the default
    #     auto route) at the same or better accuracy (error_rel <= the peer's).
    # Ratio = peer CPU / ltp CPU, i.e. "ltp is N× faster".
    ltp = read_ltp(out)
    fmt_ms = lambda s: f"{s:.3g} s" if s >= 1 else f"{s * 1e3:.3g} ms"
    fmt_ratio = lambda x: f"{x:,.0f}×" if x >= 100 else f"{x:.2g}×"
    lines = ["Partial FRFs, SciPy step-sine peer vs ltp (channel 0 -> 0, z = -2..2; error = max |H - H_ref| / "
             "max |H_ref| over the scene's frequencies and orders; CPU time for all of the scene's frequencies; "
             "ratio = peer CPU / ltp CPU, i.e. ltp is N× faster). (a): ltp's time (step-sine) route, cheapest "
             f"run with error <= {COMPARABLE:g}× the peer's; (b): ltp's cheapest PFRF route with error <= the peer's.",
             ""]
    for scene in dict.fromkeys(r["scene"] for r in rows):
        n_f = len(refs[scene][0])
        lines += [f"**{scene}** ({n_f} frequencies)", "",
                  "| peer | rtol | settle periods | error | CPU | (a) ltp time (step-sine) | CPU | "
                  "peer / ltp | (b) cheapest ltp route | CPU | peer / ltp |",
                  "|---|---|---|---|---|---|---|---|---|---|---|"]
        time_rows = [x for x in ltp if x[0] == scene and x[1] == "time (step-sine)"]
        for r in (r for r in rows if r["scene"] == scene):
            cells = [r["method"], f"{r['knob']:g}", str(r["settle_periods"]), f"{r['error_rel']:.2g}",
                     fmt_ms(r["cpu_s"])]
            for best, none in ((cheapest(ltp, scene, COMPARABLE * r["error_rel"], {"time (step-sine)"}),
                                "none that accurate" + (" (most accurate: err " +
                                f"{min(x[4] for x in time_rows):.2g})" if time_rows else " (not run)")),
                               (cheapest(ltp, scene, r["error_rel"]), "none reaches it")):
                if best is None or not math.isfinite(r["error_rel"]):
                    cells += [none, "—", "—"]
                else:
                    ratio = r["cpu_s"] / best[5] if best[5] > 0 else math.inf
                    cells += [f"{best[1]} {best[2]}={best[3]} (err {best[4]:.2g})", fmt_ms(best[5]),
                              fmt_ratio(ratio)]
            lines.append("| " + " | ".join(cells) + " |")
        lines.append("")
    lines.append(f"Peer run: {time.perf_counter() - t_start:.0f} s wall; SciPy {scipy.__version__}, "
                 f"NumPy {np.__version__}.")
    write_markdown(out, "peers_pfrf.md", lines)


if __name__ == "__main__":
    main()
