"""Overturning capacity: critical charge, critical stand-off and the P-I diagram.

All three rest on one continuous *overturning margin* of a body under a pulse, computed by
the rocking solver up to the first impact (or the tipping point):

.. math::

    \\mu = \\begin{cases}
      \\theta_{max}/\\alpha - 1 \\le 0 & \\text{no overturning (first excursion peak)}\\\\
      \\dot\\theta_\\alpha / (p\\sqrt{2(1-\\cos\\alpha)}) \\ge 0 & \\text{overturning}
    \\end{cases}

(theta_dot_alpha: angular velocity when |theta| passes alpha). Both branches tend to 0 at
the threshold, so mu is continuous and increases with the load; roots are found with
Brent's method (scipy ``brentq``) in the logarithm of the charge / stand-off / impulse
after a geometric bracket search. Only the first excursion matters: after the pulse the
energy only decreases (every impact removes a fraction 1 - e^2 of it).

References: paper Sec. "Equations of motion" (W_pc = 79.8 kg for the 10 m block at 2 m);
Masi et al. (2019), Int. J. Mech. Sci. 157 (critical impulse); P-I diagrams: Krauthammer,
*Modern Protective Structures* (2008), Ch. 5.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from .._validate import BlastscaleInputError, OutOfRangeError, check_positive, check_range
from ..blast.parameters import DEFAULT_BLAST_MODEL, blast_parameters
from ..blast.pulses import Friedlander, Pulse, Triangular, friedlander_impulse_ratio
from .solver import DEFAULT_SOLVER, RockingSolver, _check_count
from .system import RockingSystem, as_rocking_system

__all__ = ["overturn_margin", "critical_charge", "critical_standoff", "CriticalResult", "pi_diagram", "PIDiagram"]

PULSE_SHAPES = ("friedlander", "triangular", "impulsive")


def _horizon(system: RockingSystem, pulse: Pulse) -> float:
    """Simulated time long enough to reach the first impact or the tipping point [s]."""
    return float(pulse.duration) + 50.0 / system.frequency_parameter


def overturn_margin(body, pulse: Pulse, *, solver: RockingSolver | None = None, gravity=None, restitution=None) -> float:
    """Continuous overturning margin mu [-] of ``body`` under ``pulse`` (module docstring).

    Parameters
    ----------
    body : RockingSystem or RectangularBlock
        The body (a block is converted with ``gravity`` [m/s^2] and ``restitution`` [-]).
    pulse : Pulse
        Pressure pulse on the loaded face from the shock arrival.
    solver : RockingSolver, optional
        Solver (default rtol 1e-10, atol 1e-12).

    Returns
    -------
    mu : float
        ``theta_max / alpha - 1`` (< 0, survives; theta_max the first excursion peak [rad])
        or ``theta_dot_alpha / (p sqrt(2 (1 - cos alpha)))`` (>= 0, overturns); simulated up
        to the first impact or the tipping point (``pulse.duration + 50 / p`` at most).
    """
    system = as_rocking_system(body, gravity, restitution)
    if not isinstance(pulse, Pulse):
        raise BlastscaleInputError(f"pulse must be a blastscale Pulse, got {type(pulse).__name__}")
    solver = solver or DEFAULT_SOLVER
    res = solver.simulate(system, pulse, _horizon(system, pulse), stop_at_overturn=True, max_impacts=1)
    if res.overturned:
        return float(res.angular_velocity_at_tipping) / system.critical_angular_velocity
    return res.max_angle / system.alpha - 1.0


@dataclass(frozen=True)
class CriticalResult:
    """Result of a critical charge / stand-off search (SI).

    ``charge_kg`` [kg] and ``standoff_m`` [m] define the critical scenario (the one searched
    for and the one held fixed); ``pulse`` the pulse shape; ``relative_tolerance`` the
    relative accuracy of the searched quantity; ``evaluations`` the number of simulations;
    ``bracket`` the final bracket of the searched quantity.
    """

    charge_kg: float
    standoff_m: float
    searched: str
    pulse: str
    model: str
    relative_tolerance: float
    evaluations: int
    bracket: tuple[float, float]

    def to_dict(self) -> dict:
        """Plain dict with unit-suffixed keys (``critical_charge_kg`` or ``critical_standoff_m``)."""
        return {
            "critical_charge_kg" if self.searched == "charge" else "critical_standoff_m": (
                self.charge_kg if self.searched == "charge" else self.standoff_m
            ),
            "charge_kg": self.charge_kg,
            "standoff_m": self.standoff_m,
            "pulse": self.pulse,
            "model": self.model,
            "relative_tolerance": self.relative_tolerance,
            "evaluations": self.evaluations,
        }


def _search(fun, x0: float, increasing: bool, xtol_rel: float, name: str, unit: str):
    """Root of fun(x) (monotone, continuous) by bracketing in ln x then brentq."""
    check_range("xtol_rel", xtol_rel, 1e-14, 0.1)
    count = [0]

    def f(u):
        count[0] += 1
        return fun(math.exp(u))

    u0 = math.log(x0)
    try:
        f0 = f(u0)
    except OutOfRangeError as exc:
        raise BlastscaleInputError(f"critical {name} search: the starting {name} {x0:.6g} {unit} is outside the blast model's range ({exc})") from exc
    # move towards the root: if f0 > 0 (overturns) and f increasing, decrease x
    step = -math.log(2.0) if (f0 > 0) == increasing else math.log(2.0)
    ua, fa = u0, f0
    for _ in range(60):
        ub = ua + step
        try:
            fb = f(ub)
        except OutOfRangeError as exc:
            raise BlastscaleInputError(
                f"no critical {name} within the blast model's valid range: reached {math.exp(ub):.6g} {unit} "
                f"without a change of outcome ({exc})"
            ) from exc
        if (fb > 0) != (fa > 0):
            break
        ua, fa = ub, fb
    else:
        raise BlastscaleInputError(f"no critical {name} found between {x0:.6g} and {math.exp(ub):.6g} {unit}")
    lo, hi = sorted((ua, ub))
    root = brentq(f, lo, hi, xtol=xtol_rel, rtol=4 * np.finfo(float).eps, maxiter=200)
    return math.exp(root), (math.exp(lo), math.exp(hi)), count[0]


def _pulse_from_params(bp, shape: str) -> Pulse:
    if shape not in PULSE_SHAPES:
        raise BlastscaleInputError(f"pulse = {shape!r} is not known: valid values are {', '.join(PULSE_SHAPES)}")
    return bp.pulse(shape)


def critical_charge(
    body,
    standoff: float,
    *,
    pulse: str = "friedlander",
    model=DEFAULT_BLAST_MODEL,
    gravity: float | None = None,
    restitution: float | None = None,
    solver: RockingSolver | None = None,
    guess: float = 10.0,
    xtol_rel: float = 1e-9,
) -> CriticalResult:
    """Largest TNT charge [kg] at ``standoff`` [m] that the body survives without overturning.

    The reflected pulse of shape ``pulse`` from ``blast_parameters(W, standoff, model)`` loads
    the front face uniformly (paper Method A, Eq. eom). The margin mu(W) (module docstring) is
    bracketed from ``guess`` by factors of 2 and its root found by brentq in ln W.

    Parameters
    ----------
    body : RockingSystem or RectangularBlock
        The body (a block is converted with ``gravity`` [m/s^2] and ``restitution`` [-];
        the restitution does not affect the first excursion).
    standoff : float
        Stand-off R [m], > 0.
    pulse : {"friedlander", "triangular", "impulsive"}
        Reflected pulse shape (paper Eqs. 1, 3, impulsive limit).
    model : str
        Blast model, ``"kingery-bulmash"`` (Swisdak 1994) or ``"masi2021"`` (paper App. A);
        valid over its range of scaled distance Z (0.2-20 m/kg^(1/3) for masi2021).
    solver : RockingSolver, optional
        Solver (default rtol 1e-10, atol 1e-12).
    guess : float
        Starting charge [kg], > 0.
    xtol_rel : float
        Relative tolerance on the charge [-], in [1e-14, 0.1].

    Returns
    -------
    CriticalResult
        ``charge_kg`` [kg] (the critical charge), ``standoff_m`` [m], evaluations, bracket.

    Raises
    ------
    BlastscaleInputError
        If no change of outcome is found within the blast model's valid range of Z.

    Examples
    --------
    The paper's 10 m block (alpha = 15 deg) at 2 m: 79.8 kg (paper Sec. "Equations of motion").
    """
    R = float(check_positive("standoff", standoff, "m"))
    check_positive("guess", guess, "kg")
    return _critical(body, "charge", R, pulse, model, gravity, restitution, solver, guess, xtol_rel)


def critical_standoff(
    body,
    charge: float,
    *,
    pulse: str = "friedlander",
    model=DEFAULT_BLAST_MODEL,
    gravity: float | None = None,
    restitution: float | None = None,
    solver: RockingSolver | None = None,
    guess: float = 5.0,
    xtol_rel: float = 1e-9,
) -> CriticalResult:
    """Smallest stand-off [m] at which the body survives ``charge`` [kg TNT] without
    overturning (same method and parameters as :func:`critical_charge`, with ``charge`` W
    [kg] > 0 fixed and ``guess`` the starting stand-off [m]; the margin decreases with
    distance). Returns a :class:`CriticalResult` whose ``standoff_m`` [m] is the critical
    stand-off. References: paper Sec. "Equations of motion"; Masi et al. (2019)."""
    W = float(check_positive("charge", charge, "kg"))
    check_positive("guess", guess, "m")
    return _critical(body, "standoff", W, pulse, model, gravity, restitution, solver, guess, xtol_rel)


def _critical(body, searched, fixed, pulse, model, gravity, restitution, solver, guess, xtol_rel) -> CriticalResult:
    """Critical charge (``searched="charge"``, ``fixed`` the stand-off [m]; the margin grows
    with the charge) or stand-off (``"standoff"``, ``fixed`` the charge [kg]; it falls with
    the distance)."""
    system = as_rocking_system(body, gravity, restitution)
    solver = solver or DEFAULT_SOLVER
    by_charge = searched == "charge"

    def margin(x):
        W, R = (x, fixed) if by_charge else (fixed, x)
        return overturn_margin(system, _pulse_from_params(blast_parameters(W, R, model), pulse), solver=solver)

    x, br, n = _search(margin, guess, by_charge, xtol_rel, searched, "kg" if by_charge else "m")
    W, R = (x, fixed) if by_charge else (fixed, x)
    name = model if isinstance(model, str) else getattr(model, "name", str(model))
    return CriticalResult(W, R, searched, pulse, name, xtol_rel, n, br)


@dataclass(frozen=True)
class PIDiagram:
    """Pressure-impulse overturning curve of a body (SI).

    ``peak_pressure`` [Pa] and ``critical_impulse`` [Pa*s] are the points of the curve (a
    pulse of that peak overturns the body when its impulse exceeds the critical one);
    ``impulse_asymptote`` [Pa*s] is the impulsive limit ``J_o theta_dot_c / (S l)`` and
    ``pressure_asymptote`` [Pa] the uplift pressure (``P S h = m g b``), the quasi-static limit.
    """

    peak_pressure: np.ndarray
    critical_impulse: np.ndarray
    impulse_asymptote: float
    pressure_asymptote: float
    shape: str


def pi_diagram(
    body,
    peak_pressures=None,
    *,
    n: int = 25,
    shape: str = "triangular",
    decay: float = 1.0,
    gravity: float | None = None,
    restitution: float | None = None,
    solver: RockingSolver | None = None,
    xtol_rel: float = 1e-6,
) -> PIDiagram:
    """Pressure-impulse (P-I) overturning diagram of a body.

    For each peak pressure P the critical impulse i_c(P) that just overturns the body is found
    with :func:`overturn_margin` and brentq in ln i. i_c tends to the impulsive asymptote
    ``J_o p sqrt(2 (1 - cos alpha)) / (S l)`` as P grows and diverges as P falls to the uplift
    pressure ``m g r sin(alpha) / (S l)`` (``P S h = m g b`` for a block).

    Parameters
    ----------
    body : RockingSystem or RectangularBlock
        The body (a block is converted with ``gravity`` [m/s^2] and ``restitution`` [-]).
    peak_pressures : array_like, optional
        Non-empty 1-D peak pressures [Pa], each above the uplift pressure; default ``n``
        values log-spaced from 1.02 to 1e4 times the uplift pressure.
    n : int
        Number of default pressures (>= 1).
    shape : {"triangular", "friedlander"}
        Pulse shape: triangular (paper Eq. 3, duration ``2 i / P``) or Friedlander with decay
        ``decay`` d [-] (duration ``i / (P k(d))``, paper Eq. 2).
    solver : RockingSolver, optional
        Solver (default rtol 1e-10, atol 1e-12).
    xtol_rel : float
        Relative tolerance on each critical impulse [-].

    Returns
    -------
    PIDiagram
        ``peak_pressure`` [Pa], ``critical_impulse`` [Pa*s] and the two asymptotes.

    References: Krauthammer (2008), *Modern Protective Structures*, Ch. 5 (P-I diagrams);
    Masi et al. (2019), Int. J. Mech. Sci. 157 (impulsive limit).
    """
    system = as_rocking_system(body, gravity, restitution)
    solver = solver or DEFAULT_SOLVER
    p_up = system.uplift_pressure
    i_imp = system.critical_impulse
    if peak_pressures is None:
        P = p_up * np.logspace(math.log10(1.02), 4.0, _check_count("n", n, 1))
    else:
        P = np.atleast_1d(check_positive("peak pressure", peak_pressures, "Pa")).astype(float)
        if P.ndim != 1 or P.size == 0:
            raise BlastscaleInputError(f"peak_pressures must be a non-empty 1-D list of pressures [Pa], got shape {P.shape}")
        if np.any(P <= p_up):
            raise BlastscaleInputError(
                f"peak pressure = {float(P[P <= p_up][0]):.6g} Pa is out of range: must exceed the uplift "
                f"pressure {p_up:.6g} Pa (below it the body never lifts off)"
            )
    if shape == "triangular":
        def make(Pk, i):
            return Triangular(Pk, i)
    elif shape == "friedlander":
        k = friedlander_impulse_ratio(decay)

        def make(Pk, i):
            return Friedlander(Pk, i / (Pk * k), decay)
    else:
        raise BlastscaleInputError(f"P-I pulse shape = {shape!r} is not known: valid values are triangular, friedlander")
    ic = np.empty(P.size)
    for j, Pk in enumerate(P):
        ic[j] = _search(lambda i: overturn_margin(system, make(Pk, i), solver=solver), i_imp, True, xtol_rel, "impulse", "Pa*s")[0]
    return PIDiagram(P, ic, i_imp, p_up, shape)
