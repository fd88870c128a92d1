"""Forward and backward whirl of rotor modes (FloquetResult.forward_whirl) against an independent
route: the Jeffcott rotor in its rotating frame is time-invariant, and each eigenvector's (a, b)
gives the fixed-frame circles |a + jb| turning at Im s + Ω and |a − jb| at −Im s + Ω."""
import numpy as np
import pytest

import ltp


def rotating_frame_shares(m, k1, k2, c, omega):
    J = np.array([[0.0, -1.0], [1.0, 0.0]])
    K = np.diag([k1, k2]) - m * omega**2 * np.eye(2) + c * omega * J
    D = 2 * m * omega * J + c * np.eye(2)
    A = np.block([[np.zeros((2, 2)), np.eye(2)], [-K / m, -D / m]])
    s, v = np.linalg.eig(A)
    shares = []
    for k in range(4):
        a, b = v[0, k], v[1, k]
        plus, minus = abs(a + 1j * b) ** 2, abs(a - 1j * b) ** 2
        forward = (plus if s[k].imag + omega > 0 else 0) + (minus if -s[k].imag + omega > 0 else 0)
        shares.append(forward / (plus + minus))
    return np.sort(shares)


@pytest.mark.parametrize("omega", [0.5, 1.6])
def test_jeffcott_whirl_equals_the_rotating_frame(omega):
    r = ltp.floquet(ltp.scene("jeffcott", c=0.05, Omega=omega), tol=1e-11)
    assert r.forward_whirl.dtype == np.float64 and r.forward_whirl.shape == (4,)
    want = rotating_frame_shares(1.0, 1.0, 1.5, 0.05, omega)
    assert np.allclose(np.sort(r.forward_whirl), want, atol=1e-9, rtol=0)


def test_whirl_pairs_by_name_on_a_numpy_model():
    # The Jeffcott rotor again, from its matrices: K(t) = R diag(k1, k2) Rᵀ (period π/Ω).
    omega, k1, k2, c = 0.5, 1.0, 1.5, 0.05
    k0, kd = (k1 + k2) / 2, (k1 - k2) / 2
    K = np.zeros((3, 2, 2), dtype=complex)  # harmonics −1, 0, 1 of e^{j 2Ω t}
    K[1] = k0 * np.eye(2)
    K[2] = kd / 2 * np.array([[1, -1j], [-1j, -1]])
    K[0] = K[2].conj()
    s = ltp.System.from_second_order(np.pi / omega, np.eye(2), K, D=c * np.eye(2))
    assert ltp.floquet(s).forward_whirl is None  # no pairs declared
    s = s.with_labels(states=["x", "y", "vx", "vy"], whirl_pairs=[("x", "y")])
    s = s.with_rotor_speed(omega)
    got = np.sort(ltp.floquet(s, tol=1e-11).forward_whirl)
    assert np.allclose(got, rotating_frame_shares(1.0, k1, k2, c, omega), atol=1e-9, rtol=0)
    with pytest.raises(ValueError, match="not a state name"):
        s.with_labels(whirl_pairs=[("x", "z")])


def test_unbalance_orbits_equal_the_rotating_frame():
    """ltp.HarmonicTransferFunction.orbits against the rotating frame: the force (cos ωt, sin ωt)
    is Re((1, −j) e^{jνt}) there (ν = ω − Ω), the response Re(Q e^{jνt}); back in the fixed
    frame order 0 is a circle |Q1 + jQ2|/2 turning at ω, order −1 one of |Q1 − jQ2|/2 at 2Ω − ω."""
    m, k1, k2, c, Omega, omega = 1.0, 1.0, 1.5, 0.05, 0.5, 1.3
    J = np.array([[0.0, -1.0], [1.0, 0.0]])
    K = np.diag([k1, k2]) - m * Omega**2 * np.eye(2) + c * Omega * J
    D = 2 * m * Omega * J + c * np.eye(2)
    nu = omega - Omega
    Q = np.linalg.solve(K + 1j * nu * D - nu**2 * m * np.eye(2), [1, -1j])
    h = ltp.HarmonicTransferFunction(ltp.scene("jeffcott", c=c, Omega=Omega, k1=k1, k2=k2, m=m))
    o = h.orbits(omega, [1, -1j], x="x", y="y", orders=(-2, 2))
    assert o["order"].dtype == np.int64 and list(o["order"]) == [-2, -1, 0, 1, 2]
    assert o["x"].dtype == np.complex128 and o["forward"].dtype == np.float64
    assert np.allclose(o["frequency"], omega + 2 * Omega * o["order"], rtol=0, atol=1e-15)
    forward = [0, 0, abs(Q[0] + 1j * Q[1]) / 2, 0, 0]
    backward = [0, abs(Q[0] - 1j * Q[1]) / 2, 0, 0, 0]  # 2Ω − ω < 0: turning against the rotor
    assert np.allclose(o["forward"], forward, rtol=0, atol=1e-8)
    assert np.allclose(o["backward"], backward, rtol=0, atol=1e-8)
    with pytest.raises(ltp.InputError):
        h.orbits(omega, [1, -1j, 0])
