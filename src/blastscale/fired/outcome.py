"""Markers on the 3D bodies: which body carries a marker, its simulated history from the body's pose, and the
outcome judged from the measured tracks by the rule the 3D engine uses for the kind (plain arrays, SI).

* **The body** of a marker, anywhere on it (a top, a face, the side of a drum where a side camera sees it):
  the body whose solid at rest the marker's rest point is on or nearest to (:func:`marker_body`, the
  distance to the planes of its faces, :func:`blastscale.fired.inputs.body_gaps`); on a face two bodies share,
  the one whose centre of mass is nearer. (The nearest centre of mass alone gives a marker near the top of a
  tall drum to a short drum above it.)
* **A simulated marker** (:func:`pose_marker_history`): the marker's point fixed on its body, moved by the
  body's recorded pose (``body_position``, ``body_quaternion``: :func:`blastscale.sim3d.replay.point_positions`),
  so that translation, rocking and the turn out of the blast's plane all move it; its displacement along x
  (the blast) and z (up).
* **The measured outcome** (:func:`measured_outcome`): the 3D rules of :mod:`blastscale.sim3d.record`. A body
  has fallen when its centre of mass dropped by more than ``FALL_DROP_FRACTION`` of its own height, or it
  turned by more than the kind's limit: ``FALL_TILT_DEG`` for kinds that collapse when a block falls (walls,
  arches, portals, block-model files: ``collapse_rule = "fallen"``), the body's own toppling angle for a
  column or a block (``"toppling"``; there a drop by half a body's height is taken as a sufficient sign too:
  it cannot happen while the stack below stands). The structure collapsed when any body judged fell.

What a marker can tell: a track gives the marker's x and z (the camera's plane). **One marker** on a body
gives its own drop, which stands for the body's centre-of-mass drop (exact for a translation; a turn moves
the marker by ``(R - I) r`` more, r its lever from the centre of mass: a marker near the centre of mass is
best). **Two markers** on one body give its turn in the x-z plane (the angle swept by the line joining them)
and with it the centre of mass's drop exactly for a motion in that plane; a turn out of the plane is not
seen (the in-plane angle is a lower bound of the turn). Nothing is judged for a body without markers nor for a
marker without a z column; the sub-stack rule of columns (the centre of mass of the drums above outside a
drum's base) needs every drum's pose and is not judged from markers.
"""

from __future__ import annotations

import math

import numpy as np

from ..sim3d.record import FALL_DROP_FRACTION, FALL_TILT_DEG
from ..sim3d.replay import point_positions, rotations
from ..sim3d.results import body_heights
from .inputs import body_gaps

__all__ = ["MARKER_SHARED", "body_verdicts", "marker_body", "measured_outcome", "pose_marker_history"]

#: Two bodies whose distances to a marker's rest point differ by less than this [m] (x (1 + |p| / 1 m)): the
#: point is on both (a shared face) and goes to the body whose centre of mass is nearer.
MARKER_SHARED = 1e-9


def marker_body(structure, point_m) -> int:
    """Index of the body that carries a marker at rest at ``point_m`` [m], anywhere on it (module docstring):
    the body whose solid it is on or nearest to (:func:`~.inputs.body_gaps`); a point on the face two bodies
    share (a bed joint), or equally near two, goes to the one whose centre of mass is nearer."""
    p = np.asarray(point_m, dtype=float)
    gaps = body_gaps(structure, p)
    near = np.flatnonzero(gaps <= gaps.min() + MARKER_SHARED * (1.0 + float(np.max(np.abs(p)))))
    com = [np.linalg.norm(np.asarray(structure.bodies[k].com, dtype=float) - p) for k in near]
    return int(near[int(np.argmin(com))])


def pose_marker_history(ds, structure, point_m) -> tuple[np.ndarray, np.ndarray]:
    """(ux, uz) [m]: the displacement of the point at rest ``point_m`` [m], fixed on its body
    (:func:`marker_body`), from the body poses of a 3D result's dataset ``ds``."""
    k = marker_body(structure, point_m)
    pos = np.asarray(ds["body_position"].values)
    q = np.asarray(ds["body_quaternion"].values)
    local = rotations(q[0, k]).T @ (np.asarray(point_m, dtype=float) - pos[0, k])  # the point in the body frame
    w = point_positions(pos, q, [k], local[None, :])[:, 0, :]
    u = w - w[0]  # from the first record (the rest pose: the load starts at time 0)
    return u[:, 0], u[:, 2]


def body_verdicts(structure, markers: dict) -> dict:
    """Per body with at least one marker that has a z column: ``{"drop_m", "turn_rad" (None with one marker),
    "fell"}`` (module docstring). ``markers``: name -> (point_m [m], ux [m], uz [m] or None), all on the same
    frames."""
    rule = getattr(structure, "collapse_rule", "toppling")
    heights = body_heights(structure)
    by_body: dict = {}
    for point, ux, uz in markers.values():
        if uz is not None:
            by_body.setdefault(marker_body(structure, point), []).append((np.asarray(point, float), ux, uz))
    out = {}
    for k, ms in sorted(by_body.items()):
        body = structure.bodies[k]
        com0 = np.asarray(body.com, dtype=float)[[0, 2]]
        (p1, ux1, uz1) = ms[0]
        a0 = p1[[0, 2]]
        a = a0[None, :] + np.column_stack([ux1, uz1])
        turn = None
        if len(ms) >= 2:  # two markers: the turn in the x-z plane and the centre of mass through it
            p2, ux2, uz2 = ms[1]
            v0 = p2[[0, 2]] - a0
            v = v0[None, :] + np.column_stack([ux2 - ux1, uz2 - uz1])
            turn = np.arctan2(v[:, 1], v[:, 0]) - math.atan2(v0[1], v0[0])
            turn = (turn + math.pi) % (2 * math.pi) - math.pi
            c, s = np.cos(turn), np.sin(turn)
            r = com0 - a0
            drop = -(a[:, 1] + s * r[0] + c * r[1] - com0[1])
        else:  # one marker: its own drop stands for the centre of mass's
            drop = -np.asarray(uz1, dtype=float)
        limit = math.radians(FALL_TILT_DEG) if rule == "fallen" else float(body.toppling_angle)
        fell = bool(np.max(drop) > FALL_DROP_FRACTION * heights[k])
        if turn is not None:
            fell |= bool(np.max(np.abs(turn)) > limit)
        out[k] = {
            "drop_m": float(np.max(drop)),
            "turn_rad": None if turn is None else float(np.max(np.abs(turn))),
            "fell": fell,
        }
    return out


def measured_outcome(structure, markers: dict) -> bool | None:
    """True (collapsed) when any body judged from the markers fell, False when none did, None when no body
    could be judged (:func:`body_verdicts`)."""
    v = body_verdicts(structure, markers)
    return None if not v else any(b["fell"] for b in v.values())
