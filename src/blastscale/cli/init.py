"""``blastscale init``: start a scenario file from a commented template or from a shipped scenario.

``blastscale init [--kind block|column|wall|arch|portal|assembly] [--from NAME] FILE.toml`` writes FILE.toml
(through :mod:`blastscale.io.output`: the folder must exist; an existing file is replaced only with ``--force``,
and only when blastscale wrote it: a template's header, or a scenario blastscale reads), checks that it loads,
and says how to run it. ``--kind assembly`` also writes an example block model, ``FILE_blocks.json``, beside it
(an existing one is kept and named). ``--kind`` with ``--from`` must name the shipped scenario's own kind.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Optional

import typer

from .._validate import BlastscaleInputError
from ..io.output import claim, write_file
from ..io.targets import Kind, check_target
from ..scenario.files import load_scenario
from ..scenario.library import EXAMPLE_BLOCKS, library_names, library_text, template_text
from ._app import app
from ._output import console, console_err, print_written

#: The first words of every template ``init`` writes.
HEADER = "# A blastscale scenario"


def _is_ours(path: Path) -> bool:
    """Whether ``path`` is a file blastscale wrote: a template's header, or a scenario blastscale reads."""

    try:
        with open(path, "rb") as f:
            if f.read(len(HEADER.encode())) == HEADER.encode():
                return True
        load_scenario(path)
        return True
    except (OSError, ValueError, RecursionError, BlastscaleInputError):
        return False


def _source(source: str, kind: Optional[str]) -> tuple[str, str]:

    stem = source[:-5] if source.endswith(".toml") else source
    if stem not in library_names():
        raise BlastscaleInputError(
            f"from = {source!r} is not a shipped scenario: valid names are {', '.join(library_names())}"
        )
    own = load_scenario(stem).structure.kind
    if kind is not None and kind != own:
        raise BlastscaleInputError(
            f"kind = {kind!r} and from = {source!r} disagree: {stem} is a {own} scenario "
            f"(give --kind {own}, or --kind {kind} without --from for its template)"
        )
    return library_text(stem), f"a copy of the shipped scenario {stem}"


@app.command("init")
def init_cmd(
    file: Path = typer.Argument(..., metavar="FILE.toml", show_default=False, help="The scenario file to write."),
    kind: Optional[str] = typer.Option(
        None,
        "--kind",
        show_default=False,
        help="Structure of the template: block (the default), column, wall, arch, "
        "portal or assembly (with an example block-model file).",
    ),
    source: Optional[str] = typer.Option(
        None,
        "--from",
        metavar="NAME",
        show_default=False,
        help="Copy a shipped scenario instead (e.g. planar_block, "
        "paper_column_square_250kg; see blastscale reproduce --list).",
    ),
    force: bool = typer.Option(
        False, "--force", help="Replace a scenario file that blastscale wrote (never another file)."
    ),
) -> None:
    """Write a commented scenario template (or a copy of a shipped scenario) to start from."""

    if file.suffix != ".toml":
        raise BlastscaleInputError(f"file = {str(file)!r} has no .toml extension: give e.g. {str(file)}.toml")
    blocks = None
    if source is not None:
        text, what = _source(source, kind)
    else:
        kind = kind or "block"
        blocks = file.with_name(f"{file.stem}_blocks.json") if kind == "assembly" else None
        text = template_text(kind, blocks.name if blocks else "blocks.json")
        what = f"a commented {kind} scenario template"
    target = Kind("a scenario file blastscale wrote", _is_ours, folder=False)
    check_target(file, target, force, name="file")
    if file.exists() and not force:
        raise BlastscaleInputError(f"file = {str(file)!r} exists: refused (give --force to replace it)")
    if file.exists() and not (file.is_file() and _is_ours(file)):
        raise BlastscaleInputError(
            f"file = {str(file)!r} exists and is not a scenario file blastscale wrote: refused, even with --force"
        )
    keep = blocks is not None and (blocks.exists() or blocks.is_symlink())
    if blocks is not None and not keep:
        check_target(blocks, Kind("a block-model file", lambda p: False, folder=False), name="file")
    with claim(file, target, force, name="file") as c:
        if c.path.exists() and not (c.path.is_file() and _is_ours(c.path)):
            raise BlastscaleInputError(
                f"file = {str(file)!r} exists and is not a scenario file blastscale wrote: refused, even with --force"
            )
        if blocks is not None and not keep:
            write_file(blocks, json.dumps(EXAMPLE_BLOCKS, indent=1) + "\n", what="file")
        try:
            write_file(c.path, text, what="file")
        except BaseException:
            if blocks is not None and not keep:
                blocks.unlink(missing_ok=True)
            raise
    load_scenario(file)  # the template is a valid scenario as written
    if blocks is not None:
        if keep:
            console_err.print(
                f"kept {blocks}: the scenario's block-model file (init never replaces it)", soft_wrap=True
            )
        else:
            print_written(blocks, "an example block model: two blocks (docs/assemblies.md has the formats)")
    print_written(file, what)
    console.print(f"edit it, then: blastscale run {file} --out RESULTS (docs/scenarios.md has every key)")
