"""The test card of a study: what to build, what to fire, where everything stands, what to set
and what to expect, in one dict (``summary.json``'s ``test_card``; the report prints it).

Built from a :class:`~blastscale.study.StudyResult` with a design and the scenario's ``[lab]`` table
(its defaults when absent): the charge in the lab's explosive (impulse equivalence) and its pressure
equivalent (safety), the safety envelope of the specimen's shot and of the prototype event, the
debris zone (the larger of the planar and 3D reach, docs/planning.md), the instruments (rules of
:mod:`.instruments`) from the specimen's own simulated response, and the odds (:mod:`.odds`).
Lengths in m, times in s, pressures in Pa (the report shows mm, ms, kPa).
"""

from __future__ import annotations

import math
import warnings

import numpy as np

from .._validate import BlastscaleInputError
from ..analysis.intervals import wilson_interval
from ..blast.faces import face_loads
from ..blast.parameters import get_blast_model
from ..similitude.effects import FRAME, charge_position
from ..similitude.factors import to_specimen
from ..structures.from_spec import is_block
from .build import spec_dims, specimen_unit
from .debris import planar_reach, reach_3d
from .fragments import detonator_placement, fragment_hazard, pad_spec
from .instruments import IMPULSE_ARRIVAL_ERROR, instrument_settings, negative_duration_s, top_corner_displacement
from .odds import Tolerances, ensemble_odds_3d, planar_odds
from .shot import (
    DEFAULT_LAB,
    Timing,
    card_charge,
    fireability,
    rocking_timing,
    safety_envelope,
    source_card,
    specimen_friction_card,
    specimen_rigidity,
    threshold_meanings,
    timing_of,
)

__all__ = ["study_test_card", "check_lab"]

_SHORT_RISE_S = 1e-6  # piezoelectric blast gauges rise in ~1 us


def check_lab(design, lab) -> None:
    """Warn, before anything runs, of a specimen charge the lab cannot rely on (one ``warnings.warn``
    line each: below the explosive's minimum reliable charge, an initiator above
    ``initiator_max_fraction`` or carrying the whole charge); the run still completes."""
    if design is not None and lab is not None:
        ch = card_charge(design.specimen_charge_kg, lab)
        alone = list(ch.warnings) if ch.explosive_mass_kg == 0.0 else []  # the initiator fired alone
        for text in alone + [f[3] for f in fireability(ch, lab)]:
            warnings.warn(f"test card: {text}", UserWarning, stacklevel=2)


def _timing_3d(result, factors, collapsed: bool):
    """Specimen timing from the up-scaled 3D history of the top point (prototype times in specimen times,
    :func:`~blastscale.similitude.factors.to_specimen`; ``factors``: the design's)."""
    cmp3 = result.response3d
    ds = cmp3.upscaled_dataset
    x = np.abs(ds["point_displacement"].sel(point=cmp3.top_point, component="x").values)
    t = ds["time"].values - float(cmp3.design.prototype.arrival_time)
    keep = t >= 0
    summ = result.summary()["3d"]["model"]
    tm = rocking_timing(t[keep], x[keep], 0.0 if not collapsed else -1.0, False, None)
    if collapsed and summ.get("collapse_time_s") is not None:
        tm = Timing(tm.rise_s, float(summ["collapse_time_s"]) - float(cmp3.design.prototype.arrival_time))
    return Timing(to_specimen(tm.rise_s, factors, "time"), to_specimen(tm.response_s, factors, "time"))


def specimen_timing(result) -> "Timing | None":
    """The specimen's :class:`Timing` (from the shock's arrival at it [s]): the time to its first peak (or to the
    tipping point) and its whole response, from the planar model when there is one, else from the up-scaled 3D
    history of the top point; None without a specimen or a load."""
    d = result.design
    if d is None or result.blast is None:
        return None
    if result.planar is not None:
        return timing_of(result.planar.model)
    if result.response3d is not None and getattr(result.response3d, "upscaled_dataset", None) is not None:
        return _timing_3d(result, d.factors, bool(result.summary()["3d"]["model"]["collapsed"]))
    return None


