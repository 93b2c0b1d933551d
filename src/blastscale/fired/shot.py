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
the explosive's equivalence (Cooper 1996, ch. 23). That is the monument under the *similar* charge (the prototype
event the shot represents); the monument under the designed event, with the design's similarity error and a
chaotic structure's spread in its band, is :mod:`.event`'s (``similar_prototype_charge_tnt_kg``,
``designed_event``).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .._validate import BlastscaleInputError
from ..analysis.intervals import Z95
from ..analysis.upscale import upscale
from ..blast.explosives import get_explosive
from ..scenario.scenario import Scenario
from ..similitude.effects import charge_position
from ..structures.from_spec import is_block
from .calibrate import (
    calibrate_friction,
    calibrate_restitution,
    check_applies,
    check_calibrate,
)
from .effective import effective_charge, predicted_at, tnt_equivalence
from .event import BAND_RULE, DesignedEvent, designed_event_marker, similar_prototype_charge
from .gauges import GaugeDriftWarning, fit_gauge
from .inputs import gauge_incidence, shot_charge_height, shot_inputs
from .outcome import body_verdicts, marker_body
from .records import GaugeRecord, TrackRecord, record_fault
from .refit import OUTCOMES, SpecimenRun, marker_history, simulate_specimen
from .tracks import block_rotation, expected_response_s, track_first_peak

__all__ = ["AsFired", "as_fired", "worst_marker"]

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
    charge_at = charge_position(d.specimen_structure.front_x, standoff, shot_charge_height(sc, d))
    model, burst, incidence = d.specimen.blast_model, d.specimen.burst, sc.blast.incidence
    fits, out = {}, {}
    for name, p in record.pressure_Pa.items():
        g = fs.gauge[name]
        fit = fit_gauge(record.time_s, p, name, source=record.path, column=record.columns[name])
        for line in fit.warnings:
            warnings.warn(line, GaugeDriftWarning, stacklevel=2)
        R = float(np.linalg.norm(np.asarray(g.position_m) - charge_at))
        look = gauge_incidence(sc, d, standoff, name)
        a = 0.0 if look is None else look.angle_deg

        def inverted(value, distance, basis="impulse"):
            return effective_charge(value, distance, g.kind, basis, model, burst, a, incidence)

        pp, pi, pa = predicted_at(d.specimen_charge_kg, R, g.kind, model, burst, a, incidence)
        wi = inverted(fit.impulse_Pa_s, R)
        wp = inverted(fit.peak_pressure_Pa, R, "pressure")
        # sigma of ln W: the impulse's (noise and baseline, the fit's 95 % half-width) and the stand-off
        # tolerance, through the inversion
        s_i = fit.ci95_impulse_Pa_s / Z95 / fit.impulse_Pa_s
        k_i = math.log(inverted(fit.impulse_Pa_s * 1.01, R) / wi) / math.log(1.01)
        k_r = math.log(inverted(fit.impulse_Pa_s, R * 1.01) / wi) / math.log(1.01)
        tol = (sc.lab.standoff_tolerance_m if sc.lab is not None else 0.0) / R
        fits[name] = (fit, record.time_s, p - fit.baseline_Pa - fit.drift_Pa_per_s * record.time_s)
        out[name] = {
            **fit.to_dict(),
            "kind": g.kind,
            "distance_m": R,
            "incidence_deg": a,
            "normal": None if look is None else list(look.normal),
            "normal_from": None if look is None else look.found,
            "predicted_peak_pressure_Pa": pp,
            "predicted_impulse_Pa_s": pi,
            "predicted_arrival_time_s": pa,
            "effective_charge_tnt_kg": wi,
            "effective_charge_from_pressure_tnt_kg": wp,
            "sigma_ln_charge": math.hypot(k_i * s_i, k_r * tol),
        }
    return fits, out


