"""Frames of the stored motion drawn with matplotlib (3D axes): the prototype and the up-scaled specimen side
by side in prototype units, blocks coloured by their largest displacement, the ground and the charge.

The frames feed ``blastscale show RESULT_DIR --animate FILE.gif|FILE.mp4`` (GIF through Pillow, MP4 through
ffmpeg where installed); the interactive HTML view is :mod:`blastscale.report.motion`.
"""

from __future__ import annotations

import numpy as np

__all__ = ["VIEWS", "COLORMAP", "motion_figure", "render_frames"]

#: Camera of each named view: (elevation, azimuth) [deg] of matplotlib's 3D axes. ``front``: from the charge
#: (-x); ``side``: from -y, the blast going left to right; ``top``: from above; ``iso``: from the charge's side,
#: in front and above.
VIEWS = {"front": (0.0, 180.0), "side": (0.0, -90.0), "top": (90.0, -90.0), "iso": (25.0, -135.0)}
#: The colour map of the largest displacement of each block (0: dark, the largest of both systems: bright).
COLORMAP = "viridis"


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


def motion_figure(motion, view: str = "iso", charge=None, width_in: float = 5.0):
    """The figure and its updater: ``(fig, update(index))``; ``update`` puts every system at recorded state
    ``index`` (its time in the title). ``charge``: its position (3,) [m] or None."""
    import matplotlib.pyplot as plt
    from matplotlib import cm, colors
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    elev, azim = VIEWS[view]
    eye = _eye(elev, azim)
    nsys = len(motion.labels)
    fig = plt.figure(figsize=(width_in * nsys, width_in * 0.9), layout="constrained")
    lo, hi = motion.bounds()
    if charge is not None:
        lo, hi = np.minimum(lo, charge), np.maximum(hi, charge)
    lo[2] = min(lo[2], 0.0)
    span = float(max(hi - lo))
    centre = 0.5 * (lo + hi)
    disp = motion.largest_displacement()
    norm = colors.Normalize(0.0, max(float(disp.max()), 1e-12))
    cmap = plt.get_cmap(COLORMAP)
    ntri = [int((f >= 0).all(axis=1).sum()) for f in motion.faces]
    colls, title = [], fig.suptitle("")
    for s, label in enumerate(motion.labels):
        ax = fig.add_subplot(1, nsys, s + 1, projection="3d", proj_type="ortho" if view != "iso" else "persp")
        ax.computed_zorder = False  # the ground below, the blocks above it, the charge on top
        m = 0.6 * span
        gx, gy = (centre[0] - m, centre[0] + m), (centre[1] - m, centre[1] + m)
        ground = [[(gx[0], gy[0], 0.0), (gx[1], gy[0], 0.0), (gx[1], gy[1], 0.0), (gx[0], gy[1], 0.0)]]
        ax.add_collection3d(Poly3DCollection(ground, facecolor="#d8d2c4", edgecolor="none", zorder=1))
        base = np.repeat(cmap(norm(disp[s])), ntri, axis=0)
        tri, face = _facing(_triangles(motion, motion.world(s, [0])[0]), base, eye)
        coll = Poly3DCollection(tri, facecolors=face, edgecolor=(0, 0, 0, 0.2), linewidths=0.3, zorder=2)
        ax.add_collection3d(coll)
        colls.append((coll, base))
        if charge is not None:
            ax.scatter(*charge, marker="*", s=120, color="#c0392b", depthshade=False, zorder=3)
            ax.text(*charge, "  charge", color="#c0392b", fontsize=8, zorder=3)
        for set_lim, c in zip((ax.set_xlim, ax.set_ylim, ax.set_zlim), centre):
            set_lim(c - m, c + m)
        ax.set_box_aspect((1, 1, 1))
        ax.view_init(elev=elev, azim=azim)
        ax.set_xlabel("x [m]")
        ax.set_ylabel("y [m]")
        ax.set_zlabel("z [m]")
        ax.set_title(label, fontsize=10)
    fig.colorbar(
        cm.ScalarMappable(norm=norm, cmap=cmap), ax=fig.axes, shrink=0.6, label="largest displacement of the block [m]"
    )

    def update(index: int) -> None:
        for s, (coll, base) in enumerate(colls):
            tri, face = _facing(_triangles(motion, motion.world(s, [index])[0]), base, eye)
            coll.set_verts(tri)
            coll.set_facecolor(face)
        title.set_text(f"t = {motion.time[index]:.3f} s (prototype time)")

    return fig, update


def render_frames(motion, indices, view: str = "iso", charge=None, dpi: int = 80):
    """Every frame as an RGB array (height, width, 3) of uint8, one per recorded state in ``indices``."""
    import matplotlib.pyplot as plt

    fig, update = motion_figure(motion, view, charge)
    fig.set_dpi(dpi)
    try:
        for i in indices:
            update(int(i))
            fig.canvas.draw()
            yield np.asarray(fig.canvas.buffer_rgba())[..., :3].copy()
    finally:
        plt.close(fig)
