"""Bad arguments raise ValueError (ltp.InputError) with the library's one-line message, and
every public name has help text.

The messages are the library's: each names the argument and what was expected, so a user can
fix the call from the message alone.
"""
import inspect
import warnings

import numpy as np
import pytest

import ltp

MATHIEU = ltp.scene("mathieu")


@pytest.mark.parametrize("call,message", [
    (lambda: ltp.scene("no-such-scene"), r"unknown scene 'no-such-scene': not a built-in \(mathieu"),
    (lambda: ltp.scene("mathieu", nope=1), r"nope"),
    (lambda: ltp.scene("mathieu", a="1+"), r"a"),
    (lambda: ltp.floquet(MATHIEU, integrator="euler"), r"unknown integrator 'euler' \(auto, dopri5"),
    (lambda: ltp.floquet(MATHIEU, tol=0.0), r"rel_tol"),
    (lambda: ltp.floquet(MATHIEU, segments=0), r"segments must be a positive integer or 'auto', got 0"),
    (lambda: ltp.floquet(MATHIEU, multipliers="qr"), r"multipliers must be 'schur' or 'single-shot'"),
    (lambda: ltp.hill(MATHIEU, harmonics=-2), r"harmonics must be a positive integer or 'auto'"),
    (lambda: ltp.hill(MATHIEU, solver="magic"), r"solver must be 'auto', 'dense' or 'structured'"),
    (lambda: ltp.pfrf(MATHIEU, "1:0:0.1"), r"freq: F1 must be >= F0, got '1:0:0.1'"),
    (lambda: ltp.pfrf(MATHIEU, "a:b:c"), r"freq F0: 'a' is not a finite number"),
    (lambda: ltp.pfrf(MATHIEU, [0.1, np.nan]), r"freq: frequencies must be finite"),
    (lambda: ltp.pfrf(MATHIEU, "0:1:0.1", input="nope"), r"input 'nope' is not one of the system's inputs: 0 \(u\)"),
    (lambda: ltp.pfrf(MATHIEU, "0:1:0.1", output=3), r"output '3' is not one of the system's outputs"),
    (lambda: ltp.pfrf(MATHIEU, "0:1:0.1", route="fast"), r"route must be auto, modal, htf, shooting, time or all"),
    (lambda: ltp.pfrf(MATHIEU, "0:1:0.1", orders="3:-3"), r"orders: ZMIN must be <= ZMAX"),
    (lambda: ltp.snapshot(MATHIEU, "0:1:0.1"), r"give exactly one of angle= \(degrees\) and time= \(s\)"),
    (lambda: ltp.snapshot(MATHIEU, "0:1:0.1", angle=10), r"no rotor speed: give time= instead of angle="),
    (lambda: ltp.chart(MATHIEU, "a=0:1"), r"a=0:1"),
    (lambda: ltp.chart(MATHIEU, "zz=0:1:0.5"), r"zz"),
    (lambda: ltp.chart(MATHIEU, "a=0:1:0.5", tol=2.0), r"tol"),
    (lambda: ltp.chart(ltp.System.from_fourier(1.0, np.eye(2)), "a=0:1:0.5"), r"give a system made by ltp.scene"),
    (lambda: ltp.System.from_fourier(0.0, -np.eye(2)), r"period"),
    (lambda: ltp.System.from_fourier(1.0, np.zeros((2, 2, 2))), r"its length must be odd"),
    (lambda: ltp.System.from_fourier(1.0, np.eye(2), B=np.ones((3, 1))), r"B must have as many rows as A"),
    (lambda: ltp.System.from_fourier(1.0, np.array([np.eye(2), np.eye(2), 2 * np.eye(2)])),
     r"not the series of a real matrix function"),
    (lambda: ltp.System.from_function(1.0, np.eye(2)), r"A must be a callable A\(t\)"),
    # Checked as scene files are: a NaN from t = 1 on, a pole at t = 1 (each used to run for
    # seconds and return thousands of diagnostic lines).
    (lambda: ltp.System.from_function(np.pi, lambda t: np.eye(2) * (np.nan if t > 1 else 1.0)),
     r"A\(t\) is not a number at t = 1\.0"),
    (lambda: ltp.System.from_function(np.pi, lambda t: np.array([[0.0, 1.0], [-1 / (t - 1), -0.1]])),
     r"A\(t\) is unbounded near t = 1 "),
    # Refused, not truncated to their real part or analysed as a periodic extension.
    (lambda: ltp.System.from_function(np.pi, lambda t: np.array([[0, 1], [-1 + 0.1j * np.cos(2 * t), 0]])),
     r"A\(0\) has complex values \(\|Im\| up to 0\.1\)"),
    (lambda: ltp.System.from_function(np.pi, lambda t: [[0, 1], [-1 + (0.5j if t > 1 else 0), 0]]),
     r"A\(t\) at t = 1\.[0-9]+ has complex values"),
    (lambda: ltp.System.from_function(np.pi, lambda t: np.array([[0, 1], [-1 - 0.1 * np.sin(t), -0.1]])),
     r"A\(t\) is not periodic with the period T = 3\.14159"),
    # 2e9 radians per period: refused before the work, with the estimate (the CLI's --max-work).
    (lambda: ltp.floquet(ltp.System.from_fourier(2 * np.pi, np.array(
        [[[0, 0], [-4.5e15, 0]], [[0, 1], [-9e16, -0.02]], [[0, 0], [-4.5e15, 0]]])), max_work=1),
     r"this analysis would take at least .* CPU s"),
    (lambda: ltp.System.from_samples(1.0, [0.0, 0.5], np.zeros((3, 2, 2))), r"one matrix per sample time"),
    (lambda: ltp.System.from_samples(1.0, [0.5, 0.0], np.zeros((2, 2, 2))), r"strictly increasing"),
])
def test_bad_arguments_raise_input_error(call, message):
    with pytest.raises(ltp.InputError, match=message) as raised:
        call()
    assert isinstance(raised.value, ValueError) and isinstance(raised.value, ltp.Error)
    assert "\n" not in str(raised.value)  # one line


