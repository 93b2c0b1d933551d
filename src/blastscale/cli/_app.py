"""The typer application object and small output helpers shared by the commands."""

from __future__ import annotations

import json
import math
from typing import Any

import typer
from rich.console import Console
from rich.table import Table

app = typer.Typer(
    name="blastscale",
    help="Design safe reduced-scale blast experiments on masonry structures (Masi et al. scaling laws).",
    no_args_is_help=True,
    add_completion=False,
    pretty_exceptions_enable=False,
)
# Wide enough for the tables when output is piped (rich falls back to 80 columns otherwise).
console = Console(width=None if Console().is_terminal else 160)
console_err = Console(stderr=True, width=None if Console(stderr=True).is_terminal else 160)


def _jsonable(obj: Any) -> Any:
    if isinstance(obj, dict):
        return {str(k): _jsonable(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_jsonable(v) for v in obj]
    if hasattr(obj, "item") and callable(obj.item):  # numpy scalars
        obj = obj.item()
    if isinstance(obj, float) and not math.isfinite(obj):
        return None if math.isnan(obj) else ("inf" if obj > 0 else "-inf")
    return obj


def print_json(obj: dict) -> None:
    """Print one JSON object on stdout (numpy scalars converted, NaN -> null)."""
    typer.echo(json.dumps(_jsonable(obj), indent=2))


def save_figure(build, path) -> None:
    """Build a matplotlib figure with the non-interactive Agg backend and write it to ``path``.

    ``build`` is a no-argument callable returning the figure (called after the backend is set).
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig = build()
    fig.savefig(path, dpi=120)
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
