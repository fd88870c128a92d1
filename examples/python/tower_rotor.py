# ltp from Python, notebook style: the paper's tower-rotor system (Fig. 6) and a Campbell
# diagram. Run it as a script (it writes PNGs into the folder given, default ./out) or cell by
# cell (# %%) in an editor that knows the format.
#
#     PYTHONPATH=build/python python3 examples/python/tower_rotor.py out
#
# The same numbers from the command line:
#     ltp floquet tower-rotor
#     ltp snapshot tower-rotor --angle 90 --compare --input Fz_tip --output z_tip --freq 0:450:0.6
#     ltp chart rotor --set blades=2 --set C_zeta=0.02 --set cx=0.2 --set cy=0.2 --sweep Omega=0.3:1.8:0.01

# %% Setup
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")  # files only; drop this line in a notebook
import matplotlib.pyplot as plt
import numpy as np

import ltp

out = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else "out")
out.mkdir(parents=True, exist_ok=True)

# %% The paper's system: a two-bladed rotor at 100 rad/s on a flexible cantilever (40 states)
system = ltp.scene("tower-rotor")
print(system)
floquet = ltp.floquet(system)
print(floquet)
lines = floquet.frequencies_hz > 0
print("Floquet frequencies (Hz):", np.round(floquet.frequencies_hz[lines], 2))
print(f"verdict {floquet.verdict}, error estimate {floquet.error_estimate:.1e} 1/s")

# %% Fig. 6: the frozen system at 90° against the periodic system's response to an impulse
# The snapshot FRF C (jωI − A(t0))⁻¹ B is what a time-invariant analysis at that instant
# predicts; the periodic system answers with the summed partials Σ_z H_z(ω − zΩp).
fig6 = ltp.snapshot(system, "0:450:0.6", angle=90, compare=True, input="Fz_tip", output="z_tip")
print(f"summed partials checked against the HTF route: max disagreement "
      f"{fig6.max_summed_disagreement:.1e} of the largest |H_z|")

fig, ax = plt.subplots(figsize=(10, 4.5))
ax.semilogy(fig6.frequencies_hz, np.abs(fig6.snapshot), color="#7e2f8e", lw=1.3,
            label="snapshot FRF (system frozen at 90°)")
ax.semilogy(fig6.frequencies_hz, np.abs(fig6.summed), color="#2ca02c", lw=1.3,
            label="periodic system: Σ_z H_z(ω − zΩp)")
for f in floquet.frequencies_hz[lines]:
    ax.axvline(f, color="0.8", lw=0.6, zorder=0)
ax.set(xlabel="frequency [Hz]", ylabel="|z_tip / Fz_tip|", xlim=(0, 450),
       title="tower-rotor: snapshot vs periodic system (paper Fig. 6); grey: Floquet frequencies")
ax.grid(True, which="major", alpha=0.3)
ax.legend(loc="upper right")
fig.tight_layout()
fig.savefig(out / "fig6_snapshot_vs_periodic.png", dpi=110)

# %% Where the extra resonances come from: the partial FRFs H_z
pfrf = ltp.pfrf(system, "0:450:0.6", input="Fz_tip", output="z_tip", orders="-4:4")
for peak in sorted(pfrf.resonances, key=lambda p: -p["abs"])[:4]:
    print(f"|H_{peak['z']:+d}| peak at {peak['f_resp_hz']:.1f} Hz: Floquet mode at "
          f"{pfrf.floquet.frequencies_hz[peak['mode']]:.1f} Hz, harmonic {peak['harmonic']:+d}")

# %% Campbell and damping diagram of a two-bladed rotor over its speed Ω
rotor = ltp.scene("rotor", blades=2, C_zeta=0.02, cx=0.2, cy=0.2)
chart = ltp.chart(rotor, "Omega=0.3:1.8:0.01")
omega = chart.values[0]
print(f"{len(omega)} speeds: {chart.counts}; unstable intervals of Ω (rad/s):")
for lo, hi in chart.unstable_intervals:
    print(f"  {lo:.4f} … {hi:.4f}")

fig, (top, bottom) = plt.subplots(2, 1, figsize=(9, 7), sharex=True, height_ratios=[3, 2])
# One line per physical mode (a conjugate pair is one motion), named by the states carrying it.
for k, line in enumerate(chart.lines):
    top.plot(omega, line["frequency_hz"], lw=1.4, color=f"C{k}", label=line["description"])
    bottom.plot(omega, line["real_part"], lw=1.4, color=f"C{k}")
for n in chart.per_rev:  # per-rev lines nΩ/2π and where the modes cross them
    top.plot(omega, n * chart.rotor_speeds / (2 * np.pi), "k--", lw=0.7)
top.plot([c["parameter"] for c in chart.crossings], [c["frequency_hz"] for c in chart.crossings],
         "ko", mfc="none", label="crossings")
top.legend(fontsize=7)
for lo, hi in chart.unstable_intervals:
    for ax in (top, bottom):
        ax.axvspan(lo, hi, color="#d62728", alpha=0.12, lw=0)
top.set(ylabel="Floquet frequency [Hz]", title="Campbell diagram: two-bladed rotor (unstable Ω shaded)")
bottom.axhline(0, color="k", lw=0.6)
bottom.set(xlabel="rotor speed Ω [rad/s]", ylabel="Re λ [1/s]")
for ax in (top, bottom):
    ax.grid(True, alpha=0.3)
fig.tight_layout()
fig.savefig(out / "campbell.png", dpi=110)
print("wrote", out / "fig6_snapshot_vs_periodic.png", "and", out / "campbell.png")
