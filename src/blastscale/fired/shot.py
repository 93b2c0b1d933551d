"""The shot as fired: the records -> the load the specimen got -> measured vs predicted vs refit -> the monument.

:func:`as_fired` is one more stage of the Study: it reads the design (``Study(scenario).check()``), fits the
gauges (:mod:`.gauges`) and inverts the blast model for the effective charge (:mod:`.effective`), reads the
tracks (:mod:`.tracks`), re-simulates the specimen under the designed load and under the load as fired
(:mod:`.refit`, through the Study), and up-scales the measured first peaks with the one up-scaling rule
(:func:`blastscale.analysis.upscale.upscale`). The uncertainty band of the up-scaled first peak (5-95 %) is
log-normal: ``sigma^2 = (s sigma_W)^2 + (sigma_track / peak)^2``, with s = dln(peak)/dln(W) the response's
sensitivity to the charge (from the two runs, or a third at 1.1 W when the two loads are within 2 %) and
sigma_W the effective charge's: the gauges' spread (their standard error), the integrated noise of each
impulse, and the lab's stand-off tolerance (``[lab] standoff_tolerance_m``, through dln W/dln R at the
measured impulse); without gauges the weighed charge's tolerance (``[lab] charge_tolerance``) and 10 % on
the explosive's equivalence (Cooper 1996, ch. 23).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..analysis.upscale import upscale
from ..blast.explosives import get_explosive
from ..scenario.scenario import Scenario
from ..structures.from_spec import is_block
from .calibrate import (
    calibrate_friction,
    calibrate_restitution,
    check_applies,
    check_calibrate,
)
from .effective import effective_charge, predicted_at, tnt_equivalence
from .gauges import fit_gauge
from .inputs import charge_position, shot_inputs
from .outcome import body_verdicts, marker_body
from .records import GaugeRecord, TrackRecord, record_fault
from .refit import OUTCOMES, SpecimenRun, marker_history, simulate_specimen
from .tracks import block_rotation, track_first_peak

__all__ = ["AsFired", "as_fired"]

_Q95 = 1.6448536269514722  # one-sided 95 % normal quantile: the 5-95 % band


@dataclass(frozen=True)
class AsFired:
    """The shot as fired (SI).

    Attributes
    ----------
    summary : dict
        The ``as_fired`` summary (keys in docs/fired.md).
    gauges : dict of str -> (GaugeFit, t, p)
        Each gauge's fit and its baselined trace [s], [Pa].
    markers : dict of str -> dict
        Each marker's ``measured`` (t, ux, uz), ``predicted`` and ``refit`` histories [s], [m].
    design : ModelDesign
    predicted, refit : SpecimenRun
    """

    summary: dict
    gauges: dict = field(default_factory=dict)
    markers: dict = field(default_factory=dict)
    design: Any = None
    predicted: SpecimenRun | None = None
    refit: SpecimenRun | None = None


def _explosive_factor(lab, basis: str) -> float | None:
    if lab is None:
        return None
    if lab.explosive in lab.explosives:
        e = lab.explosives[lab.explosive]
        return e.impulse_factor if basis == "impulse" else e.pressure_factor
    return get_explosive(lab.explosive).factor(basis)


def _gauges(sc: Scenario, d, record: GaugeRecord, standoff: float) -> tuple[dict, dict]:
    fs = sc.fired
    for name in fs.gauge:
        if name not in record.pressure_Pa:
            raise record_fault(
                record.path, "", 1, f"gauge {name!r} of [fired.gauge.{name}] has no column (NAME_kPa, ...)"
            )
    charge_at = charge_position(sc, d, standoff)
    model, burst = d.specimen.blast_model, d.specimen.burst
    fits, out = {}, {}
    for name, p in record.pressure_Pa.items():
        g = fs.gauge[name]
        fit = fit_gauge(record.time_s, p, name, source=record.path, column=record.columns[name])
        R = float(np.linalg.norm(np.asarray(g.position_m) - charge_at))
        pp, pi, pa = predicted_at(d.specimen_charge_kg, R, g.kind, model, burst)
        wi = effective_charge(fit.impulse_Pa_s, R, g.kind, "impulse", model, burst)
        wp = effective_charge(fit.peak_pressure_Pa, R, g.kind, "pressure", model, burst)
        # sigma of ln W: the impulse's integrated noise and the stand-off tolerance, through the inversion
        dt = float(np.median(np.diff(record.time_s)))
        s_i = fit.noise_Pa * dt * math.sqrt(max(fit.samples_positive, 1)) / fit.impulse_Pa_s
        k_i = math.log(effective_charge(fit.impulse_Pa_s * 1.01, R, g.kind, "impulse", model, burst) / wi) / math.log(
            1.01
        )
        k_r = math.log(effective_charge(fit.impulse_Pa_s, R * 1.01, g.kind, "impulse", model, burst) / wi) / math.log(
            1.01
        )
        tol = (sc.lab.standoff_tolerance_m if sc.lab is not None else 0.0) / R
        fits[name] = (fit, record.time_s, p - fit.baseline_Pa)
        out[name] = {
            **fit.to_dict(),
            "kind": g.kind,
            "distance_m": R,
            "predicted_peak_pressure_Pa": pp,
            "predicted_impulse_Pa_s": pi,
            "predicted_arrival_time_s": pa,
            "effective_charge_tnt_kg": wi,
            "effective_charge_from_pressure_tnt_kg": wp,
            "sigma_ln_charge": math.hypot(k_i * s_i, k_r * tol),
        }
    return fits, out


def _load_sigma(sc: Scenario, gauges: dict) -> float:
    """sigma of ln W_eff (module docstring)."""
    if gauges:
        w = np.log([g["effective_charge_tnt_kg"] for g in gauges.values()])
        spread = float(np.std(w, ddof=1) / math.sqrt(w.size)) if w.size > 1 else 0.0
        own = math.sqrt(sum(g["sigma_ln_charge"] ** 2 for g in gauges.values())) / len(gauges)
        return math.hypot(spread, own)
    tol = sc.lab.charge_tolerance if sc.lab is not None else 0.02
    return math.hypot(tol, 0.10)


def _measured_markers(sc, d, rec: TrackRecord) -> dict:
    """Each marker's measured displacement, first peak and outcome: a block's by the planar tipping rule from
    the marker alone; every other kind's by the 3D rule for its kind on the body that carries the marker
    (:func:`~.outcome.body_verdicts`: two markers on one body give its turn)."""
    structure = d.specimen_structure
    out = {}
    for name, pos in rec.position_m.items():
        spec = sc.fired.marker[name]
        ux = pos["x"] - spec.point_m[0]
        uz = pos["z"] - spec.point_m[2] if "z" in pos else None
        outcome = None
        if is_block(structure):
            th = block_rotation(ux, uz, spec.point_m[0], spec.point_m[2], structure.b)
            outcome = OUTCOMES[bool(np.max(np.abs(th)) >= structure.alpha)]
        out[name] = {"t": rec.time_s, "ux": ux, "uz": uz, "peak": track_first_peak(rec.time_s, ux), "outcome": outcome}
    if not is_block(structure):
        verdicts = body_verdicts(structure, {n: (sc.fired.marker[n].point_m, m["ux"], m["uz"]) for n, m in out.items()})
        for n, m in out.items():
            v = verdicts.get(marker_body(structure, sc.fired.marker[n].point_m))
            if v is not None and m["uz"] is not None:
                m["outcome"] = OUTCOMES[v["fell"]]
    return out


def _ratio(a, b) -> float | None:
    return None if a is None or b is None or b == 0 else float(a / b)


def as_fired(
    scenario: Scenario,
    *,
    gauges: GaugeRecord | None = None,
    tracks: TrackRecord | None = None,
    engine: str | None = None,
    calibrate=(),
) -> AsFired:
    """The shot as fired (module docstring): ``scenario`` with its ``[fired]`` table (records read from its
    paths unless given as ``gauges`` / ``tracks``); ``engine``: the re-simulation's engine (default "planar"
    for a block, "3d" for every other kind); ``calibrate``: parameters to calibrate against the tracks
    (:mod:`.calibrate`: ``"restitution"`` for a block, ``"friction"`` for every other kind), in the summary's
    ``calibration``.

    Raises
    ------
    BlastscaleInputError
        No ``[fired]`` or ``[scale]`` table, a gauge or marker out of place (:mod:`.inputs`), or a bad record
        (one line naming the file, the column and the row).
    """
    inputs = shot_inputs(scenario, gauges=gauges, tracks=tracks)  # every input checked before any simulation
    fs, d, standoff, grec, trec = scenario.fired, inputs.design, inputs.standoff_m, inputs.gauges, inputs.tracks
    calibrate = check_calibrate(calibrate)
    check_applies(calibrate, d, scenario.structure.kind)
    if engine is None:  # blocks rock in the plane (fast, the solver's peak events); every other kind in 3D
        engine = "planar" if is_block(d.specimen_structure) else "3d"
    fits, gsum = _gauges(scenario, d, grec, standoff) if grec is not None else ({}, {})
    lab = scenario.lab
    w_design = float(d.specimen_charge_kg)
    w_i, w_p = _effective_charges(fs, lab, gsum)
    w_refit = w_i if w_i is not None else w_design
    predicted = simulate_specimen(scenario, d, w_design, d.specimen.standoff_m, engine)
    refit = simulate_specimen(scenario, d, w_refit, standoff, engine)
    sig_w = _load_sigma(scenario, gsum)
    sens = None
    markers, msum, proto = {}, {}, {}
    measured = _measured_markers(scenario, d, trec) if trec is not None else {}
    for name, meas in measured.items():
        pred = marker_history(predicted, fs.marker[name].point_m)
        fit = marker_history(refit, fs.marker[name].point_m)
        pk = meas["peak"]
        markers[name] = {"measured": meas, "predicted": pred, "refit": fit}
        msum[name] = _marker_summary(meas, pred, fit, predicted, refit)
        if pk.first_peak_m is None:
            continue
        if sens is None:
            sens = _sensitivity(scenario, d, predicted, refit, standoff, fs.marker[name].point_m)
        proto[name] = _prototype_marker(pk, d.factors, sens, sig_w)
    outs = [m["outcome_measured"] for m in msum.values() if m["outcome_measured"] is not None]
    summary = {
        "designed_charge_tnt_kg": w_design,
        "designed_standoff_m": float(d.specimen.standoff_m),
        "standoff_m": standoff,
        "charge_kg": fs.charge_kg,
        "explosive": lab.explosive if lab else None,
        "effective_charge_tnt_kg": w_i,
        "effective_charge_from_pressure_tnt_kg": w_p,
        "charge_ratio_impulse": _ratio(w_i, w_design),
        "charge_ratio_pressure": _ratio(w_p, d.specimen_charge_kg),
        "tnt_equivalence_impulse": None
        if w_i is None or fs.charge_kg is None or not gsum
        else float(tnt_equivalence(w_i, fs.charge_kg, lab.initiator_tnt_kg if lab else 0.0)),
        "tnt_equivalence_pressure": None
        if w_p is None or fs.charge_kg is None
        else float(tnt_equivalence(w_p, fs.charge_kg, lab.initiator_tnt_kg if lab else 0.0)),
        "explosive_impulse_factor": _explosive_factor(lab, "impulse"),
        "explosive_pressure_factor": _explosive_factor(lab, "pressure"),
        "refit_charge_tnt_kg": w_refit,
        "sigma_ln_charge": sig_w,
        "gauges": gsum,
        "markers": msum,
        "prototype_markers": proto,
        "outcome_measured": None if not outs else ("collapsed" if "collapsed" in outs else "stands"),
        "outcome_predicted": OUTCOMES[predicted.collapsed],
        "outcome_refit": OUTCOMES[refit.collapsed],
    }
    summary["calibration"] = None
    meas = {n: (fs.marker[n].point_m, m["measured"]["t"], m["measured"]["ux"]) for n, m in markers.items()}
    if "restitution" in calibrate:
        summary["calibration"] = calibrate_restitution(scenario, d, meas, w_refit, standoff)
    if "friction" in calibrate:
        summary["calibration"] = calibrate_friction(scenario, d, meas, w_refit, standoff)
    summary["verdict"] = as_fired_verdict_line(summary)
    return AsFired(summary=summary, gauges=fits, markers=markers, design=d, predicted=predicted, refit=refit)


def _effective_charges(fs, lab, gsum: dict) -> tuple:
    """(effective TNT charge by impulse, by peak pressure) [kg]: the geometric means over the gauges; without
    gauges, the weighed charge by its impulse factor plus the initiator (by pressure: None); None without either."""
    if gsum:
        w_i = float(np.exp(np.mean(np.log([g["effective_charge_tnt_kg"] for g in gsum.values()]))))
        w_p = float(np.exp(np.mean(np.log([g["effective_charge_from_pressure_tnt_kg"] for g in gsum.values()]))))
        return w_i, w_p
    if fs.charge_kg is not None:
        return fs.charge_kg * (_explosive_factor(lab, "impulse") or 1.0) + (lab.initiator_tnt_kg if lab else 0.0), None
    return None, None


def _marker_summary(meas: dict, pred: dict, fit: dict, predicted: SpecimenRun, refit: SpecimenRun) -> dict:
    """One marker's summary: measured, predicted and refit first peaks [m] and times [s], the refit's relative
    error on the measured first peak, and the three outcomes."""
    pk = meas["peak"]
    return {
        "first_peak_m": pk.first_peak_m,
        "first_peak_time_s": pk.first_peak_time_s,
        "max_displacement_m": pk.max_displacement_m,
        "noise_m": pk.noise_m,
        "predicted_first_peak_m": pred["first_peak_m"],
        "predicted_first_peak_time_s": pred["first_peak_time_s"],
        "refit_first_peak_m": fit["first_peak_m"],
        "refit_first_peak_time_s": fit["first_peak_time_s"],
        "refit_vs_measured": None
        if pk.first_peak_m is None or fit["first_peak_m"] is None
        else fit["first_peak_m"] / pk.first_peak_m - 1.0,
        "outcome_measured": meas["outcome"],
        "outcome_predicted": OUTCOMES[predicted.collapsed],
        "outcome_refit": OUTCOMES[refit.collapsed],
    }


def _prototype_marker(pk, factors, sens: tuple, sig_w: float) -> dict:
    """The measured first peak up-scaled (:func:`~blastscale.analysis.upscale.upscale`): what the monument would
    do [m, s], with its 5-95 % band from the load's uncertainty ``sig_w`` (through the sensitivities ``sens``,
    :func:`_sensitivity`) and the track's noise."""
    s_p, s_t = sens
    sig_p = math.hypot(s_p * sig_w, pk.noise_m / abs(pk.first_peak_m))
    sig_t = abs(s_t) * sig_w
    up_p, up_t = upscale(pk.first_peak_m, factors, "length"), upscale(pk.first_peak_time_s, factors, "time")
    lo, hi = sorted((up_p * math.exp(-_Q95 * sig_p), up_p * math.exp(_Q95 * sig_p)))
    return {
        "first_peak_m": up_p,
        "first_peak_time_s": up_t,
        "first_peak_p05_m": lo,
        "first_peak_p95_m": hi,
        "first_peak_time_p05_s": up_t * math.exp(-_Q95 * sig_t),
        "first_peak_time_p95_s": up_t * math.exp(_Q95 * sig_t),
    }


