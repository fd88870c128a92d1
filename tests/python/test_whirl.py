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
