"""Explosives and their TNT equivalence, for pressure and for impulse separately.

The blast fits of :mod:`blastscale.blast` are for TNT. A charge of another explosive of mass m is
replaced by the TNT mass that produces the same peak overpressure (``m f_P``) or the same impulse
(``m f_I``): the two *equivalent load factors* of UFC 3-340-02 (2008), Table 2-1, which differ (C-4:
1.37 for pressure, 1.19 for impulse). blastscale uses each where it belongs:

* **impulse** for the specimen's charge: the general scaling law matches the impulse (paper Eq. 8),
  so the mass of the chosen explosive is the one whose *impulse* TNT equivalent equals the design's
  TNT charge, ``m = (W_TNT - W_init) / f_I``;
* **pressure** for the safety distances: the overpressure thresholds are peak pressures, so the
  charge that sets them is ``W_P = m f_P + W_init``.

The initiator (detonator, exploding bridgewire, primer) adds its own TNT-equivalent mass ``W_init``
(the same for both bases: a detonator's equivalence is known to no better than its nominal TNT
figure); a design warns when it exceeds :data:`INITIATOR_WARNING_FRACTION` of the charge, because
the initiator's own blast (and its casing's fragments) then shape the load and its uncertainty.

References
----------
.. [1] UFC 3-340-02 (2008). *Structures to Resist the Effects of Accidental Explosions*. US DoD,
       Table 2-1 "Equivalent load factors" (TNT equivalent weight for pressure and for impulse;
       the factors hold over the table's pressure ranges, 0.035-0.69 MPa for most entries,
       0.07-1.38 MPa for C-4).
.. [2] Meyer, R., Koehler, J., Homburg, A. (2007). *Explosives*, 6th ed., Wiley-VCH: lead azide,
       heat of explosion 367 cal/g (1536 kJ/kg), density 4.8 g/cm^3.
.. [3] Cooper, P. W. (1996). *Explosives Engineering*, Wiley-VCH, ch. 23 (TNT equivalence by heat of
       detonation and by air-blast tests; the two disagree by tens of percent for primary explosives).
.. [4] UNODA (2021). IATG 01.80 *Formulae for ammunition management*, table of TNT equivalence for
       pressure and for impulse (which reproduces UFC 3-340-02 Table 2-1's factors and adds PETN's
       impulse factor, RDX and HMX): PETN 1.27 / 1.11, RDX 1.14 / 1.09, HMX 1.02 / 1.03 (pressure /
       impulse), as given by two transcriptions of it (issue #24); the original was not at hand here.
.. [5] Bogosian, D., Yokota, M. & Rigby, S. E. (2016). TNT equivalence of C-4 and PE4: a review of
       traditional sources and recent data. 24th Military Aspects of Blast and Shock (MABS 24).

Names are matched without regard to case, spaces, hyphens or underscores, with the usual aliases
(:data:`ALIASES`: "C4", "Composition C-4", "Comp B", ...). Each library entry carries its smallest
reliable charge (:mod:`.initiation`).
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from typing import Mapping, Optional

from .._validate import BlastscaleInputError
from .initiation import CRITICAL_DIAMETERS_M, INITIATORS, min_reliable_charge

__all__ = [
    "Explosive",
    "ChargeEquivalence",
    "EXPLOSIVES",
    "UFC_3_340_02_TABLE_2_1",
    "IATG_01_80",
    "TNT_ENERGY_J_KG",
    "INITIATOR_WARNING_FRACTION",
    "ALIASES",
    "canonical_name",
    "get_explosive",
    "charge_equivalence",
    "initiator_tnt_kg",
]

#: Above this fraction of the charge's TNT equivalent (impulse basis) the initiator gets a warning.
INITIATOR_WARNING_FRACTION = 0.10

#: The TNT-equivalent energy: 1 kg of TNT = 4.184 MJ (the definition of the ton of TNT, 4.184 GJ),
#: used for the equivalence of explosives by heat of explosion (UFC 3-340-02 Eq. 2-1's ratio of heats).
TNT_ENERGY_J_KG = 4.184e6

#: UFC 3-340-02 (2008) Table 2-1, "Equivalent load factors": name -> (TNT equivalent weight for
#: pressure, TNT equivalent weight for impulse, density [kg/m^3]); None where the table gives no
#: impulse factor. Transcribed from the table (two independent transcriptions agree on every
#: pressure factor: MSB B02-301 (2017) Table 2.2 and Protection Engineering Consultants' unit
#: tables); the densities are the table's (Mg/m^3 x 1000). The table itself states each factor for
#: a pressure range (mostly 0.035-0.69 MPa, C-4 0.07-1.38 MPa): outside it the equivalence is less
#: certain (Cooper 1996, ch. 23: tens of percent between tests).
UFC_3_340_02_TABLE_2_1: dict[str, tuple[float, Optional[float], float]] = {
    "tnt": (1.00, 1.00, 1600.0),
    "c-4": (1.37, 1.19, 1600.0),
    "composition-a-3": (1.09, 1.07, 1650.0),
    "composition-b": (1.11, 0.98, 1690.0),
    "cyclotol-70-30": (1.14, 1.09, 1730.0),
    "hbx-1": (1.17, 1.16, 1750.0),
    "hbx-3": (1.14, 0.97, 1850.0),
    "h-6": (1.38, 1.15, 1760.0),
    "minol-ii": (1.20, 1.11, 1820.0),
    "octol-75-25": (1.06, None, 1800.0),
    "petn": (1.27, None, 1770.0),
    "pentolite": (1.42, 1.00, 1660.0),
    "tetryl": (1.07, None, 1730.0),
    "tetrytol": (1.06, None, 1600.0),
    "tnetb": (1.36, 1.10, 1690.0),
    "tritonal": (1.07, 0.96, 1720.0),
    "anfo": (0.82, 0.82, 850.0),
}

#: IATG 01.80's entries beyond UFC 3-340-02 Table 2-1 (reference [4]): name -> (pressure factor,
#: impulse factor, density [kg/m^3]); densities: PETN the UFC table's, RDX and HMX their pressed
#: densities (Meyer, Koehler & Homburg 2007: 1.80 and 1.90 g/cm^3 crystal, pressed slightly lower).
IATG_01_80: dict[str, tuple[float, float, float]] = {
    "petn": (1.27, 1.11, 1770.0),
    "rdx": (1.14, 1.09, 1800.0),
    "hmx": (1.02, 1.03, 1900.0),
}

#: What users call the library's explosives: the squashed name (lower case, letters and digits only)
#: -> the library's name. Every library name is also matched squashed ("C4" -> "c-4").
ALIASES = {
    "compositionc4": "c-4",
    "compc4": "c-4",
    "m112": "c-4",
    "compb": "composition-b",
    "compositionb3": "composition-b",
    "compb3": "composition-b",
    "compa3": "composition-a-3",
    "cyclotol": "cyclotol-70-30",
    "octol": "octol-75-25",
    "minol": "minol-ii",
    "hexogen": "rdx",
    "cyclonite": "rdx",
    "t4": "rdx",
    "octogen": "hmx",
    "pentrite": "petn",
    "trinitrotoluene": "tnt",
    "semtexh": "semtex",
    "semtex1a": "semtex",
    "pe4plastic": "pe4",
    "leadazide": "lead-azide",
}


@dataclass(frozen=True)
class Explosive:
    """One explosive: its TNT equivalence for peak pressure and for impulse.

    Attributes
    ----------
    name : str
        Key used in scenario files (``[lab] explosive = "c-4"``).
    pressure_factor, impulse_factor : float
        TNT mass per unit mass of the explosive [-] giving the same peak overpressure, resp. the
        same impulse.
    density_kg_m3 : float or None
        Density [kg/m^3] (the charge's size on the test card); None when unknown.
    source : str
        Where the numbers come from.
    uncertainty : str
        How well they are known, in words.
    min_charge_kg : float
        Smallest charge that detonates reliably [kg] (:mod:`.initiation`); 0 when not stated.
    min_charge_source : str
        Where it comes from.
    """

    name: str
    pressure_factor: float
    impulse_factor: float
    density_kg_m3: Optional[float]
    source: str
    uncertainty: str
    min_charge_kg: float = 0.0
    min_charge_source: str = "not stated"

    def __post_init__(self):
        for attr in ("pressure_factor", "impulse_factor"):
            v = getattr(self, attr)
            if not (isinstance(v, (int, float)) and math.isfinite(v) and 0.0 < v <= 10.0):
                raise BlastscaleInputError(
                    f"explosive {self.name!r}: {attr} = {v!r} is out of range: valid range is (0, 10]"
                )

    def factor(self, basis: str) -> float:
        """The TNT equivalence factor [-] for ``basis`` ("pressure" or "impulse")."""
        if basis == "pressure":
            return self.pressure_factor
        if basis == "impulse":
            return self.impulse_factor
        raise BlastscaleInputError(f"basis = {basis!r} is not known: valid values are pressure, impulse")

    def tnt_equivalent(self, mass_kg: float, basis: str) -> float:
        """TNT-equivalent mass [kg] of ``mass_kg`` of this explosive, ``W = m f`` (UFC 3-340-02 Table 2-1)."""
        return float(mass_kg) * self.factor(basis)

    def mass_for_tnt(self, tnt_kg: float, basis: str) -> float:
        """Mass of this explosive [kg] whose TNT equivalent is ``tnt_kg``, ``m = W / f``."""
        return float(tnt_kg) / self.factor(basis)


def _with_min_charge(ex: Explosive) -> Explosive:
    cd = CRITICAL_DIAMETERS_M[ex.name]
    m = min_reliable_charge(cd.diameter_m, ex.density_kg_m3)
    return Explosive(
        ex.name,
        ex.pressure_factor,
        ex.impulse_factor,
        ex.density_kg_m3,
        ex.source,
        ex.uncertainty,
        m,
        f"hemisphere of radius the critical diameter {1e3 * cd.diameter_m:.3g} mm ({cd.form}; "
        f"{cd.source}) at {ex.density_kg_m3:g} kg/m^3",
    )


def _ufc(name: str) -> Explosive:
    p, i, rho = UFC_3_340_02_TABLE_2_1[name]
    if name in IATG_01_80:
        p, i, rho = IATG_01_80[name]
        return Explosive(
            name,
            p,
            i,
            rho,
            "UFC 3-340-02 (2008) Table 2-1 (pressure); IATG 01.80 (impulse, which the UFC table does not give)",
            "IATG's impulse factor as transcribed, not checked against "
            "the original here; +-10 % outside the table's pressure range (Cooper 1996, ch. 23)",
        )
    if i is None:
        return Explosive(
            name,
            p,
            p,
            rho,
            "UFC 3-340-02 (2008) Table 2-1 (pressure factor; the table gives no "
            "impulse factor: the pressure factor is used for impulse too)",
            "impulse equivalence not tabulated: assume +-20 % on the impulse (Cooper 1996)",
        )
    return Explosive(
        name,
        p,
        i,
        rho,
        "UFC 3-340-02 (2008) Table 2-1",
        "the table's factors hold over its pressure range; +-10 % outside it (Cooper 1996, ch. 23)",
    )


def _iatg(name: str) -> Explosive:
    p, i, rho = IATG_01_80[name]
    return Explosive(
        name,
        p,
        i,
        rho,
        "IATG 01.80 (2021), TNT equivalence for pressure and impulse",
        "as transcribed, not checked against the original here; +-10 % (Cooper 1996, ch. 23)",
    )


def _as_c4(name: str, what: str) -> Explosive:
    p, i, rho = UFC_3_340_02_TABLE_2_1["c-4"]
    return Explosive(
        name,
        p,
        i,
        rho,
        f"{what}: C-4's factors of UFC 3-340-02 (2008) Table 2-1 (no table of its own "
        "gives both factors; C-4 and PE4 reviewed together by Bogosian, Yokota & Rigby 2016)",
        "assumed by composition; measured equivalences of RDX plastic explosives scatter by +-15 % "
        "(Bogosian et al. 2016)",
    )


#: The library: name -> Explosive. UFC 3-340-02 Table 2-1 for the secondary explosives (PETN's
#: impulse factor, RDX and HMX from IATG 01.80; PE4 and Semtex as C-4); lead azide (the usual
#: primary explosive of sub-gram charges and detonators) by its heat of explosion.
EXPLOSIVES: dict[str, Explosive] = {n: _ufc(n) for n in UFC_3_340_02_TABLE_2_1}
EXPLOSIVES["rdx"], EXPLOSIVES["hmx"] = _iatg("rdx"), _iatg("hmx")
EXPLOSIVES["pe4"] = _as_c4("pe4", "PE4 (UK plastic explosive, 88 % RDX)")
EXPLOSIVES["semtex"] = _as_c4("semtex", "Semtex H (Czech plastic explosive, RDX and PETN)")
EXPLOSIVES["lead-azide"] = Explosive(
    "lead-azide",
    1.536e6 / TNT_ENERGY_J_KG,
    1.536e6 / TNT_ENERGY_J_KG,
    4800.0,
    "heat of explosion 1536 kJ/kg (Meyer, Koehler & Homburg 2007) over the TNT-equivalent energy 4.184 MJ/kg "
    "(UFC 3-340-02 Eq. 2-1, ratio of heats)",
    "air-blast equivalence of primary explosives is not tabulated; ratio of heats 0.33-0.37 with TNT's measured "
    "4.2-4.6 MJ/kg: assume +-30 %",
)
EXPLOSIVES = {n: _with_min_charge(e) for n, e in EXPLOSIVES.items()}


def _squash(name: str) -> str:
    return re.sub(r"[^a-z0-9]", "", str(name).lower())


def canonical_name(name: str, custom: Optional[Mapping[str, object]] = None) -> Optional[str]:
    """The library's (or ``custom``'s) name of the explosive a user calls ``name`` (case, spaces,
    hyphens and underscores ignored; :data:`ALIASES`), or None when none matches. An exact
    ``custom`` name wins over the library's."""
    if custom and name in custom:
        return name
    key = _squash(name)
    for table in (custom or {}), EXPLOSIVES:
        for n in table:
            if _squash(n) == key:
                return n
    return ALIASES.get(key)


