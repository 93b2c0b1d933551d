"""The first free swing in closed form: margin and peak from the state when the pulse ends.

Once the pulse is over the planar rocking motion (paper Eq. eom, in units of ``m g r`` and the
dimensionless time ``tau = p t``) is free and conservative between impacts, with the energy
``E = theta_dot^2 / 2 + cos(alpha - s theta) - cos(alpha)`` against the barrier ``B = 1 - cos(alpha)``,
and every impact multiplies the energy by ``e^2`` (Housner 1963). The outcome and the largest
rotation of the whole motion are therefore functions of the state when the pulse ends alone:
:func:`first_swing_margin` (the signed margin mu, > 0 overturns; the case table and the argument
are in :mod:`blastscale.rocking.swing`, which integrates the pulse phase) and
:func:`first_swing_peak`. Plain numpy on arrays, no kernel.

References: paper Sec. "Equations of motion"; Housner (1963), Bull. Seismol. Soc. Am. 53(2)
(energy and restitution); Masi et al. (2019), Int. J. Mech. Sci. 157.
"""

from __future__ import annotations

import numpy as np

__all__ = ["first_swing_margin", "first_swing_peak"]


def first_swing_margin(alpha, e, theta, w, tipped):
    """First-swing margin mu [-] from the state when the pulse ends (the table of :mod:`blastscale.rocking.swing`).

    Parameters
    ----------
    alpha : array_like
        Slenderness angle [rad].
    e : array_like
        Restitution on the angular velocity [-].
    theta : array_like
        Angle when the pulse ends [rad].
    w : array_like
        Angular velocity when the pulse ends, divided by p [-].
    tipped : array_like of bool
        Whether the body tipped away from the blast while the pulse acted.

    Returns
    -------
    mu : ndarray
        > 0 where the body overturns, <= 0 where it survives.
    """
    alpha, e, th, w = (np.asarray(x, dtype=float) for x in (alpha, e, theta, w))
    s = np.sign(th)
    s = np.where(s == 0.0, np.sign(w), s)
    u = s * th  # distance from upright in the current rocking mode [rad]
    v = s * w  # outward angular velocity
    B = 1.0 - np.cos(alpha)
    E = 0.5 * w * w + np.cos(alpha - u) - np.cos(alpha)
    below = (E / B - 1.0, e * e * E / B - 1.0)
    past = 1.0 - np.cos(u - alpha)  # depth below the top once beyond it
    mu = np.where(
        u < alpha,
        np.where(v >= 0.0, below[0], below[1]),
        np.where(v >= 0.0, (0.5 * w * w + past) / B, np.where(E > B, below[1], (past - 0.5 * w * w) / B)),
    )
    mu = np.where(np.asarray(tipped, dtype=bool), np.maximum(below[0], np.finfo(float).tiny), mu)
    return np.where(s == 0.0, -1.0, mu)


def first_swing_peak(alpha, e, theta, w, pulse_max, rest_velocity: float = 0.0):
    """Largest |theta| [rad] of the whole motion of a body that survives, from the state when
    the pulse ends (first-swing energy argument, :mod:`blastscale.rocking.swing`).

    After the pulse the motion is free: between impacts the energy ``E = w^2/2 + cos(alpha -
    s theta) - cos(alpha)`` is conserved and each impact multiplies it by ``e^2`` (Housner 1963),
    so every later peak is lower than the first free one. With ``y = alpha - |theta_peak|`` the
    distance of a peak below the top, ``w = 0`` there gives ``1 - cos(y) = B - E``, i.e.
    ``sin^2(y / 2) = sin^2((alpha - s theta) / 2) - w^2 / 4``, written without cancellation:

    * moving outward (below the top): the peak of this swing, ``|theta_peak| = alpha - y``;
    * moving inward (or beyond the top, climbing back over it): the body impacts with
      ``w^2 = 2 E``, rebounds with ``e w`` (at rest if ``e |w| <= rest_velocity``) and peaks on
      the other side, ``sin^2(y / 2) = sin^2(alpha / 2) - e^2 E / 2``;
    * at rest: no further peak.

    The result is the larger of that peak and ``pulse_max`` (the largest |theta| while the pulse
    acted). Where the body overturns (:func:`first_swing_margin` > 0) the value is meaningless;
    :func:`first_swing` returns pi/2 there (it ends lying on its side).

    Parameters
    ----------
    alpha, e : array_like
        Slenderness [rad] and restitution [-].
    theta, w : array_like
        Angle [rad] and angular velocity / p [-] when the pulse ends.
    pulse_max : array_like
        Largest |theta| [rad] while the pulse acted.
    rest_velocity : float
        Rebound velocity / p [-] below which the body is at rest (the solver's ``rest_velocity``).

    Returns
    -------
    ndarray
        Largest |theta| [rad] over the whole motion.
    """
    alpha, e, th, w = (np.asarray(x, dtype=float) for x in (alpha, e, theta, w))
    s = np.sign(th)
    s = np.where(s == 0.0, np.sign(w), s)
    u, v = s * th, s * w
    ha = np.sin(0.5 * alpha) ** 2  # B / 2
    r_out = np.sin(0.5 * (alpha - u)) ** 2 - 0.25 * w * w  # (B - E) / 2
    E = 2.0 * (ha - r_out)
    r_in = ha - 0.5 * e * e * E
    with np.errstate(invalid="ignore"):
        y_out = 2.0 * np.arcsin(np.sqrt(np.maximum(r_out, 0.0)))
        y_in = 2.0 * np.arcsin(np.sqrt(np.maximum(r_in, 0.0)))
    rebound = e * np.sqrt(np.maximum(2.0 * E, 0.0))
    inward_peak = np.where((rebound > rest_velocity) & (e > 0.0), alpha - y_in, 0.0)
    peak = np.where((u < alpha) & (v >= 0.0), alpha - y_out, inward_peak)
    peak = np.where(s == 0.0, 0.0, peak)
    return np.maximum(np.asarray(pulse_max, dtype=float), peak)