def test_scene_file_errors_name_the_file(tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text("name: bad\nperiod: [1\n")
    with pytest.raises(ltp.SceneError, match="bad.yaml"):
        ltp.scene(str(bad))


def test_wrong_python_types_are_type_errors():
    with pytest.raises(TypeError):
        ltp.floquet("mathieu")  # a name is not a System: ltp.scene("mathieu")
    with pytest.raises(TypeError):
        ltp.floquet(MATHIEU, tol="small")


# Complex numbers where real ones are meant: refused, never truncated to their real part (numpy
# casts a complex array or scalar to float with only a ComplexWarning). Arrays and scene
# parameters: ltp.InputError naming the value; scalar arguments: the TypeError pybind11 raises
# for Python's complex, now for numpy's complex scalars too.
@pytest.mark.parametrize("call, message", [
    (lambda: ltp.pfrf(MATHIEU, np.array([0.1 + 0.5j, 0.2])), r"freq has complex values \(\|Im\| up to 0\.5\)"),
    (lambda: ltp.pfrf(MATHIEU, [0.1, 0.2 + 1j]), r"freq has complex values"),
    (lambda: ltp.scene("mathieu", a=np.complex128(1 + 1j)), r"a scene parameter must be a real number"),
    (lambda: ltp.scene("mathieu", a=1 + 0j), r"a scene parameter must be a real number"),
    (lambda: ltp.System.from_samples(1.0, [0.0, 0.5], np.zeros((2, 2, 2)) + 1e-3j), r"A has complex values"),
    (lambda: ltp.identify(np.arange(8.0) + 1j, np.ones(8), np.ones(8), period=1.0), r"time has complex values"),
])
def test_complex_arrays_where_real_is_meant_raise_input_error(call, message):
    with pytest.raises(ltp.InputError, match=message):
        call()


@pytest.mark.parametrize("call", [
    lambda: ltp.floquet(MATHIEU, tol=np.complex128(1e-8 + 1e-9j)),
    lambda: ltp.hill(MATHIEU, tol=np.complex64(1e-8)),  # even with Im = 0: Python's 1e-8+0j is refused too
    lambda: ltp.hill(MATHIEU, tol=1e-8 + 0j),
    lambda: ltp.snapshot(ltp.scene("rotor"), "0.1:0.2:0.1", angle=np.complex128(90 + 1j)),
    lambda: MATHIEU.A(np.complex128(0.5 + 1j)),
    lambda: MATHIEU.with_rotor_speed(np.complex128(1 + 1j)),
    lambda: ltp.System.from_fourier(np.complex128(np.pi + 1j), np.eye(2)),
    lambda: ltp.System.from_function(1.0, lambda t: np.eye(1), breakpoints=np.array([0.5 + 1j])),
    lambda: ltp.System.from_samples(1.0, np.array([0.0, 0.5 + 1j]), np.zeros((2, 1, 1))),
    lambda: ltp.simulate(ltp.scene("mathieu", c=0.3), "0.1:0.2:0.1", noise=np.complex128(30 + 1j)),
    lambda: ltp.chart(MATHIEU, "a=0:1:0.5", tol=np.complex128(1e-8 + 1e-9j)),
    lambda: ltp.chart(MATHIEU, "a=0:1:0.5", refine_tol=np.complex128(1e-8)),
])
def test_complex_scalars_where_real_is_meant_raise_type_error(call):
    with pytest.raises(TypeError, match="incompatible function arguments"):
        call()


def test_complex_arrays_with_zero_imaginary_part_are_their_real_part():
    # Frequencies computed in complex arithmetic (Im = 0 exactly): taken, without a ComplexWarning,
    # as the same real frequencies (reference: the real array).
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        complex_freq = ltp.pfrf(MATHIEU, np.array([0.1, 0.2]) + 0j)
    assert np.array_equal(complex_freq.H, ltp.pfrf(MATHIEU, np.array([0.1, 0.2])).H)


def test_help_text_on_everything():
    for name in ltp.__all__:
        obj = getattr(ltp, name)
        assert obj.__doc__ and len(obj.__doc__.strip()) > 20, name
        if inspect.isclass(obj) and not issubclass(obj, BaseException):
            for member, value in vars(obj).items():
                if not member.startswith("_") and callable(getattr(value, "__get__", None)):
                    assert getattr(value, "__doc__", None), f"{name}.{member}"
    assert "integrator" in ltp.floquet.__doc__ and "tol: float = 1e-10" in ltp.floquet.__doc__
    assert "harmonics='auto'" in ltp.hill.__doc__.replace('"', "'")
    assert "orders: object = '-4:4'" in ltp.pfrf.__doc__ and "check_every: int = 10" in ltp.pfrf.__doc__
    assert "check_every: Optional[int] = None" in ltp.chart.__doc__ and "refine_tol: float = 1e-08" in ltp.chart.__doc__
    assert ltp.__doc__ and "floquet" in ltp.__doc__


def test_defaults_are_the_clis(ltp_cli):
    # `ltp floquet mathieu` without options and ltp.floquet without keywords: same analysis.
    j = ltp_cli("floquet", "mathieu")
    r = ltp.floquet(MATHIEU)
    assert j["integrator"] == r.integrator and j["tolerance"] == 1e-10 and j["segments"] == r.segments
    assert [e["re"] for e in j["exponents"]] == list(r.exponents.real)


def test_missing_or_empty_A_is_an_input_error_not_a_crash():
    # from_fourier(1.0, None) and an empty 2-D array segfaulted (hostile input, round 2).
    with pytest.raises(ltp.InputError, match="A is missing or empty"):
        ltp.System.from_fourier(1.0, None)
    with pytest.raises(ltp.InputError, match="A is missing or empty"):
        ltp.System.from_fourier(1.0, np.zeros((0, 0)))


def test_an_htf_truncation_beyond_memory_is_a_resource_error():
    # htf_harmonics = 10**7 threw std::bad_alloc inside an OpenMP region: SIGABRT, the
    # interpreter gone (hostile input, round 2).
    with pytest.raises(ltp.ResourceError, match="GiB"):
        ltp.pfrf(ltp.scene("mathieu", c=0.3), "0.1:0.3:0.1", htf_harmonics=10**7)


def test_sizes_and_times_past_what_the_cli_accepts_are_refused():
    # Hostile input, round 2: the Python door had no caps (the CLI caps grids at a million
    # frequencies) and answered NaN for times and frequencies past the double range.
    s = ltp.scene("mathieu", c=0.3)
    with pytest.raises(ltp.InputError, match=r"PfrfOptions::frequencies_hz.size\(\) = 1000001\. Violated constraint: at most a million"):
        ltp.pfrf(s, np.linspace(0, 1, 10**6 + 1))
    with pytest.raises(ltp.InputError, match=r"PfrfOptions::frequencies_hz = 1e\+308\. Violated constraint: finite and at most 1e15 Hz"):
        ltp.pfrf(s, [1e308])
    A = lambda t: np.array([[0.0, 1.0], [-(1 - 0.4 * np.cos(2 * t)), -0.3]])  # noqa: E731
    with pytest.raises(ltp.InputError, match="at most 100000 per period"):
        ltp.System.from_function(np.pi, A, breakpoints=list(np.linspace(0, np.pi, 10**5 + 1, endpoint=False)))
    r = ltp.floquet(s)
    with pytest.raises(ltp.InputError, match="finite"):
        r.mode_matrix(float("nan"))
    with pytest.raises(ltp.InputError, match="finite"):
        r.left_modes(float("inf"))
    with pytest.raises(ltp.InputError, match="finite"):
        s.A(float("nan"))
    # A periodic quantity at any finite time is its value at the time's remainder (exact fmod).
    T = s.period
    t = 3 * T + 0.25
    np.testing.assert_array_equal(s.A(1e308), s.A(np.fmod(1e308, T)))
    np.testing.assert_allclose(r.mode_matrix(t), r.mode_matrix(np.fmod(t, T)), rtol=1e-12, atol=1e-12)


def test_the_repr_says_the_verdict():
    # The repr said "(unstable)" for every result that was not stable, marginal ones included.
    r = ltp.floquet(ltp.scene("mathieu", c=0, a=1.5, q=0.3))  # undamped, between tongues
    assert r.verdict == "marginal" and "(marginal)" in repr(r)
    h = ltp.hill(ltp.scene("mathieu", c=0, a=1.5, q=0.3), harmonics=16)
    assert h.verdict in repr(h)


def test_long_work_is_announced_before_it_starts():
    # What `ltp floquet` / `ltp hill` print on stderr before a long job, Python says as a
    # UserWarning; filtered to an error, it stops the job before any work (hence fast here).
    # Both jobs are estimated at minutes on this machine (far from the 10 s announcement and the
    # hour's refusal either way, so no timing decides the test).
    A = np.zeros((3, 2, 2), complex)
    A[1] = [[0, 1], [-1, -0.01]]
    A[0][1, 0] = A[2][1, 0] = -0.05
    slow = ltp.System.from_fourier(1e7, A)  # 1e7 radians of a 1 rad/s oscillator per period
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(UserWarning, match=r"ltp.floquet: about .* CPU s of work ahead"):
            ltp.floquet(slow)
        with pytest.raises(UserWarning, match=r"ltp.hill_study: about .* truncations \(N = 1…400"):
            ltp.hill_study(ltp.scene("mathieu"), max_harmonics=400, solver="dense")
