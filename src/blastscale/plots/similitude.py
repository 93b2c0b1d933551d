"""Plots of the blast scaling factors vs lambda or gamma (paper Figs. 5 and 8).

Every function takes ``ax=`` (a new figure's axes when None) and returns it; matplotlib is
imported only when a plot is drawn. Input: :class:`~blastscale.similitude.curves.ScalingCurves`
from :func:`~blastscale.similitude.curves.scaling_curves`. As in the paper, the general law is
drawn solid and Hopkinson-Cranz dashed, in the same colour; points where the general law has
no root inside the fits (``valid`` False) are NaN and leave a gap. Axes are logarithmic
(ratios span decades), except lambda_Z, which stays within one decade (linear).
"""

from __future__ import annotations

import numpy as np

from .._validate import BlastscaleInputError, check_choice
from .sim3d import axes_or_new

__all__ = [
    "FACTOR_PLOTS",
    "plot_scaling_factor",
    "plot_pressure_ratio",
    "plot_scaled_distance_factor",
    "plot_impulse_ratio",
    "plot_duration_ratio",
    "scaling_factors_figure",
]

#: quantity -> (general-law field, Hopkinson-Cranz field, y label, log y axis)
FACTOR_PLOTS = {
    "pressure": ("pressure_ratio", "hc_pressure_ratio", "overpressure factor P_ro,m / P_ro,p [-]", True),
    "scaled_distance": (
        "scaled_distance_factor",
        "hc_scaled_distance_factor",
        "scaled-distance factor lambda_Z = Z_m / Z_p [-]",
        False,
    ),
    "impulse": ("impulse_ratio", "hc_impulse_ratio", "impulse factor i_ro,m / i_ro,p [-]", True),
    "duration": ("duration_ratio", "hc_duration_ratio", "duration factor t_o,m / t_o,p [-]", True),
}

_X = {"scale": "geometric scale lambda [-]", "density_ratio": "density ratio gamma [-]"}


def _sweep_axis(curves, x: str | None) -> str:
    """``"scale"`` or ``"density_ratio"``: the given one, else the one the curves vary in."""
    if x is None:
        x = "scale" if np.ptp(curves.scale) > 0 or np.ptp(curves.density_ratio) == 0 else "density_ratio"
    return check_choice("x", x, _X)


def _default_label(curves, x: str) -> str:
    if x == "scale":
        g = np.unique(curves.density_ratio)
        return f"gamma = {g[0]:.3g}" if g.size == 1 else "general law"
    lam = float(np.ravel(curves.scale)[0])
    return f"lambda = 1/{1 / lam:.4g}" if lam < 1 else f"lambda = {lam:.4g}"


def _readable_log_y(ax) -> None:
    """Label 1, 2, 5 x 10^k on a log y axis spanning less than 3 decades (otherwise only one
    or two powers of ten would carry a label)."""
    from matplotlib.ticker import LogFormatterSciNotation, LogLocator, NullFormatter

    lo, hi = ax.get_ylim()
    if hi > lo > 0 and np.log10(hi / lo) < 3.0:
        ax.yaxis.set_major_locator(LogLocator(base=10.0, subs=(1.0, 2.0, 5.0)))
        ax.yaxis.set_major_formatter(LogFormatterSciNotation(labelOnlyBase=False, minor_thresholds=(np.inf, np.inf)))
        ax.yaxis.set_minor_formatter(NullFormatter())