def _source_law(fs, source) -> tuple | None:
    """A source's law at the shot's control value as set (``[fired] control``): (its charge by impulse, by peak
    [kg TNT], one shot's sigma of ln W [-]: repeatability and fit,
    :meth:`~blastscale.blast.sources.PowerLaw.sigma_shot`); None for a chemical charge."""
    if source is None or fs.control is None:
        return None
    x = float(fs.control)
    return float(source.impulse.tnt_kg(x)), float(source.pressure.tnt_kg(x)), float(source.impulse.sigma_shot(x))


def _load_sigma(sc: Scenario, gauges: dict, law: tuple | None = None) -> float:
    """sigma of ln W_eff (module docstring); without gauges, a source's shot has its ``law``'s one-shot scatter
    (:func:`_source_law`)."""
    if gauges:
        w = np.log([g["effective_charge_tnt_kg"] for g in gauges.values()])
        spread = float(np.std(w, ddof=1) / math.sqrt(w.size)) if w.size > 1 else 0.0
        own = math.sqrt(sum(g["sigma_ln_charge"] ** 2 for g in gauges.values())) / len(gauges)
        return math.hypot(spread, own)
    if law is not None:
        return law[2]
    tol = sc.lab.charge_tolerance if sc.lab is not None else 0.02
    return math.hypot(tol, 0.10)


def _charge_keys(fs, lab, source, law: tuple | None, charges: tuple, w_design: float, gauged: bool) -> dict:
    """The summary's charge keys: the charge as weighed (or the source's control), the effective charges
    ``charges`` (by impulse, by peak) [kg TNT] and their ratios to the designed ``w_design`` [kg TNT], the implied
    TNT equivalences of a weighed explosive and its tables' factors (None for a source's shot), and the source's
    keys (:func:`_source_summary`; ``law``: :func:`_source_law`)."""
    w_i, w_p = charges
    init_i, init_p = (lab.initiator_tnt_kg, lab.initiator_tnt_pressure_kg) if lab else (0.0, 0.0)
    weighed = fs.charge_kg is not None
    return {
        "charge_kg": fs.charge_kg,
        "explosive": lab.explosive if lab else None,
        "effective_charge_tnt_kg": w_i,
        "effective_charge_from_pressure_tnt_kg": w_p,
        "charge_ratio_impulse": _ratio(w_i, w_design),
        "charge_ratio_pressure": _ratio(w_p, w_design),
        "tnt_equivalence_impulse": float(tnt_equivalence(w_i, fs.charge_kg, init_i))
        if weighed and gauged and w_i is not None
        else None,
        "tnt_equivalence_pressure": float(tnt_equivalence(w_p, fs.charge_kg, init_p))
        if weighed and w_p is not None
        else None,
        "explosive_impulse_factor": None if source else _explosive_factor(lab, "impulse"),
        "explosive_pressure_factor": None if source else _explosive_factor(lab, "pressure"),
        **_source_summary(fs, source, law, w_i, gauged),
    }


def _source_summary(fs, source, law: tuple | None, w_i: float | None, gauged: bool) -> dict:
    """A source's shot: the control value as set, the ``law``'s charges there (by impulse, by pressure) and one
    shot's scatter (:func:`_source_law`); with gauges, what the source delivered against its law
    (``source_yield_impulse``, the gauges' charge over the law's) and whether that lies within one shot's 95 %
    scatter (``source_yield_within``). Empty for a chemical charge."""
    if law is None:
        return {}
    x = float(fs.control)
    law_i, law_p, s = law
    ratio = w_i / law_i if gauged and w_i is not None else None
    return {
        "source": source.name,
        "control": x,
        "control_unit": source.control_unit,
        "control_setting": f"{source.control} {x:.4g} {source.control_unit}",
        "source_law_tnt_kg": law_i,
        "source_law_pressure_tnt_kg": law_p,
        "source_sigma_ln_shot": s,
        "source_yield_impulse": ratio,
        "source_yield_within": None if ratio is None else bool(abs(math.log(ratio)) <= Z95 * s),
    }


