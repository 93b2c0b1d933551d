"""The one similarity criterion: is the up-scaled specimen's response the prototype's, over the whole
structure and its damage? (docs/verdict.md)

:func:`judge` reads a study's summary (:meth:`~blastscale.study.StudyResult.summary`; the model's results
already up-scaled to prototype units) and the scenario's ``[verdict]`` tolerances
(:class:`~blastscale.scenario.specs.VerdictSpec`) and judges, on the whole structure:

* the **outcome** of every body (stands / moved / fell: fell is the engine's fall rule; moved, a residual
  displacement above ``moved_rel_height`` x the structure's height H) and of the structure (collapses or
  not, planar and 3D);
* the **first peak** and the **largest displacement** at every monitoring point (3D);
* the damage: the **residual displacement** and **residual rotation** of every body (3D);
* the planar engine's **first peak** (its ratio) and **largest rotation**.

Each quantity's relative error is

.. math:: e = \\frac{|m - p|}{\\max(|p|,\\ f \\max_k |p_k|,\\ s)}

with p the prototype's value, m the up-scaled model's, f = ``floor`` and the maximum over the structure's
values of that quantity (a value small beside the structure's largest is judged on the structure's scale).
s = 0 for first peaks and largest displacements; for the residuals (the damage) s = s_0 / r, with s_0 the
scale below which a body did not move (``moved_rel_height`` x H for displacements, ``moved_rel_height`` rad
for rotations: a rotation of 1e-3 rad moves no point of the structure more than 1e-3 H) and r = ``residual``,
so that two residuals closer than s_0 always pass: a difference smaller than "did not move" is no
difference of damage (the default block's residual rotations, 0.71 against 0.89 mrad). The quantity passes when e <= its
tolerance (``peak``, ``displacement``, ``residual``); its
``ratio`` is e / tolerance. An outcome that differs has ratio = inf.

A chaotic structure (the summary has an ``ensemble`` section: wobbling circular drums) is judged between
ensembles, never on one trajectory: for each quantity the prototype's and the model's medians and 5-95 %
bands (numpy.percentile, linear interpolation), with

.. math:: e = \\frac{\\max(d(\\tilde m, [p_{05}, p_{95}]),\\ d(\\tilde p, [m_{05}, m_{95}]))}{\\text{scale}}

where d(x, [a, b]) is the distance of x outside [a, b] (0 inside) and the scale as above; the outcomes by
the collapse and fall probabilities' intervals (Wilson 1927), which must overlap. A quantity the ensembles
do not give is judged on the single runs.

The verdict also says when the structure is not at rest before the blast (the 3D runs' ``rest`` block:
not in equilibrium, or creeping more than ``creep_rel_height`` x H under gravity alone) and when the load is
not impulsive (the general law then does not guarantee similarity).
"""

from __future__ import annotations

import math
from typing import Any, Iterable, Optional

__all__ = ["judge", "describe", "entry_value", "QUANTITIES", "STATES", "structure_height"]

#: The quantities judged (the fixed vocabulary of a verdict's ``quantity``).
QUANTITIES = (
    "outcome",
    "first peak",
    "largest displacement",
    "residual displacement",
    "residual rotation",
    "largest rotation",
    "collapse probability",
)

#: Relative slack of ``error <= tolerance`` [-]: a decimal tolerance met exactly by decimal values
#: (|1.05 - 1| = 0.05 + 4e-17 in binary) passes; 1e-9 over it fails.
_ROUNDING = 1e-12

#: A body's outcome in words, by its number (the ``prototype``/``model`` of an outcome entry: 0, 1, 2).
STATES = ("stands", "moved", "fell")

#: How many reasons the verdict line lists before "and N more".
_LINE_REASONS = 3


def _num(v: Any) -> Optional[float]:
    """A finite float, or None (missing, None, bool, NaN)."""
    if v is None or isinstance(v, bool) or not isinstance(v, (int, float)):
        return None
    v = float(v)
    return v if math.isfinite(v) else None


