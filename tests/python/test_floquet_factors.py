"""ltp.floquet(..., keep_factors=True): the segment factors behind the monodromy.

References: the formed monodromy (their product, last factor leftmost) and Liouville's formula
det Φ = exp ∫_0^T tr A dt, which holds for the factors' log-determinants even where the formed
product underflows.
"""
import math

import numpy as np

import ltp


def product(factors):
    p = np.eye(factors.shape[1])
    for f in factors:
        p = f @ p
    return p


def test_factors_multiply_to_the_monodromy_in_the_given_states():
    # Mathieu, and a version in badly scaled units (y in µm: the analysis balances the states and
    # must give the factors back in the user's units).
    for scale in (1.0, 1e6):
        a = np.zeros((3, 2, 2), complex)
        a[1] = [[0, scale], [-1.5 / scale, -0.05]]
        a[0][1, 0] = a[2][1, 0] = 0.4 / scale
        r = ltp.floquet(ltp.System.from_fourier(math.pi, a), keep_factors=True)
        f = r.segment_factors
        assert f.dtype == np.float64 and f.shape == (len(r.segment_times) - 1, 2, 2)
        assert np.max(np.abs(product(f) - r.monodromy)) < 1e-12 * np.max(np.abs(r.monodromy))
    assert ltp.floquet(ltp.System.from_fourier(math.pi, a)).segment_factors is None


def test_factors_keep_liouville_where_the_monodromy_underflows():
    # Exponents near −400 and −0.1 over T = 2π: det Φ = e^{−2514} is below the double range; the
    # formed product's determinant is round-off (e^{−50} or so, of either sign), while the
    # factors' log-determinants still add up to ∫ tr A dt = T tr A_0.
    a = np.zeros((3, 2, 2), complex)
    a[1] = [[-400.0, 1.0], [0.0, -0.1]]
    a[0][1, 0] = a[2][1, 0] = 0.3
    r = ltp.floquet(ltp.System.from_fourier(2 * math.pi, a), keep_factors=True)
    exact = 2 * math.pi * (-400.1)
    assert abs(np.linalg.slogdet(r.monodromy)[1] - exact) > 1000
    logdet = sum(np.linalg.slogdet(f)[1] for f in r.segment_factors)
    assert abs(logdet - exact) < 1e-9 * abs(exact)
    assert abs(np.sum(r.log_multipliers.real) - exact) < 1e-9 * abs(exact)
