"""The test card section of the report: one printable page with the build, the shot, the layout
(dimensioned plan and elevation, safety circles), the instruments and the predicted response, in the
specimen's own units (mm, ms, kPa, mg).

Every number printed is a ``<span class="num" data-key=... data-unit=...>`` (an SVG ``<text>`` in the
drawings) whose ``data-key`` is its path in ``summary.json``'s ``test_card`` (parts joined by ``/``:
threshold keys such as "6.9 kPa" hold a dot) and ``data-unit`` the unit
it is shown in (:data:`UNITS`: the factor from the card's SI value), written with four significant
digits: tests/system/test_test_card.py reads them back against summary.json.
"""

from __future__ import annotations

import html
import math
from typing import Any

from ..planning.card import study_test_card
from ..planning.odds import outcome_odds_text

__all__ = ["card_of", "card_section", "UNITS", "shown", "mass_unit"]

#: Display unit -> factor from the card's SI value (m, s, Pa, kg, Hz, rad, ratios).
UNITS = {
    "mm": 1e3,
    "m": 1.0,
    "ms": 1e3,
    "us": 1e6,
    "ns": 1e9,
    "s": 1.0,
    "kPa": 1e-3,
    "Pa": 1.0,
    "MHz": 1e-6,
    "kHz": 1e-3,
    "Hz": 1.0,
    "fps": 1.0,
    "g": 1e3,
    "mg": 1e6,
    "kg": 1.0,
    "rad": 1.0,
    "deg": 180.0 / math.pi,
    "%": 100.0,
    "": 1.0,
    "frames": 1.0,
    "Pa s": 1.0,
    "kg/m3": 1.0,
}


def card_of(result):
    """The test card of a study (:func:`blastscale.planning.study_test_card`), computed once and carried by the
    result (:meth:`~blastscale.study.StudyResult.view`); None without a ``[lab]`` table or without a specimen."""
    if result.scenario.lab is None or result.design is None:
        return None
    return result.view("test_card", study_test_card)


def shown(value: float, unit: str) -> str:
    """How a card value [SI] is printed in ``unit``: four significant digits."""
    return f"{value * UNITS[unit]:.4g}"


def _get(card: dict, key: str):
    node: Any = card
    for part in key.split("/"):
        node = node[int(part)] if isinstance(node, list) else node[part]
    return node


def _e(x) -> str:
    return html.escape(str(x), quote=True)


def _n(card: dict, key: str, unit: str) -> str:
    v = _get(card, key)
    if v is None or (isinstance(v, float) and not math.isfinite(v)):
        return "-"
    suffix = {"": "", "%": " %", "fps": "", "frames": ""}.get(unit, " " + unit.replace("us", "µs"))
    return f'<span class="num" data-key="{_e(key)}" data-unit="{_e(unit)}">{shown(v, unit)}</span>{_e(suffix)}'


def _t(x: float, y: float, card: dict, key: str, unit: str, anchor: str = "middle", prefix: str = "") -> str:
    v = _get(card, key)
    return (
        f'<text x="{x:.1f}" y="{y:.1f}" text-anchor="{anchor}" class="num" data-key="{_e(key)}" '
        f'data-unit="{_e(unit)}" data-prefix="{_e(prefix)}">{_e(prefix)}{shown(v, unit)}</text>'
        f'<text x="{x:.1f}" y="{y + 11:.1f}" text-anchor="{anchor}" class="u">{_e(unit)}</text>'
    )


def _rows(rows) -> str:
    return "<table>" + "".join(f"<tr><th>{_e(a)}</th><td>{b}</td></tr>" for a, b in rows) + "</table>"


def _dim(x1, y1, x2, y2, label: str) -> str:
    return (
        f'<line x1="{x1:.1f}" y1="{y1:.1f}" x2="{x2:.1f}" y2="{y2:.1f}" class="dim" marker-start="url(#a)" '
        f'marker-end="url(#a)"/>{label}'
    )


_DEFS = (
    '<defs><marker id="a" viewBox="0 0 10 10" refX="5" refY="5" markerWidth="6" markerHeight="6" '
    'orient="auto-start-reverse"><path d="M0,0L10,5L0,10z"/></marker></defs>'
)