def structure_height(summary: dict) -> Optional[float]:
    """The structure's height H [m] from the summary's scenario (block, column, wall: ``height_m``; portal:
    column and lintel; arch: piers, radius and half the thickness), else from the 3D runs' at-rest check
    (``creep_m / creep_rel_height``); None when neither tells."""
    st = (summary.get("scenario") or {}).get("structure") or {}
    if _num(st.get("height_m")):
        return float(st["height_m"])
    if _num(st.get("column_height_m")):
        return float(st["column_height_m"]) + (_num(st.get("lintel_height_m")) or 0.0)
    if _num(st.get("radius_m")):
        return (
            (_num(st.get("pier_height_m")) or 0.0) + float(st["radius_m"]) + 0.5 * (_num(st.get("thickness_m")) or 0.0)
        )
    for system in ("prototype", "model"):
        rest = (((summary.get("3d") or {}).get(system)) or {}).get("rest") or {}
        c, r = _num(rest.get("creep_m")), _num(rest.get("creep_rel_height"))
        if c and r:
            return c / r
    return None


# -- entries ------------------------------------------------------------------------------------------
def _entry(quantity, where, p, m, error, tolerance, unit, basis, **extra) -> dict:
    ok = bool(error <= tolerance * (1.0 + _ROUNDING))
    ratio = 0.0 if error == 0.0 else (error / tolerance if tolerance > 0.0 and math.isfinite(error) else math.inf)
    if ok:
        ratio = min(ratio, 1.0)  # within the rounding slack: a pass reads <= 1
    return {
        "quantity": quantity,
        "where": where,
        "prototype": p,
        "model": m,
        "error": error,
        "tolerance": tolerance,
        "ratio": ratio,
        "unit": unit,
        "basis": basis,
        **extra,
        "ok": ok,
    }


def _relative(p: float, m: float, scale: float) -> float:
    """|m - p| / max(|p|, scale); 0 when equal, inf when the scale is 0 and they differ."""
    d = abs(m - p)
    den = max(abs(p), scale)
    if d == 0.0:
        return 0.0
    return d / den if den > 0.0 else math.inf


def _outside(x: float, band: tuple) -> float:
    """Distance of x outside the closed interval ``band`` (0 inside)."""
    lo, hi = min(band), max(band)
    return max(lo - x, x - hi, 0.0)


def _judge_values(quantity, items, tolerance, unit, floor, abs_floor) -> list:
    """Single-run entries of one quantity: ``items`` = [(where, prototype, model)] over the structure."""
    items = [(w, p, m) for w, p, m in items if p is not None and m is not None]
    if not items:
        return []
    scale = max(floor * max(abs(p) for _, p, _ in items), abs_floor)
    return [_entry(quantity, w, p, m, _relative(p, m, scale), tolerance, unit, "single") for w, p, m in items]


def _judge_bands(quantity, items, tolerance, unit, floor, abs_floor) -> list:
    """Ensemble entries of one quantity: ``items`` = [(where, (p_med, p05, p95), (m_med, m05, m95))]."""
    items = [(w, p, m) for w, p, m in items if p is not None and m is not None]
    if not items:
        return []
    scale = max(floor * max(abs(p[0]) for _, p, _ in items), abs_floor)
    out = []
    for w, p, m in items:
        d = max(_outside(m[0], p[1:]), _outside(p[0], m[1:]))
        den = max(abs(p[0]), scale)
        error = 0.0 if d == 0.0 else (d / den if den > 0.0 else math.inf)
        out.append(
            _entry(
                quantity,
                w,
                p[0],
                m[0],
                error,
                tolerance,
                unit,
                "ensemble",
                prototype_band=[p[1], p[2]],
                model_band=[m[1], m[2]],
            )
        )
    return out


def _band(d: dict, stem: str, system: str, unit: str) -> Optional[tuple]:
    """(median, p05, p95) of ``{stem}_{system}_{median,p05,p95}_{unit}`` when all three are there."""
    vals = [_num(d.get(f"{stem}_{system}_{q}_{unit}")) for q in ("median", "p05", "p95")]
    return None if any(v is None for v in vals) else tuple(vals)


def _state(body: dict, moved_m: Optional[float]) -> int:
    if body.get("fallen"):
        return 2
    r = _num(body.get("residual_displacement_m"))
    return 1 if (moved_m is not None and r is not None and r > moved_m) else 0


