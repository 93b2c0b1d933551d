"""The plan's judgement of its designs by the one similarity criterion, its ranking and its recommendation
(docs/planning.md, "The recommendation").

Every design the planner simulates through a Study carries that Study's verdict
(:func:`~blastscale.study.criterion.judge`, the summary's ``verdict``, under the scenario's ``[verdict]``
tolerances). The ranking puts, in this order:

0. the designs the criterion passes (``verdict.similar`` true), by their odds (``p_outcome_agree`` to
   0.01, higher first), then the simulated error (two significant digits), then the safety radius;
1. the designs it rejects or cannot establish, closest first: by the worst judged quantity's ratio
   (error / tolerance; an outcome that differs: inf), then the comparison's own error
   (``similarity_error``, two significant digits: the same basis whether the design had an ensemble or
   not), then the safety radius;
2. the designs simulated but not judged (the planar path's designs after the first that passes), by
   their odds, simulated error and safety radius;
3. the designs screened only, by screening error, then safety radius.

The recommendation is the first design only when the criterion passes it; otherwise none is recommended
and one line says so, names the closest design (the smallest worst ratio), the binding quantity and, when
a larger specimen of the same material is what a lab limit rejects, that limit.
"""

from __future__ import annotations

import math
from typing import Optional

from .candidates import scale_label

__all__ = ["verdict_of", "rank_key", "ranked_after", "recommend", "design_words", "verdict_tolerances"]


def _two_digits(x) -> float:
    return float(f"{x:.2g}") if x is not None and math.isfinite(x) else math.inf


def verdict_of(summary: dict) -> dict:
    """The part of a Study summary's ``verdict`` a plan keeps per design: ``similar`` (True, False or None),
    ``line``, ``worst`` (quantity, where, prototype, model, error, tolerance, ratio, unit, basis; None when
    nothing was judged) and ``limits``."""
    v = summary["verdict"]
    return {"similar": v["similar"], "line": v["line"], "worst": v["worst"], "limits": list(v.get("limits") or [])}


def worst_ratio(d: dict) -> float:
    """The worst judged quantity's error / tolerance of a judged design (inf when nothing was judged)."""
    w = (d.get("verdict") or {}).get("worst")
    return math.inf if w is None else float(w["ratio"])


def rank_key(d: dict) -> tuple:
    """The plan's ranking key of a design dict (module docstring): (group, then two keys, then the safety radius)."""
    p = d.get("p_outcome_agree")
    odds = -round(p, 2) if p is not None and math.isfinite(p) else 0.0
    err = _two_digits(d.get("predicted_first_peak_error"))
    r = d["safety_radius_m"]
    if d.get("simulated_by") is None:
        return (3, _two_digits(d.get("screening_error")), 0.0, r)
    v = d.get("verdict")
    if v is None:
        return (2, odds, err, r)
    if v["similar"] is True:
        return (0, odds, err, r)
    return (1, worst_ratio(d), _two_digits(d.get("similarity_error")), r)


def ranked_after(best: dict, d: dict) -> str:
    """Why ``d`` ranks after ``best`` (:func:`rank_key`), in words."""
    kb, kd = rank_key(best), rank_key(d)
    if kb[0] < kd[0]:
        if kb[0] == 0:
            return "ranked after a design the criterion passes"
        return "ranked after the designs " + ("simulated (this one is screened only)" if kd[0] == 3 else "judged")
    if kb[1] < kd[1]:
        return (
            "ranked after a design "
            + {
                0: "with better odds",
                1: "closer to the criterion",
                2: "with better odds",
                3: "with a smaller screening error",
            }[kb[0]]
        )
    if kb[2] < kd[2]:
        return "ranked after a design with a smaller " + ("similarity error" if kb[0] == 1 else "simulated error")
    return "ranked after a design with a smaller safety radius"


def design_words(d: dict) -> str:
    """``general law, lambda = 1/4, sandstone`` (and the charge's burst when on a stand)."""
    stand = f", {d['burst']} burst" if d.get("charge_height_m") else ""
    return f"{d['law']} law, lambda = {d['scale_fraction']}, {d['material']}{stand}"


