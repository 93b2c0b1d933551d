"""Plots of 3D single-block runs: histories (prototype vs up-scaled model) and pose snapshots.

Every function takes ``ax=`` (created when None) and returns it. Inputs are the block's planar
view, :func:`blastscale.analysis.block3d_similarity.block_dataset` of a run's ``Response3D``,
already in the units to show (up-scale a model's with
:func:`blastscale.analysis.compare.upscale_dataset` first); no numerics beyond drawing live here.
"""

from __future__ import annotations

import math

import numpy as np

from .._validate import BlastscaleInputError, check_choice, check_finite
from .thinning import minmax_thin

__all__ = [
    "HISTORY_QUANTITIES",
    "axes_or_new",
    "block_outline",
    "drum_outline",
    "finish_side_view",
    "plot_history",
    "plot_rotation",
    "plot_sliding",
    "plot_velocity",
    "plot_block_angular_velocity",
    "plot_snapshots",
    "plot_comparison",
    "snapshot_times",
]

#: block dataset variable -> (axis label with units, scale factor to the unit shown)
HISTORY_QUANTITIES = {
    "rotation_y": ("rotation theta [rad]", 1.0),
    "angular_velocity_y": ("angular velocity [rad/s]", 1.0),
    "sliding": ("sliding of the base [m]", 1.0),
    "velocity_x": ("velocity x of the centre of mass [m/s]", 1.0),
    "uplift": ("uplift of the lowest base corner [mm]", 1e3),
    "com_x": ("displacement x of the centre of mass [m]", 1.0),
}


def axes_or_new(ax):
    """``ax``, or the axes of a new figure when None."""
    if ax is None:
        import matplotlib.pyplot as plt

        _, ax = plt.subplots()
    return ax


def snapshot_times(t, times=None, n: int = 6):
    """The snapshot times [s]: ``times`` checked finite, or ``n`` (>= 1) times evenly spread over
    the recorded times ``t``; and, for each, the index of the first recorded time >= it."""
    if times is None and not (isinstance(n, (int, np.integer)) and not isinstance(n, bool) and n >= 1):
        raise BlastscaleInputError(f"n = {n!r} is out of range: must be a whole number >= 1")
    t = np.asarray(t, dtype=float)
    times = np.linspace(t[0], t[-1], n) if times is None else np.atleast_1d(check_finite("snapshot times", times, "s"))
    return times, [int(np.clip(np.searchsorted(t, tk), 0, t.size - 1)) for tk in times]


def finish_side_view(ax):
    """Ground line, equal axes, x-z labels and legend of a side view (blast from -x). The axes keep their
    box and the x range widens to make the scales equal (``adjustable="datalim"``): a tall structure in a
    narrow box would otherwise shrink the axes until its x tick labels run into each other (issue #39);
    at most 4 x ticks."""
    from matplotlib.ticker import MaxNLocator

    ax.axhline(0.0, color="k", lw=1)  # spans the axes in x: the x limits stay the data's
    ax.set_aspect("equal", adjustable="datalim")
    ax.xaxis.set_major_locator(MaxNLocator(nbins=4))
    ax.set_xlabel("x [m] (blast from -x)")
    ax.set_ylabel("z [m]")
    ax.legend(fontsize="small")
    return ax


def _as_dict(results, labels=None) -> dict:
    if isinstance(results, dict) and not hasattr(results, "data_vars"):
        return results
    if not isinstance(results, (list, tuple)):
        results = [results]
    labels = labels or (["prototype", "model (up-scaled)"] + [f"run {k}" for k in range(2, len(results))])
    return dict(zip(labels, results))


def plot_history(results, quantity: str = "rotation_y", ax=None, labels=None, styles=("-", "--", ":", "-.")):
    """Time history of one recorded quantity for one or several runs.

    Parameters
    ----------
    results : xarray.Dataset, sequence of them, or dict label -> dataset
        Block datasets (:func:`~blastscale.analysis.block3d_similarity.block_dataset`) to overlay
        (a sequence is labelled prototype, model (up-scaled), ...).
    quantity : str
        One of :data:`HISTORY_QUANTITIES`.
    ax : matplotlib Axes, optional
    labels : sequence of str, optional
    styles : sequence of str
        Line styles cycled over the runs (dashed model over solid prototype).

    Returns
    -------
    matplotlib Axes
    """
    check_choice("quantity", quantity, HISTORY_QUANTITIES)
    ax = axes_or_new(ax)
    label, k = HISTORY_QUANTITIES[quantity]
    for j, (name, ds) in enumerate(_as_dict(results, labels).items()):
        ax.plot(*minmax_thin(ds["time"].values, k * ds[quantity].values[:, 0]), styles[j % len(styles)], label=name)
    ax.set_xlabel("time after arrival [s]")
    ax.set_ylabel(label)
    ax.grid(True, alpha=0.3)
    ax.legend()
    return ax


