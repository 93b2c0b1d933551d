"""The paper's Appendix A air-blast fits (hemispherical surface burst), in SI.

Masi, Stefanou & Maffi-Berthier, *Scaling laws for the rigid-body response of masonry
structures under blast loads*, Appendix A (after Vannucci et al. 2017 and Masi et al. 2019,
themselves fitted to Kingery & Bulmash 1984). The printed fits give

* the normally reflected peak pressure P_ro in **MPa**,
* the scaled reflected impulse i_rw in **MPa*ms/kg^(1/3)**,
* the scaled arrival time t_Aw and positive duration t_ow in **ms/kg^(1/3)**,

as functions of Z [m/kg^(1/3)] (units established by independent calculation, see
``docs/paper_slips.md``). This module converts them to Pa, Pa*s/kg^(1/3) and s/kg^(1/3).

Validity
--------
* pressure and impulse: Z in [0.2, 20] m/kg^(1/3) (range of the underlying Kingery-Bulmash data);
* arrival time: Z in [0.2, 20];
* duration: Z in [0.2, 6.5] only. The printed coefficients are truncated: the fit departs
  from Kingery-Bulmash by more than 10 % at Z = 7.4 and diverges above Z ~ 12. The paper's
  constant below Z = 0.18 (0.251703 ms/kg^(1/3)) does not join the formula (6.7 % jump)
  and is reached only with ``extrapolate=True``.

Only reflected quantities are given by the paper; incident pressure, incident impulse and
shock-front velocity are not part of this model.
"""

from __future__ import annotations

import numpy as np

from .base import BlastModel

__all__ = ["Masi2021", "MASI2021_COEFFICIENTS"]

#: Coefficients printed in Appendix A of the paper (in the paper's units, see module doc).
MASI2021_COEFFICIENTS = {
    # P_ro [MPa] = (1 + 1/(2 e^{10 Z})) exp(a0 + a1 lnZ + a2 ln^2 Z + a3 sin(lnZ) + a4 sin^2(lnZ))
    "reflected_pressure": (2.0304, -1.8036, -0.09293, -0.8779, -0.3603),
    # i_rw [MPa ms/kg^(1/3)] = exp(c0 + c1 lnZ + c2 ln^2 Z)
    "scaled_reflected_impulse": (-0.110157, -1.40609, 0.0847358),
    # t_Aw [ms/kg^(1/3)] = exp(a0 + a1 lnZ + a2 ln^2 Z + a3 sin(lnZ)) for Z >= 0.18, else constant
    "scaled_arrival_time": (-0.6847, 1.4288, 0.0290, 0.4108),
    "scaled_arrival_time_below_018": 0.0315495,
    # t_ow [ms/kg^(1/3)] = exp(sum_k d_k ln^k Z + e0 cos^7[e1 (lnZ - e2)] sinh[e3 (lnZ - e4)]) for Z >= 0.18
    "scaled_positive_duration_poly": (0.592, 2.913, -1.287, -1.788, 1.151, 0.325, -0.383, 0.090, -0.004, -0.0004),
    "scaled_positive_duration_trig": (0.537, 1.032, 0.859, 1.088, 2.023),
    "scaled_positive_duration_below_018": 0.251703,
}

_MPA = 1.0e6  # Pa per MPa
_MPA_MS = 1.0e3  # Pa*s per MPa*ms
_MS = 1.0e-3  # s per ms


class Masi2021(BlastModel):
    """Appendix A fits of Masi, Stefanou & Maffi-Berthier (selectable as ``"masi2021"``).

    .. math::

        P_{ro}(Z) = \\left(1 + \\tfrac{1}{2 e^{10 Z}}\\right)\\exp\\left[2.0304 - 1.8036\\ln Z
        - 0.09293\\ln^2 Z - 0.8779\\sin(\\ln Z) - 0.3603\\sin^2(\\ln Z)\\right]\\ \\mathrm{MPa}

        i_{rw}(Z) = \\exp\\left[-0.110157 - 1.40609\\ln Z + 0.0847358\\ln^2 Z\\right]
        \\ \\mathrm{MPa\\,ms/kg^{1/3}}

    and the arrival-time and duration fits of the paper's Appendix A (module docstring).
    """

    name = "masi2021"
    ranges = {
        "reflected_pressure": (0.2, 20.0),
        "scaled_reflected_impulse": (0.2, 20.0),
        "scaled_arrival_time": (0.2, 20.0),
        "scaled_positive_duration": (0.2, 6.5),
    }

    @staticmethod
    def _raw_reflected_pressure(z):
        a0, a1, a2, a3, a4 = MASI2021_COEFFICIENTS["reflected_pressure"]
        L = np.log(z)
        s = np.sin(L)
        expo = a0 + a1 * L + a2 * L**2 + a3 * s + a4 * s**2
        return (1.0 + 0.5 * np.exp(-10.0 * z)) * np.exp(expo) * _MPA

    @staticmethod
    def _raw_scaled_reflected_impulse(z):
        c0, c1, c2 = MASI2021_COEFFICIENTS["scaled_reflected_impulse"]
        L = np.log(z)
        return np.exp(c0 + c1 * L + c2 * L**2) * _MPA_MS

    @staticmethod
    def _raw_scaled_arrival_time(z):
        a0, a1, a2, a3 = MASI2021_COEFFICIENTS["scaled_arrival_time"]
        L = np.log(z)
        fit = np.exp(a0 + a1 * L + a2 * L**2 + a3 * np.sin(L))
        return np.where(z >= 0.18, fit, MASI2021_COEFFICIENTS["scaled_arrival_time_below_018"]) * _MS

    @staticmethod
    def _raw_scaled_positive_duration(z):
        d = MASI2021_COEFFICIENTS["scaled_positive_duration_poly"]
        e0, e1, e2, e3, e4 = MASI2021_COEFFICIENTS["scaled_positive_duration_trig"]
        L = np.log(z)
        poly = np.polynomial.polynomial.polyval(L, d)
        trig = e0 * np.cos(e1 * (L - e2)) ** 7 * np.sinh(e3 * (L - e4))
        fit = np.exp(poly + trig)
        return np.where(z >= 0.18, fit, MASI2021_COEFFICIENTS["scaled_positive_duration_below_018"]) * _MS