def _response(result, spec) -> dict:
    """Collapsed, first peak, timing, top displacement and reach of the specimen and reach of the prototype."""
    d = result.design
    out = {"reach_m": [], "prototype_reach_m": []}
    if result.planar is not None:
        m, p = result.planar.model, result.planar.prototype
        out.update(
            collapsed=bool(m.collapsed),
            rotation=None if m.collapsed else float(m.max_rotation),
            timing=timing_of(m),
            collapse_time=m.collapse_time,
        )
        out["top_m"] = (
            (spec.width + spec.height)
            if m.collapsed
            else top_corner_displacement(spec.width, spec.height, m.max_rotation)
        )
        out["reach_m"].append(planar_reach(spec.width, spec.height, m.max_rotation, m.collapsed))
        out["prototype_reach_m"].append(
            planar_reach(result.structure.width, result.structure.height, p.max_rotation, p.collapsed)
            if hasattr(result.structure, "width")
            else 0.0
        )
    if result.response3d is not None:
        s3 = result.summary()["3d"]
        cmp3 = result.response3d
        out["prototype_reach_m"].append(reach_3d(cmp3.prototype_dataset, result.structure))
        up = getattr(cmp3, "upscaled_dataset", None)
        if up is not None:
            out["reach_m"].append(to_specimen(reach_3d(up, result.structure), d.factors, "length"))
        if "timing" not in out:
            col = bool(s3["model"]["collapsed"])
            out.update(
                collapsed=col,
                rotation=None if col else float(s3["model"]["max_rotation_rad"]),
                timing=_timing_3d(result, d.factors, col),
                collapse_time=None
                if s3["model"]["collapse_time_s"] is None
                else to_specimen(float(s3["model"]["collapse_time_s"]), d.factors, "time"),
            )
            out["top_m"] = to_specimen(float(s3["model"]["max_top_displacement_m"]), d.factors, "length")
    return out


def _odds(result, spec, ch, lab, collapsed_p):

    sc, d = result.scenario, result.design
    if not is_block(result.structure):
        return None
    sim, bl = sc.simulation, sc.blast
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return planar_odds(
            spec,
            charge_kg=d.specimen_charge_kg,
            standoff_m=d.specimen_standoff_m,
            prototype_collapsed=collapsed_p,
            explosive_fraction=max(0.0, 1.0 - ch.initiator_fraction),
            gravity=d.specimen_gravity,
            restitution=sim.restitution,
            pulse_shape=bl.pulse_shape,
            blast_model=d.specimen.blast_model,
            tolerances=Tolerances.from_lab(lab),
            samples=lab.samples,
            seed=lab.seed,
            target=lab.first_peak_target,
        )


def _prototype_collapsed(result) -> bool:
    if result.planar is not None:
        return bool(result.planar.prototype.collapsed)
    return bool(result.summary()["3d"]["prototype"]["collapsed"])


def _layout(spec, ch, ins, standoff: float, density, charge_height: float = 0.0, burst: str = "surface") -> dict:
    """Positions [m] in the one frame of blastscale (:func:`blastscale.similitude.effects.charge_position`;
    the ``[fired]`` records' too): x along the blast, from the charge to the specimen; y across; z up; the
    origin at the centre of the specimen's footprint on the floor. The charge ``standoff`` in front of the
    specimen's front, on the floor for a surface burst, at ``charge_height`` on a stand for a free-air one."""
    hs, ws, ds = spec_dims(spec)
    front = float(spec.front_x)
    charge = charge_position(front, standoff, charge_height)
    m = ch.explosive_mass_kg
    rho = density or 1600.0
    # the charge's shape is the blast fits': a hemisphere on the floor, a sphere in free air
    radius = (3.0 * m / ((2.0 if burst == "surface" else 4.0) * math.pi * rho)) ** (1.0 / 3.0)
    cam = 4.0 * (hs + ins.displacement_range_m)
    back = front + ws
    return {
        "frame": FRAME,
        "charge": charge.tolist(),
        "charge_height_m": charge_height,
        "charge_radius_m": radius,
        "specimen_front_x_m": front,
        "specimen_centre": [0.5 * (front + back), 0.0, 0.0],
        "reflected_gauge": [front, -(0.5 * ds + 0.2 * standoff), 0.5 * hs],
        "incident_gauge": [float(charge[0]), -standoff, 0.5 * hs],
        "camera": [0.5 * (front + back), cam, 0.5 * hs],
        "camera_distance_m": cam,
        "displacement_sensor": [back + 0.5 * hs + ins.displacement_range_m, 0.0, hs],
    }


