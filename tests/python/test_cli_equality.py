"""The Python functions give the `ltp` command's numbers to the last digit.

Reference: `ltp ... --json` of the same build on the same scenes with the same options. Both
call the same library function with the same options, so any difference (a default that the
CLI sets and Python does not, a grid built differently, a lost digit in a conversion) shows
up as a mismatch in the last bit. Timings (elapsed_s) are the only fields left out.
"""
from pathlib import Path

import numpy as np
import pytest

import ltp
from conftest import number, same


def assert_modes_equal(j, r):
    """The exponents, multipliers and per-mode fields of `ltp floquet --json` vs a result."""
    assert len(j["exponents"]) == len(r.exponents)
    for k, e in enumerate(j["exponents"]):
        assert same(e["re"], r.exponents[k].real), k
        assert same(e["im"], r.exponents[k].imag), k
        assert same(e["frequency_hz"], r.frequencies_hz[k]), k
        assert same(e["damping_ratio"], r.damping_ratios[k]), k
    for k, m in enumerate(j["multipliers"]):
        assert same(m["re"], r.multipliers[k].real), k
        assert same(m["im"], r.multipliers[k].imag), k
        assert same(m["log_abs"], r.log_multipliers[k].real), k
        assert same(m["arg"], r.log_multipliers[k].imag), k
    for k, m in enumerate(j["modes"]):
        assert m["branch"] == r.branches[k]
        assert m["rigid_body"] == bool(r.rigid_body[k])
        assert same(m["central_weight"], r.central_weights[k])
        assert same(m["branch_margin"], r.branch_margins[k])
        assert same(m["eigenvector_residual"], r.eigenvector_residuals[k])


FIVE_MW = str(Path(__file__).resolve().parents[1] / "data" / "openfast" / "nrel5mw-rotating")
FLOQUET_CASES = [
    ("mathieu", {"a": "1.5", "q": "2", "c": "0.05"}, {}),
    ("meissner", {}, {}),                       # A(t) jumps: breakpoints, expm/bs pieces
    ("jeffcott", {}, {"tol": "1e-8"}),
    ("rotor", {"blades": "3"}, {"integrator": "rkf78", "segments": "16"}),
    ("tower-rotor", {}, {}),                    # the paper's 40-state system
    ("tower-rotor", {}, {"estimate": "local-errors"}),  # one run, local errors carried
    (FIVE_MW, {}, {}),                          # samples: the sampling error in the estimate
]


@pytest.mark.parametrize("scene,parameters,options", FLOQUET_CASES,
                         ids=[Path(c[0]).name for c in FLOQUET_CASES])
def test_floquet_equals_cli(ltp_cli, scene, parameters, options):
    args = ["floquet", scene]
    for k, v in parameters.items():
        args += ["--set", f"{k}={v}"]
    for k, v in options.items():
        args += [f"--{k}", v]
    j = ltp_cli(*args, "--keep-going")
    kwargs = {k: (int(v) if k == "segments" else float(v) if k == "tol" else v) for k, v in options.items()}
    system = ltp.scene(scene, **parameters)
    r = ltp.floquet(system, **kwargs)
    assert_modes_equal(j, r)
    # The rotor's multi-blade-coordinate cross-check (an independent route: eigenvalues of the
    # constant MBC system), the same in both.
    check = ltp.mbc_check(system, r)
    assert (check is None) == ("mbc_check" not in j)
    if check is not None:
        assert check["applicable"] == j["mbc_check"]["applicable"]
        assert check["blades"] == j["mbc_check"]["blades"] == 3
        assert same(j["mbc_check"]["max_difference"], check["max_difference"])
        assert check["max_difference"] < 1e-7
    assert j["ok"] == r.ok and j["stable"] == r.stable and j["verdict"] == r.verdict
    assert j["integrator"] == r.integrator and j["segments"] == r.segments
    assert j["multiplier_method"] == r.multiplier_method and j["period"] == r.period
    assert j["error_estimate_method"] == r.error_estimate_method
    assert j["estimate_source"] == r.estimate_source
    for key in ["max_real_exponent", "max_log_abs_multiplier", "error_estimate", "liouville_residual",
                "mode_condition", "model_error"]:
        assert same(j[key], getattr(r, key)), key
    assert j["rhs_evals"] == r.rhs_evals
    assert j["diagnostics"] == r.diagnostics
    assert [m["description"] for m in j["modes"]] == list(r.mode_descriptions)


