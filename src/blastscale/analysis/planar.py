"""Planar rocking runs outside the Study: the one place that builds a rocking system and runs the engine for the
planner, the weighing odds, the sweeps' outcome and fragility modes, the reproduced numbers and the CLI's
capacity commands.

A body is a :class:`~blastscale.structures.RectangularBlock` (made a
:class:`~blastscale.rocking.RockingSystem` here, with ``gravity`` [m/s^2] and ``restitution`` [-]; None:
standard gravity and Housner's restitution) or a :class:`~blastscale.rocking.RockingSystem` (taken as it is).
Each function runs one of the engine's searches or integrations on it (paper Method A, Eq. eom; the
first-swing energy criterion, docs/capacity.md):

* :func:`first_swing_of` -- outcome and largest rotation under the reflected pulse of charges [kg] at stand-offs
  [m] (:func:`blastscale.rocking.first_swing`); :func:`first_swing_under` the same under given blast parameters,
  with per-case restitution and a scaled load (:func:`blastscale.rocking.first_swing_blast`);
* :func:`history_of` -- the full history under one pulse (:meth:`blastscale.rocking.RockingSolver.simulate`);
* :func:`critical_of` -- the critical charge at a stand-off or the critical stand-off of a charge
  (:func:`blastscale.rocking.critical_charge`, :func:`blastscale.rocking.critical_standoff`);
* :func:`capacity_of` -- the capacity curve W_c(R) (:func:`blastscale.rocking.capacity_curve`); a reduced-scale
  model's, up-scaled: :func:`blastscale.analysis.capacity.model_capacity_curve`;
* :func:`negative_phase_uncertainty_of` -- the critical charge under each negative-phase model;
  :func:`pi_diagram_of` -- the pressure-impulse overturning diagram (:func:`blastscale.rocking.pi_diagram`).

References: paper Sec. "Equations of motion"; Housner (1963), BSSA 53(2) (restitution).
"""

from __future__ import annotations

import numpy as np

from .._validate import BlastscaleInputError
from ..blast.parameters import DEFAULT_BLAST_MODEL
from ..rocking.capacity import CapacityCurve, capacity_curve
from ..rocking.critical import CriticalResult, critical_charge, critical_standoff, negative_phase_uncertainty
from ..rocking.pressure_impulse import PIDiagram, pi_diagram
from ..rocking.results import RockingResult
from ..rocking.solver import DEFAULT_SOLVER, RockingSolver
from ..rocking.swing import FirstSwing, first_swing, first_swing_blast
from ..rocking.system import RockingSystem, as_rocking_system

__all__ = [
    "planar_system",
    "first_swing_of",
    "first_swing_under",
    "history_of",
    "critical_of",
    "capacity_of",
    "negative_phase_uncertainty_of",
    "pi_diagram_of",
]


def planar_system(body, gravity: float | None = None, restitution: float | None = None) -> RockingSystem:
    """The rocking system of ``body`` (module docstring): a block with ``gravity`` [m/s^2] and ``restitution``
    [-] (None: standard gravity, Housner's), a system as it is."""
    return as_rocking_system(body, gravity, restitution)


def first_swing_of(
    body,
    charge,
    standoff,
    *,
    gravity: float | None = None,
    restitution: float | None = None,
    pulse_shape: str = "friedlander",
    blast_model=DEFAULT_BLAST_MODEL,
    extrapolate: bool = False,
    load_model=None,
    solver: RockingSolver | None = None,
) -> FirstSwing:
    """Outcome and largest rotation of ``body`` (or of one body per case: a sequence of systems) under the
    reflected pulse of ``charge`` [kg TNT] at ``standoff`` [m], arrays broadcast (:func:`~blastscale.rocking.first_swing`)."""
    systems = body if isinstance(body, (list, tuple)) else planar_system(body, gravity, restitution)
    return first_swing(
        systems,
        charge,
        standoff,
        pulse_shape=pulse_shape,
        blast_model=blast_model,
        extrapolate=extrapolate,
        solver=solver,
        load_model=load_model,
    )


