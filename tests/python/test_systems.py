"""Systems made in Python: numpy Fourier coefficients, a Python callable A(t), samples.

References: the built-in `mathieu` scene (y'' + c y' + (a − 2q cos 2t) y = u, period π, an
exact Fourier series in the library, scenes/mathieu.yaml); the same coefficients given from
numpy, and a callable A(t) of the same equation, must give its exponents within the error
estimates. Liouville's formula: Re λ1 + Re λ2 = mean tr A = −c exactly.
"""
import threading
import time

import numpy as np
import pytest

import ltp

A_, Q_, C_ = 1.5, 2.0, 0.05


def mathieu_coefficients(a=A_, q=Q_, c=C_):
    """A_w for w = -1, 0, 1 of A(t) = [[0, 1], [-a + 2q cos 2t, -c]] (Ωp = 2)."""
    coefficients = np.zeros((3, 2, 2), complex)
    coefficients[1] = [[0, 1], [-a, -c]]
    coefficients[0][1, 0] = coefficients[2][1, 0] = q  # 2q cos 2t = q e^{2jt} + q e^{-2jt}
    return coefficients


def mathieu_A(t, a=A_, q=Q_, c=C_):
    return np.array([[0.0, 1.0], [-a + 2 * q * np.cos(2 * t), -c]])


def test_fourier_input_equals_the_builtin_scene():
    mine = ltp.System.from_fourier(np.pi, mathieu_coefficients())
    builtin = ltp.scene("mathieu", a=A_, q=Q_, c=C_)
    assert mine.form == "fourier" and mine.states == 2 and mine.period == np.pi
    assert np.allclose(mine.A(0.3), mathieu_A(0.3), rtol=0, atol=1e-15)
    a, b = ltp.floquet(mine), ltp.floquet(builtin)
    assert a.ok and a.verdict == "unstable"
    assert np.abs(a.exponents - b.exponents).max() <= 2 * max(a.error_estimate, b.error_estimate)
    assert abs(a.exponents.real.sum() + C_) < 1e-10  # Liouville
    h = ltp.hill(mine)
    assert h.ok and np.abs(np.sort_complex(h.exponents) - np.sort_complex(a.exponents)).max() < 1e-9


def test_callable_equals_fourier_and_what_it_costs():
    fourier = ltp.System.from_fourier(np.pi, mathieu_coefficients())
    callable_system = ltp.System.from_function(np.pi, mathieu_A)
    assert callable_system.form == "function"

    def best_of(runs, work):
        best = float("inf")
        for _ in range(runs):
            start = time.perf_counter()
            result = work()
            best = min(best, time.perf_counter() - start)
        return best, result

    t_fourier, f = best_of(3, lambda: ltp.floquet(fourier))
    t_callable, c = best_of(3, lambda: ltp.floquet(callable_system))
    assert c.ok and f.ok
    assert np.abs(c.exponents - f.exponents).max() <= 10 * max(c.error_estimate, f.error_estimate, 1e-13)
    assert abs(c.exponents.real.sum() + C_) < 1e-10
    h = ltp.hill(callable_system)  # fitted by FFT from samples of the callable
    assert np.abs(np.sort_complex(h.exponents) - np.sort_complex(f.exponents)).max() < 1e-9
    print(f"\nmathieu, ltp.floquet: Fourier input {t_fourier * 1e3:.2f} ms ({f.rhs_evals} evaluations "
          f"of A), Python callable {t_callable * 1e3:.2f} ms ({c.rhs_evals} calls), "
          f"{t_callable / t_fourier:.0f}x")
    # What the docstring promises: the callable costs its calls, not a pathological slowdown.
    per_call = t_callable / c.rhs_evals
    assert per_call < 200e-6, f"{per_call * 1e6:.1f} µs per call of A(t)"


def test_callable_with_inputs_outputs_and_labels():
    b = np.array([[0.0], [1.0]])
    cmat = np.array([[1.0, 0.0]])
    s = ltp.System.from_function(np.pi, lambda t: mathieu_A(t, a=2, q=0.5, c=0.2), B=b, C=cmat)
    s = s.with_labels(inputs=["force"], outputs=["x"])
    assert (s.inputs, s.outputs, s.input_names, s.output_names) == (1, 1, ["force"], ["x"])
    r = ltp.pfrf(s, "0.1:0.3:0.1", input="force", output="x", orders="-1:1", route="modal")
    reference = ltp.pfrf(ltp.scene("mathieu", a=2, q=0.5, c=0.2), "0.1:0.3:0.1", orders="-1:1", route="modal")
    assert r.ok and r.H.shape == (3, 3)
    assert np.abs(r.H - reference.H).max() < 1e-7 * np.abs(reference.H).max()