def _plan_svg(card: dict) -> str:
    """Plan of the set-up (x along the blast, y across), to scale, dimensioned in mm."""
    L = card["layout"]
    b = card["build"]
    R, w, d = card["standoff_m"], b["width_m"], b["depth_m"]
    span = max(R + w, 1.3 * R, d) * 1.6
    W, H = 520.0, 300.0
    k = min((W - 80) / span, (H - 80) / max(2.4 * R, d * 1.6))
    x0, y0 = 60.0 + 0.2 * R * k, H / 2

    def P(x, y):
        return x0 + x * k, y0 - y * k

    ox = L["charge"][0]  # the layout's frame (origin at the footprint's centre) drawn from the charge
    cx, cy = P(0, 0)
    sx, sy = P(R, d / 2)
    rg = P(L["reflected_gauge"][0] - ox, L["reflected_gauge"][1])
    ig = P(L["incident_gauge"][0] - ox, L["incident_gauge"][1])
    out = [
        f'<svg class="draw" viewBox="0 0 {W:.0f} {H:.0f}" width="{W:.0f}" height="{H:.0f}">{_DEFS}',
        f'<circle cx="{cx:.1f}" cy="{cy:.1f}" r="{max(3.0, L["charge_radius_m"] * k):.1f}" class="charge"/>',
        f'<text x="{cx:.1f}" y="{cy - 10:.1f}" text-anchor="middle">charge</text>',
        f'<rect x="{sx:.1f}" y="{sy:.1f}" width="{w * k:.1f}" height="{d * k:.1f}" class="spec"/>',
        f'<circle cx="{rg[0]:.1f}" cy="{rg[1]:.1f}" r="4" class="gauge"/><text x="{rg[0] + 7:.1f}" '
        f'y="{rg[1] + 4:.1f}">reflected gauge</text>',
        f'<circle cx="{ig[0]:.1f}" cy="{ig[1]:.1f}" r="4" class="gauge"/><text x="{ig[0] + 7:.1f}" '
        f'y="{ig[1] + 4:.1f}">side-on gauge</text>',
        f'<text x="{sx + w * k / 2:.1f}" y="{20:.1f}" text-anchor="middle">camera (side view) at</text>',
        _t(sx + w * k / 2 + 105, 20, card, "layout/camera_distance_m", "mm", "start"),
        _dim(cx, H - 30, sx, H - 30, _t((cx + sx) / 2, H - 36, card, "standoff_m", "mm")),
        _dim(
            sx + w * k + 14,
            sy,
            sx + w * k + 14,
            sy + d * k,
            _t(sx + w * k + 20, y0, card, "build/depth_m", "mm", "start"),
        ),
        _dim(sx, sy - 8, sx + w * k, sy - 8, _t(sx + w * k / 2, sy - 14, card, "build/width_m", "mm")),
        "</svg>",
    ]
    return "".join(out)