def _measured_markers(sc, d, rec: TrackRecord, response_s: dict) -> dict:
    """Each marker's measured displacement, first peak (searched over its expected time to the first peak
    ``response_s[name]`` [s], :func:`~.tracks.track_first_peak`) and outcome: a block's by the planar tipping
    rule from the marker alone; every other kind's by the 3D rule for its kind on the body that carries the
    marker (:func:`~.outcome.body_verdicts`: two markers on one body give its turn)."""
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
        out[name] = {
            "t": rec.time_s,
            "ux": ux,
            "uz": uz,
            "peak": track_first_peak(rec.time_s, ux, response_s[name]),
            "outcome": outcome,
        }
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
    law = _source_law(fs, inputs.source)
    w_i, w_p = _effective_charges(fs, lab, gsum, law)
    w_refit = w_i if w_i is not None else w_design
    # the design's own study (its verdict: the similarity error at each point) and the shot's (the verdict as fired)
    predicted = simulate_specimen(scenario, d, w_design, d.specimen.standoff_m, engine, compare=True)
    refit = simulate_specimen(scenario, d, w_refit, standoff, engine, compare=True)  # with the prototype: the verdict
    sig_w = _load_sigma(scenario, gsum, law)
    sens = _Sensitivity(scenario, d, predicted, refit, standoff)
    design_summary = predicted.result.summary()
    chaotic = getattr(d.prototype_structure, "section", None) == "circular"
    markers, msum, proto, event = {}, {}, {}, {}
    shot_event = DesignedEvent(d, design_summary, chaotic, sig_w, math.log(w_design / w_refit))
    sims = {}  # each tracked marker's simulated histories: the prediction's first-peak time sets the search
    for name in trec.position_m if trec is not None else ():
        sims[name] = (
            marker_history(predicted, fs.marker[name].point_m),
            marker_history(refit, fs.marker[name].point_m),
        )
    response = {
        n: expected_response_s(p["first_peak_time_s"], f["first_peak_time_s"], trec.time_s[-1])
        for n, (p, f) in sims.items()
    }
    measured = _measured_markers(scenario, d, trec, response) if trec is not None else {}
    for name, meas in measured.items():
        pred, fit = sims[name]
        pk = meas["peak"]
        markers[name] = {"measured": meas, "predicted": pred, "refit": fit}
        msum[name] = _marker_summary(meas, pred, fit, predicted, refit)
        if pk.first_peak_m is None:
            continue
        s_m = sens.at(fs.marker[name].point_m)
        proto[name] = _prototype_marker(pk, d.factors, s_m, sig_w)
        event[name] = designed_event_marker(meas, pred, fit, fs.marker[name].point_m, s_m[0], shot_event)
    outs = [m["outcome_measured"] for m in msum.values() if m["outcome_measured"] is not None]
    summary = {
        "designed_charge_tnt_kg": w_design,
        "designed_standoff_m": float(d.specimen.standoff_m),
        "standoff_m": standoff,
        **_charge_keys(fs, lab, inputs.source, law, (w_i, w_p), w_design, bool(gsum)),
        "refit_charge_tnt_kg": w_refit,
        "sigma_ln_charge": sig_w,
        **_similar(d, w_refit, standoff),
        "designed_event": _designed_event(d, design_summary, event),
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
        summary["calibration"] = calibrate_friction(scenario, d, meas, w_refit, standoff, response_s=response)
    summary["verdict"] = as_fired_verdict_line(summary)
    summary["similarity_verdict"] = refit.result.summary()["verdict"]
    return AsFired(summary=summary, gauges=fits, markers=markers, design=d, predicted=predicted, refit=refit)


def _similar(d, w_refit: float, standoff: float) -> dict:
    """The similar prototype charge and stand-off (:func:`~.event.similar_prototype_charge`); a load the
    prototype's fits do not reach is said in ``similar_prototype_charge_note`` (the rest is still read)."""
    try:
        w, r = similar_prototype_charge(d, w_refit, standoff)
        note = None
    except BlastscaleInputError as exc:
        w, r, note = None, upscale(standoff, d.factors, "length"), str(exc)
    return {
        "similar_prototype_charge_tnt_kg": w,
        "similar_prototype_standoff_m": r,
        "similar_prototype_charge_note": note,
    }


def _designed_event(d, design_summary: dict, markers: dict) -> dict:
    """The summary's ``designed_event``: the design's prototype event, the band's rule, the design's own verdict
    line and each marker's (:func:`~.event.designed_event_marker`)."""
    return {
        "charge_tnt_kg": float(d.prototype.charge_kg),
        "standoff_m": float(d.prototype.standoff_m),
        "band_rule": BAND_RULE,
        "design_verdict": design_summary["verdict"]["line"],
        "markers": markers,
    }


def _effective_charges(fs, lab, gsum: dict, law: tuple | None = None) -> tuple:
    """(effective TNT charge by impulse, by peak pressure) [kg]: the geometric means over the gauges; without
    gauges, a source's ``law`` at the control value as set (both bases, :func:`_source_law`), or the weighed
    charge by its impulse factor plus the initiator (by pressure: None); None without either."""
    if gsum:
        w_i = float(np.exp(np.mean(np.log([g["effective_charge_tnt_kg"] for g in gsum.values()]))))
        w_p = float(np.exp(np.mean(np.log([g["effective_charge_from_pressure_tnt_kg"] for g in gsum.values()]))))
        return w_i, w_p
    if law is not None:
        return law[0], law[1]
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
        "first_peak_sigma_m": pk.first_peak_sigma_m,
        "smoothing_s": pk.smoothing_s,
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
    :class:`_Sensitivity`) and the track's noise."""
    s_p, s_t = sens
    sig_p = math.hypot(s_p * sig_w, pk.first_peak_sigma_m / abs(pk.first_peak_m))
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


