"""The plan's recommendation by the one similarity criterion (:mod:`blastscale.planning.recommend`): designs the
criterion passes rank first whatever their odds; a rejected design is never recommended; when none passes, one
line names the closest design (the smallest worst ratio), the binding quantity and the lab limit that rejects
the next larger specimen."""

import math

from blastscale.planning.recommend import rank_key, ranked_after, recommend


def _worst(quantity, ratio, where="P-1"):
    return {
        "quantity": quantity,
        "where": where,
        "prototype": 0.010,
        "model": 0.010 * (1 + 0.05 * ratio),
        "error": 0.05 * ratio,
        "tolerance": 0.05,
        "ratio": ratio,
        "unit": "m",
        "basis": "single",
    }


def _d(similar, ratio, p=1.0, err=0.1, radius=5.0, scale=0.25, material="sandstone", quantity="first peak"):
    return {
        "law": "general",
        "scale": scale,
        "scale_fraction": f"1/{round(1 / scale)}",
        "material": material,
        "burst": "surface",
        "charge_height_m": 0.0,
        "simulated_by": "3d",
        "p_outcome_agree": p,
        "predicted_first_peak_error": err,
        "similarity_error": err,
        "screening_error": 0.01,
        "safety_radius_m": radius,
        "verdict": None
        if similar == "unjudged"
        else {"similar": similar, "line": "Verdict: ...", "worst": _worst(quantity, ratio), "limits": []},
    }


def test_a_passing_design_ranks_first_whatever_its_odds_and_error():
    """The old ranking (odds, then error) put the rejected design first: P 1.00 and 2 % against P 0.50 and 30 %."""
    rejected = _d(False, 1.8, p=1.0, err=0.02, radius=1.0)
    passing = _d(True, 0.9, p=0.5, err=0.30, radius=9.0)
    ranked = sorted([rejected, passing], key=rank_key)
    assert ranked == [passing, rejected]
    rec = recommend(ranked, [])
    assert rec["design"] == 0 and rec["closest"] is None and rec["line"].startswith("Recommended: general law")
    assert ranked_after(passing, rejected) == "ranked after a design the criterion passes"


def test_none_passes_one_line_names_the_closest_the_quantity_and_the_limit():
    """Three rejected designs: the closest is the one with the smallest worst ratio (1.04, not the best odds); the
    next larger sandstone specimen (1/2) is rejected by the lab's height limit: that limit binds."""
    far = _d(False, math.inf, p=1.0, err=0.01, quantity="outcome")  # an outcome that differs: ratio inf
    close = _d(False, 1.04, p=0.5, err=0.2, quantity="residual displacement")
    mid = _d(False, 3.0, p=1.0, err=0.05, scale=0.2)
    ranked = sorted([far, mid, close], key=rank_key)
    assert ranked == [close, mid, far]
    lab_rejects = [
        {
            "law": "general",
            "scale": 0.5,
            "material": "sandstone",
            "burst": "surface",
            "constraints": ["specimen_max_height_m"],
            "reasons": ["specimen 1.354 m high > specimen_max_height_m = 1 m"],
        },
        {  # larger still, and another material: not the next larger sandstone specimen
            "law": "general",
            "scale": 1.0,
            "material": "sandstone",
            "burst": "surface",
            "constraints": ["charge_max_kg"],
            "reasons": ["x"],
        },
        {
            "law": "general",
            "scale": 0.5,
            "material": "marble",
            "burst": "surface",
            "constraints": ["y"],
            "reasons": ["y"],
        },
    ]
    rec = recommend(ranked, lab_rejects)
    assert rec["design"] is None and rec["closest"] == 0
    assert rec["binding_quantity"] == "residual displacement" and rec["binding_ratio"] == 1.04
    line = rec["line"]
    assert line.startswith(
        "No design passes the similarity criterion ([verdict]; 3 judged): the closest is general law"
    )
    assert (
        "lambda = 1/4, sandstone" in line
        and "ratio 1.04" in line
        and "the binding quantity: residual displacement" in line
    )
    assert "the binding lab limit: specimen_max_height_m (the next larger specimen, lambda = 1/2 in sandstone" in line
    assert "charge_max_kg" not in line and "y" not in rec["binding_limit"].split("(")[0]
    assert ranked_after(close, mid) == "ranked after a design closer to the criterion"


def test_the_edges_no_larger_specimen_unjudged_and_not_established():
    """The largest specimen is the closest: no lab limit is named; a verdict of None (nothing compared) is never
    recommended; a design simulated but not judged ranks after the judged ones and before the screened ones."""
    only = _d(None, math.nan)
    only["verdict"]["worst"] = None
    unjudged = _d("unjudged", 0.0, p=1.0, err=0.0)
    screened = {
        **_d("unjudged", 0.0),
        "simulated_by": None,
        "p_outcome_agree": None,
        "predicted_first_peak_error": None,
    }
    ranked = sorted([screened, unjudged, only], key=rank_key)
    assert ranked == [only, unjudged, screened]
    rec = recommend(ranked, [])
    assert rec["design"] is None and rec["binding_limit"] is None and "(nothing compared)" in rec["line"]
    assert ranked_after(unjudged, screened) == "ranked after the designs simulated (this one is screened only)"


def test_rejected_designs_tie_on_their_comparison_not_on_an_ensembles_spread():
    """Two designs rejected alike (an outcome differs: ratio inf) with the same comparison (0.81 %): the one with an
    ensemble (4.3 % with its spread) and the one without (0.81 %) tie; ranked by the simulated error, the one without
    an ensemble would look closer for lack of a spread."""
    with_ensemble, without = _d(False, math.inf, err=0.043), _d(False, math.inf, err=0.0081)
    with_ensemble["similarity_error"] = without["similarity_error"] = 0.0081
    assert rank_key(with_ensemble) == rank_key(without)
    nearer = {**without, "similarity_error": 0.005}
    assert rank_key(nearer) < rank_key(with_ensemble)
    assert ranked_after(nearer, with_ensemble) == "ranked after a design with a smaller similarity error"
