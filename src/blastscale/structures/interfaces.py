"""Interfaces of an assembly of convex blocks, found by geometry; the checks of a block model.

Two blocks (or a block and the ground, the plane z = 0) touch along an **interface** when a face of
one and a face of the other are coplanar, opposed (outward normals anti-parallel) and overlap. The
overlap of two convex polygons is a convex polygon, found by clipping one with the other
(Sutherland & Hodgman 1974) in the common plane; it and its area are part of the interface. No
generator declares interfaces: contact pairs, ``Face.in_contact`` and Method C's exposed faces all
come from here.

Checks of a block model (:func:`check_assembly`; one line naming the block and the problem):
overlapping blocks (separating-axis test over face normals and edge-edge directions, Gottschalk et
al. 1996; a penetration deeper than :data:`OVERLAP_TOLERANCE` of the smaller block), a block below the
ground, a block not supported (not connected to the ground through interfaces: "floating"), and sizes
that look like millimetres (a block larger than :data:`MAX_BLOCK_SIZE_M`).

References
----------
.. [1] I. E. Sutherland & G. W. Hodgman (1974), Reentrant polygon clipping, *Comm. ACM* 17(1), 32-42.
.. [2] S. Gottschalk, M. C. Lin & D. Manocha (1996), OBBTree: a hierarchical structure for rapid
       interference detection, *SIGGRAPH '96* (the separating-axis theorem for convex polyhedra).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .._validate import BlastscaleInputError
from .polyhedron import plane_basis, polygon_area_centroid

__all__ = [
    "Interface",
    "find_interfaces",
    "clip_convex",
    "check_assembly",
    "near_pairs",
    "CONTACT_TOLERANCE",
    "OVERLAP_TOLERANCE",
    "MAX_BLOCK_SIZE_M",
]

#: Distance [fraction of the assembly's size] within which two faces are coplanar and in contact.
CONTACT_TOLERANCE = 1e-6
#: Penetration [fraction of the smaller block's size] above which two blocks overlap (a bad model).
OVERLAP_TOLERANCE = 1e-4
#: A block larger than this [m] is taken for a model written in millimetres.
MAX_BLOCK_SIZE_M = 100.0
#: Smallest interface area [fraction of size^2]: below it two faces only touch along an edge.
MIN_AREA_FRACTION = 1e-9


@dataclass(frozen=True)
class Interface:
    """A contact between two blocks at rest (or a block and the ground).

    Attributes
    ----------
    first, second : int
        Block indices, ``first < second``; the ground is -1.
    normal : tuple of float
        Unit normal of the contact plane, from ``first`` into ``second`` [-].
    polygon : tuple of tuple
        The overlap polygon, world frame at rest [m].
    area : float
        Its area [m^2].
    centroid : tuple of float
        Its centroid [m].
    faces : tuple of int
        Index of the face of ``first`` (-1 for the ground) and of ``second`` in their blocks' face lists.
    """

    first: int
    second: int
    normal: tuple
    polygon: tuple
    area: float
    centroid: tuple
    faces: tuple

    @property
    def pair(self) -> tuple:
        """(first, second)."""
        return (self.first, self.second)


def clip_convex(subject: np.ndarray, clip: np.ndarray) -> np.ndarray:
    """Intersection of two convex polygons (k, 2), both counter-clockwise (Sutherland-Hodgman)."""
    out = np.asarray(subject, dtype=float)
    c = np.asarray(clip, dtype=float)
    for a, b in zip(c, np.roll(c, -1, axis=0)):
        if len(out) == 0:
            break
        e = b - a
        side = e[0] * (out[:, 1] - a[1]) - e[1] * (out[:, 0] - a[0])  # > 0: inside (left of a -> b)
        nxt = []
        for k in range(len(out)):
            p, q = out[k], out[(k + 1) % len(out)]
            sp, sq = side[k], side[(k + 1) % len(out)]
            if sp >= 0.0:
                nxt.append(p)
            if (sp >= 0.0) != (sq >= 0.0):
                nxt.append(p + (q - p) * (sp / (sp - sq)))
        out = np.array(nxt).reshape(-1, 2)
    return out


def near_pairs(lo: np.ndarray, hi: np.ndarray, strict: bool = False) -> list:
    """Pairs (i, j), i < j, of boxes [lo, hi] (n, 3) [m] that overlap (``strict``) or touch, in (i, j) order.

    Sort and sweep along the axis where the boxes' centres spread most: O(n log n + candidates) instead of
    all n^2 pairs (a wall's or a file's blocks: a few neighbours each). The same pairs as the test of every
    pair (it is applied to each candidate)."""
    lo, hi = np.asarray(lo, dtype=float), np.asarray(hi, dtype=float)
    n = len(lo)
    if n < 2:
        return []
    ax = int(np.argmax(np.ptp(lo + hi, axis=0)))
    order = np.argsort(lo[:, ax], kind="stable")
    lo_s = lo[order, ax]
    ends = np.searchsorted(lo_s, hi[order, ax], side="right")  # candidates: sorted after i, starting before i ends
    out = []
    for p in range(n):
        if ends[p] <= p + 1:
            continue
        i, cand = order[p], order[p + 1 : ends[p]]
        if strict:
            ok = np.all(lo[cand] < hi[i], axis=1) & np.all(hi[cand] > lo[i], axis=1)
        else:
            ok = np.all(lo[cand] <= hi[i], axis=1) & np.all(hi[cand] >= lo[i], axis=1)
        for j in cand[ok]:
            out.append((int(i), int(j)) if i < j else (int(j), int(i)))
    out.sort()
    return out


def _overlap(face_a, face_b) -> tuple:
    """Overlap polygon (k, 3) and area of two coplanar opposed faces (PolygonFace), in a's plane."""
    n = face_a.normal
    u, v = plane_basis(n)
    o = face_a.centroid
    pa = np.column_stack([(face_a.vertices - o) @ u, (face_a.vertices - o) @ v])
    pb = np.column_stack([(face_b.vertices - o) @ u, (face_b.vertices - o) @ v])[::-1]  # b's is clockwise here
    poly = clip_convex(pa, pb)
    if len(poly) < 3:
        return None, 0.0
    world = o + poly[:, 0:1] * u + poly[:, 1:2] * v
    area = polygon_area_centroid(world)[0]
    return world, area


