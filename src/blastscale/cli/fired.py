"""``blastscale fired``: the shot as fired, from the lab's records to what the monument would do.

``blastscale fired SCENARIO.toml [--out DIR] [--json]`` reads the scenario's ``[fired]`` table (gauge traces,
marker tracks, the charge as weighed, the stand-off as measured; docs/fired.md), fits the gauges, finds the
effective charge, re-simulates the specimen under the designed load and under the load as fired (through the
Study), up-scales the measured response and prints the as-fired line and the similarity verdict (the prototype
under the design's event against the specimen as fired, by the one criterion: docs/verdict.md). ``--out DIR`` writes ``summary.json``
(key ``as_fired``), ``scenario.toml``, the figures and ``report.html`` into a new folder, all at once (a run
interrupted or refused leaves nothing). A bad record: one line naming the file, the column and the row, exit
status 2, nothing written.
"""

from __future__ import annotations

from pathlib import Path

import typer

from ..io.results import check_output_folder, output_folder
from ..scenario.files import load_scenario
from ._app import app
from ._output import console, fmt_value, one_line_warnings, print_json, print_written, stage_progress, styled, table
from ._signals import ignore_interrupts, raise_if_interrupted


def _print(s: dict) -> None:
    console.print(styled(("As fired", "bold"), ": " + s["verdict"].removeprefix("As fired: ")))
    console.print(styled((s["similarity_verdict"]["line"], "bold")), soft_wrap=True)  # the specimen as fired
    rows = [
        ("effective charge (impulse)", fmt_value(s["effective_charge_tnt_kg"]), "kg TNT"),
        ("effective charge (peak)", fmt_value(s["effective_charge_from_pressure_tnt_kg"]), "kg TNT"),
        ("designed charge", fmt_value(s["designed_charge_tnt_kg"]), "kg TNT"),
        ("TNT equivalence (impulse)", fmt_value(s["tnt_equivalence_impulse"], ".3g"), "-"),
        ("stand-off (as measured)", fmt_value(s["standoff_m"]), "m"),
    ]
    for name, g in s["gauges"].items():
        rows += [
            (
                f"gauge {name}: peak / predicted",
                (f"{fmt_value(g['peak_pressure_Pa'])} / {fmt_value(g['predicted_peak_pressure_Pa'])}"),
                "Pa",
            ),
            (
                f"gauge {name}: impulse / predicted",
                (f"{fmt_value(g['impulse_Pa_s'])} / {fmt_value(g['predicted_impulse_Pa_s'])}"),
                "Pa s",
            ),
        ]
    for name, m in s["markers"].items():
        rows += [
            (
                f"marker {name}: first peak measured / predicted / refit",
                (
                    f"{fmt_value(m['first_peak_m'])} / {fmt_value(m['predicted_first_peak_m'])} / "
                    f"{fmt_value(m['refit_first_peak_m'])}"
                ),
                "m",
            ),
            (f"marker {name}: outcome measured / refit", f"{m['outcome_measured'] or '-'} / {m['outcome_refit']}", ""),
        ]
    for name, p in s["prototype_markers"].items():
        rows.append(
            (
                f"monument {name} under the shot's event: first peak (5-95 %)",
                (
                    f"{fmt_value(p['first_peak_m'], '.4g')} ("
                    f"{fmt_value(p['first_peak_p05_m'], '.3g')}-{fmt_value(p['first_peak_p95_m'], '.3g')})"
                ),
                "m",
            )
        )
    ev = s.get("designed_event") or {}
    if ev.get("markers"):
        rows.append(
            (
                "similar prototype charge (the shot's event)",
                f"{fmt_value(s['similar_prototype_charge_tnt_kg'], '.4g')} at {fmt_value(s['similar_prototype_standoff_m'])}",
                "kg TNT, m",
            )
        )
    for name, e in (ev.get("markers") or {}).items():
        rows.append(
            (
                f"monument {name} under the designed {fmt_value(ev['charge_tnt_kg'], '.4g')} kg: first peak (5-95 %)",
                (
                    f"{fmt_value(e['first_peak_m'], '.4g')} ("
                    f"{fmt_value(e['first_peak_p05_m'], '.3g')}-{fmt_value(e['first_peak_p95_m'], '.3g')})"
                ),
                "m",
            )
        )
        if e["residual_displacement_m"] is not None:
            rows.append(
                (
                    f"monument {name} under the designed event: residual displacement (5-95 %)",
                    (
                        f"{fmt_value(e['residual_displacement_m'], '.4g')} ("
                        f"{fmt_value(e['residual_displacement_p05_m'], '.3g')}-"
                        f"{fmt_value(e['residual_displacement_p95_m'], '.3g')})"
                    ),
                    "m",
                )
            )
    c = s.get("calibration")
    if c is not None and "restitution" in c:
        rows.append(("calibrated restitution", c["line"], "-"))
        if c["identifiable"]:
            rows.append(
                (
                    "prototype with it: max rotation, outcome",
                    f"{fmt_value(c['prototype_max_rotation_rad'])}, {c['prototype_outcome']}",
                    "rad",
                )
            )
    if c is not None and "friction" in c:
        rows.append(("calibrated friction", c["line"], "-"))
        if c["identifiable"]:
            rows.append(("prototype with it: outcome", c["prototype_outcome"], ""))
    console.print(table("The shot as fired", rows))


