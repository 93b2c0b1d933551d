"""``blastscale init``: start a scenario file from a commented template or from a shipped scenario.

``blastscale init [--kind block|column] [--from NAME] FILE.toml`` writes FILE.toml (through
:mod:`blastscale.io.output`: the folder must exist; an existing file is replaced only with
``--force``, and only when it is a TOML file), checks that it loads, and says how to run it.
"""

from __future__ import annotations

import tomllib
from pathlib import Path
from typing import Optional

import typer

from .._validate import BlastscaleInputError
from ._app import app, console, print_written


def _is_toml(path: Path) -> bool:
    try:
        tomllib.loads(path.read_text(encoding="utf-8"))
        return True
    except (OSError, UnicodeDecodeError, tomllib.TOMLDecodeError):
        return False


@app.command("init")
def init_cmd(
    file: Path = typer.Argument(..., metavar="FILE.toml", show_default=False, help="The scenario file to write."),
    kind: str = typer.Option("block", "--kind", help="Structure of the template: block or column."),
    source: Optional[str] = typer.Option(
        None,
        "--from",
        metavar="NAME",
        show_default=False,
        help="Copy a shipped scenario instead (e.g. planar_block, "
        "paper_column_square_250kg; see blastscale reproduce --list).",
    ),
    force: bool = typer.Option(False, "--force", help="Replace an existing TOML file."),
) -> None:
    """Write a commented scenario template (or a copy of a shipped scenario) to start from."""
    from ..io.output import Kind, claim, write_file
    from ..scenario import library_names, library_text, load_scenario, template_text

    if file.suffix != ".toml":
        raise BlastscaleInputError(f"file = {str(file)!r} has no .toml extension: give e.g. {str(file)}.toml")
    if source is not None:
        stem = source[:-5] if source.endswith(".toml") else source
        if stem not in library_names():
            raise BlastscaleInputError(
                f"from = {source!r} is not a shipped scenario: valid names are {', '.join(library_names())}"
            )
        text, what = library_text(stem), f"a copy of the shipped scenario {stem}"
    else:
        text, what = template_text(kind), f"a commented {kind} scenario template"
    if file.exists() and not force:
        raise BlastscaleInputError(f"file = {str(file)!r} exists: refused (give --force to replace it)")
    with claim(file, Kind("a TOML file", _is_toml, folder=False), force, name="file") as c:
        if c.path.exists() and not (c.path.is_file() and _is_toml(c.path)):
            raise BlastscaleInputError(
                f"file = {str(file)!r} exists and is not a TOML file: refused, even with --force"
            )
        write_file(c.path, text, what="file")
    load_scenario(file)  # the template is a valid scenario as written
    print_written(file, what)
    console.print(f"edit it, then: blastscale run {file} --out RESULTS (docs/scenarios.md has every key)")
