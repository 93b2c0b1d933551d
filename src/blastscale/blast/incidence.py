"""Angle-of-incidence models: peak pressure and impulse on an oblique face (chosen by name).

Names (``INCIDENCE_MODELS``): ``"ufc"`` (default; UFC 3-340-02 Figs. 2-193/2-194, tabulated)
and ``"closed-form"`` (Randers-Pehrson & Bannister 1997). Work in progress: see issue 9.
"""

from __future__ import annotations

__all__ = ["INCIDENCE_MODELS", "DEFAULT_INCIDENCE", "oblique_peak", "oblique_impulse"]

#: Names accepted by ``incidence=`` everywhere; the first is the default.
INCIDENCE_MODELS = ("ufc", "closed-form")
DEFAULT_INCIDENCE = INCIDENCE_MODELS[0]


def oblique_peak(model: str, angle, reflected_pressure, incident_pressure):
    """Peak overpressure [Pa] on a face at angle of incidence ``angle`` [rad]."""
    raise NotImplementedError


def oblique_impulse(model: str, angle, reflected_impulse, incident_impulse, scaled_distance):
    """Positive-phase impulse [Pa*s] on a face at angle of incidence ``angle`` [rad]."""
    raise NotImplementedError
