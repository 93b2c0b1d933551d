"""The designs of a structure without a planar path, ranked (:mod:`.plan3d` for the stages): every
feasible design with its screening estimate, the best ``lab.top_3d`` of them with the 3D comparison
and the 3D odds; designs with 3D odds rank first (odds, then predicted error, then safety radius, as
the planar ranking), the screened ones after them by screening error, then safety radius."""

from __future__ import annotations

import math
from typing import Optional

from ..analysis.intervals import wilson_interval
from .build import spec_dims
from .candidates import shot_dict
from .debris import planar_reach
from .instruments import top_corner_displacement
from .odds import outcome_odds_text
from .plan3d import ENSEMBLE_3D_DEFAULT, run_3d, screening_error

__all__ = ["designs_3d", "rank_key_3d"]


def rank_key_3d(d: dict) -> tuple:
    err = d["predicted_first_peak_error"]
    err2 = float(f"{err:.2g}") if err is not None and math.isfinite(err) else math.inf
    p = d["p_outcome_agree"]
    return (p is None, -round(p, 2) if p is not None and math.isfinite(p) else 0.0, err2, d["safety_radius_m"])


def _reasons(d: dict, best: dict) -> list:
    if d["p_outcome_agree"] is None:
        return [
            f"screened only (no 3D run; lab.top_3d designs get it): screening error {100 * d['screening_error']:.2g} %",
            f"safety radius ({d['safety_threshold']}) {d['safety_radius_m']:.3g} m",
        ]
    o = d["odds_3d"] or {"agree_count": int(d["p_outcome_agree"]), "trials": 1}
    out = [
        f"outcome agrees with the prototype's (3D runs of the lab's tolerances): {outcome_odds_text(o)}",
        f"predicted error {100 * d['predicted_first_peak_error']:.2g} % (3D similarity "
        f"{100 * d['similarity_error']:.2g} %, tolerances "
        f"{'-' if d['first_peak_spread'] is None else format(100 * d['first_peak_spread'], '.2g')} %)",
        f"safety radius ({d['safety_threshold']}) {d['safety_radius_m']:.3g} m",
    ]
    if d is not best:
        kb, kd = rank_key_3d(best), rank_key_3d(d)
        out.append(
            "ranked after a design with "
            + (
                "better odds"
                if kb[1] < kd[1]
                else "a smaller predicted error"
                if kb[2] < kd[2]
                else "a smaller safety radius"
            )
        )
    return out


def designs_3d(
    scenario, ok: list, proto: dict, lab, tol, tell, *, workers: int = 0, scheduler: Optional[str] = None
) -> tuple:
    """(designs best first, the prototype's record with its 3D outcome, notes) of a plan on the 3D path."""
    method = scenario.blast.load
    scored = sorted(
        ((screening_error(e, method), e) for e in ok), key=lambda se: (float(f"{se[0]:.2g}"), se[1].safety.radius_m)
    )
    ok = [e for _, e in scored]
    members = lab.ensemble_3d if lab.ensemble_3d is not None else ENSEMBLE_3D_DEFAULT
    top = ok[: lab.top_3d]
    total = len(top) * (members + 1)
    designs, notes = [], []
    for k, (err, e) in enumerate(scored):
        h, w, _ = spec_dims(e.specimen)
        base = {"screening_error": err, "odds_3d": None, "similarity_3d": None}
        if k >= len(top):
            designs.append(
                {
                    **shot_dict(e, lab, top_corner_displacement(w, h, 0.0), planar_reach(w, h, 0.0, False)),
                    **base,
                    "p_outcome_agree": None,
                    "p_outcome_agree_low": None,
                    "p_outcome_agree_high": None,
                    "first_peak_spread": None,
                    "similarity_error": None,
                    "predicted_first_peak_error": err,
                    "charge_tolerance_needed": None,
                    "weighing_precision_kg": None,
                }
            )
            continue
        done0 = k * (members + 1)
        tell(f"3D comparison and ensemble of design {k + 1} of {len(top)}", done0, total)
        s3, sim, odds = run_3d(
            scenario,
            e,
            lab,
            members=members,
            tolerances=tol,
            workers=workers,
            scheduler=scheduler,
            tick=lambda n, d0=done0, k=k: tell(
                f"3D comparison and ensemble of design {k + 1} of {len(top)}", d0 + 1 + n, total
            ),
        )
        if proto["collapsed"] is None:
            p3 = s3["prototype"]
            proto = {
                **proto,
                "collapsed": bool(p3["collapsed"]),
                "max_top_displacement_m": float(p3["max_top_displacement_m"]),
                "reach_m": sim["prototype_reach_m"],
            }
        reach = sim["specimen_reach_m"] if math.isfinite(sim["specimen_reach_m"]) else planar_reach(w, h, 0.0, True)
        agree = 1.0 if s3["similarity"].get("outcomes_agree", True) else 0.0
        p = odds["p_outcome_agree"] if odds else agree
        lo, hi = wilson_interval(int(agree), 1)  # no ensemble: the one 3D comparison, 1 trial
        spread = odds["first_peak_spread"] if odds else None
        designs.append(
            {
                **shot_dict(e, lab, sim["specimen_top_m"], reach),
                **base,
                "p_outcome_agree": p,
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
        )
    designs.sort(key=rank_key_3d)
    for d in designs:
        d["reasons"] = _reasons(d, designs[0])
    notes.append(
        f"the best {len(top)} screened designs ran in 3D (the prototype-vs-specimen comparison and "
        f"{members} ensemble members each); the others are screened only"
    )
    return designs, proto, notes
