"""``blastscale reproduce``: every table and figure of the paper that blastscale can make.

Each item (:mod:`blastscale.report.reproduce`) is written into ``OUT/<item>/`` through a
temporary folder (:mod:`blastscale.io.output`: ``OUT`` is locked against a second writer and must be
new, empty or a reproduce folder); items already done (same mode, same scenario or script) are
skipped on a second run (resumable after Ctrl-C, SIGTERM, SIGHUP). The expected time and size are
stated before the first item starts.
``OUT/report.html`` puts the paper's numbers beside blastscale's and marks the paper's slips;
``OUT/summary.json`` holds every row.
"""

from __future__ import annotations

import fnmatch
import json
from dataclasses import dataclass, field
from pathlib import Path
from typing import Optional

import typer
from rich.table import Table

from .._validate import BlastscaleInputError
from ..io.output import claim
from ..io.results import output_folder, provenance, write_atomic, write_json
from ..io.targets import Kind
from ..report.reproduce import MARKER, item_done, items, render_reproduce_report, run_item, skipped
from ..report.reproduce_cost import expected_cost, is_reproduce_folder
from ..study.memory import format_duration
from ..units import format_size
from ._app import app
from ._output import console, console_err, one_line_warnings, print_error, print_written, stage_progress
from ._signals import set_interrupt_note


@app.command("reproduce")
def reproduce_cmd(
    out: Path = typer.Option(
        ...,
        "--out",
        show_default=False,
        help="Folder for the items and report.html (created in an existing folder; reused to resume).",
    ),
    only: list[str] = typer.Option(
        [],
        "--only",
        metavar="NAME",
        show_default=False,
        help="Only these items (repeatable; shell patterns such as 'scenario-*').",
    ),
    quick: bool = typer.Option(
        False,
        "--quick",
        help="Shortened runs (0.2 s scenarios, quick gallery): a smoke test of every item, not the paper's numbers.",
    ),
    list_items: bool = typer.Option(False, "--list", help="List the items and exit."),
    examples: Optional[Path] = typer.Option(
        None, "--examples", help="Folder of the gallery scripts (default: examples/ of a source checkout)."
    ),
) -> None:
    """Reproduce the paper's tables and figures; the report puts the paper's numbers beside ours."""

    every = items(examples)
    left_out = skipped(examples)
    if list_items:
        _list(every, left_out)
        return
    chosen = _chosen(every, only)
    kind = Kind("a blastscale reproduce folder (no item.json nor reproduce summary.json)", is_reproduce_folder)
    with claim(out, kind, reuse=lambda p: not any(p.iterdir()) or is_reproduce_folder(p)) as c:
        folder, created = c.path, not c.path.exists()
        todo = [it for it in chosen if not item_done(it, folder, quick)]
        _announce(todo, chosen, quick)
        if created:
            folder.mkdir()
        set_interrupt_note(lambda: _kept(folder, every, created))
        made = _make(chosen, todo, folder, quick, created)
        infos = _write_report(folder, every)
    _print_made(out, chosen, made, len(infos))
    for why in left_out:
        console_err.print(f"skipped: {why}")
    if made.failures:
        for f in made.failures:
            print_error(f)
        raise typer.Exit(1)


def _list(every, left_out) -> None:
    """``--list``: each item's name and title; the items this installation cannot make, on stderr."""
    for it in every:
        console.print(f"{it.name:45s} {it.title}")
    for why in left_out:
        console_err.print(f"skipped: {why}")


def _chosen(every, only: list[str]) -> list:
    """The items ``--only``'s shell patterns name (all without ``--only``); none is an error."""
    chosen = [it for it in every if not only or any(fnmatch.fnmatch(it.name, pat) for pat in only)]
    if not chosen:
        raise BlastscaleInputError(
            f"only = {' '.join(only)!r} matches no item: valid names are {', '.join(it.name for it in every)}"
        )
    return chosen


def _announce(todo: list, chosen: list, quick: bool) -> None:
    """One line on stderr: how many items are left to make, their expected time and size."""
    secs, size = expected_cost(todo, quick)
    console_err.print(
        f"reproduce: {len(todo)} of {len(chosen)} items to make"
        + (
            f", about {format_duration(secs)} and {format_size(size)} on this kind of machine"
            if todo
            else " (every one is done)"
        )
        + (
            ""
            if quick or not todo
            else f"; --quick makes every item in about {format_duration(expected_cost(todo, True)[0])} (a smoke test)"
        ),
        soft_wrap=True,
    )


@dataclass
class _Made:
    """Each chosen item's status (done in, skipped, FAILED) and the failures' one-line reasons."""

    status: dict[str, str] = field(default_factory=dict)
    failures: list[str] = field(default_factory=list)


def _make(chosen: list, todo: list, folder: Path, quick: bool, created: bool) -> _Made:
    """Make the items ``todo`` of ``chosen`` into ``folder``, one progress stage each; a failed item is
    recorded and the next one made. An interrupt before any item removes a folder this run created."""
    made = _Made()
    try:
        with one_line_warnings(), stage_progress() as tell:
            for i, it in enumerate(chosen):
                tell(f"{it.name}", i, len(chosen))
                if it not in todo:
                    made.status[it.name] = "skipped (done)"
                    continue
                try:
                    info = run_item(it, folder, quick, output_folder)
                    made.status[it.name] = f"done in {info['wall_time_s']:.1f} s"
                except (BlastscaleInputError, RuntimeError, OSError) as exc:
                    made.status[it.name] = "FAILED"
                    made.failures.append(f"{it.name}: {' '.join(str(exc).split())}")
            tell("report", len(chosen), len(chosen))
    except BaseException:
        if created and not any(folder.iterdir()):
            folder.rmdir()  # interrupted before any item: nothing left behind
        raise
    return made


def _write_report(folder: Path, every) -> list[dict]:
    """report.html and summary.json over every item done so far (chosen now or before); their item records."""
    infos = []
    for it in every:  # the report covers every item done so far, chosen now or before
        marker = folder / it.name / MARKER
        if marker.is_file():
            infos.append(json.loads(marker.read_text()))
    meta = provenance()
    write_atomic(folder / "report.html", render_reproduce_report(folder, infos, meta))
    write_json(folder / "summary.json", {**meta, "items": infos})
    return infos


def _print_made(out: Path, chosen: list, made: _Made, n_items: int) -> None:
    """The status table of the chosen items and the folder written."""
    t = Table(title=f"blastscale reproduce -> {out}", title_justify="left")
    t.add_column("item")
    t.add_column("status")
    for it in chosen:
        t.add_row(it.name, made.status[it.name])
    console.print(t)
    print_written(out, f"report.html, {n_items} items")


def _kept(folder: Path, every, created: bool) -> str:
    """What an interrupted reproduce leaves: the items done (resumable), or nothing."""

    done = sum(1 for it in every if (folder / it.name / MARKER).is_file())
    if not done:
        return "no partial results left"
    return f"{done} finished items kept in {folder} (the partial one removed): run the same command again to resume"