def _body_outcome(name: str, p: dict, m: dict, moved_m: Optional[float], tolerance: float) -> dict:
    """A body's outcome entry: stands / moved / fell in each system. Stands against moved is a disagreement
    only when the two residual displacements lie on either side of the band [s0 / (1 + tol), s0 (1 + tol)]
    around the moved height s0 (``moved_m``), tol the residual tolerance: 2.9 mm against 3.1 mm about a 3 mm
    threshold is one outcome seen twice (the residual entry judges how far apart), 2.4 mm against 3.7 mm
    is not. Fell against not fell always counts."""
    ps, ms = _state(p, moved_m), _state(m, moved_m)
    if {ps, ms} == {0, 1}:
        rs = _num((p if ps == 0 else m).get("residual_displacement_m"))
        rm = _num((m if ps == 0 else p).get("residual_displacement_m"))
        if (
            rs is not None
            and rm is not None
            and not (rs < moved_m / (1.0 + tolerance) and rm > moved_m * (1.0 + tolerance))
        ):
            return _entry("outcome", name, float(ps), float(ms), 0.0, 0.0, "outcome", "single", borderline=True)
    return _outcome(name, ps, ms)


def _outcome(where, p_state, m_state, unit="outcome") -> dict:
    same = p_state == m_state
    return _entry("outcome", where, float(p_state), float(m_state), 0.0 if same else math.inf, 0.0, unit, "single")


# -- the engines -------------------------------------------------------------------------------------
def _planar(sec: Optional[dict], tol) -> list:
    if not sec or sec.get("similarity") is None:
        return []
    sim, p, m = sec["similarity"], sec.get("prototype") or {}, sec.get("model") or {}
    out = []
    if "collapsed" in p and "collapsed" in m:
        out.append(_outcome("planar", float(bool(p["collapsed"])), float(bool(m["collapsed"])), "collapsed"))
    ratio = _num(sim.get("first_peak_ratio"))
    if ratio is not None:
        out.append(_entry("first peak", "planar", 1.0, ratio, abs(ratio - 1.0), tol.peak, "ratio", "single"))
    if not (p.get("collapsed") or m.get("collapsed")):
        out += _judge_values(
            "largest rotation",
            [("planar", _num(p.get("max_rotation_rad")), _num(m.get("max_rotation_rad")))],
            tol.displacement,
            "rad",
            tol.floor,
            0.0,
        )
    return out


