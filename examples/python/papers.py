# ltp for a paper, notebook style: an Ince–Strutt diagram with its transition curves checked
# against SciPy's Mathieu characteristic values, a Hill convergence table with the exponents at
# every truncation, and the H∞ and H2 norms of a forced damped Mathieu oscillator by two routes
# each. Run it as a script (it writes PNGs and prints the tables; it stops with an error if a
# number misses its reference) or cell by cell (# %%) in an editor or Jupyter with jupytext.
#
#     PYTHONPATH=build/python python3 examples/python/papers.py out
#
# The same from the command line:
#     ltp chart mathieu --set c=0 --sweep q=0:8:0.05 --sweep2 a=-2:26:0.05 --plot ince.pdf
#     ltp hill mathieu --set a=1.7 --set q=0.6 --set c=0.08

# %% Setup
import math
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")  # files only; drop this line in a notebook
import matplotlib.pyplot as plt
import numpy as np
from scipy import special

import ltp

out = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else "out")
out.mkdir(parents=True, exist_ok=True)

# %% 1. The Ince–Strutt diagram of y'' + (a − 2q cos 2t) y = 0 (undamped, period π)
# The map shades each grid point's verdict; the transition curves are traced by continuation
# from the refined boundary points (docs/stability-boundaries.md), down to the a axis.
chart = ltp.chart(ltp.scene("mathieu", c=0), "q=0:8:0.05", "a=-2:26:0.05")
print(f"{len(chart.boundary_curves)} transition curves, {chart.curve_evaluations} evaluations, "
      f"{chart.curves_s:.2f} s")


def nearest_characteristic(kind, symmetry, q):
    """SciPy's characteristic values of a curve's kind: multiplier +1 ↔ period π (even m), −1 ↔
    period 2π (odd m); a_m on curves of even solutions (ce_m), b_m on odd ones (se_m)."""
    ms = range(0, 8, 2) if kind == "+1" else range(1, 8, 2)
    if symmetry == "even":
        return [special.mathieu_a(m, q) for m in ms]
    return [special.mathieu_b(m, q) for m in ms if m > 0]


# Undamped Mathieu is time-reversible: each curve is a simple root of one half-period block of
# Φ(T/2) (y1, y1', y2 or y2' at T/2), so both edges of every tongue resolve down to q = 0.
worst, widest = 0.0, 0.0
for curve, kind, bracket, detail in zip(chart.boundary_curves, chart.boundary_curve_kinds,
                                        chart.boundary_curve_brackets, chart.boundary_curve_details):
    for (q, a), b in zip(curve, bracket):
        deviation = min(abs(v - a) for v in nearest_characteristic(kind, detail["symmetry"], q))
        assert deviation <= b + 1e-12, (q, a, deviation, b)  # every point within its bracket
        worst, widest = max(worst, deviation), max(widest, b)
print(f"largest deviation from scipy.special.mathieu_a/b: {worst:.1e} (widest bracket "
      f"{widest:.1e}), tips included")
assert worst < 1e-8 and widest < 1e-8

q_axis, a_axis = chart.values
unstable = np.zeros((len(a_axis), len(q_axis)))
for (q, a), verdict in zip(chart.point_values, chart.verdicts):
    unstable[np.argmin(np.abs(a_axis - a)), np.argmin(np.abs(q_axis - q))] = verdict == "unstable"
fig, ax = plt.subplots(figsize=(6, 5))
ax.pcolormesh(q_axis, a_axis, unstable, cmap="Greys", vmin=0, vmax=3, shading="nearest")
for curve, kind in zip(chart.boundary_curves, chart.boundary_curve_kinds):
    ax.plot(curve[:, 0], curve[:, 1], "-" if kind == "+1" else "--", color="C3", lw=1)
ax.set_xlabel("q")
ax.set_ylabel("a")
ax.set_title("Ince–Strutt: y'' + (a − 2q cos 2t) y = 0 (shaded: unstable)\n"
             "solid: multiplier +1 (period π), dashed: −1 (period 2π)", fontsize=9)
fig.tight_layout()
fig.savefig(out / "ince_strutt.png", dpi=120)

# %% 2. Hill's method: a convergence table with the exponents at every truncation N
# Damped Mathieu y'' + c y' + (a − 2q cos 2t) y = u; the monodromy route is the reference.
forced = ltp.scene("mathieu", a=1.7, q=0.6, c=0.08)
study = ltp.hill_study(forced, max_harmonics=10)
print("\n   N   size   λ_1 (1/s)                        |error|")
for n, size, row, err in zip(study.harmonics, study.matrix_size, study.exponents, study.errors):
    k = int(np.argmax(row.imag))  # the mode with positive frequency
    print(f"{n:4d} {size:6d}   {row[k].real:+.15f}{row[k].imag:+.15f}j   {err[k]:.1e}")
floquet = ltp.floquet(forced)
last = study.exponents[-1]
assert all(np.min(np.abs(floquet.exponents - x)) < 1e-10 for x in last)  # same branch here
matrix = ltp.hill_matrix(forced, harmonics=4)
h = ltp.hill(forced, harmonics=4)
residual = np.max(np.abs(matrix @ h.eigenvectors - h.eigenvectors * h.exponents))
print(f"Hill matrix N = 4: {matrix.shape}, ‖H v − λ v‖ = {residual:.1e}")

# %% 3. The H∞ and H2 norms of the forced damped Mathieu oscillator, by two routes each
htf = ltp.HarmonicTransferFunction(forced)
hinf, h2 = htf.hinf(), htf.h2()
print(f"\nH∞ = {hinf.value:.10f} ± {hinf.error_estimate:.1e}")
print(f"   frequency search over operator sections  {hinf.search_value:.10f} (a lower bound), "
      f"peak at ω = {hinf.peak_omega:.6f} rad/s, K = {hinf.section_harmonics}")
print(f"   Hamiltonian bisection bracket            [{hinf.lower:.10f}, {hinf.upper:.10f}] "
      f"({hinf.hamiltonian_analyses} Floquet analyses)")
print(f"H2 = {h2.value:.10f} ± {h2.error_estimate:.1e}")
print(f"   modal form, closed-form Parseval         {h2.modal_value:.12f}")
print(f"   periodic Lyapunov equation               {h2.lyapunov_value:.12f}")
assert hinf.ok and h2.ok
assert hinf.lower <= hinf.search_value * (1 + 1e-12) and hinf.search_value <= hinf.upper
assert abs(h2.modal_value - h2.lyapunov_value) < 1e-8 * h2.value

# The partial transfer functions on the axis and the operator norm above all of them.
w = np.linspace(0, 4, 801)
partials = np.array([htf.partial(1j * x, orders=(-2, 2))[:, 0, 0] for x in w])
fig, ax = plt.subplots(figsize=(6, 3.5))
for z in range(-2, 3):
    ax.semilogy(w, np.abs(partials[:, z + 2]), label=f"$|H_{{{z}}}(j\\omega)|$")
ax.axhline(hinf.value, color="k", lw=0.8, ls=":", label="‖G‖∞")
ax.set_xlabel("excitation frequency ω (rad/s)")
ax.set_title(f"damped Mathieu a = 1.7, q = 0.6, c = 0.08: ‖G‖∞ = {hinf.value:.4f}, "
             f"‖G‖₂ = {h2.value:.4f}", fontsize=9)
ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1))
fig.tight_layout()
fig.savefig(out / "mathieu_norms.png", dpi=120)
print(f"\nfigures in {out}/")
