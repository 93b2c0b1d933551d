"""Air at sea level and the Rankine-Hugoniot relations of a shock in it (perfect gas, gamma = 1.4).

The blast fits give the incident (side-on) overpressure P_so of the shock; the clearing of a
finite face (:mod:`.clearing`) and the shock velocity of a fit that does not tabulate it need the
state of the air behind the incident shock and behind the shock reflected from a rigid face. For
a perfect gas of ratio of specific heats gamma these are closed forms of the pressure ratio
``xi = (p0 + P_so) / p0`` (Rankine-Hugoniot; Kinney & Graham 1985, ch. 5; Baker 1973, ch. 2):

* shock-front velocity ``U = c0 sqrt(1 + (gamma + 1)/(2 gamma) P_so/p0)`` (= ``c0 sqrt(1 + 6 P_so/(7 p0))``);
* peak dynamic pressure ``q_o = 5 P_so^2 / (2 (P_so + 7 p0))`` (UFC 3-340-02 Fig. 2-3 charts it);
* density ratio across a shock of pressure ratio ``r``: ``((gamma+1) r + (gamma-1)) / ((gamma-1) r + (gamma+1))``;
* normally reflected shock: pressure ratio behind it ``p_r / p_1 = ((3 gamma - 1) xi - (gamma - 1)) /
  ((gamma - 1) xi + gamma + 1)``, so ``P_r = 2 P_so (7 p0 + 4 P_so) / (7 p0 + P_so)`` (gamma = 1.4);
* sound speed in the reflected region ``C_r = c0 sqrt(T_r / T_0)`` with ``T_r / T_0`` the product of
  the two shocks' temperature ratios (pressure ratio over density ratio); UFC 3-340-02 Fig. 2-192
  charts C_r against P_so.

Real air departs from gamma = 1.4 above a few MPa (dissociation); the fits' own P_r already include
it, the closed forms here are used only for the relief of a face (C_r, q_o) and for U of the
free-air fit, where the incident overpressure of the cases of interest is below ~2 MPa.

References
----------
.. [1] Kinney, G. F. & Graham, K. J. (1985). *Explosive Shocks in Air*, 2nd ed., Springer, ch. 5.
.. [2] Baker, W. E. (1973). *Explosions in Air*. University of Texas Press, ch. 2.
.. [3] UFC 3-340-02 (2008). *Structures to Resist the Effects of Accidental Explosions*,
       Fig. 2-3 (peak dynamic pressure) and Fig. 2-192 (sound velocity in the reflected region).
"""

from __future__ import annotations

import numpy as np

__all__ = [
    "SEA_LEVEL_PRESSURE",
    "SEA_LEVEL_SOUND_SPEED",
    "GAMMA_AIR",
    "shock_velocity",
    "dynamic_pressure",
    "reflected_overpressure",
    "reflected_sound_speed",
]

#: Ambient pressure at sea level p0 [Pa] (ISA).
SEA_LEVEL_PRESSURE = 101325.0
#: Sound speed at sea level c0 [m/s] (ISA, 15 C).
SEA_LEVEL_SOUND_SPEED = 340.3
#: Ratio of specific heats of air [-].
GAMMA_AIR = 1.4


def _ret(x, like):
    return x if np.ndim(like) else float(x)


def _density_ratio(r):
    """Density ratio across a shock of pressure ratio r (Rankine-Hugoniot, perfect gas)."""
    g = GAMMA_AIR
    return ((g + 1.0) * r + (g - 1.0)) / ((g - 1.0) * r + (g + 1.0))


def shock_velocity(incident_pressure):
    """Shock-front velocity U [m/s] of a shock of overpressure P_so [Pa] (>= 0) into still air.

    .. math:: U = c_0 \\sqrt{1 + \\frac{\\gamma + 1}{2\\gamma}\\,\\frac{P_{so}}{p_0}}

    Reference: Kinney & Graham (1985), ch. 5 (Rankine-Hugoniot, gamma = 1.4).
    """
    P = np.asarray(incident_pressure, dtype=float)
    g = GAMMA_AIR
    return _ret(
        SEA_LEVEL_SOUND_SPEED * np.sqrt(1.0 + (g + 1.0) / (2.0 * g) * P / SEA_LEVEL_PRESSURE), incident_pressure
    )


def dynamic_pressure(incident_pressure):
    """Peak dynamic pressure q_o [Pa] behind a shock of overpressure P_so [Pa].

    .. math:: q_o = \\frac{5}{2}\\,\\frac{P_{so}^2}{P_{so} + 7 p_0}

    (gamma = 1.4). Reference: UFC 3-340-02 (2008) Fig. 2-3; Kinney & Graham (1985), ch. 5.
    """
    P = np.asarray(incident_pressure, dtype=float)
    return _ret(2.5 * P * P / (P + 7.0 * SEA_LEVEL_PRESSURE), incident_pressure)


def reflected_overpressure(incident_pressure):
    """Normally reflected overpressure [Pa] of a shock of overpressure P_so [Pa] on a rigid wall.

    .. math:: P_r = 2 P_{so}\\,\\frac{7 p_0 + 4 P_{so}}{7 p_0 + P_{so}}

    (gamma = 1.4; the blast fits' own P_r is used for loads, this only checks them).
    Reference: Kinney & Graham (1985), ch. 5.
    """
    P = np.asarray(incident_pressure, dtype=float)
    p0 = SEA_LEVEL_PRESSURE
    return _ret(2.0 * P * (7.0 * p0 + 4.0 * P) / (7.0 * p0 + P), incident_pressure)


def reflected_sound_speed(incident_pressure):
    """Sound speed C_r [m/s] in the air behind the shock reflected from a rigid face.

    With ``xi = 1 + P_so / p0`` the incident pressure ratio and ``eta = ((3 gamma - 1) xi -
    (gamma - 1)) / ((gamma - 1) xi + gamma + 1)`` the reflected one,

    .. math:: \\frac{C_r}{c_0} = \\sqrt{\\frac{T_r}{T_0}}, \\qquad
              \\frac{T_r}{T_0} = \\frac{\\xi}{\\rho_1/\\rho_0}\\,\\frac{\\eta}{\\rho_r/\\rho_1}

    (temperature ratio = pressure ratio / density ratio across each shock; perfect gas, gamma = 1.4).
    At P_so = 0 it is c0; at P_so = 100 psi (689 kPa) 661 m/s (2.17 ft/ms, UFC 3-340-02 Fig. 2-192
    reads about 2.2 ft/ms there).

    Parameters
    ----------
    incident_pressure : float or array_like
        Incident overpressure P_so [Pa], >= 0.

    Returns
    -------
    float or ndarray
        C_r [m/s].

    References: UFC 3-340-02 (2008) Fig. 2-192; Kinney & Graham (1985), ch. 5.
    """
    P = np.asarray(incident_pressure, dtype=float)
    g = GAMMA_AIR
    xi = 1.0 + P / SEA_LEVEL_PRESSURE
    eta = ((3.0 * g - 1.0) * xi - (g - 1.0)) / ((g - 1.0) * xi + g + 1.0)
    t_ratio = (xi / _density_ratio(xi)) * (eta / _density_ratio(eta))
    return _ret(SEA_LEVEL_SOUND_SPEED * np.sqrt(t_ratio), incident_pressure)