def _three_d(sec: Optional[dict], ens: Optional[dict], tol, height: Optional[float]) -> list:
    if not sec or sec.get("similarity") is None:
        return []
    sim, p, m = sec["similarity"], sec.get("prototype") or {}, sec.get("model") or {}
    ens = ens or {}
    e_points, e_bodies = ens.get("points") or {}, ens.get("bodies") or {}
    moved_m = None if height is None else tol.moved_rel_height * height
    disp_floor = moved_m or 0.0
    collapsed = bool(p.get("collapsed") or m.get("collapsed"))
    out: list = []

    # outcome of the structure, then of every body (ensemble: the fall probabilities' intervals)
    if "collapsed" in p and "collapsed" in m:
        if ens and _num(ens.get("collapse_probability_prototype")) is not None:
            out.append(_collapse_probability(ens))
        else:
            out.append(_outcome("structure", float(bool(p["collapsed"])), float(bool(m["collapsed"])), "collapsed"))
    pb, mb = p.get("bodies") or {}, m.get("bodies") or {}
    for name in pb:
        if name not in mb:
            continue
        fall = _fall_probability(name, e_bodies.get(name) or {})
        out.append(fall if fall is not None else _body_outcome(name, pb[name], mb[name], moved_m, tol.residual))

    # first peak and largest displacement at every monitoring point
    points = sim.get("points") or {}
    pp, mp = p.get("points") or {}, m.get("points") or {}
    for quantity, stem, single, tolerance in (
        (
            "first peak",
            "first_peak",
            lambda n: _pair(points.get(n), "first_peak_prototype_m", "first_peak_model_m"),
            tol.peak,
        ),
        (
            "largest displacement",
            "max_displacement",
            lambda n: (
                _num((pp.get(n) or {}).get("max_displacement_m")),
                _num((mp.get(n) or {}).get("max_displacement_m")),
            ),
            tol.displacement,
        ),
    ):
        if quantity == "largest displacement" and collapsed:
            continue  # after a collapse only the outcome and the first peak compare
        names = list(dict.fromkeys([*points, *pp, *e_points]))
        bands = [
            (n, _band(e_points.get(n) or {}, stem, "prototype", "m"), _band(e_points.get(n) or {}, stem, "model", "m"))
            for n in names
        ]
        banded = {n for n, a, b in bands if a is not None and b is not None}
        out += _judge_bands(quantity, [b for b in bands if b[0] in banded], tolerance, "m", tol.floor, 0.0)
        out += _judge_values(
            quantity, [(n, *single(n)) for n in names if n not in banded], tolerance, "m", tol.floor, 0.0
        )

    # the damage: residual displacement and rotation of every body that did not fall; a difference below the
    # moved height s0 (H x moved_rel_height; moved_rel_height rad) is no difference of damage: the scale is at
    # least s0 / residual, so |m - p| <= s0 always passes
    standing = [n for n in pb if n in mb and not (pb[n].get("fallen") or mb[n].get("fallen"))]
    for quantity, key, stem, unit, abs_floor in (
        ("residual displacement", "residual_displacement_m", "residual_displacement", "m", disp_floor / tol.residual),
        ("residual rotation", "residual_rotation_rad", "residual_rotation", "rad", tol.moved_rel_height / tol.residual),
    ):
        bands = [
            (
                n,
                _band(e_bodies.get(n) or {}, stem, "prototype", unit),
                _band(e_bodies.get(n) or {}, stem, "model", unit),
            )
            for n in standing
        ]
        banded = {n for n, a, b in bands if a is not None and b is not None}
        out += _judge_bands(quantity, [b for b in bands if b[0] in banded], tol.residual, unit, tol.floor, abs_floor)
        out += _judge_values(
            quantity,
            [(n, _num(pb[n].get(key)), _num(mb[n].get(key))) for n in standing if n not in banded],
            tol.residual,
            unit,
            tol.floor,
            abs_floor,
        )
    return out


def _pair(d: Optional[dict], kp: str, km: str) -> tuple:
    d = d or {}
    return _num(d.get(kp)), _num(d.get(km))


def _overlap(a: tuple, b: tuple) -> bool:
    return max(a) >= min(b) and max(b) >= min(a)


def _collapse_probability(ens: dict) -> dict:
    """The structure's outcome between ensembles: the collapse probabilities' intervals overlap (without
    the intervals: both zero or both above zero)."""
    pp, pm = float(ens["collapse_probability_prototype"]), _num(ens.get("collapse_probability_model"))
    pm = 0.0 if pm is None else pm
    ip = tuple(_num(ens.get(f"collapse_probability_prototype_{s}")) for s in ("low", "high"))
    im = tuple(_num(ens.get(f"collapse_probability_model_{s}")) for s in ("low", "high"))
    if None not in ip and None not in im:
        same = _overlap(ip, im)
        extra = {"prototype_band": list(ip), "model_band": list(im)}
    else:
        same, extra = (pp > 0) == (pm > 0), {}
    return _entry(
        "collapse probability", "structure", pp, pm, 0.0 if same else math.inf, 0.0, "probability", "ensemble", **extra
    )


def _fall_probability(name: str, body: dict) -> Optional[dict]:
    pp, pm = _num(body.get("fall_probability_prototype")), _num(body.get("fall_probability_model"))
    ip = tuple(_num(body.get(f"fall_probability_prototype_{s}")) for s in ("low", "high"))
    im = tuple(_num(body.get(f"fall_probability_model_{s}")) for s in ("low", "high"))
    if pp is None or pm is None or None in ip or None in im:
        return None
    same = _overlap(ip, im)
    return _entry(
        "outcome",
        name,
        pp,
        pm,
        0.0 if same else math.inf,
        0.0,
        "fall probability",
        "ensemble",
        prototype_band=list(ip),
        model_band=list(im),
    )


