"""ltp.floquet(..., keep_factors=True): the segment factors behind the monodromy.

References: the formed monodromy (their product, last factor leftmost) and Liouville's formula
det Φ = exp ∫_0^T tr A dt, which holds for the factors' log-determinants even where the formed
product underflows. ltp.periodic_schur on those factors: the definition Z[k+1]ᵀ F[k] Z[k] = T[k]
itself, the analysis' exponents (its own, sorted periodic Schur eigenvalues), Liouville again and
closed forms of factors built from known pieces.
"""
import math

import numpy as np
import pytest

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


# ltp.periodic_schur: the periodic Schur form of the kept factors.

def mathieu_type(a_stiff, coupling, period):
    a = np.zeros((3, 2, 2), complex)
    a[1] = a_stiff
    a[0][1, 0] = a[2][1, 0] = coupling
    return ltp.System.from_fourier(period, a)


def check_schur_form(factors, s):
    # (a) the definition Z[k+1]ᵀ F[k] Z[k] = T[k] (reference: the factors themselves), Z orthogonal;
    # (b) SLICOT's structure: T[K-1] quasi-upper-triangular, the others upper triangular, exact
    # zeros below. Returns the largest relative reconstruction residual.
    k, n = factors.shape[0], factors.shape[1]
    assert s.ok and s.Z.shape == s.T.shape == factors.shape and s.quasi_triangular == k - 1
    assert s.Z.dtype == s.T.dtype == np.float64 and s.log_multipliers.dtype == np.complex128
    worst = 0.0
    for i in range(k):
        back = s.Z[(i + 1) % k] @ s.T[i] @ s.Z[i].T
        worst = max(worst, np.linalg.norm(back - factors[i]) / np.linalg.norm(factors[i]))
        assert np.linalg.norm(s.Z[i].T @ s.Z[i] - np.eye(n)) < 1e-14
        assert not np.tril(s.T[i], -2 if i == k - 1 else -1).any()
    assert worst < 1e-14
    return worst


def same_modulo_2pi_j(a, b, tol):
    # Every a matched to some b: equal real parts, imaginary parts equal modulo 2π.
    for x in a:
        d = [abs(x.real - y.real) + abs(math.remainder(x.imag - y.imag, 2 * math.pi)) for y in b]
        assert min(d) < tol * max(1.0, abs(x)), (x, b)


def test_periodic_schur_of_the_factors_gives_the_exponents():
    # A damped Mathieu oscillator (a complex pair: one 2×2 block) and a Mathieu-type system whose
    # multiplier e^{1885} overflows: its monodromy comes back NaN while the factors hold it.
    # Reference for log ρ: the analysis' exponents × T (its own periodic Schur eigenvalues, sorted,
    # a different SLICOT run), modulo 2πj; for the overflowing one also Liouville's formula
    # Σ log ρ = ∫ tr A dt = T tr A_0.
    damped = ltp.floquet(mathieu_type([[0, 1], [-1.5, -0.05]], 0.4, math.pi), keep_factors=True)
    s = ltp.periodic_schur(damped.segment_factors)
    check_schur_form(damped.segment_factors, s)
    assert np.count_nonzero(np.diag(s.T[-1], -1)) == 1
    same_modulo_2pi_j(damped.exponents * damped.period, s.log_multipliers, 1e-12)
    same_modulo_2pi_j(s.log_multipliers, damped.exponents * damped.period, 1e-12)

    growing = ltp.floquet(mathieu_type([[300.0, 1.0], [0.0, -0.1]], 0.3, 2 * math.pi),
                          keep_factors=True)
    assert not np.isfinite(growing.monodromy).all()
    s = growing.periodic_schur()  # the same as ltp.periodic_schur(growing.segment_factors)
    check_schur_form(growing.segment_factors, s)
    same_modulo_2pi_j(growing.exponents * growing.period, s.log_multipliers, 1e-12)
    exact = 2 * math.pi * 299.9
    assert abs(np.sum(s.log_multipliers).real - exact) < 1e-9 * exact


def test_periodic_schur_closed_form_beyond_the_double_range():
    # F[k] = Q[k+1] diag(e^{1000/K}, e^{-1000/K}) Q[k]ᵀ with random orthogonal Q (Q[K] = Q[0]):
    # log ρ = ±1000 in closed form; the formed product overflows. K = 200 keeps each factor's
    # range at e^{±5}, so rounding in forming the factors leaves the small multiplier intact.
    rng = np.random.default_rng(7)
    k = 200
    q = [np.linalg.qr(rng.standard_normal((2, 2)))[0] for _ in range(k)]
    d = np.diag([math.exp(1000 / k), math.exp(-1000 / k)])
    factors = np.array([q[(i + 1) % k] @ d @ q[i].T for i in range(k)])
    with np.errstate(over="ignore", invalid="ignore"):
        assert not np.isfinite(product(factors)).all()
    s = ltp.periodic_schur(factors)
    check_schur_form(factors, s)
    assert np.allclose(sorted(s.log_multipliers.real), [-1000, 1000], rtol=1e-12, atol=0)
    assert not s.log_multipliers.imag.any()


def test_periodic_schur_refuses_what_is_not_a_real_stack():
    bad = [np.eye(2), np.zeros((0, 2, 2)), np.zeros((2, 2, 3)), np.ones((2, 2, 2)) * 1j,
           np.full((1, 2, 2), np.nan), "factors"]
    for factors in bad:
        with pytest.raises(ltp.InputError, match="factors"):
            ltp.periodic_schur(factors)
    # Complex dtype with all imaginary parts 0 is its real part, as everywhere in ltp.
    s = ltp.periodic_schur(np.array([[[2.0, 1.0], [0.0, 3.0]]]) + 0j)
    assert np.allclose(sorted(s.log_multipliers.real), [math.log(2), math.log(3)], rtol=1e-15)
    with pytest.raises(ltp.InputError, match="keep_factors=True"):
        ltp.floquet(mathieu_type([[0, 1], [-1.5, -0.05]], 0.4, math.pi)).periodic_schur()
