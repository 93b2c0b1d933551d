"""The plan's candidates: scale lambda against the specimen's charge (TNT-equivalent impulse mass,
both axes logarithmic), one panel per specimen material (the materials of one scale share a lambda and
differ little in charge: on one axes they hide each other). In each panel: feasible designs coloured by
the odds that the specimen's outcome agrees with the prototype's (hollow where only screened), rejected
candidates grey, one marker per first reason, the Pareto-optimal designs ringed and the first design (the
recommended one, or the closest) starred behind its marker, so that its odds stay visible. When every
design has the same odds the colour bar says nothing: the odds are then written in the legend instead.
The title names the 3D load method the plan assumed. Takes a :class:`~blastscale.planning.Plan`; ``fig=``
a figure to draw on (a new one when None); matplotlib imported only when drawn. Returns the figure.
"""

from __future__ import annotations

import math

from .similarity_map import grid_label

__all__ = ["plot_plan"]

_MARKERS = ("x", "+", "1", "v", "^", "<", ">", "s", "D", "p", "h")
#: Panels per row.
_COLUMNS = 3


def _material(d: dict) -> str:
    return d.get("material") or "specimen"


def _materials(p) -> list:
    """The specimen materials of the plan's designs and rejected candidates, the first design's first."""
    seen: list = []
    for d in list(p.designs) + [r for r in p.rejected if r.get("tnt_equivalent_kg") is not None]:
        if _material(d) not in seen:
            seen.append(_material(d))
    return seen


def plot_plan(p, fig=None):
    """Every candidate of ``p``, one panel per material (module docstring). Returns the figure."""
    import matplotlib.pyplot as plt
    from matplotlib.ticker import NullLocator

    mats = _materials(p) or ["specimen"]
    ncol = min(_COLUMNS, len(mats))
    nrow = math.ceil(len(mats) / ncol)
    if fig is None:
        fig = plt.figure(figsize=(1.0 + 3.6 * ncol, 1.6 + 3.1 * nrow), layout="constrained")
    axes = fig.subplots(nrow, ncol, squeeze=False, sharex=True, sharey=True)
    odds = [d["p_outcome_agree"] for d in p.designs if d.get("p_outcome_agree") is not None]
    same = len(odds) > 0 and max(odds) - min(odds) < 0.005
    scales = sorted({d["scale"] for d in list(p.designs) + list(p.rejected) if d.get("scale")})
    step = max(1, math.ceil(len(scales) / 6))  # at most 6 labelled scales: a label never runs into the next
    mesh = None
    for k, ax in enumerate(axes.flat):
        if k >= len(mats):
            ax.set_visible(False)
            continue
        mesh = _panel(ax, p, mats[k], same) or mesh
        ax.set_title(mats[k], fontsize=9)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.grid(True, which="both", alpha=0.3)
        if k % ncol == 0:
            ax.set_ylabel("specimen charge [kg TNT, impulse]", fontsize=8)
        if k >= len(mats) - ncol:  # the lowest panel of its column
            ax.set_xlabel("scale lambda [-]", fontsize=8)
            ax.xaxis.set_tick_params(labelbottom=True)
        ax.set_xticks(scales[::step], [grid_label(s) for s in scales[::step]])
        ax.xaxis.set_minor_locator(NullLocator())
        ax.tick_params(labelsize=7)
        ax.legend(fontsize=6, loc="upper left")
    if mesh is not None and not same:
        fig.colorbar(mesh, ax=axes, label="P(outcome agrees)", shrink=0.8)
    method = (p.prototype or {}).get("load_method")
    load = f"; 3D load: Method {method}" if method else ""
    fig.suptitle(f"Plan: every candidate by material{load}", fontsize=10)
    return fig


def _panel(ax, p, material: str, same: bool):
    """The candidates of one material on ``ax``; returns the odds' collection (None without one)."""
    mine = [d for d in p.designs if _material(d) == material]
    reasons: dict = {}
    for r in p.rejected:
        if r.get("tnt_equivalent_kg") is not None and _material(r) == material:
            reasons.setdefault(r["constraints"][0], []).append((r["scale"], r["tnt_equivalent_kg"]))
    for k, (key, pts) in enumerate(sorted(reasons.items(), key=lambda kv: -len(kv[1]))):
        x, y = zip(*pts)
        ax.scatter(
            x, y, marker=_MARKERS[k % len(_MARKERS)], color="0.6", s=20, lw=0.8, label=f"rejected: {key} ({len(pts)})"
        )
    if p.designs and _material(p.designs[0]) == material:
        first = "recommended" if p.recommendation.get("design") == 0 else "closest (none passes)"
        # the star behind the design's own marker, larger: the marker's odds stay visible inside it
        _scatter(
            ax, [p.designs[0]], marker="*", facecolors="#ffd54f", edgecolors="C3", s=360, lw=1.0, zorder=2, label=first
        )
    screened = [d for d in mine if d.get("p_outcome_agree") is None]
    if screened:
        _scatter(
            ax, screened, facecolors="none", edgecolors="C0", s=30, zorder=3, label=f"screened only ({len(screened)})"
        )
    odds = [d for d in mine if d.get("p_outcome_agree") is not None]
    mesh = None
    if odds:
        label = f"with odds ({len(odds)})"
        if same:
            label = f"with odds {odds[0]['p_outcome_agree']:.2f} ({len(odds)})"
        mesh = _scatter(
            ax,
            odds,
            c=[d["p_outcome_agree"] for d in odds],
            cmap="viridis",
            vmin=0.0,
            vmax=1.0,
            s=36,
            edgecolors="k",
            linewidths=0.4,
            zorder=4,
            label=label,
        )
    front = [d for d in mine if d.get("pareto")]
    if front:
        _scatter(
            ax,
            front,
            facecolors="none",
            edgecolors="C3",
            s=110,
            lw=1.2,
            zorder=5,
            label=f"Pareto-optimal ({len(front)})",
        )
    return mesh


def _scatter(ax, designs, **style):
    """Scatter ``designs`` (dicts of the plan) at their scale lambda [-] and specimen charge [kg TNT];
    ``style``: :meth:`matplotlib.axes.Axes.scatter`'s keywords. Returns its collection."""
    return ax.scatter([d["scale"] for d in designs], [d["tnt_equivalent_kg"] for d in designs], **style)
