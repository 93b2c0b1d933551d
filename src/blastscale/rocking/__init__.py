"""Planar rocking of a rigid body on a rigid base under blast (paper Eq. eq:eom).

* :class:`RockingSystem` (general body) / :func:`RockingSystem.from_block` (rectangular block),
  :func:`housner_restitution`;
* :class:`RockingSolver` (compiled Dormand-Prince 5(4), impacts, peaks, overturning) with
  :meth:`~RockingSolver.simulate` (one case, full history) and
  :meth:`~RockingSolver.simulate_batch` (many cases per call), :data:`DEFAULT_SOLVER`; results
  :class:`RockingResult` and :class:`RockingBatchResult` (:mod:`.results`); :func:`encode_pulse`
  and :data:`PULSE_CODES`, the kernel form of a pulse (:mod:`.encoding`);
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
from .encoding import PULSE_CODES, encode_pulse
from .reference import simulate_reference
from .results import RockingBatchResult, RockingResult
from .solver import DEFAULT_SOLVER, RockingSolver, check_count, simulate
from .system import RockingSystem, as_rocking_system, housner_restitution

__all__ = [
    "RockingSystem",
    "as_rocking_system",
    "housner_restitution",
    "RockingSolver",
    "DEFAULT_SOLVER",
    "RockingResult",
    "RockingBatchResult",
    "simulate",
    "simulate_reference",
    "check_count",
    "PULSE_CODES",
    "encode_pulse",
    "CriticalResult",
    "CapacityCurve",
    "capacity_curve",
    "PIDiagram",
    "critical_charge",
    "critical_standoff",
    "overturn_margin",
    "pi_diagram",
]
