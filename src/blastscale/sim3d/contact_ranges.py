"""The valid values of the contact, integration and solver settings of the 3D engine: MuJoCo's vocabularies (cone,
solver, Jacobian layout) and the range of every numeric setting of :class:`~.contact.ContactSettings`, with its
unit (seconds, metres or none).

One source for both doors: :class:`~.contact.ContactSettings` checks itself against :data:`SETTING_RANGES` and the
scenario's ``[simulation.contact]`` keys read the same table (:mod:`blastscale.scenario.specs`). The MuJoCo names
are those of its XML reference (``<option cone solver jacobian>``).
"""

from __future__ import annotations

from typing import NamedTuple

from .._validate import BlastscaleInputError

__all__ = ["CONES", "JACOBIANS", "SETTING_RANGES", "SETTLINGS", "SOLVERS", "STEPS_AFTER_LOAD", "Range", "check_scalar"]

#: Friction-cone types accepted by MuJoCo.
CONES = ("elliptic", "pyramidal")
#: Constraint solvers accepted by MuJoCo.
SOLVERS = ("Newton", "CG", "PGS")
#: Constraint-Jacobian layouts accepted by MuJoCo (``<option jacobian=...>``).
JACOBIANS = ("dense", "sparse", "auto")
#: The time step once every pulse has passed (:func:`~.integrate.step_factor_after_load`).
STEPS_AFTER_LOAD = ("double", "same")
#: How a structure settles before the first arrival (:func:`~.integrate.settle_time_constants`): "plain" for
#: :data:`~.integrate.SETTLE_TIME_CONSTANTS` contact time constants, "kinetic" (kinetic damping) for
#: :data:`~.integrate.KINETIC_SETTLE_TIME_CONSTANTS`.
SETTLINGS = ("plain", "kinetic")


def check_scalar(name: str, value) -> None:
    """One number (or None), not an array: settings are per run."""
    if value is not None and not isinstance(value, str) and getattr(value, "ndim", 0) != 0:
        raise BlastscaleInputError(f"{name} must be a single number, got shape {value.shape}")


class Range(NamedTuple):
    """A valid range ``lo .. hi`` [unit], each end open or closed."""

    lo: float
    hi: float
    lo_open: bool = False
    hi_open: bool = False
    unit: str = ""


#: The valid range of every numeric setting of :class:`~.contact.ContactSettings` (its own checks and the
#: scenario's ``[simulation.contact]`` keys read them here). The upper bounds are generous physical
#: limits (a 10 s contact time constant is already five thousand times MuJoCo's default); the
#: friction coefficient bounds a scenario's too (mu = 10 is beyond any masonry interface).
SETTING_RANGES: dict[str, Range] = {
    "friction": Range(0.0, 10.0),
    "time_constant": Range(0.0, 10.0, lo_open=True, unit="s"),
    "damping_ratio": Range(0.0, 100.0, lo_open=True),
    "friction_time_constant": Range(0.0, 10.0, lo_open=True, unit="s"),
    "impedance_min": Range(0.0, 1.0, lo_open=True, hi_open=True),
    "impedance_max": Range(0.0, 1.0, lo_open=True, hi_open=True),  # and >= impedance_min
    "impedance_width": Range(0.0, 10.0, lo_open=True, unit="m"),
    "timestep": Range(0.0, 0.1, lo_open=True, unit="s"),
    "impratio": Range(0.0, 1e4, lo_open=True),
    "iterations": Range(1, 10_000),
    "tolerance": Range(0.0, 1.0, lo_open=True),
    "settle_tolerance": Range(0.0, 1.0, lo_open=True),
    "noslip_iterations": Range(0, 10_000),
}
