"""The designs of a structure without a planar path, ranked (:mod:`.plan3d` for the stages): every
feasible design with its screening estimate; the designs chosen for 3D (:func:`choose_3d`: the best
``lab.top_3d`` screened, the best screened of each material and the best at the largest admissible
scale) with the 3D comparison and the 3D odds; designs simulated in 3D rank first (odds, then the
simulated error, then safety radius, as the planar ranking), the screened ones after them by
screening error, then safety radius. The screening error (closed form) and the simulated error
(3D) are separate keys, never one column (docs/planning.md, "Any structure")."""

from __future__ import annotations

import math
from typing import Optional

from .build import spec_dims
from .candidates import scale_label, shot_dict
from .debris import planar_reach
from .instruments import top_corner_displacement
from .plan3d import ENSEMBLE_3D_DEFAULT, run_3d, screening_error

__all__ = ["designs_3d", "rank_key_3d", "choose_3d"]


def _two_digits(err) -> float:
    return float(f"{err:.2g}") if err is not None and math.isfinite(err) else math.inf


def rank_key_3d(d: dict) -> tuple:
    """The ranking of the 3D path: designs simulated in 3D first (odds to 0.01, higher first; the simulated
    error ``predicted_first_peak_error`` to two significant digits), then the screened ones by
    ``screening_error`` (two significant digits); the safety radius last."""
    p = d["p_outcome_agree"]
    if d.get("simulated_by") is None:
        return (True, 0.0, _two_digits(d["screening_error"]), d["safety_radius_m"])
    return (
        False,
        -round(p, 2) if p is not None and math.isfinite(p) else 0.0,
        _two_digits(d["predicted_first_peak_error"]),
        d["safety_radius_m"],
    )


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


def _reasons(d: dict, best: dict) -> list:
    if d["simulated_by"] is None:
        return [
            f"screened only (no 3D run: not among the screening leaders, the best of its material or the largest "
            f"admissible scale): screening error {100 * d['screening_error']:.2g} %",
            f"safety radius ({d['safety_threshold']}) {d['safety_radius_m']:.3g} m",
        ]
    o = d["odds_3d"]
    out = [
        f"simulated in 3D as the {'; '.join(d['chosen_3d_for'])}",
        f"outcome agrees with the prototype's in {100 * d['p_outcome_agree']:.1f} % of "
        f"{o['members'] if o else 1} 3D run(s) of the lab's tolerances",
        f"simulated error {100 * d['predicted_first_peak_error']:.2g} % (3D similarity "
        f"{100 * d['similarity_error']:.2g} %, tolerances "
        f"{'-' if d['first_peak_spread'] is None else format(100 * d['first_peak_spread'], '.2g')} %; "
        f"screening error {100 * d['screening_error']:.2g} %)",
        f"safety radius ({d['safety_threshold']}) {d['safety_radius_m']:.3g} m",
    ]
    if d is not best:
        kb, kd = rank_key_3d(best), rank_key_3d(d)
        out.append(
            "ranked after a design with "
            + (
                "better odds"
                if kb[1] < kd[1]
                else "a smaller simulated error"
                if kb[2] < kd[2]
                else "a smaller safety radius"
            )
        )
    return out


def _screened(e, err: float, lab) -> dict:
    """A design screened only: its screening error, no simulated error."""
    h, w, _ = spec_dims(e.specimen)
    return {
        **shot_dict(e, lab, top_corner_displacement(w, h, 0.0), planar_reach(w, h, 0.0, False)),
        "screening_error": err,
        "simulated_by": None,
        "chosen_3d_for": [],
        "odds_3d": None,
        "similarity_3d": None,
        "p_outcome_agree": None,
        "p_outcome_agree_se": None,
        "first_peak_spread": None,
        "similarity_error": None,
        "predicted_first_peak_error": None,
        "charge_tolerance_needed": None,
        "weighing_precision_kg": None,
    }


def _simulated(e, err: float, why: list, lab, s3: dict, sim: dict, odds) -> dict:
    """A design run in 3D: its screening error and, separately, its simulated error and odds."""
    h, w, _ = spec_dims(e.specimen)
    reach = sim["specimen_reach_m"] if math.isfinite(sim["specimen_reach_m"]) else planar_reach(w, h, 0.0, True)
    agree = 1.0 if s3["similarity"].get("outcomes_agree", True) else 0.0
    spread = odds["first_peak_spread"] if odds else None
    return {
        **shot_dict(e, lab, sim["specimen_top_m"], reach),
        "screening_error": err,
        "simulated_by": "3d",
        "chosen_3d_for": why,
        "p_outcome_agree": odds["p_outcome_agree"] if odds else agree,
        "p_outcome_agree_se": odds["p_outcome_agree_se"] if odds else None,
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
    """(designs best first, the prototype's record with its 3D outcome, notes) of a plan on the 3D path."""
    method = scenario.blast.load
    scored = sorted(
        ((screening_error(e, method), e) for e in ok), key=lambda se: (float(f"{se[0]:.2g}"), se[1].safety.radius_m)
    )
    members = lab.ensemble_3d if lab.ensemble_3d is not None else ENSEMBLE_3D_DEFAULT
    chosen = choose_3d(scored, lab.top_3d)
    total = len(chosen) * (members + 1)
    designs, notes = [], []
    for k, (err, e) in enumerate(scored):
        if k not in chosen:
            designs.append(_screened(e, err, lab))
            continue
        n = sum(1 for d in designs if d["simulated_by"])
        done0 = n * (members + 1)
        stage = f"3D comparison and ensemble of design {n + 1} of {len(chosen)}"
        tell(stage, done0, total)
        s3, sim, odds = run_3d(
            scenario,
            e,
            lab,
            members=members,
            tolerances=tol,
            workers=workers,
            scheduler=scheduler,
            tick=lambda i, d0=done0, st=stage: tell(st, d0 + 1 + i, total),
        )
        if proto["collapsed"] is None:
            p3 = s3["prototype"]
            proto = {
                **proto,
                "collapsed": bool(p3["collapsed"]),
                "max_top_displacement_m": float(p3["max_top_displacement_m"]),
                "reach_m": sim["prototype_reach_m"],
            }
        designs.append(_simulated(e, err, chosen[k], lab, s3, sim, odds))
    designs.sort(key=rank_key_3d)
    for d in designs:
        d["reasons"] = _reasons(d, designs[0])
    notes.append(
        f"{len(chosen)} of {len(scored)} screened designs ran in 3D (the prototype-vs-specimen comparison and "
        f"{members} ensemble members each): the best {min(lab.top_3d, len(scored))} screened, the best screened "
        f"of each material and the best at the largest admissible scale; the others are screened only"
    )
    return designs, proto, notes