def first_swing_under(
    body,
    blast,
    pulse_shape: str = "friedlander",
    *,
    restitution=None,
    density_ratio=None,
    gravity: float | None = None,
    load_model=None,
    extrapolate: bool = False,
    solver: RockingSolver | None = None,
) -> FirstSwing:
    """:class:`~blastscale.rocking.FirstSwing` of ``body`` under the n reflected pulses of ``blast``
    (:class:`~blastscale.blast.BlastParameters` on arrays), vectorised (:func:`~blastscale.rocking.first_swing_blast`).

    ``restitution`` [-] (array_like, per case) replaces the body's; ``density_ratio`` [-] (array_like, per
    case) is the block's density over the body's: a homogeneous block's load-to-weight ratio per pascal
    ``S l / (m g r cos alpha)`` is divided by it (its frequency parameter does not change).
    """
    system = planar_system(body, gravity)
    e = system.coefficient_of_restitution if restitution is None else restitution
    q = system.load_ratio_per_pascal
    return first_swing_blast(
        system.alpha,
        e,
        system.frequency_parameter,
        q if density_ratio is None else q / np.asarray(density_ratio, dtype=float),
        blast,
        pulse_shape,
        load_model=load_model,
        extrapolate=extrapolate,
        solver=solver,
    )


def history_of(
    body,
    pulse,
    duration: float,
    *,
    gravity: float | None = None,
    restitution: float | None = None,
    t_eval=None,
    solver: RockingSolver | None = None,
) -> RockingResult:
    """The full history of ``body`` at rest under ``pulse`` (a :class:`~blastscale.blast.Pulse`) over ``duration``
    [s] (:meth:`~blastscale.rocking.RockingSolver.simulate`; default solver rtol 1e-10, atol 1e-12)."""
    system = planar_system(body, gravity, restitution)
    return (solver or DEFAULT_SOLVER).simulate(system, pulse, float(duration), t_eval=t_eval)


def critical_of(
    body,
    *,
    standoff: float | None = None,
    charge: float | None = None,
    gravity: float | None = None,
    restitution: float | None = None,
    **kw,
) -> CriticalResult:
    """The critical charge [kg] of ``body`` at ``standoff`` [m], or its critical stand-off [m] under ``charge``
    [kg TNT] (exactly one given); ``kw`` as :func:`~blastscale.rocking.critical_charge` (pulse shape, blast
    model, extrapolate, load model, solver, tolerance)."""
    if (standoff is None) == (charge is None):
        raise BlastscaleInputError(
            f"standoff = {standoff}, charge = {charge}: give exactly one (the stand-off [m] finds the critical "
            "charge, the charge [kg] the critical stand-off)"
        )
    system = planar_system(body, gravity, restitution)
    if standoff is not None:
        return critical_charge(system, standoff, **kw)
    return critical_standoff(system, charge, **kw)


def capacity_of(
    body, standoffs, *, gravity: float | None = None, restitution: float | None = None, **kw
) -> CapacityCurve:
    """The capacity curve W_c(R) [kg] of ``body`` at ``standoffs`` [m] (:func:`~blastscale.rocking.capacity_curve`;
    ``kw`` as there)."""
    return capacity_curve(planar_system(body, gravity, restitution), standoffs, **kw)


def negative_phase_uncertainty_of(body, standoff: float, load_model, **kw) -> dict:
    """The critical charge [kg] of ``body`` at ``standoff`` [m] under each negative-phase model and without the
    negative phase (:func:`blastscale.rocking.critical.negative_phase_uncertainty`; ``kw`` as there)."""
    return negative_phase_uncertainty(planar_system(body), standoff, load_model, **kw)


def pi_diagram_of(body, *, gravity: float | None = None, restitution: float | None = None, **kw) -> PIDiagram:
    """The pressure-impulse overturning diagram of ``body`` (:func:`blastscale.rocking.pi_diagram`; ``kw`` as
    there)."""
    return pi_diagram(planar_system(body, gravity, restitution), **kw)
