"""ltp.campbell gives `ltp campbell`'s diagram to the last digit.

Reference: the command's JSON (lines, crossings, per-rev) and CSV (per point, each line's
natural frequency and damping ratio, written with 12 digits) on the same operating points; and
each point's MBC3 table equals ltp.mbc of that point alone (the same analysis, another door).
"""
import csv
from pathlib import Path

import numpy as np
import pytest

import ltp
from conftest import same

POINTS = sorted(str(p) for p in (Path(__file__).resolve().parents[1] / "data" / "openfast" /
                                 "rotor-speeds").iterdir())


def test_campbell_equals_cli(ltp_cli, tmp_path):
    out = tmp_path / "c.csv"
    j = ltp_cli("campbell", *POINTS, "--csv", str(out))
    c = ltp.campbell(POINTS)
    # Natural frequencies by default in both doors, as ACDC and openfast_toolbox draw them.
    assert c.frequency == j["campbell"]["frequency"] == "natural"
    assert c.axis_label == j["axis"]
    assert len(c.lines) == len(j["campbell"]["lines"])
    assert [l["description"] for l in c.lines] == [l["description"] for l in j["campbell"]["lines"]]
    assert list(c.per_rev) == j["campbell"]["per_rev"] and c.per_rev.dtype == np.int64
    assert len(c.crossings) == len(j["campbell"]["crossings"])
    for x, y in zip(c.crossings, j["campbell"]["crossings"]):
        assert x["mode"] == y["mode"] and x["per_rev"] == y["per_rev"]
        assert same(y["parameter"], x["parameter"]) and same(y["frequency_hz"], x["frequency_hz"])
    for p, q in zip(j["points"], c.points):
        assert same(p["max_real_part"], q.max_real_part)
    # The CSV: rpm first (the ordering quantity), no second rpm column, then per line its
    # frequency and damping ratio under the line's number and mode description.
    header, *rows = list(csv.reader(out.open()))
    assert header[:3] == ["rotor_speed_rpm", "wind_speed_m_s", "pitch_deg"]
    assert len(header) == 3 + 2 * len(c.lines)
    assert len(rows) == len(c.parameter)
    for k, line in enumerate(c.lines):
        name = f"mode {k + 1} ({line['description']})"
        assert header[3 + 2 * k] == f"{name} natural frequency [Hz]".replace('"', "'")
        assert header[4 + 2 * k] == f"{name} damping ratio".replace('"', "'")
    for i, row in enumerate(rows):
        assert float(row[0]) == float(f"{c.parameter[i]:.12g}")
        for k, line in enumerate(c.lines):
            if np.isfinite(line["frequency_hz"][i]):
                assert float(row[3 + 2 * k]) == float(f"{line['frequency_hz'][i]:.12g}")
                assert float(row[4 + 2 * k]) == float(f"{line['damping_ratio'][i]:.12g}")
            else:
                assert row[3 + 2 * k] == ""
    # The test files have no inputs, so no pitch: empty cells, NaN in Python.
    assert all(row[2] == "" for row in rows) and np.isnan(c.pitches).all()
    # Each point's table is ltp.mbc of its files.
    one = ltp.mbc(POINTS[0])
    assert np.array_equal(one.eigenvalues, c.points[0].eigenvalues)


def test_campbell_refuses_an_unknown_axis():
    with pytest.raises(ltp.InputError, match="by must be"):
        ltp.campbell(POINTS, by="pitch")


def test_campbell_of_a_flat_output_folder_and_keep_going(tmp_path):
    # OpenFAST's layout: every simulation's <root>.<k>.lin in one folder. Reference: the same
    # files one directory per point (the diagram above).
    import shutil
    for point in POINTS:
        for f in Path(point).glob("*.lin"):
            shutil.copy(f, tmp_path / f"{Path(point).name}.{f.name.split('.')[1]}.lin")
    flat = ltp.campbell([str(tmp_path)])
    per_point = ltp.campbell(POINTS)
    assert len(flat.points) == len(POINTS)
    assert np.array_equal(flat.parameter, per_point.parameter)
    for a, b in zip(flat.lines, per_point.lines):
        assert np.array_equal(a["frequency_hz"], b["frequency_hz"], equal_nan=True)
    (tmp_path / "broken.1.lin").write_text("not a linearisation\n")
    with pytest.raises(ltp.InputError):
        ltp.campbell([str(tmp_path)])
    kept = ltp.campbell([str(tmp_path)], keep_going=True)
    assert len(kept.points) == len(POINTS)
    assert len(kept.skipped) == 1 and "broken.1.lin" in kept.skipped[0]


def test_notes_carry_codes():
    # The notes are typed: one snake_case code per sentence, as every result's diagnostics.
    c = ltp.campbell(POINTS)
    assert len(c.note_codes) == len(c.notes)
    for code, note in zip(c.note_codes, c.notes):
        if code == "tracking_ambiguous":
            assert "ambiguous" in note
    # The 5 MW files have the generator azimuth among their states: MBC3 leaves out its rigid
    # rotation, and says so; their 3 azimuths are enough to average.
    five_mw = str(Path(__file__).resolve().parents[1] / "data" / "openfast" / "nrel5mw-rotating")
    one = ltp.campbell([five_mw])
    assert "rigid_body_mode" in one.note_codes
    assert "too_few_azimuths" not in one.note_codes
    s = ltp.scene(five_mw)
    assert len(s.note_codes) == len(s.notes)
    assert s.note_codes[0] == "azimuth_samples_resolve"
    assert "3 azimuths hold only harmonics 0 and ±1" in s.notes[0]
    # Analysed in multi-blade coordinates by default: no rotating-frame states, no ±1P note.
    assert "multi_blade_coordinates" in s.note_codes
    assert "exponents_modulo_rotor_speed" not in s.note_codes


def test_band_and_module_filters_equal_cli(ltp_cli):
    # The filters in both doors: the same lines and the same notes.
    everything = ltp.campbell(POINTS)
    band = float(np.nanmedian([l["frequency_hz"][0] for l in everything.lines]))
    j = ltp_cli("campbell", *POINTS, "--max-frequency", str(band), "--exclude-module", "XX")
    c = ltp.campbell(POINTS, max_frequency=band, exclude_modules=["XX"])
    assert [l["description"] for l in c.lines] == [l["description"] for l in j["campbell"]["lines"]]
    assert 0 < len(c.lines) < len(everything.lines)
    assert "lines_above_band_left_out" in c.note_codes
    # No state belongs to a module "XX": nothing is left out, and the note says 0.
    assert "modules_left_out" in c.note_codes
    assert any(n.startswith("0 modes over 7 points left out") for n in c.notes)
    with pytest.raises(ltp.InputError, match="exclude_modules"):
        ltp.campbell(POINTS, exclude_modules=["A D"])
