"""``blastscale source calibrate``: a blast source calibrated from the lab's own shots (docs/planning.md, "Sources").

``blastscale source calibrate SHOTS.toml --out SOURCE.toml [--json]`` reads the calibration set (the source and
its shots, each a gauge record at its control value and distance), reads every record as ``blastscale fired``
does, fits the TNT equivalence by impulse and by peak as a power law in the control value, tests the records'
self-similarity and writes the source file, at once (a bad input writes nothing: one line naming the key, its
value and valid range, exit status 2). ``[lab] source = "SOURCE.toml"`` then plans in the control value.
"""

from __future__ import annotations

from pathlib import Path

import typer

from .._validate import BlastscaleInputError
from ..report.markup import format_charge
from ._app import OneLineErrorGroup, app
from ._output import console, fmt_value, one_line_warnings, print_json, print_written, styled, table

source_app = typer.Typer(
    name="source",
    cls=OneLineErrorGroup,
    help="Blast sources: calibrate a lab's own source (an exploding-wire bank) from its shots.",
    no_args_is_help=True,
    add_completion=False,
    pretty_exceptions_enable=False,
)
app.add_typer(source_app, name="source")

#: Shipped examples: name -> the calibration set in blastscale/fired/examples (docs/planning.md, "Sources").
EXAMPLES = {"example_source": "wires/shots.toml"}


def _shipped(path: Path) -> Path:
    """``path`` itself, or the shipped example it names when no such file exists."""
    if not path.exists() and str(path) in EXAMPLES:
        from importlib.resources import files

        return Path(str(files("blastscale.fired") / "examples" / EXAMPLES[str(path)]))
    return path


def _print(s: dict) -> None:
    src = s["source"]
    unit = src["control_unit"]
    synthetic = " (SYNTHETIC: not a real source)" if src["synthetic"] else ""
    console.print(styled((f"Source {src['name']!r}{synthetic}", "bold")))
    console.print(styled((s["self_similarity"]["line"], "bold")), soft_wrap=True)
    rows = [
        ("shots", str(src["shots"]), "-"),
        (
            "calibrated control",
            f"{fmt_value(src['calibrated_control'][0], '.4g')}-{fmt_value(src['calibrated_control'][1], '.4g')}",
            unit,
        ),
        ("limits", f"{fmt_value(src['control_min'], '.4g')}-{fmt_value(src['control_max'], '.4g')}", unit),
    ]
    for basis, law in s["equivalence"].items():
        rows.append(
            (
                f"by {basis}: W = W_ref (x / {fmt_value(law['reference'], '.4g')} {unit})^k",
                f"W_ref {format_charge(law['tnt_kg_at_reference'])}, k {law['exponent']:.4g} "
                f"+- {law['ci95_exponent']:.2g}, repeatability {100 * law['repeatability']:.2g} %",
                "TNT",
            )
        )
        for a in law["at_control"]:
            lo, hi = a["ci95_tnt_kg"]
            rows.append(
                (
                    f"  at {fmt_value(a['control'], '.4g')} {unit}",
                    f"{format_charge(a['tnt_kg'])} ({format_charge(lo)}-{format_charge(hi)})",
                    "TNT (95 % band)",
                )
            )
    console.print(table("The source's TNT equivalence", rows))


@source_app.command("calibrate")
def calibrate_cmd(
    shots: Path = typer.Argument(
        ...,
        metavar="SHOTS.toml",
        show_default=False,
        help="Calibration set: [source] and its [[shot]] tables (docs/planning.md, 'Sources'), or example_source "
        "(the shipped synthetic set).",
    ),
    out: Path | None = typer.Option(
        None, "--out", show_default=False, help='Write the source file (TOML) here: [lab] source = "SOURCE.toml".'
    ),
    as_json: bool = typer.Option(False, "--json", help="Print the source_calibration summary as one JSON object."),
    force: bool = typer.Option(False, "--force", help="Replace an existing source file."),
) -> None:
    """Fit a source's TNT equivalence (by impulse and by peak) as a power law in its control value."""
    from ..fired.source_calibration import calibrate_source, read_calibration_set
    from ..io.source_file import write_source

    if out is not None and out.exists() and not force:
        raise BlastscaleInputError(f"--out = {str(out)!r} exists: give --force to replace it, or another path")
    if out is not None and not out.parent.is_dir():
        raise BlastscaleInputError(f"--out = {str(out)!r}: its folder {str(out.parent)!r} does not exist")
    with one_line_warnings():
        result = calibrate_source(read_calibration_set(_shipped(shots)))
    summary = result.summary()
    if out is not None:
        write_source(out, result.source)
    if as_json:
        print_json({"source_calibration": summary})
    else:
        _print(summary)
        for w in summary["warnings"]:
            console.print(f"warning: {w}", soft_wrap=True)
    if out is not None:
        print_written(out)