def _sensitivity(sc, d, predicted: SpecimenRun, refit: SpecimenRun, standoff: float, point) -> tuple[float, float]:
    """dln(first peak)/dln(W) and dln(first-peak time)/dln(W) of the marker at ``point``, at the refit's load."""
    a, b = marker_history(predicted, point), marker_history(refit, point)
    ratio = refit.charge_kg / predicted.charge_kg
    if abs(math.log(ratio)) < 0.02 or predicted.standoff_m != refit.standoff_m:  # a third run at 1.1 W
        other = simulate_specimen(
            sc, d, 1.1 * refit.charge_kg, standoff, "planar" if refit.rocking is not None else None
        )
        a, b, ratio = b, marker_history(other, point), 1.1
    if not (a["first_peak_m"] and b["first_peak_m"]):
        return 0.0, 0.0
    lr = math.log(ratio)
    return (
        math.log(abs(b["first_peak_m"] / a["first_peak_m"])) / lr,
        math.log((b["first_peak_time_s"]) / (a["first_peak_time_s"])) / lr,
    )


def as_fired_verdict_line(s: dict) -> str:
    """The as-fired summary's verdict: the one line at the top of its report (docs/fired.md; a study's verdict
    is :func:`blastscale.study.criterion.judge`)."""
    parts = []
    if s["charge_ratio_impulse"] is not None:
        parts.append(f"As fired: {s['charge_ratio_impulse']:.3g} x the designed charge by impulse")
    else:
        parts.append("As fired: the designed charge (no gauge, no weighed charge)")
    m = next(iter(s["markers"].items()), None)
    if m is not None and m[1]["first_peak_m"] is not None:
        name, v = m
        parts.append(
            f"the specimen rocked to {1e3 * v['first_peak_m']:.3g} mm at {v['first_peak_time_s']:.3g} s ({name})"
        )
        if v["refit_vs_measured"] is not None:
            parts.append(f"the re-simulation under that load agrees within {100 * abs(v['refit_vs_measured']):.2g} %")
        p = s["prototype_markers"].get(name)
        seen = s["outcome_measured"] or s["outcome_refit"]  # no marker judged (no z column): the refit's outcome
        word = "collapse" if seen == "collapsed" else "stand"
        if p is not None:
            parts.append(
                f"the monument would {word}, {name} first peak {p['first_peak_m']:.3g} m "
                f"({p['first_peak_p05_m']:.3g}-{p['first_peak_p95_m']:.3g}) at {p['first_peak_time_s']:.3g} s"
            )
    return "; ".join(parts)
