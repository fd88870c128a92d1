"""ltp.HarmonicTransferFunction: the HTF as an operator and its H∞/H2 norms.

References: SciPy (solve_ivp DOP853 at rtol 1e-12 and solve_discrete_lyapunov) solving the
periodic Lyapunov equation and testing the Hamiltonian's multipliers independently of ltp, and
the closed form of an LTI oscillator.
"""
import math

import numpy as np
import pytest

import ltp

A, Q, C = 1.7, 0.6, 0.08  # damped Mathieu y'' + c y' + (a − 2q cos 2t) y = u, inside a stable region
PERIOD = math.pi


def mathieu_matrices(t):
    a = np.array([[0.0, 1.0], [-(A - 2 * Q * math.cos(2 * t)), -C]])
    return a, np.array([[0.0], [1.0]]), np.array([[1.0, 0.0]])


@pytest.fixture(scope="module")
def htf():
    return ltp.HarmonicTransferFunction(ltp.scene("mathieu", a=A, q=Q, c=C))


def test_partial_and_section_shapes_dtypes_and_routes(htf):
    s = -0.05 + 0.8j
    h = htf.partial(s, orders=(-2, 2))
    assert h.dtype == np.complex128 and h.shape == (5, 1, 1)
    hill = htf.partial(s, orders=(-2, 2), route="hill")
    assert np.max(np.abs(h - hill)) < 1e-9 * np.max(np.abs(h))
    k = 2
    sec = htf.section(s, harmonics=k)
    assert sec.dtype == np.complex128 and sec.shape == (2 * k + 1, 2 * k + 1)
    # Block (v, u) is H_{v−u}(s + juΩp).
    for u in range(-k, k + 1):
        col = htf.partial(s + 1j * u * htf.omega_p, orders=(-2 * k, 2 * k))
        for v in range(-k, k + 1):
            assert sec[v + k, u + k] == col[v - u + 2 * k, 0, 0]
    with pytest.raises(ltp.InputError):
        htf.partial(s, route="shooting")


def test_h2_matches_a_scipy_periodic_lyapunov_solution(htf):
    scipy_integrate = pytest.importorskip("scipy.integrate")
    scipy_linalg = pytest.importorskip("scipy.linalg")

    # Φ(T) and W(T) = ∫ Φ(T,s) B Bᵀ Φ(T,s)ᵀ ds from P' = AP + PAᵀ + BBᵀ, P(0) = 0.
    def rhs(t, y):
        a, b, _ = mathieu_matrices(t)
        phi, p = y[:4].reshape(2, 2), y[4:].reshape(2, 2)
        return np.concatenate([(a @ phi).ravel(), (a @ p + p @ a.T + b @ b.T).ravel()])

    y0 = np.concatenate([np.eye(2).ravel(), np.zeros(4)])
    end = scipy_integrate.solve_ivp(rhs, (0, PERIOD), y0, method="DOP853", rtol=1e-12, atol=1e-14).y[:, -1]
    phi, w = end[:4].reshape(2, 2), end[4:].reshape(2, 2)
    p0 = scipy_linalg.solve_discrete_lyapunov(phi, w)  # P0 = Φ P0 Φᵀ + W

    def rhs_j(t, y):
        a, b, c = mathieu_matrices(t)
        p = y[:4].reshape(2, 2)
        return np.concatenate([(a @ p + p @ a.T + b @ b.T).ravel(), [np.trace(c @ p @ c.T)]])

    j = scipy_integrate.solve_ivp(rhs_j, (0, PERIOD), np.concatenate([p0.ravel(), [0.0]]), method="DOP853",
                                  rtol=1e-12, atol=1e-14).y[-1, -1]
    reference = math.sqrt(j / PERIOD)
    r = htf.h2()
    assert r.ok, r.failure
    assert abs(r.value - reference) < 1e-8 * reference
    assert abs(r.modal_value - reference) < 1e-8 * reference
    assert abs(r.value - reference) <= r.error_estimate + 1e-9 * reference


