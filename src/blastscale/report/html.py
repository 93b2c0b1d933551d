"""A self-contained HTML report of a study, for someone who never ran the tool.

One file, no external resources: the figures are embedded as base64 PNG, the interactive 3D view of the motion
(:mod:`.motion`) with its script and data inline. Sections (each a
``<section id=...>``): ``experiment`` (what to build and detonate), ``test_card`` (the printable
card of a scenario with a ``[lab]`` table: :mod:`.card`), ``loads`` (blast loads of
both systems, delivered vs required ratios), ``impulsive`` (the a-posteriori check),
``similarity`` (figures and numbers per engine, the critical charge), ``warnings``, ``slips``
(the paper's slips that apply), ``scenario`` (the inputs, as TOML) and ``provenance``. Cells, tables, embedded
figures and the page style come from :mod:`.markup`.
"""

from __future__ import annotations

import math
from typing import Iterable

from ..study.criterion import entry_value
from .card import CSS as _CARD_CSS, card_section
from .labels import label, specimen_rows
from .markup import (
    PAGE_CSS,
    compare_table,
    escape,
    figure_html,
    flatten,
    format_charge,
    format_value,
    html_table,
    split_unit_for_tables,
)
from .motion import motion_section
from .outcomes import ARRIVAL_NOTE, first_peak_rows, stability_lead, timing_rows
from .slips import applicable_slips

__all__ = ["SECTIONS", "render_report"]

#: Section ids of the report, in order.
SECTIONS = (
    "experiment",
    "test_card",
    "loads",
    "impulsive",
    "similarity",
    "warnings",
    "slips",
    "scenario",
    "provenance",
)


def _experiment(result) -> str:
    exp = result.experiment()
    p, m = exp["prototype"], exp["model"]
    kind = result.scenario.structure.kind
    if m is None:
        rows = [(*split_unit_for_tables(k), v) for k, v in p.items() if not isinstance(v, str)]
        return (
            '<p class="lead">Prototype only: this scenario has no <code>[scale]</code> table, so no specimen '
            "is designed and nothing is compared. The sections below give the prototype's blast load and "
            "response (add a <code>[scale]</code> table to design a reduced-scale test).</p>"
            + html_table(("quantity", "unit", "prototype"), [(q, v, u) for q, u, v in rows])
        )
    dims = ("height_m", "width_m", "depth_m")
    if kind == "block":
        size = " x ".join(f"{m[k] * 100:.4g}" for k in dims if k in m) + " cm (height x width x depth)"
    else:
        size = f"{m.get('height_m', float('nan')) * 100:.4g} cm high"
    of = "of " if kind == "block" else ""
    mat = m.get("material", "")
    mat_words = "the prototype's material" if mat == "same as the prototype" else mat
    lead = (
        f"Build a {escape(kind)} {of}{escape(size)}, {format_value(m.get('mass_kg', float('nan')) * 1e3)} g, "
        f"in {escape(mat_words)} (density {format_value(m.get('density_kg_m3'))} kg/m^3), and detonate "
        f"<b>{escape(format_charge(m['charge_kg']))} of TNT</b> (equivalent) at <b>{m['standoff_m'] * 100:.4g} cm</b> "
        "from its front face."
    )
    keys = [k for k in p if k in m and not isinstance(p[k], str)]
    rows = []
    for k in keys:
        label, unit = split_unit_for_tables(k)
        rows.append((label, p[k], m[k], unit))
    rows.append(("charge (TNT equivalent)", format_charge(p["charge_kg"]), format_charge(m["charge_kg"]), ""))
    rows.append(("material", "-", str(mat), ""))
    if "alpha_rad" in p:
        rows.append(("slenderness alpha", math.degrees(p["alpha_rad"]), math.degrees(m["alpha_rad"]), "deg"))
    scales = (
        f"Geometric scale lambda = {exp['scale']:.6g} (1/{1 / exp['scale']:.4g}), density ratio gamma = "
        f"{exp['density_ratio']:.4g}, gravity ratio = {exp['gravity_ratio']:.4g}, law: {escape(exp['law'])}."
    )
    return f'<p class="lead">{lead}</p><p>{scales}</p>' + html_table(("quantity", "prototype", "model", "unit"), rows)


