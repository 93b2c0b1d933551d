"""The designs of a structure without a planar path, ranked (:mod:`.plan3d` for the stages): every
feasible design with its screening estimate; the designs chosen for 3D (:func:`choose_3d`: the best
``lab.top_3d`` screened, the best screened of each material and the best at the largest admissible
scale) with the 3D comparison, its verdict and the 3D odds; designs simulated in 3D rank first, judged
by the similarity criterion (:mod:`.recommend`: passing designs first, then the closest), the screened
ones after them by screening error, then safety radius. The screening error (closed form) and the
simulated error (3D) are separate keys, never one column (docs/planning.md, "Any structure")."""

from __future__ import annotations

import math
from typing import Optional

from ..analysis.intervals import wilson_interval
from .build import spec_dims
from .candidates import scale_label, shot_dict
from .card import specimen_timing
from .debris import planar_reach
from .instruments import top_corner_displacement
from .odds import ensemble_odds_3d, outcome_odds_text
from .plan3d import ENSEMBLE_3D_DEFAULT, run_3d, screening_error
from .recommend import rank_key, ranked_after, verdict_of, verdict_tolerances

__all__ = ["designs_3d", "choose_3d"]


def choose_3d(scored: list, top: int) -> dict:
    """Which screened designs run in 3D, and why (docs/planning.md, "Any structure").

    ``scored``: (screening error, Evaluated) pairs in screening order (best first). Chosen: the first
    ``top`` (``lab.top_3d``); the best screened design of each material (each material the lab offers and
    the screening admits is simulated at least once); the best screened design at the largest admissible
    scale lambda (the largest specimen the lab's limits allow, whatever its screening error: the closed-form
    estimate favours small specimens whose pulse matches, not the 3D response).

    Returns
    -------
    dict
        ``{index in scored: [reasons]}``, in screening order.
    """
    why: dict = {}
    for k in range(min(top, len(scored))):
        why.setdefault(k, []).append(f"screening rank {k + 1} (lab.top_3d = {top})")
    seen: set = set()
    for k, (_, e) in enumerate(scored):
        if e.candidate.material not in seen:
            seen.add(e.candidate.material)
            why.setdefault(k, []).append(f"best screened design in {e.candidate.material}")
    if scored:
        largest = max(e.candidate.scale for _, e in scored)
        k = next(i for i, (_, e) in enumerate(scored) if e.candidate.scale == largest)
        why.setdefault(k, []).append(f"largest admissible scale ({scale_label(largest)})")
    return dict(sorted(why.items()))


def _reasons(d: dict, best: dict, tolerances: str) -> list:
    if d["simulated_by"] is None:
        return [
            f"screened only (no 3D run: not among the screening leaders, the best of its material or the largest "
            f"admissible scale): screening error {100 * d['screening_error']:.2g} %",
            f"safety radius ({d['safety_threshold']}) {d['safety_radius_m']:.3g} m",
        ]
    o = d["odds_3d"] or {"agree_count": int(d["p_outcome_agree"]), "trials": 1}  # no ensemble: the one comparison
    v = d["verdict"]
    spread = (
        "no ensemble"
        if d["first_peak_spread"] is None
        else f"spread under the lab's tolerances {100 * d['first_peak_spread']:.2g} %"
    )
    out = [
        f"simulated in 3D as the {'; '.join(d['chosen_3d_for'])}",
        v["line"].removesuffix(".") + f" (tolerances [verdict]: {tolerances})",
        f"outcome agrees with the prototype's (3D runs of the lab's tolerances): {outcome_odds_text(o)}",
        f"simulated error {100 * d['predicted_first_peak_error']:.2g} % (3D similarity of the top's first peak "
        f"{100 * d['similarity_error']:.2g} %, {spread}; screening error {100 * d['screening_error']:.2g} %)",
        f"safety radius ({d['safety_threshold']}) {d['safety_radius_m']:.3g} m",
    ]
    if d is not best:
        out.append(ranked_after(best, d))
    return out


def _screened(e, err: float, lab) -> dict:
    """A design screened only: its screening error, no simulated error."""
    h, w, _ = spec_dims(e.specimen)
    return {
        **shot_dict(e, lab, top_corner_displacement(w, h, 0.0), planar_reach(w, h, 0.0, False)),
        "screening_error": err,
        "simulated_by": None,
        "chosen_3d_for": [],
        "verdict": None,
        "odds_3d": None,
        "similarity_3d": None,
        "p_outcome_agree": None,
        "p_outcome_agree_low": None,
        "p_outcome_agree_high": None,
        "first_peak_spread": None,
        "similarity_error": None,
        "predicted_first_peak_error": None,
        "charge_tolerance_needed": None,
        "weighing_precision_kg": None,
    }


