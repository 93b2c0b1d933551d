"""Common interface of the empirical air-blast models (functions of scaled distance Z).

A model returns *scaled* quantities as functions of the Hopkinson-Cranz scaled distance
``Z = R / W**(1/3)`` [m/kg^(1/3)], in SI:

============================  ==========================  ===========================
quantity (method)             scaled unit                 to get the effective value
============================  ==========================  ===========================
reflected_pressure            Pa                          (not scaled)
incident_pressure             Pa                          (not scaled)
scaled_reflected_impulse      Pa*s/kg^(1/3)               multiply by W^(1/3)
scaled_incident_impulse       Pa*s/kg^(1/3)               multiply by W^(1/3)
scaled_arrival_time           s/kg^(1/3)                  multiply by W^(1/3)
scaled_positive_duration      s/kg^(1/3)                  multiply by W^(1/3)
shock_front_velocity          m/s                         (not scaled)
============================  ==========================  ===========================

Each quantity has its own validity range in Z (``valid_range(quantity)``). Outside it the
model raises :class:`~blastscale._validate.OutOfRangeError` naming the quantity, the Z value
and the range, unless ``extrapolate=True`` is passed, which evaluates the fit anyway and
emits an :class:`ExtrapolationWarning`. A fit extrapolated so far that it overflows or vanishes
raises :class:`~blastscale._validate.OutOfRangeError` even then (never an inf, 0 or NaN).

References: Swisdak (1994), DTIC ADA526744 (:mod:`.kingery_bulmash`); the paper's Appendix A
(:mod:`.masi_fits`); Baker et al. (1983), *Explosion Hazards and Evaluation*, ch. 2 (cube-root
scaling of time and impulse).
"""

from __future__ import annotations

import abc
import warnings
from typing import ClassVar

import numpy as np

from .._validate import OutOfRangeError, check_finite

__all__ = ["BlastModel", "ExtrapolationWarning", "QUANTITIES", "check_fit_range"]

QUANTITIES = (
    "reflected_pressure",
    "incident_pressure",
    "scaled_reflected_impulse",
    "scaled_incident_impulse",
    "scaled_arrival_time",
    "scaled_positive_duration",
    "shock_front_velocity",
)


class ExtrapolationWarning(UserWarning):
    """An empirical fit was evaluated outside its validity range on explicit request."""


def check_fit_range(z, valid_range, what: str, fit_range: str, extrapolate: bool, stacklevel: int = 2) -> None:
    """Check scaled distances against the validity range of an empirical fit.

    Parameters
    ----------
    z : ndarray
        Scaled distances Z [m/kg^(1/3)].
    valid_range : tuple of float
        ``(Z_min, Z_max)`` [m/kg^(1/3)] of the fit.
    what, fit_range : str
        What is evaluated and whose range it is, as the message names them
        (``"<what>: scaled distance Z = ... is outside <fit_range> [Z_min, Z_max] m/kg^(1/3)"``).
    extrapolate : bool
        Warn (:class:`ExtrapolationWarning`) instead of raising.
    stacklevel : int
        Of the warning, counted from the caller of this function (2: the caller's caller).

    Raises
    ------
    OutOfRangeError
        A Z outside ``[Z_min, Z_max]`` without ``extrapolate`` (the first one named).
    """
    lo, hi = valid_range
    out = (z < lo) | (z > hi)
    if np.any(out):
        zb = float(z[out].ravel()[0])
        msg = f"{what}: scaled distance Z = {zb:.6g} m/kg^(1/3) is outside {fit_range} [{lo:g}, {hi:g}] m/kg^(1/3)"
        if not extrapolate:
            raise OutOfRangeError(msg + " (opt in with extrapolate=True, CLI --extrapolate, to evaluate it anyway)")
        warnings.warn(msg + "; extrapolating", ExtrapolationWarning, stacklevel=stacklevel + 1)


