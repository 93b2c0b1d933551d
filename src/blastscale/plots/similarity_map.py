"""Similarity-map plot: for each (charge, stand-off) panel, the up-scaled model's error over the
(lambda, gamma) grid as a table of cells, each cell labelled with its value, the cases whose outcome
disagrees marked and those the blast fits cannot design left grey.

The cells are drawn one per grid point, equally sized, the ticks at the grid's own values (``1/20``,
``0.889``): a grid of a few values on a logarithmic axis reads as ``9x10^-1 / 10^0`` and squeezes its
cells, a table of cells does not (issue #39). The colour scale is logarithmic when the errors span more
than a decade, linear otherwise. Takes the dataset of
:func:`blastscale.sweeps.similarity_map.similarity_map`; matplotlib is imported only when drawn. Returns
the figure.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["plot_similarity_map", "grid_label"]

#: Largest font size of a cell's value [pt]; smaller when the cell is narrow (never below :data:`_MIN_FONT`).
_CELL_FONT = 8.0
_MIN_FONT = 5.0
#: Figure size per cell [in] (width per lambda, height per gamma) and the fixed part of a panel [in].
_CELL_W, _CELL_H, _PANEL_W, _PANEL_H = 0.62, 0.36, 1.3, 1.1


def grid_label(value: float) -> str:
    """A grid value as a person reads it: ``1/20`` for 0.05 (a scale 1/n), else 3 significant digits.

    >>> grid_label(0.05), grid_label(0.8889), grid_label(1.0)
    ('1/20', '0.889', '1')
    """
    v = float(value)
    if 0 < v < 1:
        n = 1.0 / v
        if abs(n - round(n)) <= 1e-6 * n and round(n) >= 2:
            return f"1/{round(n)}"
    return f"{v:.3g}"


def _cell_text(v: float) -> str:
    """A cell's value in at most 2 significant digits (``0.012``, ``3e-05``)."""
    if not np.isfinite(v):
        return ""
    return f"{v:.2g}".replace("e-0", "e-").replace("e+0", "e")


def _norm(finite: np.ndarray):
    """Log colour scale when the errors span more than a decade, else linear (None: nothing to colour)."""
    from matplotlib.colors import LogNorm, Normalize

    if not finite.size:
        return None
    pos = finite[finite > 0]
    if pos.size and pos.max() / pos.min() > 10.0:
        return LogNorm(vmin=float(pos.min()), vmax=float(pos.max()))
    lo, hi = float(finite.min()), float(finite.max())
    return Normalize(vmin=min(lo, 0.0), vmax=hi if hi > 0 else 1.0)


def _ticks(ax, axis: str, values) -> None:
    """Ticks at every grid value (every k-th when there are more than 8), labelled :func:`grid_label`."""
    n = len(values)
    step = max(1, math.ceil(n / 8))
    idx = list(range(0, n, step))
    labels = [grid_label(values[i]) for i in idx]
    if axis == "x":
        ax.set_xticks(idx, labels, rotation=45 if n > 5 else 0, ha="right" if n > 5 else "center", fontsize=8)
    else:
        ax.set_yticks(idx, labels, fontsize=8)