# -- at rest before the blast -------------------------------------------------------------------------
def _rest(sec: Optional[dict], tol) -> tuple:
    """(rest block or None, reasons): the 3D runs' at-rest checks against ``creep_rel_height``."""
    sec = sec or {}
    systems = {s: (sec.get(s) or {}).get("rest") for s in ("prototype", "model")}
    systems = {s: r for s, r in systems.items() if isinstance(r, dict)}
    if not systems:
        return None, []
    reasons, block = [], {"tolerance_rel_height": tol.creep_rel_height}
    who = {"prototype": "the prototype", "model": "the specimen"}
    for s, r in systems.items():
        creep, rel = _num(r.get("creep_m")), _num(r.get("creep_rel_height"))
        dur = _num(r.get("duration_s"))
        over = " over " + format(dur, ".3g") + " s" if dur is not None else ""
        at_rest = r.get("equilibrium") is not False and (rel is None or rel <= tol.creep_rel_height)
        block[s] = {**r, "at_rest": bool(at_rest)}
        if r.get("equilibrium") is False:
            reasons.append(
                f"{who[s]} is not at rest before the blast: not in equilibrium under gravity alone"
                + (
                    f" (a body falls or keeps moving; largest creep {_fmt(creep, 'm')}{over})"
                    if creep is not None
                    else ""
                )
            )
        elif rel is not None and rel > tol.creep_rel_height:
            reasons.append(
                f"{who[s]} is not at rest before the blast: it creeps {_fmt(creep, 'm')} under gravity alone{over} "
                f"({rel:.3g} H, tolerance {tol.creep_rel_height:g} H)"
            )
    block["ok"] = not reasons
    return block, reasons


# -- words ---------------------------------------------------------------------------------------------
def _fmt(v: Optional[float], unit: str) -> str:
    """A value in readable units: metres below 1 m in mm, 3 significant digits."""
    if v is None or (isinstance(v, float) and math.isnan(v)):
        return "-"
    if unit == "m":
        return f"{v * 1e3:.3g} mm" if abs(v) < 1.0 else f"{v:.3g} m"
    if unit == "rad":
        return f"{v:.3g} rad"
    if unit in ("probability", "fall probability"):
        return f"{v:.2g}"
    return f"{v:.4g}"


def entry_value(e: dict, system: str) -> str:
    """A judged entry's ``system`` value (``"prototype"`` or ``"model"``) in words and readable units: an
    outcome as stands / moved / fell (the structure: collapses or stands), a length in mm below 1 m."""
    v, unit = e[system], e["unit"]
    if unit == "outcome":
        return STATES[int(v)]
    if unit == "collapsed":
        return "collapses" if v else "stands"
    return _fmt(v, unit)


def _place(e: dict) -> str:
    w = e["where"]
    if w == "planar":
        return f"{e['quantity']} (planar)"
    if w == "structure":
        return f"{e['quantity']} of the structure"
    if w.startswith("P-") or e["quantity"] in ("first peak", "largest displacement"):
        return f"{e['quantity']} at {w}"
    return f"{e['quantity']} of {w}"


def _collapse_words(v: float, kind: str) -> str:
    return ("overturns" if kind == "block" else "collapses") if v else "stands"


