"""Similitude: pi-terms, scaling factors, the general law and Hopkinson-Cranz, model design,
and sweeps of the factors over the scale or the density ratio (the paper's Figures 5 and 8)."""

from .curves import ScalingCurves, scaling_curves
from .design import design_model
from .experiment import DEFAULT_IMPULSIVE_THRESHOLD, ImpulsiveCheck, ModelDesign, impulsive_check
from .factors import FACTOR_UNITS, ScalingFactors, pi_terms, scaling_factors
from .laws import (
    LAWS,
    ScaledDistanceSolution,
    admissible_scales,
    hopkinson_cranz_density_ratio,
    masi2021_quadratic_roots,
    solve_scaled_distance_factor,
)

__all__ = [
    "admissible_scales",
    "DEFAULT_IMPULSIVE_THRESHOLD",
    "FACTOR_UNITS",
    "ImpulsiveCheck",
    "LAWS",
    "ModelDesign",
    "ScaledDistanceSolution",
    "ScalingCurves",
    "ScalingFactors",
    "design_model",
    "hopkinson_cranz_density_ratio",
    "impulsive_check",
    "masi2021_quadratic_roots",
    "pi_terms",
    "scaling_curves",
    "scaling_factors",
    "solve_scaled_distance_factor",
]