def _simulated(e, err: float, why: list, lab, summary: dict, sim: dict, odds, timing=None) -> dict:
    """A design run in 3D: its screening error and, separately, its simulated error, odds and verdict; its
    instruments from its simulated ``timing`` (:func:`~.card.specimen_timing`: the test card's)."""
    s3 = summary["3d"]
    h, w, _ = spec_dims(e.specimen)
    reach = sim["specimen_reach_m"] if math.isfinite(sim["specimen_reach_m"]) else planar_reach(w, h, 0.0, True)
    agree = 1.0 if s3["similarity"].get("outcomes_agree", True) else 0.0
    lo, hi = wilson_interval(int(agree), 1)  # no ensemble: the one 3D comparison, 1 trial
    spread = odds["first_peak_spread"] if odds else None
    return {
        **shot_dict(e, lab, sim["specimen_top_m"], reach, timing),
        "screening_error": err,
        "simulated_by": "3d",
        "chosen_3d_for": why,
        "verdict": verdict_of(summary),
        "p_outcome_agree": odds["p_outcome_agree"] if odds else agree,
        "p_outcome_agree_low": odds["p_outcome_agree_low"] if odds else lo,
        "p_outcome_agree_high": odds["p_outcome_agree_high"] if odds else hi,
        "first_peak_spread": spread,
        "similarity_error": sim["error"],
        "predicted_first_peak_error": math.hypot(sim["error"], spread or 0.0),
        "charge_tolerance_needed": None,
        "weighing_precision_kg": None,
        "odds_3d": odds,
        "similarity_3d": {
            k2: s3["similarity"].get(k2)
            for k2 in (
                "outcomes_agree",
                "top_first_peak_ratio",
                "max_abs_top_displacement_diff_rel_peak",
                "arrival_spread_prototype_s",
                "arrival_spread_model_upscaled_s",
            )
        },
    }


def designs_3d(
    scenario, ok: list, proto: dict, lab, tol, tell, *, workers: int = 0, scheduler: Optional[str] = None
) -> tuple:
    """(designs best first, the prototype's record with its 3D outcome, notes, the first design's 3D Study result
    or None when it was not simulated) of a plan on the 3D path."""
    method = scenario.blast.load
    scored = sorted(
        ((screening_error(e, method), e) for e in ok), key=lambda se: (float(f"{se[0]:.2g}"), se[1].safety.radius_m)
    )
    members = lab.ensemble_3d if lab.ensemble_3d is not None else ENSEMBLE_3D_DEFAULT
    chosen = choose_3d(scored, lab.top_3d)
    total = len(chosen) * (members + 1)
    designs, notes, kept = [], [], None  # kept: (design, its Study result), the best ranked so far
    for k, (err, e) in enumerate(scored):
        if k not in chosen:
            designs.append(_screened(e, err, lab))
            continue
        n = sum(1 for d in designs if d["simulated_by"])
        done0 = n * (members + 1)
        stage = f"3D comparison and ensemble of design {n + 1} of {len(chosen)}"
        tell(stage, done0, total)
        lead = k < lab.top_3d  # a screening leader: its ensemble always; any other chosen design: if it passes
        res, sim, odds = run_3d(
            scenario,
            e,
            lab,
            members=members if lead else 0,
            tolerances=tol.for_shot(e.charge),
            workers=workers,
            scheduler=scheduler,
            tick=lambda i, d0=done0, st=stage: tell(st, d0 + 1 + i, total),
        )
        if not lead and members and res.summary()["verdict"]["similar"] is True:
            odds = ensemble_odds_3d(
                scenario,
                e.design,
                prototype_collapsed=bool(res.summary()["3d"]["prototype"]["collapsed"]),
                tolerances=tol.for_shot(e.charge),
                members=members,
                seed=lab.seed,
                workers=workers,
                scheduler=scheduler,
                tick=lambda i, d0=done0, st=stage: tell(st, d0 + 1 + i, total),
            )
        summary = res.summary()
        if proto["collapsed"] is None:
            p3 = summary["3d"]["prototype"]
            proto = {
                **proto,
                "collapsed": bool(p3["collapsed"]),
                "max_top_displacement_m": float(p3["max_top_displacement_m"]),
                "reach_m": sim["prototype_reach_m"],
            }
        designs.append(_simulated(e, err, chosen[k], lab, summary, sim, odds, specimen_timing(res)))
        if kept is None or rank_key(designs[-1]) < rank_key(kept[0]):  # one result held, not all
            kept = (designs[-1], res)
    designs.sort(key=rank_key)
    words = verdict_tolerances(scenario.verdict)
    for d in designs:
        d["reasons"] = _reasons(d, designs[0], words)
    notes.append(
        f"{len(chosen)} of {len(scored)} screened designs ran in 3D (the prototype-vs-specimen comparison, judged "
        f"by the criterion): the best {min(lab.top_3d, len(scored))} screened (with {members} ensemble members "
        f"each), the best screened of each material and the best at the largest admissible scale (with the "
        f"ensemble when the criterion passes them); the others are screened only"
    )
    return designs, proto, notes, kept[1] if kept is not None and kept[0] is designs[0] else None
