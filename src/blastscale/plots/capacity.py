"""Plots of overturning capacity: the critical charge curve W_c(R) of a prototype and of its
up-scaled model, with the safe stand-off of a given charge.

Every function takes ``ax=`` (a new figure's axes when None) and returns it; matplotlib is
imported only when a plot is drawn. Inputs are :class:`~blastscale.rocking.capacity.CapacityCurve`
and :class:`~blastscale.analysis.capacity.ModelCapacity` (SI: charges in kg TNT, stand-offs in m).
"""

from __future__ import annotations

import numpy as np

__all__ = ["plot_capacity", "plot_capacity_3d"]


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


def _errors(centre, interval) -> np.ndarray:
    """Asymmetric error bars (2, n) from centres and [lo, hi] intervals (NaN where absent)."""
    c = np.array([np.nan if x is None else x for x in centre], dtype=float)
    iv = np.array([[np.nan, np.nan] if x is None else x for x in interval], dtype=float).reshape(-1, 2)
    return c, np.vstack([c - iv[:, 0], iv[:, 1] - c])


def plot_capacity_3d(results, pressure_impulse, *, ax=None):
    """The 3D capacity of any structure: W_c(R) with its intervals, and the pressure-impulse diagram.

    Parameters
    ----------
    results : sequence of Critical3D
        The critical charge [kg] at each stand-off [m] with its interval
        (:func:`blastscale.sweeps.capacity3d.critical_charges_3d`).
    pressure_impulse : dict
        Their reflected pressures [Pa] and impulses [Pa s], with the intervals' ends
        (:func:`blastscale.sweeps.capacity3d.pressure_impulse_points`).
    ax : sequence of two Axes, optional
        The W_c(R) and the P-I axes (a new figure's when None).

    Returns
    -------
    Axes
        The W_c(R) axes (``.figure`` the figure).
    """
    if ax is None:
        import matplotlib.pyplot as plt

        _, ax = plt.subplots(1, 2, figsize=(10, 4.2), layout="constrained")
    a1, a2 = ax
    R = np.array([c.standoff_m for c in results], dtype=float)
    W, eW = _errors([c.critical_charge_kg for c in results], [c.interval_kg for c in results])
    a1.errorbar(R, W, yerr=eW, fmt="o-", color="C0", capsize=3, label="critical charge, interval")
    a1.set_xscale("log")
    a1.set_yscale("log")
    a1.set_xlabel("stand-off R [m]")
    a1.set_ylabel("critical charge W_c [kg TNT]")
    a1.set_title("Charge at which half the runs collapse", fontsize=10)
    a1.grid(True, which="both", alpha=0.3)
    a1.legend(fontsize=8)
    pi = pressure_impulse
    i, ei = _errors(pi["reflected_impulse_Pa_s"], pi["interval_impulse_Pa_s"])
    p, ep = _errors(pi["reflected_pressure_Pa"], pi["interval_pressure_Pa"])
    a2.errorbar(i, p, xerr=ei, yerr=ep, fmt="s-", color="C3", capsize=3, label="collapse threshold")
    for r, x, y in zip(R, i, p):
        if np.isfinite(x):
            a2.annotate(f"{r:g} m", (x, y), textcoords="offset points", xytext=(5, 4), fontsize=7)
    a2.set_xscale("log")
    a2.set_yscale("log")
    a2.set_xlabel("reflected impulse i_r [Pa s]")
    a2.set_ylabel("reflected pressure P_r [Pa]")
    a2.set_title("Pressure-impulse diagram (collapse above and right)", fontsize=10)
    a2.grid(True, which="both", alpha=0.3)
    a2.legend(fontsize=8)
    return a1