def _lab_shot(result) -> tuple:
    """(charge height [m], burst, notes) of the specimen's shot: the design's specimen burst (a surface
    burst: the charge on the floor) and ``scale.specimen_charge_height_m`` where given."""
    d, sc = result.design, result.scenario
    burst = getattr(d.specimen, "burst", "surface")
    h = sc.scale.specimen_charge_height_m if sc.scale is not None else None
    notes = []
    if burst != "surface" and h is None:
        notes.append(
            f"the specimen's charge is a {burst} burst on a stand of unstated height: give "
            "scale.specimen_charge_height_m to check that the floor's reflection arrives after the positive phase"
        )
    lb = (d.effects or {}).get("lab_burst")
    if lb is not None and lb["kind"] != burst:
        notes.append(
            f"the charge at {lb['charge_height_m']:.4g} m is {lb['kind']}, not the {burst} burst the design "
            f"assumed (floor reflection after {lb['delay_over_positive_duration']:.2g} of the positive duration)"
        )
    if sc.blast.clearing or sc.blast.negative_phase:
        notes.append(
            "the odds run the planar first swing on the uncleared positive pulse (clearing and the negative "
            "phase are in the simulations, not in the odds)"
        )
    return (0.0 if h is None else float(h)) if burst == "surface" or h is not None else None, burst, notes


def study_test_card(result, lab=None, odds_3d: dict | None = None) -> dict | None:
    """The test card of ``result`` (module docstring); None for a prototype-only study (no specimen).

    The odds: ``p_outcome_agree`` and its 95 % Wilson interval ``p_outcome_agree_low``, ``p_outcome_agree_high``
    are the planar Monte Carlo's (a block), else the 3D ensemble's (``odds_3d``), else None.

    Parameters
    ----------
    result : StudyResult
    lab : LabSpec, optional
        Default: the scenario's ``[lab]``, or every key's default.
    odds_3d : dict, optional
        The design's 3D ensemble odds already run (:func:`~.odds.ensemble_odds_3d`, the plan's), carried as
        they are; without them the card runs ``lab.ensemble_3d`` members (none when unset).
    """

    d = result.design
    if d is None:
        return None
    sc = result.scenario
    lab = lab or sc.lab or DEFAULT_LAB
    spec = result.specimen_structure
    ch = card_charge(d.specimen_charge_kg, lab)
    env = safety_envelope(ch.tnt_equivalent_safety_kg, lab.safety_threshold)
    r = _response(result, spec)
    m = d.specimen
    inc = _incident_pressure(m)
    hc, burst, shot_notes = _lab_shot(result)
    layout = _layout(
        spec, ch, _instruments(m, r, lab), d.specimen_standoff_m, ch.explosive.density_kg_m3, hc or 0.0, burst
    )
    gauges = _gauge_keys(d, ch, layout)
    ins = _instruments(m, r, lab, gauges)  # the gauges' ranges on their own predicted peaks
    collapsed_p = _prototype_collapsed(result)
    odds = _odds(result, spec, ch, lab, collapsed_p)
    odds3 = odds_3d
    if odds3 is None and lab.ensemble_3d:
        odds3 = ensemble_odds_3d(
            sc,
            d,
            prototype_collapsed=collapsed_p,
            tolerances=Tolerances.from_lab(lab),
            members=lab.ensemble_3d,
            seed=lab.seed,
        )
    if odds3 is None and result.response3d is not None and "3d" in (result.summary() or {}):
        odds3 = _one_comparison(result.summary()["3d"])
    reach = max(r["reach_m"])
    tol = None if odds is None else odds.charge_tolerance_needed
    v = result.summary()["verdict"]
    rig = specimen_rigidity(sc, d, lab)
    return {
        "verdict": {"similar": v["similar"], "line": v["line"]},
        **_shot_keys(ch, lab),
        "source": source_card(d, lab),  # [lab] source: the shot in its control value (docs/planning.md, "Sources")
        "standoff_m": d.specimen_standoff_m,
        "charge_height_m": hc,
        "burst": burst,
        "safety_distances_m": env.distances_m,
        "safety_radius_m": env.radius_m,
        "safety_threshold": env.threshold,
        "far_field": list(env.far_field),
        "thresholds": threshold_meanings(),
        "debris_radius_m": lab.debris_margin * reach,
        "debris_margin": lab.debris_margin,
        "specimen_reach_m": reach,
        "camera_fps": ins.camera_fps,
        "pressure_sampling_hz": ins.pressure_sampling_hz,
        **_agree_keys(None if odds is None else odds.to_dict(), odds3),
        "first_peak_spread": None if odds is None else odds.first_peak_spread,
        "charge_tolerance_needed": tol,
        "weighing_precision_kg": None if tol is None else tol * ch.explosive_mass_kg,
        "build": {**_build_keys(sc, d, spec), "friction": specimen_friction_card(sc, lab), "rigidity": rig.to_dict()},
        "instruments": ins.to_dict(),
        "predicted": {**_predicted_keys(r, m, inc), **gauges},
        "layout": layout,
        **_range_keys(ch, lab, layout, burst, spec, d.specimen_standoff_m),
        "prototype": _prototype_keys(d, r, lab, collapsed_p),
        "odds": None if odds is None else odds.to_dict(),
        "odds_3d": odds3,
        "tolerances": {
            "charge": lab.charge_tolerance,
            "standoff_m": lab.standoff_tolerance_m,
            "friction": lab.friction_tolerance,
            "density": lab.density_tolerance,
            "samples": lab.samples,
            "seed": lab.seed,
        },
        "warnings": _card_notes(ch, lab, env, ins, shot_notes) + ([] if rig.ok else [rig.reason]),
    }


