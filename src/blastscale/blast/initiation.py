"""What a lab can really fire: the smallest charge of each explosive that detonates reliably, and the
initiators that start it.

**Minimum reliable charge.** A detonation fails in a charge thinner than the explosive's *critical
(failure) diameter* d_c: the lateral rarefactions quench the reaction zone (Cooper 1996, ch. 17;
Gibbs & Popolato 1980). The blast fits are for a hemisphere on the floor initiated at its centre;
its detonation diverges from a point, which needs more than the steady critical diameter, so
blastscale takes the smallest reliable charge as the hemisphere whose *radius* is d_c (its
diameter twice the critical one):

.. math:: m_{min} = \\frac{2\\pi}{3}\\,\\rho\\,d_c^3

with ρ the explosive's density [kg/m^3] (UFC 3-340-02 Table 2-1, or the entry's own). d_c is the
upper end of the published range for the lab form of the explosive (pressed, cast or plastic), so
the bound errs on the side of a charge that fires. It is a planning bound, not a guarantee: a lab
that has fired smaller charges of its own explosive states it (``[lab] charge_min_kg``, or
``min_charge_kg`` of a ``[lab.explosives.NAME]`` table).

**Initiators.** An exploding-bridgewire (EBW) detonator starts a secondary explosive without a
primary one; its output pellet is itself a small charge whose blast adds to the specimen's
(:func:`blastscale.blast.explosives.charge_equivalence`). :data:`INITIATORS` lists the contents of
real ones with their makers' figures.

References
----------
.. [1] Gibbs, T. R. & Popolato, A. (eds.) (1980). *LASL Explosive Property Data*. University of
       California Press (failure diameters of pressed, cast and plastic-bonded explosives).
.. [2] Cooper, P. W. (1996). *Explosives Engineering*. Wiley-VCH, ch. 17 ("Detonation: critical
       diameter and failure").
.. [3] The Russian-language table of critical diameters of detonation (ru.wikipedia.org, article
       "Критический диаметр детонации"): pressed PETN 0.7-0.86 mm at 1.0 g/cm^3, RDX 2.5-4.4 mm,
       tetryl 5-7 mm; its primary source was not checked here.
.. [4] Teledyne RISI, *RP-80 EBW detonator* data sheet: initiating pellet 80 mg PETN, output pellet
       123 mg RDX, aluminium cup.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

__all__ = [
    "CRITICAL_DIAMETERS_M",
    "CriticalDiameter",
    "min_reliable_charge",
    "Initiator",
    "INITIATORS",
    "DEFAULT_INITIATOR",
]


@dataclass(frozen=True)
class CriticalDiameter:
    """A critical (failure) diameter [m] of an explosive in its lab form, with its source."""

    diameter_m: float
    form: str
    source: str


_LASL = "Gibbs & Popolato 1980 (LASL Explosive Property Data); Cooper 1996 ch. 17"
_RU = "the Russian-language table of critical diameters, ru.wikipedia 'critical diameter of detonation'"
_NITRAMINE = CriticalDiameter(
    4.4e-3, "pressed or plastic-bonded RDX/HMX", "upper end of pressed RDX's 2.5-4.4 mm (" + _RU + "); " + _LASL
)
_CAST_TNT = CriticalDiameter(
    15e-3,
    "cast TNT-based",
    "cast TNT fails below ~15 mm unconfined (" + _LASL + "); aluminised and TNT-based castings taken as cast TNT",
)

#: Critical diameter of each library explosive in the form a lab fires it [m] (module docstring).
CRITICAL_DIAMETERS_M: dict[str, CriticalDiameter] = {
    "tnt": CriticalDiameter(
        6e-3,
        "pressed, fine-grained",
        "pressed fine TNT 3-6 mm, cast 15 mm and more (" + _LASL + "); upper end of the pressed range",
    ),
    "petn": CriticalDiameter(
        1e-3,
        "pressed",
        "pressed PETN 0.7-0.86 mm at 1.0 g/cm^3 (" + _RU + "), about 1 mm at higher density (" + _LASL + ")",
    ),
    "rdx": _NITRAMINE,
    "hmx": _NITRAMINE,
    "c-4": CriticalDiameter(4.4e-3, "plastic (91 % RDX)", "taken as pressed RDX's upper end, 4.4 mm (" + _LASL + ")"),
    "pe4": CriticalDiameter(4.4e-3, "plastic (88 % RDX)", "taken as pressed RDX's upper end, 4.4 mm (" + _LASL + ")"),
    "semtex": CriticalDiameter(
        4.4e-3, "plastic (RDX and PETN)", "taken as pressed RDX's upper end, 4.4 mm (" + _LASL + ")"
    ),
    "composition-a-3": _NITRAMINE,
    "composition-b": CriticalDiameter(4.3e-3, "cast Comp B-3", "4.28 mm, unconfined (" + _LASL + ")"),
    "cyclotol-70-30": CriticalDiameter(4.3e-3, "cast", "taken as cast Comp B's 4.3 mm (" + _LASL + ")"),
    "octol-75-25": CriticalDiameter(4.3e-3, "cast", "taken as cast Comp B's 4.3 mm (" + _LASL + ")"),
    "pentolite": CriticalDiameter(7e-3, "cast 50/50", "taken as tetryl's upper end, 5-7 mm (" + _RU + ")"),
    "tetryl": CriticalDiameter(7e-3, "pressed", "5-7 mm (" + _RU + "); upper end"),
    "tetrytol": _CAST_TNT,
    "hbx-1": _CAST_TNT,
    "hbx-3": _CAST_TNT,
    "h-6": _CAST_TNT,
    "minol-ii": _CAST_TNT,
    "tritonal": _CAST_TNT,
    "tnetb": _CAST_TNT,
    "anfo": CriticalDiameter(
        0.1, "prilled, unconfined", "prilled ANFO fails below 75-100 mm unconfined (Cooper 1996 ch. 17); upper end"
    ),
    "lead-azide": CriticalDiameter(
        0.05e-3,
        "pressed (primary explosive)",
        "primary explosives detonate in layers of hundredths of a mm (Cooper 1996 ch. 17); taken as 0.05 mm",
    ),
}


def min_reliable_charge(critical_diameter_m: float, density_kg_m3: float) -> float:
    """Smallest reliable charge [kg]: the hemisphere of radius ``critical_diameter_m`` [m] of an
    explosive of density ``density_kg_m3`` [kg/m^3], ``m = 2 pi rho d_c^3 / 3`` (module docstring)."""
    return 2.0 * math.pi / 3.0 * float(density_kg_m3) * float(critical_diameter_m) ** 3


@dataclass(frozen=True)
class Initiator:
    """A detonator: its explosive contents ``((explosive name, mass [kg]), ...)`` and its source."""

    name: str
    contents: tuple
    source: str


#: Real initiators by name (their explosive contents from the makers' data sheets).
INITIATORS: dict[str, Initiator] = {
    "rp-80": Initiator(
        "rp-80",
        (("petn", 80e-6), ("rdx", 123e-6)),
        "Teledyne RISI RP-80 exploding-bridgewire detonator data sheet: 80 mg PETN initiating pellet, "
        "123 mg RDX output pellet",
    ),
    "none": Initiator("none", (), "no initiator (a laser or the charge's own bridgewire): state it"),
}

#: The default ``[lab] initiator``: an EBW detonator, the usual choice for sub-gram blast charges.
DEFAULT_INITIATOR = "rp-80"
