"""Is the specimen's material rigid enough? Its stresses and elastic deflection against the prototype's.

The rigid-body similitude (paper Sec. "Problem statement", Tables 1-2) reproduces the prototype's
*motion* in the specimen: lengths x lambda, times x sqrt(lambda / varsigma), angles x 1. It says
nothing of the material, which the rigid-body model assumes never yields nor deforms. In the same
scaled motion every force of the rigid bodies (inertia, weight, the contact and impact reactions)
scales as gamma varsigma lambda^3 and every area as lambda^2, so each *stress* they set up scales as

    lambda_sigma = gamma varsigma lambda            (the pressure factor of Tables 1-2)

while the material's strength f and modulus E do not scale at all. Three ratios then compare the
specimen with the prototype (index s: specimen, p: prototype; each 1 for the prototype's own
material at full scale, each above 1 where the specimen is the more loaded):

* bearing (contact) stress over strength, at the rocking pivot and the joints (force over the scaled
  contact area):

      r_b = (sigma_s / f_s) / (sigma_p / f_p) = lambda_sigma f_p / f_s;

* impact stress over strength: an elastic impact at the velocity v sets up the stress
  sigma = rho c v = v sqrt(rho E) (one-dimensional wave, c = sqrt(E / rho); Johnson 1972, ch. 1), and
  a line (Hertz) contact of force per length F' ~ gamma varsigma lambda^2 at an edge radius ~ lambda
  sigma_H = sqrt(F' E* / (pi R)) (Johnson 1985, Sec. 4.3): both scale as
  sqrt(gamma varsigma lambda E_s / E_p) (velocities x sqrt(varsigma lambda)), so

      r_i = sqrt(lambda_sigma E_s / E_p) f_p / f_s;

* elastic deflection over the rigid motion: a strain sigma / E over a length L deflects by
  sigma L / E, against a rigid displacement L theta with the same angle theta in both, so

      r_d = (sigma_s / E_s) / (sigma_p / E_p) = lambda_sigma E_p / E_s

  (the ratio of the two Cauchy numbers rho v^2 / E).

A specimen passes when all three are at most :data:`RIGIDITY_FACTOR` (2). The prototype is itself
assumed rigid (the paper's hypothesis), so the check asks only that the specimen be no less rigid
than the prototype beyond the scatter of the prototype's own material. Taking for the strength of
one stone a coefficient of variation of 0.3 (an assumption stated here, not a code value: the upper end
of the scatter between specimens of one source; the rock classes of Hoek 2007 span a factor 5, 50-250
MPa, across sources), a lognormal strength puts its 1 % fractile a factor exp(2.33 x 0.3) = 2.0 below
its median: a utilisation within 2 x the prototype's is one the prototype's own weakest blocks
reach. Above it the specimen yields or crushes at the pivots where the prototype stays rigid.

Lead in place of marble (Hopkinson-Cranz, lambda = 1 / gamma^2 = 1/17.8): lambda_sigma = 1 / gamma
= 0.237, r_b = 0.237 x 100 / 5.5 = 4.3 (the pivot's stress-to-strength 4.3 x the marble
prototype's), r_i = 4.2, r_d = 1.04: refused on strength. A granite specimen of a marble prototype
at any scale <= 1: r_b = 1.04 lambda x 100 / 150 <= 0.69: accepted.

References: Johnson, W. (1972), Impact Strength of Materials, Arnold, ch. 1 (rho c v); Johnson, K. L.
(1985), Contact Mechanics, Cambridge UP, Sec. 4.3 (line contact); Hoek, E. (2007), Practical Rock
Engineering (strength classes); the material values: :mod:`blastscale.structures.materials`.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass

from .._validate import check_positive_scalar

__all__ = ["RIGIDITY_FACTOR", "RigidityCheck", "rigidity_check"]

#: Largest ratio of the specimen's stress-to-strength (and elastic deflection to rigid motion) to the
#: prototype's that the check accepts [-]: the scatter of the prototype's own strength (module docstring).
RIGIDITY_FACTOR = 2.0


@dataclass(frozen=True)
class RigidityCheck:
    """The rigidity check of a specimen material against the prototype's (module docstring).

    Attributes
    ----------
    ok : bool
        Every ratio at most ``threshold``.
    reason : str
        One line: the worst ratio, its value and the threshold (why it fails, or that it passes).
    specimen, prototype : str
        The two materials' names.
    stress_factor : float
        lambda_sigma = gamma varsigma lambda [-].
    bearing_ratio, impact_ratio, deflection_ratio : float
        r_b, r_i, r_d [-].
    threshold : float
        The largest ratio accepted [-].
    """

    ok: bool
    reason: str
    specimen: str
    prototype: str
    stress_factor: float
    bearing_ratio: float
    impact_ratio: float
    deflection_ratio: float
    threshold: float

    def to_dict(self) -> dict:
        return asdict(self)


_WORDS = {
    "bearing_ratio": "stress-to-strength at the pivots and joints",
    "impact_ratio": "impact stress-to-strength",
    "deflection_ratio": "elastic deflection to rigid motion",
}


def rigidity_check(stress_factor: float, specimen, prototype, threshold: float = RIGIDITY_FACTOR) -> RigidityCheck:
    """Compare a specimen material's stresses and elastic deflection in the prototype's scaled motion
    with the prototype's (module docstring).

    Parameters
    ----------
    stress_factor : float
        lambda_sigma = gamma varsigma lambda [-] (a design's ``factors.pressure``).
    specimen, prototype : Material
        :class:`~blastscale.structures.materials.Material` of each (``compressive_strength_Pa`` and
        ``youngs_modulus_Pa`` are used).
    threshold : float
        Largest ratio accepted [-] (default :data:`RIGIDITY_FACTOR`).

    Returns
    -------
    RigidityCheck

    Examples
    --------
    >>> from blastscale.structures.materials import MATERIALS as M
    >>> r = rigidity_check(M["marble"].density / M["lead"].density, M["lead"], M["marble"])
    >>> r.ok, round(r.bearing_ratio, 2)
    (False, 4.31)
    >>> rigidity_check(0.05 * M["granite"].density / M["marble"].density, M["granite"], M["marble"]).ok
    True
    """
    ls = check_positive_scalar("stress factor", stress_factor)
    thr = check_positive_scalar("threshold", threshold)
    fs, fp = specimen.compressive_strength_Pa, prototype.compressive_strength_Pa
    es, ep = specimen.youngs_modulus_Pa, prototype.youngs_modulus_Pa
    ratios = {
        "bearing_ratio": ls * fp / fs,
        "impact_ratio": math.sqrt(ls * es / ep) * fp / fs,
        "deflection_ratio": ls * ep / es,
    }
    worst = max(ratios, key=ratios.get)
    ok = ratios[worst] <= thr
    pair = f"{specimen.name} in place of {prototype.name}"
    reason = (
        f"rigid: {pair}, worst {_WORDS[worst]} {ratios[worst]:.3g} x the prototype's <= {thr:g}"
        if ok
        else f"not rigid: {pair}: {_WORDS[worst]} {ratios[worst]:.3g} x the prototype's > {thr:g} (gamma varsigma "
        f"lambda = {ls:.3g}; strength {fs / 1e6:.3g} vs {fp / 1e6:.3g} MPa, modulus {es / 1e9:.3g} vs "
        f"{ep / 1e9:.3g} GPa)"
    )
    return RigidityCheck(ok, reason, specimen.name, prototype.name, ls, **ratios, threshold=thr)
