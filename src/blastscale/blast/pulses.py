"""Pressure-time pulses of the positive phase of a blast wave, with t = 0 at shock arrival.

All pulses are small immutable objects with SI attributes and vectorised methods:

* ``pressure(t)`` [Pa] for t [s] (zero before 0 and after the pulse ends),
* ``cumulative_impulse(t)`` [Pa*s], the exact running integral of the pressure,
* ``peak`` [Pa], ``duration`` [s] (time at which the pressure returns to zero),
  ``impulse`` [Pa*s] (total area), and ``kind`` (a short string).

:data:`PULSE_SHAPES` names the shapes built from blast parameters (peak, duration, impulse) all
over the package, and :func:`check_pulse_shape` checks a name against it. The Friedlander decay
coefficient itself (paper Eq. 2 and its inverse) is in :mod:`.friedlander`.

References
----------
.. [1] Friedlander, F. G. (1946). The diffraction of sound pulses I. Proc. R. Soc. A 186.
.. [2] Masi, Stefanou & Maffi-Berthier, *Scaling laws ...*, Eqs. (1)-(3) (modified Friedlander,
       its impulse, and the first-order triangular approximation).
.. [3] UFC 3-340-02 (2008), Structures to resist the effects of accidental explosions, Sec. 2-15
       (equivalent triangular pulse of equal impulse).
"""

from __future__ import annotations

import abc
import math
from dataclasses import dataclass

import numpy as np

from .._validate import BlastscaleInputError, check_choice, check_finite, check_positive
from .friedlander import friedlander_cumulative, friedlander_decay, friedlander_impulse_ratio

__all__ = [
    "Pulse",
    "Friedlander",
    "Triangular",
    "Impulsive",
    "Tabulated",
    "PULSE_SHAPES",
    "check_pulse_shape",
]

#: Pulse shapes built from blast parameters (peak, duration, impulse): the modified Friedlander
#: pulse (paper Eq. 1, decay fitted to the impulse, Eq. 2), the triangle of equal peak and
#: impulse (Eq. 3) and the impulsive limit (a Dirac of the same impulse). The one vocabulary of
#: ``pulse_shape=`` arguments across the package (``tabulated`` pulses are built from a table instead).
PULSE_SHAPES = ("friedlander", "triangular", "impulsive")


def check_pulse_shape(name: str) -> str:
    """Check a pulse-shape name against :data:`PULSE_SHAPES`.

    Parameters
    ----------
    name : str
        ``"friedlander"``, ``"triangular"`` or ``"impulsive"``.

    Returns
    -------
    str
        ``name`` itself.

    Raises
    ------
    BlastscaleInputError
        If ``name`` is not one of :data:`PULSE_SHAPES`.
    """
    return check_choice("pulse", name, PULSE_SHAPES)


class Pulse(abc.ABC):
    """A positive-phase pressure pulse starting at t = 0 (shock arrival)."""

    kind: str = "pulse"

    @property
    @abc.abstractmethod
    def peak(self) -> float:
        """Peak overpressure [Pa]."""

    @property
    @abc.abstractmethod
    def duration(self) -> float:
        """Time [s] after arrival at which the pressure is back to zero."""

    @property
    @abc.abstractmethod
    def impulse(self) -> float:
        """Total impulse of the pulse [Pa*s]."""

    @abc.abstractmethod
    def pressure(self, t):
        """Overpressure [Pa] at times t [s] after arrival (0 outside the pulse)."""

    @abc.abstractmethod
    def cumulative_impulse(self, t):
        """Running impulse [Pa*s] from arrival to t [s] (equals ``impulse`` after the pulse)."""

    def scaled(self, factors) -> "Pulse":
        """The exactly similar pulse of a specimen: pressure x ``factors.pressure`` and time x
        ``factors.time`` (``factors``: a :class:`~blastscale.similitude.ScalingFactors`), the pulse
        the rigid-body response requires (a real blast delivers its own ratios: paper Eq. 8 matches
        the impulse only)."""
        return self._rescaled(float(factors.pressure), float(factors.time))

    def _rescaled(self, pressure_factor: float, time_factor: float) -> "Pulse":
        """The same pulse shape with pressure x ``pressure_factor`` and time x ``time_factor``."""
        raise NotImplementedError  # overridden by every concrete pulse


