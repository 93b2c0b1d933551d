"""Similitude: pi-terms, scaling factors, the general law and Hopkinson-Cranz, model design,
sweeps of the factors over the scale or the density ratio (the paper's Figures 5 and 8), and the checks of a
specimen's material: its rigidity (:mod:`.rigidity`) and its friction regime (:mod:`.friction`)."""

from .curves import ScalingCurves, scaling_curves
from .design import design_model
from .experiment import DEFAULT_IMPULSIVE_THRESHOLD, ImpulsiveCheck, ModelDesign, impulsive_check
from .factors import FACTOR_UNITS, ScalingFactors, pi_terms, scaling_factors
from .friction import FrictionCheck, friction_check, sliding_thresholds
from .laws import (
    LAWS,
    ScaledDistanceSolution,
    admissible_scales,
    hopkinson_cranz_density_ratio,
    masi2021_quadratic_roots,
    solve_scaled_distance_factor,
)
from .rigidity import RIGIDITY_FACTOR, RigidityCheck, rigidity_check

__all__ = [
    "admissible_scales",
    "DEFAULT_IMPULSIVE_THRESHOLD",
    "FACTOR_UNITS",
    "FrictionCheck",
    "ImpulsiveCheck",
    "LAWS",
    "ModelDesign",
    "RIGIDITY_FACTOR",
    "RigidityCheck",
    "ScaledDistanceSolution",
    "ScalingCurves",
    "ScalingFactors",
    "design_model",
    "friction_check",
    "hopkinson_cranz_density_ratio",
    "impulsive_check",
    "masi2021_quadratic_roots",
    "pi_terms",
    "rigidity_check",
    "scaling_curves",
    "scaling_factors",
    "sliding_thresholds",
    "solve_scaled_distance_factor",
]
