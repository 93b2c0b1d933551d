"""Drawings of an assembly of convex blocks: elevation and plan with the interfaces shaded, and
snapshots of its response (prototype and up-scaled model) in a side section.

Inputs are a :class:`blastscale.structures.Assembly` (its blocks' vertices and its interfaces, found
by geometry) and, for snapshots, the ``Response3D`` datasets (the model's already up-scaled to
prototype units). Nothing here computes physics; figures are returned, never written (the caller
writes them through :mod:`blastscale.io`).

Views (the blast comes from -x): the **elevation** is the structure seen from the charge (y
horizontal, z up); the **plan** is seen from above (y horizontal, x up, the charge below). A block
is drawn as the outline of its projection (the 2D convex hull of its projected vertices). An
interface (two faces in contact, or a face on the ground) is shaded where it shows as an area in
the view and drawn as a thick line where it is seen edge on (a bed joint in elevation).
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["assembly_figure", "draw_view", "snapshot_figure", "snapshot_instants", "world_points", "VIEWS"]

#: view name -> (horizontal, vertical) world axes (0 = x, 1 = y, 2 = z), axis labels.
VIEWS = {
    "elevation": ((1, 2), ("y [m]", "z [m]"), "elevation (seen from the charge, -x)"),
    "plan": ((1, 0), ("y [m]", "x [m] (blast from -x, below)"), "plan (seen from above)"),
    "section": ((0, 2), ("x [m] (blast from -x)", "z [m]"), "side section (x-z)"),
}
_BLOCK = dict(facecolor="#d9cbb0", edgecolor="#5b4a35", lw=0.8)
_SUPPORT = dict(facecolor="#e6e6e6", edgecolor="#555555", lw=0.8, hatch="///")  # supports, fixed to the ground
_JOINT, _GROUND = "#1f77b4", "#2a9d3a"


def _hull2d(points: np.ndarray) -> np.ndarray:
    """Outline (counter-clockwise) of 2D points; degenerate sets give their extreme segment."""
    from scipy.spatial import ConvexHull, QhullError

    p = np.unique(np.round(np.asarray(points, dtype=float), 12), axis=0)
    if len(p) >= 3:
        try:
            return p[ConvexHull(p).vertices]
        except QhullError:
            pass
    d = p - p.mean(axis=0)
    axis = np.linalg.svd(d, full_matrices=False)[2][0] if len(p) > 1 else np.array([1.0, 0.0])
    s = d @ axis
    return p[[int(np.argmin(s)), int(np.argmax(s))]]


def _area2d(poly: np.ndarray) -> float:
    if len(poly) < 3:
        return 0.0
    x, y = poly[:, 0], poly[:, 1]
    return 0.5 * abs(float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1))))


def world_points(structure) -> list:
    """(name, world position at rest [m]) of each monitoring point of any structure."""
    return [
        (p.name, np.asarray(structure.bodies[p.body].com) + np.asarray(p.position)) for p in structure.monitoring_points
    ]


def draw_view(
    structure, view: str = "elevation", ax=None, interfaces: bool = True, points=True, label_points: int = 30
):
    """Draw one view of an assembly on ``ax`` (created when None); returns ``ax``.

    Parameters
    ----------
    structure : Assembly
        Blocks with ``points`` (vertices [m]) and ``interface_details``.
    view : {"elevation", "plan", "section"}
    interfaces : bool
        Shade the interfaces (blue between blocks, green on the ground).
    points : bool or list of (str, array)
        Mark the monitoring points (the structure's, or the (name, world position) given), named when
        there are at most ``label_points``.
    """
    import matplotlib.pyplot as plt
    from matplotlib.patches import Polygon

    if ax is None:
        _, ax = plt.subplots()
    (i, j), (xl, yl), title = VIEWS[view]
    depth_axis = ({0, 1, 2} - {i, j}).pop()
    order = np.argsort([b.points[:, depth_axis].mean() for b in structure.blocks])
    if view == "elevation":  # nearest the viewer (smallest x) drawn last
        order = order[::-1]
    elif view == "plan":  # highest drawn last
        order = np.argsort([b.points[:, 2].max() for b in structure.blocks])
    for b in getattr(structure, "supports", ()):  # fixed to the ground: hatched, behind the blocks
        ax.add_patch(Polygon(_hull2d(b.points[:, [i, j]]), closed=True, zorder=0.5, **_SUPPORT))
    for k in order:
        ax.add_patch(Polygon(_hull2d(structure.blocks[k].points[:, [i, j]]), closed=True, zorder=1, **_BLOCK))
    if interfaces:
        for itf in structure.interface_details:
            poly = np.asarray(itf.polygon, dtype=float)[:, [i, j]]
            colour = _GROUND if itf.first < 0 else _JOINT
            outline = _hull2d(poly)
            if _area2d(outline) > 1e-6 * max(itf.area, 1e-300) and len(outline) >= 3:
                ax.add_patch(
                    Polygon(
                        outline,
                        closed=True,
                        facecolor=colour,
                        alpha=0.35 if view != "plan" else 0.12,
                        edgecolor=colour,
                        lw=0.6,
                        zorder=2,
                    )
                )
            else:
                ax.plot(outline[:, 0], outline[:, 1], color=colour, lw=2.0, solid_capstyle="butt", zorder=3)
    if points is not False:
        mp = world_points(structure) if points is True else list(points)
        if mp:
            xy = np.array([q for _, q in mp])
            ax.plot(xy[:, i], xy[:, j], "o", ms=3, color="#c0392b", zorder=4)
            if len(mp) <= label_points:
                for name, q in mp:
                    ax.annotate(name, (q[i], q[j]), fontsize=6, xytext=(2, 2), textcoords="offset points", zorder=5)
    v = np.vstack([b.points for b in structure.blocks + tuple(getattr(structure, "supports", ()))])
    pad = 0.05 * float(np.ptp(v, axis=0).max())
    ax.set_xlim(v[:, i].min() - pad, v[:, i].max() + pad)
    ax.set_ylim(min(v[:, j].min(), 0.0) - pad, v[:, j].max() + pad)
    if j == 2:
        ax.axhline(0.0, color="k", lw=1.0, zorder=0)
    ax.set_aspect("equal")
    ax.set_xlabel(xl)
    ax.set_ylabel(yl)
    ax.set_title(title, fontsize=9)
    return ax


def assembly_figure(structure, title: str | None = None, standoff_m: float | None = None, points=True):
    """Elevation (top) and plan (bottom) of an assembly, interfaces shaded; with ``standoff_m`` the
    plan marks the direction and distance of the charge; ``points`` as in :func:`draw_view`."""
    import matplotlib.pyplot as plt
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    v = np.vstack([b.points for b in structure.blocks])
    ext = np.ptp(v, axis=0)
    ratio = (ext[2] + ext[0] + 0.2 * ext.max()) / max(ext[1], 1e-9)
    width = 7.5
    fig, (ax_e, ax_p) = plt.subplots(
        2,
        1,
        figsize=(width, min(max(width * ratio * 0.9, 4.5), 11.0)),
        layout="constrained",
        height_ratios=[max(ext[2], 1e-9), max(ext[0], 0.25 * ext[2])],
    )
    draw_view(structure, "elevation", ax=ax_e, points=points)
    draw_view(structure, "plan", ax=ax_p, points=points, label_points=0)
    if standoff_m is not None:
        x0 = float(structure.front_x)
        lo, hi = ax_p.get_ylim()
        lo2 = lo - 0.5 * (hi - lo)
        ax_p.set_ylim(lo2, hi)
        ax_p.annotate(
            f"charge {standoff_m:.3g} m in front (-x)",
            xy=(0.0, x0),
            xytext=(0.0, lo2),
            ha="center",
            va="bottom",
            fontsize=7,
            color="#c0392b",
            arrowprops=dict(arrowstyle="->", color="#c0392b"),
        )
    handles = [
        Line2D([], [], color=_JOINT, lw=4, alpha=0.6, label="interface between blocks"),
        Line2D([], [], color=_GROUND, lw=4, alpha=0.6, label="interface on the ground"),
        Line2D([], [], marker="o", ls="", color="#c0392b", ms=4, label="monitoring point"),
    ]
    if getattr(structure, "supports", ()):
        handles.append(Patch(label="support (fixed)", **_SUPPORT))
    ax_e.legend(handles=handles, fontsize=7, loc="upper right")
    d = structure.describe()
    sup = f", {d['supports']} supports" if d.get("supports") else ""
    fig.suptitle(
        title
        or f"{d.get('kind', 'assembly')}: {d['blocks']} blocks{sup}, {d['mass_kg']:.4g} kg, "
        f"{d['interfaces']} interfaces",
        fontsize=10,
    )
    return fig


def snapshot_instants(time, first_peak_time_s: float | None = None, n: int = 4) -> np.ndarray:
    """``n`` instants [s] for snapshots: the start, the first peak (when given, inside the run), the
    end, and evenly spread instants between (sorted, distinct)."""
    t = np.asarray(time, dtype=float)
    out = list(np.linspace(t[0], t[-1], max(int(n), 2)))
    if first_peak_time_s is not None and t[0] < first_peak_time_s < t[-1]:
        k = int(np.argmin(np.abs(np.asarray(out[1:-1]) - first_peak_time_s))) + 1 if n > 2 else None
        if k is not None:
            out[k] = float(first_peak_time_s)
    return np.array(sorted(set(out)))


def _posed(block_pts: np.ndarray, com0: np.ndarray, disp: np.ndarray, theta: float, amp: float) -> np.ndarray:
    """x-z outline of a block turned by ``amp * theta`` about y through its centre of mass and moved by
    ``amp * disp`` (x, z)."""
    c, s = math.cos(amp * theta), math.sin(amp * theta)
    rel = block_pts - com0
    x = c * rel[:, 0] + s * rel[:, 2] + com0[0] + amp * disp[0]
    z = -s * rel[:, 0] + c * rel[:, 2] + com0[2] + amp * disp[2]
    return _hull2d(np.column_stack([x, z]))


def snapshot_figure(
    structure, prototype, model=None, instants=None, first_peak_time_s: float | None = None, n: int = 4
):
    """Side sections (x-z) of an assembly at a few instants: the prototype (filled) and, when given,
    the up-scaled model (dashed outline) at the same prototype time.

    Each block is turned by its ``rotation_y`` about its centre of mass and moved by its
    ``com_displacement`` (x, z): the out-of-plane response to a blast from -x. Motions too small to
    see are amplified by one factor for the whole figure (stated in the title).

    Parameters
    ----------
    structure : Assembly
    prototype, model : xarray.Dataset
        ``Response3D.dataset`` of the prototype and the model up-scaled to prototype units.
    instants : array, optional
        Times [s]; default :func:`snapshot_instants`.
    """
    import matplotlib.pyplot as plt
    from matplotlib.patches import Polygon

    t = prototype["time"].values
    inst = snapshot_instants(t, first_peak_time_s, n) if instants is None else np.atleast_1d(instants)
    v = np.vstack([b.points for b in structure.blocks])
    H = float(np.ptp(v[:, 2])) or 1.0
    systems = [(prototype, "prototype")] + ([(model, "model (up-scaled)")] if model is not None else [])
    peak = max(float(np.abs(ds["com_displacement"].values).max()) for ds, _ in systems)
    amp = 1.0
    if 0.0 < peak < 0.1 * H:  # the largest 1-2-5 step that keeps the amplified motion under 0.2 H
        target = 0.2 * H / peak
        e = 10.0 ** math.floor(math.log10(target))
        amp = max(m * e for m in (1.0, 2.0, 5.0) if m * e <= target)
    coms = [np.asarray(b.com) for b in structure.bodies]
    fig, axes = plt.subplots(
        1, len(inst), figsize=(2.6 * len(inst) + 1.0, 3.8), layout="constrained", sharey=True, squeeze=False
    )
    for ax, tk in zip(axes[0], inst):
        for blk in getattr(structure, "supports", ()):  # fixed to the ground: they do not move
            ax.add_patch(Polygon(_hull2d(blk.points[:, [0, 2]]), closed=True, zorder=0.5, **_SUPPORT))
        for ds, who in systems:
            k = int(np.argmin(np.abs(ds["time"].values - tk)))
            disp, rot = ds["com_displacement"].values[k], ds["rotation_y"].values[k]
            for b, blk in enumerate(structure.blocks):
                outline = _posed(blk.points, coms[b], disp[b], float(rot[b]), amp)
                if who == "prototype":
                    ax.add_patch(Polygon(outline, closed=True, zorder=1, alpha=0.8, **_BLOCK))
                else:
                    ax.add_patch(
                        Polygon(outline, closed=True, fill=False, edgecolor="#c0392b", ls="--", lw=0.9, zorder=2)
                    )
        ax.axhline(0.0, color="k", lw=1.0)
        ax.autoscale_view()
        ax.set_aspect("equal", adjustable="datalim")
        ax.set_title(f"t = {tk:.3g} s", fontsize=9)
        ax.set_xlabel("x [m]")
    axes[0][0].set_ylabel("z [m]")
    what = "prototype (filled) and up-scaled model (dashed)" if model is not None else "prototype"
    fig.suptitle(f"Side sections of the {what}" + (f", motion x {amp:g}" if amp > 1.0 else ""), fontsize=10)
    return fig
