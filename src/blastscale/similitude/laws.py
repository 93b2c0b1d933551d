"""Blast scaling laws: the paper's general law (Eq. 8) and Hopkinson-Cranz.

General law
-----------
With the stand-off scaled geometrically (R_model = lambda R), the charge factor is
lambda_W = (lambda / lambda_Z)^3 and the reflected-impulse factor is
lambda_i = [i_hat(lambda_Z Z) / i_hat(Z)] lambda / lambda_Z (paper Eq. 6). Matching it to the
impulse factor the rigid-body response requires, gamma sqrt(varsigma lambda^3) (paper Eq. 7,
generalised to a gravity ratio varsigma), gives paper Eq. (8):

.. math:: \\text{find } \\lambda_Z:\\quad
          \\frac{1}{\\lambda_Z}\\,\\frac{\\hat i(Z\\lambda_Z)}{\\hat i(Z)} = \\gamma\\sqrt{\\varsigma\\lambda}.

In x = ln(lambda_Z) the residual g(x) = ln i_hat(Z e^x) - ln i_hat(Z) - x - ln(gamma sqrt(varsigma lambda))
has slope d ln i_hat / d ln Z - 1 < 0 wherever the scaled impulse decreases with Z (true for
both models over their ranges), so the root is unique on the fit's range; it is bracketed by that
range and found to double precision (regula falsi, Illinois), for one prototype Z or an array of them at once
(:func:`solve_scaled_distance_factors`: the Study's design and the sweeps' vectorised outcome mode
solve the law with the same code). For the paper's fit (ln i_hat quadratic in ln Z) Eq. (8) is
a quadratic in x with two roots: the physical one lies inside the fit's range and equals the
bracketed root; the other is absurd (lambda_Z ~ 1e12) and is reported only for the record.

Hopkinson-Cranz
---------------
lambda_Z = 1 (same scaled distance, same pressure), lambda_W = lambda^3, impulse factor lambda.
Under the impulsive hypothesis it satisfies the rigid-body similarity only when
gamma = 1 / sqrt(varsigma lambda) (= lambda^(-1/2) for equal gravity, paper Table 2).

References: paper Sec. "Scaling laws", Eqs. (6)-(8); Baker, Westine & Dodge (1991), ch. 5.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .._validate import BlastscaleInputError, OutOfRangeError, check_positive, check_positive_scalar
from ..blast.base import BlastModel
from ..blast.masi_fits import MASI2021_COEFFICIENTS, Masi2021
from ..blast.parameters import DEFAULT_BLAST_MODEL, get_blast_model
from ..roots import bracketed_root, root_of_bracket

__all__ = [
    "admissible_scales",
    "ScaledDistanceSolution",
    "solve_scaled_distance_factor",
    "solve_scaled_distance_factors",
    "masi2021_quadratic_roots",
    "hopkinson_cranz_density_ratio",
    "LAWS",
]

LAWS = ("general", "hopkinson-cranz")


@dataclass(frozen=True)
class ScaledDistanceSolution:
    """Root of the general law.

    Attributes
    ----------
    factor : float
        lambda_Z = Z_model / Z_prototype [-].
    residual : float
        g(ln lambda_Z) at the root (natural-log units) [-].
    note : str
        Which root was taken and why.
    other_roots : tuple[float, ...]
        Non-physical roots of the closed form, when the model has one (paper fit).
    """

    factor: float
    residual: float
    note: str
    other_roots: tuple[float, ...] = ()


def masi2021_quadratic_roots(prototype_scaled_distance: float, target: float) -> tuple[float, float]:
    """Both roots lambda_Z of Eq. (8) for the paper's impulse fit, in closed form.

    With ln i_hat = c0 + c1 L + c2 L^2 (L = ln Z, coefficients of paper Appendix A), Eq. (8) in
    x = ln lambda_Z reads

    .. math:: c_2 x^2 + (c_1 - 1 + 2 c_2 \\ln Z)\\,x - \\ln(\\gamma\\sqrt{\\varsigma\\lambda}) = 0.

    Parameters
    ----------
    prototype_scaled_distance : float
        Z of the prototype [m/kg^(1/3)], > 0 (the fit holds for Z in [0.2, 20]).
    target : float
        Required impulse ratio over the charge factor, gamma sqrt(varsigma lambda) [-], > 0.

    Returns
    -------
    (float, float)
        The two lambda_Z = e^x [-], physical one first (the root of smaller |x|; inside the fit's
        range); the other is ~1e12 (inf if it overflows).

    Raises
    ------
    BlastscaleInputError
        Non-positive input, or no real root.

    References: paper Eq. (8) and Appendix A.
    """
    _, c1, c2 = MASI2021_COEFFICIENTS["scaled_reflected_impulse"]
    L = math.log(check_positive_scalar("prototype scaled distance", prototype_scaled_distance, "m/kg^(1/3)"))
    a, b, c = c2, c1 - 1.0 + 2.0 * c2 * L, -math.log(check_positive_scalar("target impulse factor", target))
    disc = b * b - 4.0 * a * c
    if disc < 0.0:
        raise BlastscaleInputError(f"general law has no real root for Z = {prototype_scaled_distance:.6g}")
    sq = math.sqrt(disc)
    # numerically stable pair (no cancellation)
    q = -0.5 * (b + math.copysign(sq, b))
    x1, x2 = q / a, c / q
    xs = sorted((x1, x2), key=abs)
    return math.exp(xs[0]), math.exp(xs[1]) if xs[1] < 700 else math.inf


def admissible_scales(
    prototype_scaled_distance: float,
    density_ratio: float = 1.0,
    gravity_ratio: float = 1.0,
    blast_model: "str | BlastModel" = DEFAULT_BLAST_MODEL,
    z_range: tuple[float, float] | None = None,
    specimen_blast_model: "str | BlastModel | None" = None,
) -> tuple[float, float]:
    """Range of the scale lambda for which the general law puts the model's Z inside ``z_range``.

    Eq. (8) solved for lambda at a given model scaled distance Z_m:

    .. math:: \\lambda(Z_m) = \\frac{1}{\\varsigma}\\left[\\frac{Z}{\\gamma Z_m}\\,
              \\frac{\\hat i(Z_m)}{\\hat i(Z)}\\right]^2,

    decreasing in Z_m where the scaled impulse falls faster than 1/Z (the law's monotone range).

    Parameters
    ----------
    prototype_scaled_distance : float
        Z of the prototype [m/kg^(1/3)], inside the impulse fit's range.
    density_ratio, gravity_ratio : float
        gamma and varsigma [-], > 0.
    blast_model : str or BlastModel
        Blast model giving the scaled reflected impulse i_hat.
    z_range : (float, float), optional
        Allowed model Z [m/kg^(1/3)]; default the impulse fit's range. It is intersected with it.
    specimen_blast_model : str or BlastModel, optional
        The specimen's fit when it differs from the prototype's (another burst type); default the same.

    Returns
    -------
    (float, float)
        (lambda_min, lambda_max) [-]: lambda_min puts the model at the far end of ``z_range``.

    Reference: paper Eq. (8).
    """
    m = get_blast_model(blast_model)
    ms = m if specimen_blast_model is None else get_blast_model(specimen_blast_model)
    z = check_positive_scalar("prototype scaled distance", prototype_scaled_distance, "m/kg^(1/3)")
    gam = check_positive_scalar("density ratio", density_ratio)
    sig = check_positive_scalar("gravity ratio", gravity_ratio)
    lo, hi = ms.valid_range("scaled_reflected_impulse")
    if z_range is not None:
        lo, hi = max(lo, float(z_range[0])), min(hi, float(z_range[1]))
    i0 = m.scaled_reflected_impulse(z)

    def lam_at(zm: float) -> float:
        return ((z / zm) * ms.scaled_reflected_impulse(zm) / i0 / gam) ** 2 / sig

    return lam_at(hi), lam_at(lo)


def solve_scaled_distance_factor(
    prototype_scaled_distance: float,
    scale: float,
    density_ratio: float = 1.0,
    gravity_ratio: float = 1.0,
    blast_model: "str | BlastModel" = DEFAULT_BLAST_MODEL,
    specimen_blast_model: "str | BlastModel | None" = None,
) -> ScaledDistanceSolution:
    """Solve the general scaling law (paper Eq. 8) for the scaled-distance factor lambda_Z.

    Parameters
    ----------
    prototype_scaled_distance : float
        Z of the prototype [m/kg^(1/3)], inside the impulse fit's range.
    scale : float
        lambda [-].
    density_ratio : float
        gamma [-].
    gravity_ratio : float
        varsigma [-].
    blast_model : str or BlastModel
        Blast model providing the scaled reflected impulse i_hat(Z).
    specimen_blast_model : str or BlastModel, optional
        The specimen's fit when it differs (another burst type: Eq. 8 then reads
        ``i_hat_s(Z lambda_Z) / (lambda_Z i_hat_p(Z)) = gamma sqrt(varsigma lambda)``); default the same.

    Returns
    -------
    ScaledDistanceSolution
        lambda_Z with |residual| < 1e-12 and a note on the root taken.

    Raises
    ------
    OutOfRangeError
        If the prototype Z is outside the impulse fit's range, or if the model Z the law requires
        would be: the message then gives the range of ``scale`` that keeps it inside (for the given
        gamma and varsigma). The law is never solved on an extrapolated fit.

    Notes
    -----
    Valid range: the prototype and the model scaled distances both inside the range of the model's
    scaled reflected impulse (Kingery-Bulmash: Z in [0.06, 40]; masi2021: [0.2, 20] m/kg^(1/3)).
    Reference: paper Eq. (8) (Sec. "Scaling laws").
    """
    m = get_blast_model(blast_model)
    ms = m if specimen_blast_model is None else get_blast_model(specimen_blast_model)
    z = check_positive_scalar("prototype scaled distance", prototype_scaled_distance, "m/kg^(1/3)")
    lam = check_positive_scalar("scale", scale)
    gam = check_positive_scalar("density ratio", density_ratio)
    sig = check_positive_scalar("gravity ratio", gravity_ratio)
    target = gam * math.sqrt(sig * lam)
    zmin, zmax = ms.valid_range("scaled_reflected_impulse")
    lz_arr = solve_scaled_distance_factors(z, lam, gam, sig, m, ms)
    if not np.isfinite(lz_arr):
        # the residual decreases in lambda_Z: positive at Z_max means that even Z_max gives too much
        # impulse (scale too small for this gamma), negative at Z_min that even Z_min gives too little.
        lam_lo, lam_hi = admissible_scales(z, gam, sig, m, specimen_blast_model=ms)
        side = "Z_max" if _residual(m, z, math.log(zmax / z), target, ms=ms) > 0.0 else "Z_min"
        raise OutOfRangeError(
            f"scale = {lam:.6g} is out of range for the general law: with density ratio = {gam:.6g}, gravity ratio "
            f"= {sig:.6g} and prototype Z = {z:.6g} m/kg^(1/3), the model Z would lie beyond {side} of the "
            f"{m.name} impulse fit [{zmin:g}, {zmax:g}] m/kg^(1/3); valid range of scale is [{lam_lo:.6g}, {lam_hi:.6g}]"
        )
    x = math.log(float(lz_arr))
    res = _residual(m, z, x, target, ms=ms)
    lz = float(lz_arr)
    note = f"unique root of Eq. (8) on the {ms.name} impulse range Z in [{zmin:g}, {zmax:g}] (Illinois)"
    if ms is not m:
        note += f"; prototype {m.name}, specimen {ms.name}"
    others: tuple[float, ...] = ()
    if isinstance(m, Masi2021) and ms is m:
        phys, other = masi2021_quadratic_roots(z, target)
        others = (other,)
        note += (
            f"; closed-form quadratic roots lambda_Z = {phys:.10g} (taken, inside the fit's range) and "
            f"{other:.4g} (rejected: model Z = {other * z:.3g} m/kg^(1/3) is far outside it)"
        )
    return ScaledDistanceSolution(factor=lz, residual=res, note=note, other_roots=others)


def _residual(m, z, x, target, ln_i0=None, ms=None):
    """g(x) = ln i_hat_s(Z e^x) - ln i_hat(Z) - x - ln(target), the general law (Eq. 8) in x = ln lambda_Z:
    decreasing in x where the law is monotone (arrays broadcast; Z e^x clipped to the specimen's
    impulse fit ``ms``, default ``m``; ``ln_i0`` = ln i_hat(Z) of the prototype's fit ``m`` when known)."""
    ms = m if ms is None else ms
    zmin, zmax = ms.valid_range("scaled_reflected_impulse")
    zz = np.clip(z * np.exp(x), zmin, zmax)  # guard round-off at the bracket ends
    if ln_i0 is None:
        ln_i0 = np.log(m.scaled_reflected_impulse(z))
    return np.log(ms.scaled_reflected_impulse(zz)) - ln_i0 - x - np.log(target)


def solve_scaled_distance_factors(
    prototype_scaled_distance,
    scale: float,
    density_ratio: float = 1.0,
    gravity_ratio: float = 1.0,
    blast_model: "str | BlastModel" = DEFAULT_BLAST_MODEL,
    specimen_blast_model: "str | BlastModel | None" = None,
):
    """lambda_Z of the general law (paper Eq. 8) for every prototype Z of an array, at once.

    A bracketed root in x = ln lambda_Z on the impulse fit's range of the model Z (the residual
    decreases in x where the law is monotone, so a root is bracketed exactly when the residual
    changes sign between Z_min and Z_max), found by the package's root finder
    (:func:`blastscale.roots.bracketed_root`: the Illinois variant of regula falsi, Dowell & Jarratt 1971,
    BIT 11, 168-174, with a bisection safeguard) to the resolution of double precision (about ten
    evaluations of the fit).

    Parameters
    ----------
    prototype_scaled_distance : float or array_like
        Z of the prototype [m/kg^(1/3)], > 0 (inside the impulse fit's range for a root).
    scale, density_ratio, gravity_ratio : float
        lambda, gamma, varsigma [-], > 0.
    blast_model : str or BlastModel
        Blast model providing the scaled reflected impulse i_hat(Z).
    specimen_blast_model : str or BlastModel, optional
        The specimen's fit when it differs (another burst type); default the same.

    Returns
    -------
    float or ndarray
        lambda_Z [-] of the shape of ``prototype_scaled_distance``; NaN where no root lies in the
        impulse fit's range (the prototype Z itself outside it, or a model Z beyond Z_min or Z_max).

    Reference: paper Eq. (8) (Sec. "Scaling laws").
    """
    m = get_blast_model(blast_model)
    ms = m if specimen_blast_model is None else get_blast_model(specimen_blast_model)
    z = np.asarray(check_positive("prototype scaled distance", prototype_scaled_distance, "m/kg^(1/3)"), dtype=float)
    lam = check_positive_scalar("scale", scale)
    gam = check_positive_scalar("density ratio", density_ratio)
    sig = check_positive_scalar("gravity ratio", gravity_ratio)
    target = gam * math.sqrt(sig * lam)
    pmin, pmax = m.valid_range("scaled_reflected_impulse")
    zmin, zmax = ms.valid_range("scaled_reflected_impulse")
    inside = (z >= pmin) & (z <= pmax)
    zs = np.where(inside, z, 1.0 if pmin <= 1.0 <= pmax else pmin)  # a placeholder where Z itself is out
    ln_i0 = np.log(m.scaled_reflected_impulse(zs))

    def g(x):
        return _residual(m, zs, x, target, ln_i0, ms)

    a, b = np.log(zmin / zs), np.log(zmax / zs)  # g(a) >= 0 >= g(b) where a root is bracketed
    fa, fb = g(a), g(b)
    ok = inside & (fa >= 0.0) & (fb <= 0.0)
    x = np.zeros(z.size)
    idx = np.flatnonzero(ok)
    if idx.size:  # the package's root finder, on -g (increasing in x)
        zsf, lnf, af, bf, faf, fbf = (np.ravel(v)[idx] for v in (zs, ln_i0, a, b, fa, fb))

        def minus_g(j, u):
            return -_residual(m, zsf[j], u, target, lnf[j], ms)

        x[idx] = root_of_bracket(*bracketed_root(minus_g, af, bf, -faf, -fbf)[:4])
    lz = np.where(ok, np.exp(x.reshape(z.shape)), np.nan)
    return float(lz) if lz.ndim == 0 else lz


def hopkinson_cranz_density_ratio(scale: float, gravity_ratio: float = 1.0) -> float:
    """Density ratio that Hopkinson-Cranz scaling imposes on rigid-body similarity [-].

    .. math:: \\gamma = 1 / \\sqrt{\\varsigma\\lambda}

    from Eq. (8) with lambda_Z = 1. ``scale`` lambda [-] and ``gravity_ratio`` varsigma [-], both > 0.
    Reference: paper Table 2 (varsigma = 1).
    """
    lam = check_positive_scalar("scale", scale)
    sig = check_positive_scalar("gravity ratio", gravity_ratio)
    return 1.0 / math.sqrt(sig * lam)
