"""The result folder of ``blastscale plan --out``: the plan and the best design's study with its
test card (:func:`write_plan`), and the plan's section of the report."""

from __future__ import annotations

import io
from pathlib import Path

from ..analysis.intervals import probability_text
from ..io.results import jsonable, write_atomic, write_json
from ..planning.card import study_test_card
from ..plots.plan import plot_plan
from . import write_study
from .markup import charge_text, escape, figure_html, html_table

__all__ = ["write_plan", "plan_section", "error_cells", "verdict_cell", "first_design_label"]


def error_cells(d: dict) -> tuple:
    """The two error cells of a design's row, never one mixed column: the screening error (closed form, no
    simulation: ``screening_error``) and the simulated error labelled by its engine (``predicted_first_peak_error``,
    ``simulated_by`` planar or 3D; "-" for a design screened only)."""
    scr = d.get("screening_error")
    sim = d.get("predicted_first_peak_error") if d.get("simulated_by") else None
    return (
        "-" if scr is None else f"{100 * scr:.2g} %",
        "-" if sim is None else f"{100 * sim:.2g} % ({'3D' if d['simulated_by'] == '3d' else 'planar'})",
    )


def verdict_cell(d: dict) -> str:
    """A design's verdict in a cell: ``similar``, ``NOT (ratio 1.8)`` (its worst quantity's error / tolerance),
    ``not established``, or ``-`` (not judged)."""
    v = d.get("verdict")
    if v is None:
        return "-"
    if v["similar"] is None:
        return "not established"
    r = None if v["worst"] is None else v["worst"]["ratio"]
    if v["similar"]:
        return "similar" if r is None else f"similar ({r:.2g})"
    return "NOT" if r is None else f"NOT ({r:.2g})"


def first_design_label(p) -> str:
    """``Recommended design`` when the criterion passes the plan's first design, else ``Closest design (not
    recommended)``."""
    return "Recommended design" if p.recommendation.get("design") == 0 else "Closest design (not recommended)"


def plan_section(p, top: int = 15) -> str:
    """The plan as HTML: the feasible designs (best first, with the reasons of the best) and the
    rejected candidates with their reasons."""

    rows = [
        (
            str(i),
            d["law"],
            d["scale_fraction"],
            d["material"],
            charge_text(d),
            f"{d['standoff_m'] * 1e3:.4g} mm",
            f"{d['specimen_height_m'] * 1e3:.4g} mm",
            f"{d['safety_radius_m']:.3g} m",
            verdict_cell(d),
            "-"
            if d["p_outcome_agree"] is None
            else f"{probability_text(d['p_outcome_agree'])} ({probability_text(d['p_outcome_agree_low'])}-"
            f"{probability_text(d['p_outcome_agree_high'])})",
            *error_cells(d),
            {True: "yes", False: "", None: "-"}[d.get("pareto")],
        )
        for i, d in enumerate(p.designs[:top], 1)
    ]
    best = p.designs[0]
    rej = [(r["law"], r["scale_fraction"], r["material"], "; ".join(r["reasons"])) for r in p.rejected]
    return (
        f'<p class="lead"><b>{escape(p.recommendation.get("line", ""))}</b></p>'
        f'<p class="lead">{first_design_label(p)}: {escape(best["law"])} law, lambda = '
        f"{escape(best['scale_fraction'])}, {escape(best['material'])}. "
        + " ".join(escape(r) + "." for r in best["reasons"])
        + (f" Assumed {escape(p.prototype['load_assumed'])}." if p.prototype.get("load_assumed") else "")
        + "</p>"
        + html_table(
            (
                "#",
                "law",
                "lambda",
                "material",
                "charge",
                "stand-off",
                "specimen height",
                "safety radius",
                "verdict (worst ratio)",
                "P(outcome agrees) (95 %)",
                "screened error",
                "simulated error",
                "Pareto",
            ),
            rows,
            numeric_from=99,
        )
        + f"<details><summary>{len(rej)} rejected candidates and why</summary>"
        + html_table(("law", "lambda", "material", "reasons"), rej, numeric_from=99)
        + "</details>"
    )


def write_plan(p, result, folder) -> list[str]:
    """Write ``plan.json``, the best design's study (:func:`~blastscale.report.write_study`: summary.json
    with its ``test_card``, histories, figures, scenario.toml) and ``report.html`` with the plan's section
    into ``folder`` (which must exist). Returns the file names."""

    folder = Path(folder)
    png = plan_figure(p)
    # the card carries the best design's 3D odds the plan ran (none on the planar path without lab.ensemble_3d)
    if result.scenario.lab is not None and result.design is not None:
        result.view("test_card", lambda r: study_test_card(r, odds_3d=p.designs[0].get("odds_3d")))
    files = write_study(
        result,
        folder,
        plan_html=plan_section(p)
        + figure_html(
            png,
            "The plan's candidates",
            "Scale against the specimen's charge, one panel per material; feasible designs coloured by the odds "
            "that the outcome agrees (hollow: screened only; equal odds written in the legend), rejected ones grey "
            "by their first reason, the Pareto-optimal designs ringed, the first starred behind its marker "
            "(recommended, or the closest when the criterion passes none)",
            "plan_candidates",
        ),
    )
    write_atomic(folder / "plan_candidates.png", png)
    write_json(folder / "plan.json", jsonable(p.to_dict()))
    return ["plan.json", "plan_candidates.png"] + files


def plan_figure(p) -> bytes:
    """The plan's candidates (:func:`~blastscale.plots.plan.plot_plan`) as PNG bytes."""

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig = plot_plan(p)
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=110)
    plt.close(fig)
    return buf.getvalue()
