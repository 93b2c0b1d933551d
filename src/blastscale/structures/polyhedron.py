"""Convex polyhedra: exact mass properties and faces (the geometry of a general rigid block).

A block is the convex hull of its vertices (:class:`scipy.spatial.ConvexHull`). Its volume, centre of
mass and inertia tensor are integrated exactly over the hull by the divergence theorem: each volume
integral of 1, x, y, z, x^2, y^2, z^2, xy, yz, zx becomes a sum over the boundary triangles of
polynomials in their vertex coordinates (Eberly 2002, after Mirtich 1996),

.. math:: \\int_V x^2\\,dV = \\frac{1}{3}\\oint_{\\partial V} x^3 n_x\\,dA
          = \\sum_{\\text{triangles}} \\frac{d_x}{60} f_3(x_0, x_1, x_2), \\quad \\dots

with :math:`\\mathbf d = (\\mathbf p_1 - \\mathbf p_0) \\times (\\mathbf p_2 - \\mathbf p_0)` (outward) and
:math:`f_3` the symmetric cubic of the triangle's coordinates. The vertices are shifted to their mean
first (round-off). Faces are the hull's triangles merged into coplanar convex polygons, each with its
outward unit normal, area and centroid.

References
----------
.. [1] D. Eberly (2002, rev. 2009), *Polyhedral Mass Properties (Revisited)*, Geometric Tools.
.. [2] B. Mirtich (1996), Fast and accurate computation of polyhedral mass properties, *Journal of
       Graphics Tools* 1(2), 31-50.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .._validate import BlastscaleInputError

__all__ = [
    "PolyhedronMassProperties",
    "PolygonFace",
    "hull_of",
    "polyhedron_mass_properties",
    "polyhedron_faces",
    "polygon_area_centroid",
    "face_label",
    "COPLANAR_TOLERANCE",
]

#: Relative tolerance (of the block's size) under which two hull facets are one plane face.
COPLANAR_TOLERANCE = 1e-9


@dataclass(frozen=True)
class PolyhedronMassProperties:
    """Mass properties of a homogeneous convex polyhedron.

    Attributes
    ----------
    volume : float
        [m^3].
    mass : float
        [kg].
    centroid : ndarray (3,)
        Centre of mass [m], the vertices' frame.
    inertia : ndarray (3, 3)
        Inertia tensor about the centre of mass, axes of the vertices' frame [kg m^2].
    """

    volume: float
    mass: float
    centroid: np.ndarray
    inertia: np.ndarray


@dataclass(frozen=True)
class PolygonFace:
    """A plane face of a convex polyhedron.

    Attributes
    ----------
    vertices : ndarray (k, 3)
        The polygon, counter-clockwise seen from outside [m].
    normal : ndarray (3,)
        Outward unit normal [-].
    area : float
        [m^2].
    centroid : ndarray (3,)
        [m].
    """

    vertices: np.ndarray
    normal: np.ndarray
    area: float
    centroid: np.ndarray


def hull_of(vertices, name: str = "block"):
    """The convex hull of ``vertices`` (n, 3) [m]; one-line error naming ``name`` for fewer than 4
    points, non-finite values or a flat (zero-volume) set."""
    from scipy.spatial import ConvexHull, QhullError

    v = np.asarray(vertices, dtype=float)
    if v.ndim != 2 or v.shape[1] != 3 or v.shape[0] < 4:
        raise BlastscaleInputError(
            f"block {name!r}: vertices of shape {v.shape} are not a solid: give at least 4 "
            "points [x, y, z] that span a volume"
        )
    if not np.all(np.isfinite(v)):
        raise BlastscaleInputError(f"block {name!r}: vertices contain non-finite values")
    try:
        hull = ConvexHull(v)
    except QhullError:
        raise BlastscaleInputError(
            f"block {name!r} has zero volume: its {len(v)} vertices are coplanar or collinear"
        ) from None
    size = float(np.ptp(v, axis=0).max())
    if hull.volume <= 1e-12 * size**3:
        raise BlastscaleInputError(f"block {name!r} has zero volume ({hull.volume:.3g} m^3)")
    return hull


def _outward_triangles(hull) -> np.ndarray:
    """The hull's triangles (nt, 3, 3) [m], each counter-clockwise seen from outside."""
    tri = hull.points[hull.simplices]
    d = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    flip = np.einsum("ij,ij->i", d, hull.equations[:, :3]) < 0.0
    tri[flip] = tri[flip][:, ::-1]
    return tri


