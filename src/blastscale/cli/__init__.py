"""Command-line interface (typer), thin over the library.

Each command lives in its own module and registers itself on :data:`app`:
``blast``/``design`` (:mod:`.loads`), ``rock``/``critical`` (:mod:`.rocking`),
``block3d`` (:mod:`.block3d`), ``run`` (:mod:`.main_job`), ``reproduce`` (:mod:`.reproduce`), ``plan``
(:mod:`.plan`), ``init`` (:mod:`.init`), ``show`` (:mod:`.show`), ``fired`` (:mod:`.fired`). Units at this
edge are those named in each option's help text; everything is converted to SI before calling the library.

Bad input raises :class:`~blastscale._validate.BlastscaleInputError` in the library; ``main``
prints its one-line message and exits with status 2, without a traceback.
"""

from __future__ import annotations

import sys

from . import block3d as _block3d  # noqa: F401
from . import column as _column  # noqa: F401
from . import fired as _fired  # noqa: F401
from . import init as _init  # noqa: F401

# command modules register themselves on `app` when imported
from . import loads as _loads  # noqa: F401
from . import main_job as _main_job  # noqa: F401
from . import plan as _plan  # noqa: F401
from . import reproduce as _reproduce  # noqa: F401
from . import rocking as _rocking  # noqa: F401
from . import show as _show  # noqa: F401
from . import sweeps as _sweeps  # noqa: F401
from ._app import app, print_error

__all__ = ["app", "main"]


def main(argv: list[str] | None = None) -> None:
    """Entry point of the ``blastscale`` console script."""
    from .._validate import BlastscaleInputError

    try:
        app(args=argv, prog_name="blastscale")
    except BlastscaleInputError as exc:
        print_error(str(exc))
        sys.exit(2)