def test_hinf_bracket_is_confirmed_by_scipy_hamiltonian_multipliers(htf):
    scipy_integrate = pytest.importorskip("scipy.integrate")
    r = htf.hinf()
    assert r.ok, r.failure
    assert r.lower <= r.value <= r.upper and r.upper - r.lower < 1e-7 * r.value
    assert r.search_value <= r.upper

    def unit_circle_distance(gamma):
        # The bounded-real Hamiltonian (D = 0): [[A, BBᵀ/γ²], [−CᵀC, −Aᵀ]]; its monodromy by SciPy.
        def rhs(t, y):
            a, b, c = mathieu_matrices(t)
            h = np.block([[a, b @ b.T / gamma**2], [-c.T @ c, -a.T]])
            return (h @ y.reshape(4, 4)).ravel()

        phi = scipy_integrate.solve_ivp(rhs, (0, PERIOD), np.eye(4).ravel(), method="DOP853", rtol=1e-12,
                                        atol=1e-14).y[:, -1].reshape(4, 4)
        return np.min(np.abs(np.abs(np.linalg.eigvals(phi)) - 1))

    assert unit_circle_distance(r.value * (1 - 1e-4)) < 1e-8  # below the norm: on the circle
    assert unit_circle_distance(r.value * (1 + 1e-4)) > 1e-4  # above: off it


def test_closed_form_of_an_lti_oscillator():
    # y'' + c y' + k y = u as a periodic system: ‖G‖∞ = 1/(c√(k − c²/4)), ‖G‖₂ = 1/√(2ck).
    k, c = 2.0, 0.1
    a = np.array([[0.0, 1.0], [-k, -c]])
    system = ltp.System.from_fourier(2.0, a, B=np.array([[0.0], [1.0]]), C=np.array([[1.0, 0.0]]))
    h = ltp.HarmonicTransferFunction(system)
    peak = 1 / (c * math.sqrt(k - c * c / 4))
    assert abs(h.hinf().value - peak) < 1e-7 * peak
    assert abs(h.h2().value - 1 / math.sqrt(2 * c * k)) < 1e-9
    g = h.partial(0.3 + 1.1j, orders=0)[0, 0, 0]
    s = 0.3 + 1.1j
    assert abs(g - 1 / (s * s + c * s + k)) < 1e-10


def test_unstable_system_has_infinite_norms():
    h = ltp.HarmonicTransferFunction(ltp.scene("mathieu", a=1.0, q=0.3, c=0.02))
    assert math.isinf(h.hinf().value) and math.isinf(h.h2().value)


def test_h2_of_an_output_far_from_the_input_matches_scipy():
    # A chain of 6 damped Mathieu oscillators forced at the first, observed at the last: ‖G‖₂ ~ 1e-6
    # while the Gramian's largest entries are O(1), below what the Lyapunov route's error control
    # resolves. The value must come from the modal route, with an estimate that covers its error.
    # Reference: SciPy's periodic Lyapunov solution (DOP853 at rtol 1e-13, atol 1e-22).
    scipy_integrate = pytest.importorskip("scipy.integrate")
    scipy_linalg = pytest.importorskip("scipy.linalg")
    dofs, n = 6, 12
    a0, a1 = np.zeros((n, n)), np.zeros((n, n))
    for i in range(dofs):
        a0[2 * i:2 * i + 2, 2 * i:2 * i + 2] = [[0, 1], [-(1.7 + 0.53 * i), -0.05]]
        a1[2 * i + 1, 2 * i] = 0.1  # + 0.2 cos 2t in A: the coefficient of each e^{±2jt}
        if i:
            a0[2 * i + 1, 2 * i - 2] = a0[2 * i - 1, 2 * i] = 0.05
    b, c = np.zeros((n, 1)), np.zeros((1, n))
    b[1], c[0, -2] = 1, 1
    fourier = np.array([a1, a0, a1], complex)
    h = ltp.HarmonicTransferFunction(ltp.System.from_fourier(PERIOD, fourier, B=b, C=c))
    r = h.h2()

    def matrix(t):
        return a0 + 2 * a1 * math.cos(2 * t)

    def rhs(t, y):
        a, phi, p = matrix(t), y[:n * n].reshape(n, n), y[n * n:].reshape(n, n)
        return np.concatenate([(a @ phi).ravel(), (a @ p + p @ a.T + b @ b.T).ravel()])

    end = scipy_integrate.solve_ivp(rhs, (0, PERIOD), np.concatenate([np.eye(n).ravel(), np.zeros(n * n)]),
                                    method="DOP853", rtol=1e-13, atol=1e-22).y[:, -1]
    p0 = scipy_linalg.solve_discrete_lyapunov(end[:n * n].reshape(n, n), end[n * n:].reshape(n, n))

    def rhs_j(t, y):
        a, p = matrix(t), y[:n * n].reshape(n, n)
        return np.concatenate([(a @ p + p @ a.T + b @ b.T).ravel(), [(c @ p @ c.T)[0, 0]]])

    j = scipy_integrate.solve_ivp(rhs_j, (0, PERIOD), np.concatenate([p0.ravel(), [0.0]]), method="DOP853",
                                  rtol=1e-13, atol=1e-22).y[-1, -1]
    reference = math.sqrt(j / PERIOD)
    assert r.ok, r.failure
    assert abs(r.value - reference) < 1e-9 * reference
    assert abs(r.value - reference) <= r.error_estimate + 1e-12 * reference
    assert "norm_unresolved" in r.diagnostic_codes


