"""The rocking frame: free-standing columns capped by a free lintel, as one equivalent block.

Makris & Vassiliou (2013) show that N identical free-standing rectangular columns (half-width b,
half-height h, size R = sqrt(b^2 + h^2), slenderness alpha = atan(b / h), mass m each) capped by a
freely supported rigid beam of mass m_b rock in their plane (the columns turning together about
their base corners, the beam translating) exactly as a single column of the same slenderness with
the frequency parameter

.. math:: \\hat p = p\\,\\sqrt{\\frac{1 + 2\\gamma}{1 + 3\\gamma}},\\qquad
          p = \\sqrt{\\frac{3 g}{4 R}},\\qquad \\gamma = \\frac{m_b}{N m},

i.e. a larger column, R_eq = R (1 + 3 gamma) / (1 + 2 gamma): the heavier the beam, the more stable
the frame, while the acceleration that uplifts it, g tan(alpha), does not depend on gamma.
Derivation (checked here by Lagrange's equation): the beam rides on the column tops diagonally
opposite the pivots, at 2R from them, so it moves with speed 2R theta_dot and its centre of mass
rises as 2R cos(alpha - theta); kinetic energy (N (4/3) m R^2 + 4 m_b R^2) theta_dot^2 / 2,
potential (N m + 2 m_b) g R cos(alpha - theta), hence
theta_ddot = -p_hat^2 sin(alpha - theta) for theta > 0.

From rest at theta = 0 with angular velocity omega_0 (an impulse), energy conservation gives the
peak rotation and the overturning threshold (Housner 1963 with p -> p_hat):

.. math:: \\cos(\\alpha - \\theta_{max}) = \\cos\\alpha + \\frac{\\omega_0^2}{2 \\hat p^2},\\qquad
          \\omega_{crit} = \\hat p \\sqrt{2 (1 - \\cos\\alpha)}.

References
----------
.. [1] N. Makris & M. F. Vassiliou (2013), Planar rocking response and stability analysis of an array
       of free-standing columns capped with a freely supported rigid beam, *Earthquake Engng Struct.
       Dyn.* 42(3), 431-449, doi:10.1002/eqe.2222.
.. [2] G. W. Housner (1963), The behavior of inverted pendulum structures during earthquakes,
       *Bull. Seismol. Soc. Am.* 53(2), 403-417.
"""

from __future__ import annotations

import math

from .._validate import check_positive_scalar, check_range
from ..constants import STANDARD_GRAVITY

__all__ = ["frame_frequency_parameter", "free_rocking_peak", "overturning_angular_velocity"]


def frame_frequency_parameter(size_m: float, mass_ratio: float, gravity: float = STANDARD_GRAVITY) -> float:
    """p_hat of a rocking frame [rad/s] (module docstring, Makris & Vassiliou 2013).

    Parameters
    ----------
    size_m : float
        R of one column, half its diagonal [m], > 0.
    mass_ratio : float
        gamma = beam mass / total mass of the columns [-], >= 0 (0: a free column, p_hat = p).
    gravity : float
        g [m/s^2].

    Returns
    -------
    float
        sqrt(3 g / 4 R) sqrt((1 + 2 gamma) / (1 + 3 gamma)) [rad/s].
    """
    R = check_positive_scalar("column size R", size_m, "m")
    gam = float(check_range("frame mass ratio gamma", mass_ratio, 0.0, math.inf))
    g = check_positive_scalar("gravity", gravity, "m/s^2")
    return math.sqrt(3.0 * g / (4.0 * R)) * math.sqrt((1.0 + 2.0 * gam) / (1.0 + 3.0 * gam))


def free_rocking_peak(angular_velocity: float, alpha: float, p: float) -> float:
    """Peak rotation [rad] of a block (or frame) started upright with ``angular_velocity`` omega_0
    [rad/s]; inf when it overturns (omega_0 >= :func:`overturning_angular_velocity`).

    .. math:: \\theta_{max} = \\alpha - \\arccos\\left(\\cos\\alpha + \\frac{\\omega_0^2}{2 p^2}\\right)
    """
    a = float(check_range("slenderness alpha", alpha, 0.0, math.pi / 2, "rad", lo_open=True, hi_open=True))
    pp = check_positive_scalar("frequency parameter p", p, "rad/s")
    c = math.cos(a) + float(angular_velocity) ** 2 / (2.0 * pp * pp)
    return math.inf if c >= 1.0 else a - math.acos(c)


def overturning_angular_velocity(alpha: float, p: float) -> float:
    """Least initial angular velocity [rad/s] that overturns a block (or frame) started upright,
    p sqrt(2 (1 - cos alpha)) (Housner 1963; p_hat for the frame)."""
    a = float(check_range("slenderness alpha", alpha, 0.0, math.pi / 2, "rad", lo_open=True, hi_open=True))
    return check_positive_scalar("frequency parameter p", p, "rad/s") * math.sqrt(2.0 * (1.0 - math.cos(a)))
