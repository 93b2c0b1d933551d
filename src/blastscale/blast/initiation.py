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
.. [5] Teledyne RISI, *RP-83 EBW detonator* data sheet: initiating pellet 80 mg PETN, output pellet
       1031 mg RDX, aluminium cup (the figures as quoted in issue #37; the sheet itself was not at hand
       here: check the lot's sheet).
.. [6] Dyno Nobel, *NONEL user's manual*, p. 8: a detonator of strength No. 8 (Prior test) holds
       "approx. 1 g" of explosive in all (a PETN initiation element and the base charge) in an aluminium
       shell; Meyer, Koehler & Homburg (2007), *Explosives*, 6th ed., "Cap sensitivity": the European
       test detonator's secondary charge is 0.6 g PETN. blastscale's ``"no-8"`` is 0.8 g PETN base
       charge and 0.2 g lead azide primer (1.0 g in all, the upper end of both figures: a safety
       figure errs large); a lab that knows its detonator's contents states ``initiator_tnt_kg``.

**TNT equivalents of an initiator.** Each content's mass times its factor for peak pressure (``f_P``)
and for impulse (``f_I``), summed (:func:`blastscale.blast.explosives.initiator_tnt_kg`): the RP-80
is 80 x 1.27 + 123 x 1.14 = 241.8 mg TNT by pressure and 80 x 1.11 + 123 x 1.09 = 222.9 mg by
impulse. The design (the impulse the specimen must receive) uses the impulse basis; everything about
safety (the safety distances, the licence limit ``[lab] tnt_max_kg``) uses the *stricter* (larger)
of the two, so that no basis under-states the hazard.
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
    """A detonator: its explosive contents ``((explosive name, mass [kg]), ...)``, its source, and its
    shell (the metal cup whose fragments the test card's fragment distance throws: material, density
    [kg/m^3] and mass [kg]; nominal, to be checked by weighing one of the lot)."""

    name: str
    contents: tuple
    source: str
    shell_material: str = ""
    shell_density_kg_m3: float = 0.0
    shell_mass_kg: float = 0.0
    shell_source: str = ""
    description: str = ""

    @property
    def explosive_mass_kg(self) -> float:
        """The explosive in the initiator, all contents together [kg]."""
        return float(sum(m for _, m in self.contents))


_ALUMINIUM = 2700.0  # kg/m^3
_SHELL_NOMINAL = "nominal, not from the data sheet: weigh one shell of the lot (the fragment distance grows with it)"

#: Real initiators by name (their explosive contents from the makers' data sheets; module docstring).
INITIATORS: dict[str, Initiator] = {
    "rp-80": Initiator(
        "rp-80",
        (("petn", 80e-6), ("rdx", 123e-6)),
        "Teledyne RISI RP-80 exploding-bridgewire detonator data sheet: 80 mg PETN initiating pellet, "
        "123 mg RDX output pellet",
        "aluminium",
        _ALUMINIUM,
        0.5e-3,
        _SHELL_NOMINAL,
        "Teledyne RISI RP-80 EBW detonator (80 mg PETN + 123 mg RDX)",
    ),
    "rp-83": Initiator(
        "rp-83",
        (("petn", 80e-6), ("rdx", 1031e-6)),
        "Teledyne RISI RP-83 exploding-bridgewire detonator data sheet: 80 mg PETN initiating pellet, "
        "1031 mg RDX output pellet (as quoted in issue #37; check the lot's sheet)",
        "aluminium",
        _ALUMINIUM,
        1.0e-3,
        _SHELL_NOMINAL,
        "Teledyne RISI RP-83 EBW detonator (80 mg PETN + 1031 mg RDX)",
    ),
    "no-8": Initiator(
        "no-8",
        (("petn", 0.8e-3), ("lead-azide", 0.2e-3)),
        "a commercial No. 8 detonator: about 1 g of explosive in all (Dyno Nobel NONEL user's manual p. 8); "
        "taken as 0.8 g PETN base charge and 0.2 g lead azide primer (Meyer, Koehler & Homburg 2007: "
        "the European test detonator holds 0.6 g PETN); state initiator_tnt_kg for your own",
        "aluminium",
        _ALUMINIUM,
        1.5e-3,
        _SHELL_NOMINAL,
        "a commercial No. 8 detonator (0.8 g PETN base charge + 0.2 g lead azide)",
    ),
    "none": Initiator("none", (), "no initiator (a laser or the charge's own bridgewire): state it"),
}

#: The default ``[lab] initiator``: an EBW detonator, the usual choice for sub-gram blast charges.
DEFAULT_INITIATOR = "rp-80"