def test_zeros_of_an_lti_system_match_scipy():
    # A 3-state SISO system with D = 0.25 as a periodic one (T = 1.3): its zeros are those of
    # C(sI − A)⁻¹B + D. Reference: scipy.signal.ss2zpk. Constant coefficients put every zero's
    # direction on harmonic 0, so `centred` is the zero itself and `zeros` its strip
    # representative.
    scipy_signal = pytest.importorskip("scipy.signal")
    a = np.array([[-0.3, 2.0, 0.1], [-2.0, -0.3, 0.4], [0.2, 0.0, -0.9]])
    b = np.array([[1.0], [0.5], [-1.0]])
    c = np.array([[0.7, -1.2, 0.4]])
    d = np.array([[0.25]])
    period = 1.3
    h = ltp.HarmonicTransferFunction(ltp.System.from_fourier(period, a, B=b, C=c, D=d))
    r = h.zeros()
    assert r.ok, r.failure
    assert r.route == "hill" and r.check_route == "zero-dynamics"
    for name in ("zeros", "centred", "hill_values", "check_values"):
        assert getattr(r, name).dtype == np.complex128 and getattr(r, name).shape == (3,)
    for name in ("error_estimates", "truncation_changes", "centroids", "check_error_estimates"):
        assert getattr(r, name).dtype == np.float64 and getattr(r, name).shape == (3,)
    reference = scipy_signal.ss2zpk(a, b, c, d)[0]
    omega = 2 * math.pi / period
    for z in reference:
        assert np.min(np.abs(r.centred - z)) < 1e-10
        strip = complex(z.real, math.remainder(z.imag, omega))
        assert np.min(np.abs(r.zeros - strip)) < 1e-10
    assert np.all(np.abs(r.zeros.imag) <= omega / 2)
    assert np.all(r.error_estimates < 1e-8)
    assert np.max(np.abs(r.check_values - r.centred)) < 1e-8


def test_zeros_of_a_mimo_lti_system_match_the_rosenbrock_pencil():
    # 2 inputs, 2 outputs, 4 states, D = 0 with CB invertible: two zeros, checked by the
    # relative-degree-one route. Reference: the finite generalized eigenvalues of the Rosenbrock
    # pencil [[A, B], [C, 0]] − s diag(I, 0) by scipy.linalg.eig.
    scipy_linalg = pytest.importorskip("scipy.linalg")
    a = np.array([[-0.5, 1.0, 0.0, 0.2], [-1.0, -0.5, 0.3, 0.0], [0.0, 0.1, -1.2, 2.0],
                  [0.4, 0.0, -2.0, -1.2]])
    b = np.array([[1.0, 0.0], [0.0, 0.5], [0.3, 1.0], [0.0, -0.4]])
    c = np.array([[1.0, 0.2, 0.0, 0.5], [0.0, 1.0, -0.3, 0.0]])
    pencil = np.block([[a, b], [c, np.zeros((2, 2))]])
    e = np.diag([1.0, 1.0, 1.0, 1.0, 0.0, 0.0])
    values = scipy_linalg.eig(pencil, e, right=False)
    reference = values[np.isfinite(values) & (np.abs(values) < 1e8)]
    assert len(reference) == 2
    h = ltp.HarmonicTransferFunction(ltp.System.from_fourier(2.0, a, B=b, C=c))
    r = h.zeros()
    assert r.ok, r.failure
    assert r.check_route == "relative-degree-one" and r.zeros.shape == (2,)
    for z in reference:
        assert np.min(np.abs(r.centred - z)) < 1e-9


def test_zeros_refuse_non_square_systems():
    a = np.array([[0.0, 1.0], [-2.0, -0.1]])
    system = ltp.System.from_fourier(2.0, a, B=np.array([[0.0], [1.0]]), C=np.eye(2))
    h = ltp.HarmonicTransferFunction(system)
    with pytest.raises(ltp.InputError, match="square"):
        h.zeros()
    with pytest.raises(ltp.InputError):
        ltp.HarmonicTransferFunction(ltp.scene("mathieu", a=A, q=Q, c=C)).zeros(tol=0)