def _elevation_svg(card: dict) -> str:
    """Elevation (x along the blast, z up), to scale: floor, charge, specimen at rest and at its
    predicted first peak (dashed), gauge heights."""
    b, p = card["build"], card["predicted"]
    R, w, h = card["standoff_m"], b["width_m"], b["height_m"]
    W, H = 520.0, 300.0
    k = min((W - 120) / (R + w + 0.9 * h), (H - 80) / h)
    x0, z0 = 60.0, H - 40

    def P(x, z):
        return x0 + x * k, z0 - z * k

    fx, fz = P(R, 0)
    out = [
        f'<svg class="draw" viewBox="0 0 {W:.0f} {H:.0f}" width="{W:.0f}" height="{H:.0f}">{_DEFS}',
        f'<line x1="10" y1="{z0:.1f}" x2="{W - 10:.1f}" y2="{z0:.1f}" class="floor"/>',
        (
            f'<path d="M{x0 - 6:.1f},{z0:.1f} A6,6 0 0 1 {x0 + 6:.1f},{z0:.1f}z" class="charge"/>'
            if not card.get("charge_height_m")
            # a free-air charge on its stand
            else f'<line x1="{x0:.1f}" y1="{z0:.1f}" x2="{x0:.1f}" y2="{P(0, card["charge_height_m"])[1]:.1f}" class="floor"/>'
            f'<circle cx="{x0:.1f}" cy="{P(0, card["charge_height_m"])[1]:.1f}" r="6" class="charge"/>'
        ),
        f'<rect x="{fx:.1f}" y="{z0 - h * k:.1f}" width="{w * k:.1f}" height="{h * k:.1f}" class="spec"/>',
    ]
    th = 0.5 * math.pi if p["collapsed"] else (p["first_peak_rotation_rad"] or 0.0)
    pivot = (R + w, 0.0)
    pts = []
    for x, z in ((R, 0.0), (R + w, 0.0), (R + w, h), (R, h)):
        dx, dz = x - pivot[0], z - pivot[1]
        pts.append(
            P(pivot[0] + dx * math.cos(th) + dz * math.sin(th), pivot[1] - dx * math.sin(th) + dz * math.cos(th))
        )
    out.append('<polygon points="' + " ".join(f"{a:.1f},{c:.1f}" for a, c in pts) + '" class="peak"/>')
    gz = P(0, card["layout"]["reflected_gauge"][2])[1]
    out += [
        f'<circle cx="{fx - 6:.1f}" cy="{gz:.1f}" r="4" class="gauge"/>',
        _dim(x0, z0 + 18, fx, z0 + 18, _t((x0 + fx) / 2, z0 + 12 - 14, card, "standoff_m", "mm")),
        _dim(
            fx + w * k + 60,
            z0,
            fx + w * k + 60,
            z0 - h * k,
            _t(fx + w * k + 66, z0 - h * k / 2, card, "build/height_m", "mm", "start"),
        ),
        f'<text x="{fx + w * k + 8:.1f}" y="{z0 - h * k - 8:.1f}">first peak (dashed):</text>',
        _t(fx + w * k + 8, z0 - h * k + 6, card, "predicted/top_displacement_m", "mm", "start", "top moves "),
        "</svg>",
    ]
    return "".join(out)


def _site_svg(card: dict) -> str:
    """Site plan: the safety circles around the charge (radii on a logarithmic scale; the numbers are
    the distances) with the specimen and its debris zone."""
    keys = [t["key"] for t in card["thresholds"] if t["pressure_Pa"] is not None]
    dist = [card["safety_distances_m"][k] for k in keys]
    lo, hi = math.log(min(dist)), math.log(max(dist))
    W = H = 420.0
    c = W / 2

    def rad(x):
        return 40.0 + (c - 60.0) * ((math.log(x) - lo) / (hi - lo) if hi > lo else 1.0)

    out = [
        f'<svg class="draw" viewBox="0 0 {W:.0f} {H:.0f}" width="{W:.0f}" height="{H:.0f}">',
        '<text x="8" y="14">radii on a logarithmic scale; the numbers are the distances</text>',
    ]
    for i, (key, x) in enumerate(zip(keys, dist)):
        r = rad(x)
        a = math.radians(35.0 + 30.0 * i)
        out.append(f'<circle cx="{c}" cy="{c}" r="{r:.1f}" class="ring"/>')
        out.append(f'<text x="{c + r * math.cos(a) + 3:.1f}" y="{c - r * math.sin(a) - 3:.1f}">{_e(key)}:</text>')
        out.append(
            _t(c + r * math.cos(a) + 3, c - r * math.sin(a) + 9, card, f"safety_distances_m/{key}", "m", "start")
        )
    out.append(
        f'<circle cx="{c}" cy="{c}" r="3" class="charge"/><text x="{c}" y="{c + 16}" text-anchor="middle">'
        "charge</text></svg>"
    )
    return "".join(out)


