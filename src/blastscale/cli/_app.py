"""The typer application object and small output helpers shared by the commands.

Console text is literal: the consoles read no markup and no emoji codes (``Console(markup=False,
emoji=False)``), so a title, a path or a grid typed by the user is printed as typed ("[model 2]",
"[/b]", ":100:"); styles are given as :class:`rich.text.Text` (:func:`styled`).
"""

from __future__ import annotations

import os
import sys

from . import _signals

if os.path.basename(sys.argv[0]) == "blastscale":
    _signals.at_import()  # a signal while importing: one line; a local Dask worker: Ctrl-C ignored

import contextlib  # noqa: E402
import errno  # noqa: E402
import io  # noqa: E402
import json  # noqa: E402
import logging  # noqa: E402
import warnings  # noqa: E402
from fractions import Fraction  # noqa: E402
from pathlib import Path  # noqa: E402

import typer  # noqa: E402
from rich.console import Console  # noqa: E402
from rich.progress import (
    BarColumn,
    MofNCompleteColumn,
    Progress,
    SpinnerColumn,
    TextColumn,  # noqa: E402
    TimeElapsedColumn,
    TimeRemainingColumn,
)
from rich.table import Table  # noqa: E402
from rich.text import Text  # noqa: E402
from typer.core import TyperGroup, TyperOption  # noqa: E402

from .._validate import BlastscaleInputError  # noqa: E402
from ..io.output import format_size, tree_size, write_file  # noqa: E402
from ..io.results import jsonable, with_legacy_keys  # noqa: E402
from ._progress import plain_lines, plain_progress, progress_seconds  # noqa: E402
from ._signals import Interrupted, ignore_interrupts, raise_if_interrupted  # noqa: F401 (re-exported)


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


_display_type_rich = getattr(TyperOption, "display_type_rich", None)


def _flag_display_type(self, ctx):
    """A flag takes no value: --help shows ``--json`` alone, not ``--json <bool>`` (recent typer
    prints the value type of every option, flags included)."""
    if getattr(self, "is_flag", False) and self.metavar is None:
        return None
    return _display_type_rich(self, ctx)


if _display_type_rich is not None:  # older typer prints no types at all
    TyperOption.display_type_rich = _flag_display_type


class OneLineErrorGroup(TyperGroup):
    """The command group, with click's usage errors (bad number, missing or unknown option) printed as
    one ``error:`` line naming the option, exit status 2, instead of typer's multi-line box."""

    def main(self, args=None, prog_name=None, complete_var=None, standalone_mode=True, **extra):
        if not standalone_mode:
            return super().main(args, prog_name, complete_var, standalone_mode=False, **extra)
        saved = _signals.install()
        args = normalise_ratios(list(sys.argv[1:] if args is None else args))
        try:
            _check_stdout()
            rv = super().main(args, prog_name, complete_var, standalone_mode=False, **extra)
            if sys.stdout is not None:
                sys.stdout.flush()  # a full device says so now, not in Python's exit
        except BaseException as exc:
            if _stdout_fault(exc):
                _stdout_to_null()
                print_error(
                    f"standard output cannot be written: {_why(exc)} (what was printed is incomplete; "
                    "files written are whole)"
                )
                sys.exit(2)
            signum = _signals.interrupted_signal()
            if isinstance(exc, Interrupted) or (signum is not None and not isinstance(exc, SystemExit)):
                _quiet_after_interrupt()
                print_error(_signals.message(signum))
                sys.exit(_signals.exit_status(signum))
            if isinstance(exc, BlastscaleInputError):
                print_error(_adapt_hint(str(exc), self, args))
                sys.exit(2)
            if isinstance(exc, typer.TyperException):  # click's ClickException / UsageError
                message = exc.format_message().strip()
                if message and type(exc).__name__ != "NoArgsIsHelpError":  # that one has printed the help
                    ctx = getattr(exc, "ctx", None)
                    hint = f" (see '{ctx.command_path} --help')" if ctx is not None else ""
                    print_error(message + hint)
                sys.exit(getattr(exc, "exit_code", 2))
            if isinstance(exc, typer.Abort):
                print_error("aborted")
                sys.exit(1)
            raise
        finally:
            _signals.restore(saved)
            _signals.set_interrupt_note(None)
        sys.exit(rv if isinstance(rv, int) else 0)


def _check_stdout() -> None:
    """Refuse to start with standard output closed (``>&-``): what a command prints would be lost."""
    try:
        closed = sys.stdout is None or not os.fstat(sys.stdout.fileno())
    except (AttributeError, ValueError, io.UnsupportedOperation):  # a captured or replaced stream: fine
        closed = False
    except OSError:
        closed = True
    if closed:
        raise BlastscaleInputError(
            "standard output is closed: give it a file or /dev/null (> out.txt); nothing was run"
        )