def test_callable_errors_are_raised_by_the_analysis():
    state = {"fail": False}

    def fails_later(t):
        if state["fail"]:
            raise KeyError("failure inside A(t)")
        return mathieu_A(t)

    s = ltp.System.from_function(np.pi, fails_later)
    state["fail"] = True
    with pytest.raises(KeyError, match="failure inside A"):
        ltp.floquet(s)
    # A callable that goes wrong inside the period is caught by the checks at construction
    # (bounded, periodic), as a scene file is when it is read.
    with pytest.raises(ltp.InputError, match=r"A\(t\) must return a real 2×2 array, got shape \(3,\)"):
        ltp.System.from_function(np.pi, lambda t: mathieu_A(t) if t < 0.1 else np.zeros(3))
    with pytest.raises(ZeroDivisionError):
        ltp.System.from_function(1.0, lambda t: 1 / 0)  # A(0) is called to learn the size


def test_piecewise_constant_samples():
    # Meissner's equation x'' + (a ± b) x = 0 on two halves of the period: the built-in scene is
    # a function with a jump; the same as two samples is exact (products of matrix exponentials).
    a, b, period = 1.0, 0.5, 2.0
    k_plus, k_minus = a + b, a - b
    samples = np.array([[[0, 1], [-k_plus, 0]], [[0, 1], [-k_minus, 0]]], float)
    s = ltp.System.from_samples(period, [0.0, period / 2], samples)
    assert s.form == "piecewise-constant"
    r = ltp.floquet(s)
    # Closed form: tr Φ = 2 cos(√k+ T/2) cos(√k− T/2) − (√k+/√k− + √k−/√k+) sin sin.
    wp, wm = np.sqrt(k_plus) * period / 2, np.sqrt(k_minus) * period / 2
    trace = 2 * np.cos(wp) * np.cos(wm) - (np.sqrt(k_plus / k_minus) + np.sqrt(k_minus / k_plus)) * np.sin(wp) * np.sin(wm)
    assert abs(r.multipliers.sum().real - trace) < 1e-12
    assert abs(np.trace(r.monodromy) - trace) < 1e-12


def test_floquet_result_fields_are_numpy_arrays():
    r = ltp.floquet(ltp.scene("mathieu", a=A_, q=Q_, c=C_))
    n = r.states
    for name in ["exponents", "multipliers", "log_multipliers", "frequencies_hz", "damping_ratios",
                 "branches", "segment_times", "sample_times"]:
        assert isinstance(getattr(r, name), np.ndarray), name
    assert r.exponents.dtype == complex and r.exponents.shape == (n,)
    H = (r.mode_harmonics.shape[0] - 1) // 2
    assert r.mode_harmonics.shape == (2 * H + 1, n, n) and list(r.mode_harmonic_orders) == list(range(-H, H + 1))
    assert r.mode_samples.shape == (len(r.sample_times), n, n)
    # The mode shapes at t = 0 from their harmonics equal the sampled ones.
    xi0 = r.mode_harmonics.sum(axis=0)
    assert np.abs(xi0 - r.mode_samples[0]).max() < 1e-9 * np.abs(xi0).max()
    assert np.abs(r.mode_matrix(0.0) - r.mode_samples[0]).max() < 1e-9
    assert r.monodromy.shape == (n, n) and isinstance(r.diagnostics, list)
    assert r.error_estimate > 0 and r.verdict in ("stable", "unstable", "marginal", "failed")


def test_the_gil_is_released_during_long_work():
    # Another Python thread keeps counting while a 40-state analysis runs: it would stall if the
    # analysis held the GIL.
    system = ltp.scene("tower-rotor")
    ticks, done = [0], threading.Event()

    def count():
        while not done.is_set():
            ticks[0] += 1
            time.sleep(0.001)

    counter = threading.Thread(target=count)
    counter.start()
    start = time.perf_counter()
    before = ticks[0]
    ltp.pfrf(system, "0:20:0.5", input="Fz_tip", output="z_tip")
    elapsed = time.perf_counter() - start
    during = ticks[0] - before
    done.set()
    counter.join()
    assert elapsed > 0.05
    assert during >= 0.2 * elapsed / 0.001 * 0.1, f"{during} ticks in {elapsed:.2f} s"