HILL_CASES = [("mathieu", {"a": "1.5", "q": "2"}, []), ("meissner", {}, []),
              ("jeffcott", {}, ["--harmonics", "12"]),
              (FIVE_MW, {}, ["--harmonics", "6"])]  # samples: the sampling error, a rigid mode


@pytest.mark.parametrize("scene,parameters,extra", HILL_CASES,
                         ids=[Path(c[0]).name for c in HILL_CASES])
def test_hill_equals_cli(ltp_cli, scene, parameters, extra):
    args = ["floquet", scene, "--method", "hill", "--keep-going", *extra]
    for k, v in parameters.items():
        args += ["--set", f"{k}={v}"]
    j = ltp_cli(*args)
    harmonics = int(extra[1]) if extra else "auto"
    h = ltp.hill(ltp.scene(scene, **parameters), harmonics=harmonics)
    assert_modes_equal(j, h)
    assert j["harmonics"] == h.harmonics and j["matrix_size"] == h.matrix_size
    assert j["solver"] == h.solver and j["selection_rule"] == h.selection_rule
    for k, m in enumerate(j["modes"]):
        assert same(m["selection_margin"], h.selection_margins[k])
        assert same(m["tail_weight"], h.tail_weights[k])
    for key in ["max_real_exponent", "truncation_estimate", "apriori_bound", "koopman_discrepancy",
                "error_estimate", "fourier_fit_error", "model_error"]:
        assert same(j[key], getattr(h, key)), key
    assert j["tolerance_met"] == h.tolerance_met
    assert j["coefficient_decay"]["kind"] == h.coefficient_decay["kind"]
    assert same(j["coefficient_decay"]["rate"], h.coefficient_decay["rate"])
    assert j["verdict"] == h.verdict and j["ok"] == h.ok
    assert j["diagnostics"] == h.diagnostics
    if scene == FIVE_MW:  # the samples' error is in the estimate; the rigid rotation is not a verdict
        assert h.model_error > 0 and h.error_estimate >= h.model_error
        assert sum(h.rigid_body) == 1 and h.verdict == "stable"


def assert_pfrf_equal(j, r):
    assert j["orders"] == [int(r.orders[0]), int(r.orders[-1])]
    assert j["primary_route"] == r.primary_route and j["route_choice"] == r.route_choice
    assert j["route_reason"] == r.route_reason
    assert j["input"] == r.input and j["output"] == r.output
    assert same(j["fp_hz"], r.fp_hz) and same(j["period"], r.period)
    zmin = int(r.orders[0])
    assert len(j["values"]) == r.H.size
    for v in j["values"]:
        i = int(np.searchsorted(r.frequencies_hz, v["f_exc_hz"]))
        assert r.frequencies_hz[i] == v["f_exc_hz"]
        c = v["z"] - zmin
        assert same(v["re"], r.H[i, c].real) and same(v["im"], r.H[i, c].imag)
        assert same(v["error_estimate"], r.error_estimate[i, c])
        assert same(v["f_resp_hz"], r.response_frequencies_hz[i, c])
        assert v["checked"] == bool(r.checked[i])
    for key in ["max_disagreement", "max_relative_disagreement", "htf_truncation_change", "settle_time"]:
        assert same(j[key], getattr(r, key)), key
    assert j["htf_harmonics"] == r.htf_harmonics
    assert j["modal_reliable"] == r.modal_reliable
    assert same(j["modal_condition"], r.modal_condition) if r.modal_condition is not None else j["modal_condition"] is None
    for k, e in enumerate(j["floquet_exponents"]):
        assert same(e["re"], r.floquet.exponents[k].real) and same(e["im"], r.floquet.exponents[k].imag)
    assert len(j["resonances"]) == len(r.resonances)
    for a, b in zip(j["resonances"], r.resonances):
        assert a["z"] == b["z"] and a["mode"] == b["mode"] + 1 and a["harmonic"] == b["harmonic"]
        for key in ["f_exc_hz", "f_resp_hz", "abs", "mode_line_hz", "share"]:
            assert same(a[key], b[key]), key
    for a, b in zip(j["routes"], r.routes):
        assert a["route"] == b["route"] and a["points"] == len(b["points"]) and a["failures"] == b["failures"]
        assert same(a["max_deviation_from_primary"], b["max_deviation_from_primary"])
    assert j["ok"] == r.ok and j["diagnostics"] == r.diagnostics


