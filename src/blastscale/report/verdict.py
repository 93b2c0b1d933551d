"""The report's first line, ``Verdict: ...``, its labels in words, and the response expected on the
specimen in the specimen's own units.

The verdict reads the study's summary only:

* **similar** when every engine's outcomes agree (stands / collapses), every first-peak ratio (the
  up-scaled specimen's first peak over the prototype's: planar rotation, 3D top displacement) lies
  within :data:`PEAK_TOLERANCE` of 1, the ensembles' collapse probabilities agree on whether
  collapse happens, and the load is impulsive where that check applies;
* **not similar** otherwise, with each reason;
* then where the comparison stops being meaningful: after a collapse only the outcome and the
  tipping time compare; circular drums wobble chaotically, so single trajectories compare up to the
  first peak and the rest through ensembles (their horizon);
* a prototype-only study (no ``[scale]``) says so and gives the prototype's outcome; a study under
  gravity alone (no charge) says that nothing is scaled and gives the structure's stability.
"""

from __future__ import annotations

import math
from typing import Any, Optional

from ..units import split_unit

__all__ = ["PEAK_TOLERANCE", "verdict", "verdict_line", "label", "LABELS", "specimen_rows"]

#: Largest |first-peak ratio - 1| of a similar specimen [-] (the 3D similarity map's default tolerance).
PEAK_TOLERANCE = 0.05

#: Result keys in words (the report's row labels); a key not here reads as its words without the unit.
LABELS = {
    "collapsed": "collapsed",
    "max_rotation_rad": "largest rotation",
    "collapse_time_s": "collapse (tipping) time",
    "first_impact_time_s": "first impact time",
    "n_impacts": "impacts",
    "end_time_s": "simulated until",
    "max_top_displacement_m": "largest top displacement",
    "delivered_impulse_Ns": "impulse delivered (x, y, z)",
    "first_arrival_time_s": "blast arrival time",
    "max_displacement_m": "largest displacement",
    "max_displacement_x_m": "largest displacement along the blast",
    "max_velocity_m_s": "largest velocity",
    "max_sliding_m": "largest sliding",
    "final_sliding_m": "final sliding",
    "max_uplift_m": "largest uplift",
    "peak_angular_velocity_rad_s": "peak angular velocity",
    "peak_velocity_x_m_s": "peak velocity along the blast",
    "max_abs_rotation_diff_rad": "largest rotation difference",
    "max_abs_angular_velocity_diff_rad_s": "largest angular velocity difference",
    "max_abs_rotation_diff_to_tipping_rad": "largest rotation difference up to tipping",
    "collapse_time_diff_s": "collapse time difference (model - prototype)",
    "tipping_angular_velocity_diff_rad_s": "angular velocity difference at tipping",
    "max_fall_phase_diff_rad": "fall compared at equal angle",
    "first_peak_ratio": "first-peak ratio (model / prototype)",
    "outcomes_agree": "outcomes agree",
    "top_point": "top monitoring point",
    "compared_to_collapse_s": "compared up to the collapse at",
    "top_first_peak_ratio": "first-peak ratio at the top (model / prototype)",
    "max_abs_top_displacement_diff_m": "largest top displacement difference",
    "max_abs_top_displacement_diff_rel_peak": "largest top displacement difference, of the peak",
    "first_peak_prototype_m": "first peak, prototype",
    "first_peak_model_m": "first peak, model (up-scaled)",
    "first_peak_time_s": "time of the first peak",
    "max_abs_displacement_diff_m": "largest displacement difference",
    "max_abs_displacement_diff_rel_peak": "largest displacement difference, of the peak",
    "max_abs_velocity_diff_m_s": "largest velocity difference",
    "max_abs_velocity_diff_rel_peak": "largest velocity difference, of the peak",
    "time_compared_s": "time compared",
    "load_end_s": "end of the load",
    "arrival_spread_prototype_s": "arrival-time spread over the faces, prototype",
    "arrival_spread_model_upscaled_s": "arrival-time spread over the faces, model (up-scaled)",
    "max_abs_sliding_diff_m": "largest sliding difference",
    "max_abs_uplift_diff_m": "largest uplift difference",
    "first_peak_rotation_ratio": "first-peak rotation ratio (model / prototype)",
    "first_peak_prototype_mean_m": "first peak, prototype mean",
    "first_peak_prototype_spread_m": "first peak, prototype spread",
    "first_peak_model_mean_m": "first peak, model mean",
    "first_peak_model_spread_m": "first peak, model spread",
    "peak_prototype_m": "peak, prototype",
    "peak_model_m": "peak, model",
    "noise_floor_rel_peak": "noise floor (prototype spread), of the peak",
    "model_noise_floor_rel_peak": "noise floor (model spread), of the peak",
    "envelope_mismatch_rel_peak": "envelope mismatch, of the peak",
    "horizon_prototype_s": "horizon (spread > 5 % of the peak), prototype",
    "horizon_model_s": "horizon (spread > 5 % of the peak), model",
    "collapse_probability_prototype": "collapse probability, prototype",
    "collapse_probability_model": "collapse probability, model",
}