def describe(e: dict, structure_kind: str = "block") -> str:
    """One judged entry in words: ``residual displacement of D-1, 14.1 mm (up-scaled model) vs 33.8 mm
    (prototype), 58.3 % off (tolerance 20 %)``."""
    q, unit = e["quantity"], e["unit"]
    if q == "outcome" and unit == "outcome":
        p, m = STATES[int(e["prototype"])], STATES[int(e["model"])]
        return f"the outcomes disagree at {e['where']}: the prototype's {p}, the model's {m}"
    if q == "outcome" and unit == "collapsed":
        eng = "planar" if e["where"] == "planar" else "3D"
        p, m = (_collapse_words(e[s], structure_kind) for s in ("prototype", "model"))
        return f"the outcomes disagree ({eng}): the prototype {p}, the model {m}"
    if unit in ("probability", "fall probability"):
        what = "collapse" if q == "collapse probability" else f"the fall of {e['where']}"
        pb, mb = e.get("prototype_band"), e.get("model_band")
        bands = (
            f" ({_fmt(pb[0], unit)}-{_fmt(pb[1], unit)} vs {_fmt(mb[0], unit)}-{_fmt(mb[1], unit)})"
            if pb and mb
            else ""
        )
        return (
            f"the ensembles disagree on {what}: probability {_fmt(e['prototype'], unit)} (prototype) vs "
            f"{_fmt(e['model'], unit)} (model){bands}"
        )
    if unit == "ratio":
        return (
            f"{_place(e)}, ratio {e['model']:.4g} (up-scaled model / prototype), "
            f"{e['error'] * 100:.3g} % off (tolerance {e['tolerance'] * 100:g} %)"
        )
    if e["basis"] == "ensemble":
        pb, mb = e["prototype_band"], e["model_band"]
        return (
            f"{_place(e)}, median {_fmt(e['model'], unit)} (up-scaled model, 5-95 % {_fmt(mb[0], unit)} to "
            f"{_fmt(mb[1], unit)}) vs {_fmt(e['prototype'], unit)} (prototype, {_fmt(pb[0], unit)} to "
            f"{_fmt(pb[1], unit)}), {e['error'] * 100:.3g} % apart (tolerance {e['tolerance'] * 100:g} %)"
        )
    return (
        f"{_place(e)}, {_fmt(e['model'], unit)} (up-scaled model) vs {_fmt(e['prototype'], unit)} (prototype), "
        f"{e['error'] * 100:.3g} % off (tolerance {e['tolerance'] * 100:g} %)"
    )


# -- the verdict ---------------------------------------------------------------------------------------
def _unscaled(summary: dict, structure_kind: str, tol) -> dict:
    """Prototype only, or gravity alone: nothing is compared (similar = None)."""
    outs = []
    for eng, name in (("planar", "planar rocking"), ("3d", "3D")):
        p = (summary.get(eng) or {}).get("prototype")
        if p is not None and "collapsed" in p:
            outs.append(f"the prototype {_collapse_words(p['collapsed'], structure_kind)} ({name})")
    rest, rest_reasons = _rest(summary.get("3d"), tol)
    if not ((summary.get("scenario") or {}).get("blast") or {}).get("charge_kg"):  # gravity alone
        stab = [
            f"the structure {p['stability']} (3D)"
            for p in [((summary.get("3d") or {}).get("prototype") or {})]
            if p.get("stability")
        ]
        facts = stab or outs
        line = "Verdict: gravity alone (no charge): nothing is scaled or compared" + (
            f"; {', '.join(facts)}" if facts else ""
        )
    else:
        facts = outs
        line = (
            "Verdict: prototype only: no specimen is designed and nothing is compared (the scenario has no "
            "[scale] table)" + (f"; {', '.join(outs)}" if outs else "")
        )
    if rest_reasons:
        line += "; " + "; ".join(rest_reasons)
    return _verdict(None, line + ".", rest_reasons, facts, [], [], rest)


def _verdict(similar, line, reasons, facts, limits, judged, rest) -> dict:
    worst = max(judged, key=lambda e: e["ratio"], default=None)
    return {
        "similar": similar,
        "line": line,
        "reasons": reasons,
        "facts": facts,
        "limits": limits,
        "worst": None if worst is None else {k: v for k, v in worst.items() if k != "ok"},
        "judged": judged,
        "rest": rest,
    }


def _limits(summary: dict, circular: bool) -> list:
    limits = []
    for eng, name in (("planar", "planar"), ("3d", "3D")):
        sec = summary.get(eng) or {}
        if sec.get("similarity") is None:
            continue
        if (sec.get("prototype") or {}).get("collapsed") or (sec.get("model") or {}).get("collapsed"):
            limits.append(f"after a collapse ({name}) only the outcome and the first peak compare")
    ens = summary.get("ensemble")
    if ens:
        horizons = [pt.get("horizon_prototype_s") for pt in (ens.get("points") or {}).values()]
        horizons = [h for h in horizons if _num(h) is not None]
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
    return limits