def _panel(ax, ds, i: int, j: int, norm, cmap, font: float):
    """One (charge, stand-off) panel in grid-index coordinates; returns the mesh."""
    from matplotlib.colors import LogNorm

    lam, gam = ds["length"].values, ds["density_ratio"].values
    e = ds["error"].values[:, :, i, j].T  # (gamma, lambda)
    valid = ds["valid"].values[:, :, i, j].T.astype(bool)
    agree = ds["outcomes_agree"].values[:, :, i, j].T.astype(bool)
    ax.set_facecolor("0.85")
    shown = np.where(valid & np.isfinite(e), e, np.nan)
    if isinstance(norm, LogNorm):  # a log scale cannot show 0: such a cell keeps its value, uncoloured
        shown = np.where(shown > 0, shown, np.nan)
    x, y = np.arange(lam.size + 1) - 0.5, np.arange(gam.size + 1) - 0.5
    mesh = ax.pcolormesh(x, y, shown, norm=norm, cmap=cmap, edgecolors="w", linewidth=0.5)
    for g in range(gam.size):
        for k in range(lam.size):
            if not valid[g, k]:
                ax.text(k, g, "no\ndesign", ha="center", va="center", fontsize=font * 0.8, color="0.35")
                continue
            v = e[g, k]
            text = _cell_text(v) or "n/a"
            dark = bool(np.isfinite(shown[g, k]) and norm is not None and norm(shown[g, k]) < 0.6)
            color = "w" if dark else "k"
            if not agree[g, k]:
                text = "\u00d7 " + text  # the outcome differs (a multiplication sign, in every font)
                ax.add_patch(_cell_frame(k, g))
            ax.text(k, g, text, ha="center", va="center", fontsize=font, color=color)
    if valid.any() and lam.size > 1 and gam.size > 1:
        worst = ds["worst_ratio"].values[:, :, i, j].T
        ax.contour(np.arange(lam.size), np.arange(gam.size), np.where(valid, worst, np.nan), levels=[1.0], colors="w")
    ax.set_xlim(-0.5, lam.size - 0.5)
    ax.set_ylim(-0.5, gam.size - 0.5)
    _ticks(ax, "x", lam)
    _ticks(ax, "y", gam)
    return mesh


def _cell_frame(k: int, g: int):
    from matplotlib.patches import Rectangle

    return Rectangle((k - 0.47, g - 0.47), 0.94, 0.94, fill=False, edgecolor="C3", linewidth=1.6)


def plot_similarity_map(ds, fig=None):
    """One panel per (charge, stand-off): the model's error (planar: angle [rad], 3D: relative top
    displacement [-]) in a cell per (lambda, gamma), its value written in the cell; a red frame and
    ``x`` before the value: the outcomes disagree; grey "no design": the blast fits cannot design the
    case; white contour: the verdict's limit (worst ratio = 1, docs/verdict.md). Module docstring for the
    layout. Returns the figure."""
    import matplotlib.pyplot as plt

    W, R = ds["charge_kg"].values, ds["standoff_m"].values
    lam, gam = ds["length"].values, ds["density_ratio"].values
    if fig is None:
        w = R.size * max(3.4, _PANEL_W + _CELL_W * lam.size) + 1.4
        h = W.size * max(2.6, _PANEL_H + _CELL_H * gam.size) + 0.9
        fig = plt.figure(figsize=(w, h), layout="constrained")
    axes = np.atleast_2d(fig.subplots(W.size, R.size, squeeze=False))
    err = ds["error"].values
    finite = err[np.isfinite(err) & ds["valid"].values.astype(bool)]
    norm = _norm(finite)
    # the cell's font: 8 pt, smaller in a narrow cell (7 characters across ~0.9 of the cell's width)
    cell_pt = 72.0 * (fig.get_figwidth() - 1.4) / max(R.size, 1) * 0.8 / max(lam.size, 1)
    font = float(np.clip(cell_pt * 0.9 / (0.6 * 7), _MIN_FONT, _CELL_FONT))
    mesh = None
    for i, w_kg in enumerate(W):
        for j, r in enumerate(R):
            ax = axes[i, j]
            mesh = _panel(ax, ds, i, j, norm, "viridis", font)
            ax.set_title(f"W = {w_kg:g} kg, R = {r:g} m", fontsize=9)
            if i == W.size - 1:
                ax.set_xlabel("scale lambda [-]", fontsize=9)
            if j == 0:
                ax.set_ylabel("density ratio gamma [-]", fontsize=9)
    unit = ds.attrs.get("error_units", "rad")
    if mesh is not None and norm is not None:
        what = "angle error to tipping [rad]" if unit == "rad" else "top displacement error / peak [-]"
        fig.colorbar(mesh, ax=axes, label=what, shrink=0.9)
    fig.suptitle(f"Similarity map ({ds.attrs.get('engine', 'planar')}): the up-scaled model's error", fontsize=10)
    fig.supxlabel(
        "red frame, \u00d7: outcomes differ; grey: no design; white line: the verdict's limit",
        fontsize=8,
        wrap=True,
    )
    return fig
