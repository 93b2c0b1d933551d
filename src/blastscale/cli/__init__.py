"""Command-line interface (typer), thin over the library.

Each command lives in its own module and registers itself on :data:`app`:
``blast``/``design`` (:mod:`.loads`), ``rock`` (:mod:`.rocking`), ``critical``/``capacity`` (:mod:`.capacity`),
``block3d`` (:mod:`.block3d`), ``run`` (:mod:`.main_job`), ``reproduce`` (:mod:`.reproduce`), ``plan``
(:mod:`.plan`), ``init`` (:mod:`.init`), ``show`` (:mod:`.show`), ``fired`` (:mod:`.fired`). Units at this
edge are those named in each option's help text; everything is converted to SI before calling the library.

Bad input raises :class:`~blastscale._validate.BlastscaleInputError` in the library; ``main``
prints its one-line message and exits with status 2, without a traceback. So does a command that needs
an optional extra that is not installed (:mod:`blastscale._extras`): one line naming the extra and its
install command.
"""

from __future__ import annotations

import sys

from .._extras import extra_of, missing_extra_message
from .._validate import BlastscaleInputError
from ._app import app, print_error

# command modules register themselves on `app` when imported (in this order: `blastscale --help` lists them so)
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

__all__ = ["app", "main"]


def _command(argv: list[str] | None) -> str:
    """``blastscale COMMAND`` as the user typed it (the first word that is not an option)."""
    words = [str(a) for a in (sys.argv[1:] if argv is None else argv)]
    return " ".join(["blastscale"] + next(([w] for w in words if not w.startswith("-")), []))


def main(argv: list[str] | None = None) -> None:
    """Entry point of the ``blastscale`` console script."""

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
