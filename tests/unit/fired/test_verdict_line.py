"""Every marker enters the as-fired verdict (issue #36 item 3): the line names the marker whose measured and
re-simulated first peaks disagree most. The issue's case: a base marker read 0.96 mm and re-simulated 0.24 mm
(4x) beside a top marker within 3.8 %: the line says 75 % at the base, not 3.8 % at the top."""

from __future__ import annotations

from blastscale.fired.shot import as_fired_verdict_line, worst_marker


def marker(measured, refit):
    return {
        "first_peak_m": measured,
        "first_peak_time_s": None if measured is None else 0.186,
        "refit_first_peak_m": refit,
        "refit_vs_measured": None if measured is None or refit is None else refit / measured - 1.0,
    }


def summary(markers: dict) -> dict:
    return {
        "charge_ratio_impulse": 1.17,
        "markers": markers,
        "prototype_markers": {},
        "outcome_measured": "stands",
        "outcome_refit": "stands",
    }


def test_the_worst_marker_is_named():
    m = {"top": marker(45.4e-3, 47.1e-3), "base": marker(0.96e-3, 0.24e-3)}
    assert worst_marker(m) == "base"
    line = as_fired_verdict_line(summary(m))
    assert "agrees within 75 % at every marker (worst: base)" in line and "(base)" in line
    assert "3.8 %" not in line


def test_a_marker_with_no_re_simulated_peak_is_the_worst():
    """Edge: a measured peak with none re-simulated is an infinite disagreement."""
    m = {"top": marker(45.4e-3, 47.1e-3), "side": marker(2.0e-3, None)}
    assert worst_marker(m) == "side"
    assert "the re-simulation under that load has no first peak at side" in as_fired_verdict_line(summary(m))


def test_one_marker_names_no_worst_and_no_peak_says_nothing():
    """No: one marker is not "every marker"; a marker that never left the noise names no peak."""
    line = as_fired_verdict_line(summary({"top": marker(45.4e-3, 47.1e-3)}))
    assert "agrees within 3.7 %" in line and "worst" not in line
    assert worst_marker({"still": marker(None, None), "top": marker(45.4e-3, 47.1e-3)}) == "top"
    assert worst_marker({}) is None
    assert "rocked" not in as_fired_verdict_line(summary({"still": marker(None, None)}))
