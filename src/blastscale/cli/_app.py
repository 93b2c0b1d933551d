"""The typer application object, its one-line error handling and the fraction form of ratio options.

What the commands print (consoles, progress, tables, JSON, figures) is in :mod:`._output`; the signal handling
in :mod:`._signals`; the commands import them from there.
"""

from __future__ import annotations

import os
import sys

from ._signals import at_import

if os.path.basename(sys.argv[0]) == "blastscale":
    at_import()  # a signal while importing: one line; a local Dask worker: Ctrl-C ignored

import errno  # noqa: E402
import io  # noqa: E402
import logging  # noqa: E402
import warnings  # noqa: E402
from fractions import Fraction  # noqa: E402

import typer  # noqa: E402
from typer.core import TyperGroup, TyperOption  # noqa: E402

from .._validate import BlastscaleInputError  # noqa: E402
from ._output import print_error  # noqa: E402
from ._signals import (  # noqa: E402
    Interrupted,
    exit_status,
    install,
    interrupted_signal,
    message as signal_message,
    restore,
    set_interrupt_note,
)

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
        saved = install()  # the signal handlers
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
            signum = interrupted_signal()
            if isinstance(exc, Interrupted) or (signum is not None and not isinstance(exc, SystemExit)):
                _quiet_after_interrupt()
                print_error(signal_message(signum))
                sys.exit(exit_status(signum))
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
            restore(saved)
            set_interrupt_note(None)
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
