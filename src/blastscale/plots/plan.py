"""The plan's candidates: scale lambda against the specimen's charge (TNT-equivalent impulse mass,
both axes logarithmic); feasible designs coloured by the odds that the specimen's outcome agrees with
the prototype's (hollow where only screened), rejected candidates grey, one marker per first reason,
the Pareto-optimal designs ringed. Takes a :class:`~blastscale.planning.Plan`; ``ax=`` as every
plot function (a new figure's axes when None); matplotlib imported only when drawn.
"""

from __future__ import annotations

__all__ = ["plot_plan"]

_MARKERS = ("x", "+", "1", "v", "^", "<", ">", "s", "D", "p", "*", "h")


def plot_plan(p, ax=None):
    """Every candidate of ``p`` (module docstring)."""
    if ax is None:
        import matplotlib.pyplot as plt

        _, ax = plt.subplots(figsize=(7.0, 4.8), layout="constrained")
    reasons: dict = {}
    for r in p.rejected:
        if r.get("tnt_equivalent_kg") is not None:
            reasons.setdefault(r["constraints"][0], []).append((r["scale"], r["tnt_equivalent_kg"]))
    for k, (key, pts) in enumerate(sorted(reasons.items(), key=lambda kv: -len(kv[1]))):
        x, y = zip(*pts)
        ax.scatter(
            x, y, marker=_MARKERS[k % len(_MARKERS)], color="0.6", s=22, lw=0.8, label=f"rejected: {key} ({len(pts)})"
        )
    odds = [d for d in p.designs if d["p_outcome_agree"] is not None]
    screened = [d for d in p.designs if d["p_outcome_agree"] is None]
    if screened:
        _scatter_designs(
            ax,
            screened,
            facecolors="none",
            edgecolors="C0",
            s=30,
            label=f"feasible, screened only ({len(screened)})",
        )
    if odds:
        sc = _scatter_designs(
            ax,
            odds,
            c=[d["p_outcome_agree"] for d in odds],
            cmap="viridis",
            vmin=0.0,
            vmax=1.0,
            s=36,
            edgecolors="k",
            linewidths=0.4,
            zorder=3,
            label=f"feasible, with odds ({len(odds)})",
        )
        ax.figure.colorbar(sc, ax=ax, label="P(outcome agrees)")
    front = [d for d in p.designs if d.get("pareto")]
    if front:
        _scatter_designs(
            ax,
            front,
            facecolors="none",
            edgecolors="C3",
            s=110,
            lw=1.4,
            zorder=4,
            label=f"Pareto-optimal ({len(front)})",
        )
    first = (
        "recommended design" if p.recommendation.get("design") == 0 else "closest design (the criterion passes none)"
    )
    _scatter_designs(ax, [p.designs[0]], marker="*", color="C3", s=140, zorder=5, label=first)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("scale lambda [-]")
    ax.set_ylabel("specimen charge [kg TNT, impulse]")
    ax.set_title("Plan: every candidate (odds; rejected by their first reason; Pareto front)", fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7, loc="best")
    return ax


def _scatter_designs(ax, designs, **style):
    """Scatter ``designs`` (dicts of the plan) at their scale lambda [-] and specimen charge [kg TNT];
    ``style``: :meth:`matplotlib.axes.Axes.scatter`'s keywords. Returns its collection."""
    return ax.scatter([d["scale"] for d in designs], [d["tnt_equivalent_kg"] for d in designs], **style)
