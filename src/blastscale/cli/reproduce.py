"""``blastscale reproduce``: every table and figure of the paper that blastscale can make.

Each item (:mod:`blastscale.report.reproduce`) is written into ``OUT/<item>/`` through a
temporary folder; items already done (same mode, same scenario or script) are skipped on a
second run (resumable after Ctrl-C).
``OUT/report.html`` puts the paper's numbers beside blastscale's and marks the paper's slips;
``OUT/summary.json`` holds every row.
"""

from __future__ import annotations

import fnmatch
from pathlib import Path
from typing import Optional

import typer
from rich.table import Table

from .._validate import BlastscaleInputError
from ._app import app, console, console_err, one_line_warnings, stage_progress


@app.command("reproduce")
def reproduce_cmd(
    out: Path = typer.Option(..., "--out", show_default=False,
                             help="Folder for the items and report.html (created; reused to resume)."),
    only: list[str] = typer.Option([], "--only", metavar="NAME", show_default=False,
                                   help="Only these items (repeatable; shell patterns such as 'scenario-*')."),
    quick: bool = typer.Option(False, "--quick", help="Shortened runs (0.2 s scenarios, quick gallery): a smoke "
                                                      "test of every item, not the paper's numbers."),
    list_items: bool = typer.Option(False, "--list", help="List the items and exit."),
    examples: Optional[Path] = typer.Option(None, "--examples", help="Folder of the gallery scripts (default: "
                                                                      "examples/ of a source checkout)."),
) -> None:
    """Reproduce the paper's tables and figures; the report puts the paper's numbers beside ours."""
    from ..io.results import output_folder, provenance, write_atomic, write_json
    from ..report.reproduce import MARKER, item_done, items, render_reproduce_report, run_item, skipped

    every = items(examples)
    left_out = skipped(examples)
    if list_items:
        for it in every:
            console.print(f"{it.name:45s} {it.title}", highlight=False)
        for why in left_out:
            console_err.print(f"skipped: {why}", highlight=False)
        return
    chosen = [it for it in every if not only or any(fnmatch.fnmatch(it.name, pat) for pat in only)]
    if not chosen:
        raise BlastscaleInputError(f"only = {' '.join(only)!r} matches no item: valid names are "
                                   f"{', '.join(it.name for it in every)}")
    out = out.expanduser()
    if out.exists() and not out.is_dir():
        raise BlastscaleInputError(f"out = {str(out)!r} is a file, not a folder: give the path of a folder")
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise BlastscaleInputError(f"out = {str(out)!r} cannot be created: {exc.strerror or exc}") from None
    status: dict[str, str] = {}
    failures: list[str] = []
    with one_line_warnings(), stage_progress() as tell:
        for i, it in enumerate(chosen):
            tell(f"{it.name}", i, len(chosen))
            if item_done(it, out, quick):
                status[it.name] = "skipped (done)"
                continue
            try:
                info = run_item(it, out, quick, output_folder)
                status[it.name] = f"done in {info['wall_time_s']:.1f} s"
            except (BlastscaleInputError, RuntimeError, OSError) as exc:
                status[it.name] = "FAILED"
                failures.append(f"{it.name}: {' '.join(str(exc).split())}")
        tell("report", len(chosen), len(chosen))
    import json

    infos = []
    for it in every:  # the report covers every item done so far, chosen now or before
        marker = out / it.name / MARKER
        if marker.is_file():
            infos.append(json.loads(marker.read_text()))
    meta = provenance()
    write_atomic(out / "report.html", render_reproduce_report(out, infos, meta))
    write_json(out / "summary.json", {**meta, "items": infos})
    t = Table(title=f"blastscale reproduce -> {out}", title_justify="left")
    t.add_column("item")
    t.add_column("status")
    for it in chosen:
        t.add_row(it.name, status[it.name])
    console.print(t)
    console_err.print(f"wrote {out / 'report.html'} ({len(infos)} items)", highlight=False)
    for why in left_out:
        console_err.print(f"skipped: {why}", highlight=False)
    if failures:
        for f in failures:
            console_err.print(f"[bold red]error:[/] {f}", highlight=False, soft_wrap=True)
        raise typer.Exit(1)
