"""Figures to files: the one place a drawing is written (``blastscale show --plot``).

:func:`check_figure_path` refuses, before any work, a path whose folder does not exist or whose
suffix is not a format written here; :func:`write_figure` renders the figure in memory and writes
the bytes atomically (:func:`~.results.write_atomic`): a failure leaves nothing behind.
"""

from __future__ import annotations

import io
from pathlib import Path

from .._validate import BlastscaleInputError
from .results import write_atomic

__all__ = ["FIGURE_FORMATS", "check_figure_path", "write_figure"]

#: File suffixes a figure is written as.
FIGURE_FORMATS = (".png", ".svg", ".pdf")


def check_figure_path(path, name: str = "plot") -> Path:
    """The path, checked: a known suffix (:data:`FIGURE_FORMATS`), an existing folder, not a folder."""
    p = Path(path)
    if p.suffix.lower() not in FIGURE_FORMATS:
        raise BlastscaleInputError(f"{name} = {str(p)!r} has an unknown image format: valid suffixes are "
                                   f"{', '.join(FIGURE_FORMATS)}")
    if not p.parent.is_dir():
        raise BlastscaleInputError(f"{name} = {str(p)!r} cannot be written: no folder {str(p.parent)!r}")
    if p.is_dir():
        raise BlastscaleInputError(f"{name} = {str(p)!r} cannot be written: it is a folder")
    return p


def write_figure(path, figure, name: str = "plot", dpi: int = 120) -> Path:
    """Render a matplotlib ``figure`` (closed afterwards) and write it to ``path`` atomically."""
    import matplotlib.pyplot as plt

    p = check_figure_path(path, name)
    buf = io.BytesIO()
    try:
        figure.savefig(buf, format=p.suffix.lower()[1:], dpi=dpi)
    finally:
        plt.close(figure)
    try:
        write_atomic(p, buf.getvalue())
    except OSError as exc:
        raise BlastscaleInputError(f"{name} = {str(p)!r} cannot be written: {exc.strerror or exc}") from None
    return p
