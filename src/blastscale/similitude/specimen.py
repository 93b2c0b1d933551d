"""The specimen system: the one place where a prototype's structure, load model, contact settings and
simulated time become the specimen's (the reduced-scale physical model's).

:func:`specimen_system` scales each part it is given by the design's factors, once:

* the structure, of any kind (a block, column, wall, arch, portal, assembly, or a planar
  :class:`~blastscale.rocking.RockingSystem`): ``structure.scaled(factors)`` (lengths x lambda,
  density x gamma; a rocking system also carries its gravity, x varsigma);
* the load model (clearing on the loaded face, the negative phase): ``load_model.scaled(factors)`` (the
  specimen's face is lambda times the prototype's);
* the 3D contact settings: ``contact.scaled(factors)`` (times x lambda_t, lengths x lambda, the
  friction x lambda_mu: the specimen material's own, :mod:`blastscale.structures.materials`);
* the simulated time [s]: x lambda_t;
* gravity [m/s^2]: x varsigma.

:func:`~.design.design_model` calls it for the design it returns (``ModelDesign.specimen_*``); a
capacity curve, which sweeps stand-offs without a charge (:func:`blastscale.analysis.capacity.model_capacity_curve`),
and the 3D systems of a design made without its structure, contact or duration
(:meth:`blastscale.analysis.systems.Systems3D.of_design`), and a study of a design's specimen run alone
(:meth:`blastscale.study.Study.from_design`: its contact settings) call it too: no other code scales a
specimen.

References: paper Sec. "Problem statement" (the pi-terms, Tables 1-2) for the factors.
"""

from __future__ import annotations

from typing import Any, NamedTuple

from .factors import ScalingFactors, to_specimen

__all__ = ["SpecimenSystem", "specimen_system"]


class SpecimenSystem(NamedTuple):
    """The specimen's parts (each None where the prototype's was not given).

    Attributes
    ----------
    structure : structure or RockingSystem or None
        The specimen structure (``structure.scaled(factors)``).
    load_model : LoadModel or None
        The specimen's load model (its face lambda times the prototype's).
    contact : ContactSettings or None
        The specimen's 3D contact settings (times x lambda_t, lengths x lambda, friction x lambda_mu).
    duration : float or None
        The specimen's simulated time [s] (x lambda_t).
    gravity : float or None
        The specimen's gravity [m/s^2] (x varsigma).
    """

    structure: Any = None
    load_model: Any = None
    contact: Any = None
    duration: float | None = None
    gravity: float | None = None


def specimen_system(
    factors: ScalingFactors,
    structure=None,
    load_model=None,
    contact=None,
    duration: float | None = None,
    gravity: float | None = None,
) -> SpecimenSystem:
    """The specimen system of a prototype's parts, each scaled once by ``factors`` (module docstring).

    Parameters
    ----------
    factors : ScalingFactors
        Model / prototype factors (:func:`~.factors.scaling_factors` or a design's ``factors``): ``length``
        lambda, ``density`` gamma, ``gravity`` varsigma and ``time`` lambda_t [-] are used (lambda_Z is not).
    structure : structure or RockingSystem, optional
        The prototype structure (anything with ``scaled(factors)``).
    load_model : LoadModel, optional
        The prototype's load model.
    contact : ContactSettings, optional
        The prototype's 3D contact settings.
    duration : float, optional
        The prototype's simulated time [s].
    gravity : float, optional
        The prototype's gravity [m/s^2].

    Returns
    -------
    SpecimenSystem
    """
    return SpecimenSystem(
        structure=None if structure is None else structure.scaled(factors),
        load_model=None if load_model is None else load_model.scaled(factors),
        contact=None if contact is None else contact.scaled(factors),
        duration=None if duration is None else to_specimen(float(duration), factors, "time", "duration"),
        gravity=None if gravity is None else to_specimen(float(gravity), factors, "gravity"),
    )
