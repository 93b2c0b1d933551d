"""The typer application object and small output helpers shared by the commands."""

from __future__ import annotations

import contextlib
import json
import math
import sys
import warnings
from typing import Any

import typer
from rich.console import Console
from rich.table import Table
from typer.core import TyperGroup

from .._validate import BlastscaleInputError

# Wide enough for the tables when output is piped (rich falls back to 80 columns otherwise).
console = Console(width=None if Console().is_terminal else 160)
console_err = Console(stderr=True, width=None if Console(stderr=True).is_terminal else 160)


def print_error(message: str) -> None:
    """Print ``error: <message>`` as one line on stderr (newlines folded)."""
    console_err.print(f"[bold red]error:[/] {' '.join(str(message).split())}", highlight=False, soft_wrap=True,
                      markup=True)


class OneLineErrorGroup(TyperGroup):
    """The command group, with click's usage errors (bad number, missing or unknown option) printed as
    one ``error:`` line naming the option, exit status 2, instead of typer's multi-line box."""

    def main(self, args=None, prog_name=None, complete_var=None, standalone_mode=True, **extra):
        if not standalone_mode:
            return super().main(args, prog_name, complete_var, standalone_mode=False, **extra)
        try:
            rv = super().main(args, prog_name, complete_var, standalone_mode=False, **extra)
        except typer.TyperException as exc:  # click's ClickException / UsageError
            message = exc.format_message().strip()
            if message and type(exc).__name__ != "NoArgsIsHelpError":  # that one has printed the help
                ctx = getattr(exc, "ctx", None)
                hint = f" (see '{ctx.command_path} --help')" if ctx is not None else ""
                print_error(message + hint)
            sys.exit(getattr(exc, "exit_code", 2))
        except typer.Abort:
            print_error("aborted")
            sys.exit(1)
        sys.exit(rv if isinstance(rv, int) else 0)


app = typer.Typer(
    name="blastscale",
    cls=OneLineErrorGroup,
    help="Design safe reduced-scale blast experiments on masonry structures (Masi et al. scaling laws).",
    no_args_is_help=True,
    add_completion=False,
    pretty_exceptions_enable=False,
)


@contextlib.contextmanager
def one_line_warnings():
    """Print the library's warnings (e.g. extrapolation) as one ``warning:`` line each on stderr,
    without Python's file/line prefix; each distinct message once."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            yield
        finally:
            seen = set()
            for w in caught:
                msg = " ".join(str(w.message).split())
                if msg not in seen:
                    seen.add(msg)
                    console_err.print(f"[yellow]warning:[/] {msg}", highlight=False, soft_wrap=True)


def _jsonable(obj: Any) -> Any:
    if isinstance(obj, dict):
        return {str(k): _jsonable(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_jsonable(v) for v in obj]
    if hasattr(obj, "tolist") and getattr(obj, "ndim", 0) > 0:  # numpy arrays
        return _jsonable(obj.tolist())
    if hasattr(obj, "item") and callable(obj.item):  # numpy scalars
        obj = obj.item()
    if isinstance(obj, float) and not math.isfinite(obj):
        return None if math.isnan(obj) else ("inf" if obj > 0 else "-inf")
    return obj


def print_json(obj: dict) -> None:
    """Print one JSON object on stdout (numpy scalars converted, NaN -> null)."""
    typer.echo(json.dumps(_jsonable(obj), indent=2))


def fmt_value(x, spec: str = ".6g") -> str:
    """A table cell: ``-`` for None (not applicable), yes/no for booleans, numbers with ``spec``."""
    if x is None:
        return "-"
    if isinstance(x, bool):
        return "yes" if x else "no"
    if isinstance(x, str):
        return x
    return format(x, spec)


def save_figure(build, path) -> None:
    """Build a matplotlib figure with the non-interactive Agg backend and write it to ``path``.

    ``build`` is a no-argument callable returning the figure (called after the backend is set).
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig = build()
    try:
        fig.savefig(path, dpi=120)
    except (OSError, ValueError) as exc:  # missing folder, no permission, unknown image format
        raise BlastscaleInputError(f"plot = {str(path)!r} cannot be written: {exc}") from exc
    finally:
        plt.close(fig)


def table(title: str, rows: list[tuple[str, str, str]]) -> Table:
    """A three-column (quantity, value, unit) rich table."""
    t = Table(title=title, title_justify="left")
    t.add_column("quantity")
    t.add_column("value", justify="right")
    t.add_column("unit")
    for r in rows:
        t.add_row(*r)
    return t
