"""``blastscale plan``: the designs a lab can fire for a scenario's prototype, best first.

``blastscale plan SCENARIO.toml [--json] [--out DIR] [--workers N | --scheduler ADDR]`` reads the prototype
(any structure kind) and the ``[lab]`` table (every key optional, docs/planning.md), searches lambda, gamma
(the lab's materials), the law and the specimen's burst (:func:`blastscale.planning.plan`: a block on the
planar kernels; any other structure screened, then its best designs in 3D with an ensemble each), and
prints the feasible designs ranked by trustworthiness then safety, the Pareto-optimal ones marked, with the
reasons of the rejected ones; ``--out`` also writes ``plan_candidates.png``. ``--out DIR`` also runs the best design's Study and
writes ``plan.json``, ``summary.json`` (with its ``test_card``), ``scenario.toml`` (the best design:
``blastscale run`` reproduces its card) and ``report.html`` (the plan and the printable test card).
A lab no design fits: one line naming the constraint and what would relax it, exit status 2.
"""

from __future__ import annotations

import warnings
from pathlib import Path
from typing import Optional

import typer
from rich.table import Table

from ..analysis.intervals import probability_text
from ..io.results import check_output_folder, output_folder
from ..planning.odds import outcome_odds_text
from ..planning.plan3d import ensemble_members
from ..planning.planner import plan
from ..report.markup import charge_text, format_charge
from ..report.plan_files import error_cells, first_design_label, verdict_cell
from ..scenario.files import load_scenario
from ..scenario.lab import LabSpec
from ..scenario.scenario import Scenario
from ..structures import from_spec
from ._app import app
from ._output import console, one_line_warnings, print_json, print_written, stage_progress, styled
from ._signals import ignore_interrupts, raise_if_interrupted

#: Columns whose cells are short (a number and its unit, on two lines at most), held narrow so that, at 160
#: columns, rich's even shrinking of the widest columns leaves the odds' interval ("1.00 (0.998-1.00)") whole.
_NARROW = {"specimen": 8, "safety radius": 7, "screened error": 8, "simulated error": 9}


def _print_plan(p, top: int) -> None:

    t = Table(
        title=f"Feasible designs, best first ({len(p.designs)}; {len(p.rejected)} rejected; "
        f"{p.prototype['load_assumed']})",
        title_justify="left",
    )
    for c in (
        "#",
        "law",
        "lambda",
        "material",
        "charge",
        "stand-off",
        "specimen",
        "safety radius",
        "camera",
        "verdict",
        "P(outcome agrees) (95 %)",
        "screened error",
        "simulated error",
        "Pareto",
    ):
        t.add_column(c, justify="left" if c in ("law", "material") else "right", max_width=_NARROW.get(c))
    for i, d in enumerate(p.designs[:top], 1):
        stand = f" on a {d['charge_height_m'] * 100:.3g} cm stand" if d.get("charge_height_m") else ""
        t.add_row(
            str(i),
            d["law"],
            d["scale_fraction"],
            d["material"],
            f"{charge_text(d)}{stand}",
            f"{d['standoff_m'] * 100:.3g} cm",
            f"{d['specimen_height_m'] * 100:.3g} cm, {d['specimen_mass_kg']:.3g} kg",
            f"{d['safety_radius_m']:.3g} m",
            f"{d['camera_fps']:g}/s",
            verdict_cell(d),
            "-"
            if d["p_outcome_agree"] is None
            else f"{probability_text(d['p_outcome_agree'])} ({probability_text(d['p_outcome_agree_low'])}-"
            f"{probability_text(d['p_outcome_agree_high'])})",
            *error_cells(d),
            {True: "yes", False: "", None: "-"}[d["pareto"]],
        )
    console.print(t)
    b = p.designs[0]
    stand = (
        f", on a stand {b['charge_height_m'] * 100:.3g} cm high ({b['burst']} burst)"
        if b.get("charge_height_m")
        else ""
    )
    console.print(styled((p.recommendation["line"], "bold")))
    console.print(
        styled(
            (f"{first_design_label(p)}:", "bold"),
            f" {b['law']} law, lambda = {b['scale_fraction']}, {b['material']}: "
            f"{charge_text(b)} at {b['standoff_m'] * 100:.3g} cm"
            f"{stand}",
        )
    )
    for r in b["reasons"]:
        console.print(f"  - {r}")
    if b.get("source"):
        src = b["source"]
        console.print(
            f"  - fireable: {src['control']} {src['control_value']:.4g} {src['control_unit']} within the source's "
            f"limits {src['control_min']:.4g}-{src['control_max']:.4g} {src['control_unit']}; one shot's scatter "
            f"{100 * src['sigma_ln_impulse']:.2g} % (repeatability and fit, in place of charge_tolerance)"
        )
    else:
        console.print(
            f"  - fireable: above {b['explosive']}'s minimum reliable charge "
            f"{format_charge(b['explosive_min_charge_kg'])}; initiator {format_charge(b['initiator_tnt_kg'])} TNT, "
            f"{100 * b['initiator_fraction']:.3g} % of the charge's impulse (at most "
            f"{100 * p.lab['initiator_max_fraction']:g} %)"
        )
    o3 = b.get("odds_3d")
    if o3:
        console.print(
            f"  - 3D ensemble: {o3['members']} members, outcome agrees: {outcome_odds_text(o3)}, "
            f"largest top displacement 5-95 %: "
            f"{1e3 * o3['top_displacement_p05_m']:.3g}-{1e3 * o3['top_displacement_p95_m']:.3g} mm"
        )
    for w in b.get("warnings", []):
        console.print(f"  - warning: {w}")
    reasons: dict = {}
    for r in p.rejected:
        for key in r["constraints"]:
            reasons[key] = reasons.get(key, 0) + 1
    if reasons:
        console.print(
            "rejected candidates, by the constraint they break: "
            + ", ".join(f"{k} {n}" for k, n in sorted(reasons.items(), key=lambda kv: -kv[1]))
        )