def _loads(result) -> str:
    d = result.design
    if result.blast is None:
        return (
            "<p>No charge: the structure under gravity alone, the stability check a designer runs before any "
            "blast (section 4 says whether it stands, settles or collapses).</p>"
        )
    if d is None:
        b = result.blast
        rows = [
            ("scaled distance Z", b.scaled_distance, "m/kg^(1/3)"),
            ("reflected peak pressure", b.reflected_pressure, "Pa"),
            ("reflected impulse", b.reflected_impulse, "Pa s"),
            ("positive duration", b.positive_duration, "s"),
            ("arrival time", b.arrival_time, "s"),
        ]
        return (
            html_table(("quantity", "prototype", "unit"), rows)
            + f"<p>Blast model: <b>{escape(b.blast_model)}</b>, pulse: <b>{escape(result.scenario.blast.pulse_shape)}</b>, load "
            f"method <b>{escape(result.scenario.blast.load)}</b>.</p>" + _load_model(result)
        )
    p, m, f = d.prototype, d.specimen, d.factors
    rows = [
        ("scaled distance Z", p.scaled_distance, m.scaled_distance, d.scaled_distance_factor, None, "m/kg^(1/3)"),
        ("reflected peak pressure", p.reflected_pressure, m.reflected_pressure, d.pressure_ratio, f.pressure, "Pa"),
        ("reflected impulse", p.reflected_impulse, m.reflected_impulse, d.impulse_ratio, f.impulse, "Pa s"),
        ("positive duration", p.positive_duration, m.positive_duration, d.duration_ratio, f.time, "s"),
        ("arrival time", p.arrival_time, m.arrival_time, m.arrival_time / p.arrival_time, None, "s"),
    ]
    note = (
        "<p>Only the impulse follows the scaling law exactly (delivered = required); the peak pressure and "
        "the duration do not, which is harmless while the load is impulsive (next section). Blast model: "
        f"<b>{escape(p.blast_model)}</b>, pulse: <b>{escape(result.scenario.blast.pulse_shape)}</b>, load method "
        f"<b>{escape(result.scenario.blast.load)}</b>. {escape(d.root_note)} {escape(ARRIVAL_NOTE)}</p>"
    )
    return (
        html_table(("quantity", "prototype", "model", "delivered ratio", "required ratio", "unit"), rows)
        + note
        + _load_model(result)
    )


def _load_model(result) -> str:
    """Which load model was used (burst, clearing, negative phase: the paper's unless asked for) and,
    with a design, what clearing and the negative phase do to each system (docs/blast_physics.md)."""
    bl, d = result.scenario.blast, result.design
    sb = d.specimen.burst if d is not None else None
    used = [
        f"{bl.burst} burst" + (f" (specimen: {sb} burst)" if sb and sb != bl.burst else ""),
        "clearing of the finite faces (UFC 3-340-02 Sec. 2-15.3.2)" if bl.clearing else "no clearing (unbounded faces)",
        "negative phase (UFC 3-340-02 Fig. 2-16, Granström's cubic)" if bl.negative_phase else "positive phase only",
    ]
    paper = bl.burst == "surface" and not bl.clearing and not bl.negative_phase and (sb in (None, "surface"))
    note = " (the paper's assumptions)" if paper else ""
    out = f"<p>Load model: {escape('; '.join(used) + note)}.</p>"
    e = None if d is None else d.effects
    if not e:
        return out
    rows = []
    for key, name, unit in (
        ("clearing_time_s", "clearing time t_c", "s"),
        ("clearing_time_over_positive_duration", "t_c / t_o", "-"),
        ("uncleared_impulse_Pa_s", "uncleared impulse", "Pa s"),
        ("cleared_impulse_Pa_s", "cleared impulse", "Pa s"),
        ("cleared_over_uncleared_impulse", "cleared / uncleared impulse", "-"),
    ):
        if "clearing" in e:
            rows.append((name, e["clearing"]["prototype"][key], e["clearing"]["model"][key], unit))
    for key, name, unit in (
        ("negative_impulse_Pa_s", "negative impulse", "Pa s"),
        ("negative_over_positive_impulse", "negative / positive impulse", "-"),
    ):
        if "negative_phase" in e:
            rows.append((name, e["negative_phase"]["prototype"][key], e["negative_phase"]["model"][key], unit))
    if rows:
        out += (
            "<p>What the scaling law does not match (a difference above 5 % is listed under Warnings):</p>"
            + html_table(("quantity", "prototype", "model", "unit"), rows)
        )
    if "lab_burst" in e:
        lb = e["lab_burst"]
        out += (
            f"<p>Lab charge {lb['charge_height_m'] * 100:.3g} cm above the floor: <b>{escape(lb['kind'])}</b> burst "
            f"(the floor's reflection arrives {lb['delay_over_positive_duration']:.2g} positive durations after "
            "the shock).</p>"
        )
    return out


