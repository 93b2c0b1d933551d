"""The report's labels in words (:data:`LABELS`, :func:`label`) and the response expected on the specimen in
the specimen's own units (:func:`specimen_rows`). The verdict is the study's
(:func:`blastscale.study.criterion.judge`, ``summary["verdict"]``).
"""

from __future__ import annotations

from ..units import split_unit

__all__ = ["label", "LABELS", "specimen_rows"]

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
