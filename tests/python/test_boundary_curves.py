"""Stability boundaries as curves (ltp.chart(...).boundary_curves) on the undamped Mathieu map,
y'' + (a − 2q cos 2t) y = 0, against SciPy's characteristic values a_m(q), b_m(q)
(scipy.special.mathieu_a/mathieu_b: the same convention, period π). docs/charts.md."""
import numpy as np
import pytest

import ltp

special = pytest.importorskip("scipy.special")


def characteristic(kind, symmetry, q):
    """The same-kind characteristic values at q, m ≤ 7 (σ = +1: even m, σ = −1: odd m): a_m for
    a curve of even solutions (ce_m), b_m for odd ones (se_m)."""
    ms = range(0, 8, 2) if kind == "+1" else range(1, 8, 2)
    if symmetry == "even":
        return np.array([special.mathieu_a(m, q) for m in ms]), list(ms)
    return np.array([special.mathieu_b(m, q) for m in ms if m > 0]), [m for m in ms if m > 0]


def test_undamped_mathieu_curves_follow_the_characteristic_values():
    c = ltp.chart(ltp.scene("mathieu", c=0), "q=0:6:0.2", "a=-2:27:0.2")
    assert list(c.axes) == ["q", "a"]
    assert len(c.boundary_curves) == 11  # a_0, then b_m and a_m for m = 1..5
    assert c.boundary_curve_kinds.dtype.kind == "U"
    worst = {}
    tips = []
    for curve, kind, bracket, detail in zip(c.boundary_curves, c.boundary_curve_kinds,
                                            c.boundary_curve_brackets, c.boundary_curve_details):
        assert curve.dtype == np.float64 and curve.shape[1] == 2 and len(bracket) == len(curve)
        assert detail["end_notes"] == ("reached the map's edge", "reached the map's edge")
        # Undamped Mathieu is time-reversible: each curve is one half-period block's root.
        assert detail["symmetry"] in ("even", "odd")
        assert not any(detail["merged"])  # both edges resolved down to the tips
        for (q, a), b in zip(curve, bracket):
            values, orders = characteristic(kind, detail["symmetry"], q)
            k = int(np.argmin(np.abs(values - a)))
            dev = abs(values[k] - a)
            assert dev <= b + 1e-12, (q, a, b)  # the promise: within ±bracket
            assert b <= 1e-8 and dev <= 1e-8, (q, a, b)
            m = orders[k]
            worst[m] = max(worst.get(m, 0.0), dev)
            if q == 0:
                tips.append(a)
    # Every tongue reaches the a axis at m² (scipy: a_m(0) = b_m(0) = m²).
    assert np.allclose(sorted(tips), [0, 1, 1, 4, 4, 9, 9, 16, 16, 25, 25], atol=1e-10, rtol=0)
    assert set(worst) == {0, 1, 2, 3, 4, 5}


def test_chart_columns_are_numpy_arrays():
    c = ltp.chart(ltp.scene("mathieu"), "a=0:1:0.5")
    assert isinstance(c.verdicts, np.ndarray) and c.verdicts.dtype.kind == "U"
    assert isinstance(c.axes, np.ndarray) and c.axes.dtype.kind == "U"
    assert isinstance(c.per_rev, np.ndarray) and c.per_rev.dtype.kind == "i"
    assert c.mode_tracking["ambiguous_points"].dtype.kind == "i"
    assert c.boundary_curves == []  # 1-D: no curves
