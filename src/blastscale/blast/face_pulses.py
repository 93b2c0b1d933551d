"""Positive-phase pulses of many faces at once, each at its own arrival time since detonation.

:class:`FacePulses` holds, on arrays of shape (nface,), the pulses that
:meth:`~blastscale.blast.faces.FaceLoads.pulses` builds from the faces' blast parameters, and
evaluates them in one vectorised call per time:

* modified Friedlander pulse (paper Eq. 1, Friedlander 1946), with :math:`x = (t - t_A)/t_o`,

  .. math:: p(t) = P\\,(1 - x)\\,e^{-d x}, \\qquad
            I(t) = P\\,t_o\\,J(x, d) \\quad (0 \\le x \\le 1),

  the running impulse J of :func:`~blastscale.blast.friedlander.friedlander_cumulative`;
* triangle of equal peak and impulse (paper Eq. 3), duration :math:`t_o = 2 i / P`,
  :math:`p = P (1 - x)`, :math:`I = P t_o (x - x^2/2)`;
* impulsive limit: a Dirac of area i at the arrival (p = 0, I = i after :math:`t_A`).

The impulse over a step [t0, t1] is the **exact** difference of the running impulses, whatever
the step.

Optional effects (:mod:`.face_effects`, each a closed form too): a cleared face (UFC 3-340-02
Sec. 2-15.3.2, :mod:`.clearing`) follows ``(0, P) -> (t1, P1) -> (t2, 0)`` instead of its pulse;
a negative phase (Granström's cubic, :mod:`.negative_phase`) of peak suction ``neg_peak`` and
duration ``neg_duration`` starts ``neg_start`` after the arrival.

References
----------
.. [1] Friedlander, F. G. (1946). The diffraction of sound pulses I. Proc. R. Soc. A 186.
.. [2] Masi, Stefanou & Maffi-Berthier, *Scaling laws ...*, Eqs. (1)-(3).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .clearing import bilinear_cumulative, bilinear_pressure
from .friedlander import friedlander_cumulative
from .negative_phase import cubic_cumulative, cubic_pressure

__all__ = ["FacePulses"]


@dataclass(frozen=True)
class FacePulses:
    """Positive-phase pulses of many faces, all arrays of shape (nface,), times since detonation.

    Attributes
    ----------
    kind : str
        ``"friedlander"`` (paper Eq. 1, decay fitted to the impulse, Eq. 2), ``"triangular"``
        (equal peak and impulse, duration 2 i / P, Eq. 3) or ``"impulsive"`` (a Dirac of area i at
        the arrival).
    arrival_time : ndarray
        Shock arrival at each face [s] since detonation.
    peak : ndarray
        Peak overpressure [Pa] (inf for impulsive).
    duration : ndarray
        Time from arrival to the end of the pulse [s] (0 for impulsive).
    decay : ndarray
        Friedlander decay coefficient d [-] (0 for the other shapes).
    impulse : ndarray
        Total impulse [Pa*s] (of the positive phase; for a cleared face the cleared one).
    cleared : ndarray of bool, optional
        Faces whose cleared pulse ``(0, peak) -> (clear_t1, clear_p1) -> (clear_t2, 0)`` [s after
        arrival, Pa] replaces their pulse (None: none).
    neg_peak, neg_start, neg_duration : ndarray, optional
        Negative phase of each face: peak suction [Pa] (> 0), start after the arrival [s] and
        duration [s] (None: none).
    """

    kind: str
    arrival_time: np.ndarray
    peak: np.ndarray
    duration: np.ndarray
    decay: np.ndarray
    impulse: np.ndarray
    cleared: np.ndarray | None = None
    clear_t1: np.ndarray | None = None
    clear_p1: np.ndarray | None = None
    clear_t2: np.ndarray | None = None
    neg_peak: np.ndarray | None = None
    neg_start: np.ndarray | None = None
    neg_duration: np.ndarray | None = None

    @property
    def end_time(self) -> float:
        """Latest end of any pulse [s] since detonation (cleared pulses and negative phases included)."""
        end = self.duration
        if self.cleared is not None:
            end = np.where(self.cleared, self.clear_t2, end)
        if self.neg_peak is not None:
            end = np.maximum(end, self.neg_start + self.neg_duration)
        return float(np.max(self.arrival_time + end))

    def pressure(self, t: float) -> np.ndarray:
        """Overpressure on every face at time t [s] since detonation, shape (nface,) [Pa]."""
        if self.kind == "impulsive":
            p = np.zeros_like(self.arrival_time)
        else:
            x = (t - self.arrival_time) / self.duration
            inside = (x >= 0.0) & (x <= 1.0)
            xc = np.clip(x, 0.0, 1.0)  # no overflow of exp(-d x) far before an arrival
            shape = (1.0 - xc) * (np.exp(-self.decay * xc) if self.kind == "friedlander" else 1.0)
            p = np.where(inside, self.peak * shape, 0.0)
            if self.cleared is not None:
                p = np.where(
                    self.cleared,
                    bilinear_pressure(t - self.arrival_time, self.peak, self.clear_t1, self.clear_p1, self.clear_t2),
                    p,
                )
        if self.neg_peak is not None:
            p = p + cubic_pressure((t - self.arrival_time - self.neg_start) / self.neg_duration, self.neg_peak)
        return p

    def cumulative_impulse(self, t: float) -> np.ndarray:
        """Impulse delivered to every face from detonation to t [s], shape (nface,) [Pa*s] (exact)."""
        s = t - self.arrival_time
        if self.kind == "impulsive":
            out = np.where(s >= 0.0, self.impulse, 0.0)
        else:
            x = np.clip(s / self.duration, 0.0, 1.0)
            if self.kind == "friedlander":
                out = self.peak * self.duration * friedlander_cumulative(x, self.decay)
            else:
                out = self.peak * self.duration * (x - 0.5 * x**2)
            if self.cleared is not None:
                out = np.where(
                    self.cleared, bilinear_cumulative(s, self.peak, self.clear_t1, self.clear_p1, self.clear_t2), out
                )
        if self.neg_peak is not None:
            out = out + cubic_cumulative((s - self.neg_start) / self.neg_duration, self.neg_peak, self.neg_duration)
        return out

    def impulse_between(self, t0: float, t1: float) -> np.ndarray:
        """Exact impulse of every face over [t0, t1] [s since detonation], shape (nface,) [Pa*s]."""
        return self.cumulative_impulse(t1) - self.cumulative_impulse(t0)
