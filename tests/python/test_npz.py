"""A finite-element shaft saved by numpy (np.savez, np.savez_compressed; C and Fortran order)
and named array by array in a scene file's second_order block ("shaft.npz:K") is the system
ltp.System.from_second_order builds from the same arrays: the same A(t) to the last bit and the
same exponents. numpy is the writer, so the reader is checked against the format's own
implementation; bad archives are refused with the archive and the array named."""
import io
import zipfile

import numpy as np
import pytest

import ltp
from fe_rotor import fe_rotor

SCENE = """
period: {period!r}
second_order:
  M: {{file: shaft.npz:M}}
  D: {{file: shaft.npz:D}}
  K:
    file: shaft.npz:K0
    harmonics:
      - {{order: 1, cos: shaft.npz:Kc, sin: shaft.npz:Ks}}
"""


@pytest.mark.parametrize("compressed,fortran", [(False, False), (True, False), (False, True)])
def test_fe_shaft_from_an_npz_archive(tmp_path, compressed, fortran):
    period, M, D, K = fe_rotor(3)
    parts = {"M": M, "D": D, "K0": K[1].real, "Kc": 2 * K[2].real, "Ks": -2 * K[2].imag}
    if fortran:
        parts = {k: np.asfortranarray(v) for k, v in parts.items()}
    (np.savez_compressed if compressed else np.savez)(tmp_path / "shaft.npz", **parts)
    (tmp_path / "shaft.yaml").write_text(SCENE.format(period=period))
    from_file = ltp.scene(str(tmp_path / "shaft.yaml"))
    direct = ltp.System.from_second_order(period, M=M, K=K, D=D)
    for t in [0.0, 0.3 * period, 0.71 * period]:
        assert np.array_equal(from_file.A(t), direct.A(t)), t
    a, b = ltp.floquet(from_file), ltp.floquet(direct)
    assert np.array_equal(a.exponents, b.exponents)


def test_npz_dtypes_and_refusals(tmp_path):
    period, M, D, K = fe_rotor(1)
    n = M.shape[0]
    scene = tmp_path / "s.yaml"

    def load(**arrays):
        np.savez(tmp_path / "shaft.npz", **arrays)
        return ltp.scene(str(scene))

    scene.write_text(f"""
period: {period!r}
second_order:
  M: {{file: shaft.npz:M}}
  K: {{file: shaft.npz:K}}
""")
    # Integers and float32 are read exactly (the float32 values are exact binary fractions).
    eye = np.eye(n, dtype=np.int64)
    s = load(M=eye, K=(4 * eye).astype(np.float32))
    assert np.array_equal(s.A(0.0)[n:, :n], -4 * np.eye(n))
    with pytest.raises(ltp.SceneError, match=r"no array 'K' \(the archive holds: M, Q\)"):
        load(M=eye, Q=eye)
    with pytest.raises(ltp.SceneError, match="dtype '<c16' not read"):
        load(M=eye, K=eye + 0j)
    with pytest.raises(ltp.SceneError, match="3-dimensional array"):
        load(M=eye, K=np.zeros((n, n, 2)))
    with pytest.raises(ltp.SceneError, match="non-finite value"):
        bad = np.eye(n)
        bad[0, 1] = np.nan
        load(M=eye, K=bad)
    # Big-endian data, a truncated member, and not an archive at all.
    with pytest.raises(ltp.SceneError, match="dtype '>f8' not read"):
        load(M=eye, K=np.eye(n).astype(">f8"))
    buffer = io.BytesIO()
    np.save(buffer, np.eye(n))
    with zipfile.ZipFile(tmp_path / "shaft.npz", "w") as z:
        z.writestr("M.npy", buffer.getvalue())
        z.writestr("K.npy", buffer.getvalue()[:-8])
    with pytest.raises(ltp.SceneError, match="data bytes for"):
        ltp.scene(str(scene))
    (tmp_path / "shaft.npz").write_text("not a zip archive")
    with pytest.raises(ltp.SceneError, match=r"not a \.npz \(zip\) archive"):
        ltp.scene(str(scene))
    scene.write_text(f"""
period: {period!r}
second_order:
  M: {{file: shaft.npz}}
  K: {{file: shaft.npz:K}}
""")
    with pytest.raises(ltp.SceneError, match="name the array in the archive: shaft.npz:K"):
        ltp.scene(str(scene))
