"""Plots of multi-body 3D runs (multi-drum columns): monitoring-point histories, prototype vs
up-scaled model (the paper's Sec. 6 figures), pose snapshots, ensemble envelopes.

Inputs are response datasets of the comparison contract (``Response3D.dataset``, up-scaled
with :func:`blastscale.analysis.compare.upscale_dataset`), already in the units to show. Every
function takes ``ax=`` (created when None) and returns it; no numerics beyond drawing live here.
"""

from __future__ import annotations

import numpy as np

from .._validate import BlastscaleInputError, check_choice
from .sim3d import axes_or_new, drum_outline, finish_side_view, snapshot_times
from .thinning import minmax_thin

__all__ = [
    "POINT_QUANTITIES",
    "plot_column_comparison",
    "plot_column_snapshots",
    "plot_ensemble_envelope",
    "plot_point_histories",
    "shared_legend",
]

#: dataset variable -> (axis label with units, factor to the unit shown)
POINT_QUANTITIES = {
    "point_displacement": ("horizontal displacement [m]", 1.0),
    "point_velocity": ("horizontal velocity [m/s]", 1.0),
}


def _colours(n: int, cmap: str):
    import matplotlib

    return matplotlib.colormaps[cmap](np.linspace(0.0, 0.9, max(n, 2)))


def plot_point_histories(
    prototype,
    model=None,
    quantity: str = "point_displacement",
    points=None,
    ax=None,
    component: str = "x",
    cmap: str = "viridis",
    legend: bool = True,
):
    """Histories of the monitoring points, prototype solid and up-scaled model dashed, one
    colour per point (paper, Sec. 6 figures (a) displacement and (b) velocity).

    Parameters
    ----------
    prototype : xarray.Dataset
        Prototype response.
    model : xarray.Dataset, optional
        Up-scaled model response (prototype units).
    quantity : str
        One of :data:`POINT_QUANTITIES`.
    points : sequence of str, optional
        Points to draw (default all).
    ax : matplotlib Axes, optional
    component : {"x", "y", "z"}
        Component drawn (default x: along the blast, horizontal).
    cmap : str
        Colormap of the points.
    legend : bool
        Draw the legend in the axes (False: panels that share one, :func:`shared_legend`).

    Returns
    -------
    matplotlib Axes
    """
    check_choice("quantity", quantity, POINT_QUANTITIES)
    names = [str(p) for p in prototype["point"].values]
    points = names if points is None else [str(p) for p in points]
    unknown = [p for p in points if p not in names]
    if unknown:
        raise BlastscaleInputError(f"points = {unknown[0]!r} is not recorded: valid values are {', '.join(names)}")
    ax = axes_or_new(ax)
    label, k = POINT_QUANTITIES[quantity]
    colours = _colours(len(points), cmap)
    for j, p in enumerate(points):
        v = prototype[quantity].sel(point=p, component=component)
        ax.plot(*minmax_thin(prototype["time"].values, k * v.values), "-", color=colours[j], lw=1.2, label=p)
        if model is not None:  # (thinned to each pixel's extremes: plots.thinning)
            vm = model[quantity].sel(point=p, component=component)
            ax.plot(*minmax_thin(model["time"].values, k * vm.values), "--", color=colours[j], lw=1.2)
    if model is not None:  # one legend entry per point, and the two line styles
        ax.plot([], [], "-", color="0.4", label="prototype")
        ax.plot([], [], "--", color="0.4", label="model (up-scaled)")
    ax.set_xlabel("time after arrival [s] (prototype)")
    ax.set_ylabel(label.replace("horizontal", f"{component}") if component != "x" else label)
    ax.grid(True, alpha=0.3)
    if legend:
        ax.legend(fontsize="x-small")
    return ax


def shared_legend(fig, ax) -> None:
    """One legend for panels that draw the same entries (``ax``'s), below them, outside every axes (a
    constrained-layout figure): no curve hidden, and no search of the panels' vertices for the emptiest
    corner (matplotlib's ``loc="best"``: a third of a column report's figure)."""
    handles, labels = ax.get_legend_handles_labels()
    fig.legend(handles, labels, loc="outside lower center", ncol=min(len(labels), 12), fontsize="x-small")


def _drum_sections(structure) -> list[tuple[float, float, float, float]]:
    """(half_bottom, half_top, z_bottom, z_top) of each body in its frame [m]: the x-extent of its solid
    (``RigidBody.vertices``, a drum's frustum, a block's box) at its base and at its top, the silhouette
    seen from the side."""
    out = []
    for b in structure.bodies:
        v = np.asarray(b.vertices, dtype=float)
        z0, z1 = float(v[:, 2].min()), float(v[:, 2].max())
        tol = 1e-9 * (z1 - z0)
        wb, wt = (float(np.abs(v[np.abs(v[:, 2] - z) <= tol, 0]).max()) for z in (z0, z1))
        out.append((wb, wt, z0, z1))
    return out


