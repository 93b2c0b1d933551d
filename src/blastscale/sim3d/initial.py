"""Initial state of a 3D run: a structure tilted onto a base edge, rocking about it, or moving.

The planar rocking problem starts a block from a tilt theta_0 resting on one base edge
(Housner's free rocking) or from an angular velocity about that edge (his overturning
threshold). The engine starts any structure that way, rigidly: every body turned by theta_0
about the y axis through the supporting base edge of the lowest body
(:func:`tilt_bodies`, used when the scene is built), and every body given the rigid velocity of
a rotation omega_0 about that edge plus a common translation (:func:`rigid_rocking_velocity`,
applied after settling). For one block both reduce to the planar initial conditions of
:mod:`blastscale.rocking`. Any other motion (a mechanism: the columns of a rocking frame, each about
its own edge, and the lintel translating) is given body by body (:func:`body_velocities`).
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from .._validate import BlastscaleInputError

__all__ = ["body_velocities", "rigid_rocking_velocity", "support_edge", "tilt_bodies"]


def support_edge(shape, side: float) -> np.ndarray:
    """Mid-point of a body's supporting base edge in its body frame [m], shape (3,): the base's
    largest x (``side`` > 0, the rear edge a blast from -x rocks it about) or smallest x
    (``side`` < 0), at the base's lowest z, on y = 0."""
    bp = np.asarray(shape.base_points(), dtype=float)
    return np.array([bp[:, 0].max() if side > 0 else bp[:, 0].min(), 0.0, bp[:, 2].min()])


def _quaternion_product(p, q) -> tuple:
    """Hamilton product p q of unit quaternions (w, x, y, z): the rotation q, then p."""
    pw, px, py, pz = p
    qw, qx, qy, qz = q
    return (
        pw * qw - px * qx - py * qy - pz * qz,
        pw * qx + px * qw + py * qz - pz * qy,
        pw * qy - px * qz + py * qw + pz * qx,
        pw * qz + px * qy - py * qx + pz * qw,
    )


def tilt_bodies(bodies, rotation: float) -> tuple:
    """The bodies turned rigidly by ``rotation`` theta_0 [rad] about the y axis through the
    supporting base edge of the lowest body (:func:`support_edge` of ``bodies[0]``: its +x edge
    when theta_0 > 0, its -x edge when theta_0 < 0), top towards +x when theta_0 > 0:

    .. math:: p' = P + R_y(\\theta_0)\\,(p - P),\\qquad q' = q_{\\theta_0}\\, q,

    so a block rests on that edge exactly where it stood upright (Housner's initial tilt).

    Parameters
    ----------
    bodies : sequence of BodySpec
        The bodies at rest, the lowest first.
    rotation : float
        theta_0 [rad], |theta_0| < pi/2.

    Returns
    -------
    tuple of BodySpec
    """
    th = float(rotation)
    if not abs(th) < math.pi / 2:
        raise BlastscaleInputError(f"initial rotation = {th:.6g} rad is out of range: valid range is (-pi/2, pi/2)")
    bodies = tuple(bodies)
    if th == 0.0:
        return bodies
    edge = support_edge(bodies[0].shape, 1.0 if th > 0 else -1.0)
    px, pz = bodies[0].position[0] + edge[0], bodies[0].position[2] + edge[2]
    c, sn = math.cos(th), math.sin(th)
    q_th = (math.cos(th / 2), 0.0, math.sin(th / 2), 0.0)  # rotation th about +y: body z tilts towards +x
    out = []
    for b in bodies:
        dx, dz = b.position[0] - px, b.position[2] - pz
        pos = (px + c * dx + sn * dz, b.position[1], pz + -sn * dx + c * dz)
        out.append(replace(b, position=pos, quaternion=_quaternion_product(q_th, b.quaternion)))
    return tuple(out)


def rigid_rocking_velocity(scene, rotation: float, angular_velocity: float, velocity, factors=(1.0, 1.0)):
    """The initial velocity of a rigid rotation about the supporting base edge plus a translation,
    as a function ``initial(mj_model, data)`` setting MuJoCo's ``qvel`` (None when both are zero).

    .. math:: v_k = \\omega \\times (x_k - P) + v_0,\\qquad \\omega = (0, \\omega_0, 0),

    with P the edge of :func:`support_edge` of the lowest body (the +x edge when theta_0 > 0, or
    theta_0 = 0 and omega_0 >= 0, else the -x edge), x_k each body's centre of mass; a free
    joint's angular velocity is given in its body frame (R_k^T omega).

    Parameters
    ----------
    scene : Scene
        The scene, in the engine's reference units.
    rotation : float
        The initial tilt theta_0 [rad] (chooses the edge).
    angular_velocity : float
        omega_0 [rad/s], physical units.
    velocity : array (3,)
        v_0 [m/s], physical units.
    factors : (float, float)
        Length and time factors (a, b) to the reference units
        (:func:`~.reference.reference_factors`): angular velocities / b, velocities x a / b.

    Returns
    -------
    callable or None
    """
    om0, v0 = float(angular_velocity), np.asarray(velocity, dtype=float)
    if om0 == 0.0 and not np.any(v0 != 0.0):
        return None
    a, b = factors
    th0 = float(rotation)
    s = 1.0 if (th0 > 0.0 or (th0 == 0.0 and om0 >= 0.0)) else -1.0
    edge = support_edge(scene.bodies[0].shape, s)

    def initial(m, d):
        import mujoco

        mujoco.mj_forward(m, d)
        ids, dofs = scene.body_ids, scene.qvel_index().reshape(-1, 6)
        pivot = d.xmat[ids[0]].reshape(3, 3) @ edge + d.xpos[ids[0]]
        w = np.array([0.0, om0 / b, 0.0])
        for i, q in zip(ids, dofs):
            d.qvel[q[0:3]] = np.cross(w, d.xpos[i] - pivot) + v0 * (a / b)
            d.qvel[q[3:6]] = d.xmat[i].reshape(3, 3).T @ w  # body frame

    return initial


def body_velocities(velocities, scene, factors=(1.0, 1.0)):
    """The initial velocity of each body given whole, as a function ``initial(mj_model, data)``
    adding to MuJoCo's ``qvel`` after settling (None when ``velocities`` is None).

    Parameters
    ----------
    velocities : array (nbody, 6)
        Per body: velocity of its centre of mass [m/s] and angular velocity [rad/s], world frame,
        physical units.
    scene : Scene
        The scene (its bodies' MuJoCo ids, :attr:`~.model.Scene.body_ids`).
    factors : (float, float)
        Length and time factors (a, b) to the reference units.

    Returns
    -------
    callable or None
    """
    if velocities is None:
        return None
    ids, dofs = scene.body_ids, scene.qvel_index().reshape(-1, 6)
    nbody = ids.size
    v = np.asarray(velocities, dtype=float)
    if v.shape != (nbody, 6) or not np.all(np.isfinite(v)):
        raise BlastscaleInputError(f"initial body velocities must be finite, shape ({nbody}, 6), got {v.shape}")
    a, b = factors

    def initial(m, d):
        import mujoco

        mujoco.mj_forward(m, d)
        for k, (i, q) in enumerate(zip(ids, dofs)):
            d.qvel[q[0:3]] += v[k, 0:3] * (a / b)
            d.qvel[q[3:6]] += d.xmat[i].reshape(3, 3).T @ (v[k, 3:6] / b)  # body frame

    return initial
