"""The one table from a key's unit suffix to its unit and physical dimension.

Every result key of blastscale ends with its unit (``charge_kg``, ``max_rotation_rad``,
``peak_velocity_x_m_s``, ``reflected_impulse_Pa_s``, ``delivered_impulse_Ns``); keys without one
are dimensionless ratios, counts or flags. Summaries, the report, the NetCDF histories and the
sweep stores all read units here, and the up-scaling of a summary reads the dimension (the
:class:`~blastscale.similitude.ScalingFactors` field that converts it between specimen and
prototype).

>>> unit_of("peak_velocity_x_m_s"), unit_of("reflected_impulse_Pa_s"), unit_of("n_impacts")
('m/s', 'Pa s', '1')
>>> dimension_of("delivered_impulse_Ns"), dimension_of("outcomes_agree")
('momentum', None)
>>> unit_of("scaled_distance_m_per_kg13")
'm/kg^(1/3)'
"""

from __future__ import annotations

from typing import NamedTuple, Optional

__all__ = ["Suffix", "SUFFIXES", "DIMENSIONLESS_UNIT", "unit_of", "dimension_of", "split_unit", "format_size"]


class Suffix(NamedTuple):
    """A key suffix, its unit (UDUNITS / CF spelling) and the physical dimension it measures."""

    suffix: str
    unit: str
    dimension: str


#: Unit suffixes, longest first (``_m_s`` before ``_s``, ``_Pa_s`` before ``_Pa`` and ``_s``).
SUFFIXES: tuple[Suffix, ...] = (
    Suffix("_rel_peak", "1", "dimensionless"),  # a difference as a fraction of the prototype's peak
    Suffix("_m_per_kg13", "m/kg^(1/3)", "scaled_distance"),  # Hopkinson-Cranz scaled distance Z = R / W^(1/3)
    Suffix("_kg_m3", "kg/m^3", "density"),
    Suffix("_kg_m2", "kg m^2", "inertia"),
    Suffix("_rad_s2", "rad/s^2", "angular_acceleration"),
    Suffix("_m_s2", "m/s^2", "acceleration"),
    Suffix("_rad_s", "rad/s", "angular_velocity"),
    Suffix("_m_s", "m/s", "velocity"),
    Suffix("_Pa_s", "Pa s", "impulse"),
    Suffix("_N_s", "N s", "momentum"),
    Suffix("_Ns", "N s", "momentum"),
    Suffix("_Pa", "Pa", "pressure"),
    Suffix("_rad", "rad", "angle"),
    Suffix("_deg", "deg", "angle"),
    Suffix("_kg", "kg", "mass"),
    Suffix("_J", "J", "energy"),
    Suffix("_N", "N", "force"),
    Suffix("_Hz", "Hz", "frequency"),
    Suffix("_m", "m", "length"),
    Suffix("_s", "s", "time"),
)

#: The unit of a dimensionless quantity (CF conventions: "1").
DIMENSIONLESS_UNIT = "1"


def _match(key: str) -> Optional[Suffix]:
    for s in SUFFIXES:
        if key.endswith(s.suffix) and len(key) > len(s.suffix):
            return s
    return None


def unit_of(key: str) -> str:
    """The unit of a result or scenario key, from its suffix; ``"1"`` when it has none."""
    s = _match(str(key).split(".")[-1])
    return DIMENSIONLESS_UNIT if s is None else s.unit


def dimension_of(key: str) -> Optional[str]:
    """The physical dimension of a key (a ScalingFactors field name), None when dimensionless."""
    s = _match(str(key).split(".")[-1])
    return None if s is None or s.dimension == "dimensionless" else s.dimension


def split_unit(key: str) -> tuple[str, str]:
    """(words, unit) of a key: ``"max_rotation_rad"`` -> (``"max rotation"``, ``"rad"``); the unit
    is ``""`` when the key has none."""
    s = _match(key)
    if s is None:
        return key.replace("_", " "), ""
    return key[: -len(s.suffix)].replace("_", " "), s.unit


def format_size(n: float) -> str:
    """Bytes in words: ``1.3 MB`` (decimal units, like ``ls -lh --si``)."""
    for unit in ("B", "kB", "MB", "GB", "TB"):
        if abs(n) < 1000 or unit == "TB":
            return f"{n:.0f} {unit}" if unit == "B" else f"{n:.3g} {unit}"
        n /= 1000.0
