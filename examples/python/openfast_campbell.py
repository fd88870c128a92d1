# A Campbell diagram and a damping plot from OpenFAST linearisations, notebook style: the
# folder OpenFAST writes (every simulation's <root>.<k>.lin side by side) goes in as it is.
# Run it as a script (PNG into the folder given, default ./out) or cell by cell (# %%).
#
#     PYTHONPATH=build/python python3 examples/python/openfast_campbell.py out
#
# The same diagram from the command line (the numbers are equal, tests/python/test_campbell.py):
#     ltp campbell FOLDER --plot campbell.svg

# %% Setup
import pathlib
import shutil
import sys
import tempfile

import matplotlib

matplotlib.use("Agg")  # files only; drop this line in a notebook
import matplotlib.pyplot as plt
import numpy as np

import ltp

out = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else "out")
out.mkdir(parents=True, exist_ok=True)

# %% An OpenFAST output folder: seven simulations of a three-bladed rotor, three azimuths each.
# (ltp's test data keep one directory per rotor speed; here they are copied into one flat
# folder the way OpenFAST and ACDC write them: omega-0.4.1.lin, omega-0.4.2.lin, …)
data = pathlib.Path(__file__).resolve().parents[2] / "tests" / "data" / "openfast" / "rotor-speeds"
folder = pathlib.Path(tempfile.mkdtemp(prefix="openfast-"))
for point in sorted(data.iterdir()):
    for lin in point.glob("*.lin"):
        shutil.copy(lin, folder / f"{point.name}.{lin.name.split('.')[1]}.lin")
print(len(list(folder.glob("*.lin"))), "files in", folder)

# %% MBC3 at each operating point, modes tracked across the points by their shapes.
# Natural frequencies |λ|/2π, as ACDC and openfast_toolbox draw them.
c = ltp.campbell([str(folder)])  # natural frequencies |λ|/2π, as ACDC draws them
print(c)
print("operating points:", np.round(c.parameter, 3), c.axis_label)
for k, line in enumerate(c.lines, start=1):
    print(f"  line {k}: {line['description']}")
    print(f"     f_n [Hz] {np.round(line['frequency_hz'], 4)}")
    print(f"     ζ [%]    {np.round(100 * line['damping_ratio'], 2)}")

# %% The figure: frequencies with the per-rev lines, and the damping ratio below.
fig, (top, bottom) = plt.subplots(2, 1, figsize=(8, 7), sharex=True,
                                  gridspec_kw={"height_ratios": [3, 2]})
markers = "osd^v<>ph*"
for k, line in enumerate(c.lines):
    style = dict(marker=markers[k % len(markers)], label=f"{k + 1}: {line['description'][:48]}")
    top.plot(c.parameter, line["frequency_hz"], **style)
    bottom.plot(c.parameter, 100 * line["damping_ratio"], **style)
f_top = 1.1 * max(np.nanmax(line["frequency_hz"]) for line in c.lines)
rpm = np.linspace(0, c.parameter.max() * 1.05, 50)
for n in c.per_rev:  # n·Ω: labelled where each leaves the plot
    top.plot(rpm, n * rpm / 60, color="0.75", lw=0.8, zorder=0)
    x = min(rpm[-1], 0.97 * f_top * 60 / n)
    top.annotate(f"{n}P", (x, n * x / 60), fontsize=8, color="0.4", ha="right", va="bottom")
for x in c.crossings:
    top.plot(x["parameter"], x["frequency_hz"], "kx")
top.set_ylim(0, f_top)
top.set_ylabel("natural frequency [Hz]")
bottom.set_ylabel("damping ratio ζ [%]")
bottom.set_xlabel(c.axis_label)
top.set_title("Campbell diagram from an OpenFAST output folder (MBC3 at each point)")
fig.legend(*top.get_legend_handles_labels(), loc="lower center", ncol=2, fontsize=8)
fig.tight_layout(rect=(0, 0.12, 1, 1))
fig.savefig(out / "openfast_campbell.png", dpi=110)
print("crossings with the per-rev lines:", len(c.crossings))
print("wrote", out / "openfast_campbell.png")
shutil.rmtree(folder)