@app.command("plan")
def plan_cmd(
    scenario: Optional[Path] = typer.Argument(
        None,
        metavar="SCENARIO.toml",
        show_default=False,
        help="Scenario file with the prototype and a \\[lab] table (docs/planning.md). Default: the built-in "
        "scenario and every \\[lab] default.",
    ),
    as_json: bool = typer.Option(False, "--json", help="Print the plan as one JSON object instead of tables."),
    out: Optional[Path] = typer.Option(
        None,
        "--out",
        show_default=False,
        help="Also run the best design and write plan.json, summary.json (test card), "
        "scenario.toml and report.html into this new folder.",
    ),
    force: bool = typer.Option(False, "--force", help="Replace an existing result folder."),
    top: int = typer.Option(10, "--top", min=1, help="Designs shown in the table."),
    workers: int = typer.Option(
        0,
        "--workers",
        min=0,
        help="Local Dask workers of the 3D ensembles (lab.ensemble_3d; 0: native threads in this process).",
    ),
    scheduler: Optional[str] = typer.Option(
        None, "--scheduler", show_default=False, help="Address of a running Dask scheduler for the 3D ensemble."
    ),
) -> None:
    """Plan a lab test: the designs the lab can fire safely, with the charge, the safety zone, the instruments
    and the odds."""

    with one_line_warnings():  # e.g. a [lab.explosives] table that redefines a library explosive
        sc = Scenario.default() if scenario is None else load_scenario(scenario)

    members = ensemble_members(sc, from_spec(sc.structure), sc.lab or LabSpec())
    unused = [
        f"{flag} {v}"
        for flag, v, given in (("--scheduler", scheduler, scheduler is not None), ("--workers", workers, workers > 0))
        if given
    ]
    if unused and not members:
        with one_line_warnings():
            warnings.warn(
                f"{' and '.join(unused)} not used: the plan runs on Dask only for its 3D ensemble, and "
                f"lab.ensemble_3d = {members} (give it a number of members to use them)",
                stacklevel=1,
            )
    markers = ("plan.json", "summary.json")
    if out is not None:
        check_output_folder(out, force, markers)
    written = None
    with one_line_warnings(), stage_progress(quiet=as_json) as tell:
        if out is None:
            p = plan(sc, workers=workers, scheduler=scheduler, progress=tell)
        else:  # the folder claimed (checked, locked) before any work: a second writer is refused at once
            from ..report.plan_files import write_plan
            from ..study.study import Study

            with output_folder(
                out, force, before_commit=raise_if_interrupted, after_commit=ignore_interrupts, markers=markers
            ) as tmp:
                p = plan(sc, workers=workers, scheduler=scheduler, progress=tell)
                if p.best_result is not None:  # the Study that judged it: the report's verdict is the plan's
                    result = p.best_result
                else:
                    tell("the best design's study", 0, 1)
                    result = Study(p.best_scenario).run()
                written = write_plan(p, result, tmp)
    if as_json:
        print_json(p.to_dict())
    else:
        _print_plan(p, top)
    if written is not None:
        print_written(out, ", ".join(written))
