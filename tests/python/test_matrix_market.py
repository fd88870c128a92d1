"""A finite-element shaft written by SciPy (scipy.io.mmwrite: dense symmetric matrices as
'array symmetric', sparse ones as 'coordinate') and read by a scene file's second_order block
gives `ltp floquet` the same system as ltp.System.from_second_order of the matrices SciPy's own
reader (scipy.io.mmread) finds in the same files: the same exponents and estimate to the last
digit printed."""
import numpy as np
import pytest
import scipy.io
import scipy.sparse

import ltp
from conftest import same
from fe_rotor import fe_rotor


@pytest.mark.parametrize("sparse", [False, True])
def test_fe_shaft_from_matrix_market_files(ltp_cli, tmp_path, sparse):
    period, M, D, K = fe_rotor(4)
    parts = {"M": M, "D": D, "K0": K[1].real, "Kc": 2 * K[2].real, "Ks": -2 * K[2].imag}
    read = {}
    for name, matrix in parts.items():
        scipy.io.mmwrite(tmp_path / f"{name}.mtx",
                         scipy.sparse.coo_matrix(matrix) if sparse else matrix)
        back = scipy.io.mmread(tmp_path / f"{name}.mtx")
        read[name] = back.toarray() if sparse else back
        # SciPy writes sparse entries to 16 digits: the files hold the matrices to ~1e-15.
        assert np.abs(read[name] - matrix).max() <= 1e-14 * np.abs(matrix).max(), name
    K_read = np.stack([(read["Kc"] + 1j * read["Ks"]) / 2, read["K0"] + 0j,
                       (read["Kc"] - 1j * read["Ks"]) / 2])
    (tmp_path / "shaft.yaml").write_text(f"""
period: {period!r}
second_order:
  M: {{file: M.mtx}}
  D: {{file: D.mtx}}
  K:
    file: K0.mtx
    harmonics:
      - {{order: 1, cos: Kc.mtx, sin: Ks.mtx}}
""")
    j = ltp_cli("floquet", str(tmp_path / "shaft.yaml"))
    r = ltp.floquet(ltp.System.from_second_order(period, M=read["M"], K=K_read, D=read["D"]))
    assert j["ok"] and r.ok and j["integrator"] == r.integrator == "taylor"
    for key in ["max_real_exponent", "error_estimate", "mode_condition"]:
        assert same(j[key], getattr(r, key)), key
    assert len(j["exponents"]) == len(r.exponents) == 40
    for k, e in enumerate(j["exponents"]):
        assert same(e["re"], r.exponents[k].real) and same(e["im"], r.exponents[k].imag), k
