"""Planar rocking of a rigid body on a rigid base under blast (paper Eq. eq:eom).

* :class:`RockingSystem` (general body) / :func:`RockingSystem.from_block` (rectangular block),
  :func:`housner_restitution`;
* :class:`RockingSolver` (compiled Dormand-Prince 5(4), impacts, peaks, overturning) with
  :meth:`~RockingSolver.simulate` (one case, full history) and
  :meth:`~RockingSolver.simulate_batch` (many cases per call), results :class:`RockingResult`
  and :class:`RockingBatchResult`;
* :func:`simulate_reference` — the slow scipy ``solve_ivp`` (DOP853) reference path;
* capacity (first-swing energy criterion, docs/capacity.md): :func:`critical_charge`,
  :func:`critical_standoff`, :func:`capacity_curve`, :func:`pi_diagram`.
"""

from .capacity import (
    CapacityCurve,
    CriticalResult,
    PIDiagram,
    capacity_curve,
    critical_charge,
    critical_standoff,
    overturn_margin,
    pi_diagram,
)
from .reference import simulate_reference
from .solver import RockingBatchResult, RockingResult, RockingSolver, simulate
from .system import RockingSystem, as_rocking_system, housner_restitution

__all__ = [
    "RockingSystem",
    "as_rocking_system",
    "housner_restitution",
    "RockingSolver",
    "RockingResult",
    "RockingBatchResult",
    "simulate",
    "simulate_reference",
    "CriticalResult",
    "CapacityCurve",
    "capacity_curve",
    "PIDiagram",
    "critical_charge",
    "critical_standoff",
    "overturn_margin",
    "pi_diagram",
]
