"""Pi-terms and scaling factors of the rigid-body response (paper Sec. "Problem statement").

A scaling factor is ``lambda_f = f_model / f_prototype``. With the geometric scale
``lambda = l_model / l_prototype``, the density ratio ``gamma = rho_model / rho_prototype``
and the gravity ratio ``varsigma = g_model / g_prototype``, similarity of the pi-terms

.. math::

    \\pi_{02} = x/l,\\ \\pi_{03} = \\theta,\\ \\pi_{11} = \\ddot\\theta\\, l/g,\\
    \\pi_{12} = \\dot\\theta\\sqrt{l/g},\\ \\pi_{13} = \\ddot x/g,\\ \\pi_{14} = \\dot x/\\sqrt{l g},\\
    \\pi_{15} = t\\sqrt{g/l},\\ \\pi_{21} = \\mu,\\ \\pi_{22} = J/(m l^2),\\
    \\pi_{23} = \\mathcal{P} l^2/(m g),\\ \\pi_{24} = (\\mathcal{I}/m)\\sqrt{l^3/g}

gives every factor (paper Tables 1 and 2 for varsigma = 1).

Two slips of the paper are corrected here (see ``docs/paper_slips.md``): Tables 1 and 2 swap
the linear and angular acceleration factors (from pi_13 and pi_11 they are varsigma and
varsigma/lambda, i.e. 1 and 1/lambda for equal gravity, not 1/lambda and 1), and the text
gives ``lambda_t = sqrt(varsigma lambda)`` where pi_15 gives ``sqrt(lambda / varsigma)``
(identical for varsigma = 1).
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass

from .._validate import BlastscaleInputError, check_finite, check_positive_scalar, check_range

__all__ = [
    "ScalingFactors",
    "scaling_factors",
    "pi_terms",
    "FACTOR_UNITS",
    "DIMENSIONLESS",
    "dimension_factor",
    "to_specimen",
]

#: What each factor scales (prototype unit), for tables and metadata.
FACTOR_UNITS = {
    "length": "m",
    "density": "kg/m^3",
    "gravity": "m/s^2",
    "displacement": "m",
    "velocity": "m/s",
    "acceleration": "m/s^2",
    "angle": "rad",
    "angular_velocity": "rad/s",
    "angular_acceleration": "rad/s^2",
    "time": "s",
    "mass": "kg",
    "inertia": "kg m^2",
    "force": "N",
    "pressure": "Pa",
    "impulse": "Pa s",
    "momentum": "N s",
    "energy": "J",
    "friction": "-",
    "scaled_distance": "m/kg^(1/3)",
    "charge": "kg",
}


@dataclass(frozen=True)
class ScalingFactors:
    """Model-to-prototype factors ``f_model / f_prototype`` of every quantity [-].

    Attributes (paper Tables 1-2, generalised to a gravity ratio varsigma):

    ============================  =================================
    length, displacement          lambda
    density                       gamma
    gravity                       varsigma
    velocity (linear)             sqrt(varsigma lambda)
    acceleration (linear)         varsigma
    angle                         1
    angular_velocity              sqrt(varsigma / lambda)
    angular_acceleration          varsigma / lambda
    time                          sqrt(lambda / varsigma)
    mass                          gamma lambda^3
    inertia                       gamma lambda^5
    force                         gamma varsigma lambda^3
    pressure (specific thrust)    gamma varsigma lambda
    impulse (specific, Pa s)      gamma sqrt(varsigma lambda^3)
    momentum (N s)                gamma sqrt(varsigma) lambda^(7/2)
    energy                        gamma varsigma lambda^4
    friction                      lambda_mu (1 for the prototype's own material)
    scaled_distance               lambda_Z (None until a blast law fixes it)
    charge                        (lambda / lambda_Z)^3 (None likewise)
    ============================  =================================

    ``pressure`` and ``time`` are the factors the rigid-body response *requires*; the blast
    delivers its own ratios (see :class:`~blastscale.similitude.experiment.ModelDesign`), and only
    the impulse can be matched (impulsive hypothesis, paper Eq. 8).
    """

    length: float
    density: float
    gravity: float
    displacement: float
    velocity: float
    acceleration: float
    angle: float
    angular_velocity: float
    angular_acceleration: float
    time: float
    mass: float
    inertia: float
    force: float
    pressure: float
    impulse: float
    momentum: float
    energy: float
    friction: float
    scaled_distance: float | None = None
    charge: float | None = None

    def to_dict(self) -> dict[str, float | None]:
        """Factors by name (model / prototype)."""
        return asdict(self)


def scaling_factors(
    scale: float,
    density_ratio: float = 1.0,
    gravity_ratio: float = 1.0,
    scaled_distance_factor: float | None = None,
    friction_ratio: float = 1.0,
) -> ScalingFactors:
    """Every scaling factor of the rigid-body response (paper Tables 1-2).

    Parameters
    ----------
    scale : float
        Geometric scale lambda = l_model / l_prototype [-], > 0.
    density_ratio : float
        gamma = rho_model / rho_prototype [-], > 0.
    gravity_ratio : float
        varsigma = g_model / g_prototype [-], > 0 (1 unless the model runs in a centrifuge).
    scaled_distance_factor : float, optional
        lambda_Z = Z_model / Z_prototype, when a blast law has fixed it; then the charge
        factor (lambda / lambda_Z)^3 is filled in too.
    friction_ratio : float
        lambda_mu = mu_model / mu_prototype [-], > 0: 1 for rigid-body similitude (pi_21 = mu); a
        specimen of another material has its own joint friction (:mod:`blastscale.structures.materials`,
        checked by :mod:`.friction`), and its 3D contacts carry the prototype's mu x lambda_mu.

    Returns
    -------
    ScalingFactors
    """
    lam = check_positive_scalar("scale", scale)
    gam = check_positive_scalar("density ratio", density_ratio)
    sig = check_positive_scalar("gravity ratio", gravity_ratio)
    fr = check_positive_scalar("friction ratio", friction_ratio)
    lz = (
        None
        if scaled_distance_factor is None
        else check_positive_scalar("scaled distance factor", scaled_distance_factor)
    )
    return ScalingFactors(
        length=lam,
        density=gam,
        gravity=sig,
        displacement=lam,
        velocity=math.sqrt(sig * lam),
        acceleration=sig,
        angle=1.0,
        angular_velocity=math.sqrt(sig / lam),
        angular_acceleration=sig / lam,
        time=math.sqrt(lam / sig),
        mass=gam * lam**3,
        inertia=gam * lam**5,
        force=gam * sig * lam**3,
        pressure=gam * sig * lam,
        impulse=gam * math.sqrt(sig * lam**3),
        momentum=gam * math.sqrt(sig) * lam**3.5,
        energy=gam * sig * lam**4,
        friction=fr,
        scaled_distance=lz,
        charge=None if lz is None else (lam / lz) ** 3,
    )


def pi_terms(
    length: float,
    gravity: float,
    mass: float,
    inertia: float,
    pressure: float,
    impulse: float,
    friction: float = 0.0,
    *,
    time: float = 0.0,
    displacement: float = 0.0,
    velocity: float = 0.0,
    acceleration: float = 0.0,
    angle: float = 0.0,
    angular_velocity: float = 0.0,
    angular_acceleration: float = 0.0,
) -> dict[str, float]:
    """The dimensionless groups of the rigid-body response (paper Eq. 5).

    Parameters
    ----------
    length : float
        Characteristic length l [m] (e.g. the structure's height).
    gravity : float
        g [m/s^2].
    mass : float
        m [kg].
    inertia : float
        Characteristic mass moment of inertia J [kg m^2].
    pressure : float
        Maximum specific thrust (peak pressure) P [Pa].
    impulse : float
        Maximum specific impulse I [Pa s].
    friction : float
        Coulomb friction coefficient mu [-].
    time, displacement, velocity, acceleration, angle, angular_velocity, angular_acceleration
        Response quantities t [s], x [m], x' [m/s], x'' [m/s^2], theta [rad], theta' [rad/s],
        theta'' [rad/s^2] at which the kinematic groups are evaluated.

    Returns
    -------
    dict
        ``pi_02 .. pi_24`` by the paper's names.
    """
    l = check_positive_scalar("length", length, "m")
    g = check_positive_scalar("gravity", gravity, "m/s^2")
    m = check_positive_scalar("mass", mass, "kg")
    check_positive_scalar("inertia", inertia, "kg m^2")
    for name, value, unit in (("pressure", pressure, "Pa"), ("impulse", impulse, "Pa s"), ("friction", friction, "")):
        check_range(name, value, 0.0, unit=unit)
    for name, value in (
        ("time", time),
        ("displacement", displacement),
        ("velocity", velocity),
        ("acceleration", acceleration),
        ("angle", angle),
        ("angular velocity", angular_velocity),
        ("angular acceleration", angular_acceleration),
    ):
        check_finite(name, value)
    return {
        "pi_02": displacement / l,
        "pi_03": angle,
        "pi_11": angular_acceleration * l / g,
        "pi_12": angular_velocity * math.sqrt(l / g),
        "pi_13": acceleration / g,
        "pi_14": velocity / math.sqrt(l * g),
        "pi_15": time * math.sqrt(g / l),
        "pi_21": friction,
        "pi_22": inertia / (m * l**2),
        "pi_23": pressure * l**2 / (m * g),
        "pi_24": impulse / m * math.sqrt(l**3 / g),
    }


#: Dimensions that no scaling factor changes.
DIMENSIONLESS = ("dimensionless", "count")


def dimension_factor(factors, dimension: str, name: str = "variable") -> float:
    """The specimen / prototype factor [-] of a physical ``dimension``: 1 for dimensionless and
    count, else the :class:`ScalingFactors` field of that name (``name`` labels the error).

    The one factor lookup of both directions: prototype -> specimen (:func:`to_specimen`, ``x * factor``) and
    specimen -> prototype (:func:`blastscale.analysis.upscale.upscale`, ``x / factor``; summaries:
    :func:`blastscale.analysis.upscale.upscale_summary`; histories:
    :func:`blastscale.analysis.compare.upscale_dataset`)."""
    if dimension in DIMENSIONLESS:
        return 1.0
    value = getattr(factors, dimension, None) if isinstance(dimension, str) else None
    if value is None:
        raise BlastscaleInputError(
            f"dimension of {name!r} = {dimension!r} has no scaling factor: valid values are "
            f"{', '.join(DIMENSIONLESS)} or a ScalingFactors field (length, velocity, angle, angular_velocity, "
            "time, momentum, force, mass, ...)"
        )
    return float(value)


def to_specimen(value, factors, dimension: str, name: str = "value"):
    """``value`` (prototype units) in specimen units: ``value * factor(dimension)``; None stays None.

    The one down-scaling rule, the inverse of :func:`blastscale.analysis.upscale.upscale` (``value /
    factor``) through the same table, :func:`dimension_factor`: a prototype length x lambda, a time x
    sqrt(lambda / varsigma), a mass x gamma lambda^3, ... (:class:`ScalingFactors`).

    Parameters
    ----------
    value : float or array_like or None
        A prototype quantity [SI] (a float or a numpy array).
    factors : ScalingFactors
        Specimen / prototype factors.
    dimension : str
        Its physical dimension: a :class:`ScalingFactors` field (``"length"``, ``"time"``, ``"mass"``,
        ``"impulse"``, ...) or one of :data:`DIMENSIONLESS`.
    name : str
        The quantity's name, for the error message.

    Returns
    -------
    float or ndarray or None
        ``value * dimension_factor(factors, dimension)`` [SI, specimen].

    Raises
    ------
    BlastscaleInputError
        ``dimension`` is not a factor's name, or its factor is not known (``charge`` before a blast law).

    Examples
    --------
    >>> f = scaling_factors(0.25)
    >>> to_specimen(2.0, f, "length"), to_specimen(2.0, f, "time"), to_specimen(None, f, "mass")
    (0.5, 1.0, None)
    """
    if value is None:
        return None
    return value * dimension_factor(factors, dimension, name)