def _subexpressions(w0, w1, w2):
    """Eberly's f1, f2, f3, g0, g1, g2 of one coordinate of the triangles' vertices."""
    t0 = w0 + w1
    t1 = w0 * w0
    t2 = t1 + w1 * t0
    f1 = t0 + w2
    f2 = t2 + w2 * f1
    f3 = w0 * t1 + w1 * t2 + w2 * f2
    return f1, f2, f3, f2 + w0 * (f1 + w0), f2 + w1 * (f1 + w1), f2 + w2 * (f1 + w2)


def polyhedron_mass_properties(vertices, density: float, name: str = "block") -> PolyhedronMassProperties:
    """Exact volume, mass, centre of mass and inertia tensor of the convex hull of ``vertices``.

    Parameters
    ----------
    vertices : array_like (n, 3)
        Points [m]; their convex hull is the body.
    density : float
        rho [kg/m^3].
    name : str
        The block's name (error messages).

    Returns
    -------
    PolyhedronMassProperties

    Notes
    -----
    Divergence theorem over the hull's outward triangles (Eberly 2002; Mirtich 1996): with
    :math:`\\mathbf d` the triangle's doubled area vector, :math:`V = \\sum d_x f_1(x)/6`,
    :math:`\\int x\\,dV = \\sum d_x f_2(x)/24`, :math:`\\int x^2\\,dV = \\sum d_x f_3(x)/60`,
    :math:`\\int xy\\,dV = \\sum d_x (y_0 g_0(x) + y_1 g_1(x) + y_2 g_2(x))/120` (cyclic), then
    :math:`I = \\rho[\\int (r^2 \\mathbf 1 - \\mathbf r \\mathbf r^T) dV] - m (|c|^2 \\mathbf 1 - c c^T)`.
    """
    hull = hull_of(vertices, name)
    shift = hull.points[hull.vertices].mean(axis=0)
    tri = _outward_triangles(hull) - shift
    p0, p1, p2 = tri[:, 0], tri[:, 1], tri[:, 2]
    d = np.cross(p1 - p0, p2 - p0)
    fx = _subexpressions(p0[:, 0], p1[:, 0], p2[:, 0])
    fy = _subexpressions(p0[:, 1], p1[:, 1], p2[:, 1])
    fz = _subexpressions(p0[:, 2], p1[:, 2], p2[:, 2])
    vol = float(d[:, 0] @ fx[0]) / 6.0
    first = np.array([d[:, 0] @ fx[1], d[:, 1] @ fy[1], d[:, 2] @ fz[1]]) / 24.0
    second = np.array([d[:, 0] @ fx[2], d[:, 1] @ fy[2], d[:, 2] @ fz[2]]) / 60.0  # int x^2, y^2, z^2
    xy = float(d[:, 0] @ (p0[:, 1] * fx[3] + p1[:, 1] * fx[4] + p2[:, 1] * fx[5])) / 120.0
    yz = float(d[:, 1] @ (p0[:, 2] * fy[3] + p1[:, 2] * fy[4] + p2[:, 2] * fy[5])) / 120.0
    zx = float(d[:, 2] @ (p0[:, 0] * fz[3] + p1[:, 0] * fz[4] + p2[:, 0] * fz[5])) / 120.0
    c = first / vol
    rho = float(density)
    m = rho * vol
    cov = rho * np.array([[second[0], xy, zx], [xy, second[1], yz], [zx, yz, second[2]]]) - m * np.outer(c, c)
    inertia = np.trace(cov) * np.eye(3) - cov
    return PolyhedronMassProperties(vol, m, c + shift, 0.5 * (inertia + inertia.T))