def _instruments(m, r: dict, lab, gauges: dict | None = None):
    """The card's :func:`~.instruments.instrument_settings` for the specimen's pulse ``m`` and response ``r``: the
    gauges' ranges on their own predicted peaks (``gauges``: :func:`_gauge_keys`) where the fits give them, else on
    the face's reflected peak and the side-on peak at the specimen (the planner's, an upper bound)."""
    g = gauges or {}
    refl, side = g.get("reflected_gauge_pressure_Pa", math.nan), g.get("incident_gauge_pressure_Pa", math.nan)
    return instrument_settings(
        reflected_pressure_Pa=refl if math.isfinite(refl) else m.reflected_pressure,
        incident_pressure_Pa=side if math.isfinite(side) else _incident_pressure(m),
        positive_duration_s=m.positive_duration,
        friedlander_decay=m.friedlander_decay,
        arrival_time_s=m.arrival_time,
        rise_time_s=r["timing"].rise_s,
        response_time_s=r["timing"].response_s,
        top_displacement_m=r["top_m"],
        camera_max_fps=lab.camera_max_fps,
        gauge_rate_max_hz=lab.gauge_rate_max_hz,
        negative_duration_s=negative_duration_s(m.scaled_distance, m.charge_kg, m.burst),
    )


def _range_keys(ch, lab, layout: dict, burst: str, spec, standoff: float) -> dict:
    """The card's ``fragments``, ``pad`` and ``detonator`` (:mod:`.fragments`): what the range safety officer
    signs beyond the blast."""
    pad = pad_spec(ch.tnt_equivalent_safety_kg, layout["charge_radius_m"], standoff, *spec_dims(spec)[1:])
    return {
        "fragments": fragment_hazard(ch, lab.initiator_named or "none", ch.explosive.name, pad),
        "pad": pad,
        "detonator": detonator_placement(lab.initiator, lab.initiator_used, burst, layout["charge_radius_m"], ch),
    }


