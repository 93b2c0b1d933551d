"""The blast model inverted within its valid range of scaled distance: the charge or stand-off
that delivers a reflected impulse.

The critical-load searches (:mod:`blastscale.rocking.critical`, :mod:`blastscale.rocking.capacity`)
work in ``u = ln x`` (x the charge [kg] or the stand-off [m]) within the blast model's valid range of
Z = R / W^(1/3) [m/kg^(1/3)] (widened 5x each way with ``extrapolate``), start from the load that
delivers the impulsive critical impulse (:func:`_invert_impulse`), and warn once when a result lies
outside the fits (:func:`_check_extrapolated`). :func:`charge_for_impulse` is the public inverse
(used to up-scale a model's critical charge to the prototype).

References: Hopkinson-Cranz scaling (Baker et al. 1983, Explosion Hazards and Evaluation); the
reflected impulse grows with the charge and falls with the distance at fixed charge; paper Eq. 8
(the general law matches the impulse only).
"""

from __future__ import annotations

import warnings

import numpy as np

from .._validate import check_positive
from ..blast.base import ExtrapolationWarning
from ..blast.parameters import DEFAULT_BLAST_MODEL, get_blast_model, valid_scaled_distance_range

__all__ = ["charge_for_impulse"]

# widening of the blast model's valid Z range with extrapolate=True (factor each side)
_EXTRAPOLATE_WIDENING = 5.0


def _model_name(blast_model) -> str:
    return blast_model if isinstance(blast_model, str) else getattr(blast_model, "name", str(blast_model))


def _z_range(blast_model, extrapolate: bool) -> tuple[float, float]:
    zlo, zhi = valid_scaled_distance_range(blast_model)
    if extrapolate:
        return zlo / _EXTRAPOLATE_WIDENING, zhi * _EXTRAPOLATE_WIDENING
    return zlo * (1.0 + 1e-12), zhi * (1.0 - 1e-12)


def _invert_impulse(target, blast_model, by_charge: bool, fixed, lo, hi, extrapolate: bool):
    """ln of the charge [kg] (``by_charge``, ``fixed`` the stand-offs [m]) or of the stand-off [m]
    (``fixed`` the charges [kg]) whose reflected impulse is ``target`` [Pa*s], by bisection on the
    blast model alone between ``lo`` and ``hi`` (ln x; the result is clipped to them). The
    reflected impulse grows with the charge and falls with the distance (Hopkinson-Cranz)."""
    bm = get_blast_model(blast_model)
    lo, hi = np.array(lo, dtype=float), np.array(hi, dtype=float)

    def impulse(u):
        W, R = (np.exp(u), fixed) if by_charge else (fixed, np.exp(u))
        w13 = np.cbrt(W)
        return bm.scaled_reflected_impulse(R / w13, extrapolate=extrapolate) * w13

    for _ in range(45):  # the ln-range is < 40 wide: 45 halvings leave < 1e-12
        mid = 0.5 * (lo + hi)
        more = impulse(mid) > target  # too much impulse: less load
        if by_charge:
            hi, lo = np.where(more, mid, hi), np.where(more, lo, mid)
        else:
            lo, hi = np.where(more, mid, lo), np.where(more, hi, mid)
    return 0.5 * (lo + hi)


def charge_for_impulse(impulse, standoff, blast_model=DEFAULT_BLAST_MODEL, *, extrapolate: bool = False, z_range=None):
    """TNT charge [kg] whose reflected impulse at ``standoff`` [m] is ``impulse`` [Pa*s] (arrays
    broadcast), inverting the blast model over its valid range of Z (NaN where out of it), or over
    ``z_range`` (Z_min, Z_max) [m/kg^(1/3)] when given.

    Used to up-scale a model's critical charge to the prototype: under the paper's general law
    only the impulse is matched (Eq. 8), so the prototype charge that corresponds to a model
    charge is the one delivering the model's impulse divided by the impulse factor
    ``gamma sqrt(varsigma lambda^3)``.
    """
    i, R = np.broadcast_arrays(check_positive("impulse", impulse, "Pa*s"), check_positive("standoff", standoff, "m"))
    i, R = i.astype(float).ravel(), R.astype(float).ravel()
    zlo, zhi = _z_range(blast_model, extrapolate) if z_range is None else (float(z_range[0]), float(z_range[1]))
    ulo, uhi = 3.0 * np.log(R / zhi), 3.0 * np.log(R / zlo)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ExtrapolationWarning)
        u = _invert_impulse(i, blast_model, True, R, ulo, uhi, extrapolate)
    W = np.where((u - ulo > 1e-9) & (uhi - u > 1e-9), np.exp(u), np.nan)
    return W.reshape(np.shape(np.broadcast_arrays(impulse, standoff)[0]))


def _check_extrapolated(blast_model, values_z, extrapolate):
    if extrapolate:
        zlo, zhi = valid_scaled_distance_range(blast_model)
        z = np.asarray(values_z)[np.isfinite(values_z)]
        if np.any((z < zlo) | (z > zhi)):
            warnings.warn(
                f"critical scenarios at Z outside the {_model_name(blast_model)} fits' range [{zlo:g}, {zhi:g}] m/kg^(1/3): "
                "extrapolated",
                ExtrapolationWarning,
                stacklevel=3,
            )
