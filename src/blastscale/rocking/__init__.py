"""Planar rocking of a rigid body on a rigid base under blast (paper Eq. eq:eom).

* :class:`RockingSystem` (general body) / :func:`RockingSystem.from_block` (rectangular block),
  :func:`housner_restitution` (:mod:`.system`);
* :class:`RockingSolver` (compiled Dormand-Prince 5(4), impacts, peaks, overturning) with
  :meth:`~RockingSolver.simulate` (one case, full history) and
  :meth:`~RockingSolver.simulate_batch` (many cases per call), :data:`DEFAULT_SOLVER`,
  :func:`simulate` (:mod:`.solver`); results :class:`RockingResult` and
  :class:`RockingBatchResult` (:mod:`.results`); :func:`encode_pulse` and
  :data:`PULSE_CODES`, the kernel form of a pulse (:mod:`.encoding`);
* :func:`simulate_reference` — the slow scipy ``solve_ivp`` (DOP853) reference path;
* capacity (first-swing energy criterion, docs/capacity.md): :func:`overturn_margin`,
  :func:`first_swing`, :func:`overturns` (:mod:`.swing`); :func:`first_swing_margin`,
  :func:`first_swing_peak` (the first free swing in closed form, :mod:`.free_swing`); :func:`critical_charge`,
  :func:`critical_standoff` (:mod:`.critical`); :func:`capacity_curve` (:mod:`.capacity`; a model's
  curve up-scaled to the prototype: :func:`blastscale.analysis.capacity.model_capacity_curve`);
  :func:`pi_diagram` (:mod:`.pressure_impulse`).
"""

from .capacity import CapacityCurve, capacity_curve
from .critical import CriticalResult, critical_charge, critical_standoff
from .critical_reference import critical_charge_by_bisection
from .encoding import PULSE_CODES, encode_pulse
from .free_swing import first_swing_margin, first_swing_peak
from .swing import FirstSwing, first_swing, first_swing_blast, overturn_margin, overturns
from .frame import frame_frequency_parameter, free_rocking_peak, overturning_angular_velocity
from .pressure_impulse import PIDiagram, pi_diagram
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
    "critical_charge_by_bisection",
    "FirstSwing",
    "first_swing",
    "first_swing_blast",
    "first_swing_margin",
    "first_swing_peak",
    "overturn_margin",
    "overturns",
    "pi_diagram",
    "frame_frequency_parameter",
    "free_rocking_peak",
    "overturning_angular_velocity",
]