def plot_scaling_factor(
    curves,
    quantity: str = "pressure",
    ax=None,
    x: str | None = None,
    label: str | None = None,
    hopkinson_cranz: bool = True,
    color=None,
    legend: bool = True,
):
    """One scaling factor vs lambda or gamma: general law solid, Hopkinson-Cranz dashed.

    Parameters
    ----------
    curves : ScalingCurves
        Output of :func:`~blastscale.similitude.curves.scaling_curves` (1-D sweep).
    quantity : {"pressure", "scaled_distance", "impulse", "duration"}
        Factor drawn (paper Fig. 5/8 panels a, b, c; duration is an extra) [-].
    ax : matplotlib Axes, optional
    x : {"scale", "density_ratio"}, optional
        Abscissa: lambda [-] (Fig. 5) or gamma [-] (Fig. 8); default the one the curves vary in.
    label : str, optional
        Legend label of the general-law line (default names the fixed gamma or lambda).
    hopkinson_cranz : bool
        Also draw the Hopkinson-Cranz factor dashed (constant in gamma: that law imposes
        gamma = 1/sqrt(lambda) whatever the material).
    color : matplotlib colour, optional
        Shared by both lines (default: the axes' next colour).
    legend : bool
        Draw the axes' legend (off when a figure carries one legend for all panels).

    Returns
    -------
    matplotlib Axes
    """
    check_choice("quantity", quantity, FACTOR_PLOTS)
    ax = axes_or_new(ax)
    x = _sweep_axis(curves, x)
    gen, hc, ylabel, logy = FACTOR_PLOTS[quantity]
    xs = np.ravel(getattr(curves, x))
    lab = label or _default_label(curves, x)
    (line,) = ax.plot(xs, np.ravel(getattr(curves, gen)), "-", color=color, label=f"{lab}, general law")
    if hopkinson_cranz:
        if x == "scale":  # Hopkinson-Cranz imposes its own density ratio: it is not the general law's gamma
            hc_lab = "Hopkinson-Cranz (gamma = 1/sqrt(varsigma lambda) imposed)"
        else:
            hc_lab = f"{lab}, Hopkinson-Cranz (gamma = {float(np.ravel(curves.hc_density_ratio)[0]):.3g} imposed)"
        ax.plot(xs, np.ravel(getattr(curves, hc)), "--", color=line.get_color(), label=hc_lab)
    ax.set_xscale("log")
    if logy:
        ax.set_yscale("log")
        _readable_log_y(ax)
    ax.set_xlabel(_X[x])
    ax.set_ylabel(ylabel)
    ax.grid(True, which="both", alpha=0.3)
    if legend:
        ax.legend(fontsize="small")
    return ax


def plot_pressure_ratio(curves, ax=None, **kwargs):
    """Peak reflected overpressure factor [-] (paper Figs. 5a, 8a); see :func:`plot_scaling_factor`."""
    return plot_scaling_factor(curves, "pressure", ax, **kwargs)


def plot_scaled_distance_factor(curves, ax=None, **kwargs):
    """Scaled-distance factor lambda_Z [-] (paper Figs. 5b, 8b); see :func:`plot_scaling_factor`."""
    return plot_scaling_factor(curves, "scaled_distance", ax, **kwargs)


def plot_impulse_ratio(curves, ax=None, **kwargs):
    """Reflected impulse factor [-] (paper Figs. 5c, 8c); see :func:`plot_scaling_factor`."""
    return plot_scaling_factor(curves, "impulse", ax, **kwargs)


def plot_duration_ratio(curves, ax=None, **kwargs):
    """Positive-duration factor [-] (not in the paper's figures); see :func:`plot_scaling_factor`."""
    return plot_scaling_factor(curves, "duration", ax, **kwargs)


def scaling_factors_figure(
    curves, x: str | None = None, labels=None, quantities=("pressure", "scaled_distance", "impulse")
):
    """Paper Fig. 5 / Fig. 8 layout: one panel per factor, (a) overpressure, (b) scaled
    distance, (c) impulse, for one or several sweeps (e.g. the two lambdas of Fig. 8).

    ``curves``: a ScalingCurves or a sequence of them; ``labels``: one legend label per sweep.
    One legend below the panels serves them all. Returns the figure.
    """
    import matplotlib.pyplot as plt

    runs = list(curves) if isinstance(curves, (list, tuple)) else [curves]
    labels = list(labels) if labels is not None else [None] * len(runs)
    if len(labels) != len(runs):
        raise BlastscaleInputError(f"labels has {len(labels)} entries: must have one per sweep ({len(runs)})")
    fig, axes = plt.subplots(1, len(quantities), figsize=(5 * len(quantities), 4.6), layout="constrained")
    axes = np.atleast_1d(axes)
    for k, (ax, q) in enumerate(zip(axes, quantities)):
        for j, (c, lab) in enumerate(zip(runs, labels)):
            plot_scaling_factor(c, q, ax=ax, x=x, label=lab, color=f"C{j}", legend=False)
        ax.set_title(f"({chr(ord('a') + k)}) {q.replace('_', ' ')}")
    handles, texts = axes[0].get_legend_handles_labels()
    fig.legend(handles, texts, loc="outside lower center", ncol=min(len(texts), 4), fontsize="small")
    return fig