def _impulsive(result) -> str:
    if result.design is None:
        return "<p>No specimen: the impulsive check of the scaling law does not apply.</p>"
    imp = result.design.impulsive
    if imp is None:
        return (
            "<p>The impulsive check t<sub>o</sub> p needs a rocking frequency p; it is computed for a single "
            "block. For this structure, compare the blast duration with the response time in the figures.</p>"
        )
    ok = imp.impulsive
    verdict = (
        '<span class="ok">impulsive: the general law applies</span>'
        if ok
        else '<span class="bad">NOT impulsive: similarity is not guaranteed</span>'
    )
    return (
        f"<p>The general law matches the impulse only. It holds while the pulse is short compared with the "
        f"structure's own time: t<sub>o</sub> p &lt; {imp.threshold:g} with p = sqrt(3 g / 4 r) "
        f"(Housner). Prototype: t<sub>o</sub> p = {imp.prototype_ratio:.3g}; model: {imp.model_ratio:.3g} "
        f"&rarr; {verdict}.</p>"
    )


#: Rows of the verdict's table: every quantity outside its tolerance, and the closest of the others up to this many.
_VERDICT_ROWS = 12


def _judged(verdict: dict) -> str:
    """The verdict quantity by quantity: the worst first (every failing one, then the closest to their limits)."""
    judged = sorted(verdict["judged"], key=lambda e: -e["ratio"])
    if not judged:
        return ""
    rows = [e for e in judged if not e["ok"]]
    rows += [e for e in judged if e["ok"]][: max(0, _VERDICT_ROWS - len(rows))]
    body = [
        (
            e["quantity"] + (" (ensemble medians)" if e["basis"] == "ensemble" else ""),
            e["where"],
            entry_value(e, "prototype"),
            entry_value(e, "model"),
            "differs" if math.isinf(e["error"]) else f"{e['error'] * 100:.3g} %",
            "-" if e["tolerance"] == 0 else f"{e['tolerance'] * 100:g} %",
            "yes" if e["ok"] else "NO",
        )
        for e in rows
    ]
    return (
        f"<h3>The verdict, quantity by quantity</h3><p>{len(judged)} quantities judged over the whole structure "
        f"(docs/verdict.md), the worst first; {len(rows)} shown ({len(judged) - len(rows)} more within their "
        "tolerances in summary.json, <code>verdict.judged</code>).</p>"
        + html_table(("quantity", "where", "prototype", "up-scaled model", "off", "tolerance", "within"), body)
    )


