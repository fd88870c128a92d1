#!/usr/bin/python3
"""Independent MBC3 reference for OpenFAST .lin files (numpy only; no ltp code).

Implements the multi-blade coordinate transformation with azimuth averaging exactly as
published in G. Bir, "Multi-Blade Coordinate Transformation and its Application to Wind
Turbine Analysis", NREL/CP-500-42553 (2008), Eq. 29 (first-order state matrix), the same
formulation as OpenFAST's MBC3 (matlab-toolbox MBC/Source/fx_mbc3.m) and openfast_toolbox
(linearization/mbc.py):

    A_NR(psi) = blkdiag(t~^-1) { A_R(psi) [[T1, 0], [Omega T2, T1]]
                                 - [[Omega T2, 0], [Omega^2 T3 + OmegaDot T2, 2 Omega T2]] },
    t~ = [1, cos psi_b, sin psi_b] (b = 1..3),  psi_b = psi + 2 pi (b - 1)/3,
    T2 = dT1/dpsi, T3 = d^2T1/dpsi^2 (blockwise), t~^-1 in the closed form of fx_mbc3.m,

then AvgA = mean over the azimuth files, eig(AvgA), and per eigenvalue lambda:
natural frequency |lambda|/2pi, damped frequency Im(lambda)/2pi, damping -Re(lambda)/|lambda|.
Omega and OmegaDot come from the operating-point derivative of the generator azimuth
(DOF_GeAz), as fx_getMats.m does. Blade triplets: rotating-frame states whose description,
with "(internal DOF index = ...)" removed, differs only in the digit after "blade ".

Usage:  /usr/bin/python3 benchmarks/peers/mbc3_reference.py FILE.lin ... [--json | --eigenvalues]
(needs python3-numpy: Debian's /usr/bin/python3, not a pyenv python without numpy).
--eigenvalues prints "re im" (17 digits) per mode with Im >= 0, sorted by natural frequency:
tests/openfast/mbc3_test.cc runs it on tests/data/openfast/nrel5mw-rotating/*.lin and compares
ltp's Campbell table with it.

Checked against OpenFAST's own published numbers: on those files openfast_toolbox's example
ex2a_MultiLinFiles_OneOP.py asserts natural frequencies [0.588, 0.722, 0.842, 0.937] Hz and
damping [63.106, 52.529, 44.01, 1.634] % for its first four (oscillatory) modes; this script
gives 0.587830, 0.722483, 0.841645, 0.937126 Hz and 63.106, 52.529, 44.010, 1.634 %.
"""
import json
import re
import sys

import numpy as np


def read_lin(path):
    """Minimal independent reader: header values, the state table, matrix A."""
    with open(path) as f:
        lines = f.read().splitlines()
    info = {"path": path}
    i = 0
    while i < len(lines):
        line = lines[i]
        if "Rotor Speed:" in line:
            info["rotor_speed"] = float(line.split(":")[1].split()[0])
        elif re.match(r"\s*Azimuth:", line):
            info["azimuth"] = float(line.split(":")[1].split()[0])
        elif "Number of continuous states:" in line:
            info["nx"] = int(line.split(":")[1])
        elif line.strip() == "Order of continuous states:":
            rows, op, rot, order, desc = [], [], [], [], []
            for row in lines[i + 3:i + 3 + info["nx"]]:
                parts = row.split()
                op.append(float(parts[1]))
                rot.append(parts[2] == "T")
                order.append(int(parts[3]))
                desc.append(" ".join(parts[4:]))
            info.update(x_op=op, x_rot=rot, x_order=order, x_desc=desc)
            i += 3 + info["nx"]
            continue
        elif line.strip() == "Order of continuous state derivatives:":
            info["xdot_op"] = [float(row.split()[1]) for row in lines[i + 3:i + 3 + info["nx"]]]
            i += 3 + info["nx"]
            continue
        elif re.match(r"^A:\s*\d+\s*x\s*\d+", line.strip()):
            n = info["nx"]
            info["A"] = np.array([[float(v) for v in r.split()] for r in lines[i + 1:i + 1 + n]])
            i += 1 + n
            continue
        i += 1
    return info


def blade_key(desc):
    desc = re.sub(r"\s*\(internal DOF index = [^)]*\)", "", desc)
    m = re.search(r"[Bb]lade (\d)", desc)
    if not m:
        return None, None
    return desc[:m.start(1)] + "#" + desc[m.end(1):], int(m.group(1))