#: Where a write to standard output fails (click's echo, rich's console, our flush).
_STDOUT_WRITERS = ("click/utils.py", "rich/console.py", "cli/_app.py")


def _stdout_fault(exc: BaseException) -> bool:
    """Whether ``exc`` is a failed write to standard output (a full device, a closed pipe)."""
    if not isinstance(exc, OSError) or exc.errno not in (
        errno.ENOSPC,
        errno.EPIPE,
        errno.EIO,
        errno.EBADF,
        errno.EDQUOT,
    ):
        return False
    tb = exc.__traceback__
    last = None
    while tb is not None:
        last = tb.tb_frame.f_code.co_filename.replace("\\", "/")
        tb = tb.tb_next
    return last is not None and last.endswith(_STDOUT_WRITERS)


def _why(exc: OSError) -> str:
    if exc.errno == errno.ENOSPC:
        return "no space left on the device"
    if exc.errno == errno.EPIPE:
        return "its reader closed it"
    return exc.strerror or str(exc)


def _stdout_to_null() -> None:
    """Point standard output at /dev/null so that Python's own flush at exit says nothing more."""
    try:
        null = os.open(os.devnull, os.O_WRONLY)
        os.dup2(null, 1)
        os.close(null)
    except OSError:
        pass


def _quiet_after_interrupt() -> None:
    """After a signal the one line says it all: Dask's and asyncio's shutdown chatter is not shown."""

    for name in ("distributed", "asyncio", "tornado"):
        logging.getLogger(name).setLevel(logging.CRITICAL)
    warnings.filterwarnings("ignore")


#: Options whose value is a dimensionless ratio: they also accept a fraction such as 1/200.
RATIO_OPTIONS = ("--scale", "--density-ratio", "--gravity-ratio")


def normalise_ratios(args: list[str]) -> list[str]:
    """The command line with fraction values of :data:`RATIO_OPTIONS` (``--scale 1/200``,
    ``--scale=1/200``) turned into decimals, for every command at once; anything that is not a
    fraction is left for the option's own check."""

    def conv(text: str) -> str:
        if "/" not in text:
            return text
        try:
            return repr(float(Fraction(text.replace(" ", ""))))
        except (ValueError, ZeroDivisionError):
            return text

    out = list(args)
    for i, a in enumerate(out):
        if a in RATIO_OPTIONS and i + 1 < len(out):
            out[i + 1] = conv(out[i + 1])
        elif "=" in a and a.split("=", 1)[0] in RATIO_OPTIONS:
            name, value = a.split("=", 1)
            out[i] = f"{name}={conv(value)}"
    return out


def _adapt_hint(message: str, group, args) -> str:
    """Library messages suggest ``--extrapolate``; a command without that option gets the hint
    that works for it (``run``: the scenario key), or none."""
    hint = "CLI --extrapolate, "
    if hint not in message:
        return message
    argv = list(sys.argv[1:] if args is None else args)
    name = next((a for a in argv if not a.startswith("-")), None)
    cmd = group.commands.get(name) if name else None
    opts = {o for p in (cmd.params if cmd is not None else []) for o in getattr(p, "opts", [])}
    if "--extrapolate" in opts:
        return message
    if name == "run":
        return message.replace(hint, "in a scenario: blast.extrapolate = true or --set blast.extrapolate=true, ")
    return message.replace(
        "(opt in with extrapolate=True, CLI --extrapolate, to evaluate it anyway)",
        f"(`{name}` has no --extrapolate: choose values inside the range)",
    ).replace(hint, "")


def _version(value: bool) -> None:
    if value:
        from .. import __version__

        typer.echo(f"blastscale {__version__}")
        raise typer.Exit()


app = typer.Typer(
    name="blastscale",
    cls=OneLineErrorGroup,
    help="Design safe reduced-scale blast experiments on masonry structures (Masi et al. scaling laws).",
    no_args_is_help=True,
    add_completion=False,
    pretty_exceptions_enable=False,
)


@app.callback()
def _main(
    version: bool = typer.Option(
        False, "--version", callback=_version, is_eager=True, help="Print the version and exit."
    ),
) -> None:
    """Design safe reduced-scale blast experiments on masonry structures (Masi et al. scaling laws)."""


def announce_run(study, writes: bool = False, quiet: bool = False) -> float | None:
    """:func:`._progress.announce_run` on standard error: the run's size said before it starts."""
    from ._progress import announce_run as announce

    return announce(study, console_err, writes, quiet)


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
    import time

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
            from ..study.memory import format_duration

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