def initiator_tnt_kg(name: str) -> float:
    """TNT-equivalent mass [kg] (impulse basis) of the initiator ``name`` of
    :data:`~.initiation.INITIATORS`: the sum of its contents' masses times their impulse factors."""
    return float(sum(m * EXPLOSIVES[ex].impulse_factor for ex, m in INITIATORS[name].contents))


def get_explosive(name: str, custom: Optional[Mapping[str, Explosive]] = None) -> Explosive:
    """The explosive named ``name``: a user-defined one (``custom``, e.g. a scenario's
    ``[lab.explosives.NAME]`` tables) first, then the library :data:`EXPLOSIVES`."""
    table = {**EXPLOSIVES, **dict(custom or {})}
    try:
        return table[canonical_name(name, custom) if isinstance(name, str) else name]
    except (KeyError, TypeError):
        raise BlastscaleInputError(
            f"explosive = {name!r} is not known: valid values are {', '.join(table)} "
            "(or define it in a [lab.explosives.NAME] table)"
        ) from None


@dataclass(frozen=True)
class ChargeEquivalence:
    """The specimen's charge in a real explosive (SI).

    Attributes
    ----------
    explosive : Explosive
    explosive_mass_kg : float
        Mass of the explosive to weigh [kg] (without the initiator).
    initiator_tnt_kg : float
        The initiator's TNT-equivalent mass [kg].
    tnt_equivalent_impulse_kg : float
        TNT equivalent of explosive + initiator for impulse [kg] (= the design's TNT charge).
    tnt_equivalent_pressure_kg : float
        TNT equivalent of explosive + initiator for peak pressure [kg] (sets the safety distances).
    initiator_fraction : float
        Initiator / total TNT equivalent (impulse basis) [-].
    warnings : tuple of str
    """

    explosive: Explosive
    explosive_mass_kg: float
    initiator_tnt_kg: float
    tnt_equivalent_impulse_kg: float
    tnt_equivalent_pressure_kg: float
    initiator_fraction: float
    warnings: tuple = ()

    def to_dict(self) -> dict:
        return {
            "explosive": self.explosive.name,
            "explosive_mass_kg": self.explosive_mass_kg,
            "initiator_tnt_kg": self.initiator_tnt_kg,
            "tnt_equivalent_impulse_kg": self.tnt_equivalent_impulse_kg,
            "tnt_equivalent_pressure_kg": self.tnt_equivalent_pressure_kg,
            "pressure_factor": self.explosive.pressure_factor,
            "impulse_factor": self.explosive.impulse_factor,
            "initiator_fraction": self.initiator_fraction,
            "explosive_min_charge_kg": self.explosive.min_charge_kg,
            "min_charge_source": self.explosive.min_charge_source,
            "equivalence_source": self.explosive.source,
            "equivalence_uncertainty": self.explosive.uncertainty,
            "warnings": list(self.warnings),
        }


