"""Frames of the stored motion drawn with matplotlib (3D axes): the prototype and the up-scaled specimen side
by side in prototype units at one displacement magnification (:func:`auto_magnification`, stated), blocks
coloured by their displacement at the frame shown, the ground and the charge.

The frames feed ``blastscale show RESULT_DIR --animate FILE.gif|FILE.mp4`` (GIF through Pillow, MP4 through
ffmpeg where installed); the interactive HTML view is :mod:`blastscale.report.motion`.
"""

from __future__ import annotations

import math

import numpy as np

from ..sim3d.replay import world_vertices

__all__ = [
    "VIEWS",
    "COLORMAP",
    "VISIBLE_FRACTION",
    "END_ON",
    "peak_motion",
    "record_height",
    "magnification_for",
    "auto_magnification",
    "magnified_world",
    "motion_figure",
    "render_frames",
]

#: Camera of each named view: (elevation, azimuth) [deg] of matplotlib's 3D axes. ``front``: from the charge
#: (-x); ``side``: from -y, the blast going left to right; ``top``: from above; ``iso``: from the charge's side,
#: in front and above.
VIEWS = {"front": (0.0, 180.0), "side": (0.0, -90.0), "top": (90.0, -90.0), "iso": (25.0, -135.0)}
#: The colour map of the largest displacement of each block (0: dark, the largest of both systems: bright).
COLORMAP = "viridis"


#: The fraction of the structure's height the largest motion is drawn as by default (issue 39): a column that
#: rocks 8 cm at the top of 10.4 m is drawn x 10 (0.8 m), a motion of 10 % of the height or more as it is.
VISIBLE_FRACTION = 0.1


def _sample(motion, most: int = 200) -> np.ndarray:
    """At most ``most`` recorded states evenly over the run, the first and the last among them."""
    n = len(motion.time)
    return np.unique(np.round(np.linspace(0, n - 1, min(n, most))).astype(int))


def peak_motion(motion, indices=None) -> float:
    """The largest displacement of any vertex from where it was at the first record [m] (true, not
    magnified), over the recorded states ``indices`` (default: 200 evenly over the run) of every system."""
    idx = _sample(motion) if indices is None else np.asarray(indices, dtype=int)
    peak = 0.0
    for s in range(len(motion.labels)):
        w = motion.world(s, np.r_[0, idx])
        peak = max(peak, float(np.nanmax(np.linalg.norm(w[1:] - w[:1], axis=-1), initial=0.0)))
    return peak


def record_height(motion) -> float:
    """The height of a motion record at its first state [m]: the vertical extent of the first system's
    vertices, from the ground (z = 0) or the lowest vertex if lower, to the highest. Not
    :func:`blastscale.study.criterion.structure_height` (a run summary's height)."""
    z = motion.world(0, [0])[0][..., 2]
    return float(np.nanmax(z) - min(float(np.nanmin(z)), 0.0))


def magnification_for(peak: float, height: float) -> float:
    """The default displacement magnification M: the largest 1-2-5 step (1, 2, 5, 10, 20, ...) with
    M x ``peak`` <= :data:`VISIBLE_FRACTION` x ``height``, at least 1 (a large motion is drawn as it is).
    Like the 2D snapshots' amplification (:func:`blastscale.plots.assembly.snapshot_figure`), a round factor
    the drawing states.

    >>> magnification_for(0.08, 10.4)  # a column rocking 8 cm: 0.1 x 10.4 / 0.08 = 13
    10.0
    >>> magnification_for(2.0, 10.0), magnification_for(0.0, 10.0)
    (1.0, 1.0)
    """
    if not (peak > 0.0 and height > 0.0) or peak >= VISIBLE_FRACTION * height:
        return 1.0
    target = VISIBLE_FRACTION * height / peak
    e = 10.0 ** math.floor(math.log10(target))
    return max(m * e for m in (1.0, 2.0, 5.0) if m * e <= target * (1 + 1e-12))


def auto_magnification(motion, indices=None) -> float:
    """:func:`magnification_for` the motion's :func:`peak_motion` over ``indices`` and its
    :func:`record_height`."""
    return magnification_for(peak_motion(motion, indices), record_height(motion))


