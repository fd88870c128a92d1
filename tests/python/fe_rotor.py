"""A finite-element rotor as rotordynamicists write one, in SI units: Euler-Bernoulli shaft
elements with rotary inertia (4 DOF per node: v, w and their slopes), consistent mass,
gyroscopic coupling, a shaft whose bending stiffness differs in its two principal directions
(in the fixed frame K(t) = K_0 + K_c cos 2Ωt + K_s sin 2Ωt: period π/Ω), two discs and
anisotropic bearings at the ends. Used by test_large_models.py and the model-size benchmark's
SciPy peer (benchmarks/peers/fe_rotor_scipy.py)."""
import numpy as np


def fe_rotor(elements, rpm=3000.0, length=1.2, diameter=0.05, young=2.1e11, density=7850.0,
             asymmetry=0.1, bearings=((2e7, 4e7), (2e3, 3e3)),
             discs=((0.33, 8.0, 0.06, 0.12), (0.66, 12.0, 0.09, 0.18))):
    """Returns (period, M, D, K): M and D constant (q x q), K as Fourier coefficients (3, q, q)
    for harmonics -1, 0, 1 of 2 pi / period; q = 4 (elements + 1)."""
    nodes = elements + 1
    q = 4 * nodes
    l = length / elements
    area, inertia = np.pi * diameter ** 2 / 4, np.pi * diameter ** 4 / 64
    ke = young * inertia / l ** 3 * np.array([[12, 6 * l, -12, 6 * l], [6 * l, 4 * l * l, -6 * l, 2 * l * l],
                                              [-12, -6 * l, 12, -6 * l], [6 * l, 2 * l * l, -6 * l, 4 * l * l]])
    me = density * area * l / 420 * np.array([[156, 22 * l, 54, -13 * l], [22 * l, 4 * l * l, 13 * l, -3 * l * l],
                                              [54, 13 * l, 156, -22 * l], [-13 * l, -3 * l * l, -22 * l, 4 * l * l]])
    mr = density * inertia / (30 * l) * np.array([[36, 3 * l, -36, 3 * l], [3 * l, 4 * l * l, -3 * l, -l * l],
                                                  [-36, -3 * l, 36, -3 * l], [3 * l, -l * l, -3 * l, 4 * l * l]])
    M, G, K0, Kc, Ks, C = (np.zeros((q, q)) for _ in range(6))
    for e in range(elements):
        v = [4 * e, 4 * e + 2, 4 * e + 4, 4 * e + 6]
        w = [4 * e + 1, 4 * e + 3, 4 * e + 5, 4 * e + 7]
        for idx in (v, w):
            M[np.ix_(idx, idx)] += me + mr
            K0[np.ix_(idx, idx)] += ke
        Kc[np.ix_(v, v)] += asymmetry * ke
        Kc[np.ix_(w, w)] -= asymmetry * ke
        Ks[np.ix_(v, w)] += asymmetry * ke
        Ks[np.ix_(w, v)] += asymmetry * ke
        G[np.ix_(v, w)] += 2 * mr
        G[np.ix_(w, v)] -= 2 * mr
    for position, mass, polar, diametral in discs:
        b = 4 * int(round(position * elements))
        M[b, b] += mass
        M[b + 1, b + 1] += mass
        M[b + 2, b + 2] += diametral
        M[b + 3, b + 3] += diametral
        G[b + 2, b + 3] += polar
        G[b + 3, b + 2] -= polar
    (kx, ky), (cx, cy) = bearings
    for b in (0, 4 * (nodes - 1)):
        K0[b, b] += kx
        K0[b + 1, b + 1] += ky
        C[b, b] += cx
        C[b + 1, b + 1] += cy
    omega = rpm * 2 * np.pi / 60
    K = np.zeros((3, q, q), complex)
    K[1] = K0
    K[2] = (Kc - 1j * Ks) / 2
    K[0] = (Kc + 1j * Ks) / 2
    return np.pi / omega, M, C + omega * G, K
