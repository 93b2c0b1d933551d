"""What the commands print: the consoles, progress on stderr, tables, JSON, figures and the files written.

Console text is literal: the consoles read no markup and no emoji codes (``Console(markup=False,
emoji=False)``), so a title, a path or a grid typed by the user is printed as typed ("[model 2]",
"[/b]", ":100:"); styles are given as :class:`rich.text.Text` (:func:`styled`). Imported by :mod:`._app`
after its signal guard; the commands import these helpers from here.
"""

from __future__ import annotations

import contextlib
import io
import json
import time
import warnings
from pathlib import Path

import typer
from rich.console import Console
from rich.progress import (
    BarColumn,
    MofNCompleteColumn,
    Progress,
    SpinnerColumn,
    TextColumn,
    TimeElapsedColumn,
    TimeRemainingColumn,
)
from rich.table import Table
from rich.text import Text

from .._validate import BlastscaleInputError
from ..io.output import tree_size, write_file
from ..io.results import jsonable, with_legacy_keys
from ..study.memory import format_duration
from ..units import format_size
from ._progress import plain_lines, plain_progress, progress_seconds
from ._signals import raise_if_interrupted


def _console(stderr: bool = False) -> Console:
    # wide enough for the tables when output is piped (rich falls back to 80 columns otherwise)
    probe = Console(stderr=stderr)
    return Console(stderr=stderr, width=None if probe.is_terminal else 160, markup=False, emoji=False, highlight=False)


console = _console()
console_err = _console(stderr=True)


def styled(*parts) -> Text:
    """A line of literal text with styled pieces: ``styled(("error:", "bold red"), " ", user_text)``."""
    return Text.assemble(*parts)


def print_error(message: str) -> None:
    """Print ``error: <message>`` as one line on stderr (newlines folded; the message literal)."""
    console_err.print(styled(("error:", "bold red"), " ", " ".join(str(message).split())), soft_wrap=True)


def show_progress(quiet: bool = False) -> bool:
    """Whether a command shows progress: on a terminal (stderr), and not with ``--json`` (``quiet``)."""
    return not quiet and console_err.is_terminal


@contextlib.contextmanager
def stage_progress(quiet: bool = False, expected_s: float | None = None):
    """A rich progress bar on stderr for a staged job; yields ``tell(stage, done, total)``.
    Transient (it disappears when the job ends); shown only on a terminal and not with ``--json``. Off a
    terminal (a batch job, CI), plain lines every :func:`progress_seconds` instead (the stage, the time elapsed
    and ``expected_s``, the run's estimate [s], when given)."""

    state = {"stage": "starting", "done": 0, "total": None, "expected_s": expected_s}
    with (
        Progress(
            SpinnerColumn(),
            TextColumn("{task.description}", markup=False),
            BarColumn(),
            MofNCompleteColumn(),
            TimeElapsedColumn(),
            console=console_err,
            transient=True,
            disable=not show_progress(quiet),
        ) as bar,
        plain_lines(state, plain_progress(console_err, quiet), console_err),
    ):
        task = bar.add_task("starting", total=None)

        def tell(stage: str, done: int, total: int) -> None:
            raise_if_interrupted()
            state.update(stage=stage, done=done, total=total)
            bar.update(task, description=stage, completed=done, total=total)

        yield tell


@contextlib.contextmanager
def activity(label: str, quiet: bool = False):
    """A spinner with the elapsed time on stderr while one long step runs (a terminal only, not with
    ``--json``)."""
    with stage_progress(quiet) as tell:
        tell(label, 0, None)
        yield


def count_progress(label: str, quiet: bool = False):
    """A progress bar over cases (done / total, elapsed, remaining) and its ``tick(done, total)``."""

    bar = Progress(
        TextColumn(label, markup=False),
        BarColumn(),
        MofNCompleteColumn(),
        TimeElapsedColumn(),
        TimeRemainingColumn(),
        console=console_err,
        transient=True,
        disable=not show_progress(quiet),
    )
    task = bar.add_task(label, total=None)
    plain, every, t0, last = (
        plain_progress(console_err, quiet),
        progress_seconds(),
        time.monotonic(),
        [time.monotonic()],
    )

    def tick(done: int, total: int) -> None:
        raise_if_interrupted()
        bar.update(task, completed=done, total=total)
        now = time.monotonic()
        if plain and now - last[0] >= every:  # off a terminal: a plain line at most every progress_seconds()
            last[0] = now
            console_err.print(
                f"progress: {label}: {done} of {total} done, {format_duration(now - t0)} elapsed", soft_wrap=True
            )

    return bar, tick


def print_written(path, what: str = "") -> None:
    """One line on stderr: what a command wrote and how big it is (``wrote DIR/ (7 files, 2.1 MB)``)."""

    p = Path(path)
    try:
        size = format_size(tree_size(p))
    except OSError:
        size = "?"
    if p.is_dir():
        n = sum(1 for f in p.rglob("*") if f.is_file())
        detail = f"{n} files, {size}" + (f": {what}" if what else "")
        console_err.print(f"wrote {path}{'' if str(path).endswith('/') else '/'} ({detail})", soft_wrap=True)
    else:
        console_err.print(f"wrote {path} ({size}{', ' + what if what else ''})", soft_wrap=True)


@contextlib.contextmanager
def one_line_warnings():
    """Print the library's warnings (e.g. extrapolation) as one ``warning:`` line each on stderr,
    without Python's file/line prefix; each distinct message once. A ``ResourceWarning`` (a socket of
    a Dask cluster torn down after a fault or a signal) says nothing about the user's job: not printed."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            yield
        finally:
            seen = set()
            for w in caught:
                if issubclass(w.category, ResourceWarning):
                    continue
                msg = " ".join(str(w.message).split())
                if msg not in seen:
                    seen.add(msg)
                    console_err.print(styled(("warning:", "yellow"), " ", msg), soft_wrap=True)


def print_json(obj: dict, engine: "str | None" = None) -> None:
    """Print one JSON object on stdout (numpy scalars converted, NaN -> null), each renamed key
    with its deprecated name beside it (:func:`blastscale.io.results.with_legacy_keys`; ``engine``:
    the engine of the command's outcome keys, ``"planar"`` or ``"3d"``)."""
    typer.echo(json.dumps(jsonable(with_legacy_keys(obj, engine)), indent=2))


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
    """Build a matplotlib figure with the non-interactive Agg backend and write it to ``path``
    atomically (:func:`blastscale.io.output.write_file`: nothing half-written, one line on a fault).

    ``build`` is a no-argument callable returning the figure (called after the backend is set).
    """

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig = build()
    buf = io.BytesIO()
    try:
        fig.savefig(buf, dpi=120, format=Path(path).suffix.lstrip(".").lower() or "png")
    except ValueError as exc:  # an image format matplotlib cannot write
        raise BlastscaleInputError(f"plot = {str(path)!r} cannot be written: {exc}") from None
    finally:
        plt.close(fig)
    write_file(Path(path).expanduser(), buf.getvalue(), what="plot")


def table(title: str, rows: list[tuple[str, str, str]]) -> Table:
    """A three-column (quantity, value, unit) rich table (title and cells literal)."""
    t = Table(title=title, title_justify="left")
    t.add_column("quantity")
    t.add_column("value", justify="right")
    t.add_column("unit")
    for r in rows:
        t.add_row(*r)
    return t
