"""ltp.floquet(progress=...): a notebook's progress bar hears each phase of the analysis.

Reference: the phases the result says were run (refined-run estimate: 'run' and 'refined run';
mode shapes) each reach a fraction of exactly 1, rising, and the numbers are those of a call
without the callback (the callback only watches).
"""
import numpy as np
import pytest

import ltp


def test_every_phase_rises_to_one_and_changes_nothing():
    system = ltp.scene("mathieu", a=1.5, q=2)
    seen = {}
    r = ltp.floquet(system, integrator="bs", progress=lambda phase, f: seen.setdefault(phase, []).append(f))
    plain = ltp.floquet(system, integrator="bs")
    assert r.error_estimate_method == "refined-run"
    assert {"run", "refined run"} <= set(seen) <= {"run", "refined run", "mode shapes"}
    for phase, fractions in seen.items():
        assert fractions[-1] == 1.0, phase
        assert all(0 <= f <= 1 for f in fractions), phase
        assert all(b > a for a, b in zip(fractions, fractions[1:])), phase
    assert np.array_equal(r.exponents, plain.exponents)


def test_what_the_callback_raises_is_raised_after_the_work():
    def stop(phase, fraction):
        raise RuntimeError("from the callback")

    with pytest.raises(RuntimeError, match="from the callback"):
        ltp.floquet(ltp.scene("mathieu"), progress=stop)
    with pytest.raises(ValueError, match="progress must be a callable"):
        ltp.floquet(ltp.scene("mathieu"), progress=3)