def test_pfrf_tower_rotor_equals_cli(ltp_cli):
    # The paper's system (Fig. 5) on a band around its first resonances, by channel names.
    j = ltp_cli("pfrf", "tower-rotor", "--input", "Fz_tip", "--output", "z_tip", "--freq", "0:40:0.5",
                "--orders", "-4:4")
    r = ltp.pfrf(ltp.scene("tower-rotor"), "0:40:0.5", input="Fz_tip", output="z_tip", orders="-4:4")
    assert_pfrf_equal(j, r)


def test_pfrf_mathieu_all_routes_equals_cli(ltp_cli):
    j = ltp_cli("pfrf", "mathieu", "--set", "a=2", "--set", "c=0.2", "--freq", "0.1:0.5:0.1",
                "--route", "all", "--orders", "-1:1", "--check-every", "2")
    r = ltp.pfrf(ltp.scene("mathieu", a=2, c=0.2), "0.1:0.5:0.1", route="all", orders=(-1, 1), check_every=2)
    assert_pfrf_equal(j, r)


def test_snapshot_fig6_equals_cli(ltp_cli):
    # Paper Fig. 6: the frozen system at 90° against the periodic system's summed partials.
    j = ltp_cli("snapshot", "tower-rotor", "--angle", "90", "--compare", "--freq", "0:200:2",
                "--input", "Fz_tip", "--output", "z_tip")
    s = ltp.snapshot(ltp.scene("tower-rotor"), "0:200:2", angle=90, compare=True, input="Fz_tip",
                     output="z_tip")
    assert j["time"] == s.time and j["angle_deg"] == s.angle_deg
    for i, v in enumerate(j["values"]):
        assert v["f_hz"] == s.frequencies_hz[i]
        assert same(v["re"], s.snapshot[i].real) and same(v["im"], s.snapshot[i].imag)
        assert same(v["summed_re"], s.summed[i].real) and same(v["summed_im"], s.summed[i].imag)
        assert same(v["summed_error_estimate"], s.summed_error[i])
    for k, e in enumerate(j["snapshot_eigenvalues"]):
        assert same(e["re"], s.eigenvalues[k].real) and same(e["im"], s.eigenvalues[k].imag)
    for k, e in enumerate(j["floquet_exponents"]):
        assert same(e["re"], s.floquet_exponents[k].real) and same(e["im"], s.floquet_exponents[k].imag)
    assert same(j["max_summed_disagreement"], s.max_summed_disagreement)
    assert j["modal_reliable"] == s.modal_reliable and j["diagnostics"] == s.diagnostics


