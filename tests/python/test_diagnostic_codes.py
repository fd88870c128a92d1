"""Diagnostics carry a code beside their sentence: result.diagnostic_codes is parallel to
result.diagnostics (same length, same order), one stable snake_case name per entry."""
import pathlib
import re

import ltp


def test_floquet_diagnostic_codes_are_parallel_to_the_sentences():
    # The integrator and segment choices are always reported under auto (ltp floquet mathieu
    # prints them as "integrator auto → …" and "segments auto → …").
    r = ltp.floquet(ltp.scene("mathieu", a=1.5, q=2))
    assert r.ok and r.termination == "completed"
    assert len(r.diagnostics) >= 2
    assert len(r.diagnostic_codes) == len(r.diagnostics)
    assert all(re.fullmatch(r"[a-z0-9_]+", c) for c in r.diagnostic_codes)
    sentences = dict(zip(r.diagnostic_codes, r.diagnostics))
    assert sentences["integrator_chosen"].startswith("integrator auto → ")
    assert sentences["segments_chosen"].startswith("segments auto → ")


def test_a_failed_check_is_named_by_its_code():
    # One segment with single-shot multipliers loses the multiplier e^{-120π} of
    # stiff-rotating.yaml (exponents −60 and 2): the Liouville check fails (the CLI exits 1,
    # tests/cli/cli_test.cc), and the code and the termination say so.
    stiff = pathlib.Path(__file__).resolve().parents[1] / "data" / "stiff-rotating.yaml"
    r = ltp.floquet(ltp.scene(str(stiff)), segments=1, multipliers="single-shot")
    assert not r.ok and r.termination == "checks_failed"
    assert "liouville_check_failed" in r.diagnostic_codes
    k = r.diagnostic_codes.index("liouville_check_failed")
    assert r.diagnostics[k] == r.failure


def test_the_route_choice_has_a_code_beside_its_sentence():
    # Damped Mathieu: the modal model is resolved, so auto runs the modal route first, checked
    # by htf (as tests/htf/pfrf_route_choice_test.cc finds for the same kind of system); a named
    # route is "as requested".
    mathieu = ltp.scene("mathieu", a=2, c=0.2)
    auto = ltp.pfrf(mathieu, "0.1:0.5:0.1", orders=(-1, 1))
    assert auto.primary_route == "modal" and auto.route_reason == "modal_resolved"
    named = ltp.pfrf(mathieu, "0.1:0.5:0.1", route="htf", orders=(-1, 1))
    assert named.primary_route == "htf" and named.route_reason == "as_requested"
    assert named.route_choice.endswith("as requested")
