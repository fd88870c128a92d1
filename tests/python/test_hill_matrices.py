"""Hill's matrices for papers and notebooks: ltp.hill_matrix, HillResult.eigenvectors and the
per-truncation exponents of ltp.hill_study.

References: the damped Mathieu equation y'' + c y' + (a − 2q cos 2t) y = 0 (period π, Ωp = 2),
whose Hill matrix is written out here in closed form from DESIGN.md's convention (block (v,u) =
A_{v−u} − j v Ωp δ_vu I, harmonics −N..N) with A_0 = [[0, 1], [−a, −c]], A_{±1} = [[0, 0], [q, 0]]
(2q cos 2t = q e^{2jt} + q e^{−2jt}); numpy's eigen-solver on that matrix; and the monodromy
route (ltp.floquet) for the exponents.
"""
import numpy as np
import pytest

import ltp

OMEGA = 2.0  # Ωp of the period π


def mathieu(a, q, c):
    """The Mathieu system from its Fourier coefficients A_w, w = -1, 0, 1."""
    A = np.zeros((3, 2, 2), complex)
    A[1] = [[0, 1], [-a, -c]]
    A[0][1, 0] = A[2][1, 0] = q
    return ltp.System.from_fourier(np.pi, A)


def closed_form_hill(a, q, c, N):
    """The Hill matrix block by block, written from the convention (independent of ltp)."""
    blocks = {0: np.array([[0, 1], [-a, -c]], complex), 1: np.array([[0, 0], [q, 0]], complex),
              -1: np.array([[0, 0], [q, 0]], complex)}
    H = np.zeros((2 * (2 * N + 1), 2 * (2 * N + 1)), complex)
    for v in range(-N, N + 1):
        for u in range(-N, N + 1):
            block = blocks.get(v - u, np.zeros((2, 2), complex)).copy()
            if v == u:
                block -= 1j * v * OMEGA * np.eye(2)
            H[2 * (v + N):2 * (v + N) + 2, 2 * (u + N):2 * (u + N) + 2] = block
    return H


def distance_modulo(x, y):
    """|x − y| with the imaginary part taken modulo jΩp (exponents are defined so)."""
    d = np.remainder(x.imag - y.imag + OMEGA / 2, OMEGA) - OMEGA / 2
    return np.hypot(x.real - y.real, d)


def test_hill_matrix_is_the_closed_form_and_has_hills_eigenvalues():
    a, q, c, N = 2.5, 0.5, 0.05, 5
    H = ltp.hill_matrix(mathieu(a, q, c), harmonics=N)
    assert H.dtype == np.complex128 and H.shape == (22, 22)
    assert np.abs(H - closed_form_hill(a, q, c, N)).max() == 0  # exact coefficients, same entries
    # Every eigenvalue of the dense Hill analysis is one of numpy's eigenvalues of this matrix.
    h = ltp.hill(mathieu(a, q, c), harmonics=N, solver="dense")
    mine = np.linalg.eigvals(H)
    assert len(h.eigenvalues) == len(mine)
    for value in h.eigenvalues:
        assert np.abs(mine - value).min() < 1e-12 * np.abs(H).max()
    # A(t) given as a callable is fitted by FFT, as ltp.hill fits it: the same matrix to round-off.
    callable_system = ltp.System.from_function(
        np.pi, lambda t: np.array([[0.0, 1.0], [-a + 2 * q * np.cos(2 * t), -c]]))
    assert np.abs(ltp.hill_matrix(callable_system, harmonics=N) - H).max() < 1e-13
    assert ltp.hill_matrix(mathieu(a, q, c), harmonics=0).shape == (2, 2)
    with pytest.raises(ltp.InputError, match="harmonics must be an integer >= 0"):
        ltp.hill_matrix(mathieu(a, q, c), harmonics=-1)


