"""Fast rocking solver (compiled Dormand-Prince 5(4) with events); results in :mod:`.results`.

The equation (paper Eq. eq:eom, see :mod:`blastscale.rocking.system`) is integrated in the
dimensionless time ``tau = p t`` with the state ``(theta, theta_dot / p)``, so that the
tolerances mean the same thing at every scale. Time ``t = 0`` is the arrival of the shock at
the loaded face; the pulse acts from there on.

Overturning criterion (rigorous for the piecewise equation):

* Rocking away from the blast (theta > 0): once theta reaches alpha with theta_dot > 0 the
  centre of mass has passed over the pivot; gravity and the (non-negative) blast pressure
  then both push the body further, so it can never come back. The *overturn time* is the
  time of that crossing.
* Rocking toward the blast (theta < 0): the pressure pushes back, so crossing -alpha counts
  only once the pulse is over (and, if the body is then already past -alpha moving back,
  only if its kinetic energy cannot lift it back over the top).
* After overturning the motion is followed until the body lies on its side
  (|theta| = pi/2), where it is then held (theta = +-pi/2, theta_dot = 0).

Impacts: at theta = 0 the angular velocity is multiplied by the restitution e and the pivot
changes (Housner 1963). When the rebound velocity falls below ``rest_velocity * p`` the body
is at rest (this ends the Zeno sequence of ever smaller impacts; the excursions cut off are
below ``rest_velocity^2 / (2 sin alpha)`` rad). A body at rest lifts off whenever the
load-to-weight ratio exceeds ``tan(alpha)`` (``P S h > m g b`` for a rectangle).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Sequence

import numpy as np

from .._threads import resolve_threads
from .._validate import BlastscaleInputError, check_finite, check_positive, check_range
from ..blast.pulses import Pulse
from ..structures.block import RectangularBlock
from .encoding import encode_pulse
from .layout import (
    PAR_SIZE,
    S_END_TAU,
    S_FIRST_IMPACT_TAU,
    S_FIRST_PEAK,
    S_MAX_ABS_THETA,
    S_N_IMPACTS,
    S_NREJECT,
    S_NSTEPS,
    S_OVERTURN_TAU,
    S_OVERTURNED,
    S_STATUS,
    S_W_AT_ALPHA,
)
from .results import RockingBatchResult, RockingResult, none_if_nan
from .system import RockingSystem, as_rocking_system

__all__ = ["RockingSolver", "DEFAULT_SOLVER", "simulate", "check_count"]


def check_count(name: str, value, lo: int) -> int:
    """``value`` as an int; raise unless it is a whole number >= ``lo``.

    Parameters
    ----------
    name : str
        Name of the quantity in the error message.
    value : int or float
        A count (an integral float such as ``3.0`` is accepted; a bool is not).
    lo : int
        Smallest valid value.

    Returns
    -------
    int

    Raises
    ------
    BlastscaleInputError
        If ``value`` is not a whole number >= ``lo``.
    """
    ok = isinstance(value, (int, np.integer)) and not isinstance(value, bool)
    if not ok and isinstance(value, (float, np.floating)) and math.isfinite(value) and float(value).is_integer():
        ok = True
    if not ok or int(value) < lo:
        raise BlastscaleInputError(f"{name} = {value!r} is out of range: must be a whole number >= {lo}")
    return int(value)


@dataclass(frozen=True)
class RockingSolver:
    """Adaptive Dormand-Prince 5(4) rocking solver with impact, peak and overturn events.

    Parameters
    ----------
    rtol, atol : float
        Relative and absolute tolerances on (theta [rad], theta_dot / p [-]) per step
        (defaults 1e-10, 1e-12). The global error over seconds of rocking with tens of
        impacts stays below ~1e-8 rad (checked against scipy's DOP853 at rtol 1e-10,
        atol 1e-12 in the tests).
    rest_velocity : float
        Rebound velocity below which the body is taken to be at rest, as a fraction of p
        [-] (default 1e-8).
    max_steps : int
        Step budget per case (default 20 million); exceeding it raises an error.
    threads : int, optional
        Threads over which a batch's cases are split (:meth:`simulate_batch`, the pulse phases of
        :mod:`.swing`), >= 1; the results are bitwise those of one thread. None: the cores this
        process may use, or its share on a local Dask worker (:mod:`blastscale._threads`).
    """

    rtol: float = 1e-10
    atol: float = 1e-12
    rest_velocity: float = 1e-8
    max_steps: int = 20_000_000
    threads: int | None = None

    def __post_init__(self):
        check_range("rtol", self.rtol, 1e-14, 1e-2)
        check_range("atol", self.atol, 1e-16, 1e-2)
        check_range("rest_velocity", self.rest_velocity, 0.0, 1e-2)
        check_count("max_steps", self.max_steps, 1)
        if self.threads is not None:
            resolve_threads(self.threads)

    # ------------------------------------------------------------------ one case
    def simulate(
        self,
        body: "RockingSystem | RectangularBlock",
        pulse: Pulse | None,
        duration: float,
        *,
        theta0: float = 0.0,
        theta_dot0: float = 0.0,
        t_eval=None,
        stop_at_overturn: bool = False,
        max_impacts: int | None = None,
        gravity: float | None = None,
        restitution: float | None = None,
    ) -> RockingResult:
        """Simulate one body under one pulse.

        Parameters
        ----------
        body : RockingSystem or RectangularBlock
            The rocking body (a block is converted with ``gravity`` [m/s^2] and ``restitution``).
        pulse : Pulse or None
            Pressure pulse on the loaded face from the shock arrival (t = 0); None: no load.
        duration : float
            Simulated time [s], > 0.
        theta0, theta_dot0 : float
            Initial angle [rad] (|theta0| < pi/2) and angular velocity [rad/s].
        t_eval : array_like, optional
            Increasing times in [0, duration] [s] at which to sample the solution.
        stop_at_overturn : bool
            Stop at the tipping point instead of following the fall.
        max_impacts : int, optional
            Stop after this many impacts.

        Returns
        -------
        RockingResult
        """
        system = as_rocking_system(body, gravity, restitution)
        dur = float(check_positive("duration", duration, "s"))
        th0 = float(
            check_range("initial angle theta0", theta0, -math.pi / 2, math.pi / 2, "rad", lo_open=True, hi_open=True)
        )
        om0 = float(check_finite("initial angular velocity", theta_dot0, "rad/s"))
        p = system.frequency_parameter
        tev = self._check_t_eval(t_eval, dur)
        kind, par, tt, tf, dw = (
            (0, np.zeros(PAR_SIZE), np.zeros(0), np.zeros(0), 0.0)
            if pulse is None
            else encode_pulse(pulse, system, th0)
        )
        settings = self._kernel_settings(max_impacts, stop_at_overturn, True)
        e = system.coefficient_of_restitution
        from .kernel import solve_case  # noqa: PLC0415 -- start-up: numba loads on the first solve, not with `import blastscale.cli`

        summ, the, we, hist, imp, pk = solve_case(
            system.alpha,
            e,
            th0,
            om0 / p + dw,
            dur * p,
            kind,
            par,
            tt,
            tf,
            (tev if tev is not None else np.zeros(0)) * p,
            *settings,
        )
        self._check_status(summ[S_STATUS])
        return RockingResult(
            t=hist[:, 0] / p,
            theta=hist[:, 1].copy(),
            theta_dot=hist[:, 2] * p,
            impact_times=imp[:, 0] / p,
            impact_velocity_before=imp[:, 1] * p,
            impact_velocity_after=imp[:, 2] * p,
            peak_times=pk[:, 0] / p,
            peak_angles=pk[:, 1].copy(),
            collapsed=bool(summ[S_OVERTURNED]),
            collapse_time=none_if_nan(summ[S_OVERTURN_TAU] / p),
            first_impact_time=none_if_nan(summ[S_FIRST_IMPACT_TAU] / p),
            max_rotation=float(summ[S_MAX_ABS_THETA]),
            end_time=float(summ[S_END_TAU] / p),
            n_steps=int(summ[S_NSTEPS]),
            n_rejected=int(summ[S_NREJECT]),
            restitution=e,
            angular_velocity_at_tipping=none_if_nan(summ[S_W_AT_ALPHA] * p),
            t_eval=tev,
            theta_eval=None if tev is None else the,
            theta_dot_eval=None if tev is None else we * p,
            system=system,
        )

    # --------------------------------------------------------------- many cases
    def simulate_batch(
        self,
        bodies: "RockingSystem | RectangularBlock | Sequence",
        pulses: "Pulse | None | Sequence",
        duration: float,
        t_eval,
        *,
        theta0=0.0,
        theta_dot0=0.0,
        stop_at_overturn: bool = False,
        max_impacts: int | None = None,
        gravity: float | None = None,
    ) -> RockingBatchResult:
        """Simulate n cases in one compiled call, sampled at the same times.

        ``bodies`` and ``pulses`` are single objects or sequences of length n (a single one is
        broadcast); ``theta0`` / ``theta_dot0`` scalars or arrays of length n [rad], [rad/s];
        ``t_eval`` (m,) increasing times in [0, duration] [s]; ``duration`` [s] > 0;
        ``max_impacts`` / ``stop_at_overturn`` / ``gravity`` [m/s^2] as in :meth:`simulate`
        (each body keeps its own restitution). Wrong lengths raise a
        :class:`~blastscale._validate.BlastscaleInputError` naming them.

        Returns
        -------
        RockingBatchResult
            ``theta`` [rad] and ``theta_dot`` [rad/s] shaped (n, m) at ``t`` [s]; outcome,
            overturn and first-impact times [s], peak angles [rad], counts, shaped (n,).
        """
        dur = float(check_positive("duration", duration, "s"))
        tev = self._check_t_eval(t_eval, dur)
        if tev is None:
            raise BlastscaleInputError("t_eval is required for a batch (the common sampling times)")
        blist = list(bodies) if isinstance(bodies, (list, tuple)) else [bodies]
        plist = list(pulses) if isinstance(pulses, (list, tuple)) else [pulses]
        th0 = np.atleast_1d(
            check_range("initial angle theta0", theta0, -math.pi / 2, math.pi / 2, "rad", lo_open=True, hi_open=True)
        )
        om0 = np.atleast_1d(check_finite("initial angular velocity", theta_dot0, "rad/s"))
        if th0.ndim != 1 or om0.ndim != 1:
            raise BlastscaleInputError(
                f"theta0 and theta_dot0 must be scalars or 1-D arrays, got shapes {th0.shape} and {om0.shape}"
            )
        lens = {len(blist), len(plist), th0.size, om0.size} - {1}
        if len(lens) > 1:
            raise BlastscaleInputError(
                f"batch lengths disagree: bodies {len(blist)}, pulses {len(plist)}, "
                f"theta0 {th0.size}, theta_dot0 {om0.size} (each must be n or 1)"
            )
        n = lens.pop() if lens else 1
        # each body given converted (and checked) once, before a single one is broadcast to the n runs
        consts = [_body_constants(as_rocking_system(b, gravity)) for b in blist]
        consts = consts * n if len(consts) == 1 else consts
        blist = blist * n if len(blist) == 1 else blist
        plist = plist * n if len(plist) == 1 else plist
        th0 = np.broadcast_to(th0, (n,)).astype(float)
        om0 = np.broadcast_to(om0, (n,)).astype(float)
        alpha = np.empty(n)
        e = np.empty(n)
        pvec = np.empty(n)
        w0 = np.empty(n)
        kinds = np.empty(n, dtype=np.int64)
        par = np.zeros((n, PAR_SIZE))
        tabs_t, tabs_f = [], []
        off = np.zeros(n + 1, dtype=np.int64)
        for i, ((sysi, pvec[i], alpha[i], e[i]), pul) in enumerate(zip(consts, plist)):
            if pul is None:
                k, pr, tt, tf, dw = 0, np.zeros(PAR_SIZE), np.zeros(0), np.zeros(0), 0.0
            else:
                k, pr, tt, tf, dw = encode_pulse(pul, sysi, th0[i])
            kinds[i] = k
            par[i] = pr
            tabs_t.append(tt)
            tabs_f.append(tf)
            off[i + 1] = off[i] + tt.size
            w0[i] = om0[i] / pvec[i] + dw
        tab_t = np.concatenate(tabs_t) if off[-1] else np.zeros(0)
        tab_f = np.concatenate(tabs_f) if off[-1] else np.zeros(0)
        settings = self._kernel_settings(max_impacts, stop_at_overturn, False)
        from ._batch import solve_batch  # noqa: PLC0415 -- start-up: numba loads on the first solve, not with `import blastscale.cli`

        summ, th, w = solve_batch(
            alpha,
            e,
            th0,
            w0,
            dur * pvec,
            kinds,
            par,
            tab_t,
            tab_f,
            off,
            np.ascontiguousarray(tev[None, :] * pvec[:, None]),
            *settings,
            threads=self.threads,
        )
        bad = summ[:, S_STATUS] != 0
        if np.any(bad):
            self._check_status(summ[np.argmax(bad), S_STATUS], int(np.argmax(bad)))
        return RockingBatchResult(
            t=tev,
            theta=th,
            theta_dot=w * pvec[:, None],
            collapsed=summ[:, S_OVERTURNED].astype(bool),
            collapse_time=summ[:, S_OVERTURN_TAU] / pvec,
            first_impact_time=summ[:, S_FIRST_IMPACT_TAU] / pvec,
            max_rotation=summ[:, S_MAX_ABS_THETA].copy(),
            first_peak_angle=summ[:, S_FIRST_PEAK].copy(),
            angular_velocity_at_tipping=summ[:, S_W_AT_ALPHA] * pvec,
            n_impacts=summ[:, S_N_IMPACTS].astype(np.int64),
            n_steps=summ[:, S_NSTEPS].astype(np.int64),
            end_time=summ[:, S_END_TAU] / pvec,
        )

    # ------------------------------------------------------------------ helpers
    def _kernel_settings(self, max_impacts, stop_at_overturn, record: bool) -> tuple:
        """The trailing arguments of the compiled kernel (:func:`.kernel.solve_case`,
        :func:`._batch.solve_batch`): ``(rtol, atol, rest_velocity, max_impacts (-1: never),
        stop_at_overturn, max_steps, record)`` as plain Python numbers.

        ``record`` is passed from Python (a plain bool): a literal inside the kernel would compile a
        second specialisation of ``solve_case`` (~3 s). ``max_impacts`` None or a count >= 0.
        """
        mi = -1 if max_impacts is None else check_count("max_impacts", max_impacts, 0)
        return (
            float(self.rtol),
            float(self.atol),
            float(self.rest_velocity),
            mi,
            bool(stop_at_overturn),
            int(self.max_steps),
            bool(record),
        )

    @staticmethod
    def _check_t_eval(t_eval, duration: float):
        if t_eval is None:
            return None
        t = check_finite("t_eval", t_eval, "s")
        if t.ndim != 1:
            raise BlastscaleInputError(f"t_eval must be 1-D, got shape {t.shape}")
        if t.size and (t[0] < 0.0 or t[-1] > duration * (1 + 1e-12)):
            raise BlastscaleInputError(
                f"t_eval spans [{t[0]:.6g}, {t[-1]:.6g}] s: out of range, valid range is [0, {duration:.6g}] s"
            )
        if np.any(np.diff(t) < 0.0):
            raise BlastscaleInputError("t_eval must be non-decreasing")
        return np.ascontiguousarray(t)

    def _check_status(self, status: float, case: int | None = None) -> None:
        where = "" if case is None else f" (case {case})"
        if status == 1:
            raise BlastscaleInputError(
                f"rocking solver step budget max_steps = {self.max_steps} exhausted{where}: "
                "shorten the duration or raise max_steps"
            )
        if status == 2:
            raise BlastscaleInputError(f"rocking solver step size underflow{where}: the tolerances cannot be met")


#: Solver with the default tolerances (rtol 1e-10, atol 1e-12).
DEFAULT_SOLVER = RockingSolver()


def simulate(body, pulse, duration, **kwargs) -> RockingResult:
    """Shortcut for ``RockingSolver().simulate(body, pulse, duration, **kwargs)``."""
    return DEFAULT_SOLVER.simulate(body, pulse, duration, **kwargs)


def _body_constants(system) -> tuple:
    """(system, frequency parameter p [1/s], alpha [rad], coefficient of restitution [-]) of a rocking system."""
    return system, system.frequency_parameter, system.alpha, system.coefficient_of_restitution