def _qmul(a, b):
    """Hamilton product of quaternions (..., 4) (w, x, y, z)."""
    aw, ax, ay, az = np.moveaxis(a, -1, 0)
    bw, bx, by, bz = np.moveaxis(b, -1, 0)
    return np.stack(
        [
            aw * bw - ax * bx - ay * by - az * bz,
            aw * bx + ax * bw + ay * bz - az * by,
            aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw,
        ],
        -1,
    )


def magnified_world(motion, system: int, indices, magnification: float = 1.0) -> np.ndarray:
    """World vertices (len(indices), nbody, nvertex, 3) [m] of ``system`` with its motion magnified.

    Each body keeps its shape: its centre of mass moves ``M`` times its displacement from the first record,
    ``c0 + M (c - c0)``, and it turns ``M`` times the angle of its rotation from the first record about the
    same axis, ``q_M = (cos(M phi / 2), n sin(M phi / 2)) q0`` where ``q q0^-1 = (cos(phi / 2), n sin(phi / 2))``
    (the same rule as the 2D snapshots, :func:`blastscale.plots.assembly._posed`, in 3D). ``M = 1`` is
    :meth:`~blastscale.sim3d.replay.Motion.world`. To first order in the angle a point that does not move (a
    rocking block's pivot) still does not move: its displacement, ``dc + phi x r``, is magnified as a whole.
    """
    idx = np.asarray(indices, dtype=int)
    if magnification == 1.0:
        return motion.world(system, idx)
    p0, q0 = motion.position[system, 0], motion.quaternion[system, 0]
    q0 = q0 / np.linalg.norm(q0, axis=-1, keepdims=True)
    q = motion.quaternion[system, idx]
    rel = _qmul(q / np.linalg.norm(q, axis=-1, keepdims=True), q0 * np.array([1.0, -1.0, -1.0, -1.0]))
    rel = np.where(rel[..., :1] < 0.0, -rel, rel)  # the shorter way round
    s = np.linalg.norm(rel[..., 1:], axis=-1, keepdims=True)
    half = np.arctan2(s, rel[..., :1])  # phi / 2
    axis = np.divide(rel[..., 1:], s, out=np.zeros_like(rel[..., 1:]), where=s > 0.0)
    qm = _qmul(np.concatenate([np.cos(magnification * half), axis * np.sin(magnification * half)], -1), q0)
    pm = p0 + magnification * (motion.position[system, idx] - p0)
    return world_vertices(pm, qm, motion.vertices)


def _triangles(motion, world) -> np.ndarray:
    """(ntri, 3, 3) [m] of world vertices (nbody, nvertex, 3), the padding dropped."""
    out = [world[k][f[(f >= 0).all(axis=1)]] for k, f in enumerate(motion.faces)]
    return np.concatenate(out)


#: Direction towards the light (world frame) shading the faces: from the charge's side, above.
LIGHT = np.array([-0.5, -0.4, 0.77])


def _facing(tri, base, eye):
    """The triangles (ntri, 3, 3) that face the camera (direction ``eye`` (3,) towards it: the others are
    hidden by their own block, and matplotlib's depth sort would draw some over the near faces) and their
    colours: ``base`` (ntri, 4) darkened by the angle of each to :data:`LIGHT`."""
    n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    n /= np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-300)
    keep = n @ eye > 1e-9
    out = base[keep].copy()
    out[:, :3] *= (0.55 + 0.45 * np.clip(n[keep] @ (LIGHT / np.linalg.norm(LIGHT)), 0.0, 1.0))[:, None]
    return tri[keep], out


def _eye(elev: float, azim: float) -> np.ndarray:
    """Unit vector from the scene towards matplotlib's camera at (elevation, azimuth) [deg]."""
    e, a = np.radians(elev), np.radians(azim)
    return np.array([np.cos(e) * np.cos(a), np.cos(e) * np.sin(a), np.sin(e)])


#: The axis each view looks along (its tick labels would all fall on one point): hidden in that view.
END_ON = {"front": "x", "side": "y", "top": "z"}