def card_section(result) -> str:
    """The section's HTML (a hint to add a ``[lab]`` table when there is none)."""
    c = card_of(result)
    if c is None:
        return _no_card(result)
    build, shot, safety = _build_table(c), _shot_table(c), _safety_table(c)
    inst, pred = _instruments_table(c), _predicted_table(c)
    warn = "".join(f'<li class="warn">{_e(w)}</li>' for w in c["warnings"])
    v = c["verdict"]
    return (
        f'<div class="card"><p class="{"lead" if v["similar"] else "warn"}"><b>{_e(v["line"])}</b></p>'
        f'<div class="cols"><div><h3>Build</h3>{build}</div><div><h3>Shot</h3>{shot}</div></div>'
        f"<h3>Layout: plan and elevation (to scale)</h3>{_plan_svg(c)}{_elevation_svg(c)}"
        f'<h3>Safety circles (around the charge) and the debris zone</h3><div class="cols">{_site_svg(c)}'
        f"{safety}</div><h3>Range safety: fragments, pad, detonator</h3>{_range_section(c)}"
        f'<div class="cols"><div><h3>Instruments</h3>{inst}</div><div><h3>Predicted response '
        f"(specimen units)</h3>{pred}</div></div>" + (f"<ul>{warn}</ul>" if warn else "") + "</div>"
    )


def _no_card(result) -> str:
    """Why there is no card, and how to get one."""
    why = (
        "no specimen (the scenario has no [scale] table)"
        if result.design is None
        else "the scenario has no [lab] table"
    )
    return (
        f"<p>No test card: {_e(why)}. Add a <code>[lab]</code> table (docs/planning.md) for the charge in a "
        "real explosive, the safety envelope, the instruments and the odds, or let <code>blastscale plan"
        "</code> choose the design.</p>"
    )


def mass_unit(kg) -> str:
    """The unit a mass [kg] reads in: mg below 1 g, g below 1 kg, else kg (no "5.592e+04 g").

    >>> mass_unit(55.92), mass_unit(0.0559), mass_unit(7.816e-4)
    ('kg', 'g', 'mg')
    """
    if kg is None or not math.isfinite(kg) or kg >= 1.0:
        return "kg"
    return "g" if kg >= 1e-3 else "mg"


def _m(c: dict, key: str) -> str:
    """A mass of the card in the unit it reads in (:func:`mass_unit`)."""
    v = _get(c, key)
    return _n(c, key, mass_unit(v if isinstance(v, (int, float)) else None))


def _build_table(c: dict) -> str:
    """The specimen to build: its kind, material, size, mass, scale (and one unit of an assembly)."""
    b = c["build"]
    return _rows(
        [
            ("specimen", f"{_e(b['kind'])}, {_e(b['material'])}"),
            (
                "height x width x depth",
                f"{_n(c, 'build/height_m', 'mm')} x {_n(c, 'build/width_m', 'mm')} x {_n(c, 'build/depth_m', 'mm')}",
            ),
            ("mass", _m(c, "build/mass_kg")),
            ("density", _n(c, "build/density_kg_m3", "kg/m3")),
            ("scale lambda", _n(c, "build/scale", "")),
            ("density ratio gamma", _n(c, "build/density_ratio", "")),
            (
                "joint friction",
                f"{_e(b['friction']['pair'])} {_n(c, 'build/friction/nominal', '')} nominal "
                f"({_n(c, 'build/friction/low', '')}-{_n(c, 'build/friction/high', '')}), the prototype's "
                f"{_n(c, 'build/friction/prototype', '')}: measure by tilt test (mu = tan of the tilt angle at the "
                "first slip)",
            ),
            *(
                [
                    (
                        f"one unit ({_e(b['unit']['name'])}, of {b['unit']['bodies']}), x x y x z",
                        " x ".join(_n(c, f"build/unit/size_{a}_m", "mm") for a in "xyz")
                        + f", {_m(c, 'build/unit/mass_kg')}",
                    )
                ]
                if b.get("unit")
                else []
            ),
        ]
    )