class BlastModel(abc.ABC):
    """Abstract empirical blast model: scaled blast parameters as functions of Z.

    Subclasses set :attr:`name`, :attr:`ranges` (quantity -> (Z_min, Z_max) in
    m/kg^(1/3)) and implement the ``_raw_<quantity>`` methods (or one ``_raw(quantity, z)``)
    on plain float arrays, in SI. Quantities a model does not provide are absent from :attr:`ranges`.
    """

    name: ClassVar[str]
    ranges: ClassVar[dict[str, tuple[float, float]]]
    #: Burst type the fits describe (:mod:`.bursts`): "surface" (hemispherical) or "free-air" (spherical).
    burst: ClassVar[str] = "surface"

    # ----------------------------------------------------------------- helpers
    def provides(self, quantity: str) -> bool:
        """True when the model has a fit for ``quantity``."""
        return quantity in self.ranges

    def valid_range(self, quantity: str) -> tuple[float, float]:
        """Validity range ``(Z_min, Z_max)`` [m/kg^(1/3)] of ``quantity``."""
        if quantity not in self.ranges:
            raise NotImplementedError(f"blast model {self.name!r} provides no fit for {quantity}")
        return self.ranges[quantity]

    def _raw(self, quantity: str, z: np.ndarray) -> np.ndarray:
        """The fit of ``quantity`` at Z [m/kg^(1/3)] (float array), in SI, without range checks.

        Dispatches to ``_raw_<quantity>``; a model with one formula for every quantity overrides this.
        """
        return getattr(self, "_raw_" + quantity)(z)

    def _evaluate(self, quantity: str, Z, extrapolate: bool):
        z = check_finite("scaled distance Z", Z, "m/kg^(1/3)")
        lo, hi = self.valid_range(quantity)
        if np.any(z <= 0.0):
            raise OutOfRangeError(
                f"scaled distance Z = {float(z[z <= 0.0].ravel()[0]):.6g} m/kg^(1/3) is out of range: must be > 0"
            )
        check_fit_range(z, (lo, hi), f"{quantity} ({self.name})", "the fit's valid range", extrapolate, stacklevel=3)
        with np.errstate(over="ignore", under="ignore"):
            res = self._raw(quantity, z)
        bad = ~(np.isfinite(res) & (res > 0.0))
        if np.any(bad):  # reachable only by extrapolating far out: the fit overflows or vanishes
            zb = float(z[bad].ravel()[0])
            raise OutOfRangeError(
                f"{quantity} ({self.name}): scaled distance Z = {zb:.6g} m/kg^(1/3) is too far outside the fit's "
                f"valid range [{lo:g}, {hi:g}] m/kg^(1/3) even to extrapolate (the fit gives "
                f"{float(np.asarray(res)[bad].ravel()[0]):.3g})"
            )
        return res if np.ndim(Z) else float(res)

    # ------------------------------------------------------------- public API
    def reflected_pressure(self, Z, *, extrapolate: bool = False):
        """Peak normally reflected overpressure P_ro [Pa] at scaled distance Z [m/kg^(1/3)]."""
        return self._evaluate("reflected_pressure", Z, extrapolate)

    def incident_pressure(self, Z, *, extrapolate: bool = False):
        """Peak incident (side-on) overpressure P_so [Pa] at scaled distance Z [m/kg^(1/3)]."""
        return self._evaluate("incident_pressure", Z, extrapolate)

    def scaled_reflected_impulse(self, Z, *, extrapolate: bool = False):
        """Scaled positive-phase reflected impulse i_r / W^(1/3) [Pa*s/kg^(1/3)]."""
        return self._evaluate("scaled_reflected_impulse", Z, extrapolate)

    def scaled_incident_impulse(self, Z, *, extrapolate: bool = False):
        """Scaled positive-phase incident impulse i_s / W^(1/3) [Pa*s/kg^(1/3)]."""
        return self._evaluate("scaled_incident_impulse", Z, extrapolate)

    def scaled_arrival_time(self, Z, *, extrapolate: bool = False):
        """Scaled shock arrival time t_A / W^(1/3) [s/kg^(1/3)]."""
        return self._evaluate("scaled_arrival_time", Z, extrapolate)

    def scaled_positive_duration(self, Z, *, extrapolate: bool = False):
        """Scaled positive-phase duration t_o / W^(1/3) [s/kg^(1/3)]."""
        return self._evaluate("scaled_positive_duration", Z, extrapolate)

    def shock_front_velocity(self, Z, *, extrapolate: bool = False):
        """Shock-front velocity U [m/s] at scaled distance Z [m/kg^(1/3)]."""
        return self._evaluate("shock_front_velocity", Z, extrapolate)

    def __repr__(self) -> str:  # pragma: no cover - cosmetic
        return f"<{type(self).__name__} {self.name!r}>"