def mbc3(files):
    data = sorted((read_lin(p) for p in files), key=lambda d: d["azimuth"])
    d0 = data[0]
    n, order, desc, rot = d0["nx"], d0["x_order"], d0["x_desc"], d0["x_rot"]
    ndof2 = sum(1 for o in order if o == 2) // 2
    assert ndof2 * 2 == n, "reference script handles second-order (ElastoDyn) states only"
    # Triplets among the displacement states (the first ndof2 states).
    groups = {}
    for i in range(ndof2):
        if rot[i]:
            key, blade = blade_key(desc[i])
            groups.setdefault(key, {})[blade] = i
    triplets = [[g[1], g[2], g[3]] for g in groups.values()]
    fixed = [i for i in range(ndof2) if not rot[i]]
    seq_dof2 = fixed + [i for t in triplets for i in t]
    seq = np.array(seq_dof2 + [i + ndof2 for i in seq_dof2])
    nf, nt = len(fixed), len(triplets)
    geaz = [i for i in range(ndof2) if "DOF_GeAz" in desc[i]]
    mats = []
    for d in data:
        if geaz:
            omega, omega_dot = d["xdot_op"][geaz[0]], d["xdot_op"][geaz[0] + ndof2]
        else:
            omega, omega_dot = d["rotor_speed"], 0.0
        az = d["azimuth"] + 2 * np.pi / 3 * np.arange(3)
        c, s = np.cos(az), np.sin(az)
        tt = np.column_stack((np.ones(3), c, s))
        ttv = np.array([[c[1] * s[2] - s[1] * c[2], c[2] * s[0] - s[2] * c[0], c[0] * s[1] - s[0] * c[1]],
                        [s[1] - s[2], s[2] - s[0], s[0] - s[1]],
                        [c[2] - c[1], c[0] - c[2], c[1] - c[0]]]) / (1.5 * np.sqrt(3))
        tt2 = np.column_stack((np.zeros(3), -s, c))
        tt3 = np.column_stack((np.zeros(3), -c, -s))

        def blk(fix, t):
            m = np.zeros((nf + 3 * nt, nf + 3 * nt))
            m[:nf, :nf] = fix
            for k in range(nt):
                m[nf + 3 * k:nf + 3 * k + 3, nf + 3 * k:nf + 3 * k + 3] = t
            return m
        T1, T1v, T2, T3 = blk(np.eye(nf), tt), blk(np.eye(nf), ttv), blk(0 * np.eye(nf), tt2), blk(0 * np.eye(nf), tt3)
        Z = np.zeros_like(T1)
        L = np.block([[T1, Z], [omega * T2, T1]])
        R = np.block([[omega * T2, Z], [omega ** 2 * T3 + omega_dot * T2, 2 * omega * T2]])
        A = d["A"][np.ix_(seq, seq)]
        mats.append(np.block([[T1v, Z], [Z, T1v]]) @ (A @ L - R))
    avg = np.mean(mats, axis=0)
    lam, vec = np.linalg.eig(avg)
    names = []
    for i in seq_dof2:
        names.append(desc[i])
    modes = []
    for k in range(len(lam)):
        if lam[k].imag < 0:
            continue
        w = abs(lam[k])
        modes.append({"re": lam[k].real, "im": lam[k].imag,
                      "natural_frequency_hz": w / (2 * np.pi),
                      "damped_frequency_hz": lam[k].imag / (2 * np.pi),
                      "damping_ratio": -lam[k].real / w if w > 0 else float("nan")})
    modes.sort(key=lambda m: m["natural_frequency_hz"])
    return {"files": [d["path"] for d in data],
            "azimuths_rad": [d["azimuth"] for d in data],
            "rotor_speed_rad_s": float(np.mean([d["rotor_speed"] for d in data])),
            "blades": 3, "triplets": len(triplets), "modes": modes}


if __name__ == "__main__":
    files = [a for a in sys.argv[1:] if not a.startswith("--")]
    result = mbc3(files)
    if "--json" in sys.argv:
        print(json.dumps(result, indent=1))
    elif "--eigenvalues" in sys.argv:
        for m in result["modes"]:
            print("%.17g %.17g" % (m["re"], m["im"]))
    else:
        print("rotor speed %.6g rad/s, azimuths %s" % (result["rotor_speed_rad_s"], result["azimuths_rad"]))
        print("%12s %12s %12s %14s %14s" % ("f_n [Hz]", "f_d [Hz]", "zeta", "Re", "Im"))
        for m in result["modes"]:
            print("%12.6f %12.6f %12.6f %14.8g %14.8g" % (m["natural_frequency_hz"], m["damped_frequency_hz"],
                                                       m["damping_ratio"], m["re"], m["im"]))