def _limits(motion, magnification: float, charge=None) -> tuple[np.ndarray, np.ndarray]:
    """Lower and upper corners (3,) [m] of the box every panel shows: every vertex of every system at a sample
    of the recorded states with its motion magnified, the charge, the ground (z = 0); x and y padded by 8 % of
    the largest extent (the ground around the structure), every side at least 35 % of the longest."""
    idx = np.unique(np.r_[np.arange(0, len(motion.time), max(1, len(motion.time) // 100)), len(motion.time) - 1])
    lo, hi = np.full(3, np.inf), np.full(3, -np.inf)
    for s in range(len(motion.labels)):
        w = magnified_world(motion, s, idx, magnification)
        lo, hi = np.minimum(lo, np.nanmin(w, axis=(0, 1, 2))), np.maximum(hi, np.nanmax(w, axis=(0, 1, 2)))
    if charge is not None:
        lo, hi = np.minimum(lo, charge), np.maximum(hi, charge)
    lo[2] = min(lo[2], 0.0)
    pad = 0.08 * float(max(hi - lo))
    lo, hi = lo - [pad, pad, 0.0], hi + [pad, pad, 0.0]
    widen = np.maximum(0.0, 0.35 * float(max(hi - lo)) - (hi - lo))  # no axis under 35 % of the longest: room
    lo, hi = lo - widen * [0.5, 0.5, 0.0], hi + widen * [0.5, 0.5, 1.0]  # for its ticks; z from the ground up
    return lo, hi


def motion_figure(motion, view: str = "iso", charge=None, width_in: float = 5.0, magnification=None):
    """The figure and its updater: ``(fig, update(index))``; ``update`` puts every system at recorded state
    ``index`` (its time in the title) with its motion magnified (:func:`magnified_world`; ``magnification``
    None: :func:`auto_magnification`, stated in the title), each block coloured by its displacement at that
    state (true, not magnified; one colour scale for the run and both systems). ``charge``: its position (3,)
    [m] or None.

    ``update`` changes only the blocks and the title, which :func:`render_frames` draws over a background drawn
    once (blitting)."""
    fig, update, _ = _motion_figure(motion, view, charge, width_in, magnification)
    return fig, update


def _motion_figure(motion, view: str, charge, width_in: float, magnification):
    """:func:`motion_figure` and the artists its updater changes (the blocks of each system, the title)."""
    import matplotlib.pyplot as plt
    from matplotlib import cm, colors
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    peak, height = peak_motion(motion), record_height(motion)
    mag = magnification_for(peak, height) if magnification is None else float(magnification)
    elev, azim = VIEWS[view]
    eye = _eye(elev, azim)
    nsys = len(motion.labels)
    fig = plt.figure(figsize=(width_in * nsys, width_in * 0.9), layout="constrained")
    lo, hi = _limits(motion, mag, charge)
    com = np.linalg.norm(motion.position - motion.position[:, :1], axis=-1)  # (nsys, n, nbody) [m], true
    norm = colors.Normalize(0.0, max(float(com.max()), 1e-12))
    cmap = plt.get_cmap(COLORMAP)
    ntri = [int((f >= 0).all(axis=1).sum()) for f in motion.faces]
    colls = []
    why = f"; largest motion {peak:.2g} m, height {height:.3g} m" if mag != 1.0 else ""  # what M was chosen from
    title = fig.suptitle("", fontsize=10)
    for s, label in enumerate(motion.labels):
        ax = fig.add_subplot(1, nsys, s + 1, projection="3d", proj_type="ortho" if view != "iso" else "persp")
        ax.computed_zorder = False  # the ground below, the blocks above it, the charge on top
        gx, gy = (lo[0], hi[0]), (lo[1], hi[1])
        ground = [[(gx[0], gy[0], 0.0), (gx[1], gy[0], 0.0), (gx[1], gy[1], 0.0), (gx[0], gy[1], 0.0)]]
        ax.add_collection3d(Poly3DCollection(ground, facecolor="#d8d2c4", edgecolor="none", zorder=1))
        coll = Poly3DCollection(np.zeros((0, 3, 3)), linewidths=0.4, zorder=2)  # edges: the face's colour
        ax.add_collection3d(coll)
        colls.append(coll)
        if charge is not None:
            ax.scatter(*charge, marker="*", s=120, color="#c0392b", depthshade=False, zorder=3)
            ax.text(*charge, "  charge", color="#c0392b", fontsize=8, zorder=3)
        for set_lim, a, b in zip((ax.set_xlim, ax.set_ylim, ax.set_zlim), lo, hi):
            set_lim(a, b)
        aspect = hi - lo  # one scale on the three axes, but the one seen end-on: matplotlib fits the whole box,
        if view in END_ON:  # so its length would shrink the other two for nothing
            k = "xyz".index(END_ON[view])
            aspect[k] = min(np.delete(aspect, k))
        ax.set_box_aspect(tuple(aspect), zoom=0.72)  # room for the labels (checked by tests/unit/test_figure_text.py)
        ax.view_init(elev=elev, azim=azim)
        _axes_ticks(ax, view, lo, hi)
        ax.set_title(f"{label}, motion drawn x {mag:g}", fontsize=9)
    fig.colorbar(
        cm.ScalarMappable(norm=norm, cmap=cmap),
        ax=fig.axes,
        shrink=0.6,
        label="displacement at this time [m] (true)",
    )

    def update(index: int) -> None:
        for s, coll in enumerate(colls):
            base = np.repeat(cmap(norm(com[s, index])), ntri, axis=0)
            world = magnified_world(motion, s, [index], mag)[0]
            tri, face = _facing(_triangles(motion, world), base, eye)
            coll.set_verts(tri)
            coll.set_facecolor(face)
            coll.set_edgecolor(face)  # no seams, no lines across a face split in triangles
        title.set_text(f"t = {motion.time[index]:.3f} s (prototype time){why}")

    return fig, update, [*colls, title]


def _axes_ticks(ax, view: str, lo, hi) -> None:
    """The 3D axes' ticks and labels of one panel: about one tick per 20 % of the box (the axis seen end-on none);
    in a perspective view the horizontal axes meet at a corner where their end labels would fall on each other:
    ticks within 10 % of either end are left out there (tests/unit/test_figure_text.py)."""
    import matplotlib.pyplot as plt

    for a in "xyz":
        axis = getattr(ax, f"{a}axis")
        k = "xyz".index(a)
        span = (hi - lo)[k] / max(hi - lo)
        corner = view not in END_ON and a != "z"
        loc = plt.MaxNLocator(max(4 if corner else 2, round(5 * span)))
        if corner:
            ends, edge = (lo[k], hi[k]), 0.1 * (hi[k] - lo[k])
            ticks = [v for v in loc.tick_values(*ends) if ends[0] + edge < v < ends[1] - edge]
            loc = plt.FixedLocator(ticks)
        axis.set_major_locator(loc)
        if END_ON.get(view) == a:  # seen end-on: its ticks would fall on one point
            axis.set_ticks([])
            axis.set_label_text("")
        else:
            axis.set_label_text(f"{a} [m]")
            axis.labelpad = 16 if a == "z" else 12 if view in END_ON else 14  # clear of the tick labels


def render_frames(motion, indices, view: str = "iso", charge=None, dpi: int = 80, magnification=None):
    """Every frame as an RGB array (height, width, 3) of uint8, one per recorded state in ``indices``
    (:func:`motion_figure`'s figure at ``magnification``, None: automatic).

    The axes, the ground, the charge and the colour bar are drawn once; each frame restores that background and
    draws only the blocks and the title (matplotlib's blitting): a 10-drum column's 80 frames in a few seconds
    rather than redrawing every axis of every frame."""
    import matplotlib.pyplot as plt

    fig, update, animated = _motion_figure(motion, view, charge, 5.0, magnification)
    fig.set_dpi(dpi)
    try:
        update(int(indices[0]))
        fig.canvas.draw()  # lays out the figure (constrained), sets each 3D axes' projection
        fig.set_layout_engine("none")  # the layout stays as drawn: the background fits every frame
        for a in animated:
            a.set_animated(True)
        fig.canvas.draw()
        background = fig.canvas.copy_from_bbox(fig.bbox)
        for i in indices:
            update(int(i))
            fig.canvas.restore_region(background)
            for a in animated:
                if hasattr(a, "do_3d_projection"):
                    a.do_3d_projection()  # Axes3D.draw does this for its collections; draw_artist does not
                    a.axes.draw_artist(a)
                else:
                    fig.draw_artist(a)
            yield np.asarray(fig.canvas.buffer_rgba())[..., :3].copy()
    finally:
        plt.close(fig)
