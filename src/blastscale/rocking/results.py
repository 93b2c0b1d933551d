"""Result types of the rocking solver (SI; times from the shock arrival).

:class:`RockingResult` holds one simulated history (paper Eq. eq:eom with Housner's impacts,
see :mod:`blastscale.rocking.solver`): the solver's steps and events, the impacts, the peaks
and the outcome; :class:`RockingBatchResult` n cases sampled at common times. Angles in
[rad], angular velocities in [rad/s], times in [s].
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .system import RockingSystem

__all__ = ["RockingResult", "RockingBatchResult"]


@dataclass(frozen=True)
class RockingResult:
    """Response of one rocking body (SI; times from the shock arrival).

    Attributes
    ----------
    t, theta, theta_dot : ndarray
        History at every accepted solver step and event [s], [rad], [rad/s]; an impact
        appears twice at the same time (velocity before, then after).
    t_eval, theta_eval, theta_dot_eval : ndarray or None
        The history sampled at the requested times (dense output, 4th order), when asked.
    impact_times, impact_velocity_before, impact_velocity_after : ndarray
        Every impact [s], [rad/s], [rad/s].
    peak_times, peak_angles : ndarray
        Every local extremum of |theta| [s], [rad] (signed angle).
    collapsed : bool
        Whether the body overturned (the outcome word of every engine: collapsed) (criterion: :mod:`blastscale.rocking.solver`).
    collapse_time : float or None
        Time it passed its tipping point [s].
    first_impact_time : float or None
        Time of the first impact [s].
    max_rotation : float
        Largest |theta| over the run [rad] (pi/2 once it lies on its side).
    end_time : float
        Time the simulated motion ends [s] (the requested duration, or when it lay down or
        the requested early stop happened).
    n_steps, n_rejected : int
        Solver steps (accepted + rejected) and rejected steps.
    restitution : float
        Restitution used [-].
    angular_velocity_at_tipping : float or None
        |theta_dot| when it passed its tipping point [rad/s].
    system : RockingSystem or None
        The body simulated.
    """

    t: np.ndarray
    theta: np.ndarray
    theta_dot: np.ndarray
    impact_times: np.ndarray
    impact_velocity_before: np.ndarray
    impact_velocity_after: np.ndarray
    peak_times: np.ndarray
    peak_angles: np.ndarray
    collapsed: bool
    collapse_time: float | None
    first_impact_time: float | None
    max_rotation: float
    end_time: float
    n_steps: int
    n_rejected: int
    restitution: float
    angular_velocity_at_tipping: float | None = None
    t_eval: np.ndarray | None = None
    theta_eval: np.ndarray | None = None
    theta_dot_eval: np.ndarray | None = None
    system: RockingSystem | None = field(default=None, repr=False)

    @property
    def n_impacts(self) -> int:
        """Number of impacts [-]."""
        return int(self.impact_times.size)

    def to_dataset(self):
        """The history as an ``xarray.Dataset`` (dimension ``time`` [s]; ``theta`` [rad],
        ``theta_dot`` [rad/s]; units and the scalar results in the attributes). Needs the
        ``io`` extra (xarray); imported only here."""
        import xarray as xr

        ds = xr.Dataset(
            {
                "theta": ("time", self.theta, {"units": "rad", "long_name": "rocking angle"}),
                "theta_dot": ("time", self.theta_dot, {"units": "rad/s", "long_name": "angular velocity"}),
            },
            coords={"time": ("time", self.t, {"units": "s", "long_name": "time after shock arrival"})},
        )
        for k, v in self.summary().items():
            ds.attrs[k] = "none" if v is None else (int(v) if isinstance(v, bool) else v)
        ds.attrs["restitution"] = self.restitution
        ds.attrs["equation"] = "Masi, Stefanou & Maffi-Berthier, Eq. (eom); Housner (1963) impacts"
        return ds

    def summary(self) -> dict:
        """Plain dict of the scalar results (unit-suffixed keys, None where absent)."""
        return {
            "collapsed": bool(self.collapsed),
            "max_rotation_rad": float(self.max_rotation),
            "collapse_time_s": self.collapse_time,
            "first_impact_time_s": self.first_impact_time,
            "n_impacts": self.n_impacts,
            "end_time_s": float(self.end_time),
        }


@dataclass(frozen=True)
class RockingBatchResult:
    """Responses of n cases sampled at m common times (arrays shaped ``(n,)`` / ``(n, m)``).

    ``theta``/``theta_dot`` are NaN only after an early stop the caller asked for
    (``stop_at_overturn``/``max_impacts``); elsewhere every sample is simulated.
    """

    t: np.ndarray
    theta: np.ndarray
    theta_dot: np.ndarray
    collapsed: np.ndarray
    collapse_time: np.ndarray  # NaN where none [s]
    first_impact_time: np.ndarray  # NaN where none [s]
    max_rotation: np.ndarray
    first_peak_angle: np.ndarray  # NaN where none [rad]
    angular_velocity_at_tipping: np.ndarray  # NaN where none [rad/s]
    n_impacts: np.ndarray
    n_steps: np.ndarray
    end_time: np.ndarray

    def __len__(self) -> int:
        return int(self.collapsed.size)


def none_if_nan(x: float) -> float | None:
    """``float(x)``, or None where x is NaN or infinite (an absent event time)."""
    return None if not math.isfinite(x) else float(x)
