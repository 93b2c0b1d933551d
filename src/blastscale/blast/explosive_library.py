"""The library of explosives: each one's TNT equivalence for peak pressure and for impulse, with its sources.

UFC 3-340-02 (2008) Table 2-1 gives the two *equivalent load factors* of the secondary explosives
(:data:`UFC_3_340_02_TABLE_2_1`); IATG 01.80 adds PETN's impulse factor, RDX and HMX
(:data:`IATG_01_80`); PE4 and Semtex take C-4's factors; lead azide (the usual primary explosive of
sub-gram charges and detonators) is rated by its heat of explosion. Each entry of :data:`EXPLOSIVES`
also carries its smallest reliable charge (:mod:`.initiation`). Looking an explosive up by name and
the specimen's charge in it: :mod:`.explosives`.

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
       impulse), as given by two transcriptions of it (issue #24); the original was not at hand here
       (nor in issue #37's search). HMX's 1.02 / 1.03 is **not used** (below).

**HMX (issue #37).** HMX (C4H8N8O8) and RDX (C3H6N6O6) have the same elemental composition,
(CH2N2O2)n, and nearly the same heat of formation per unit mass (RDX about +70 kJ/mol over 222.1
g/mol = +0.32 MJ/kg, beta-HMX about +75 kJ/mol over 296.2 g/mol = +0.25 MJ/kg; Cooper 1996 ch. 3,
Meyer, Koehler & Homburg 2007): they detonate to the same products with heats of detonation per unit
mass within about 2 % of each other, and HMX, denser, detonates faster. Its air-blast TNT
equivalence cannot sit 10 % below RDX's, as the transcribed 1.02 / 1.03 would have it (heat of
detonation puts both near 1.2-1.3 by the ratio of heats, UFC 3-340-02 Eq. 2-1): the most likely
reading is a transcription slip. blastscale gives HMX RDX's measured factors, 1.14 / 1.09
(:data:`EXPLOSIVES` ``"hmx"``), with RDX's +-10 % widened to +-15 % for the substitution.
.. [5] Bogosian, D., Yokota, M. & Rigby, S. E. (2016). TNT equivalence of C-4 and PE4: a review of
       traditional sources and recent data. 24th Military Aspects of Blast and Shock (MABS 24).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional

from .._validate import BlastscaleInputError, check_choice
from .initiation import CRITICAL_DIAMETERS_M, min_reliable_charge

__all__ = ["Explosive", "EXPLOSIVES", "UFC_3_340_02_TABLE_2_1", "IATG_01_80", "TNT_ENERGY_J_KG"]

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
        check_choice("basis", basis, ("pressure", "impulse"))
        return self.pressure_factor if basis == "pressure" else self.impulse_factor

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
EXPLOSIVES["rdx"] = _iatg("rdx")
EXPLOSIVES["hmx"] = Explosive(
    "hmx",
    IATG_01_80["rdx"][0],
    IATG_01_80["rdx"][1],
    IATG_01_80["hmx"][2],
    "RDX's factors of IATG 01.80 (2021): HMX and RDX share the composition (CH2N2O2)n and their heats of "
    "detonation per unit mass agree within ~2 % (module docstring); the transcribed HMX 1.02 / 1.03 is taken "
    "for a slip",
    "by composition and heat of detonation, not an air-blast test of HMX: +-15 %",
)
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
