"""The monument under the designed event, from the shot as fired (docs/fired.md, "The monument under the designed event").

A shot fired off its design is a similar model of *another* prototype event: the **similar charge**. Under the
design's law the specimen's reflected impulse is the prototype's times the impulse factor
``gamma sqrt(varsigma lambda^3)`` (paper Eq. 8; Hopkinson-Cranz is the case lambda_Z = 1), at the stand-off
``R / lambda``; so the as-fired load (the effective charge W at the measured stand-off R) represents the prototype
charge

.. math:: W_s = \\mathrm{charge\\_for}\\left(\\frac{i_m(W, R)}{\\gamma\\sqrt{\\varsigma\\lambda^3}},\\
          \\frac{R}{\\lambda}\\right)

(:func:`blastscale.blast.inverse.charge_for`, the one inversion; i_m the specimen's reflected impulse under its
blast model and burst). At the design's own load it gives the design's prototype charge (to the root's
precision). The measured response up-scaled (:func:`blastscale.analysis.upscale.upscale`) is the monument's
under ``W_s``, not under the designed charge.

**The designed event**: the measured first peak u is corrected to the designed load by the response's measured
sensitivity to the charge, ``u_e = u (W_d / W)^s`` with s = dln(peak)/dln(W) from the prediction (designed load)
and the refit (as fired), which is the ratio of the two runs' first peaks at the marker
(``charge_correction``; it carries a stand-off difference too), then up-scaled. The residual displacement
(the mean over the record's last :data:`RESIDUAL_FRACTION` of frames, |(ux, uz)|) likewise, by the ratio of the
two runs' residuals when both exceed :data:`RESIDUAL_CORRECTION_NOISE` x the track's noise (else uncorrected,
``residual_correction`` null).

**The band** (5-95 %): independent log-normal errors, ``sigma^2 = sum_k sigma_k^2``, ``[u_e e^{-1.645 sigma},
u_e e^{1.645 sigma}]``; the terms (each in ``band_terms``, with its source):

* ``load``: ``s sigma_ln W``, the effective charge's uncertainty (the gauges' spread and noise, the stand-off
  tolerance; :mod:`.shot`) through the correction;
* ``track``: ``sigma_track / |u|`` (the track's noise, :mod:`.tracks`);
* ``refit``: ``|ln(u_refit / u)|``, the re-simulation under the load as fired against the measurement: the
  correction ``u_pred / u_refit`` assumes the engine under the effective charge is the shot, and misses by what
  the stated load error does not cover (an effective charge off by more than its sigma, the engine's own
  error); taken as one standard uncertainty (RSSu, below);
* ``similarity``: ``|ln(m / p)|``, the design's own similarity error at the marker's point: the up-scaled
  specimen's first peak m against the prototype's p under the designed event, from the study's verdict
  (:func:`blastscale.study.criterion.judge`, its ``judged`` entry "first peak" at the monitoring point on the
  marker's body nearest to it; "planar" for a block; for a residual, "residual displacement" of the body). It is
  a bias the measurement cannot see; it is not corrected (the engine's estimate of it is no better than the
  engine) but taken as one standard uncertainty, the RSSu rule for an uncorrected bias (Phillips, Eberhardt &
  Parry 1997, J. Res. NIST 102(5) 577-585);
* ``ensemble``: for a chaotic structure (circular drums), the prototype ensemble's spread at that point,
  ``ln(p95 / p05) / (2 x 1.645)`` (its 5-95 % band as a log-normal's), when the study ran ensembles
  (``simulation.ensemble_members >= 2``); otherwise null, and ``notes`` says it is missing.

Why log-normal and independent: each term multiplies the response (a charge factor through a power law, a
relative noise, a relative bias, a relative spread), the response is positive, and their sources (gauges,
camera, the engine's scaling, the structure's chaos) share nothing (JCGM 100:2008 (GUM) 5.1.2 with the
logarithm as the measurand). One overlap is kept on purpose: the ``refit`` miss holds the part of the charge's
error that ``load`` states; counting both widens the band (the conservative side).

The residual displacement's band has the same terms (``residual_band_terms``: the runs' dln(residual)/dln(W),
the residual's standard error, the refit's residual against the measured one, the design's "residual
displacement" of the marker's body, the ensemble's spread of that body's residual); a measured residual within
:data:`RESIDUAL_CORRECTION_NOISE` x its standard error has the band [0, its 95 % bound]; a marker still moving at
the record's end (:func:`marker_residual`) has none.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Optional

import numpy as np

from ..analysis.upscale import upscale
from ..blast.inverse import charge_for
from ..blast.parameters import blast_parameters, model_for_burst
from .outcome import marker_body

__all__ = [
    "BAND_RULE",
    "DesignedEvent",
    "RESIDUAL_CORRECTION_NOISE",
    "RESIDUAL_FRACTION",
    "REST_FRACTION",
    "designed_event_marker",
    "marker_residual",
    "similar_prototype_charge",
]

#: One-sided 95 % normal quantile: the 5-95 % band is ``exp(+-Q95 sigma)``.
Q95 = 1.6448536269514722

#: The band's rule in words (``designed_event.band_rule``).
BAND_RULE = (
    "independent log-normal errors: sigma_ln^2 = load^2 + track^2 + refit^2 + similarity^2 + ensemble^2; "
    "5-95 % = first peak x exp(-+1.645 sigma_ln)"
)

#: Fraction of the record's frames (its end) whose mean is the residual displacement [-].
RESIDUAL_FRACTION = 0.05

#: A marker still moves at the record's end when its range there exceeds this fraction of its first peak [-]
#: (and the noise's multiple below).
REST_FRACTION = 0.01

#: A residual is corrected for the charge only when both runs' residuals exceed this multiple of the noise [-].
RESIDUAL_CORRECTION_NOISE = 10.0


def similar_prototype_charge(design, charge_kg: float, standoff_m: float) -> tuple[float, float]:
    """(W_s [kg TNT], R_s [m]): the prototype event whose scaled event the specimen under ``charge_kg`` [kg TNT]
    at ``standoff_m`` [m] is, through the design's law (module docstring).

    Examples
    --------
    >>> from blastscale.similitude import design_model
    >>> d = design_model(50.0, 2.0, 1 / 20, blast_model="masi2021")
    >>> [round(v, 9) for v in similar_prototype_charge(d, d.specimen_charge_kg, d.specimen.standoff_m)]
    [50.0, 2.0]
    """
    sp, pr, f = design.specimen, design.prototype, design.factors
    i_m = blast_parameters(charge_kg, standoff_m, sp.blast_model, burst=sp.burst).reflected_impulse
    r_s = upscale(float(standoff_m), f, "length")
    w_s = charge_for(upscale(i_m, f, "impulse"), r_s, "reflected_impulse", model_for_burst(pr.blast_model, pr.burst))
    return float(w_s), r_s


def marker_residual(ux, uz=None, noise_m: float = 0.0, peak_m: float = 0.0) -> tuple[Optional[float], float]:
    """(residual displacement [m] or None, its standard error [m]) of a marker's history: |(mean ux, mean uz)|
    over the last :data:`RESIDUAL_FRACTION` of the frames (at least 5); the error ``noise / sqrt(n)``. None when
    the marker still moves there (its range over those frames above :data:`RESIDUAL_CORRECTION_NOISE` x the
    noise and :data:`REST_FRACTION` x |``peak_m``|): the record ends before the motion does."""
    ux = np.asarray(ux, dtype=float)
    n = max(5, int(math.ceil(RESIDUAL_FRACTION * ux.size)))
    tail = [ux[-n:]] + ([] if uz is None else [np.asarray(uz, dtype=float)[-n:]])
    moving = max(float(np.ptp(w)) for w in tail) > max(RESIDUAL_CORRECTION_NOISE * noise_m, REST_FRACTION * abs(peak_m))
    se = float(noise_m) / math.sqrt(n)
    return (None if moving else math.hypot(*(float(np.mean(w)) for w in tail))), se


def _point_of(structure, point_m) -> Optional[str]:
    """The monitoring point on the marker's body nearest to it (rest positions), else the nearest of all."""
    k = marker_body(structure, point_m)
    p = np.asarray(point_m, dtype=float)
    pts = list(structure.monitoring_points)
    if not pts:
        return None

    def dist(mp):
        return float(np.linalg.norm(np.asarray(structure.bodies[mp.body].com, float) + np.asarray(mp.position) - p))

    own = [mp for mp in pts if mp.body == k]
    return min(own or pts, key=dist).name


