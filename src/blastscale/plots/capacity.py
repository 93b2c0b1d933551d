"""Plots of overturning capacity: the critical charge curve W_c(R) of a prototype and of its
up-scaled model, with the safe stand-off of a given charge.

Every function takes ``ax=`` (a new figure's axes when None) and returns it; matplotlib is
imported only when a plot is drawn. Inputs are :class:`~blastscale.rocking.capacity.CapacityCurve`
and :class:`~blastscale.analysis.capacity.ModelCapacity` (SI: charges in kg TNT, stand-offs in m).
"""

from __future__ import annotations

import numpy as np

__all__ = ["plot_capacity"]


def plot_capacity(curve, model=None, *, charge=None, safe_standoff=None, ax=None, label: str = "prototype"):
    """Critical charge against stand-off on log-log axes; the region above the curve overturns.

    Parameters
    ----------
    curve : CapacityCurve
        Prototype W_c(R) [kg] at R [m].
    model : ModelCapacity, optional
        The reduced-scale model's curve, up-scaled to prototype charges (markers).
    charge, safe_standoff : float, optional
        A charge [kg] and its safe stand-off [m], marked on the curve.
    """
    if ax is None:
        import matplotlib.pyplot as plt

        _, ax = plt.subplots(figsize=(6, 4.5), layout="constrained")
    R, W = curve.standoff_m, curve.critical_charge_kg
    ax.loglog(R, W, "-", color="C0", label=f"{label} W_c(R)")
    ok = np.isfinite(W)
    if np.any(ok):
        ax.fill_between(R[ok], W[ok], np.nanmax(W) * 10, color="C3", alpha=0.08, label="overturns")
        ax.set_ylim(np.nanmin(W) / 2, np.nanmax(W) * 2)
    if model is not None:
        ax.loglog(
            R,
            model.upscaled_charge_kg,
            "o",
            ms=4,
            mfc="none",
            color="C1",
            label=f"model lambda = {model.scale:g}, gamma = {model.density_ratio:g} (up-scaled)",
        )
    if charge is not None and safe_standoff is not None and np.isfinite(safe_standoff):
        ax.plot([safe_standoff], [charge], "s", color="C3", label=f"{charge:g} kg: safe beyond {safe_standoff:.4g} m")
    ax.set_xlabel("stand-off R [m]")
    ax.set_ylabel("critical charge W_c [kg TNT]")
    ax.set_title(f"Overturning capacity ({curve.blast_model}, {curve.pulse_shape})", fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    return ax