def label(key: str) -> str:
    """A dotted result key in words: ``points.P-1.first_peak_prototype_m`` -> ``P-1: first peak, prototype``."""

    parts = key.split(".")
    last = parts[-1]
    words = LABELS.get(last) or split_unit(last)[0]
    where = [p for p in parts[:-1] if p not in ("points", "prototype", "model", "similarity")]
    return f"{' '.join(where)}: {words}" if where else words


def _peak_ok(ratio: Any) -> Optional[bool]:
    if ratio is None or not isinstance(ratio, (int, float)) or math.isnan(ratio):
        return None
    return abs(ratio - 1.0) <= PEAK_TOLERANCE


def _state(collapsed: Any, kind: str) -> str:
    return ("overturns" if kind == "block" else "collapses") if collapsed else "stands"


def verdict(summary: dict, structure_kind: str = "block", circular: bool = False) -> dict:
    """The verdict of a study's summary: ``similar`` (True, False or None for a prototype-only study),
    ``reasons`` (why not), ``facts`` (what was compared), ``limits`` (where the comparison stops being
    meaningful) and ``line`` (the report's first line)."""
    facts, ratios, reasons, limits = [], [], [], []
    if summary.get("design") is None:
        outs = []
        for eng, name in (("planar", "planar rocking"), ("3d", "3D")):
            p = (summary.get(eng) or {}).get("prototype")
            if p is not None and "collapsed" in p:
                outs.append(f"the prototype {_state(p['collapsed'], structure_kind)} ({name})")
        if not ((summary.get("scenario") or {}).get("blast") or {}).get("charge_kg"):  # gravity alone
            stab = [
                f"the structure {p['stability']} ({name})"
                for eng, name in (("3d", "3D"),)
                if ((summary.get(eng) or {}).get("prototype") or {}).get("stability")
            ]
            line = (
                "Verdict: gravity alone (no charge): nothing is scaled or compared"
                + (f"; {', '.join(stab or outs)}" if stab or outs else "")
                + "."
            )
            return {"similar": None, "reasons": [], "facts": stab or outs, "limits": [], "line": line}
        line = (
            "Verdict: prototype only: no specimen is designed and nothing is compared (the scenario has no "
            "[scale] table)" + (f"; {', '.join(outs)}" if outs else "") + "."
        )
        return {"similar": None, "reasons": [], "facts": outs, "limits": [], "line": line}
    for eng, name in (("planar", "planar"), ("3d", "3D")):
        sec = summary.get(eng)
        if not sec or sec.get("similarity") is None:
            continue
        sim, p, m = sec["similarity"], sec.get("prototype") or {}, sec.get("model") or {}
        if sim.get("outcomes_agree") is False:
            reasons.append(
                f"the outcomes disagree ({name}): the prototype {_state(p.get('collapsed'), structure_kind)}, "
                f"the model {_state(m.get('collapsed'), structure_kind)}"
            )
        elif "collapsed" in p:
            facts.append((_state(p["collapsed"], structure_kind), name))
        ratio = sim.get("first_peak_ratio", sim.get("top_first_peak_ratio"))
        where = f"{name}, {sim['top_point']}" if sim.get("top_point") else name
        ok = _peak_ok(ratio)
        if ok is False:
            reasons.append(f"first-peak ratio {ratio:.4g} ({where}) is more than {PEAK_TOLERANCE * 100:g} % from 1")
        elif ok:
            ratios.append(f"{ratio:.4g} ({where})")
        if p.get("collapsed") or m.get("collapsed"):
            limits.append(f"after a collapse ({name}) only the outcome and the tipping time compare")
    ens = summary.get("ensemble")
    if ens and ens.get("collapse_probability_model") is not None:
        pp, pm = ens["collapse_probability_prototype"], ens["collapse_probability_model"]
        if (pp > 0) != (pm > 0):
            reasons.append(f"the ensembles disagree on collapse: probability {pp:.2g} (prototype) vs {pm:.2g} (model)")
        else:
            ratios.append(f"ensemble collapse probabilities {pp:.2g} (prototype) and {pm:.2g} (model)")
        horizons = [pt.get("horizon_prototype_s") for pt in (ens.get("points") or {}).values()]
        horizons = [h for h in horizons if isinstance(h, (int, float)) and math.isfinite(h)]
        if horizons:
            limits.append(
                f"the ensembles spread beyond 5 % of the peak after {min(horizons):.3g} s: later, only "
                "envelopes and collapse probabilities are meaningful"
            )
    if circular:
        limits.append(
            "circular drums wobble chaotically: single trajectories compare up to the first peak"
            + ("" if ens else "; set simulation.ensemble_members >= 2 to compare the rest by ensembles")
        )
    imp = (summary.get("design") or {}).get("impulsive")
    if isinstance(imp, dict) and imp.get("impulsive") is False:
        reasons.append("the load is not impulsive, so the general law does not guarantee similarity")
    similar = not reasons and bool(facts or ratios)
    plural = {"stands": "stand", "overturns": "overturn", "collapses": "collapse"}
    said = []
    for state in dict.fromkeys(st for st, _ in facts):
        said.append(
            f"prototype and up-scaled model both {plural[state]} ("
            + ", ".join(n for st, n in facts if st == state)
            + ")"
        )
    peaks = [r for r in ratios if not r.startswith("ensemble")]
    if peaks:
        said.append(
            f"first-peak ratio{'s' if len(peaks) > 1 else ''} {' and '.join(peaks)}, within "
            f"{PEAK_TOLERANCE * 100:g} % of 1"
        )
    said += [r for r in ratios if r.startswith("ensemble")]
    if reasons:
        line = "Verdict: NOT similar: " + "; ".join(reasons)
    elif said:
        line = "Verdict: similar: " + "; ".join(said)
    else:
        line = "Verdict: not established: no engine compared the prototype and the model"
    if limits:
        line += ". Limits: " + "; ".join(limits)
    return {"similar": similar, "reasons": reasons, "facts": said, "limits": limits, "line": line + "."}


