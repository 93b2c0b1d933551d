"""``blastscale run``: one scenario file (or the built-in default) through the whole method.

``blastscale run [SCENARIO.toml] --out DIR`` loads and validates the scenario
(:mod:`blastscale.scenario`), checks everything that can be checked before simulating
(blast-fit ranges, engines, memory, the output folder), runs
:class:`blastscale.study.Study` and writes, through a temporary sibling folder renamed into
place at the end: ``summary.json``, ``histories.nc`` (``histories.csv`` with ``--csv``), the
figures, ``scenario.toml`` and a self-contained ``report.html`` (:mod:`blastscale.io.output`: a
second writer of the same folder is refused, only a blastscale result is replaced). Ctrl-C, SIGTERM
or SIGHUP at any moment leave no partial folder (exit status 130, 143, 129). Without a scenario the built-in default runs: the paper's
10 m block, 50 kg TNT at 2 m, lambda = 1/200, masi2021, friction 0.7 (so that ``make run``
reproduces the paper's model 2).
"""

from __future__ import annotations

from pathlib import Path
from typing import Optional

import typer
from rich.table import Table

from .._hooks import pause_point
from ..io.results import check_output_folder
from ..planning.odds import outcome_odds_text
from ..report import write_study
from ..report.card import card_of
from ..report.labels import label
from ..report.markup import format_charge, split_unit_for_tables
from ..study.study import Study
from ._app import app
from ._output import (
    console,
    console_err,
    fmt_value,
    one_line_warnings,
    print_json,
    print_written,
    stage_progress,
    styled,
    table,
)
from ._progress import announce_run
from .flags import SET_VALUES
from .loads import print_design
from .steps import SIMILARITY_TITLE, read_scenario, result_folder


def _compare_table(title: str, prototype: dict, model: dict) -> Table:

    t = Table(title=title, title_justify="left")
    columns = (
        ("quantity", "prototype", "unit") if model is None else ("quantity", "prototype", "model (up-scaled)", "unit")
    )
    for c in columns:
        t.add_column(c, justify="left" if c in ("quantity", "unit") else "right")
    for k, v in prototype.items():
        if isinstance(v, (dict, list, str)):
            continue
        values = (fmt_value(v),) if model is None else (fmt_value(v), fmt_value(model.get(k)))
        t.add_row(label(k), *values, split_unit_for_tables(k)[1])
    return t


def _similarity_table(sim: dict) -> Table:
    """The similarity figures of one engine, in words (the per-point figures are in the report)."""

    return table(
        SIMILARITY_TITLE,
        [
            (label(k), fmt_value(v, ".3g"), split_unit_for_tables(k)[1])
            for k, v in sim.items()
            if not isinstance(v, (dict, list))
        ],
    )


def _print_engine(title: str, engine: dict, note=None) -> None:
    """One engine's summary: its comparison table, a ``note`` under it, its similarity table (with a model)."""
    console.print(_compare_table(title, engine["prototype"], engine["model"]))
    if note is not None:
        console.print(note)
    if engine.get("similarity") is not None:
        console.print(_similarity_table(engine["similarity"]))


def _damage_words(d: dict) -> str:
    """The damage states of the prototype and of the up-scaled model in words (docs/sweeps.md, "Damage states")."""

    def one(st: dict) -> str:
        name = st["name"] if st["state"] != "damaged" else f"damaged ({st['band']})"
        drift = st["residual_drift"]
        return name + ("" if drift is None or drift != drift else f", residual drift {drift * 100:.3g} %")

    said = [f"the prototype {one(d['prototype'])}"]
    if d.get("model") is not None:
        said.append(f"the up-scaled model {one(d['model'])}")
    return "; ".join(said) + f" ({d['engine']}; limits: [damage])"


def _print_result(result) -> None:
    sc, s = result.scenario, result.summary()
    exp = s["experiment"]

    console.rule(styled(("blastscale run", "bold"), f" — {sc.title or 'scenario'}"))
    console.print(styled((s["verdict"]["line"], "bold")), soft_wrap=True)
    m = exp["model"]
    if m is None and sc.blast.gravity_only:
        console.print(styled(("Gravity alone", "bold"), " (no charge): no specimen, no comparison."))
    elif m is None:
        console.print(
            styled(("Prototype only", "bold"), " (the scenario has no [scale] table): no specimen, no comparison.")
        )
    else:
        print_design(result.design)
        console.print(
            styled(
                ("Model experiment:", "bold"),
                f" {m.get('height_m', float('nan')):.4g} m high "
                f"{sc.structure.kind}, {m.get('mass_kg', float('nan')):.4g} kg ({m['material']}), ",
                (f"{format_charge(m['charge_kg'])} TNT at {m['standoff_m']:.4g} m", "bold"),
            )
        )
    if s["planar"] is not None:
        _print_engine(f"Planar rocking ({sc.blast.pulse_shape} pulse, {sc.simulation.duration_s:g} s)", s["planar"])
    if s["critical"] is not None:
        console.print(
            styled(
                f"critical charge at {sc.blast.standoff_m:g} m (planar, {sc.blast.pulse_shape}): ",
                (f"{result.critical.charge_kg:.4g} kg", "bold"),
                f" ({result.critical.evaluations} simulations)",
            )
        )
    if s["3d"] is not None:
        r3 = s["3d"]
        stab, note = (r3.get("prototype") or {}).get("stability"), None
        if stab is not None:
            from ..report.outcomes import STABILITY_RULE, stability_words

            note = styled("under gravity alone the structure ", (stability_words(stab), "bold"), f" ({STABILITY_RULE})")
        _print_engine(f"3D rigid bodies, MuJoCo (friction {sc.structure.friction:g}, Method {sc.blast.load})", r3, note)
    if s.get("damage") is not None:
        console.print(styled(("Damage:", "bold"), " " + _damage_words(s["damage"])), soft_wrap=True)

    card = card_of(result)
    if card is not None:
        p = outcome_odds_text(card["odds"] or card["odds_3d"])
        console.print(
            styled(
                ("Test card:", "bold"),
                f" {format_charge(card['explosive_mass_kg'])} of {card['explosive']} at "
                f"{card['standoff_m'] * 1e3:.4g} mm; safety radius ({card['safety_threshold']}) "
                f"{card['safety_radius_m']:.3g} m, fragments {card['fragments']['distance_m']:.3g} m, debris zone "
                f"{card['debris_radius_m'] * 1e3:.4g} mm; camera "
                f"{card['camera_fps']:g} frames/s, gauges sampled at {card['pressure_sampling_hz']:g} Hz"
                + ("" if p == "-" else f"; outcome agrees with the prototype's: {p}")
                + " (report.html: the printable card)",
            )
        )
    # result.warnings were printed as they came, one line each (one_line_warnings)