class _Sensitivity:
    """dln(first peak)/dln(W) and dln(first-peak time)/dln(W) at a marker, at the refit's load: from the
    prediction and the refit, or from the refit and a third run at 1.1 W (run once, when first asked) when the
    two loads are within 2 % or at different stand-offs."""

    def __init__(self, sc, d, predicted: SpecimenRun, refit: SpecimenRun, standoff: float):
        self.sc, self.d, self.predicted, self.refit, self.standoff = sc, d, predicted, refit, standoff
        self.ratio = refit.charge_kg / predicted.charge_kg
        self.third = abs(math.log(self.ratio)) < 0.02 or predicted.standoff_m != refit.standoff_m
        self._other = None

    def at(self, point) -> tuple[float, float]:
        a, b = marker_history(self.predicted, point), marker_history(self.refit, point)
        ratio = self.ratio
        if self.third:  # a third run at 1.1 W
            if self._other is None:
                self._other = simulate_specimen(
                    self.sc,
                    self.d,
                    1.1 * self.refit.charge_kg,
                    self.standoff,
                    "planar" if self.refit.rocking is not None else None,
                )
            a, b, ratio = b, marker_history(self._other, point), 1.1
        if not (a["first_peak_m"] and b["first_peak_m"]):
            return 0.0, 0.0
        lr = math.log(ratio)
        return (
            math.log(abs(b["first_peak_m"] / a["first_peak_m"])) / lr,
            math.log((b["first_peak_time_s"]) / (a["first_peak_time_s"])) / lr,
        )


def _designed_word(s: dict) -> str:
    """ "stand" or "collapse" under the designed event: the measured outcome (else the refit's) when the shot's
    load bounds the designed one on its side (stood under more, or collapsed under less), else the
    prediction's (the specimen under the designed load)."""
    seen = s["outcome_measured"] or s["outcome_refit"]  # no marker judged (no z column): the refit's outcome
    hotter = (s["charge_ratio_impulse"] or 1.0) >= 1.0
    if (seen == "stands") == hotter:
        return "collapse" if seen == "collapsed" else "stand"
    return "collapse" if s["outcome_predicted"] == "collapsed" else "stand"


