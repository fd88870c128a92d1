"""ltp.deflection gives `ltp floquet --deflection-csv`'s frames (another door, the same numbers
to the CSV's 12 digits), and its motion is the mode's own: the cantilever tip's deflection is
the scene's output z_tip = Cd q of Re(e^{λt} ξ(t)) times the reported scale.
"""
import csv

import numpy as np
import pytest

import ltp


def test_deflection_equals_cli(ltp_cli, tmp_path):
    out = tmp_path / "d.csv"
    j = ltp_cli("floquet", "tower-rotor", "--mode-samples", "8", "--deflection-csv", str(out),
                "--deflection-mode", "2")
    s = ltp.scene("tower-rotor")
    r = ltp.floquet(s, mode_samples=8)
    assert np.array_equal(r.exponents.real, [e["re"] for e in j["exponents"]])
    d = ltp.deflection(s, r, modes=[1])
    assert d["bodies"] == ["cantilever", "shaft", "blade1", "blade2"]
    assert len(d["t"]) == 8
    m = d["modes"][0]
    assert m["mode"] == 1 and m["exponent"] == r.exponents[1]
    rows = list(csv.DictReader(out.open()))
    assert {row["mode"] for row in rows} == {"2"}
    for row in rows:
        f = int(np.argmin(abs(d["t"] - float(row["t"]))))
        body, node = row["body"], int(row["node"])
        for i, axis in enumerate("xyz"):
            assert float(row[axis]) == float(f"{m['moved'][body][f, node, i]:.12g}")
            assert float(row[axis + "_rest"]) == float(f"{m['rest'][body][f, node, i]:.12g}")


def test_tip_motion_is_the_modes_output():
    s = ltp.scene("tower-rotor")
    r = ltp.floquet(s, mode_samples=8)
    d = ltp.deflection(s, r, amplitude=0.05)
    dofs = s.states // 2
    cd = s.C(0.0)[:, :dofs]  # rows z_tip, y_tip on the displacement coordinates
    for m in d["modes"]:
        k = m["mode"]
        q = (np.exp(m["exponent"] * d["t"])[:, None] * r.mode_samples[:, :dofs, k]).real
        tip = m["moved"]["cantilever"][:, -1, :] - m["rest"]["cantilever"][:, -1, :]
        expected = m["scale"] * q @ cd.T
        size = np.abs(expected).max() + 1e-300
        assert np.allclose(tip[:, 2], expected[:, 0], rtol=0, atol=1e-12 * size), k
        assert np.allclose(tip[:, 1], expected[:, 1], rtol=0, atol=1e-12 * size), k
        assert np.allclose(tip[:, 0], 0, atol=1e-15)  # the cantilever does not stretch
        # On the structure as it stands at t = 0: the cantilever and the shaft do not turn, so
        # they are where they moved at every time; everything is where it moved at t = 0.
        for b in ("cantilever", "shaft"):
            assert np.array_equal(m["standing"][b], m["moved"][b]), (k, b)
        for b in d["bodies"]:
            assert np.array_equal(m["standing"][b][0], m["moved"][b][0]), (k, b)
        # The largest node displacement is amplitude × the structure's size.
        largest = max(np.linalg.norm(m["moved"][b] - m["rest"][b], axis=2).max() for b in d["bodies"])
        nodes = np.vstack([m["rest"][b][0] for b in d["bodies"]])
        size = np.linalg.norm(nodes[:, None, :] - nodes[None, :, :], axis=2).max()
        assert largest == pytest.approx(0.05 * size, rel=1e-12) or m["scale"] == 0


def test_deflection_refuses_a_system_without_structure():
    s = ltp.scene("mathieu")
    with pytest.raises(ltp.InputError, match="no structure to draw"):
        ltp.deflection(s, ltp.floquet(s))