def find_interfaces(faces: list, size: float) -> list:
    """Every interface of blocks given by their faces (list per block of PolygonFace, world frame).

    Parameters
    ----------
    faces : list of list of PolygonFace
        Each block's faces at rest [m].
    size : float
        The assembly's size (largest extent) [m], for the tolerances.

    Returns
    -------
    list of Interface
        Ground interfaces first (by block), then block-block ones ordered by (first, second).
    """
    tol = CONTACT_TOLERANCE * size
    amin = MIN_AREA_FRACTION * size * size
    out = []
    down = np.array([0.0, 0.0, -1.0])
    for i, fs in enumerate(faces):
        for k, f in enumerate(fs):
            if f.normal @ down > 1.0 - 1e-9 and np.all(np.abs(f.vertices[:, 2]) <= tol) and f.area > amin:
                out.append(
                    Interface(
                        -1, i, (0.0, 0.0, 1.0), tuple(map(tuple, f.vertices)), float(f.area), tuple(f.centroid), (-1, k)
                    )
                )
    lo = np.array([np.min([f.vertices.min(axis=0) for f in fs], axis=0) for fs in faces]) - tol
    hi = np.array([np.max([f.vertices.max(axis=0) for f in fs], axis=0) for fs in faces]) + tol
    for i, j in near_pairs(lo, hi):
        best = None
        for ka, fa in enumerate(faces[i]):
            for kb, fb in enumerate(faces[j]):
                if fa.normal @ fb.normal > -1.0 + 1e-9:
                    continue
                if abs(fa.normal @ (fb.centroid - fa.centroid)) > tol:
                    continue
                poly, area = _overlap(fa, fb)
                if poly is not None and area > amin and (best is None or area > best[1]):
                    best = (poly, area, ka, kb, fa.normal)
        if best is not None:
            poly, area, ka, kb, n = best
            cent = polygon_area_centroid(poly)[1]
            out.append(
                Interface(
                    i, int(j), tuple(float(x) for x in n), tuple(map(tuple, poly)), float(area), tuple(cent), (ka, kb)
                )
            )
    return out


