"""Pressure-impulse (P-I) overturning diagram of a rocking body.

For each peak pressure P the critical impulse i_c(P) that just overturns the body is a root
of the first-swing margin (:mod:`blastscale.rocking.swing`) in ln i, all pressures at
once (:func:`blastscale.roots.vector_root`). i_c tends to the impulsive asymptote
``J_o p sqrt(2 (1 - cos alpha)) / (S l)`` as P grows and diverges as P falls to the uplift
pressure ``m g r sin(alpha) / (S l)``.

References: Krauthammer (2008), *Modern Protective Structures*, Ch. 5 (P-I diagrams);
Masi et al. (2019), Int. J. Mech. Sci. 157 (impulsive limit); Housner (1963).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .._validate import BlastscaleInputError, check_choice, check_positive, check_range
from ..blast.friedlander import friedlander_impulse_ratio
from ..roots import vector_root
from .encoding import PULSE_CODES
from .layout import PAR_SIZE
from .solver import DEFAULT_SOLVER, RockingSolver, check_count
from .swing import pulse_phase
from .system import as_rocking_system

__all__ = ["pi_diagram", "PIDiagram"]


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
    with the first-swing criterion (:mod:`blastscale.rocking.swing`), all pressures at once, in ln i. i_c
    tends to the impulsive asymptote ``J_o p sqrt(2 (1 - cos alpha)) / (S l)`` as P grows and
    diverges as P falls to the uplift pressure ``m g r sin(alpha) / (S l)`` (``P S h = m g b``
    for a block).

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
    check_range("xtol_rel", xtol_rel, 1e-14, 0.1)
    p_up = system.uplift_pressure
    i_imp = system.critical_impulse
    if peak_pressures is None:
        P = p_up * np.logspace(math.log10(1.02), 4.0, check_count("n", n, 1))
    else:
        P = np.atleast_1d(check_positive("peak pressure", peak_pressures, "Pa")).astype(float)
        if P.ndim != 1 or P.size == 0:
            raise BlastscaleInputError(
                f"peak_pressures must be a non-empty 1-D list of pressures [Pa], got shape {P.shape}"
            )
        if np.any(P <= p_up):
            raise BlastscaleInputError(
                f"peak pressure = {float(P[P <= p_up][0]):.6g} Pa is out of range: must exceed the uplift "
                f"pressure {p_up:.6g} Pa (below it the body never lifts off)"
            )
    check_choice("P-I pulse shape", shape, ("triangular", "friedlander"))
    if shape == "triangular":
        kind, dur_per_impulse, d = PULSE_CODES[shape], 2.0 / P, 0.0
    else:  # friedlander
        kind, dur_per_impulse, d = PULSE_CODES[shape], 1.0 / (P * float(friedlander_impulse_ratio(decay))), float(decay)
    pf, q = system.frequency_parameter, system.load_ratio_per_pascal

    def evaluate(idx, u):
        m = idx.size
        par = np.zeros((m, PAR_SIZE))
        par[:, 0] = q * P[idx]
        par[:, 1] = pf * np.exp(u) * dur_per_impulse[idx]
        par[:, 2] = d
        return pulse_phase(
            solver,
            np.full(m, system.alpha),
            np.full(m, system.coefficient_of_restitution),
            np.zeros(m),
            np.full(m, kind, dtype=np.int64),
            par,
        ).margin

    u0 = np.full(P.size, math.log(i_imp))
    lo, hi, _, status = vector_root(evaluate, u0, u0 - 1.0, u0 + 40.0, xtol_rel)
    if np.any(status != 0):
        raise BlastscaleInputError(
            f"peak pressure = {float(P[status != 0][0]):.6g} Pa: no critical impulse found up to e^40 times the impulsive one"
        )
    return PIDiagram(P, np.exp(hi), i_imp, p_up, shape)