def verdict_line(result) -> str:
    """The ``Verdict: ...`` line of a :class:`~blastscale.study.StudyResult`."""
    s = result.summary()
    return verdict(s, result.scenario.structure.kind, getattr(result.structure, "section", None) == "circular")["line"]


#: Quantities of the specimen to measure: (section, key, words, dimension), dimension one of the
#: scaling factors (:meth:`~blastscale.similitude.ScalingFactors.to_dict`).
_SPECIMEN = (
    ("planar", "max_rotation_rad", "largest rotation", "angle"),
    ("planar", "first_impact_time_s", "first impact time", "time"),
    ("planar", "collapse_time_s", "tipping time", "time"),
    ("3d", "max_top_displacement_m", "largest top displacement", "displacement"),
    ("3d", "max_rotation_rad", "largest rotation", "angle"),
    ("3d", "max_sliding_m", "largest sliding", "displacement"),
    ("3d", "max_uplift_m", "largest uplift", "displacement"),
    ("3d", "peak_velocity_x_m_s", "peak velocity along the blast", "velocity"),
    ("3d", "collapse_time_s", "collapse time", "time"),
)

#: SI unit -> (the lab's unit, its size in SI).
_LAB_UNITS = {"displacement": ("mm", 1e-3), "time": ("ms", 1e-3), "angle": ("rad", 1.0), "velocity": ("mm/s", 1e-3)}


def specimen_rows(summary: dict, factors: dict) -> list:
    """Rows (quantity, prototype in SI, expected on the specimen in lab units, lab unit): the up-scaled
    model's values brought back to the specimen's own size (value x scaling factor: mm, ms, rad), for
    comparison with a measurement."""
    rows = []
    for eng, key, words, dim in _SPECIMEN:
        sec = summary.get(eng) or {}
        p, m = sec.get("prototype") or {}, sec.get("model") or {}
        v = m.get(key)
        if v is None or isinstance(v, bool) or not isinstance(v, (int, float)) or dim not in factors:
            continue
        unit, size = _LAB_UNITS[dim]
        rows.append((f"{words} ({'planar' if eng == 'planar' else '3D'})", p.get(key), v * factors[dim] / size, unit))
    for name, pt in (((summary.get("3d") or {}).get("similarity") or {}).get("points") or {}).items():
        if isinstance(pt.get("first_peak_model_m"), (int, float)):
            rows.append(
                (
                    f"{name}: first peak (3D)",
                    pt.get("first_peak_prototype_m"),
                    pt["first_peak_model_m"] * factors["displacement"] / 1e-3,
                    "mm",
                )
            )
    return rows
