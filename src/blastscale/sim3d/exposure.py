"""Line of sight from the charge: which faces Method C loads, and how much of each.

The rule (docs/assemblies.md, "Method C on assemblies"): a face is loaded only if it is **exposed**
(not covered by an interface: ``Face.in_contact`` False; a face partly covered carries its exposed
area and centroid, :mod:`blastscale.structures.assembly`). A face turned towards the charge
(cos a > 0) gets the reflected pulse only where it is **in line of sight** of the charge; where it is
hidden behind another body it is *shadowed* and sees the side-on (incident) pulse, as Method C
already loads the faces turned away (the passing wave engulfs the structure: UFC 3-340-02, Sec.
2-15, loads the side walls, roof and rear wall of a building, which the front wall hides, with the
incident pressure). The sight test is a ray cast: the straight segment from the charge centre to a point of the face is
blocked when it passes through the interior of another body's convex hull (segment against the
hull's half-spaces, the parametric clipping of Cyrus & Beck 1978). Each face is sampled at its
(exposed) centroid and at the points halfway from it to each vertex of the face polygon; the face is
given the pressure and impulse ``v P_r,a + (1 - v) P_so`` with v the fraction of its sample points in
sight. Neither diffraction's build-up time nor channelling between blocks is modelled (the empirical
fits describe a free-field surface burst). The sight is decided at rest, once: blocks move by
millimetres while the blast acts.

References
----------
.. [1] M. Cyrus & J. Beck (1978), Generalized two- and three-dimensional clipping, *Computers &
       Graphics* 3(1), 23-28.
.. [2] UFC 3-340-02 (2008), *Structures to resist the effects of accidental explosions*, Sec. 2-15
       (roof, side and rear walls loaded by the incident pressure).
"""

from __future__ import annotations

import numpy as np

__all__ = ["body_hulls", "segment_blocked", "visible_fractions"]


def body_hulls(structure) -> list:
    """Each body's convex hull at rest as half-spaces (A (k, 3), b (k,)) with A x + b <= 0 inside,
    the hull's size [m] and its bounding box: the hull of the body's solid (``RigidBody.vertices``: a
    drum's frustum, not its contact prism; an assembly's blocks at their given coordinates)."""
    from scipy.spatial import ConvexHull

    out = []
    blocks = getattr(structure, "blocks", None)
    for k, b in enumerate(structure.bodies):
        if blocks is not None:
            v = blocks[k].points
        else:
            v = np.asarray(b.vertices, dtype=float) + np.asarray(b.com, dtype=float)
        h = ConvexHull(v)
        out.append(
            (h.equations[:, :3], h.equations[:, 3], float(np.ptp(v, axis=0).max()), v.min(axis=0), v.max(axis=0))
        )
    return out


def segment_blocked(p, q, A, b, tol: float) -> bool:
    """Does the segment p -> q pass through the interior of the hull {A x + b <= 0} over a length
    of more than ``tol`` [m] (Cyrus-Beck clipping)?"""
    d = q - p
    num = -(A @ p + b)  # A (p + t d) + b <= 0  <=>  t (A d) <= num
    den = A @ d
    par = np.abs(den) < 1e-300
    if np.any(par & (num < 0.0)):
        return False
    with np.errstate(divide="ignore", invalid="ignore"):
        t = num / den
    t1 = min(1.0, float(t[(den > 0) & ~par].min(initial=np.inf)))
    t0 = max(0.0, float(t[(den < 0) & ~par].max(initial=-np.inf)))
    return (t1 - t0) * float(np.linalg.norm(d)) > tol


def visible_fractions(structure, faces, charge_position) -> np.ndarray:
    """Fraction of each face in line of sight of the charge [-] (module docstring).

    Parameters
    ----------
    structure : structure
        Any structure of :mod:`blastscale.structures`, at rest.
    faces : sequence of (int, Face)
        Body index and face (body frame).
    charge_position : array_like (3,)
        Charge centre [m].

    Returns
    -------
    ndarray (nface,)
    """
    hulls = body_hulls(structure)
    c = np.asarray(charge_position, dtype=float)
    out = np.ones(len(faces))
    if len(hulls) < 2:
        return out
    coms = [np.asarray(b.com, dtype=float) for b in structure.bodies]
    lo = np.array([h[3] for h in hulls])
    hi = np.array([h[4] for h in hulls])
    for k, (i, f) in enumerate(faces):
        centre = coms[i] + np.asarray(f.centre, dtype=float)
        if np.dot(f.normal, c - centre) <= 0.0:  # turned away: engulfed by the passing wave (side-on)
            continue
        pts = [centre] + [0.5 * (centre + coms[i] + np.asarray(v, dtype=float)) for v in getattr(f, "vertices", ())]
        seen = 0
        for p in pts:
            near = np.flatnonzero(np.all(lo <= np.maximum(c, p), axis=1) & np.all(hi >= np.minimum(c, p), axis=1))
            blocked = any(j != i and segment_blocked(c, p, hulls[j][0], hulls[j][1], 1e-6 * hulls[j][2]) for j in near)
            seen += not blocked
        out[k] = seen / len(pts)
    return out