def assert_chart_equal(j, c):
    assert j["integrator"] == c.integrator and j["method"] == c.method and j["tol"] == c.tol
    assert j["points"] == len(c.verdicts)
    for verdict in ["stable", "marginal", "unstable", "failed"]:
        assert j[verdict] == c.counts[verdict], verdict
    assert j["checked_points"] == c.checked_points
    assert same(j["max_error_estimate"], c.max_error_estimate)
    assert [a["name"] for a in j["sweep"]] == list(c.axes)
    assert [a["count"] for a in j["sweep"]] == [len(v) for v in c.values]


def test_chart_campbell_equals_cli(ltp_cli, tmp_path):
    # A two-bladed rotor with unstable bands (README's Campbell diagram, a coarser grid).
    sets = {"blades": "2", "C_zeta": "0.02", "cx": "0.2", "cy": "0.2"}
    args = ["chart", "rotor", "--sweep", "Omega=0.3:1.8:0.05", "--csv", str(tmp_path / "c.csv")]
    for k, v in sets.items():
        args += ["--set", f"{k}={v}"]
    j = ltp_cli(*args)
    c = ltp.chart(ltp.scene("rotor", **sets), "Omega=0.3:1.8:0.05")
    assert_chart_equal(j, c)
    assert len(j["unstable_intervals"]) == len(c.unstable_intervals) > 0
    for (lo, hi), (plo, phi) in zip(j["unstable_intervals"], c.unstable_intervals):
        assert same(lo, plo) and same(hi, phi)
    assert same(j["mode_tracking"]["min_mac"], c.mode_tracking["min_mac"])
    # Per point, the CSV (written with 12 significant digits) against the arrays.
    rows = (tmp_path / "c.csv").read_text().splitlines()
    header = rows[0].split(",")
    assert len(rows) - 1 == len(c.verdicts)
    for i, row in enumerate(rows[1:]):
        cells = dict(zip(header, row.split(",")))
        assert cells["Omega"] == f"{c.point_values[i, 0]:.12g}"
        assert cells["max_real_exponent"] == f"{c.max_real_exponent[i]:.12g}"
        assert cells["verdict"] == c.verdicts[i]
        unchecked = np.isnan(c.error_estimate[i])  # an empty CSV cell
        assert cells["error_estimate"] == ("" if unchecked else f"{c.error_estimate[i]:.12g}")
        for k, line in enumerate(c.lines):  # the Campbell lines, one per physical mode
            assert cells[f"freq_hz_{k + 1}"] == f"{line['frequency_hz'][i]:.12g}"
            assert cells[f"real_{k + 1}"] == f"{line['real_part'][i]:.12g}"
    # The same lines, names and crossings as the CLI's JSON.
    assert [l["description"] for l in j["campbell"]["lines"]] == [l["description"] for l in c.lines]
    assert len(j["campbell"]["crossings"]) == len(c.crossings)
    for a, b in zip(j["campbell"]["crossings"], c.crossings):
        assert a["per_rev"] == b["per_rev"] and same(a["parameter"], b["parameter"])


def test_chart_stability_map_equals_cli(ltp_cli):
    # A coarse Ince–Strutt chart of the damped Mathieu equation.
    j = ltp_cli("chart", "mathieu", "--sweep", "a=-1:5:0.5", "--sweep2", "q=0:3:0.5", "--refine-lines", "4")
    c = ltp.chart("mathieu", "a=-1:5:0.5", ("q", 0, 3, 0.5), refine_lines=4)
    assert_chart_equal(j, c)
    assert c.check_every == 97 and c.integrator == "taylor"  # Mathieu: a Fourier series
    assert len(j["boundary_points"]) == len(c.boundary_points) > 0
    for (a, q), (pa, pq) in zip(j["boundary_points"], c.boundary_points):
        assert same(a, pa) and same(q, pq)


