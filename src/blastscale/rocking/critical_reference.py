"""The slow, independent reference for the critical charge: bisection on full simulations.

:func:`critical_charge_by_bisection` decides each trial charge [kg] by a full simulation of the
planar rocking equation (paper Eq. eom, :class:`~blastscale.rocking.solver.RockingSolver`) to rest,
every impact included, with no use of the first-swing criterion of :mod:`blastscale.rocking.swing`;
the fast searches of :mod:`blastscale.rocking.critical` are checked against it (tests, benchmarks).

References: paper Sec. "Equations of motion" (W_pc = 79.8 kg for the 10 m block at 2 m); Housner
(1963), Bull. Seismol. Soc. Am. 53(2) (impacts).
"""

from __future__ import annotations

import math

from .._validate import BlastscaleInputError
from ..blast.load_model import front_face_pulse
from ..blast.parameters import DEFAULT_BLAST_MODEL, blast_parameters, valid_scaled_distance_range
from .solver import DEFAULT_SOLVER, RockingSolver
from .system import as_rocking_system

__all__ = ["critical_charge_by_bisection"]


def critical_charge_by_bisection(
    body,
    standoff: float,
    guess: float,
    *,
    pulse_shape: str = "friedlander",
    blast_model=DEFAULT_BLAST_MODEL,
    rel: float = 1e-8,
    solver: RockingSolver | None = None,
    gravity: float | None = None,
    restitution: float | None = None,
    load_model=None,
) -> float:
    """The slow reference: critical charge [kg] by bisection in ln W on full simulations (to rest:
    ``pulse + 200 / p`` of motion, every impact, no early stop), independent of the first-swing
    criterion. The bracket ``[guess / 1.5, 1.5 guess]`` [kg], kept inside the blast model's valid
    range of Z, must straddle the threshold (checked); ``rel`` is the relative width at which it
    stops; ``load_model`` as :func:`critical_charge` (the pulse of
    :func:`~blastscale.blast.load_model.front_face_pulse`). For tests and benchmarks."""

    system = as_rocking_system(body, gravity, restitution)
    solver = solver or DEFAULT_SOLVER

    def over(W):
        p = front_face_pulse(blast_parameters(W, standoff, blast_model), pulse_shape, load_model)
        return solver.simulate(system, p, p.duration + 200.0 / system.frequency_parameter).collapsed

    zlo, zhi = valid_scaled_distance_range(blast_model)
    lo = max(guess / 1.5, (standoff / zhi) ** 3 * (1.0 + 1e-12))  # the charges whose Z lies in the fits
    hi = min(guess * 1.5, (standoff / zlo) ** 3 * (1.0 - 1e-12))
    if over(lo) or not over(hi):
        raise BlastscaleInputError(
            f"guess = {guess:.6g} kg: [guess/1.5, 1.5 guess] does not straddle the critical charge"
        )
    while math.log(hi / lo) > rel:
        mid = math.sqrt(lo * hi)
        lo, hi = (lo, mid) if over(mid) else (mid, hi)
    return math.sqrt(lo * hi)