def charge_equivalence(
    tnt_kg: float,
    explosive: "str | Explosive" = "tnt",
    initiator_tnt_kg: float = 0.0,
    custom: Optional[Mapping[str, Explosive]] = None,
) -> ChargeEquivalence:
    """The mass of ``explosive`` that, with the initiator, delivers the impulse of ``tnt_kg`` of TNT.

    .. math:: m = \\frac{W - W_{init}}{f_I}, \\qquad W_P = m f_P + W_{init}

    (UFC 3-340-02 Table 2-1: ``f_I`` and ``f_P`` the explosive's impulse and pressure factors).

    Parameters
    ----------
    tnt_kg : float
        The design's TNT charge W [kg] (impulse basis: the general law matches the impulse), > 0.
    explosive : str or Explosive
        Name in :data:`EXPLOSIVES` (or ``custom``), or an :class:`Explosive`.
    initiator_tnt_kg : float
        The initiator's TNT-equivalent mass W_init [kg], >= 0 and < W.
    custom : mapping, optional
        User-defined explosives by name.

    Returns
    -------
    ChargeEquivalence

    Raises
    ------
    BlastscaleInputError
        When the initiator alone carries the whole charge (W_init >= W), or bad values.

    Examples
    --------
    >>> c = charge_equivalence(1.0, "c-4")
    >>> round(c.explosive_mass_kg, 4), round(c.tnt_equivalent_pressure_kg, 4)
    (0.8403, 1.1513)
    """
    W = float(tnt_kg)
    w0 = float(initiator_tnt_kg)
    if not (math.isfinite(W) and W > 0):
        raise BlastscaleInputError(f"charge = {tnt_kg!r} kg TNT is out of range: must be > 0 kg")
    if not (math.isfinite(w0) and w0 >= 0):
        raise BlastscaleInputError(f"initiator_tnt_kg = {initiator_tnt_kg!r} is out of range: must be >= 0 kg")
    ex = explosive if isinstance(explosive, Explosive) else get_explosive(explosive, custom)
    if w0 >= W:
        raise BlastscaleInputError(
            f"initiator_tnt_kg = {w0:.4g} kg is out of range: the initiator alone delivers at least the whole "
            f'charge ({W:.4g} kg TNT); use a smaller initiator (initiator_tnt_kg; initiator = "none" for a laser) or a '
            "larger scale"
        )
    m = (W - w0) / ex.impulse_factor
    frac = w0 / W
    notes = []
    if frac > INITIATOR_WARNING_FRACTION:
        notes.append(
            f"the initiator is {100 * frac:.3g} % of the charge (TNT equivalent, above "
            f"{100 * INITIATOR_WARNING_FRACTION:g} %): its own blast and its uncertainty shape the load"
        )
    return ChargeEquivalence(ex, m, w0, W, m * ex.pressure_factor + w0, frac, tuple(notes))
