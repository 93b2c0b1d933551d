"""The result folder of ``blastscale plan --out``: the plan and the best design's study with its
test card (:func:`write_plan`), and the plan's section of the report."""

from __future__ import annotations

import html
from pathlib import Path

__all__ = ["write_plan", "plan_section"]


def _e(x) -> str:
    return html.escape(str(x), quote=True)


def plan_section(p, top: int = 15) -> str:
    """The plan as HTML: the feasible designs (best first, with the reasons of the best) and the
    rejected candidates with their reasons."""
    from .html import _table, format_charge

    rows = [
        (
            str(i),
            d["law"],
            d["scale_fraction"],
            d["material"],
            f"{format_charge(d['explosive_mass_kg'])} {d['explosive']}",
            f"{d['standoff_m'] * 1e3:.4g} mm",
            f"{d['specimen_height_m'] * 1e3:.4g} mm",
            f"{d['safety_radius_m']:.3g} m",
            f"{d['p_outcome_agree']:.3f}",
            f"{100 * d['predicted_first_peak_error']:.2g} %",
        )
        for i, d in enumerate(p.designs[:top], 1)
    ]
    best = p.designs[0]
    rej = [(r["law"], r["scale_fraction"], r["material"], "; ".join(r["reasons"])) for r in p.rejected]
    return (
        f'<p class="lead">Best design: {_e(best["law"])} law, lambda = {_e(best["scale_fraction"])}, '
        f"{_e(best['material'])}. "
        + " ".join(_e(r) + "." for r in best["reasons"])
        + "</p>"
        + _table(
            (
                "#",
                "law",
                "lambda",
                "material",
                "charge",
                "stand-off",
                "specimen height",
                "safety radius",
                "P(outcome agrees)",
                "first-peak error",
            ),
            rows,
            numeric_from=99,
        )
        + f"<details><summary>{len(rej)} rejected candidates and why</summary>"
        + _table(("law", "lambda", "material", "reasons"), rej, numeric_from=99)
        + "</details>"
    )


def write_plan(p, result, folder) -> list[str]:
    """Write ``plan.json``, the best design's study (:func:`~blastscale.report.write_study`: summary.json
    with its ``test_card``, histories, figures, scenario.toml) and ``report.html`` with the plan's section
    into ``folder`` (which must exist). Returns the file names."""
    from ..io.results import jsonable, write_json
    from . import write_study

    folder = Path(folder)
    files = write_study(result, folder, plan_html=plan_section(p))
    write_json(folder / "plan.json", jsonable(p.to_dict()))
    return ["plan.json"] + files
