"""The specimen's capacity: a reduced-scale model's capacity curve, up-scaled to the prototype.

The rocking engine (:mod:`blastscale.rocking.capacity`) gives the critical charge W_c(R) of one body on
plain arrays; comparing prototype and model is the analysis' part: :func:`model_capacity_curve` builds the
specimen system once (:func:`blastscale.similitude.specimen.specimen_system`: lengths x lambda, density x
gamma, gravity x varsigma, the load model's face x lambda), searches its own critical charges at the
model stand-offs ``lambda R`` and up-scales each with the paper's general law: the prototype charge that
delivers, at the prototype stand-off, the model's reflected impulse over the impulse factor

.. math:: \\lambda_i = \\gamma \\sqrt{\\varsigma \\lambda^3}

(paper Eq. 8, Table 1), by the package's one inversion of the blast fits
(:func:`blastscale.blast.inverse.charge_for`).

References: paper Sec. "Similitude" (Eq. 8, Table 1); Hopkinson-Cranz scaling (Baker et al. 1983).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .._validate import check_positive
from ..blast.inverse import charge_for, scaled_distance_range
from ..blast.parameters import DEFAULT_BLAST_MODEL, blast_parameters
from ..rocking.capacity import CapacityCurve, capacity_curve, finite_or_none
from ..rocking.solver import RockingSolver
from ..rocking.system import as_rocking_system
from ..similitude.factors import scaling_factors, to_specimen
from ..similitude.specimen import specimen_system
from .upscale import upscale

__all__ = ["model_capacity_curve", "ModelCapacity"]


@dataclass(frozen=True)
class ModelCapacity:
    """Capacity curve of a reduced-scale model and its up-scaling to the prototype (SI).

    ``curve`` is the model's own W_c at the model stand-offs ``lambda R`` [m] (model charges
    [kg]); ``upscaled_charge_kg`` (n,) [kg] the prototype charges they correspond to under the
    paper's general law (equal impulse up to the factor ``gamma sqrt(varsigma lambda^3)``, Eq. 8),
    to be read against the prototype's W_c(R); ``scale``, ``density_ratio``, ``gravity_ratio``
    are lambda, gamma, varsigma [-].
    """

    curve: CapacityCurve
    upscaled_charge_kg: np.ndarray
    scale: float
    density_ratio: float
    gravity_ratio: float

    def to_dict(self) -> dict:
        """Plain dict (lists; None for NaN)."""
        d = self.curve.to_dict()
        return {
            "scale": self.scale,
            "density_ratio": self.density_ratio,
            "gravity_ratio": self.gravity_ratio,
            "standoff_m": d["standoff_m"],
            "critical_charge_kg": d["critical_charge_kg"],
            "upscaled_critical_charge_kg": finite_or_none(self.upscaled_charge_kg),
            "seconds_per_case": d["seconds_per_case"],
        }


def model_capacity_curve(
    body,
    standoffs,
    scale: float,
    density_ratio: float = 1.0,
    gravity_ratio: float = 1.0,
    *,
    pulse_shape: str = "friedlander",
    blast_model=DEFAULT_BLAST_MODEL,
    gravity: float | None = None,
    restitution: float | None = None,
    solver: RockingSolver | None = None,
    xtol_rel: float = 1e-9,
    extrapolate: bool = False,
    load_model=None,
) -> ModelCapacity:
    """Capacity curve of the reduced-scale model of ``body`` and its up-scaling to the prototype.

    The model is the prototype with lengths x ``scale`` (lambda), density x ``density_ratio``
    (gamma) and gravity x ``gravity_ratio`` (varsigma), same restitution, and the load model's face
    x lambda: the specimen system of :func:`blastscale.similitude.specimen.specimen_system` (the one place
    a specimen is scaled, as for a design: :meth:`RockingSystem.scaled`, :meth:`LoadModel.scaled`); its critical charges
    are searched at the stand-offs ``scale * standoffs`` [m] (as :func:`capacity_curve`) and each
    is up-scaled to the prototype charge that delivers, at the prototype stand-off, the model's
    reflected impulse divided by ``gamma sqrt(varsigma lambda^3)`` (paper Eq. 8, Table 1).
    In the impulsive limit the up-scaled curve equals the prototype's exactly; finite pulses
    depart from it by the effect of the pulse duration, which the law does not match.
    """

    lam = float(check_positive("scale", scale))
    gam = float(check_positive("density ratio", density_ratio))
    sig = float(check_positive("gravity ratio", gravity_ratio))
    R = np.atleast_1d(check_positive("standoffs", standoffs, "m")).astype(float)
    f = scaling_factors(lam, gam, sig)  # no charge, no lambda_Z: the specimen system needs lambda, gamma, varsigma
    spec = specimen_system(f, as_rocking_system(body, gravity, restitution), load_model)  # scaled once, there
    curve = capacity_curve(
        spec.structure,
        to_specimen(R, f, "length"),
        pulse_shape=pulse_shape,
        blast_model=blast_model,
        solver=solver,
        xtol_rel=xtol_rel,
        extrapolate=extrapolate,
        load_model=spec.load_model,
    )
    ok = np.isfinite(curve.critical_charge_kg)
    up = np.full(R.size, np.nan)
    if np.any(ok):
        im = blast_parameters(
            curve.critical_charge_kg[ok], to_specimen(R[ok], f, "length"), blast_model, extrapolate=extrapolate
        ).reflected_impulse
        up[ok] = charge_for(
            upscale(im, f, "impulse"),
            R[ok],
            "reflected_impulse",
            blast_model,
            extrapolate=extrapolate,
            z_range=scaled_distance_range(blast_model, extrapolate),
            outside="nan",
        )
    return ModelCapacity(curve, up, lam, gam, sig)