def _similarity(result, figures) -> str:
    out = []
    s = result.summary()
    figs = {f.name: (f, png) for f, png in figures}
    out.append(_judged(s["verdict"]))  # "" when nothing is judged
    if result.design is not None:
        rows = specimen_rows(s, result.design.factors.to_dict()) + timing_rows(result)
        if rows:
            out.append(
                "<h3>What to measure on the specimen</h3><p>The up-scaled model's response brought back to "
                "the specimen's own size (times the scaling factors): compare a measurement with these "
                "directly.</p>" + html_table(("quantity", "prototype (SI)", "expected on the specimen", "unit"), rows)
            )
    if result.planar is not None:
        pl = s["planar"]
        out.append("<h3>Planar rocking (paper Eq. of motion, Housner impacts)</h3>")
        out.append(compare_table(pl["prototype"], pl["model"]))
        if pl["similarity"] is not None:
            out.append(
                html_table(
                    ("similarity figure", "value", "unit"),
                    [(label(k), v, split_unit_for_tables(k)[1]) for k, v in pl["similarity"].items()],
                )
            )
        if "planar_rocking" in figs:
            f, png = figs["planar_rocking"]
            out.append(figure_html(png, f.title, f.caption, f.name))
    if result.response3d is not None:
        r3 = s["3d"]
        out.append(f"<h3>3D rigid bodies (MuJoCo, Coulomb friction {result.scenario.structure.friction:g})</h3>")
        out.append(stability_lead(r3.get("prototype")))
        out.append(compare_table(r3["prototype"], r3["model"]))
        peaks = first_peak_rows(r3.get("similarity"))
        if peaks is not None:
            out.append(peaks[0] + html_table(peaks[1], peaks[2]))
        if r3.get("similarity") is not None:
            out.append(
                html_table(
                    ("similarity figure", "value", "unit"),
                    [
                        (label(k), v, split_unit_for_tables(k.split(".")[-1])[1])
                        for k, v in flatten(r3["similarity"])
                        if not isinstance(v, str) and not (peaks is not None and k.startswith("points."))
                    ],
                )
            )
        for name in ("snapshots_3d", "response_3d"):
            if name in figs:
                f, png = figs[name]
                out.append(figure_html(png, f.title, f.caption, f.name))
    if result.ensemble is not None:
        en = s["ensemble"]
        out.append(
            f"<h3>3D ensembles ({en['n_members']} members per system, loads perturbed by up to "
            f"{en['perturbation']:g})</h3>"
        )
        out.append(
            html_table(
                ("quantity", "value", "unit"),
                [
                    (label(k), v, split_unit_for_tables(k.split(".")[-1])[1])
                    for k, v in flatten(en)
                    if not isinstance(v, str) and k not in ("n_members", "perturbation")
                ],
            )
        )
        if "ensemble_envelopes" in figs:
            f, png = figs["ensemble_envelopes"]
            out.append(figure_html(png, f.title, f.caption, f.name))
    if result.critical is not None:
        c = result.critical
        out.append(
            f"<h3>Capacity</h3><p>Critical charge of the prototype at {c.standoff_m:g} m (planar, the largest "
            f"charge it survives without overturning): <b>{c.charge_kg:.4g} kg</b> "
            f"({c.evaluations} simulations). The scenario's charge is "
            f"{result.scenario.blast.charge_kg / c.charge_kg:.3g} of it.</p>"
        )
    if not "".join(out):
        out.append("<p>No engine was run.</p>")
    return "".join(out)


def _warnings(result) -> str:
    if not result.warnings:
        return "<p>None.</p>"
    return "<ul>" + "".join(f'<li class="warn">{escape(w)}</li>' for w in result.warnings) + "</ul>"


def _slips(result) -> str:
    rows = [(f"#{s.number}", s.where, s.text) for s in applicable_slips(result.scenario, result.design)]
    return (
        "<p>Where the printed paper is wrong or ambiguous blastscale implements the physics; these items "
        "concern this scenario (details and the tests that hold each: docs/paper_slips.md).</p>"
        + html_table(("#", "where", "what blastscale does"), rows, numeric_from=99)
    )


