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

Each name is imported from its submodule on first access (module ``__getattr__``, PEP 562): importing the
package, or one of its light submodules (:mod:`.system`, :mod:`.results`), loads neither numba nor scipy.
Code inside blastscale imports from the defining submodule.
"""

import importlib

#: The submodule that defines each public name: imported on first access (PEP 562), so that
#: ``import blastscale.rocking.system`` (or any light submodule) does not load numba and scipy through
#: the compiled solver and the scipy reference path.
_HOMES = {
    "RockingSystem": "system",
    "as_rocking_system": "system",
    "housner_restitution": "system",
    "RockingSolver": "solver",
    "DEFAULT_SOLVER": "solver",
    "RockingResult": "results",
    "RockingBatchResult": "results",
    "simulate": "solver",
    "simulate_reference": "reference",
    "check_count": "solver",
    "PULSE_CODES": "encoding",
    "encode_pulse": "encoding",
    "CriticalResult": "critical",
    "CapacityCurve": "capacity",
    "capacity_curve": "capacity",
    "PIDiagram": "pressure_impulse",
    "critical_charge": "critical",
    "critical_standoff": "critical",
    "critical_charge_by_bisection": "critical_reference",
    "FirstSwing": "swing",
    "first_swing": "swing",
    "first_swing_blast": "swing",
    "first_swing_margin": "free_swing",
    "first_swing_peak": "free_swing",
    "overturn_margin": "swing",
    "overturns": "swing",
    "pi_diagram": "pressure_impulse",
    "frame_frequency_parameter": "frame",
    "free_rocking_peak": "frame",
    "overturning_angular_velocity": "frame",
}

#: The public names: those :data:`_HOMES` maps to their submodule (one list, so the two cannot drift).
__all__ = list(_HOMES)


def __getattr__(name: str):
    """The public name ``name`` from its defining submodule (:data:`_HOMES`), imported on first use."""
    home = _HOMES.get(name)
    if home is None:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    value = getattr(importlib.import_module(f"{__name__}.{home}"), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
