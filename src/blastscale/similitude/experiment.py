"""A designed experiment as data: :class:`ModelDesign` (the specimen's charge and stand-off, every
factor, the blast parameters of both systems, the delivered and the required ratios) and the
a-posteriori check that the load is impulsive (:class:`ImpulsiveCheck`, :func:`impulsive_check`).

Impulsive check
---------------
The general law matches the impulse only; the pulse duration and peak do not scale as the
response requires (paper Sec. "Scaling laws"). This is harmless when the pulse is short
compared with the structure's characteristic time: for a rocking block, when
``t_o * p << 1`` with Housner's frequency parameter ``p = sqrt(3 g / (4 r))``. We flag the
load as impulsive when ``t_o p`` is below ``impulsive_threshold`` (default 0.4) in *both*
prototype and model; 0.4 is the bound of the impulsive regime of a linear oscillator,
``omega t_d < 0.4`` (Baker et al. 1983, *Explosion Hazards and Evaluation*, ch. 4), applied
with p in place of omega. The paper's wording "pi_23 << 1" is not literally true (the peak
force exceeds the weight by orders of magnitude); t_o p is the meaningful measure.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from .._validate import check_positive
from ..blast.load_model import load_model_record
from ..blast.parameters import BlastParameters
from ..constants import STANDARD_GRAVITY
from ..structures.block import RectangularBlock
from ..structures.from_spec import is_block
from .factors import ScalingFactors, to_specimen

__all__ = ["ImpulsiveCheck", "ModelDesign", "impulsive_check", "DEFAULT_IMPULSIVE_THRESHOLD"]

DEFAULT_IMPULSIVE_THRESHOLD = 0.4


@dataclass(frozen=True)
class ImpulsiveCheck:
    """A-posteriori check of the impulsive hypothesis.

    Attributes
    ----------
    prototype_ratio, model_ratio : float
        t_o * p of prototype and model [-] (t_o the positive duration [s], p = sqrt(3 g / 4 r) [rad/s]).
    threshold : float
        Bound below which the load counts as impulsive [-].
    impulsive : bool
        Both ratios below the threshold.
    """

    prototype_ratio: float
    model_ratio: float
    threshold: float

    @property
    def impulsive(self) -> "bool | np.ndarray":
        """Both t_o p below the threshold (an array for a design of arrays; False where NaN)."""
        if np.ndim(self.prototype_ratio) or np.ndim(self.model_ratio):
            return np.maximum(self.prototype_ratio, self.model_ratio) < self.threshold
        return max(self.prototype_ratio, self.model_ratio) < self.threshold

    def to_dict(self) -> dict:
        return {
            "prototype_to_p": self.prototype_ratio,
            "model_to_p": self.model_ratio,
            "threshold": self.threshold,
            "impulsive": self.impulsive,
        }


def impulsive_check(duration: float, block: RectangularBlock, gravity: float = STANDARD_GRAVITY) -> float:
    """The impulsiveness measure of a pulse on a rocking block [-].

    .. math:: t_o\\,p, \\qquad p = \\sqrt{3 g / (4 r)}

    with ``duration`` t_o [s] (> 0), ``block`` (r = half-diagonal [m]) and ``gravity`` g [m/s^2].
    The load acts as an impulse when t_o p << 1; :func:`design_model` flags it below 0.4 (the
    impulsive regime omega t_d < 0.4 of Baker et al. 1983, ch. 4). References: Housner (1963)
    for p; docs/design.md on why this, not the paper's "pi_23 << 1", is the meaningful check.
    """
    check_positive("positive duration", duration, "s")
    return float(duration) * block.frequency_parameter(gravity)


@dataclass(frozen=True)
class ModelDesign:
    """A designed reduced-scale experiment (all SI; ratios are model / prototype).

    Attributes
    ----------
    law : str
        ``"general"`` (paper Eq. 8) or ``"hopkinson-cranz"``.
    scale, density_ratio, gravity_ratio : float
        lambda, gamma, varsigma [-].
    scaled_distance_factor : float
        lambda_Z = Z_model / Z_prototype [-].
    root_note : str
        Which root of the law was taken.
    prototype, specimen : BlastParameters
        Blast parameters at the prototype's and the specimen's stand-offs (the specimen: the
        reduced-scale physical model, the paper's "model").
    factors : ScalingFactors
        Every factor (charge and scaled distance included).
    impulsive : ImpulsiveCheck or None
        Present when the structure was given and is a rectangular block.
    prototype_structure, specimen_structure : structure or None
        The prototype structure (any kind), when given, and its specimen (``structure.scaled(factors)``:
        lengths x lambda, density x gamma), built once by the design.
    gravity : float
        Prototype gravity [m/s^2] (the specimen's: :attr:`specimen_gravity`).
    valid : bool or ndarray
        True for a design of one charge and stand-off (an invalid one raises); for arrays, the
        cases that could be designed (their scaled distances inside the blast fits); the numbers of
        the others are NaN.
    effects : dict or None
        Clearing, negative phase and burst types of both systems (:func:`~.effects.blast_effects`),
        when any was asked for.
    notes : tuple of str
        Differences between the systems above 5 % that the scaling law does not see (warned).
    load_model, specimen_load_model : LoadModel
        The prototype's load model (clearing on its face, the negative phase; the paper's load when none
        was given) and the specimen's (its face x lambda: :meth:`LoadModel.scaled`, once).
    contact, specimen_contact : ContactSettings or None
        The prototype's 3D contact settings, when given, and the specimen's (``contact.scaled(factors)``).
    duration, specimen_duration : float or None
        The prototype's simulated time [s], when given, and the specimen's (x lambda_t).
    """

    law: str
    scale: float
    density_ratio: float
    gravity_ratio: float
    scaled_distance_factor: float
    root_note: str
    prototype: BlastParameters
    specimen: BlastParameters
    factors: ScalingFactors
    impulsive: ImpulsiveCheck | None = None
    prototype_structure: Any = None
    specimen_structure: Any = None
    gravity: float = STANDARD_GRAVITY
    valid: "bool | np.ndarray" = True
    effects: dict | None = None
    notes: tuple = ()
    load_model: Any = None
    specimen_load_model: Any = None
    contact: Any = None
    specimen_contact: Any = None
    duration: float | None = None
    specimen_duration: float | None = None

    # convenient views -------------------------------------------------------
    @property
    def prototype_block(self) -> RectangularBlock | None:
        """The prototype structure when it is a single rectangular block (planar rocking), else None."""
        return self.prototype_structure if is_block(self.prototype_structure) else None

    @property
    def specimen_block(self) -> RectangularBlock | None:
        """The specimen structure when it is a single rectangular block (planar rocking), else None."""
        return self.specimen_structure if is_block(self.specimen_structure) else None

    @property
    def specimen_gravity(self) -> float:
        """The specimen's gravity [m/s^2] (= varsigma g)."""
        return to_specimen(self.gravity, self.factors, "gravity")

    @property
    def specimen_charge_kg(self) -> float:
        """The specimen's TNT-equivalent charge [kg]."""
        return self.specimen.charge_kg

    @property
    def specimen_standoff_m(self) -> float:
        """The specimen's stand-off [m] (= lambda R)."""
        return self.specimen.standoff_m

    @property
    def pressure_ratio(self) -> float:
        """Delivered peak reflected pressure ratio P_model / P_prototype [-]."""
        return self.specimen.reflected_pressure / self.prototype.reflected_pressure

    @property
    def impulse_ratio(self) -> float:
        """Delivered reflected impulse ratio i_model / i_prototype [-] (= gamma sqrt(varsigma lambda^3))."""
        return self.specimen.reflected_impulse / self.prototype.reflected_impulse

    @property
    def duration_ratio(self) -> float:
        """Delivered positive-duration ratio t_o,model / t_o,prototype [-]."""
        return self.specimen.positive_duration / self.prototype.positive_duration

    def to_dict(self) -> dict:
        """Plain dict (the CLI's ``design --json`` object; its keys keep the paper's label
        ``model`` for the specimen: ``model_charge_kg``, ``model``)."""
        out = {
            "law": self.law,
            "blast_model": self.prototype.blast_model,
            "scale": self.scale,
            "density_ratio": self.density_ratio,
            "gravity_ratio": self.gravity_ratio,
            "prototype_charge_kg": self.prototype.charge_kg,
            "prototype_standoff_m": self.prototype.standoff_m,
            "prototype_scaled_distance": self.prototype.scaled_distance,
            "model_scaled_distance": self.specimen.scaled_distance,
            "scaled_distance_factor": self.scaled_distance_factor,
            "root": self.root_note,
            "model_charge_kg": self.specimen_charge_kg,
            "model_standoff_m": self.specimen_standoff_m,
            "pressure_ratio": self.pressure_ratio,
            "impulse_ratio": self.impulse_ratio,
            "duration_ratio": self.duration_ratio,
            "required_pressure_ratio": self.factors.pressure,
            "required_impulse_ratio": self.factors.impulse,
            "required_duration_ratio": self.factors.time,
            "factors": self.factors.to_dict(),
            "prototype": self.prototype.to_dict(),
            "model": self.specimen.to_dict(),
        }
        if self.impulsive is not None:
            out["impulsive"] = self.impulsive.to_dict()
        if self.effects is not None:
            out["blast_effects"] = self.effects
            out["load_model"] = self.effects["load_model"]
        else:
            out["load_model"] = {
                "prototype": load_model_record(self.prototype.blast_model, self.prototype.burst),
                "model": load_model_record(self.specimen.blast_model, self.specimen.burst),
            }
        if self.notes:
            out["notes"] = list(self.notes)
        return out