def _worst_words(w: dict) -> str:
    if w["quantity"] == "outcome" or not math.isfinite(w["ratio"]):
        return f"{w['quantity']} of {w['where']} differs"
    unit, k = w.get("unit") or "", 1.0
    if unit == "m":
        unit, k = "mm", 1e3
    return (
        f"{w['quantity']} at {w['where']}, {k * w['model']:.4g} {unit} (up-scaled model) vs {k * w['prototype']:.4g} "
        f"{unit} (prototype), {100 * w['error']:.3g} % off, tolerance {100 * w['tolerance']:.3g} %, ratio "
        f"{w['ratio']:.3g}"
    ).replace("  ", " ")


def _binding_limit(d: dict, rejected: list) -> Optional[str]:
    """The lab limit that rejects the next larger specimen of ``d``'s material, law and burst (None: there is
    none, or it is feasible)."""
    same = [
        r
        for r in rejected
        if r["material"] == d["material"]
        and r["law"] == d["law"]
        and r.get("burst") == d.get("burst")
        and r["scale"] > d["scale"]
    ]
    if not same:
        return None
    nxt = min(same, key=lambda r: r["scale"])
    return (
        f"the binding lab limit: {', '.join(nxt['constraints'])} (the next larger specimen, lambda = "
        f"{scale_label(nxt['scale'])} in {nxt['material']}, is rejected: {'; '.join(nxt['reasons'])})"
    )


def recommend(designs: list, rejected: list) -> dict:
    """The plan's recommendation from its ranked ``designs`` (best first, :func:`rank_key`) and its ``rejected``
    candidates.

    Returns
    -------
    dict
        ``design``: the index of the recommended design (0) or None when the criterion passes none;
        ``closest``: the index of the closest judged design when none passes (else None);
        ``binding_quantity``, ``binding_where``, ``binding_ratio`` (the closest's worst judged quantity);
        ``binding_limit`` (a sentence or None) and ``line``, the one line the plan prints.
    """
    out = {
        "design": None,
        "closest": None,
        "binding_quantity": None,
        "binding_where": None,
        "binding_ratio": None,
        "binding_limit": None,
    }
    if not designs:
        return {**out, "line": "No design to recommend."}
    best = designs[0]
    v = best.get("verdict")
    if v is not None and v["similar"] is True:
        w = v["worst"]
        tail = "" if w is None else f"; the closest to its limit: {_worst_words(w)}"
        return {**out, "design": 0, "line": f"Recommended: {design_words(best)}: the criterion passes it{tail}."}
    judged = [d for d in designs if d.get("verdict") is not None]
    if not judged:
        return {
            **out,
            "line": f"No design is recommended: none was judged by the similarity criterion (the first ranked: "
            f"{design_words(best)}).",
        }
    c = min(range(len(designs)), key=lambda i: (rank_key(designs[i])[0] != 1, rank_key(designs[i])))
    d = designs[c]
    w = d["verdict"]["worst"]
    limit = _binding_limit(d, rejected)
    line = (
        f"No design passes the similarity criterion ([verdict]; {len(judged)} judged): the closest is "
        f"{design_words(d)}"
        + (f" ({_worst_words(w)}); the binding quantity: {w['quantity']}" if w else " (nothing compared)")
        + (f"; {limit}" if limit else "")
        + "."
    )
    return {
        **out,
        "closest": c,
        "binding_quantity": None if w is None else w["quantity"],
        "binding_where": None if w is None else w["where"],
        "binding_ratio": None if w is None else w["ratio"],
        "binding_limit": limit,
        "line": line,
    }


def verdict_tolerances(verdict_spec) -> str:
    """The ``[verdict]`` tolerances in words: ``peak 5 %, displacement 10 %, residual 20 % (floor 10 %)``."""
    t = verdict_spec
    return (
        f"peak {100 * t.peak:.3g} %, displacement {100 * t.displacement:.3g} %, residual {100 * t.residual:.3g} % "
        f"(floor {100 * t.floor:.3g} % of the structure's largest)"
    )