def plot_column_snapshots(structure, dataset, times=None, ax=None, n: int = 4, cmap: str = "plasma"):
    """Side view (x-z) of the structure's pose at a few times: each body a polygon, one colour
    per time (the blast comes from -x, the left).

    Parameters
    ----------
    structure : structure
        The structure simulated (its bodies' rest positions and shapes, in the dataset's units).
    dataset : xarray.Dataset
        Its response (``com_displacement``, ``rotation_y``).
    times : sequence of float, optional
        Times [s]; default ``n`` times evenly spread over the run.
    ax : matplotlib Axes, optional
    n : int
        Number of snapshots when ``times`` is None, >= 1.
    cmap : str
        Colormap for time.

    Returns
    -------
    matplotlib Axes
    """
    if dataset.sizes.get("body", 0) != len(structure.bodies):
        raise BlastscaleInputError(
            f"dataset bodies = {dataset.sizes.get('body', 0)} do not match the structure's {len(structure.bodies)}"
        )
    t = dataset["time"].values
    times, idx = snapshot_times(t, times, n)
    ax = axes_or_new(ax)
    colours = _colours(len(times), cmap)
    sections = _drum_sections(structure)
    disp = dataset["com_displacement"]
    rot = dataset["rotation_y"]
    for k, i in enumerate(idx):
        for j, (b, sec) in enumerate(zip(structure.bodies, sections)):
            dx = float(disp.isel(time=i, body=j).sel(component="x"))
            dz = float(disp.isel(time=i, body=j).sel(component="z"))
            xy = drum_outline(b.com[0] + dx, b.com[2] + dz, float(rot.isel(time=i, body=j)), *sec)
            ax.plot(xy[:, 0], xy[:, 1], color=colours[k], lw=1.0, label=f"t = {t[i]:.3g} s" if j == 0 else None)
    return finish_side_view(ax)


def plot_column_comparison(structure, prototype, model=None, points=None, fig=None):
    """A three-panel figure: horizontal displacement and velocity of the monitoring points
    (prototype solid, up-scaled model dashed) and the prototype's pose snapshots. Returns the
    figure."""
    import matplotlib.pyplot as plt

    fig = fig or plt.figure(figsize=(15, 5.5), layout="constrained")
    axs = fig.subplots(1, 3, gridspec_kw={"width_ratios": [2, 2, 1]})
    plot_point_histories(prototype, model, "point_displacement", points, ax=axs[0], legend=False)
    plot_point_histories(prototype, model, "point_velocity", points, ax=axs[1], legend=False)
    shared_legend(fig, axs[0])
    # snapshots at rest, at the top point's two largest excursions, and at the end
    top_point = prototype.attrs.get("top_point", str(prototype["point"].values[-1]))
    top = prototype["point_displacement"].sel(point=top_point, component="x").values
    t = prototype["time"].values
    times = sorted({float(t[0]), float(t[int(np.argmax(top))]), float(t[int(np.argmin(top))]), float(t[-1])})
    plot_column_snapshots(structure, prototype, times=times, ax=axs[2])
    return fig


def plot_ensemble_envelope(ensemble, point=None, ax=None):
    """Envelopes (min-max over the members) of a point's x displacement, prototype and
    up-scaled model (the prototype alone for a prototype-only ensemble), with each ensemble's mean.

    Parameters
    ----------
    ensemble : blastscale.analysis.ensemble.EnsembleComparison
    point : str, optional
        Monitoring point (default the top: the highest at rest).
    ax : matplotlib Axes, optional

    Returns
    -------
    matplotlib Axes
    """
    names = list(ensemble.points)
    point = ensemble.top_point if point is None else str(point)
    if point not in names:
        raise BlastscaleInputError(f"point = {point!r} is not recorded: valid values are {', '.join(names)}")
    j = names.index(point)
    ax = axes_or_new(ax)
    t = ensemble.time
    for stats, members, colour, name in (
        (ensemble.prototype, ensemble.prototype_members, "C0", "prototype"),
        (ensemble.model, ensemble.model_members, "C3", "model (up-scaled)"),
    ):
        if stats is None:  # a prototype-only ensemble
            continue
        ax.fill_between(
            t,
            stats["envelope_min"][:, j],
            stats["envelope_max"][:, j],
            color=colour,
            alpha=0.25,
            lw=0,
            label=f"{name}: envelope of {len(members)} runs",
        )
        ax.plot(
            t,
            members[:, :, j].mean(axis=0),
            color=colour,
            lw=1.0,
            ls="-" if name == "prototype" else "--",
            label=f"{name}: mean",
        )
    ax.set_xlabel("time after arrival [s] (prototype)")
    ax.set_ylabel(f"horizontal displacement of {point} [m]")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize="x-small")
    return ax