@app.command("run")
def run_cmd(
    scenario: Optional[Path] = typer.Argument(
        None,
        metavar="SCENARIO.toml",
        show_default=False,
        help="Scenario file (TOML; docs/scenarios.md). Default: the built-in scenario, the paper's 10 m block, "
        "50 kg TNT at 2 m, lambda 1/200, masi2021, friction 0.7.",
    ),
    out: Optional[Path] = typer.Option(
        None,
        "--out",
        show_default=False,
        help="Result folder to create (summary.json, histories.nc, figures, report.html); its parent folder must "
        "exist. Refused if it exists, unless --force.",
    ),
    force: bool = typer.Option(
        False, "--force", help="Replace an existing blastscale result folder (never another folder)."
    ),
    values: list[str] = SET_VALUES,
    blast_model: Optional[str] = typer.Option(
        None,
        "--model",
        "--blast-model",
        show_default=False,
        help="Blast model, kingery-bulmash or masi2021 (default: the scenario's).",
    ),
    charge: Optional[float] = typer.Option(
        None, "--charge", show_default=False, help="Prototype charge W \\[kg] (default: the scenario's)."
    ),
    friction: Optional[float] = typer.Option(
        None, "--friction", show_default=False, help="Coulomb friction mu \\[-] (default: the scenario's)."
    ),
    duration: Optional[float] = typer.Option(
        None, "--duration", show_default=False, help="Simulated time \\[s] (default: the scenario's)."
    ),
    csv: bool = typer.Option(
        False,
        "--csv",
        help="Also write histories.csv (the histories flat, for spreadsheets; large: ~150 MB for a column).",
    ),
    as_json: bool = typer.Option(False, "--json", help="Print the summary as one JSON object instead of tables."),
) -> None:
    """Run a scenario: design the model, simulate prototype and model, compare, write a report."""

    pause_point("run:started")
    sc = read_scenario(
        scenario,
        values,
        {
            "blast.blast_model": blast_model,
            "blast.charge_kg": charge,
            "structure.friction": friction,
            "simulation.duration_s": duration,
        },
    )
    if out is not None:
        check_output_folder(out, force)  # before any simulation
    study = Study(sc)
    with one_line_warnings():
        expected = _check(study, writes=out is not None, quiet=as_json)
        result = _run(study, out, force, csv, expected, as_json)
    _answer(result, out, csv, as_json)


def _check(study, writes: bool, quiet: bool) -> float | None:
    """Everything that can be checked before any work (blast-fit and scale ranges, engines, memory, the
    ``[lab]`` table's charge), one line each; then the run's size said. Returns its expected seconds."""
    sc = study.scenario
    design = study.check().design  # blast-fit and scale ranges, engines, memory: one line before any work
    if sc.lab is not None:  # the [lab] table's charge (the initiator below it): one line before any work
        from ..planning.card import check_lab

        check_lab(design, sc.lab)
    return announce_run(study, console_err, writes=writes, quiet=quiet)  # its size, before it starts


class _RunProgress:
    """One progress bar for the study's stages and then the writing of its ``writes`` files; the test pause
    points at the first simulation and at the first write."""

    def __init__(self, tell, writes: int):
        self.tell, self.writes = tell, writes
        self.done, self.total = 0, 1

    def study(self, stage: str, done: int, total: int) -> None:
        self.done, self.total = done, total + self.writes
        self.tell(stage, done, total + self.writes)
        if done == 1:
            pause_point("run:simulating")

    def write(self, stage: str) -> None:
        self.tell(f"writing {stage}", self.done, self.total)
        if self.done == self.total - self.writes:
            pause_point("run:writing")
        self.done += 1


def _run(study, out: Optional[Path], force: bool, csv: bool, expected: float | None, quiet: bool):
    """Run the study and, with ``out``, write its result folder (histories, figures, report) through a
    partial folder renamed into place at the end."""
    writes = 3 if out is not None else 0  # histories, figures, report
    with stage_progress(quiet=quiet, expected_s=expected) as tell:
        progress = _RunProgress(tell, writes)
        if out is None:
            return study.run(progress=progress.study)
        with result_folder(out, force) as tmp:
            result = study.run(progress=progress.study)
            write_study(result, tmp, progress=progress.write, csv=csv)
    return result


def _answer(result, out: Optional[Path], csv: bool, as_json: bool) -> None:
    """The summary as one JSON object or as tables; the folder written."""
    if as_json:
        from ..report import summary_dict

        print_json(summary_dict(result))
    else:
        _print_result(result)
    if out is not None:
        print_written(
            out,
            "report.html, summary.json, histories.nc" + (", histories.csv" if csv else "") + ", scenario.toml, figures",
        )