def _one_comparison(s3: dict) -> dict:
    """The 3D odds of a card without an ensemble: the one prototype-vs-specimen 3D comparison, 1 trial, with its
    Wilson interval (:func:`~blastscale.analysis.intervals.wilson_interval`); ``members`` 0 says it."""
    agree = int(bool(s3.get("similarity", {}).get("outcomes_agree", True)))
    lo, hi = wilson_interval(agree, 1)
    return {
        "p_outcome_agree": float(agree),
        "p_outcome_agree_low": lo,
        "p_outcome_agree_high": hi,
        "agree_count": agree,
        "trials": 1,
        "members": 0,
        "note": "the one 3D comparison (no ensemble: lab.ensemble_3d for one)",
    }


def _gauge_keys(d, ch, layout: dict) -> dict:
    """The reflected gauge's own predicted load: peak pressure [Pa] and impulse [Pa s] at its slant distance [m]
    and angle of incidence [deg] (flush in a rigid wall beside the specimen, facing the charge: normal -x;
    :func:`~blastscale.blast.faces.face_loads` on the design's TNT charge, its blast model where it gives oblique
    loads, else Kingery-Bulmash), and the side-on gauge's incident peak and impulse. NaN outside the fits."""
    keys = (
        "reflected_gauge_pressure_Pa",
        "reflected_gauge_impulse_Pa_s",
        "reflected_gauge_distance_m",
        "reflected_gauge_angle_deg",
        "incident_gauge_pressure_Pa",
        "incident_gauge_impulse_Pa_s",
    )
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        try:
            f = face_loads(
                float(d.specimen_charge_kg),
                layout["charge"],
                np.array([layout["reflected_gauge"], layout["incident_gauge"]]),
                np.array([[-1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]),
                blast_model="kingery-bulmash",
            )
        except BlastscaleInputError:
            return dict.fromkeys(keys, math.nan)
    return dict(
        zip(
            keys,
            (
                float(f.pressure[0]),
                float(f.impulse[0]),
                float(f.distance[0]),
                math.degrees(float(f.angle_of_incidence[0])),
                float(f.incident_pressure[1]),
                float(f.incident_impulse[1]),
            ),
        )
    )


def _agree_keys(planar: dict | None, odds3: dict | None) -> dict:
    """``p_outcome_agree`` with its interval ``_low``, ``_high``: the planar odds', else the 3D ensemble's."""
    o = planar or odds3 or {}
    return {k: o.get(k) for k in ("p_outcome_agree", "p_outcome_agree_low", "p_outcome_agree_high")}


def _incident_pressure(m) -> float:
    """The specimen's side-on (incident) peak pressure [Pa] at its scaled distance, from Kingery-Bulmash for its
    burst (NaN outside the fit's range)."""
    kb = get_blast_model(
        "kingery-bulmash-free-air" if getattr(m, "burst", "surface") == "free-air" else "kingery-bulmash"
    )
    z = float(m.scaled_distance)
    lo, hi = kb.valid_range("incident_pressure")
    return float(kb.incident_pressure(z)) if lo <= z <= hi else math.nan


def _shot_keys(ch, lab) -> dict:
    """The card's charge keys: the explosive, its mass, the initiator and the TNT equivalences."""
    return {
        "explosive": ch.explosive.name,
        "explosive_mass_kg": ch.explosive_mass_kg,
        "explosive_min_charge_kg": ch.explosive.min_charge_kg,
        "min_charge_source": ch.explosive.min_charge_source,
        "initiator": lab.initiator,
        "initiator_tnt_kg": ch.initiator_tnt_kg,
        "initiator_fraction": ch.initiator_fraction,
        "initiator_max_fraction": lab.initiator_max_fraction,
        "tnt_equivalent_impulse_kg": ch.tnt_equivalent_impulse_kg,
        "tnt_equivalent_pressure_kg": ch.tnt_equivalent_pressure_kg,
        "tnt_equivalent_safety_kg": ch.tnt_equivalent_safety_kg,
        "initiator_used": lab.initiator_used,
        "pressure_factor": ch.explosive.pressure_factor,
        "impulse_factor": ch.explosive.impulse_factor,
        "equivalence_source": ch.explosive.source,
        "equivalence_uncertainty": ch.explosive.uncertainty,
    }


def _build_keys(sc, d, spec) -> dict:
    """The card's ``build``: the specimen's kind, dimensions [m], mass [kg], material and scales."""
    hs, ws, ds = spec_dims(spec)
    mat = sc.scale.specimen_material or (
        "same as the prototype" if abs(d.density_ratio - 1.0) < 1e-12 else f"density ratio {d.density_ratio:.4g}"
    )
    return {
        "kind": sc.structure.kind,
        "height_m": hs,
        "width_m": ws,
        "depth_m": ds,
        "mass_kg": float(sum(b.mass for b in spec.bodies)),
        "material": mat,
        "density_kg_m3": float(getattr(spec, "density", to_specimen(sc.structure.density_kg_m3, d.factors, "density"))),
        "scale": d.scale,
        "density_ratio": d.density_ratio,
        "law": d.law,
        "unit": specimen_unit(spec),
    }


def _predicted_keys(r: dict, m, inc: float) -> dict:
    """The card's ``predicted``: the specimen's simulated response and its load."""
    return {
        "collapsed": r["collapsed"],
        "first_peak_rotation_rad": r["rotation"],
        "first_peak_time_s": r["timing"].rise_s,
        "response_time_s": r["timing"].response_s,
        "top_displacement_m": r["top_m"],
        "arrival_time_s": m.arrival_time,
        "reflected_pressure_Pa": m.reflected_pressure,
        "incident_pressure_Pa": inc,
        "reflected_impulse_Pa_s": m.reflected_impulse,
        "positive_duration_s": m.positive_duration,
    }


def _prototype_keys(d, r: dict, lab, collapsed: bool) -> dict:
    """The card's ``prototype``: its outcome, charge, reach and safety distances, for reference."""
    reach_p = max(r["prototype_reach_m"])
    env_p = safety_envelope(d.prototype.charge_kg, lab.safety_threshold)
    return {
        "collapsed": collapsed,
        "charge_kg": d.prototype.charge_kg,
        "reach_m": reach_p,
        "debris_radius_m": lab.debris_margin * reach_p,
        "safety_distances_m": env_p.distances_m,
    }


def _card_notes(ch, lab, env, ins, shot_notes: list) -> list:
    """The card's warnings: the charge's, what cannot be fired, the shot's, the far field, gauges too slow for
    the rise and a camera too slow for the response."""
    notes = list(ch.warnings) + [f[3] for f in fireability(ch, lab)] + shot_notes
    if env.far_field:
        many = len(env.far_field) > 1
        notes.append(
            f"the {', '.join(env.far_field)} distance{'s lie' if many else ' lies'} beyond the Kingery-Bulmash "
            "range (Kinney-Graham far field, anchored at Z = 198.5 m/kg^(1/3)): less certain"
        )
    if ins.pressure_rise_time_s < _SHORT_RISE_S:
        notes.append(
            f"the gauges must rise in {ins.pressure_rise_time_s * 1e9:.3g} ns, faster than the ~1 us of "
            "piezoelectric blast gauges: the peak will be under-read; the impulse is still measured"
        )
    if ins.pressure_sampling_hz < ins.pressure_sampling_needed_hz:
        notes.append(
            f"the gauges sample at {ins.pressure_sampling_hz:.4g} Hz, below the {ins.pressure_sampling_needed_hz:.4g} Hz "
            "that resolves the pulse (10 (1 + d) samples over the positive phase): the peak will be read low"
        )
    if ins.pressure_impulse_arrival_error > IMPULSE_ARRIVAL_ERROR * (1.0 + 1e-9):
        notes.append(
            f"at {ins.pressure_sampling_hz:.4g} Hz the shock's position between two samples leaves the gauges' impulse "
            f"uncertain by {100 * ins.pressure_impulse_arrival_error:.2g} % (95 %), more than the "
            f"{100 * IMPULSE_ARRIVAL_ERROR:g} % the setting aims at: the effective charge read from them about 1.5 "
            "times that"
        )
    if ins.camera_fps_required > lab.camera_max_fps:
        notes.append(
            f"the camera needs {ins.camera_fps_required:.4g} frames/s, above camera_max_fps = {lab.camera_max_fps:g}"
        )
    return notes