def _facts(judged: Iterable[dict], structure_kind: str) -> list:
    plural = {"stands": "stand", "overturns": "overturn", "collapses": "collapse"}
    states: dict = {}
    for e in judged:
        if e["quantity"] == "outcome" and e["unit"] == "collapsed" and e["ok"]:
            states.setdefault(_collapse_words(e["prototype"], structure_kind), []).append(
                "planar" if e["where"] == "planar" else "3D"
            )
    return [f"prototype and up-scaled model both {plural[s]} ({', '.join(n)})" for s, n in states.items()]


def judge(summary: dict, tolerances, *, structure_kind: str = "block", circular: bool = False) -> dict:
    """The verdict of a study's summary on the one similarity criterion (module docstring, docs/verdict.md).

    Parameters
    ----------
    summary : dict
        A study's summary (:meth:`~blastscale.study.StudyResult.summary`: ``design``, ``planar``, ``3d``,
        ``ensemble``, ``scenario``); ``3d.model`` and ``ensemble`` in prototype units (up-scaled).
    tolerances : blastscale.scenario.specs.VerdictSpec
        The scenario's ``[verdict]`` table.
    structure_kind : str
        The structure's kind (a block "overturns", others "collapse").
    circular : bool
        Circular drums (chaotic: the verdict's limits say so).

    Returns
    -------
    dict
        ``similar`` (True, False, or None when nothing is compared: prototype only, gravity alone, no
        engine compared), ``line`` (``Verdict: ...``), ``reasons`` (why not), ``facts``, ``limits``,
        ``worst`` (the judged entry with the largest ratio, None when none), ``judged`` (every quantity
        judged: ``quantity``, ``where``, ``prototype``, ``model`` [SI, prototype units], ``error``,
        ``tolerance`` [-], ``ratio`` = error / tolerance, ``unit``, ``basis`` (single or ensemble), ``ok``)
        and ``rest`` (the at-rest check, None when the 3D runs have none).

    Examples
    --------
    A planar comparison whose first swing is 10 % short:

    >>> from blastscale.scenario import VerdictSpec
    >>> rot = {"collapsed": False, "max_rotation_rad": 0.1}
    >>> s = {"design": {}, "planar": {"prototype": rot, "model": rot, "similarity": {"first_peak_ratio": 0.9}}}
    >>> v = judge(s, VerdictSpec())
    >>> v["line"]
    'Verdict: NOT similar: first peak (planar), ratio 0.9 (up-scaled model / prototype), 10 % off (tolerance 5 %).'
    >>> round(v["worst"]["ratio"], 12), len(v["judged"])
    (2.0, 3)
    """
    if summary.get("design") is None:
        return _unscaled(summary, structure_kind, tolerances)
    judged = _planar(summary.get("planar"), tolerances) + _three_d(
        summary.get("3d"), summary.get("ensemble"), tolerances, structure_height(summary)
    )
    failing = sorted((e for e in judged if not e["ok"]), key=lambda e: -e["ratio"])
    rest, rest_reasons = _rest(summary.get("3d"), tolerances)
    # not at rest first: a response to a blast on a structure still moving is not the blast's
    reasons = rest_reasons + [describe(e, structure_kind) for e in failing]
    imp = (summary.get("design") or {}).get("impulsive")
    if isinstance(imp, dict) and imp.get("impulsive") is False:
        reasons.append("the load is not impulsive, so the general law does not guarantee similarity")
    limits = _limits(summary, circular)
    facts = _facts(judged, structure_kind)
    if reasons:
        similar = False
        shown = reasons[:_LINE_REASONS]
        more = len(reasons) - len(shown)
        line = "Verdict: NOT similar: " + "; ".join(shown) + (f"; and {more} more" if more else "")
    elif judged:
        similar = True
        worst = max(judged, key=lambda e: e["ratio"])
        said = [*facts, f"all {len(judged)} quantities judged within their tolerances"]
        if worst["quantity"] != "outcome" and worst["unit"] not in ("probability", "fall probability"):
            said.append(f"the closest to its limit: {describe(worst, structure_kind)}")
        line = "Verdict: similar: " + "; ".join(said)
    else:
        similar = None
        line = "Verdict: not established: no engine compared the prototype and the model"
    if limits:
        line += ". Limits: " + "; ".join(limits)
    return _verdict(similar, line + ".", reasons, facts, limits, judged, rest)
