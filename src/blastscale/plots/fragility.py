"""Fragility plot: the empirical probability of overturning against the charge (binomial 95 %
bars) and the fitted lognormal curve with its median.

Takes a :class:`~blastscale.sweeps.fragility.FragilityResult` (charges in kg TNT); ``ax=`` as
every plot function (a new figure's axes when None); matplotlib imported only when drawn.
"""

from __future__ import annotations

import numpy as np

__all__ = ["plot_fragility"]


def plot_fragility(result, ax=None, label: str = "Monte Carlo"):
    """P(overturn | W) points with 1.96 binomial standard errors and the lognormal fit."""
    if ax is None:
        import matplotlib.pyplot as plt

        _, ax = plt.subplots(figsize=(6.5, 4.5), layout="constrained")
    W, p, n = result.charge_kg, result.probability, result.samples
    ax.errorbar(
        W,
        p,
        yerr=1.96 * result.standard_error,
        fmt="o",
        ms=4,
        capsize=2,
        color="C0",
        label=f"{label} ({n} draws per charge)",
    )
    f = result.fit
    if f is not None and f.beta is None:  # complete separation: only the bracket of the median is known
        ax.axvspan(
            f.median_ci_kg[0],
            f.median_ci_kg[1],
            color="C3",
            alpha=0.12,
            label=f"median between {f.median_ci_kg[0]:.4g} and {f.median_ci_kg[1]:.4g} kg (beta not bounded)",
        )
    elif f is not None:
        x = np.geomspace(W.min() / 1.2, W.max() * 1.2, 300)
        ax.plot(
            x,
            f.probability(x),
            "-",
            color="C3",
            label=f"lognormal fit: median {f.median_charge_kg:.4g} kg "
            f"[{f.median_ci_kg[0]:.4g}, {f.median_ci_kg[1]:.4g}], beta {f.beta:.3g}",
        )
        ax.axvline(f.median_charge_kg, color="C3", lw=0.8, ls=":")
    ax.set_xscale("log")
    ax.set_ylim(-0.02, 1.02)
    ax.set_xlabel("charge W [kg TNT]")
    ax.set_ylabel("P(overturn | W)")
    ax.set_title("Fragility: " + ", ".join(f"{k} ({v['distribution']})" for k, v in result.fields.items()), fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    return ax