def _axes_overlap(va, vb, axes) -> float:
    """Smallest overlap of the projections of vertex sets va, vb on unit ``axes`` (m, 3) [m]."""
    pa, pb = va @ axes.T, vb @ axes.T
    return float((np.minimum(pa.max(axis=0), pb.max(axis=0)) - np.maximum(pa.min(axis=0), pb.min(axis=0))).min())


def _edges(faces) -> np.ndarray:
    e = [np.roll(f.vertices, -1, axis=0) - f.vertices for f in faces]
    e = np.vstack(e)
    e /= np.linalg.norm(e, axis=1)[:, None]
    return np.unique(np.round(e * np.sign(e[:, [0]] + 1e-12), 9), axis=0)


def penetration(va, fa, vb, fb) -> float:
    """Depth [m] by which two convex blocks overlap (<= 0: apart or touching): the least overlap of
    their projections over face normals and edge-edge cross products (separating-axis theorem)."""
    axes = np.array([f.normal for f in fa] + [f.normal for f in fb])
    depth = _axes_overlap(va, vb, axes)
    if depth <= 0.0:
        return depth
    ea, eb = _edges(fa), _edges(fb)
    cr = np.cross(ea[:, None, :], eb[None, :, :]).reshape(-1, 3)
    norm = np.linalg.norm(cr, axis=1)
    cr = cr[norm > 1e-9] / norm[norm > 1e-9, None]
    return min(depth, _axes_overlap(va, vb, cr)) if len(cr) else depth


def check_assembly(names, vertices, faces, interfaces, size: float, fixed: int = 0) -> None:
    """Raise :class:`BlastscaleInputError` (one line naming the block and the problem) for a bad
    block model: a block larger than :data:`MAX_BLOCK_SIZE_M` (millimetres?), below the ground,
    overlapping another, or not connected to the ground through interfaces (floating). The last
    ``fixed`` blocks are supports, fixed to the ground: they may reach below it, and a block resting
    on one is connected to the ground."""
    nfree = len(names) - fixed
    for k, (n, v) in enumerate(zip(names, vertices)):
        ext = float(np.ptp(v, axis=0).max())
        if ext > MAX_BLOCK_SIZE_M:
            raise BlastscaleInputError(
                f"block {n!r} is {ext:.6g} m across: the units look like millimetres (give metres; valid block size "
                f"<= {MAX_BLOCK_SIZE_M:g} m)"
            )
        if k < nfree and v[:, 2].min() < -CONTACT_TOLERANCE * size:
            raise BlastscaleInputError(
                f"block {n!r} reaches z = {v[:, 2].min():.6g} m: below the ground (z = 0); "
                "blocks must stand on or above it (only supports may reach below)"
            )
    lo = np.array([v.min(axis=0) for v in vertices])
    hi = np.array([v.max(axis=0) for v in vertices])
    for i, j in near_pairs(lo, hi, strict=True):
        d = penetration(vertices[i], faces[i], vertices[j], faces[j])
        small = min(np.ptp(vertices[i], axis=0).min(), np.ptp(vertices[j], axis=0).min())
        if d > OVERLAP_TOLERANCE * small:
            raise BlastscaleInputError(
                f"blocks {names[i]!r} and {names[j]!r} overlap by {d:.4g} m: blocks may touch, not interpenetrate"
            )
    linked = {-1, *range(nfree, len(names))}
    adj: dict = {}
    for itf in interfaces:
        adj.setdefault(itf.first, []).append(itf.second)
        adj.setdefault(itf.second, []).append(itf.first)
    todo = sorted(linked)
    while todo:
        k = todo.pop()
        for m in adj.get(k, ()):
            if m not in linked:
                linked.add(m)
                todo.append(m)
    for i, n in enumerate(names):
        if i not in linked:
            z = float(vertices[i][:, 2].min())
            raise BlastscaleInputError(
                f"block {n!r} floats in the air (lowest point at z = {z:.6g} m): it touches neither the ground nor a "
                "block connected to it along a face"
            )