def plot_rotation(results, ax=None, labels=None):
    """Rocking angle theta [rad] vs time; see :func:`plot_history`."""
    return plot_history(results, "rotation_y", ax, labels)


def plot_sliding(results, ax=None, labels=None):
    """Sliding of the base [m] vs time; see :func:`plot_history`."""
    return plot_history(results, "sliding", ax, labels)


def plot_velocity(results, ax=None, labels=None):
    """Horizontal velocity of the centre of mass [m/s] vs time; see :func:`plot_history`."""
    return plot_history(results, "velocity_x", ax, labels)


def plot_block_angular_velocity(results, ax=None, labels=None):
    """A 3D block run's angular velocity about y [rad/s] vs time; see :func:`plot_history` (a planar run's:
    :func:`blastscale.plots.rocking.plot_planar_angular_velocity`)."""
    return plot_history(results, "angular_velocity_y", ax, labels)


def drum_outline(
    com_x: float, com_z: float, theta: float, half_bottom: float, half_top: float, z_bottom: float, z_top: float
) -> np.ndarray:
    """Closed outline (5, 2) of a drum's x-z section [m]: the trapezoid of half-widths
    ``half_bottom`` at ``z_bottom`` and ``half_top`` at ``z_top`` (body frame, relative to the
    centre of mass), rotated by theta about y (top towards +x when theta > 0) and placed at the
    centre of mass (com_x, com_z)."""
    c, s = math.cos(theta), math.sin(theta)  # rotation about +y: x' = x c + z s, z' = -x s + z c
    local = np.array(
        [
            [-half_bottom, z_bottom],
            [half_bottom, z_bottom],
            [half_top, z_top],
            [-half_top, z_top],
            [-half_bottom, z_bottom],
        ]
    )
    return np.column_stack([com_x + local[:, 0] * c + local[:, 1] * s, com_z - local[:, 0] * s + local[:, 1] * c])


def block_outline(com_x: float, com_z: float, theta: float, b: float, h: float) -> np.ndarray:
    """Closed outline (5, 2) of the block's x-z section [m]: corners of the 2b x 2h rectangle
    rotated by theta about y (top towards +x when theta > 0) and centred on the centre of mass
    (:func:`drum_outline` of an untapered section)."""
    return drum_outline(com_x, com_z, theta, b, b, -h, h)


def plot_snapshots(block, dataset, times=None, ax=None, n: int = 6, cmap: str = "viridis"):
    """Outlines of the block in the x-z plane at chosen times (the blast comes from the left).

    Parameters
    ----------
    block : RectangularBlock
        The block drawn (its half-width and half-height, in the dataset's units).
    dataset : xarray.Dataset
        Its :func:`~blastscale.analysis.block3d_similarity.block_dataset` (``com_x``,
        ``com_z``, ``rotation_y``).
    times : sequence of float, optional
        Times [s]; default ``n`` times evenly spread over the run.
    ax : matplotlib Axes, optional
    n : int
        Number of snapshots when ``times`` is None.
    cmap : str
        Colormap for time.

    Returns
    -------
    matplotlib Axes
    """
    import matplotlib

    t = dataset["time"].values
    times, idx = snapshot_times(t, times, n)
    ax = axes_or_new(ax)
    x, z, th = (dataset[v].values[:, 0] for v in ("com_x", "com_z", "rotation_y"))
    colors = matplotlib.colormaps[cmap](np.linspace(0, 1, max(len(times), 2)))
    for k, i in enumerate(idx):
        xy = block_outline(x[i], z[i], th[i], block.b, block.h)
        ax.plot(xy[:, 0], xy[:, 1], color=colors[k], label=f"t = {t[i]:.3g} s")
    return finish_side_view(ax)


def plot_comparison(block, prototype, model_upscaled=None, fig=None):
    """A 2 x 2 figure: rotation, sliding, velocity histories (prototype vs up-scaled model block
    datasets) and the prototype's pose snapshots (``block``: the prototype). Returns the figure."""
    import matplotlib.pyplot as plt

    fig = fig or plt.figure(figsize=(11, 8))
    axs = fig.subplots(2, 2)
    runs = [prototype] if model_upscaled is None else [prototype, model_upscaled]
    plot_rotation(runs, ax=axs[0, 0])
    plot_sliding(runs, ax=axs[0, 1])
    plot_velocity(runs, ax=axs[1, 0])
    plot_snapshots(block, prototype, ax=axs[1, 1])
    fig.tight_layout()
    return fig
