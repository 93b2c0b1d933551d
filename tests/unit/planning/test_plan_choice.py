"""Which screened designs the planner runs in 3D (:func:`~blastscale.planning.plan3d_designs.choose_3d`), and the
ranking's two error columns (screened and simulated, never one mixed column)."""

import math

from blastscale.planning.candidates import Candidate, Evaluated
from blastscale.planning.plan3d_designs import choose_3d
from blastscale.planning.recommend import rank_key
from blastscale.report.plan_files import error_cells


def _scored(*rows):
    """(screening error, Evaluated) pairs in screening order from (error, material, 1/lambda) rows."""
    return [(err, Evaluated(Candidate("general", 1.0 / n, mat, 1.0))) for err, mat, n in rows]


def test_the_best_of_each_material_and_the_largest_scale_run_in_3d():
    """The old rule (the first lab.top_3d = 3 by screening error) ran three marble designs and missed both the
    only sandstone design and the 1/8 specimen (the largest the lab admits); the new rule runs them too."""
    scored = _scored(
        (0.010, "marble", 20),
        (0.011, "marble", 25),
        (0.012, "marble", 40),
        (0.050, "sandstone", 10),
        (0.055, "sandstone", 15),  # not the best sandstone, not the largest scale: screened only
        (0.060, "marble", 8),
    )
    old = set(range(3))
    chosen = choose_3d(scored, 3)
    assert 3 not in old and 5 not in old  # what the old rule missed
    assert list(chosen) == [0, 1, 2, 3, 5]  # screening order kept; index 4 is not chosen (the answer "no")
    assert chosen[3] == ["best screened design in sandstone"]
    assert chosen[5] == ["largest admissible scale (1/8)"]
    assert chosen[0] == ["screening rank 1 (lab.top_3d = 3)", "best screened design in marble"]


def test_the_choice_at_its_edges():
    """lab.top_3d larger than the feasible designs: all of them, once each; one design: it alone, for all three
    reasons; the largest scale already the best of its material: no second run."""
    scored = _scored((0.01, "same", 10), (0.02, "same", 4))
    assert list(choose_3d(scored, 50)) == [0, 1]
    (only,) = choose_3d(scored[:1], 1).values()
    assert only == [
        "screening rank 1 (lab.top_3d = 1)",
        "best screened design in same",
        "largest admissible scale (1/10)",
    ]
    assert list(choose_3d(_scored((0.01, "lead", 2), (0.02, "lead", 4)), 1)) == [0]


def _design(sim_by, p, sim_err, scr_err, radius=1.0):
    return {
        "simulated_by": sim_by,
        "p_outcome_agree": p,
        "predicted_first_peak_error": sim_err,
        "screening_error": scr_err,
        "safety_radius_m": radius,
    }


def test_a_design_simulated_ranks_before_one_screened_whatever_the_two_errors():
    """The screened design's 1.7 % (closed form) is not compared with the simulated 16 % (3D): two kinds of error,
    two columns; simulated designs first, then screened ones by their screening error."""
    sim = _design("3d", 1.0, 0.16, 0.02)
    scr_a, scr_b = _design(None, None, None, 0.017), _design(None, None, None, 0.0125, radius=9.0)
    ranked = sorted([scr_a, sim, scr_b], key=rank_key)
    assert ranked == [sim, scr_b, scr_a]  # 1.2 % before 1.7 % despite the larger safety radius
    assert error_cells(sim) == ("2 %", "16 % (3D)")
    assert error_cells(scr_a) == ("1.7 %", "-")
    assert error_cells(_design("planar", 1.0, 0.064, 0.0007)) == ("0.07 %", "6.4 % (planar)")
    assert math.isinf(rank_key(_design(None, None, None, math.nan))[1])  # no estimate: last of the screened