def _ret(x, t):
    return x if np.ndim(t) else float(x)


@dataclass(frozen=True)
class _PeakPulse(Pulse):
    """A pulse that jumps to its peak overpressure ``peak_pressure`` [Pa] (> 0) at arrival and
    decays from there (:class:`Friedlander`, :class:`Triangular`)."""

    peak_pressure: float

    def __post_init__(self):
        check_positive("peak pressure", self.peak_pressure, "Pa")

    @property
    def peak(self) -> float:
        return float(self.peak_pressure)


@dataclass(frozen=True)
class Friedlander(_PeakPulse):
    """Modified Friedlander pulse, paper Eq. (1):

    .. math:: P(t) = P_{ro}\\,(1 - t/t_o)\\,e^{-d\\,t/t_o}, \\quad 0 \\le t \\le t_o,

    with impulse :math:`i = P_{ro} t_o (e^{-d} + d - 1)/d^2` (Eq. 2).

    Attributes: ``peak_pressure`` P_ro [Pa], ``positive_duration`` t_o [s], ``decay`` d [-].
    Use :meth:`from_impulse` to fit d to a known impulse.
    """

    positive_duration: float
    decay: float
    kind = "friedlander"

    def __post_init__(self):
        super().__post_init__()
        check_positive("positive duration", self.positive_duration, "s")
        d = float(check_finite("Friedlander decay", self.decay))
        if d <= -1.0:
            raise BlastscaleInputError(
                f"Friedlander decay = {d:.6g} is out of range: valid range is (-1, inf) (monotone pulse)"
            )

    @classmethod
    def from_impulse(cls, peak, duration, impulse, *, allow_negative: bool = True) -> "Friedlander":
        """Friedlander pulse of peak [Pa] and duration [s] whose area equals ``impulse`` [Pa*s]."""
        d = friedlander_decay(peak, duration, impulse, allow_negative=allow_negative)
        return cls(float(peak), float(duration), float(d))

    @property
    def duration(self) -> float:
        return float(self.positive_duration)

    @property
    def impulse(self) -> float:
        return float(self.peak_pressure * self.positive_duration * friedlander_impulse_ratio(self.decay))

    def pressure(self, t):
        x = np.asarray(t, dtype=float) / self.positive_duration
        inside = (x >= 0.0) & (x <= 1.0)
        p = np.where(inside, self.peak_pressure * (1.0 - x) * np.exp(-self.decay * x), 0.0)
        return _ret(p, t)

    def cumulative_impulse(self, t):
        x = np.clip(np.asarray(t, dtype=float) / self.positive_duration, 0.0, 1.0)
        return _ret(self.peak_pressure * self.positive_duration * friedlander_cumulative(x, self.decay), t)

    def _rescaled(self, pressure_factor: float, time_factor: float) -> "Friedlander":
        return Friedlander(self.peak_pressure * pressure_factor, self.positive_duration * time_factor, self.decay)


@dataclass(frozen=True)
class Triangular(_PeakPulse):
    """First-order (triangular) pulse of equal peak and impulse, paper Eq. (3):

    .. math:: P(t) = P_{ro}\\,(1 - t/\\bar t_o), \\quad 0 \\le t \\le \\bar t_o = 2\\,i_{ro}/P_{ro}.

    The paper prints the cut-off at t_o; the pulse must be cut at t_bar_o so that its area is
    i_ro (with the printed cut, the area would be wrong whenever t_bar_o != t_o).
    Attributes: ``peak_pressure`` [Pa], ``total_impulse`` [Pa*s].
    """

    total_impulse: float
    kind = "triangular"

    def __post_init__(self):
        super().__post_init__()
        check_positive("impulse", self.total_impulse, "Pa*s")

    @property
    def duration(self) -> float:
        return float(2.0 * self.total_impulse / self.peak_pressure)

    @property
    def impulse(self) -> float:
        return float(self.total_impulse)

    def pressure(self, t):
        x = np.asarray(t, dtype=float) / self.duration
        return _ret(np.where((x >= 0.0) & (x <= 1.0), self.peak_pressure * (1.0 - x), 0.0), t)

    def cumulative_impulse(self, t):
        x = np.clip(np.asarray(t, dtype=float) / self.duration, 0.0, 1.0)
        return _ret(self.peak_pressure * self.duration * (x - 0.5 * x**2), t)

    def _rescaled(self, pressure_factor: float, time_factor: float) -> "Triangular":
        return Triangular(self.peak_pressure * pressure_factor, self.total_impulse * pressure_factor * time_factor)