def _entry(judged: list, quantity: str, where: str) -> Optional[dict]:
    return next((e for e in judged if e["quantity"] == quantity and e["where"] == where), None)


def _bias(entry: Optional[dict]) -> Optional[float]:
    """|ln(model / prototype)| of a judged entry, None when it has no positive pair."""
    if entry is None:
        return None
    p, m = entry.get("prototype"), entry.get("model")
    if not (isinstance(p, (int, float)) and isinstance(m, (int, float))) or p <= 0 or m <= 0:
        return None
    return abs(math.log(m / p))


def _spread(band: Optional[tuple]) -> Optional[float]:
    """sigma of ln from a (p05, p95) band: ln(p95 / p05) / (2 Q95); None without a positive band."""
    if band is None or None in band or min(band) <= 0:
        return None
    return math.log(max(band) / min(band)) / (2.0 * Q95)


def _band(value: float, terms: dict) -> tuple[float, float, float]:
    sig = math.sqrt(sum(t["sigma_ln"] ** 2 for t in terms.values() if t["sigma_ln"] is not None))
    return sig, value * math.exp(-Q95 * sig), value * math.exp(Q95 * sig)


@dataclass(frozen=True)
class DesignedEvent:
    """The shot's inputs to the designed-event step, common to its markers.

    Attributes
    ----------
    design : ModelDesign
    design_summary : dict
        The design's study at its own load (the prototype under the designed event and the specimen under the
        designed load: ``summary()`` with ``verdict`` and, when run, ``ensemble``).
    chaotic : bool
        A chaotic structure (circular drums): the ensemble term applies.
    sigma_ln_charge : float
        The effective charge's sigma of ln W [-].
    log_charge_ratio : float
        ln(W_designed / W_as_fired) of the prediction's and the refit's charges [-].
    """

    design: Any
    design_summary: dict
    chaotic: bool
    sigma_ln_charge: float
    log_charge_ratio: float


