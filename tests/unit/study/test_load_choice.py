"""The load method's and clearing's weight against the verdict's tolerance (issue #39, deliverable 3;
blastscale.study.load_choice): Method A on a circular column warns with the measured factor, the reference
method does not, a tolerance wider than the difference does not, and the plan states the load it assumed."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from blastscale.planning.planner import load_assumed
from blastscale.scenario import Scenario, load_scenario
from blastscale.sim3d.load_methods import make_load
from blastscale.study import Study
from blastscale.study.load_choice import load_choice, overturning_impulse


def _checked(name, **values):
    sc = load_scenario(name).with_values(values)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return sc, Study(sc).check()


@pytest.fixture(scope="module")
def circular():
    """The issue's case: the paper's circular column (10 drums) under 500 kg at 20 m, Method A."""
    return _checked(
        "paper_column_circular_200kg", **{"blast.charge_kg": 500.0, "blast.standoff_m": 20.0, "scale.length": 0.05}
    )


def test_method_a_overturning_impulse_is_the_reflected_impulse_times_the_faces_moments(circular):
    """Closed form of Method A: every drum's front gets the reflected impulse i_r at normal incidence, so
    H = -i_r sum_b S_b n_x,b z_b (S_b the front's area, n_x,b its outward normal's x component: the taper tilts
    it by ~1e-4 rad here, z_b the drum's centre height); to round-off."""
    sc, plan = circular
    s, bp = plan.structure, plan.blast
    load = make_load("A", s, bp, pulse_shape=sc.blast.pulse_shape)
    hand = bp.pulse(sc.blast.pulse_shape).impulse * sum(
        -b.load_face.area * b.load_face.normal[0] * b.com[2] for b in s.bodies
    )
    assert overturning_impulse(load, s) == pytest.approx(hand, rel=1e-12)


def test_method_a_on_a_circular_column_warns_with_the_measured_factor(circular):
    sc, plan = circular
    c = load_choice(sc, plan.structure, plan.blast, plan.design)
    H = c.overturning_impulse_N_s_m
    assert c.reference == "C" and c.method_factor == pytest.approx(H["A"] / H["C"], rel=1e-12)
    # Method C loads the cylinder's oblique faces at their incidence and pushes back on the rear: well below A.
    # Its square (the first peak's estimate) near the 3D runs' 151 mm / 22 mm = 6.9 (issue #39): within 15 %.
    assert 2.0 < c.method_factor < 3.5
    assert c.method_factor**2 == pytest.approx(151 / 22, rel=0.15)
    (note,) = [n for n in c.notes if n.startswith("load method A")]
    assert f"x{c.method_factor:.3g}" in note and "Method C" in note and "cylinder" in note
    assert "UFC 3-340-02 Sec. 2-16" in note and "docs/face_loads.md" in note


def test_no_warning_for_the_reference_method_or_a_wide_tolerance():
    sc, plan = _checked("paper_column_square_250kg", **{"blast.load": "C"})
    c = load_choice(sc, plan.structure, plan.blast)
    assert c.method_factor == 1.0 and not [n for n in c.notes if n.startswith("load method")]
    # the edge: Method A, factor ~2.4 on the square column, under a tolerance of 10 (its largest): |f - 1| < 10
    sc, plan = _checked("paper_column_square_250kg", **{"verdict.peak": 10.0})
    c = load_choice(sc, plan.structure, plan.blast)
    assert 1.5 < c.method_factor < 3.5 and c.notes == ()
    assert load_choice(Scenario.default().with_values({"engine": "planar"}), plan.structure, plan.blast) is None


def test_a_run_says_so_and_keeps_the_figures(circular):
    """A short 3D run (3 drums, 0.02 s): the warning among the study's, the numbers in its summary."""
    sc = load_scenario("paper_column_circular_200kg").with_values(
        {
            "structure.drums": 3,
            "simulation.duration_s": 0.02,
            "blast.charge_kg": 500.0,
            "blast.standoff_m": 20.0,
            "scale.length": 0.05,
        }
    )
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        r = Study(sc).run()
    s = r.summary()["load_choice"]
    assert s["method"] == "A" and s["reference"] == "C" and s["method_factor"] > 1.05
    assert s["first_peak_factor_estimate"] == pytest.approx(s["method_factor"] ** 2)
    assert any(w.startswith("load method A") and f"x{s['method_factor']:.3g}" in w for w in r.warnings)
    assert np.isfinite(s["overturning_impulse_N_s_m"]["C"])


def test_the_plan_states_the_load_it_assumed():
    sc = load_scenario("paper_column_square_250kg")
    assert load_assumed(sc, planar=False)["load_method"] == "A"
    assert load_assumed(sc.with_values({"blast.load": "C"}), planar=False)["load_assumed"].startswith("load: Method C")
    planar = load_assumed(sc.with_values({"blast.load": "C"}), planar=True)  # the planar path is A's load
    assert planar["load_method"] == "A" and "planar" in planar["load_assumed"]
