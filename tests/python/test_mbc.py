"""ltp.mbc gives `ltp mbc --no-floquet --json`'s MBC3 table to the last digit.

Reference for the numbers themselves: the CLI's MBC3 is checked against an independent numpy
MBC3 of the same files (benchmarks/peers/mbc3_reference.py, tests/openfast/mbc3_test.cc); here
the Python door must give the same numbers, names and whirl directions as the command.
"""
from pathlib import Path

import numpy as np

import ltp
from conftest import same

FIVE_MW = str(Path(__file__).resolve().parents[1] / "data" / "openfast" / "nrel5mw-rotating")


def test_mbc_equals_cli(ltp_cli):
    j = ltp_cli("mbc", FIVE_MW, "--no-floquet")
    m = ltp.mbc(FIVE_MW)
    assert m.applicable and m.blades == j["blades"] == 3
    assert len(j["modes"]) == len(m.eigenvalues) == len(m.descriptions)
    for k, mode in enumerate(j["modes"]):
        assert same(mode["natural_frequency_hz"], m.natural_frequencies_hz[k]), k
        assert same(mode["damped_frequency_hz"], m.damped_frequencies_hz[k]), k
        assert same(mode["re"], m.eigenvalues[k].real) and same(mode["im"], m.eigenvalues[k].imag), k
        if mode["damping_ratio"] is None:
            assert m.rigid_body[k] and np.isnan(m.damping_ratios[k])
        else:
            assert same(mode["damping_ratio"], m.damping_ratios[k]), k
        assert mode["kind"] == m.kinds[k] and mode["rigid_body"] == m.rigid_body[k]
        assert mode["whirl"] == m.whirl[k] and mode["description"] == m.descriptions[k]
    assert same(j["max_real_part"], m.max_real_part) and same(j["periodic_part"], m.periodic_part)
    # The mode shapes are eigenvectors of the averaged matrix: A v = λ v.
    v = m.eigenvectors
    assert v.shape == (len(m.states), len(m.eigenvalues))
    residual = np.linalg.norm(m.A @ v - v * m.eigenvalues, axis=0) / np.linalg.norm(v, axis=0)
    assert residual.max() < 1e-9 * np.linalg.norm(m.A)
    assert "backward" in m.whirl and "forward" in m.whirl


def test_mbc_refuses_what_is_not_lin_files(tmp_path):
    import pytest
    with pytest.raises(ltp.InputError):
        ltp.mbc(str(tmp_path))
    with pytest.raises(ltp.InputError):
        ltp.mbc(3)