def designed_event_marker(
    meas: dict, pred: dict, refit: dict, point_m, sensitivity: float, event: DesignedEvent
) -> dict:
    """What the monument would do at one marker under the designed event (module docstring) [m, s].

    Parameters
    ----------
    meas : dict
        The measured marker: ``peak`` (:class:`~.tracks.TrackPeak`), ``ux``, ``uz`` [m] (specimen units).
    pred, refit : dict
        The marker's simulated histories under the designed load and the load as fired
        (:func:`~.refit.marker_history`).
    point_m : sequence of float
        The marker at rest [m] (specimen, record axes).
    sensitivity : float
        s = dln(first peak)/dln(W) at the marker [-] (the load term).
    event : DesignedEvent
        The design, its study's summary, whether chaotic, the charge's uncertainty and the runs' charge ratio.

    Returns
    -------
    dict
        ``first_peak_m``, ``first_peak_p05_m``, ``first_peak_p95_m``, ``first_peak_time_s``,
        ``residual_displacement_m`` (and ``_p05_m``, ``_p95_m``), the as-fired values up-scaled
        (``as_fired_first_peak_m``, ``as_fired_residual_displacement_m``), ``charge_correction``,
        ``residual_correction``, ``sensitivity``, ``point``, ``body``, ``sigma_ln`` and ``band_terms`` (first
        peak) and ``residual_band_terms``, ``notes``.
    """
    sigma_ln_charge, log_charge_ratio = event.sigma_ln_charge, event.log_charge_ratio
    f = event.design.factors
    pk = meas["peak"]
    structure = event.design.specimen_structure
    judged = (event.design_summary.get("verdict") or {}).get("judged") or []
    planar = any(e["where"] == "planar" for e in judged)
    where = "planar" if planar else _point_of(structure, point_m)
    body = structure.bodies[marker_body(structure, point_m)].name
    notes = []

    u = float(pk.first_peak_m)
    c = 1.0
    if pred.get("first_peak_m") and refit.get("first_peak_m"):
        c = abs(pred["first_peak_m"] / refit["first_peak_m"])
    else:
        notes.append("no simulated first peak at the marker: not corrected to the designed load")
    ct = 1.0
    if pred.get("first_peak_time_s") and refit.get("first_peak_time_s"):
        ct = pred["first_peak_time_s"] / refit["first_peak_time_s"]
    value = upscale(abs(u) * c, f, "length")

    track_sigma = pk.first_peak_sigma_m if pk.first_peak_sigma_m is not None else pk.noise_m
    terms = _first_peak_terms(u, track_sigma, refit, sensitivity * sigma_ln_charge, where, event, notes)
    sig, lo, hi = _band(value, terms)

    # the damage: the residual displacement, corrected by the runs' residuals when both are clear of the noise
    res = _residual(meas, pred, refit, c, body, event, notes)
    res["terms"]["load"]["sigma_ln"] = _residual_load(res["rc"], log_charge_ratio, sigma_ln_charge, terms)
    res.update(zip(("sigma_ln", "p05", "p95"), _residual_band(res, f, notes)))
    return {
        "first_peak_m": value,
        "first_peak_p05_m": lo,
        "first_peak_p95_m": hi,
        "first_peak_time_s": upscale(pk.first_peak_time_s * ct, f, "time"),
        "sigma_ln": sig,
        "band_terms": terms,
        "residual_displacement_m": res["value"],
        "residual_displacement_p05_m": res["p05"],
        "residual_displacement_p95_m": res["p95"],
        "residual_sigma_ln": res["sigma_ln"],
        "residual_band_terms": res["terms"],
        "as_fired_first_peak_m": upscale(abs(u), f, "length"),
        "as_fired_residual_displacement_m": res["as_fired"],
        "charge_correction": c,
        "residual_correction": res["rc"],
        "sensitivity": sensitivity,
        "point": where,
        "body": body,
        "notes": notes,
    }