def worst_marker(markers: dict) -> str | None:
    """The marker whose measured and re-simulated first peaks disagree most: the largest
    ``|refit_vs_measured|``; a marker with a measured first peak and none re-simulated counts as the worst
    (an infinite disagreement); among markers with no measured first peak, the first. None without markers.
    Every marker enters the as-fired verdict through it (the line names it)."""
    if not markers:
        return None

    def badness(v: dict) -> float:
        if v["first_peak_m"] is None:
            return -1.0
        r = v["refit_vs_measured"]
        return math.inf if r is None else abs(r)

    return max(markers, key=lambda n: badness(markers[n]))


def as_fired_verdict_line(s: dict) -> str:
    """The as-fired summary's verdict: the one line at the top of its report (docs/fired.md; a study's verdict
    is :func:`blastscale.study.criterion.judge`)."""
    parts = []
    by_law = s.get("control") is not None and not s["gauges"]
    if s["charge_ratio_impulse"] is not None and by_law:
        parts.append(
            f"As fired: {s['charge_ratio_impulse']:.3g} x the designed charge by the source's law "
            f"({s['control_setting']}; no gauge: one shot's scatter {100 * s['source_sigma_ln_shot']:.2g} %)"
        )
    elif s["charge_ratio_impulse"] is not None:
        parts.append(f"As fired: {s['charge_ratio_impulse']:.3g} x the designed charge by impulse")
    else:
        parts.append("As fired: the designed charge (no gauge, no weighed charge)")
    if s.get("source_yield_impulse") is not None:
        within = "within" if s["source_yield_within"] else "outside"
        parts.append(
            f"the source gave {s['source_yield_impulse']:.3g} x its law ({s['control_setting']}; {within} one "
            f"shot's 95 % scatter, {100 * Z95 * s['source_sigma_ln_shot']:.2g} %)"
        )
    m = worst_marker(s["markers"])
    if m is not None and s["markers"][m]["first_peak_m"] is not None:
        name, v = m, s["markers"][m]
        parts.append(
            f"the specimen rocked to {1e3 * v['first_peak_m']:.3g} mm at {v['first_peak_time_s']:.3g} s ({name})"
        )
        every = " at every marker" if len(s["markers"]) > 1 else ""
        worst = f" (worst: {name})" if len(s["markers"]) > 1 else ""
        if v["refit_vs_measured"] is not None:
            parts.append(
                f"the re-simulation under that load agrees within {100 * abs(v['refit_vs_measured']):.2g} %{every}{worst}"
            )
        elif v["refit_first_peak_m"] is None:
            parts.append(f"the re-simulation under that load has no first peak at {name}")
        p = s["prototype_markers"].get(name)
        e = (s.get("designed_event") or {}).get("markers", {}).get(name)
        if p is not None and e is not None:
            ev = s["designed_event"]
            ws = s["similar_prototype_charge_tnt_kg"]
            represents = "no charge of the fits" if ws is None else f"{ws:.3g} kg TNT"
            seen = s["outcome_measured"] or s["outcome_refit"]  # no marker judged (no z column): the refit's
            parts.append(
                f"the shot represents {represents} at {s['similar_prototype_standoff_m']:.3g} m on the monument, "
                f"which would {'collapse' if seen == 'collapsed' else 'stand'} ({name} first peak "
                f"{p['first_peak_m']:.3g} m up-scaled)"
            )
            parts.append(
                f"under the designed {ev['charge_tnt_kg']:.3g} kg at {ev['standoff_m']:.3g} m it would "
                f"{_designed_word(s)}, {name} first peak {e['first_peak_m']:.3g} m "
                f"({e['first_peak_p05_m']:.3g}-{e['first_peak_p95_m']:.3g}) at {e['first_peak_time_s']:.3g} s"
            )
    return "; ".join(parts)
