"""Models as finite-element packages give them: System.from_second_order, physical units.
References: the first-order Fourier form of the same equation (another ltp route) and SciPy's
solve_ivp (DOP853, rtol 1e-12) on the n x n matrix ODE, an independent integrator."""
import numpy as np
import pytest

import ltp
from fe_rotor import fe_rotor


def test_second_order_mathieu_equals_its_first_order_form():
    # y'' + c y' + (a - 2q cos 2t) y = 0, period pi (from_fourier's docstring example).
    a, q, c = 1.5, 0.5, 0.05
    K = np.zeros((3, 1, 1), complex)
    K[1, 0, 0], K[0, 0, 0], K[2, 0, 0] = a, -q, -q
    second = ltp.System.from_second_order(np.pi, M=[[1.0]], K=K, D=[[c]])
    A = np.zeros((3, 2, 2), complex)
    A[1] = [[0, 1], [-a, -c]]
    A[0][1, 0] = A[2][1, 0] = q
    first = ltp.System.from_fourier(np.pi, A)
    assert np.allclose(second.fourier_A, first.fourier_A, atol=1e-15)
    r1, r2 = ltp.floquet(second), ltp.floquet(first)
    assert np.allclose(np.sort_complex(r1.exponents), np.sort_complex(r2.exponents), atol=1e-12)


def scipy_max_real_exponent(period, A):
    from scipy.integrate import solve_ivp
    n = A.shape[1]
    w = 2 * np.pi / period
    a0, ac, as_ = A[1].real, 2 * A[2].real, -2 * A[2].imag

    def rhs(t, y):
        return ((a0 + ac * np.cos(w * t) + as_ * np.sin(w * t)) @ y.reshape(n, n)).ravel()

    sol = solve_ivp(rhs, (0, period), np.eye(n).ravel(), method="DOP853", rtol=1e-12, atol=1e-14)
    rho = np.linalg.eigvals(sol.y[:, -1].reshape(n, n))
    return np.log(np.abs(rho)).max() / period


def test_finite_element_rotor_in_si_units_matches_scipy():
    # 40 states, stiffness entries to 1e9 N/m and slopes in rad: ‖A‖_F = 8e9 against a
    # spectral radius of 2.6e4. Unbalanced, ltp reported an estimate of 2e-4 1/s; the states
    # are now balanced inside the analysis.
    pytest.importorskip("scipy")
    period, M, D, K = fe_rotor(4)
    system = ltp.System.from_second_order(period, M=M, K=K, D=D)
    assert system.states == 40
    r = ltp.floquet(system)
    assert r.ok and r.verdict == "stable"
    assert "states_balanced" in r.diagnostic_codes
    assert r.error_estimate < 1e-6
    reference = scipy_max_real_exponent(period, system.fourier_A)
    assert abs(r.max_real_exponent - reference) <= r.error_estimate



def test_modes_below_a_frequency_match_the_full_analysis():
    # The same 40-state rotor, only the modes of the mean A below the 12th smallest |λ|: the
    # reference is the full analysis (no projection), whose own estimate is far smaller.
    period, M, D, K = fe_rotor(4)
    system = ltp.System.from_second_order(period, M=M, K=K, D=D)
    moduli = np.sort(np.abs(np.linalg.eigvals(system.fourier_A[system.fourier_A.shape[0] // 2].real)))
    cutoff_hz = 0.5 * (moduli[11] + moduli[12]) / (2 * np.pi)
    full = ltp.floquet(system)
    r = ltp.floquet(system, modes_below=cutoff_hz)
    assert r.ok and r.reduction["states"] == 12 and r.reduction["check_states"] > 12
    assert len(r.reduction["dropped_mean_eigenvalues"]) == 28
    assert r.mode_samples.shape[1:] == (40, 12)  # shapes in the given states
    w = 2 * np.pi / period
    for e, est in zip(r.exponents, r.exponent_error_estimates):
        d = np.hypot((full.exponents - e).real,
                     np.remainder((full.exponents - e).imag + w / 2, w) - w / 2).min()
        assert d <= est - full.error_estimate
    assert ltp.floquet(system).reduction is None
