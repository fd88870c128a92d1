"""ltp.simulate and ltp.identify on numpy arrays.

References: (1) a rig written here in numpy — the scalar periodic system of tests/support/rig.h,
x' = −a x + (1 + β cos θ) u, y = (1 + γ cos θ) x, whose steady state under u = cos ωt at a
constant speed is a sum of lines with closed-form amplitudes, evaluated directly (no
integration); its rotor runs 1 % fast and a tacho pulse marks θ = 0. (2) `ltp simulate` and
`ltp identify` on the same test: the Python door gives the command's numbers.
"""
import json
import os
import subprocess

import numpy as np
import pytest

import ltp

A, BETA, GAMMA = 0.5, 0.6, 0.4


def closed_form(f_hz, speed):
    """H_z, z = -2..2, of the rig at excitation f_hz and rotor speed (rad/s)."""
    w = 2 * np.pi * f_hz
    G = lambda nu: 1 / (A + 1j * nu)  # noqa: E731
    bg = BETA * GAMMA / 4
    return np.array([bg * G(w - speed), BETA / 2 * G(w - speed) + GAMMA / 2 * G(w),
                     G(w) + bg * (G(w + speed) + G(w - speed)),
                     BETA / 2 * G(w + speed) + GAMMA / 2 * G(w), bg * G(w + speed)])


def rig_record(f_hz, speed, theta0=0.4, samples=1300, dt=2 / 64, output_delay=0.0):
    """Time, input, output and tacho of the rig's steady state: u = cos ωt, lines at ωt + zθ;
    the output sampled output_delay (s) late."""
    t = np.arange(samples) * dt
    theta = theta0 + speed * t
    H = closed_form(f_hz, speed)
    w = 2 * np.pi * f_hz
    # u = (e^{jωt} + c.c.)/2, so U = 1/2 and y = Σ_z (U H_z e^{j(ωt + zθ)} + c.c.).
    late, theta_late = t - output_delay, theta - speed * output_delay
    y = sum(np.real(H[k] * np.exp(1j * (w * late + (k - 2) * theta_late))) for k in range(5))
    edge = 0.5  # smoothstep edges of the tacho, rising through mid-level at θ = 0 (mod 2π)
    x = np.mod(theta + np.pi, 2 * np.pi) - np.pi
    step = lambda s: np.clip(s, 0, 1) ** 2 * (3 - 2 * np.clip(s, 0, 1))  # noqa: E731
    tacho = step(x / edge + 0.5) * (1 - step((x - 1.5) / edge + 0.5))
    return t, np.cos(w * t), y, tacho


def test_identify_on_a_tacho_meets_the_closed_form():
    speed = 1.01 * np.pi  # the model's T = 2 s, the rotor 1 % fast
    freqs = [0.1373, 0.6121]
    records = [rig_record(f, speed) for f in freqs]
    r = ltp.identify([x[0] for x in records], [x[1] for x in records], [x[2] for x in records],
                     tacho=[x[3] for x in records])
    assert r.H.shape == (2, 5) and list(r.orders) == [-2, -1, 0, 1, 2]
    np.testing.assert_allclose(r.excitation_hz, freqs, rtol=1e-10)
    np.testing.assert_allclose(r.speed, speed, rtol=1e-7)
    assert r.measured_speed is not None and abs(r.measured_speed["mean"] / speed - 1) < 1e-7
    assert abs(r.period * speed / (2 * np.pi) - 1) < 1e-7  # the period comes from the tacho
    for k, f in enumerate(freqs):
        truth = closed_form(f, speed)
        assert np.abs(r.H[k] - truth).max() < 1e-8 * np.abs(truth).max()
    # Read at the model's speed instead, the bias is large and named.
    blind = ltp.identify([x[0] for x in records], [x[1] for x in records], [x[2] for x in records],
                         period=2.0)
    assert np.abs(blind.H[0] - closed_form(freqs[0], speed)).max() > 1e-2
    assert "speed_off_model" in blind.diagnostic_codes


def test_an_output_delay_is_undone():
    speed = 1.01 * np.pi
    freqs = [0.1373, 0.6121]
    records = [rig_record(f, speed, output_delay=0.07) for f in freqs]  # 2.2 samples late
    args = ([x[0] for x in records], [x[1] for x in records], [x[2] for x in records])
    tacho = [x[3] for x in records]
    late = ltp.identify(*args, tacho=tacho)
    fixed = ltp.identify(*args, tacho=tacho, output_delay=0.07)
    for k, f in enumerate(freqs):
        truth = closed_form(f, speed)
        assert np.abs(late.H[k] - truth).max() > 1e-2 * np.abs(truth).max()
        assert np.abs(fixed.H[k] - truth).max() < 1e-8 * np.abs(truth).max()
    with pytest.raises(ValueError, match="output_delay"):
        ltp.identify(*args, tacho=tacho, output_delay=float("nan"))


def test_python_equals_the_command():
    system = ltp.scene("mathieu", a=2, c=0.2, q=0.3)
    s = ltp.simulate(system, "0.05:0.4:0.05", periods=16, noise=30, seed=3)
    r = ltp.identify(s.time, s.input, s.output, period=s.period, excitation_hz=s.excitation_hz)
    binary = os.environ["LTP_BINARY"]
    csv = os.path.join(os.environ.get("TMPDIR", "/tmp"), f"ltp-py-identify-{os.getpid()}.csv")
    subprocess.run([binary, "simulate", "mathieu", "--set", "a=2", "--set", "c=0.2", "--set",
                    "q=0.3", "--excitation", "stepsine:0.05:0.4:0.05", "--periods", "16",
                    "--noise", "30", "--seed", "3", "--out", csv], check=True, capture_output=True)
    out = subprocess.run([binary, "identify", csv, "--json"], check=True, capture_output=True,
                         text=True).stdout
    os.remove(csv)
    j = json.loads(out)
    assert len(j["frequencies"]) == len(r.excitation_hz)
    for k, f in enumerate(j["frequencies"]):
        assert abs(f["excitation_hz"] - r.excitation_hz[k]) < 1e-12 * f["excitation_hz"]
        for h in f["H"]:
            z = list(r.orders).index(h["z"])
            # The CSV keeps 15 digits: the estimates agree to that, not to the last bit.
            scale = np.abs(r.H[k]).max()
            assert abs(complex(h["re"], h["im"]) - r.H[k, z]) < 1e-11 * scale
            assert abs(h["bound_95"] - r.bound[k, z]) < 1e-6 * h["bound_95"]


def test_bad_arrays_are_refused():
    t, u, y, _ = rig_record(0.2, np.pi)
    with pytest.raises(ltp.InputError, match="period"):
        ltp.identify(t, u, y)
    with pytest.raises(ltp.InputError, match="same number of records"):
        ltp.identify([t, t], [u], [y, y], period=2.0)
    with pytest.raises(ltp.InputError, match="differ in length"):
        ltp.identify(t, u[:-1], y, period=2.0)
    with pytest.raises(ltp.InputError):
        ltp.identify(t, u + 1j, y, period=2.0)
    with pytest.raises(ltp.InputError, match="not finite"):
        ltp.identify(t, np.where(t > 3, np.nan, u), y, period=2.0)
    with pytest.raises(ltp.InputError, match="excitation"):
        ltp.simulate(ltp.scene("mathieu", a=2, c=0.2, q=0.3), [0.1], excitation="chirp")