def test_eigenvectors_are_the_selected_eigenpairs():
    a, q, c, N = 2.5, 0.5, 0.05, 8  # stable, exponents -c/2 ± 1.555j: no tie between branches
    system = mathieu(a, q, c)
    h = ltp.hill(system, harmonics=N)
    H = closed_form_hill(a, q, c, N)
    V = h.eigenvectors
    assert V.dtype == np.complex128 and V.shape == ((2 * N + 1) * 2, 2)
    for k in range(2):
        v, lam = V[:, k], h.exponents[k]
        assert abs(np.linalg.norm(v) - 1) < 1e-14
        assert np.linalg.norm(H @ v - lam * v) < 1e-14 * np.linalg.norm(H, 2)  # measured 1.6e-16
        weights = np.linalg.norm(v.reshape(2 * N + 1, 2), axis=1) ** 2  # per harmonic block
        assert np.argmax(weights) == N  # block 0 (harmonic 0) carries most: the physical branch
        # The mode shape at t = 0 is the blocks summed (up to a factor).
        shape, total = h.mode_shapes[:, k], v.reshape(2 * N + 1, 2).sum(axis=0)
        assert abs(abs(np.vdot(total, shape)) - np.linalg.norm(total) * np.linalg.norm(shape)) < 1e-12


def test_eigenvectors_at_a_tie_are_eigenvectors_too():
    # The first tongue (a = 1.5, q = 2): multipliers negative, exponents on the strip edge
    # Im λ = Ωp/2, each centred between blocks 0 and -1 (a tie: both weights equal).
    N = 20
    h = ltp.hill(mathieu(1.5, 2.0, 0.05), harmonics=N)
    H = closed_form_hill(1.5, 2.0, 0.05, N)
    assert all(h.ambiguous)
    for k in range(2):
        v = h.eigenvectors[:, k]
        assert np.linalg.norm(H @ v - h.exponents[k] * v) < 1e-12 * np.linalg.norm(H, 2)  # 1e-17
        weights = np.linalg.norm(v.reshape(2 * N + 1, 2), axis=1) ** 2
        assert weights[N] >= weights.max() * (1 - 1e-9)


@pytest.mark.parametrize("reference", [True, False])
def test_hill_study_exponents_per_truncation(reference):
    a, q, c = 2.5, 0.5, 0.05
    system = mathieu(a, q, c)
    s = ltp.hill_study(system, max_harmonics=16, reference=reference)
    assert s.harmonics.dtype == np.int64 and s.matrix_size.dtype == np.int64
    assert list(s.matrix_size) == [2 * (2 * N + 1) for N in s.harmonics]
    assert s.exponents.dtype == np.complex128 and s.exponents.shape == (len(s.harmonics), 2)
    assert s.harmonics[-1] == 16 and np.array_equal(s.exponents[-1], s.last.exponents)
    # The last row against the monodromy route, within both estimates.
    f = ltp.floquet(system)
    for lam in s.exponents[-1]:
        assert np.abs(f.exponents - lam).min() <= f.error_estimate + s.last.error_estimate
    # The rows converge to it: each column's distance to the last row falls with N down to
    # round-off (measured: 1.1e-3 at N = 1, 4.3e-6 at 2, 1.6e-9 at 3, 1.5e-13 at 4, then 1e-15).
    # The last row matched ltp.floquet's exponents to 5.6e-16 (estimates 1.8e-13 and 1.8e-15).
    d = distance_modulo(s.exponents, s.exponents[-1]).max(axis=1)
    above = d[d > 1e-12]
    assert len(above) >= 3 and np.all(np.diff(above) < 0)
    assert d[list(s.harmonics).index(10)] < 1e-12


def test_hill_study_rows_follow_the_last_analysis_at_a_tie():
    # a = 1.5, q = 2: two exponents with the same Im λ = Ωp/2, ordered by round-off in each
    # analysis. The study's columns (reference, errors, exponents) follow last.exponents.
    s = ltp.hill_study(mathieu(1.5, 2.0, 0.05), max_harmonics=12)
    assert np.array_equal(s.exponents[-1], s.last.exponents)
    assert np.allclose(distance_modulo(s.exponents, s.reference[np.newaxis, :]), s.errors, rtol=1e-9, atol=1e-15)