def cross_rows(a, b) -> np.ndarray:
    """Cross products of 3-vectors, (3,) or (k, 3): the same floating-point operations as ``np.cross``
    (bitwise the same results) without its axis handling, ~10x faster on the small arrays of a block's
    faces (issue #41: the geometry of a 200-block wall is built on every new structure)."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    a0, a1, a2 = a[..., 0], a[..., 1], a[..., 2]
    b0, b1, b2 = b[..., 0], b[..., 1], b[..., 2]
    return np.stack([a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0], axis=-1)


def polygon_area_centroid(poly: np.ndarray) -> tuple:
    """Area [m^2], centroid (3,) [m] and area vector of a plane convex polygon (k, 3) given in order."""
    p = np.asarray(poly, dtype=float)
    a = cross_rows(p[1:-1] - p[0], p[2:] - p[0])  # fan triangles' doubled area vectors
    w = np.linalg.norm(a, axis=1)
    area = 0.5 * float(w.sum())
    if area <= 0.0:
        return 0.0, p.mean(axis=0), np.zeros(3)
    cent = ((p[0] + p[1:-1] + p[2:]) / 3.0 * w[:, None]).sum(axis=0) / w.sum()
    return area, cent, 0.5 * a.sum(axis=0)


def plane_basis(normal) -> tuple:
    """Two unit vectors (u, v) with (u, v, normal) right-handed."""
    n = np.asarray(normal, dtype=float)
    helper = np.array([0.0, 0.0, 1.0]) if abs(n[2]) < 0.9 else np.array([1.0, 0.0, 0.0])
    u = cross_rows(helper, n)
    u /= np.linalg.norm(u)
    return u, cross_rows(n, u)


def _ordered(points: np.ndarray, normal: np.ndarray) -> np.ndarray:
    """Coplanar points of a convex polygon, counter-clockwise about ``normal``, duplicates dropped."""
    u, v = plane_basis(normal)
    c = points.mean(axis=0)
    ang = np.arctan2((points - c) @ v, (points - c) @ u)
    return points[np.argsort(ang)]


def polyhedron_faces(vertices, name: str = "block") -> list:
    """The plane faces of the convex hull of ``vertices``: coplanar hull triangles merged.

    Returns
    -------
    list of PolygonFace
        Outward normals; facets whose unit normals differ by < 1e-9 and whose planes lie within
        ``COPLANAR_TOLERANCE`` x the block's size are one face.
    """
    hull = hull_of(vertices, name)
    pts = hull.points
    size = float(np.ptp(pts[hull.vertices], axis=0).max())
    eq = hull.equations
    groups: list = []
    reps = np.empty((0, 4))
    for k in range(len(eq)):
        if len(reps):
            hit = np.flatnonzero(
                (np.abs(reps[:, :3] - eq[k, :3]).max(axis=1) < 1e-9)
                & (np.abs(reps[:, 3] - eq[k, 3]) < COPLANAR_TOLERANCE * size)
            )
            if hit.size:
                groups[hit[0]].append(k)
                continue
        groups.append([k])
        reps = np.vstack([reps, eq[k]])
    faces = []
    for g in groups:
        n = eq[g[0], :3] / np.linalg.norm(eq[g[0], :3])
        idx = np.unique(hull.simplices[g].ravel())
        poly = _ordered(pts[idx], n)
        area, cent, _ = polygon_area_centroid(poly)
        faces.append(PolygonFace(poly, n, area, cent))
    return faces


def face_label(normal) -> str:
    """ "front" (mostly -x, towards the charge), "rear" (+x), "top" (+z), "bottom" (-z) or "side" (+-y),
    after the largest component of the outward normal."""
    n = np.asarray(normal, dtype=float)
    k = int(np.argmax(np.abs(n)))
    if k == 0:
        return "front" if n[0] < 0 else "rear"
    if k == 2:
        return "top" if n[2] > 0 else "bottom"
    return "side"


def principal_moments(inertia: np.ndarray) -> tuple:
    """Eigenvalues of an inertia tensor [kg m^2], ascending."""
    return tuple(float(x) for x in np.linalg.eigvalsh(inertia))
