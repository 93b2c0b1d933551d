"""Command-line interface (typer), thin over the library.

Each command lives in its own module and registers itself on :data:`app`:
``blast``/``design`` (:mod:`.loads`), ``rock`` (:mod:`.rocking`), ``critical``/``capacity`` (:mod:`.capacity`),
``block3d`` (:mod:`.block3d`), ``run`` (:mod:`.main_job`), ``reproduce`` (:mod:`.reproduce`), ``plan``
(:mod:`.plan`), ``init`` (:mod:`.init`), ``show`` (:mod:`.show`), ``fired`` (:mod:`.fired`), ``source`` (:mod:`.source`: ``source calibrate``). Units at this
edge are those named in each option's help text; everything is converted to SI before calling the library.

Bad input raises :class:`~blastscale._validate.BlastscaleInputError` in the library; ``main``
prints its one-line message and exits with status 2, without a traceback. So does a command that needs
an optional extra that is not installed (:mod:`blastscale._extras`): one line naming the extra and its
install command.
"""

from __future__ import annotations

import gc
import sys

from .._extras import extra_of, missing_extra_message
from .._validate import BlastscaleInputError
from ._app import app
from ._output import print_error

# command modules register themselves on `app` when imported (in this order: `blastscale --help` lists them so)
# isort: off
from . import loads as _loads  # noqa: F401,E402
from . import rocking as _rocking  # noqa: F401,E402
from . import capacity as _capacity  # noqa: F401,E402
from . import block3d as _block3d  # noqa: F401,E402
from . import column as _column  # noqa: F401,E402
from . import main_job as _main_job  # noqa: F401,E402
from . import reproduce as _reproduce  # noqa: F401,E402
from . import sweeps as _sweeps  # noqa: F401,E402
from . import plan as _plan  # noqa: F401,E402
from . import init as _init  # noqa: F401,E402
from . import show as _show  # noqa: F401,E402
from . import fired as _fired  # noqa: F401,E402
from . import source as _source  # noqa: F401,E402
# isort: on

__all__ = ["app", "main", "GC_THRESHOLDS"]

#: The cyclic garbage collector's thresholds while a command runs (Python's are 700, 10, 10). A command's
#: objects (modules, scenario, histories, figures) mostly live to its end, and each full pass over them finds
#: little: with Python's thresholds the collector took 0.46 s of a 4.2 s column ``run`` (5 full passes,
#: 0.35 s), with these 0.12 s (1 full pass); the peak memory 3-5 % higher (434 -> 446-449 MB; docs/performance.md). Restored
#: when the command returns (``main`` may be called in a longer-lived process).
GC_THRESHOLDS = (10_000, 50, 100)


def _command(argv: list[str] | None) -> str:
    """``blastscale COMMAND`` as the user typed it (the first word that is not an option)."""
    words = [str(a) for a in (sys.argv[1:] if argv is None else argv)]
    return " ".join(["blastscale"] + next(([w] for w in words if not w.startswith("-")), []))


def main(argv: list[str] | None = None) -> None:
    """Entry point of the ``blastscale`` console script (the collector's thresholds :data:`GC_THRESHOLDS`
    while it runs)."""

    before = gc.get_threshold()
    gc.set_threshold(*GC_THRESHOLDS)
    try:
        app(args=argv, prog_name="blastscale")
    except BlastscaleInputError as exc:
        print_error(str(exc))
        sys.exit(2)
    except ImportError as exc:  # an optional extra's module, imported by us or by a library (xarray's zarr)
        extra = extra_of(exc)
        if extra is None:
            raise
        print_error(missing_extra_message(_command(argv), extra, exc.name))
        sys.exit(2)
    finally:
        gc.set_threshold(*before)