def _residual(meas, pred, refit, c: float, body: str, event: DesignedEvent, notes: list) -> dict:
    """The residual displacement under the designed event [m] (prototype units), before its band."""
    noise, u, f = float(meas["peak"].noise_m), float(meas["peak"].first_peak_m), event.design.factors
    judged = (event.design_summary.get("verdict") or {}).get("judged") or []
    ens, chaotic = event.design_summary.get("ensemble") or {}, event.chaotic
    res, se = marker_residual(meas["ux"], meas.get("uz"), noise, u)
    rp = marker_residual(pred["ux"], pred.get("uz"), 0.0, pred.get("first_peak_m") or u * c)[0]
    rr = marker_residual(refit["ux"], refit.get("uz"), 0.0, refit.get("first_peak_m") or u)[0]
    floor = RESIDUAL_CORRECTION_NOISE * noise
    rc = rp / rr if rp is not None and rr is not None and min(rp, rr) > floor else None
    if res is None:
        notes.append("the marker still moves at the end of the record: no residual displacement")
    rens = None
    if chaotic:
        b = (ens.get("bodies") or {}).get(body) or {}
        rens = _spread((b.get("residual_displacement_prototype_p05_m"), b.get("residual_displacement_prototype_p95_m")))
    terms = {
        "load": {"sigma_ln": None, "source": "the effective charge's sigma_ln W x dln(residual)/dln(W) (the runs)"},
        "track": {
            "sigma_ln": None if not res else se / res,
            "source": "the track's noise / sqrt(frames averaged) / the measured residual",
        },
        "refit": {
            "sigma_ln": abs(math.log(rr / res)) if res and rr else None,
            "source": "|ln(refit / measured residual)|",
        },
        "similarity": {
            "sigma_ln": _bias(_entry(judged, "residual displacement", body)),
            "source": f"|ln(up-scaled model / prototype)| of the design's residual displacement of {body}",
        },
        "ensemble": {"sigma_ln": rens, "source": f"the prototype ensemble's residual displacement of {body}"},
    }
    return {
        "value": None if res is None else upscale(res * (rc or 1.0), f, "length"),
        "as_fired": upscale(res, f, "length"),
        "measured": res,
        "se": se,
        "rc": rc,
        "terms": terms,
    }


