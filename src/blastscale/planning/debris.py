"""How far the blocks travel: the reach of a simulated response and the debris zone.

The *reach* is the largest horizontal distance of any point of any block from the structure's
original base centre, over the simulated response:

* planar rocking of a block (width 2b, height 2h, rotating about its far base edge): the top corner
  away from the charge reaches ``b + 2h sin(theta_max)``; a block that overturns ends on its side,
  ``b + 2h``;
* 3D rigid bodies: ``max_t |x_c(t) - x_0|_horizontal + rho_b + c_b sin(phi_b(t))`` over the bodies,
  x_c a body's centre of mass, x_0 the structure's base centre, rho_b the largest horizontal distance
  of the body's solid (its vertices, ``RigidBody.vertices``) from its centre of mass at rest (a box:
  sqrt(a^2 + d^2)), c_b their largest height above or depth below it (a box: c) and phi_b its tilt: a
  bound on any of its points (a point's horizontal offset from the centre of mass grows by at most
  |z| sin(phi) when the body tilts by phi); blocks that slide or fly off are followed as far as the
  simulation goes.

The debris zone is a circle around the specimen of radius ``margin x reach`` (``[lab]
debris_margin``, default 2: blocks that fall bounce and slide on a real floor, which neither model
follows after the impact).
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["planar_reach", "reach_3d", "body_extent"]


def planar_reach(width_m: float, height_m: float, max_rotation_rad: float, collapsed: bool) -> float:
    """Reach [m] of a rocking block (module docstring): ``b + 2h sin(theta_max)``, ``b + 2h`` when
    it overturns."""
    th = 0.5 * math.pi if collapsed else min(abs(float(max_rotation_rad)), 0.5 * math.pi)
    return 0.5 * float(width_m) + float(height_m) * math.sin(th)


def body_extent(body) -> tuple:
    """(rho, c) [m] of a rigid body at rest (module docstring): the largest horizontal distance of its
    solid's vertices from its centre of mass (a box: sqrt(a^2 + d^2); a drum: its base's circumradius
    or half-diagonal) and their largest vertical distance from it (a box: its half height c)."""
    v = np.asarray(body.vertices, dtype=float)
    return float(np.hypot(v[:, 0], v[:, 1]).max()), float(np.abs(v[:, 2]).max())


def reach_3d(dataset, structure) -> float:
    """Reach [m] of a 3D response (module docstring) from its ``com_displacement`` (time, body,
    component) [m] and ``tilt`` (time, body) [rad] histories and the structure's bodies."""
    d = np.asarray(dataset["com_displacement"].values, dtype=float)  # (time, body, 3)
    tilt = np.asarray(dataset["tilt"].values, dtype=float)  # (time, body)
    bodies = list(structure.bodies)
    com0 = np.array([b.com for b in bodies], dtype=float)  # original centres, structure frame
    centre = np.array([com0[0, 0], com0[0, 1]])
    pos = com0[None, :, :2] + d[:, :, :2]
    dist = np.sqrt(((pos - centre) ** 2).sum(axis=-1))  # (time, body)
    ext = np.array([body_extent(b) for b in bodies])  # (body, 2)
    return float(np.nanmax(dist + ext[None, :, 0] + ext[None, :, 1] * np.sin(np.minimum(np.abs(tilt), 0.5 * np.pi))))