#: Shipped examples: name -> file in blastscale/fired/examples (docs/fired.md).
EXAMPLES = {"example_shot": "shot.toml"}


def _shipped(path: Path) -> Path:
    """``path`` itself, or the shipped example it names when no such file exists."""
    if not path.exists() and str(path) in EXAMPLES:
        from importlib.resources import files

        return Path(str(files("blastscale.fired") / "examples" / EXAMPLES[str(path)]))
    return path


@app.command("fired")
def fired_cmd(
    scenario: Path = typer.Argument(
        ...,
        metavar="SCENARIO.toml",
        show_default=False,
        help="Scenario file with a \\[fired] table (docs/fired.md), or example_shot (the shipped example).",
    ),
    out: Path | None = typer.Option(
        None,
        "--out",
        show_default=False,
        help="Write summary.json (as_fired), scenario.toml, the figures and report.html into this new folder.",
    ),
    as_json: bool = typer.Option(False, "--json", help="Print the as_fired summary as one JSON object."),
    force: bool = typer.Option(False, "--force", help="Replace an existing result folder."),
    calibrate: str = typer.Option(
        "",
        "--calibrate",
        show_default=False,
        help="Contact parameters to fit to the measured response, comma-separated: "
        "restitution (a block), friction (every other kind, 3D).",
    ),
) -> None:
    """After the shot: the load the specimen got, measured vs predicted vs re-simulated, and what the monument
    would do."""
    from ..fired.inputs import shot_inputs
    from ..fired.shot import as_fired

    sc = load_scenario(_shipped(scenario))
    markers = ("summary.json",)
    if out is not None:
        check_output_folder(out, force, markers)
    written = None
    with one_line_warnings(), stage_progress(quiet=as_json) as tell:
        tell("records, gauge fits, prediction and refit", 0, 1)
        # the shot's geometry and every record checked before the engines are imported (a bad value is refused
        # at once) and before the folder is claimed (a bad one writes nothing)
        inputs = shot_inputs(sc)
        from ..fired.shot import as_fired

        result = as_fired(sc, gauges=inputs.gauges, tracks=inputs.tracks, calibrate=calibrate.split(","))
        if out is not None:
            from ..report.fired import write_fired

            with output_folder(
                out, force, before_commit=raise_if_interrupted, after_commit=ignore_interrupts, markers=markers
            ) as tmp:
                written = write_fired(result, sc, tmp)
    if as_json:
        print_json({"as_fired": result.summary})
    else:
        _print(result.summary)
    if written is not None:
        print_written(out, ", ".join(written))
