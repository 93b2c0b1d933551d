"""Plots of the shot as fired: gauge traces over their fits and the predicted pulse, marker histories over the
prediction and the re-simulation (docs/fired.md). Every function takes ``ax=`` and returns it; the inputs are
plain arrays (SI: s, Pa, m); matplotlib is imported only when a plot is drawn."""

from __future__ import annotations

import numpy as np

from ..analysis.upscale import upscale
from .sim3d import axes_or_new

__all__ = ["plot_gauge", "plot_marker"]


def plot_gauge(t, p, fitted, predicted=None, *, name: str = "gauge", ax=None):
    """A gauge's baselined trace ``p`` [Pa] at ``t`` [s], its fit ``fitted`` [Pa] (same times) and the
    predicted pulse ``predicted`` [Pa] (same times; None: not drawn), in kPa and ms."""
    ax = axes_or_new(ax)
    t = np.asarray(t) * 1e3
    ax.plot(t, np.asarray(p) / 1e3, color="0.6", lw=0.6, label=f"{name} (record)")
    ax.plot(t, np.asarray(fitted) / 1e3, color="C0", lw=1.4, label="Friedlander fit")
    if predicted is not None:
        ax.plot(t, np.asarray(predicted) / 1e3, color="C3", lw=1.0, ls="--", label="predicted (designed charge)")
    ax.set_xlabel("time after firing [ms]")
    ax.set_ylabel("overpressure [kPa]")
    ax.legend(fontsize="small")
    return ax


def plot_marker(
    measured,
    predicted,
    refit,
    *,
    name: str = "marker",
    factors=None,
    units: str = "specimen",
    peak=None,
    ax=None,
):
    """A marker's horizontal displacement: ``measured``, ``predicted`` and ``refit``, each ``(t [s], ux [m])``;
    in the specimen's units, or with ``factors`` (the design's :class:`~blastscale.similitude.ScalingFactors`)
    up-scaled to the prototype's (:func:`~blastscale.analysis.upscale.upscale`), shown in mm (specimen) or m (prototype) and s.
    ``peak``: the detected first peak of the measured track ``(t [s], u [m])`` (None: none found), marked with a
    cross and its value."""
    ax = axes_or_new(ax)
    k = 1e3 if units == "specimen" else 1.0
    if peak is not None:
        tp, up = float(peak[0]), k * float(peak[1])
        if factors is not None:
            tp, up = float(upscale(tp, factors, "time")), float(upscale(up, factors, "length"))
        unit = "mm" if units == "specimen" else "m"
        ax.plot(
            [tp], [up], "x", color="k", ms=9, mew=2, zorder=5, label=f"first peak found: {up:.4g} {unit} at {tp:.3g} s"
        )
        ax.axvline(tp, color="k", lw=0.5, ls=":")
    for (t, u), style, label in (
        (measured, {"color": "0.3", "lw": 0.8}, "measured"),
        (predicted, {"color": "C3", "ls": "--", "lw": 1.2}, "predicted (designed load)"),
        (refit, {"color": "C0", "lw": 1.4}, "re-simulated (as fired)"),
    ):
        t, u = np.asarray(t), k * np.asarray(u)
        if factors is not None:
            t, u = upscale(t, factors, "time"), upscale(u, factors, "length")
        ax.plot(t, u, label=label, **style)
    ax.set_xlabel(f"time after firing [s] ({units})")
    # the marker and the units in the title: a label "M1: horizontal displacement [mm] (specimen)" is longer
    # than the figure is high (issue #39)
    ax.set_ylabel(f"horizontal displacement [{'mm' if units == 'specimen' else 'm'}]")
    ax.set_title(f"{name} ({units})", fontsize=9)
    ax.legend(fontsize="small")
    return ax
