"""ltp.chart over a Python builder: builder(**parameters) -> ltp.System, swept like a scene.

Reference: the same map of the built-in Mathieu scene (the builder writes the scene's Fourier
coefficients by hand, from its definition y'' + c y' + (a − 2q cos 2t) y = 0), and the
characteristic values of scipy.special for one boundary."""
import numpy as np
import pytest

import ltp


def mathieu(a, q, c):
    A = np.zeros((3, 2, 2), complex)
    A[1] = [[0, 1], [-a, -c]]
    A[0][1, 0] = A[2][1, 0] = q  # −2q cos 2t in the stiffness is +q e^{±2jt} in A
    return ltp.System.from_fourier(np.pi, A)


def test_a_builder_map_equals_the_scene_map():
    built = ltp.chart(mathieu, "q=0:3:0.1", "a=-1:5:0.1", parameters=dict(a=1.0, q=0.5, c=0.0))
    scene = ltp.chart(ltp.scene("mathieu", c=0), "q=0:3:0.1", "a=-1:5:0.1")
    assert np.array_equal(built.verdicts, scene.verdicts)
    assert len(built.boundary_curves) == len(scene.boundary_curves) > 0
    for x, y in zip(built.boundary_curves, scene.boundary_curves):
        assert np.max(np.abs(x - y)) < 1e-12
    special = pytest.importorskip("scipy.special")
    for curve in built.boundary_curves:  # where the tongues are wide (q > 1): within 1e-8
        for q, a in curve[curve[:, 0] > 1]:
            values = [special.mathieu_a(m, q) for m in range(4)] + [special.mathieu_b(m, q) for m in range(1, 4)]
            assert min(abs(v - a) for v in values) < 1e-8, (q, a)


def test_a_raising_builder_fails_its_points_with_the_message():
    def partial(a, q, c):
        if a > 4:
            raise RuntimeError("no model above a = 4")
        return mathieu(a, q, c)

    chart = ltp.chart(partial, "q=0:3:0.5", "a=-1:5:0.5", parameters=dict(a=1.0, q=0.5, c=0.0))
    failed = chart.verdicts == "failed"
    assert np.all(failed == (chart.point_values[:, 1] > 4))
    assert chart.failures[0]["reason"] == "the builder raised RuntimeError: no model above a = 4"


@pytest.mark.parametrize("builder, parameters, message", [
    (mathieu, None, r"parameters=\{name: default"),
    (mathieu, {"a": 1j, "q": 0.5, "c": 0.0}, r"a must be a real number"),
    (mathieu, {"a": np.complex128(1), "q": 0.5, "c": 0.0}, r"a must be a real number"),
    (mathieu, {"a": 1.0}, r"builder raised TypeError"),
    (lambda a, q, c: 3, {"a": 1.0, "q": 0.5, "c": 0.0}, r"must return an ltp.System, got int"),
    (42, {"a": 1.0}, r"a builder callable"),
])
def test_bad_builders_are_refused_up_front(builder, parameters, message):
    with pytest.raises(ltp.InputError, match=message):
        ltp.chart(builder, "a=0:1:0.5", parameters=parameters)


def test_parameters_belong_to_builders_only():
    with pytest.raises(ltp.InputError, match="belongs to a builder"):
        ltp.chart(ltp.scene("mathieu"), "a=0:1:0.5", parameters={"a": 1.0})