def test_hill_study_equals_cli(ltp_cli):
    j = ltp_cli("hill", "mathieu", "--set", "a=1.5", "--set", "q=2", "--max-harmonics", "12")
    s = ltp.hill_study(ltp.scene("mathieu", a=1.5, q=2), max_harmonics=12)
    assert len(j["rows"]) == len(s.harmonics)
    for i, row in enumerate(j["rows"]):
        assert row["harmonics"] == s.harmonics[i] and row["matrix_size"] == s.matrix_size[i]
        for key in ["max_error", "apriori_bound", "truncation_estimate", "selection_margin", "tail_weight"]:
            assert same(row[key], getattr(s, key)[i]), (i, key)
        assert all(same(e, s.errors[i, k]) for k, e in enumerate(row["errors"]))
    for k, e in enumerate(j["reference"]):
        assert same(e["re"], s.reference[k].real) and same(e["im"], s.reference[k].imag)
    for k, e in enumerate(j["exponents"]):
        assert same(e["re"], s.last.exponents[k].real) and same(e["im"], s.last.exponents[k].imag)
        assert same(e["centroid"], s.last.centroids[k])
    assert j["convergence"]["kind"] == s.convergence["kind"] and same(j["convergence"]["rate"], s.convergence["rate"])
    assert same(j["koopman_discrepancy"], s.last.koopman_discrepancy)
    assert j["ok"] == s.last.ok and j["diagnostics"] == s.diagnostics


def test_orbit(ltp_cli):
    """`ltp orbit --unbalance` equals HarmonicTransferFunction.orbits with the weights (1, -1j)
    at ω = 2π·f (the CLI takes Hz, Python rad/s), order by order."""
    j = ltp_cli("orbit", "jeffcott", "--set", "c=0.05", "--set", "Omega=0.5", "--unbalance",
                "fx,fy", "--freq", "0.1,0.25", "--orders", "-2:2")
    h = ltp.HarmonicTransferFunction(ltp.scene("jeffcott", c=0.05, Omega=0.5))
    for f in j["frequencies"]:
        o = h.orbits(2 * np.pi * f["f_exc_hz"], [1, -1j], x="x", y="y", orders=(-2, 2))
        for k, v in enumerate(f["orders"]):
            assert v["z"] == o["order"][k]
            # the CLI prints Hz: the frequency back in rad/s to rounding
            assert abs(v["f_resp_hz"] * 2 * np.pi - o["frequency"][k]) < 1e-15
            assert same(v["x"]["re"], o["x"][k].real) and same(v["x"]["im"], o["x"][k].imag), k
            assert same(v["y"]["re"], o["y"][k].real) and same(v["y"]["im"], o["y"][k].imag), k
            for key in ("forward", "backward", "semi_major", "semi_minor"):
                assert same(v[key], o[key][k]), (key, k)


def test_orbit_sweep(ltp_cli):
    """HarmonicTransferFunction.orbit_sweep is what `ltp orbit` prints: the same values, each
    value's estimate (the two routes' difference), its sense, the routes and the verdict."""
    j = ltp_cli("orbit", "jeffcott", "--set", "c=0.05", "--set", "Omega=0.5", "--unbalance",
                "fx,fy", "--freq", "0.1,0.25", "--orders", "-2:2")
    h = ltp.HarmonicTransferFunction(ltp.scene("jeffcott", c=0.05, Omega=0.5))
    r = h.orbit_sweep([2 * np.pi * 0.1, 2 * np.pi * 0.25], [1, -1j], x="x", y="y", orders=(-2, 2))
    assert r["ok"] == j["ok"] and r["route"] == j["route"] and r["check_route"] == j["check_route"]
    assert r["forward"].shape == (2, 5) and r["order"].dtype == np.int64
    for i, f in enumerate(j["frequencies"]):
        for k, v in enumerate(f["orders"]):
            assert v["z"] == r["order"][k]
            for key in ("forward", "backward", "semi_major", "semi_minor", "error_estimate"):
                assert same(v[key], r[key][i, k]), (key, i, k)
            assert v["whirl"] == r["sense"][i][k], (i, k)