@dataclass(frozen=True)
class Impulsive(Pulse):
    """Impulsive limit: a Dirac pulse of area ``total_impulse`` [Pa*s] at t = 0.

    ``pressure`` is zero everywhere (the load acts as an initial velocity); ``peak`` is inf.
    """

    total_impulse: float
    kind = "impulsive"

    def __post_init__(self):
        check_positive("impulse", self.total_impulse, "Pa*s")

    @property
    def peak(self) -> float:
        return math.inf

    @property
    def duration(self) -> float:
        return 0.0

    @property
    def impulse(self) -> float:
        return float(self.total_impulse)

    def pressure(self, t):
        return _ret(np.zeros_like(np.asarray(t, dtype=float)), t)

    def cumulative_impulse(self, t):
        return _ret(np.where(np.asarray(t, dtype=float) >= 0.0, self.total_impulse, 0.0), t)

    def _rescaled(self, pressure_factor: float, time_factor: float) -> "Impulsive":
        return Impulsive(self.total_impulse * pressure_factor * time_factor)


class Tabulated(Pulse):
    """Arbitrary pulse from a table of (time [s], overpressure [Pa]), linear in between.

    Times must start at 0 and increase strictly; pressures must be finite and >= 0, and the
    last one 0 (the pulse ends). The impulse is the exact (trapezoidal) area of the
    piecewise-linear curve.
    """

    kind = "tabulated"

    def __init__(self, times, pressures):
        t = check_finite("pulse times", times, "s")
        p = check_finite("pulse pressures", pressures, "Pa")
        if t.ndim != 1 or p.shape != t.shape or t.size < 2:
            raise BlastscaleInputError(
                f"tabulated pulse needs 1-D times and pressures of equal length >= 2, got shapes {t.shape} and {p.shape}"
            )
        if t[0] != 0.0:
            raise BlastscaleInputError(f"pulse times[0] = {t[0]:.6g} s is out of range: the table must start at 0 s")
        dt = np.diff(t)
        if np.any(dt <= 0.0):
            raise BlastscaleInputError("pulse times must increase strictly (a pulse with negative duration)")
        if np.any(p < 0.0):
            raise BlastscaleInputError(
                f"pulse pressure = {float(p[p < 0][0]):.6g} Pa is out of range: must be >= 0 (positive phase only)"
            )
        if p[-1] != 0.0:
            p = np.append(p, 0.0)
            t = np.append(t, t[-1] + 1e-12 * max(t[-1], 1.0))
        self.times = t
        self.pressures = p
        self._cum = np.concatenate([[0.0], np.cumsum(0.5 * (p[1:] + p[:-1]) * np.diff(t))])

    @property
    def peak(self) -> float:
        return float(self.pressures.max())

    @property
    def duration(self) -> float:
        return float(self.times[-1])

    @property
    def impulse(self) -> float:
        return float(self._cum[-1])

    def pressure(self, t):
        tt = np.asarray(t, dtype=float)
        return _ret(np.interp(tt, self.times, self.pressures, left=0.0, right=0.0), t)

    def cumulative_impulse(self, t):
        tt = np.clip(np.asarray(t, dtype=float), 0.0, self.times[-1])
        j = np.clip(np.searchsorted(self.times, tt, side="right") - 1, 0, self.times.size - 2)
        t0 = self.times[j]
        p0 = self.pressures[j]
        slope = (self.pressures[j + 1] - p0) / (self.times[j + 1] - t0)
        dt = tt - t0
        return _ret(self._cum[j] + p0 * dt + 0.5 * slope * dt**2, t)

    def _rescaled(self, pressure_factor: float, time_factor: float) -> "Tabulated":
        return Tabulated(self.times * time_factor, self.pressures * pressure_factor)

    def __repr__(self) -> str:
        return f"Tabulated(n={self.times.size}, peak={self.peak:.6g} Pa, duration={self.duration:.6g} s)"