def _provenance(meta: dict, files: Iterable[str]) -> str:
    v = meta.get("versions", {})
    rows = [(k, str(val)) for k, val in v.items()]
    rows += [
        ("git commit", str(meta.get("git_commit") or "not a git checkout")),
        ("written (UTC)", str(meta.get("timestamp", ""))),
    ]
    return (
        html_table(("item", "value"), rows, numeric_from=99)
        + f'<p class="muted">Files next to this report: {escape(", ".join(files))}. Model results are '
        "up-scaled to prototype units; every history carries its unit in histories.nc.</p>"
    )


def _verdict(result) -> str:
    """The page's first statement: the study's ``Verdict: ...`` (:func:`blastscale.study.criterion.judge`),
    before the build instructions."""
    v = result.summary()["verdict"]
    cls = {True: "lead", False: "warn", None: "muted"}[v["similar"]]
    return f'<p id="verdict" class="{cls}"><b>{escape(v["line"])}</b></p>'


def render_report(
    result, figures, meta: dict, files: Iterable[str] = (), plan_html: str | None = None, motion: str | None = None
) -> str:
    """The report as one HTML string.

    Parameters
    ----------
    result : blastscale.study.StudyResult
        The study.
    figures : list of (Figure, bytes)
        :func:`blastscale.report.figures.render_figures` output (embedded as base64 PNG).
    meta : dict
        :func:`blastscale.io.results.provenance`.
    files : iterable of str
        Names of the other files of the result folder.
    plan_html : str, optional
        The plan of ``blastscale plan --out`` (a section ``plan`` before the test card).
    motion : str, optional
        The 3D views' section when the caller made it (:func:`~blastscale.report.motion.motion_section`);
        made here otherwise.

    Returns
    -------
    str
    """
    sc = result.scenario
    title = sc.title or "blast experiment"
    figs = {f.name: (f, png) for f, png in figures}
    pulses = ""
    if "blast_pulses" in figs:
        f, png = figs["blast_pulses"]
        pulses = figure_html(png, f.title, f.caption, f.name)
    drawing = "".join(figure_html(png, f.title, f.caption, f.name) for f, png in figures if f.name == "assembly")
    body = {
        "experiment": ("1. The experiment to build", _experiment(result) + drawing),
        "test_card": ("Test card", card_section(result)),
        "loads": (
            "2. Blast loads of the prototype" + ("" if result.design is None else " and the model"),
            _loads(result) + pulses,
        ),
        "impulsive": ("3. Impulsive check", _impulsive(result)),
        "similarity": (
            "4. Response of the prototype" if result.design is None else "4. Similarity: prototype vs up-scaled model",
            _similarity(result, figures) + (motion_section(result) if motion is None else motion),
        ),
        "warnings": ("5. Warnings", _warnings(result)),
        "slips": ("6. The paper's slips that apply", _slips(result)),
        "scenario": ("7. Scenario (inputs)", f"<pre>{escape(sc.to_toml())}</pre>"),
        "provenance": ("8. Provenance", _provenance(meta, files)),
    }
    order = list(SECTIONS)
    if plan_html is not None:
        body["plan"] = ("The plan: designs the lab can fire, best first", plan_html)
        order.insert(order.index("test_card"), "plan")
    sections = "".join(
        f'<section id="{sid}"><h2>{escape(h)}</h2>{content}</section>'
        for sid, (h, content) in ((k, body[k]) for k in order)
    )
    return (
        '<!DOCTYPE html><html lang="en"><head><meta charset="utf-8">'
        f'<meta name="viewport" content="width=device-width, initial-scale=1"><title>blastscale: {escape(title)}'
        f"</title><style>{PAGE_CSS}{_CARD_CSS}</style></head><body><header><h1>blastscale report: {escape(title)}</h1>"
        f"{_verdict(result)}"
        '<p class="muted">Reduced-scale blast experiment designed with the scaling laws of Masi, Stefanou '
        "&amp; Maffi-Berthier (general law), checked by simulating prototype and model. All values SI unless "
        "stated; model results are up-scaled to prototype units.</p></header>"
        f"<main>{sections}</main></body></html>\n"
    )
