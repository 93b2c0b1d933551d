"""Up-scaling: a specimen quantity in prototype units, ``x_prototype = x_specimen / factor``.

The one up-scaling rule of blastscale (paper, Sec. "Validation": "the model is up-scaled, i.e., all
quantities are multiplied by the inverse of the scaling factor"). The factor of a quantity is that
of its physical dimension (:class:`~blastscale.similitude.ScalingFactors`: length lambda, time
sqrt(lambda / varsigma), velocity sqrt(varsigma lambda), angle 1, momentum gamma sqrt(varsigma)
lambda^(7/2), ...); a summary key names its dimension by its unit suffix (:mod:`blastscale.units`).
Summaries are up-scaled by :func:`upscale_summary`, histories by
:func:`~blastscale.analysis.compare.upscale_dataset`; both divide by
:func:`~blastscale.similitude.factors.dimension_factor` (the one factor lookup).
"""

from __future__ import annotations

from ..similitude.factors import dimension_factor
from ..units import dimension_of

__all__ = ["upscale", "upscale_summary"]


def upscale(value, factors, dimension: str, name: str = "value"):
    """``value`` (specimen units) in prototype units: ``value / factor(dimension)``; None stays None.

    The inverse of :func:`~blastscale.similitude.factors.to_specimen` (``value * factor``) through the same
    table, :func:`~blastscale.similitude.factors.dimension_factor`."""
    if value is None:
        return None
    return value / dimension_factor(factors, dimension, name)


def upscale_summary(summary, factors):
    """A specimen's summary dict in prototype units: each number divided by the factor of the
    dimension its key's unit suffix names (``_m`` length, ``_s`` time, ``_m_s`` velocity, ``_rad``
    angle, ``_Ns`` momentum, ...: :func:`blastscale.units.dimension_of`); booleans, counts, None and
    keys without a unit are kept. Nested dicts (``points``) and lists (``[x, y, z]``) are handled
    recursively, a list taking its key's dimension.

    Parameters
    ----------
    summary : dict
        A specimen run's summary [specimen units].
    factors : ScalingFactors
        Specimen / prototype factors.

    Returns
    -------
    dict
    """

    def scale(key: str, value):
        if isinstance(value, dict):
            return {k: scale(k, v) for k, v in value.items()}
        if isinstance(value, (list, tuple)):
            return [scale(key, v) for v in value]
        if isinstance(value, bool) or value is None or not isinstance(value, (int, float)):
            return value
        dim = dimension_of(key)
        return value if dim is None else float(value) / dimension_factor(factors, dim, key)

    return {k: scale(k, v) for k, v in summary.items()}