def _residual_load(rc, log_charge_ratio: float, sigma_ln_charge: float, terms: dict) -> Optional[float]:
    """The residual's load term: dln(residual)/dln(W) from the runs x sigma_ln W; the first peak's when the loads
    are within 2 %; None when the runs' residuals are not clear of the noise."""
    if rc is None:
        return None
    if abs(log_charge_ratio) >= 0.02:
        return abs(math.log(rc) / log_charge_ratio) * sigma_ln_charge
    return terms["load"]["sigma_ln"]


def _residual_band(res: dict, f, notes: list) -> tuple:
    """(sigma_ln, p05, p95) of the residual [m]: log-normal when the measured residual is clear of its noise
    (:data:`RESIDUAL_CORRECTION_NOISE` x its standard error); else [0, its 95 % bound]; None without one."""
    if res["value"] is None:
        return None, None, None
    if res["measured"] > RESIDUAL_CORRECTION_NOISE * res["se"]:
        return _band(res["value"], res["terms"])
    notes.append("the residual displacement is within the track's noise: its band is [0, the 95 % bound]")
    return None, 0.0, upscale(res["measured"] * (res["rc"] or 1.0) + 2.0 * Q95 * res["se"], f, "length")


def _first_peak_terms(u: float, noise: float, refit, load: float, where, event: DesignedEvent, notes: list) -> dict:
    """The first peak's band terms (module docstring): ``load`` = s sigma_ln W, ``track``, ``refit``,
    ``similarity`` at ``where`` and ``ensemble``."""
    judged = (event.design_summary.get("verdict") or {}).get("judged") or []
    ens, chaotic = event.design_summary.get("ensemble") or {}, event.chaotic
    sim = _bias(_entry(judged, "first peak", where))
    ens_sig = None
    if chaotic:
        pt = (ens.get("points") or {}).get(where) or {}
        ens_sig = _spread((pt.get("first_peak_prototype_p05_m"), pt.get("first_peak_prototype_p95_m")))
        if ens_sig is None:
            notes.append(
                "a chaotic structure without an ensemble: its spread is not in the band "
                "(set simulation.ensemble_members >= 2)"
            )
    if sim is None:
        notes.append(f"no similarity error judged at {where}: not in the band")
    terms = {
        "load": {
            "sigma_ln": abs(load),
            "source": "the effective charge's sigma_ln W x dln(first peak)/dln(W) (prediction and refit)",
        },
        "track": {
            "sigma_ln": float(noise) / abs(u),
            "source": "the first peak's standard error (fired.tracks: the parabola through the raw samples; else the "
            "track's noise) / the measured first peak",
        },
        "refit": {
            "sigma_ln": abs(math.log(abs(refit["first_peak_m"] / u))) if refit.get("first_peak_m") else None,
            "source": "|ln(refit / measured first peak)|: the re-simulation under the load as fired misses the "
            "measurement by it (the load or the engine), and the correction to the designed load inherits it",
        },
        "similarity": {
            "sigma_ln": sim,
            "source": f"|ln(up-scaled model / prototype)| of the design's first peak at {where} (study verdict)",
        },
        "ensemble": {
            "sigma_ln": ens_sig,
            "source": f"ln(p95 / p05) / 3.29 of the prototype ensemble's first peak at {where}"
            if chaotic
            else "not chaotic: none",
        },
    }
    return terms
