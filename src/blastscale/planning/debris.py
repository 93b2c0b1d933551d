"""How far the blocks travel: the reach of a simulated response and the debris zone.

The *reach* is the largest horizontal distance of any point of any block from the structure's
original base centre, over the simulated response:

* planar rocking of a block (width 2b, height 2h, rotating about its far base edge): the top corner
  away from the charge reaches ``b + 2h sin(theta_max)``; a block that overturns ends on its side,
  ``b + 2h``;
* 3D rigid bodies: ``max_t |x_c(t) - x_0|_horizontal + r_b`` over the bodies, x_c a body's centre of
  mass, x_0 the structure's base centre, r_b the body's circumscribed radius (a bound on any of its
  points; blocks that slide or fly off are followed as far as the simulation goes).

The debris zone is a circle around the specimen of radius ``margin x reach`` (``[lab]
debris_margin``, default 2: blocks that fall bounce and slide on a real floor, which neither model
follows after the impact).
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["planar_reach", "reach_3d", "body_radius"]


def planar_reach(width_m: float, height_m: float, max_rotation_rad: float, collapsed: bool) -> float:
    """Reach [m] of a rocking block (module docstring): ``b + 2h sin(theta_max)``, ``b + 2h`` when
    it overturns."""
    th = 0.5 * math.pi if collapsed else min(abs(float(max_rotation_rad)), 0.5 * math.pi)
    return 0.5 * float(width_m) + float(height_m) * math.sin(th)


def body_radius(body) -> float:
    """Circumscribed radius [m] of a rigid body's shape about its centre of mass (a box: its
    half-diagonal; a prism: sqrt(radius^2 + half height^2))."""
    shape = body.shape
    if hasattr(shape, "half_width"):
        return math.sqrt(shape.half_width ** 2 + shape.half_depth ** 2 + shape.half_height ** 2)
    return math.sqrt(shape.radius ** 2 + shape.half_height ** 2)


def reach_3d(dataset, structure) -> float:
    """Reach [m] of a 3D response (module docstring) from its ``com_displacement`` (time, body,
    component) history [m] and the structure's bodies."""
    d = np.asarray(dataset["com_displacement"].values, dtype=float)  # (time, body, 3)
    bodies = list(structure.bodies)
    com0 = np.array([b.com for b in bodies], dtype=float)  # original centres, structure frame
    centre = np.array([com0[0, 0], com0[0, 1]])
    pos = com0[None, :, :2] + d[:, :, :2]
    dist = np.sqrt(((pos - centre) ** 2).sum(axis=-1))  # (time, body)
    radii = np.array([body_radius(b) for b in bodies])
    return float(np.nanmax(dist + radii[None, :]))