def _shot_table(c: dict) -> str:
    """The charge to fire: a calibrated source's setting, or the explosive, its mass to weigh, its TNT equivalents
    (each on its own line), the initiator, where it stands, the weighing precision."""
    src = c.get("source")  # a calibrated source: its setting first (docs/planning.md, "Sources")
    return _rows(
        [
            *([("source (its setting)", _e(f"{src['name']}: {src['setting']}"))] if src else []),
            ("explosive", _e(c["explosive"])),
            ("to weigh", _m(c, "explosive_mass_kg")),
            ("TNT equivalent, impulse (the design)", _m(c, "tnt_equivalent_impulse_kg")),
            ("TNT equivalent, pressure", _m(c, "tnt_equivalent_pressure_kg")),
            ("TNT equivalent, safety (the stricter basis; the licence limit)", _m(c, "tnt_equivalent_safety_kg")),
            (
                f"initiator ({c['detonator']['initiator']}), TNT equivalent by impulse",
                _m(c, "detonator/tnt_impulse_kg"),
            ),
            (
                f"initiator ({c['detonator']['initiator']}), TNT equivalent by pressure",
                _m(c, "detonator/tnt_pressure_kg"),
            ),
            ("stand-off to the front face", _n(c, "standoff_m", "mm")),
            ("positions (this card, the plan and [fired])", _e(c["layout"]["frame"])),
            ("the specimen's front face at x", _n(c, "layout/specimen_front_x_m", "mm")),
            *(
                [
                    ("charge height (on the floor: surface burst)", _n(c, "charge_height_m", "mm")),
                    ("charge radius (hemisphere)", _n(c, "layout/charge_radius_m", "mm")),
                ]
                if c.get("burst", "surface") == "surface"
                else [
                    ("charge height (on a stand: free-air burst)", _n(c, "charge_height_m", "mm")),
                    ("charge radius (sphere)", _n(c, "layout/charge_radius_m", "mm")),
                ]
            ),
            ("weighing precision (1 sd) to keep the first peak", _m(c, "weighing_precision_kg")),
        ]
    )


def _safety_table(c: dict) -> str:
    """The safety distance of each threshold, the debris zone, and the prototype event's for scale."""
    return _rows(
        [(f"{t['key']}: {t['meaning']}", _n(c, f"safety_distances_m/{t['key']}", "m")) for t in c["thresholds"]]
        + [
            (f"debris zone around the specimen (x {c['debris_margin']:g} the reach)", _n(c, "debris_radius_m", "mm")),
            ("prototype event: 6.9 kPa", _n(c, "prototype/safety_distances_m/6.9 kPa", "m")),
            ("prototype event: debris zone", _n(c, "prototype/debris_radius_m", "m")),
        ]
    )


def _range_section(c: dict) -> str:
    """What the range safety officer signs beyond the blast: the fragment hazard distance and each source's, the pad,
    the detonator (the numbers tagged; the methods and sources in words below them)."""
    f, pad, det = c["fragments"], c["pad"], c["detonator"]
    table = _rows(
        [
            ("fragment hazard distance (keep-out)", _n(c, "fragments/distance_m", "m")),
            *(
                (f"fragments: {s['source']} (lands at most)", _n(c, f"fragments/sources/{i}/distance_m", "m"))
                for i, s in enumerate(f["sources"])
            ),
            ("pad: steel plate on concrete, thickness", _n(c, "pad/thickness_m", "mm")),
            ("pad plan, along x across", f"{_n(c, 'pad/length_m', 'mm')} x {_n(c, 'pad/width_m', 'mm')}"),
            ("detonator inserted to the charge's centre, depth", _n(c, "detonator/insertion_depth_m", "mm")),
        ]
    )
    notes = [
        f"Fragments: {f['method']}. "
        + " ".join(f"{s['source']}: {s['note']}; {s['method']}." for s in f["sources"])
        + f" The pad: {f['pad_fragments']}.",
        f"Pad: {pad['material']}: {pad['why']}.",
        f"Detonator: {det['used']}; {det['placement']}. {det['counted'][0].upper()}{det['counted'][1:]}.",
    ]
    return table + "".join(f'<p class="muted">{_e(n)}</p>' for n in notes)


