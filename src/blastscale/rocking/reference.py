"""Slow reference path: the rocking equation in physical time with scipy's ``solve_ivp``.

An independent implementation of paper Eq. (eq:eom) (dimensional, Python right-hand side,
scipy's DOP853 and its event location), used to check the compiled solver in the tests
and in ``benchmarks/bench_rocking.py``. It follows the same conventions (see
:mod:`blastscale.rocking.solver`): impacts with restitution, rest below
``rest_velocity * p``, lift-off when the load exceeds the uplift pressure, tipping at
|theta| = alpha (toward the blast only after the pulse), lying down at |theta| = pi/2.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.integrate import solve_ivp

from .._validate import check_positive
from ..blast.pulses import Impulsive, Pulse, Tabulated
from ..roots import scalar_root
from .results import RockingResult, none_if_nan
from .system import RockingSystem, as_rocking_system

__all__ = ["simulate_reference"]


def _event(fun, direction: float, terminal: bool):
    fun.direction = direction
    fun.terminal = terminal
    return fun


def _lift_time(pulse: Pulse | None, t: float, p_lift: float) -> float:
    """First time >= t at which the pressure exceeds p_lift (inf if never)."""
    if pulse is None or isinstance(pulse, Impulsive) or t > pulse.duration:
        return math.inf
    if pulse.pressure(t) > p_lift:
        return t
    if isinstance(pulse, Tabulated):
        knots = pulse.times[pulse.times > t]
        a = t
        for b in knots:
            if pulse.pressure(b) > p_lift:
                r = scalar_root(lambda x: pulse.pressure(x) - p_lift, a, b)
                return min(np.nextafter(r, math.inf), b)
            a = b
    return math.inf  # analytical pulses decrease monotonically


def simulate_reference(
    body,
    pulse: Pulse | None,
    duration: float,
    *,
    theta0: float = 0.0,
    theta_dot0: float = 0.0,
    t_eval=None,
    rtol: float = 1e-10,
    atol: float = 1e-12,
    method: str = "DOP853",
    rest_velocity: float = 1e-8,
    stop_at_overturn: bool = False,
    max_impacts: int | None = None,
    gravity: float | None = None,
    restitution: float | None = None,
) -> RockingResult:
    """Reference solution with ``scipy.integrate.solve_ivp`` (default DOP853, rtol 1e-10,
    atol 1e-12 on theta [rad] and theta_dot [rad/s]); same arguments and result as
    :meth:`blastscale.rocking.RockingSolver.simulate`. Slow (Python right-hand side)."""
    sysm: RockingSystem = as_rocking_system(body, gravity, restitution)
    dur = float(check_positive("duration", duration, "s"))
    m, g, r, J, al = sysm.mass, sysm.gravity, sysm.radius, sysm.inertia_pivot, sysm.alpha
    Sl = sysm.loaded_area * sysm.lever_arm / math.cos(al)
    e = sysm.coefficient_of_restitution
    p = sysm.frequency_parameter
    t_pend = 0.0 if pulse is None or isinstance(pulse, Impulsive) else pulse.duration
    bps = [t_pend] if t_pend > 0 else []
    if isinstance(pulse, Tabulated):
        bps = list(pulse.times[1:])
    tev = None if t_eval is None else np.asarray(t_eval, dtype=float)
    th_ev = None if tev is None else np.full(tev.size, np.nan)
    om_ev = None if tev is None else np.full(tev.size, np.nan)
    press = (lambda t: 0.0) if (pulse is None or isinstance(pulse, Impulsive)) else pulse.pressure

    th, om = float(theta0), float(theta_dot0)
    if isinstance(pulse, Impulsive):
        s0 = -1.0 if th < 0 else 1.0
        om += pulse.impulse * Sl * math.cos(al * s0 - th) / J
    s = 1.0 if (th > 0 or (th == 0 and om > 0)) else (-1.0 if (th < 0 or om < 0) else 0.0)
    t = 0.0
    hist = [(t, th, om)]
    impacts, peaks = [], []
    overturned, t_over, om_over, lying, max_abs = False, math.nan, math.nan, False, abs(th)
    nsteps = 0
    p_lift = sysm.uplift_pressure

    def fill(sol, a, b):
        if tev is None:
            return
        idx = np.nonzero((tev >= a) & (tev <= b))[0]
        if idx.size:
            y = sol(np.clip(tev[idx], sol.t_min, sol.t_max))
            th_ev[idx] = y[0]
            om_ev[idx] = y[1]

    def fill_const(a, b, thv, omv):
        if tev is not None:
            idx = (tev >= a) & (tev <= b)
            th_ev[idx] = thv
            om_ev[idx] = omv

    stop = False
    while t < dur and not stop:
        if s == 0.0:
            tl = _lift_time(pulse, t, p_lift)
            fill_const(t, min(tl, dur), 0.0, 0.0)
            if tl >= dur:
                t = dur
                break
            t, th, om, s = tl, 0.0, 0.0, 1.0
            continue
        nxt = [b for b in bps if b > t]
        t1 = min(nxt[0], dur) if nxt else dur
        sm = s

        def rhs(tt, y, sm=sm):
            a = al * sm - y[0]
            return [y[1], (-m * g * r * math.sin(a) + Sl * press(tt) * math.cos(a)) / J]

        ev_imp = _event(lambda tt, y: y[0], -sm, True)
        ev_pk = _event(lambda tt, y: y[1], -sm, False)
        ev_lie = _event(lambda tt, y, sm=sm: y[0] - sm * math.pi / 2, sm, True)
        events = [ev_imp, ev_pk, ev_lie]
        check_tip = not overturned and (sm > 0 or t >= t_pend)
        if check_tip:
            events.append(_event(lambda tt, y, sm=sm: y[0] - sm * al, sm, bool(stop_at_overturn)))
        sol = solve_ivp(rhs, (t, t1), [th, om], method=method, rtol=rtol, atol=atol, events=events, dense_output=True)
        nsteps += sol.t.size - 1
        hist.extend(zip(sol.t[1:], sol.y[0, 1:], sol.y[1, 1:]))
        max_abs = max(max_abs, float(np.max(np.abs(sol.y[0]))))
        for tp, yp in zip(sol.t_events[1], sol.y_events[1]):
            peaks.append((tp, yp[0]))
            max_abs = max(max_abs, abs(yp[0]))
        if check_tip and sol.t_events[3].size:
            overturned, t_over, om_over = True, float(sol.t_events[3][0]), abs(float(sol.y_events[3][0][1]))
        if check_tip and abs(th) >= al and not overturned:
            # already past the top at the segment start (the initial state, or -alpha when the
            # load ended): it overturns unless it moves back inward with the kinetic energy to
            # climb over the top, J_o om^2 / 2 > m g r (1 - cos(|th| - alpha))
            if not (sm * om < 0 and 0.5 * (om / p) ** 2 > 1.0 - math.cos(abs(th) - al)):
                overturned, t_over, om_over = True, t, abs(om)
        t_end = float(sol.t[-1])
        fill(sol.sol, t, t_end)
        if sol.status == 1:  # a terminal event
            if sol.t_events[2].size:  # lying down
                fill_const(t_end, dur, sm * math.pi / 2, 0.0)
                t, th, om, lying, max_abs = t_end, sm * math.pi / 2, 0.0, True, math.pi / 2
                hist.append((t, th, om))
                break
            if check_tip and stop_at_overturn and sol.t_events[3].size:
                t, th, om = t_end, float(sol.y[0, -1]), float(sol.y[1, -1])
                break
            # impact
            om_b = float(sol.y_events[0][0][1])
            om_a = e * om_b
            impacts.append((t_end, om_b, om_a))
            hist.append((t_end, 0.0, om_a))
            t, th = t_end, 0.0
            if abs(om_a) <= rest_velocity * p or e == 0.0:
                om, s = 0.0, 0.0
            else:
                om, s = om_a, -sm
            if max_impacts is not None and len(impacts) >= max_impacts:
                break
            continue
        t, th, om = t_end, float(sol.y[0, -1]), float(sol.y[1, -1])
    if tev is not None and not lying and s == 0.0:
        fill_const(t, math.inf, 0.0, 0.0)
    h = np.array(hist)
    imp = np.array(impacts).reshape(-1, 3)
    pk = np.array(peaks).reshape(-1, 2)
    return RockingResult(
        t=h[:, 0],
        theta=h[:, 1],
        theta_dot=h[:, 2],
        impact_times=imp[:, 0],
        impact_velocity_before=imp[:, 1],
        impact_velocity_after=imp[:, 2],
        peak_times=pk[:, 0],
        peak_angles=pk[:, 1],
        collapsed=overturned,
        collapse_time=none_if_nan(t_over),
        first_impact_time=float(imp[0, 0]) if imp.shape[0] else None,
        max_rotation=float(max_abs),
        end_time=float(t),
        n_steps=int(nsteps),
        n_rejected=0,
        restitution=e,
        angular_velocity_at_tipping=none_if_nan(om_over),
        t_eval=tev,
        theta_eval=th_ev,
        theta_dot_eval=om_ev,
        system=sysm,
    )