def test_scenes_and_scene_files(tmp_path):
    names = [s["name"] for s in ltp.scenes()]
    assert "tower-rotor" in names and "mathieu" in names
    rotor = ltp.scene("rotor", blades=3, Omega="2*pi/3")
    assert rotor.parameters["blades"] == 3 and abs(rotor.parameters["Omega"] - 2 * np.pi / 3) < 1e-15
    assert rotor.rotor_speed is not None
    yaml = tmp_path / "spring.yaml"
    yaml.write_text("name: spring\nperiod: 1\nparameters: {k: 4}\n"
                    "state_space:\n  A: [[\"0\", \"1\"], [\"-k*(1 + 0.1*cos(2*pi*t))\", \"-0.1\"]]\n")
    s = ltp.scene(str(yaml), k=9)
    assert s.scene == "spring" and s.parameters == {"k": 9.0}
    assert np.allclose(s.A(0.0), [[0, 1], [-9.9, -0.1]])


def test_from_fourier_docstring_example_is_the_scene():
    # The docstring's example, run as written: the same A(t) as the built-in scene (closed form
    # A(t) of mathieu_A above), so its sign convention is the scene's.
    doc = ltp.System.from_fourier.__doc__
    example = doc[doc.index("A = np.zeros"):doc.index("system = ltp")].replace("\n    ", "\n")
    scope = {"np": np, "a": A_, "q": Q_, "c": C_}
    exec(example, scope)
    system = ltp.System.from_fourier(np.pi, scope["A"])
    scene = ltp.scene("mathieu", a=A_, q=Q_, c=C_)
    for t in (0.0, 0.4, 1.3):
        assert np.abs(system.A(t) - mathieu_A(t)).max() < 1e-15
        assert np.abs(system.A(t) - scene.A(t)).max() < 1e-15  # and the built-in scene's A(t)


def test_study_and_chart_columns_have_numpy_dtypes():
    s = ltp.hill_study(ltp.scene("mathieu"), max_harmonics=4)
    assert s.harmonics.dtype == np.int64 and list(s.harmonics) == [1, 2, 3, 4]
    assert s.matrix_size.dtype == np.int64 and list(s.matrix_size) == [6, 10, 14, 18]
    # Integers are int64, text per mode a numpy str array (as chart.verdicts); the values from
    # their definitions (orders zmin..zmax, harmonics -H..H, the branch m of λ = Log ρ/T + jmΩp).
    system = ltp.scene("mathieu", a=A_, q=Q_, c=C_)
    f = ltp.floquet(system)
    assert f.branches.dtype == np.int64 and ltp.hill(system).branches.dtype == np.int64
    assert np.allclose(f.exponents, f.log_multipliers / f.period + 1j * f.branches * 2.0, atol=1e-12)
    H = (len(f.mode_harmonic_orders) - 1) // 2
    assert f.mode_harmonic_orders.dtype == np.int64 and list(f.mode_harmonic_orders) == list(range(-H, H + 1))
    assert isinstance(f.mode_descriptions, np.ndarray) and f.mode_descriptions.dtype.kind == "U"
    assert f.mode_descriptions.shape == (2,)
    p = ltp.pfrf(system, "0.1:0.2:0.1", orders="-2:3")
    assert p.orders.dtype == np.int64 and list(p.orders) == [-2, -1, 0, 1, 2, 3]
    assert all(r["points"].dtype == np.int64 for r in p.routes)
    d = ltp.simulate(ltp.scene("mathieu", c=0.3), "0.1:0.2:0.1")  # stable: a steady state
    i = ltp.identify(d.time, d.input, d.output, period=np.pi, orders="-1:1")
    assert i.orders.dtype == np.int64 and list(i.orders) == [-1, 0, 1]
    c = ltp.chart(ltp.scene("mathieu"), "a=0:1:0.5")
    assert isinstance(c.verdicts, np.ndarray) and c.verdicts.dtype.kind == "U"
    assert set(c.verdicts) <= {"stable", "marginal", "unstable", "failed"}


def test_hill_study_gives_the_exponents_of_every_truncation():
    # Per-N exponents (a convergence table for a paper): each row's exponents, in the
    # reference's order, are at the row's error from the monodromy route's (modulo jΩp).
    scene = ltp.scene("mathieu", a=A_, q=Q_, c=C_)
    s = ltp.hill_study(scene, max_harmonics=12)
    ref = ltp.floquet(scene, integrator="dopri5", tol=1e-12).exponents  # the study's reference
    omega = 2.0  # Ωp of the period π
    assert s.exponents.shape == s.errors.shape == (len(s.harmonics), 2)
    for row, errors in zip(s.exponents, s.errors):
        for lam, r, err in zip(row, ref, errors):
            d = np.hypot(lam.real - r.real, np.remainder(lam.imag - r.imag + omega / 2, omega) - omega / 2)
            assert abs(d - err) <= 1e-12 + 1e-9 * err
    assert s.max_error[-1] < 1e-9  # and they converge to it
