"""Long histories thinned for drawing: the per-bin extremes, so a figure shows what the full series shows.

A column's 8 s history recorded every millisecond has 8000 samples per line, 44 lines in the report's
figure, drawn into axes a few hundred pixels wide: matplotlib then spends most of a column ``run``'s
figure time rasterising segments that fall on the same pixels and placing the legend among all those
vertices (issue #28: 38 % of a column ``run`` in drawing). :func:`minmax_thin` keeps, in time order,
the first and last samples and the smallest and largest value in each of ``bins`` consecutive index
bins (min-max decimation; M4, Jugel et al. 2014, "M4: a visualization-oriented time series data
aggregation", Proc. VLDB Endow. 7(10), also keeps each bin's first and last): every peak and trough
survives, so a line drawn through them covers the same pixels in axes up to ``bins`` pixels wide. The data, the numbers and the files are unchanged;
only the vertices handed to matplotlib are fewer.
"""

from __future__ import annotations

import numpy as np

__all__ = ["DRAW_BINS", "minmax_thin"]

#: Bins of a thinned history: more than the pixels across the widest history axes of a report figure
#: (a column's: 2/5 of 15 in at 110 dpi, ~660 px; a block's: 11 in / 2 at 110 dpi, ~600 px).
DRAW_BINS = 1000


def minmax_thin(t, y, bins: int = DRAW_BINS):
    """``(t, y)`` reduced to the first and last samples and each bin's minimum and maximum of ``y``.

    Parameters
    ----------
    t : array_like, shape (n,)
        Times [any unit], increasing.
    y : array_like, shape (n,)
        Values [any unit].
    bins : int
        Consecutive index bins (>= 1); a series of at most ``2 bins + 2`` samples, or one holding a
        non-finite value, is returned whole.

    Returns
    -------
    (ndarray, ndarray)
        The kept times and values, in time order (at most ``2 bins + 2`` of each).
    """
    t = np.asarray(t)
    y = np.asarray(y)
    n = y.size
    if n <= 2 * bins + 2 or not np.all(np.isfinite(y)):
        return t, y
    m = -(-n // bins)  # samples per bin
    nb = -(-n // m)
    full = (nb - 1) * m  # the last bin may be short: its extremes separately
    head = y[:full].reshape(nb - 1, m)
    start = np.arange(nb - 1) * m
    tail = y[full:]
    keep = np.concatenate(
        (
            [0, n - 1],
            start + np.argmin(head, axis=1),
            start + np.argmax(head, axis=1),
            [full + int(np.argmin(tail)), full + int(np.argmax(tail))],
        )
    )
    keep = np.unique(keep)
    return t[keep], y[keep]
