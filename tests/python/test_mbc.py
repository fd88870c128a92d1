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
    # Numbers as numpy arrays: the files' azimuths (rad), as the JSON lists them.
    assert m.azimuths.dtype == np.float64 and len(m.azimuths) == 3
    assert same(j["max_real_part"], m.max_real_part) and same(j["periodic_part"], m.periodic_part)
    # The mode shapes are eigenvectors of the averaged matrix: A v = λ v.
    v = m.eigenvectors
    assert v.shape == (len(m.states), len(m.eigenvalues))
    residual = np.linalg.norm(m.A @ v - v * m.eigenvalues, axis=0) / np.linalg.norm(v, axis=0)
    assert residual.max() < 1e-9 * np.linalg.norm(m.A)
    assert "backward" in m.whirl and "forward" in m.whirl
    # The same shapes in the JSON (state_names, shape re/im), each scaled so its largest
    # entry is 1 (phases relative to the leading state).
    assert j["state_names"] == list(m.states)
    for k, mode in enumerate(j["modes"]):
        shape = np.array(mode["shape"]["re"]) + 1j * np.array(mode["shape"]["im"])
        assert np.abs(shape - v[:, k]).max() <= 1e-12
        assert abs(np.abs(v[:, k]).max() - 1) < 1e-15 and 1 in v[:, k]


def test_mbc_shapes_csv(ltp_cli, tmp_path):
    import csv
    out = tmp_path / "shapes.csv"
    ltp_cli("mbc", FIVE_MW, "--no-floquet", "--shapes-csv", str(out))
    m = ltp.mbc(FIVE_MW)
    header, *rows = list(csv.reader(out.open()))
    assert header[0] == "state" and len(header) == 1 + 2 * len(m.eigenvalues)
    assert header[1] == f"mode 1 ({m.descriptions[0]}) magnitude"
    assert [r[0] for r in rows] == list(m.states)
    for i, row in enumerate(rows):
        for k in range(len(m.eigenvalues)):
            assert abs(float(row[1 + 2 * k]) - abs(m.eigenvectors[i, k])) <= 1e-11
            if abs(m.eigenvectors[i, k]) > 1e-9:
                phase = np.degrees(np.angle(m.eigenvectors[i, k]))
                assert abs((float(row[2 + 2 * k]) - phase + 180) % 360 - 180) <= 1e-7


def test_mbc_refuses_what_is_not_lin_files(tmp_path):
    import pytest
    with pytest.raises(ltp.InputError):
        ltp.mbc(str(tmp_path))
    with pytest.raises(ltp.InputError):
        ltp.mbc(3)


def test_mbc_participation_against_numpy(ltp_cli):
    """Participation factors p_ik = V[i,k] inv(V)[k,i] of numpy's own eigen-decomposition of
    the averaged matrix; each column sums to 1; the leading single state's share is its
    displacement's and rate's |p| summed, over the sum of every displacement's."""
    j = ltp_cli("mbc", FIVE_MW, "--no-floquet")
    m = ltp.mbc(FIVE_MW)
    values, vectors = np.linalg.eig(m.A)
    left = np.linalg.inv(vectors)
    p = m.participation
    assert p.shape == (len(m.states), len(m.eigenvalues))
    for k, lam in enumerate(m.eigenvalues):
        i = np.argmin(np.abs(values - lam))
        reference = vectors[:, i] * left[i, :]
        assert np.abs(p[:, k] - reference).max() <= 1e-9, k
        assert abs(p[:, k].sum() - 1) <= 1e-9, k
        mode = j["modes"][k]
        json_p = np.array(mode["participation"]["re"]) + 1j * np.array(mode["participation"]["im"])
        assert np.abs(json_p - p[:, k]).max() <= 1e-12, k
    # Displacement d and its rate r: "... First time derivative of X, m/s" beside "... X, m".
    names = list(m.states)
    base = [n.replace("First time derivative of ", "").rsplit(", ", 1)[0] for n in names]
    displacement = [base.index(b) for b in base]  # the first state with the same base
    for k, mode in enumerate(j["modes"]):
        per_dof = np.zeros(len(names), complex)
        for i in range(len(names)):
            per_dof[displacement[i]] += p[i, k]
        shares = np.abs(per_dof) / np.abs(per_dof).sum()
        lead = mode["dominant_states"][0]
        assert abs(shares[names.index(lead["state"])] - lead["share"]) <= 1e-9, k
        assert np.argmax(shares) == names.index(lead["state"]), k
