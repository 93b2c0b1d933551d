"""Scaling-factor curves: the blast ratios a law delivers over a sweep of lambda or gamma.

For a prototype charge W at stand-off R, :func:`scaling_curves` evaluates, over arrays of the
geometric scale lambda and of the density ratio gamma (broadcast together), the
scaled-distance factor lambda_Z and the ratios model / prototype of the peak reflected
pressure, the reflected impulse and the positive duration, under the paper's general law
(Eq. 8) and under Hopkinson-Cranz. These are the data of the paper's Figure 5 (factors vs
lambda, gamma = 1) and Figure 8 (factors vs gamma, two lambdas, W = 50 kg).

Each point is the :func:`~blastscale.similitude.design_model` of that (lambda, gamma): the
same admissible range (:func:`~blastscale.similitude.admissible_scales` on the range where
every fit holds), the same root (:func:`~blastscale.similitude.solve_scaled_distance_factor`),
the same blast evaluation (:func:`~blastscale.blast.blast_parameters`, vectorised over the
valid points). A point where the law has no root inside that range is NaN in every general-law
array and False in ``valid``; the sweep itself never raises for it.

Pure numerics: no plotting imports (plots: :mod:`blastscale.plots.similitude`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .._validate import BlastscaleInputError, check_positive, check_positive_scalar
from ..blast.base import BlastModel
from ..blast.parameters import (
    DEFAULT_BLAST_MODEL,
    blast_parameters,
    get_blast_model,
    scaled_distance,
    valid_scaled_distance_range,
)
from .laws import admissible_scales, hopkinson_cranz_density_ratio, solve_scaled_distance_factor

__all__ = ["ScalingCurves", "scaling_curves"]


@dataclass(frozen=True)
class ScalingCurves:
    """Blast scaling factors over a sweep (model / prototype ratios; arrays of one shape).

    Attributes
    ----------
    charge, standoff : float
        Prototype charge W [kg TNT] and stand-off R [m].
    prototype_scaled_distance : float
        Z = R / W^(1/3) of the prototype [m/kg^(1/3)].
    blast_model : str
        Blast model used (``"kingery-bulmash"`` or ``"masi2021"``).
    gravity_ratio : float
        varsigma [-].
    z_range : (float, float)
        Range of model Z where every fit holds [m/kg^(1/3)] (defines ``valid``).
    scale, density_ratio : ndarray
        lambda and gamma of each point [-] (the inputs, broadcast).
    valid : ndarray of bool
        True where the general law has its root with the model's Z inside ``z_range``
        (the points :func:`~blastscale.similitude.design_model` accepts); False elsewhere,
        where every general-law array below is NaN.
    scaled_distance_factor : ndarray
        General law: lambda_Z = Z_model / Z_prototype [-] (paper Eq. 8); NaN where not ``valid``.
    model_scaled_distance : ndarray
        General law: Z of the model [m/kg^(1/3)]; NaN where not ``valid``.
    charge_ratio : ndarray
        General law: W_model / W [-] = (lambda / lambda_Z)^3; NaN where not ``valid``.
    pressure_ratio : ndarray
        General law: peak reflected pressure ratio P_ro,model / P_ro [-]; NaN where not ``valid``.
    impulse_ratio : ndarray
        General law: reflected impulse ratio i_ro,model / i_ro [-] (= gamma sqrt(varsigma lambda^3));
        NaN where not ``valid``.
    duration_ratio : ndarray
        General law: positive-duration ratio t_o,model / t_o [-]; NaN where not ``valid``.
    hc_scaled_distance_factor, hc_charge_ratio, hc_pressure_ratio, hc_impulse_ratio, hc_duration_ratio : ndarray
        Hopkinson-Cranz: lambda_Z = 1, W ratio lambda^3, pressure ratio 1, impulse and duration
        ratios lambda [-] (every point; independent of gamma).
    hc_density_ratio : ndarray
        The density ratio Hopkinson-Cranz imposes for rigid-body similarity, 1 / sqrt(varsigma lambda) [-].
    """

    charge: float
    standoff: float
    prototype_scaled_distance: float
    blast_model: str
    gravity_ratio: float
    z_range: tuple[float, float]
    scale: np.ndarray
    density_ratio: np.ndarray
    valid: np.ndarray
    scaled_distance_factor: np.ndarray
    model_scaled_distance: np.ndarray
    charge_ratio: np.ndarray
    pressure_ratio: np.ndarray
    impulse_ratio: np.ndarray
    duration_ratio: np.ndarray
    hc_scaled_distance_factor: np.ndarray
    hc_charge_ratio: np.ndarray
    hc_pressure_ratio: np.ndarray
    hc_impulse_ratio: np.ndarray
    hc_duration_ratio: np.ndarray
    hc_density_ratio: np.ndarray


def scaling_curves(
    charge: float,
    standoff: float,
    scale,
    density_ratio=1.0,
    gravity_ratio: float = 1.0,
    blast_model: "str | BlastModel" = DEFAULT_BLAST_MODEL,
) -> ScalingCurves:
    """Scaling factors of scaled distance, pressure, impulse and duration over a sweep.

    General law (paper Eq. 8): for each point, lambda_Z solves

    .. math:: \\frac{1}{\\lambda_Z}\\,\\frac{\\hat i(Z\\lambda_Z)}{\\hat i(Z)} = \\gamma\\sqrt{\\varsigma\\lambda},

    the model is W_m = W (lambda/lambda_Z)^3 at R_m = lambda R, and the ratios are
    P_ro(Z_m)/P_ro(Z), i_ro,m / i_ro and t_o,m / t_o from the blast model (paper Eq. 6).
    Hopkinson-Cranz: lambda_Z = 1, so the pressure ratio is 1 and the impulse and duration
    ratios are lambda (cube-root scaling).

    Parameters
    ----------
    charge : float
        Prototype TNT-equivalent charge W [kg], > 0.
    standoff : float
        Prototype stand-off R [m], > 0; Z = R / W^(1/3) must lie where every fit of ``blast_model``
        holds (kingery-bulmash [0.2, 40], masi2021 [0.2, 6.5] m/kg^(1/3)).
    scale : array_like
        Geometric scales lambda [-], > 0 (paper Fig. 5: a sweep; Fig. 8: one value).
    density_ratio : array_like
        Density ratios gamma [-], > 0, broadcast against ``scale`` (Fig. 5: 1; Fig. 8: a sweep).
    gravity_ratio : float
        varsigma [-], > 0.
    blast_model : str or BlastModel
        Blast model (``"kingery-bulmash"`` default, ``"masi2021"`` the paper's fits).

    Returns
    -------
    ScalingCurves
        Arrays of the broadcast shape of ``scale`` and ``density_ratio``; general-law arrays
        are NaN where ``valid`` is False (the law's root would put the model's Z outside the
        range where every fit holds: the sweep does not raise for such points).

    Raises
    ------
    BlastscaleInputError
        A non-positive or non-finite input, shapes that do not broadcast, or a gravity ratio
        that is not a single number (the message names the parameter, its value and the range).
    OutOfRangeError
        The *prototype's* Z outside the range where every fit holds (nothing to sweep).

    Notes
    -----
    Point by point identical to :func:`~blastscale.similitude.design_model` (same root, same
    blast evaluation). Valid range per point: that of ``design_model`` without extrapolation.
    References: paper Sec. "Scaling laws", Eqs. (6)-(8), Figs. 5 and 8; Hopkinson (1915),
    Cranz (1926) for lambda_Z = 1.

    Examples
    --------
    The text near Fig. 8: lambda = 1/200, masi2021, pressure ratio 5.8 % for gamma = 1 and
    0.19 % for gamma = 0.05:

    >>> c = scaling_curves(50.0, 2.0, 1 / 200, [1.0, 0.05], blast_model="masi2021")
    >>> [round(100 * float(p), 2) for p in c.pressure_ratio]
    [5.85, 0.19]
    """
    W = check_positive_scalar("charge", charge, "kg")
    R = check_positive_scalar("standoff", standoff, "m")
    sig = check_positive_scalar("gravity ratio", gravity_ratio)
    lam, gam = _broadcast(scale, density_ratio)
    bm = get_blast_model(blast_model)
    zr = valid_scaled_distance_range(bm)
    proto = blast_parameters(W, R, bm)  # raises for a prototype outside the fits
    z = proto.scaled_distance
    shape = lam.shape
    lam, gam = lam.ravel(), gam.ravel()  # work on 1-D; reshaped on return
    lz = _scaled_distance_factors(z, lam, gam, sig, bm, zr)
    return ScalingCurves(
        charge=W,
        standoff=R,
        prototype_scaled_distance=z,
        blast_model=bm.name,
        gravity_ratio=sig,
        z_range=zr,
        scale=lam.reshape(shape),
        density_ratio=gam.reshape(shape),
        **_general_law(W, R, lam, lz, proto, bm, zr, shape),
        **_hopkinson_cranz(lam, sig, shape),
    )


def _broadcast(scale, density_ratio) -> tuple[np.ndarray, np.ndarray]:
    """lambda and gamma [-], each checked > 0, broadcast together (float copies)."""
    lam_in = check_positive("scale", scale)
    gam_in = check_positive("density ratio", density_ratio)
    try:
        lam, gam = (np.array(a, dtype=float) for a in np.broadcast_arrays(lam_in, gam_in))
    except ValueError:
        raise BlastscaleInputError(
            f"scale and density ratio have shapes {lam_in.shape} and {gam_in.shape}, which do not broadcast together"
        ) from None
    return lam, gam


def _scaled_distance_factors(z: float, lam: np.ndarray, gam: np.ndarray, sig: float, bm, zr) -> np.ndarray:
    """The general law's lambda_Z [-] at each (lambda, gamma) of a flat sweep: NaN where lambda lies outside the
    admissible range of that gamma (design_model's own range check)."""
    lz = np.full(lam.size, np.nan)
    for k in range(lam.size):  # the root is scalar (Brent); the blast evaluation is vectorised
        lo, hi = admissible_scales(z, gam[k], sig, bm, zr)  # design_model's own range check
        if lo <= lam[k] <= hi:
            lz[k] = solve_scaled_distance_factor(z, lam[k], gam[k], sig, bm).factor
    return lz


def _general_law(W: float, R: float, lam: np.ndarray, lz: np.ndarray, proto, bm, zr, shape: tuple) -> dict:
    """The general law's fields of :class:`ScalingCurves` (``valid``, the factors and the model / prototype
    ratios) from the flat lambda and lambda_Z: the model W_m = W (lambda/lambda_Z)^3 at R_m = lambda R, kept
    where its Z lies inside the fits' range ``zr``; NaN elsewhere, in ``shape``."""
    ok = np.isfinite(lz)
    W_m = W * (lam[ok] / lz[ok]) ** 3  # as design_model: W * factors.charge at R * lambda
    R_m = R * lam[ok]
    z_m = scaled_distance(W_m, R_m) if W_m.size else W_m
    inside = (z_m >= zr[0]) & (z_m <= zr[1])  # round-off at the ends of the admissible range
    ok[ok] = inside
    model_params = blast_parameters(W_m[inside], R_m[inside], bm) if np.any(inside) else None

    def general(values) -> np.ndarray:
        """Values on the valid points, NaN elsewhere, in the input's shape."""
        out = np.full(lam.size, np.nan)
        out[ok] = values
        return out.reshape(shape)

    def ratio(field: str) -> np.ndarray:
        """Model / prototype ratio of a BlastParameters field."""
        return general(getattr(model_params, field) / getattr(proto, field) if model_params is not None else [])

    lz_ok = lz[ok]
    return dict(
        valid=ok.reshape(shape),
        scaled_distance_factor=general(lz_ok),
        model_scaled_distance=general(z_m[inside]),
        charge_ratio=general((lam[ok] / lz_ok) ** 3),
        pressure_ratio=ratio("reflected_pressure"),
        impulse_ratio=ratio("reflected_impulse"),
        duration_ratio=ratio("positive_duration"),
    )


def _hopkinson_cranz(lam: np.ndarray, sig: float, shape: tuple) -> dict:
    """Hopkinson-Cranz's fields of :class:`ScalingCurves`: lambda_Z = 1, so the pressure ratio is 1, the charge
    ratio lambda^3, the impulse and duration ratios lambda; and the density ratio the law needs."""
    return dict(
        hc_scaled_distance_factor=np.ones(shape),
        hc_charge_ratio=(lam**3).reshape(shape),
        hc_pressure_ratio=np.ones(shape),
        hc_impulse_ratio=lam.reshape(shape).copy(),
        hc_duration_ratio=lam.reshape(shape).copy(),
        hc_density_ratio=np.array([hopkinson_cranz_density_ratio(x, sig) for x in lam]).reshape(shape),
    )
