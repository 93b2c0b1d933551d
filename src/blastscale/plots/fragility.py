"""Fragility plot: per damage state, the observed fraction of draws that reach it against the charge
(points, with 95 % Wilson intervals: :func:`blastscale.analysis.intervals.wilson_interval`), the fitted
lognormal curve and its pointwise 95 % band (:meth:`~blastscale.sweeps.fragility.LognormalFit.band`).

Takes a :class:`~blastscale.sweeps.fragility.FragilityResult` (charges in kg TNT); ``ax=`` as
every plot function (a new figure's axes when None); matplotlib imported only when drawn. Titles and
labels are in words (the uncertain fields by :func:`~blastscale.sweeps.fragility.field_words`).
"""

from __future__ import annotations

import numpy as np

from ..analysis.intervals import wilson_interval
from ..sweeps.fragility import field_words

__all__ = ["plot_fragility"]


#: What a state means, in the legend.
_WORDS = {
    "slight": "damaged (slight) or worse",
    "moderate": "damaged (moderate) or worse",
    "severe": "damaged (severe) or worse",
    "collapse": "collapse",
}


def _state_label(name: str, criterion: str) -> str:
    return "overturns" if (criterion == "first-swing" and name == "collapse") else _WORDS.get(name, name)


def _draw_state(ax, W, st, color, label: str, dodge: float = 1.0) -> None:
    """One state: points with Wilson bars (at ``W x dodge``, so that the states' points sit side by side), the fit
    and its band (the band only where the fit is bounded; the median's bracket when beta is open)."""
    ok = st.trials > 0
    p = st.probability[ok]
    bounds = np.array([wilson_interval(int(k), int(n)) for k, n in zip(st.exceeded[ok], st.trials[ok])])
    yerr = np.vstack([p - bounds[:, 0], bounds[:, 1] - p]) if bounds.size else None
    ax.errorbar(W[ok] * dodge, p, yerr=yerr, fmt="o", ms=4, capsize=2, color=color, label=f"{label}: observed")
    f = st.fit
    if f is not None and f.beta is None:  # complete separation: only the bracket of the median is known
        ax.axvspan(
            f.median_ci_kg[0],
            f.median_ci_kg[1],
            color=color,
            alpha=0.12,
            label=f"{label}: median between {f.median_ci_kg[0]:.4g} and {f.median_ci_kg[1]:.4g} kg",
        )
    elif f is not None:
        x = np.geomspace(W.min() / 1.2, W.max() * 1.2, 300)
        band = f.band(x) if f.bounded else None
        if band is not None:
            ax.fill_between(x, band[0], band[1], color=color, alpha=0.15, lw=0)
        ax.plot(
            x,
            f.probability(x),
            "-",
            color=color,
            label=f"{label}: lognormal fit, median {f.median_charge_kg:.4g} kg "
            f"[{f.median_ci_kg[0]:.4g}, {f.median_ci_kg[1]:.4g}], beta {f.beta:.3g}",
        )


def plot_fragility(result, ax=None):
    """P(state reached | W) per damage state: observed fractions with 95 % Wilson intervals, the lognormal fit
    and its 95 % band (module docstring).

    Parameters
    ----------
    result : FragilityResult
    ax : matplotlib.axes.Axes, optional

    Returns
    -------
    matplotlib.axes.Axes
    """
    if ax is None:
        import matplotlib.pyplot as plt

        _, ax = plt.subplots(figsize=(7.5, 5.0), layout="constrained")
    from matplotlib.ticker import LogLocator, NullFormatter, ScalarFormatter

    W = np.asarray(result.charge_kg, dtype=float)
    n = len(result.states)
    for i, (name, st) in enumerate(result.states.items()):
        _draw_state(ax, W, st, f"C{i}", _state_label(name, result.criterion), 1.0 + 0.012 * (i - (n - 1) / 2))
    ax.set_xscale("log")
    ax.xaxis.set_major_locator(LogLocator(subs=(1.0, 2.0, 5.0)))
    ax.xaxis.set_major_formatter(ScalarFormatter())
    ax.xaxis.set_minor_formatter(NullFormatter())  # plain numbers at 1, 2, 5 x 10^k, not 2 x 10^0
    ax.set_ylim(-0.02, 1.02)
    ax.set_xlabel("charge W [kg TNT]")
    ax.set_ylabel("probability of reaching the state")
    how = "first swing of the block" if result.criterion == "first-swing" else "damage states, one run per draw"
    fields = "; ".join(field_words(v["path"], v) for v in result.fields.values())
    ax.set_title(
        f"Fragility of the prototype ({how}, {result.samples} draws per charge)\nuncertain: {fields}", fontsize=9
    )
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7, loc="upper left")
    return ax
