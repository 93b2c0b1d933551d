"""The typer application object and small output helpers shared by the commands."""

from __future__ import annotations

import os
import signal
import sys


def _interrupted_while_starting(signum, frame):  # pragma: no cover - timing dependent
    """Ctrl-C while the command line tool is still importing: one line, exit 130, nothing written."""
    os.write(2, b"error: interrupted (Ctrl-C): no partial results left\n")
    os._exit(130)


if os.path.basename(sys.argv[0]) == "blastscale" and signal.getsignal(signal.SIGINT) is signal.default_int_handler:
    signal.signal(signal.SIGINT, _interrupted_while_starting)  # replaced by the command's own handler

import contextlib  # noqa: E402
import json
import warnings

import typer
from rich.console import Console
from rich.table import Table
from typer.core import TyperGroup, TyperOption

from .._validate import BlastscaleInputError
from ..io.results import jsonable, with_legacy_keys

# Wide enough for the tables when output is piped (rich falls back to 80 columns otherwise).
console = Console(width=None if Console().is_terminal else 160)
console_err = Console(stderr=True, width=None if Console(stderr=True).is_terminal else 160)


def print_error(message: str) -> None:
    """Print ``error: <message>`` as one line on stderr (newlines folded)."""
    from rich.markup import escape

    # escaped: "[structure]" or "[0.2, 20]" in a message are text, not rich markup
    console_err.print(f"[bold red]error:[/] {escape(' '.join(str(message).split()))}", highlight=False,
                      soft_wrap=True, markup=True)


_display_type_rich = getattr(TyperOption, "display_type_rich", None)


def _flag_display_type(self, ctx):
    """A flag takes no value: --help shows ``--json`` alone, not ``--json <bool>`` (recent typer
    prints the value type of every option, flags included)."""
    if getattr(self, "is_flag", False) and self.metavar is None:
        return None
    return _display_type_rich(self, ctx)


if _display_type_rich is not None:  # older typer prints no types at all
    TyperOption.display_type_rich = _flag_display_type


class Interrupted(BaseException):
    """Ctrl-C (SIGINT) inside a command. Raised instead of KeyboardInterrupt so that click does
    not turn it into its two-line "Aborted!"; a BaseException, so that no ``except Exception``
    swallows it; clean-ups (``finally``, the output folder) still run."""


_INTERRUPTED: list = []  # set by the handler: an import that turns Interrupted into ImportError is still Ctrl-C


def _raise_interrupted(signum, frame):
    _INTERRUPTED.append(signum)
    f, depth = frame, 0
    while f is not None and depth < 30:  # inside a finaliser Python would ignore the exception:
        if f.f_code.co_name == "__del__":  # the flag is checked at the next stage instead
            return
        f, depth = f.f_back, depth + 1
    raise Interrupted()


def _unraisable(info) -> None:
    """Ctrl-C that landed where Python cannot raise (a finaliser, a ctypes callback of the JIT):
    not printed; the flag stays set and :func:`raise_if_interrupted` raises at the next stage."""
    if isinstance(info.exc_value, Interrupted) or _INTERRUPTED:  # or a consequence of it (a half-made
        return  # file object closed at exit): the one line printed says what happened
    sys.__unraisablehook__(info)


def raise_if_interrupted() -> None:
    """Raise :class:`Interrupted` when Ctrl-C came at a moment that could not raise (a finaliser)."""
    if _INTERRUPTED:
        raise Interrupted()


def ignore_interrupts() -> None:
    """From here on Ctrl-C is ignored: the results are in place, only the printing remains."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)


class OneLineErrorGroup(TyperGroup):
    """The command group, with click's usage errors (bad number, missing or unknown option) printed as
    one ``error:`` line naming the option, exit status 2, instead of typer's multi-line box."""

    def main(self, args=None, prog_name=None, complete_var=None, standalone_mode=True, **extra):
        if not standalone_mode:
            return super().main(args, prog_name, complete_var, standalone_mode=False, **extra)
        previous = signal.getsignal(signal.SIGINT)
        previous_hook = sys.unraisablehook
        if previous is not signal.SIG_IGN:  # a background job keeps ignoring Ctrl-C
            signal.signal(signal.SIGINT, _raise_interrupted)
            sys.unraisablehook = _unraisable
        args = normalise_ratios(list(sys.argv[1:] if args is None else args))
        try:
            rv = super().main(args, prog_name, complete_var, standalone_mode=False, **extra)
        except BaseException as exc:
            if isinstance(exc, Interrupted) or (_INTERRUPTED and not isinstance(exc, SystemExit)):
                print_error("interrupted (Ctrl-C): no partial results left")
                sys.exit(130)
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
            signal.signal(signal.SIGINT, previous)
            if not _INTERRUPTED:  # after Ctrl-C, keep quiet about finalisers that run at exit
                sys.unraisablehook = previous_hook
        sys.exit(rv if isinstance(rv, int) else 0)


#: Options whose value is a dimensionless ratio: they also accept a fraction such as 1/200.
RATIO_OPTIONS = ("--scale", "--density-ratio", "--gravity-ratio")


def normalise_ratios(args: list[str]) -> list[str]:
    """The command line with fraction values of :data:`RATIO_OPTIONS` (``--scale 1/200``,
    ``--scale=1/200``) turned into decimals, for every command at once; anything that is not a
    fraction is left for the option's own check."""
    from fractions import Fraction

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
    return message.replace("(opt in with extrapolate=True, CLI --extrapolate, to evaluate it anyway)",
                           f"(`{name}` has no --extrapolate: choose values inside the range)").replace(hint, "")


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
    version: bool = typer.Option(False, "--version", callback=_version, is_eager=True,
                                 help="Print the version and exit."),
) -> None:
    """Design safe reduced-scale blast experiments on masonry structures (Masi et al. scaling laws)."""


@contextlib.contextmanager
def stage_progress():
    """A rich progress bar on stderr for a staged job; yields ``tell(stage, done, total)``.
    Transient: it disappears when the job ends."""
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, SpinnerColumn, TextColumn, TimeElapsedColumn

    with Progress(SpinnerColumn(), TextColumn("{task.description}"), BarColumn(), MofNCompleteColumn(),
                  TimeElapsedColumn(), console=console_err, transient=True,
                  disable=not console_err.is_terminal) as bar:
        task = bar.add_task("starting", total=None)

        def tell(stage: str, done: int, total: int) -> None:
            raise_if_interrupted()
            bar.update(task, description=stage, completed=done, total=total)

        yield tell


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
                    from rich.markup import escape

                    console_err.print(f"[yellow]warning:[/] {escape(msg)}", highlight=False, soft_wrap=True)


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