def _instruments_table(c: dict) -> str:
    """The gauges' and the camera's ranges, rates and records."""
    i = "instruments/"
    return _rows(
        [
            ("reflected gauge range", _n(c, i + "reflected_gauge_range_Pa", "kPa")),
            ("side-on gauge range", _n(c, i + "incident_gauge_range_Pa", "kPa")),
            ("gauge rise time at most", _n(c, i + "pressure_rise_time_s", "us")),
            ("sampling rate", _n(c, "pressure_sampling_hz", "MHz")),
            (
                "impulse error from the shock between two samples (95 %)",
                _n(c, i + "pressure_impulse_arrival_error", "%"),
            ),
            ("pressure record", _n(c, i + "pressure_record_s", "ms")),
            ("camera frame rate", _n(c, "camera_fps", "fps") + " frames/s"),
            ("camera record", _n(c, i + "camera_record_s", "ms")),
            (
                "frames over the pulse / the rise / the response",
                f"{_n(c, i + 'frames_over_pulse', '')} / {_n(c, i + 'frames_over_rise', '')} / "
                f"{_n(c, i + 'frames_over_response', '')}",
            ),
            ("displacement range", _n(c, i + "displacement_range_m", "mm")),
            ("trigger delay (arrival)", _n(c, i + "trigger_delay_s", "us")),
        ]
    )


def _predicted_table(c: dict) -> str:
    """The specimen's predicted response and load, in its own units, and the odds of the outcome agreeing."""
    p = "predicted/"
    outcome = "overturns" if p_get(c, "collapsed") else "rocks and stands"
    return _rows(
        [
            ("outcome", outcome),
            ("first peak rotation", _n(c, p + "first_peak_rotation_rad", "deg")),
            ("time of the first peak (from the arrival)", _n(c, p + "first_peak_time_s", "ms")),
            ("top corner displacement", _n(c, p + "top_displacement_m", "mm")),
            ("whole response", _n(c, p + "response_time_s", "ms")),
            ("arrival time", _n(c, p + "arrival_time_s", "us")),
            ("reflected peak pressure, the specimen's face", _n(c, p + "reflected_pressure_Pa", "kPa")),
            ("reflected impulse, the specimen's face", _n(c, p + "reflected_impulse_Pa_s", "Pa s")),
            ("reflected gauge: slant distance", _n(c, p + "reflected_gauge_distance_m", "mm")),
            ("reflected gauge: angle of incidence (deg)", _n(c, p + "reflected_gauge_angle_deg", "")),
            ("reflected gauge: its peak pressure", _n(c, p + "reflected_gauge_pressure_Pa", "kPa")),
            ("reflected gauge: its impulse", _n(c, p + "reflected_gauge_impulse_Pa_s", "Pa s")),
            ("side-on gauge: its peak pressure", _n(c, p + "incident_gauge_pressure_Pa", "kPa")),
            ("side-on gauge: its impulse", _n(c, p + "incident_gauge_impulse_Pa_s", "Pa s")),
            ("positive duration", _n(c, p + "positive_duration_s", "us")),
            ("outcome agrees with the prototype (planar Monte Carlo)", _e(outcome_odds_text(c["odds"]))),
            (
                "outcome agrees with the prototype (3D: "
                + ("the one comparison" if (c["odds_3d"] or {}).get("members") == 0 else "ensemble")
                + ")",
                _e(outcome_odds_text(c["odds_3d"]))
                if c["odds_3d"]
                else "not run in 3D (set lab.ensemble_3d for an ensemble)",
            ),
            ("first-peak spread (1 sd, relative)", _n(c, "first_peak_spread", "%")),
        ]
    )


def p_get(card: dict, key: str):
    return card["predicted"][key]


#: Styles of the card (added to the report's).
CSS = """
.card table{font-size:.92em;max-width:100%}.card th{overflow-wrap:anywhere;font-weight:normal;text-align:left}.card .cols{display:flex;flex-wrap:wrap;gap:1.2em}.card h3{margin:.6em 0 .2em}
svg.draw{border:1px solid #d0d7de;margin:.3em .6em .3em 0;font-size:10px;background:#fff}
svg .spec{fill:#c9b79c;stroke:#333}svg .peak{fill:none;stroke:#b02a2a;stroke-dasharray:4 3}
svg .charge{fill:#d08a00;stroke:#333}svg .gauge{fill:#2b6cb0}svg .floor{stroke:#333;stroke-width:2}
svg .dim{stroke:#444}svg .ring{fill:none;stroke:#b02a2a}svg .debris{fill:#c9b79c;fill-opacity:.5;stroke:#333}
svg text.u{fill:#57606a;font-size:9px}
@media print{section#test_card{page-break-before:always;page-break-after:always}}
"""
