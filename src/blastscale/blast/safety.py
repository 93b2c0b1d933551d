"""Safety distances of a surface burst: overpressure thresholds and DoD quantity-distance.

The free-field incident (side-on) overpressure of a hemispherical TNT surface burst is the
Kingery-Bulmash fit (Swisdak 1994, :mod:`.kingery_bulmash`) over its range, Z = 0.2-198.5
m/kg^(1/3). Beyond it (the 140 dB hearing limit of a gram of TNT lies there) the far-field law is
Kinney & Graham's (1985) free-air overpressure

.. math:: \\frac{P_{so}}{p_0} = \\frac{808\\,[1 + (Z/4.5)^2]}{\\sqrt{1 + (Z/0.048)^2}\\,
          \\sqrt{1 + (Z/0.32)^2}\\,\\sqrt{1 + (Z/1.35)^2}}

(p0 = 101.325 kPa, Z in m/kg^(1/3)) for the surface burst taken as a free-air burst of 1.8 W
(UFC 3-340-02 (2008), the surface-burst environment: the ground is not a perfect reflector and
the charge is amplified by 1.8 rather than 2). At
the joint Z_j = 198.5 m/kg^(1/3) that law gives 2.06 times the Kingery-Bulmash pressure (0.514 kPa
against 0.249 kPa: the last Kingery-Bulmash piece falls as Z^-1.41, Kinney-Graham's as ~Z^-1.1).
blastscale keeps Kinney-Graham's *decay* beyond the joint and anchors it to Kingery-Bulmash there,

.. math:: P(Z > Z_j) = P_{KB}(Z_j)\\, \\frac{P_{KG}(Z / 1.8^{1/3})}{P_{KG}(Z_j / 1.8^{1/3})},

so the curve is continuous (jump 0, :func:`far_field_joint` states the raw jump) and agrees with
the DoD quantity-distance tables, which follow Kingery-Bulmash (K328: 0.0655 psi). Distances in
this far field are less certain (Kinney-Graham unanchored would put the 200 Pa distance of 1 kg at
510 m instead of 248 m): they are marked as such.

A distance to a threshold is the *largest* distance at which the overpressure is still at or
above it (a bracketed root in ln Z, conservative where the fit's pieces do not join monotonically).

The DoD quantity-distance is ``D = K W^(1/3)`` with D in ft and W in lb (DoD 6055.09-M, Vol. 3):
K24 (~2.3 psi, public traffic route distance), K40 (~1.2 psi, inhabited building distance) and
K50 (~0.9 psi, inhabited building distance for large quantities), converted exactly (1 ft = 0.3048
m, 1 lb = 0.45359237 kg).

References
----------
.. [1] Kinney, G. F., Graham, K. J. (1985). *Explosive Shocks in Air*, 2nd ed., Springer, ch. 6.
.. [2] Swisdak, M. M. (1994). Simplified Kingery airblast calculations. 26th DoD Explosives Safety
       Seminar (DTIC ADA526744).
.. [3] DoD 6055.09-M (2008, admin. reissued 2010). *DoD Ammunition and Explosives Safety
       Standards*, Vol. 3 (quantity-distance, HD 1.1).
.. [4] Baker, W. E., Cox, P. A., Westine, P. S., Kulesz, J. J., Strehlow, R. A. (1983). *Explosion
       Hazards and Evaluation*, Elsevier, ch. 7 and 9 (human tolerance: eardrum rupture threshold
       5 psi (White 1968); glass breakage, 0.15 psi typical (Clancey 1972)).
.. [5] Directive 2003/10/EC (noise at work), Art. 3: exposure limit 140 dB(C) peak (200 Pa);
       OSHA 29 CFR 1910.95(b)(1): impulse noise should not exceed 140 dB peak.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

from .._validate import BlastscaleInputError, OutOfRangeError
from ..roots import scalar_root
from .kingery_bulmash import KingeryBulmash

__all__ = [
    "PSI",
    "FT_LB13",
    "SURFACE_BURST_FACTOR",
    "Threshold",
    "SAFETY_THRESHOLDS",
    "QD_K_FACTORS",
    "kinney_graham_overpressure",
    "surface_burst_overpressure",
    "far_field_joint",
    "overpressure_distance",
    "quantity_distance",
    "safety_distances",
]

#: One pound-force per square inch [Pa] (0.45359237 kg x 9.80665 m/s^2 / (0.0254 m)^2, exact).
PSI = 0.45359237 * 9.80665 / 0.0254**2

#: One ft/lb^(1/3) in m/kg^(1/3) (0.3048 m / (0.45359237 kg)^(1/3), exact): K-factors to SI.
FT_LB13 = 0.3048 / 0.45359237 ** (1.0 / 3.0)

#: A surface burst as a free-air burst of this many times its charge (UFC 3-340-02, surface burst).
SURFACE_BURST_FACTOR = 1.8

_P0 = 101325.0  # Kinney & Graham's sea-level ambient pressure [Pa]
_KB = KingeryBulmash()
_Z_LO, _Z_J = _KB.valid_range("incident_pressure")  # 0.2, 198.5 m/kg^(1/3)
_Z_MAX = 1.0e7  # far enough for any threshold above ~1e-3 Pa


@dataclass(frozen=True)
class Threshold:
    """An overpressure threshold: ``key`` names its value (``"6.9 kPa"``), ``pressure_Pa`` [Pa],
    what happens at it (``meaning``) and the ``source``."""

    key: str
    pressure_Pa: float
    meaning: str
    source: str


#: The default thresholds of the safety envelope, highest first.
SAFETY_THRESHOLDS: tuple[Threshold, ...] = (
    Threshold(
        "34.5 kPa", 5.0 * PSI, "threshold of eardrum rupture (5 psi)", "White (1968) via Baker et al. (1983) ch. 9"
    ),
    Threshold(
        "6.9 kPa",
        1.0 * PSI,
        "1 psi: injuries from flying glass, light structures damaged",
        "Glasstone & Dolan (1977) ch. 5; Baker et al. (1983) ch. 9",
    ),
    Threshold(
        "1.03 kPa",
        0.15 * PSI,
        "typical pressure for window glass breakage (0.15 psi)",
        "Clancey (1972) via Baker et al. (1983) ch. 7",
    ),
    Threshold(
        "200 Pa",
        200.0,
        "impulse-noise limit for hearing: 140 dB peak (20 uPa x 10^(140/20))",
        "Directive 2003/10/EC Art. 3; OSHA 29 CFR 1910.95(b)(1)",
    ),
)

#: DoD 6055.09-M quantity-distance factors [ft/lb^(1/3)] and what they protect (HD 1.1).
QD_K_FACTORS: dict[str, tuple[float, str]] = {
    "K24": (24.0, "public traffic route distance (~2.3 psi)"),
    "K40": (40.0, "inhabited building distance (~1.2 psi)"),
    "K50": (50.0, "inhabited building distance for large quantities (~0.9 psi)"),
}


def kinney_graham_overpressure(Z):
    """Kinney & Graham (1985) free-air incident overpressure [Pa] of a TNT charge at sea level.

    Parameters
    ----------
    Z : float or array_like
        Scaled distance R / W^(1/3) of the free-air burst [m/kg^(1/3)], > 0.

    Returns
    -------
    float or ndarray
        P_so [Pa] (module docstring equation, p0 = 101.325 kPa).
    """
    z = np.asarray(Z, dtype=float)
    p = (
        _P0
        * 808.0
        * (1.0 + (z / 4.5) ** 2)
        / np.sqrt((1.0 + (z / 0.048) ** 2) * (1.0 + (z / 0.32) ** 2) * (1.0 + (z / 1.35) ** 2))
    )
    return p if p.ndim else float(p)


def _kg_surface(z):
    return kinney_graham_overpressure(np.asarray(z, dtype=float) / SURFACE_BURST_FACTOR ** (1.0 / 3.0))


def far_field_joint() -> dict:
    """Where the far-field law takes over and its raw jump there: ``scaled_distance_m_per_kg13``
    Z_j, ``kingery_bulmash_Pa`` and ``kinney_graham_Pa`` (unanchored, surface burst as 1.8 W) at Z_j,
    their ratio ``raw_jump`` (Kinney-Graham / Kingery-Bulmash) and the ``jump`` of the curve used (0)."""
    pkb = float(_KB.incident_pressure(_Z_J))
    pkg = float(_kg_surface(_Z_J))
    return {
        "scaled_distance_m_per_kg13": _Z_J,
        "kingery_bulmash_Pa": pkb,
        "kinney_graham_Pa": pkg,
        "raw_jump": pkg / pkb,
        "jump": 0.0,
    }


def surface_burst_overpressure(Z):
    """Free-field incident overpressure [Pa] of a hemispherical TNT surface burst at Z [m/kg^(1/3)]:
    Kingery-Bulmash for 0.2 <= Z <= 198.5, Kinney-Graham's decay anchored at 198.5 beyond
    (module docstring). Z below 0.2 (inside the fireball's reach) is refused."""
    z = np.asarray(Z, dtype=float)
    if np.any(~np.isfinite(z)) or np.any(z < _Z_LO):
        bad = float(z[~(np.isfinite(z) & (z >= _Z_LO))].ravel()[0])
        raise OutOfRangeError(
            f"scaled distance Z = {bad:.6g} m/kg^(1/3) is out of range for the overpressure: "
            f"valid range is >= {_Z_LO:g} m/kg^(1/3)"
        )
    near = z <= _Z_J
    out = np.empty_like(z)
    if np.any(near):
        out[near] = _KB.incident_pressure(z[near])
    if np.any(~near):
        anchor = float(_KB.incident_pressure(_Z_J)) / float(_kg_surface(_Z_J))
        out[~near] = anchor * _kg_surface(z[~near])
    return out if out.ndim else float(out)


def overpressure_distance(tnt_kg: float, threshold_Pa: float) -> float:
    """The largest distance [m] at which a surface burst of ``tnt_kg`` still produces an incident
    overpressure of at least ``threshold_Pa`` [Pa].

    The root of ``P(Z) = threshold`` in ln Z (:func:`surface_burst_overpressure`), bracketed on a
    geometric grid of 4000 points between 0.2 and 1e7 m/kg^(1/3) from the far end (the last grid
    point at or above the threshold), then the package's root finder (:func:`blastscale.roots.scalar_root`,
    Illinois regula falsi) to double precision in ln Z; ``R = Z W^(1/3)``.

    Raises
    ------
    BlastscaleInputError
        A charge or threshold that is not finite and > 0, or a threshold above the fit's highest
        pressure (at Z = 0.2 m/kg^(1/3)).
    """
    W, thr = float(tnt_kg), float(threshold_Pa)
    if not (math.isfinite(W) and W > 0):
        raise BlastscaleInputError(f"charge = {tnt_kg!r} kg TNT is out of range: must be > 0 kg")
    if not (math.isfinite(thr) and thr > 0):
        raise BlastscaleInputError(f"threshold = {threshold_Pa!r} Pa is out of range: must be > 0 Pa")
    return _scaled_distance_to(thr) * W ** (1.0 / 3.0)


@functools.lru_cache(maxsize=256)
def _scaled_distance_to(thr: float) -> float:
    """The largest Z [m/kg^(1/3)] where the overpressure is at least ``thr`` [Pa] (cube-root scaling:
    one root per threshold, whatever the charge)."""
    top = float(surface_burst_overpressure(_Z_LO))
    if thr > top:
        raise BlastscaleInputError(
            f"threshold = {thr:.6g} Pa is out of range: valid range is <= {top:.6g} Pa "
            f"(the overpressure at Z = {_Z_LO:g} m/kg^(1/3))"
        )
    u = np.linspace(math.log(_Z_LO), math.log(_Z_MAX), 4000)
    p = surface_burst_overpressure(np.exp(u))
    k = int(np.flatnonzero(p >= thr)[-1])
    if k == u.size - 1:
        raise BlastscaleInputError(
            f"threshold = {thr:.6g} Pa is out of range: the overpressure stays above it "
            f"beyond Z = {_Z_MAX:g} m/kg^(1/3)"
        )
    f = lambda x: math.log(float(surface_burst_overpressure(math.exp(x)))) - math.log(thr)  # noqa: E731
    root = scalar_root(f, u[k], u[k + 1]) if p[k] > thr else u[k]
    return math.exp(root)


def quantity_distance(tnt_kg: float, k_factor: float) -> float:
    """DoD quantity-distance [m]: ``D = K W^(1/3)`` with D in ft, W in lb (DoD 6055.09-M Vol. 3),
    i.e. ``D = K x 0.3048 x (W_kg / 0.45359237)^(1/3)`` m for ``tnt_kg`` [kg] and K [ft/lb^(1/3)]."""
    W, K = float(tnt_kg), float(k_factor)
    if not (math.isfinite(W) and W > 0):
        raise BlastscaleInputError(f"charge = {tnt_kg!r} kg TNT is out of range: must be > 0 kg")
    if not (math.isfinite(K) and K > 0):
        raise BlastscaleInputError(f"K = {k_factor!r} ft/lb^(1/3) is out of range: must be > 0")
    return K * 0.3048 * (W / 0.45359237) ** (1.0 / 3.0)


def safety_distances(tnt_kg: float, thresholds=SAFETY_THRESHOLDS, k_factors=QD_K_FACTORS) -> dict:
    """Every safety distance of a surface burst of ``tnt_kg`` [kg TNT, pressure basis]: threshold
    key (``"6.9 kPa"``) or K-factor name (``"K40"``) -> distance [m]."""
    out = {t.key: overpressure_distance(tnt_kg, t.pressure_Pa) for t in thresholds}
    out.update({name: quantity_distance(tnt_kg, k) for name, (k, _) in k_factors.items()})
    return out


def far_field(tnt_kg: float, distance_m: float) -> bool:
    """Whether ``distance_m`` [m] from ``tnt_kg`` [kg TNT] lies beyond the Kingery-Bulmash range
    (the anchored Kinney-Graham far field, less certain)."""
    return float(distance_m) / float(tnt_kg) ** (1.0 / 3.0) > _Z_J
