"""A small, cited library of specimen materials: density, joint friction, strength and stiffness.

The general scaling law leaves the density ratio gamma = rho_model / rho_prototype free
(paper Sec. "Different material modeling"); a scenario may name the model's material
instead of giving gamma (``[scale] specimen_material = "balsa"``). The same name then fixes the
specimen's joint friction (its :attr:`Material.friction` against itself, the 3D engine's Coulomb
coefficient of the specimen) and, for the planner's rigidity check
(:mod:`blastscale.similitude.rigidity`), its compressive strength and Young's modulus.

Every value is *nominal*: real stone varies by quarry, a joint's friction by its finish and
wear, wood by its density. Each entry carries the range its source gives (density, friction)
and the source of every property; a test designer weighs their own specimens and measures the
friction of their own joints by a tilt test (:func:`friction_card_line`).

Sources
-------
[EN1991] EN 1991-1-1:2002, Eurocode 1: Actions on structures - Part 1-1: densities, self-weight,
    imposed loads. Annex A, nominal densities of construction materials (given there as unit
    weights in kN/m^3; converted here with g = 9.81 m/s^2 and rounded).
[EN1992] EN 1992-1-1:2004, Eurocode 2: Design of concrete structures. Table 3.1 (mean compressive
    strength f_cm and secant modulus E_cm per strength class) and 6.2.5(2) (friction of concrete
    interfaces: 0.5 very smooth, 0.6 smooth, 0.7 rough, 0.9 indented).
[EN1993] EN 1993-1-1:2005, Eurocode 3: Design of steel structures. Table 3.1 (yield strength f_y:
    S235 235 MPa to S460 460 MPa) and 3.2.6 (E = 210 GPa).
[EN1996] EN 1996-1-1:2005, Eurocode 6: Design of masonry structures. 3.7.2 (short-term secant
    modulus E = K_E f_k, K_E = 1000 recommended); with EN 771-1 (declared mean compressive
    strength of clay units, classes about 10 to 50 MPa) and EN 998-2 (mortar classes M1 to M20,
    1 to 20 MPa).
[EN1999] EN 1999-1-1:2007, Eurocode 9: Design of aluminium structures. Table 3.2b (0.2 % proof
    strength f_o of extrusions, EN AW-6060 T5 about 120 MPa to EN AW-6082 T6 260 MPa) and 3.2.5
    (E = 70 GPa).
[HOEK] Hoek, E. (2007), Practical Rock Engineering, ch. 11, Table 3 (field estimates of the
    uniaxial compressive strength of intact rock after ISRM 1981: granite, marble, limestone,
    sandstone, tuff in the classes R3 25-50, R4 50-100, R5 100-250 and R6 > 250 MPa).
[HD2006] Hoek, E. & Diederichs, M. S. (2006), Empirical estimation of rock mass modulus, Int. J. Rock
    Mech. Min. Sci. 43, 203-215, Table 3 (modulus ratio MR = E / sigma_ci: marble 700-1000,
    limestone 400-1000, granite 300-550, sandstone 200-350, tuff 200-400). E = MR x f_c here.
[LR2004] Lourenco, P. B. & Ramos, L. F. (2004), Characterization of cyclic behavior of dry masonry
    joints, J. Struct. Eng. 130(5), 779-786 (dry stone joints: friction depends on the finish,
    rough sawn joints near 0.6-0.7, polished ones lower).
[VL2009] Vasconcelos, G. & Lourenco, P. B. (2009), Experimental characterization of stone masonry in
    shear and compression, Constr. Build. Mater. 23, 3337-3345 (dry granite joints, friction
    coefficient about 0.6-0.8 by finish).
[MSM] Masi, Stefanou & Maffi-Berthier, *Scaling laws for the rigid-body response of masonry
    structures under blast loads*: Sec. "Validation" (friction angle 35 deg, mu = 0.7, "common for
    many geomaterials"), Sec. "Different material modeling" (balsa, 140 kg/m^3, gamma = 0.07 for a
    2000 kg/m^3 prototype).
[MARKS] Avallone, E. A. & Baumeister, T. (eds.), Marks' Standard Handbook for Mechanical Engineers,
    Sec. 3.2, table of static friction coefficients (clean, dry: mild steel on mild steel 0.74,
    aluminium on aluminium 1.05-1.35 by cleanliness, wood on wood 0.25-0.5).
[DUBBEL] Grote, K.-H. & Feldhusen, J. (eds.), Dubbel Taschenbuch fuer den Maschinenbau, table of
    static friction (dry: steel-steel 0.45-0.80, aluminium alloy pairs 0.15-0.60, wood-wood
    0.40-0.65, steel-lead 0.5).
[BT1950] Bowden, F. P. & Tabor, D. (1950), The Friction and Lubrication of Solids, ch. 5 (soft clean
    metals on themselves in air: mu about 1 and above, with junction growth and seizure).
[LEAD] Pure lead: Young's modulus 14 GPa, yield stress 11 MPa (Callister, Materials Science and
    Engineering, 1994); annealed pure lead: 0.2 % proof 5.5 MPa, E 16 GPa (ASM Handbook Vol. 2,
    Properties of pure metals).
[WH2010] Forest Products Laboratory (2010), Wood Handbook, General Technical Report FPL-GTR-190,
    USDA, ch. 5 (balsa at 12 % moisture, specific gravity about 0.16: compression parallel to the
    grain 14.9 MPa, modulus of elasticity 3.4 GPa; density range of the species).
[BG2015] Borrega, M. & Gibson, L. J. (2015), Mechanics of balsa (Ochroma pyramidale) wood, Mech.
    Mater. 84, 75-90 (axial modulus and strength linear in density over 60-380 kg/m^3).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

from .._validate import BlastscaleInputError

__all__ = [
    "Material",
    "MATERIALS",
    "MATERIAL_PROPERTIES",
    "PROTOTYPE_KINDS",
    "material_density",
    "get_material",
    "prototype_material",
    "specimen_material",
    "friction_card_line",
]


@dataclass(frozen=True)
class Material:
    """One entry of the library.

    Attributes
    ----------
    name : str
        Key used in scenario files.
    kind : str
        ``"stone"``, ``"masonry"``, ``"metal"`` or ``"wood"`` (stone and masonry may be prototypes).
    density : float
        Nominal density [kg/m^3].
    density_low, density_high : float
        Range of densities the source gives [kg/m^3].
    density_source : str
        Citation of the density (keys: the module docstring).
    friction : float
        Nominal static Coulomb friction coefficient of a dry joint of the material against
        itself [-] (the specimen's mu).
    friction_low, friction_high : float
        Range of the friction coefficient the sources give [-].
    friction_source : str
        Citation of the friction.
    compressive_strength_Pa : float
        Nominal uniaxial compressive strength [Pa] (for a ductile metal: its yield or 0.2 % proof
        stress, where it stops being rigid; wood: parallel to the grain).
    strength_source : str
        Citation of the strength.
    youngs_modulus_Pa : float
        Nominal Young's modulus [Pa].
    modulus_source : str
        Citation of the modulus.
    """

    name: str
    kind: str
    density: float
    density_low: float
    density_high: float
    density_source: str
    friction: float
    friction_low: float
    friction_high: float
    friction_source: str
    compressive_strength_Pa: float
    strength_source: str
    youngs_modulus_Pa: float
    modulus_source: str


#: Every property of a :class:`Material` and the field naming its source.
MATERIAL_PROPERTIES = {
    "density": "density_source",
    "friction": "friction_source",
    "compressive_strength_Pa": "strength_source",
    "youngs_modulus_Pa": "modulus_source",
}

#: The kinds of material a prototype may be made of (the library entries the planner may take for it).
PROTOTYPE_KINDS = ("stone", "masonry")

_STONE_MU = "MSM (35 deg, 0.7); LR2004 (dry stone joints 0.6-0.8 by finish, polished lower)"


def _entry(name: str, kind: str, *, density: tuple, friction: tuple, strength: tuple, modulus: tuple) -> Material:
    """A library entry from its properties: ``density`` and ``friction`` (nominal, low, high, source),
    ``strength`` and ``modulus`` (nominal [Pa], source)."""
    return Material(name, kind, *density, *friction, *strength, *modulus)


#: The library: name -> Material (SI: kg/m^3, Pa; friction [-]), each value with its source.
MATERIALS: dict[str, Material] = {
    m.name: m
    for m in (
        _entry(
            "marble",
            "stone",
            density=(2700.0, 2600.0, 2850.0, "EN1991 (marble, 28 kN/m^3 upper value)"),
            friction=(0.7, 0.5, 0.8, _STONE_MU),
            strength=(100e6, "HOEK (marble: R4-R5, 50-250 MPa; nominal 100 MPa)"),
            modulus=(70e9, "HD2006 (MR 700 x 100 MPa)"),
        ),
        _entry(
            "limestone",
            "stone",
            density=(2500.0, 2040.0, 2960.0, "EN1991 (dense limestone, 20-29 kN/m^3)"),
            friction=(0.7, 0.6, 0.8, "LR2004 (dry limestone joints); MSM (35 deg)"),
            strength=(80e6, "HOEK (limestone: R4-R5, 50-250 MPa; nominal 80 MPa)"),
            modulus=(56e9, "HD2006 (MR 700 x 80 MPa; limestone 400-1000)"),
        ),
        _entry(
            "sandstone",
            "stone",
            density=(2400.0, 2140.0, 2750.0, "EN1991 (sandstone, grey wacke, 21-27 kN/m^3)"),
            friction=(0.7, 0.6, 0.8, _STONE_MU),
            strength=(70e6, "HOEK (sandstone: R4-R5, 50-250 MPa, weak ones lower; nominal 70 MPa)"),
            modulus=(20e9, "HD2006 (MR about 285 x 70 MPa; sandstone 200-350)"),
        ),
        _entry(
            "granite",
            "stone",
            density=(2800.0, 2750.0, 3060.0, "EN1991 (granite, syenite, porphyry, 27-30 kN/m^3)"),
            friction=(0.7, 0.6, 0.8, "VL2009 (dry granite joints, 0.6-0.8 by finish); MSM (35 deg)"),
            strength=(150e6, "HOEK (granite: R5-R6, 100-250+ MPa; nominal 150 MPa)"),
            modulus=(60e9, "HD2006 (MR 400 x 150 MPa; granite 300-550)"),
        ),
        _entry(
            "tuff",
            "stone",
            density=(2000.0, 1500.0, 2040.0, "EN1991 (volcanic tuff, 20 kN/m^3)"),
            friction=(0.7, 0.6, 0.8, _STONE_MU),
            strength=(20e6, "HOEK (tuff: R3-R5 by welding, 25-250 MPa; soft building tuffs lower; nominal 20 MPa)"),
            modulus=(6e9, "HD2006 (MR 300 x 20 MPa; tuff 200-400)"),
        ),
        _entry(
            "brick",
            "masonry",
            density=(1900.0, 1600.0, 2100.0, "EN1991 (solid clay masonry)"),
            friction=(0.7, 0.6, 0.8, "MSM (35 deg, geomaterials); LR2004 (dry joints 0.6-0.8)"),
            strength=(20e6, "EN1996 (EN 771-1 clay units, classes about 10-50 MPa; nominal 20 MPa)"),
            modulus=(20e9, "EN1996 (E = 1000 x f, 3.7.2, applied to the unit)"),
        ),
        _entry(
            "concrete",
            "masonry",
            density=(2400.0, 2300.0, 2450.0, "EN1991 (normal-weight concrete, 24 kN/m^3)"),
            friction=(0.6, 0.5, 0.9, "EN1992 (6.2.5(2): smooth 0.6; very smooth 0.5 to indented 0.9)"),
            strength=(38e6, "EN1992 (Table 3.1, C30/37: f_cm = 38 MPa; C20/25 28 to C50/60 58 MPa)"),
            modulus=(33e9, "EN1992 (Table 3.1, C30/37: E_cm = 33 GPa)"),
        ),
        _entry(
            "mortar",
            "masonry",
            density=(2100.0, 1940.0, 2350.0, "EN1991 (cement mortar, 19-23 kN/m^3)"),
            friction=(0.6, 0.5, 0.9, "EN1992 (6.2.5(2), cementitious interfaces: smooth 0.6)"),
            strength=(10e6, "EN1996 (EN 998-2 class M10; M1-M20)"),
            modulus=(10e9, "EN1996 (E = 1000 x f, 3.7.2, applied to the mortar)"),
        ),
        _entry(
            "aluminium",
            "metal",
            density=(2700.0, 2700.0, 2750.0, "EN1991 (aluminium, 27 kN/m^3)"),
            friction=(1.05, 0.15, 1.35, "MARKS (clean, dry, 1.05-1.35); DUBBEL (alloy pairs 0.15-0.60)"),
            strength=(260e6, "EN1999 (Table 3.2b, EN AW-6082 T6 f_o = 260 MPa; 6060 T5 about 120 MPa)"),
            modulus=(70e9, "EN1999 (3.2.5, E = 70 GPa)"),
        ),
        _entry(
            "steel",
            "metal",
            density=(7850.0, 7850.0, 8000.0, "EN1991 (steel, 77-78.5 kN/m^3)"),
            friction=(0.74, 0.45, 0.8, "MARKS (mild steel on mild steel, dry, 0.74); DUBBEL (0.45-0.80)"),
            strength=(235e6, "EN1993 (Table 3.1, S235 f_y = 235 MPa; to S460 460 MPa)"),
            modulus=(210e9, "EN1993 (3.2.6, E = 210 GPa)"),
        ),
        _entry(
            "lead",
            "metal",
            density=(11400.0, 11400.0, 11600.0, "EN1991 (lead, 112-114 kN/m^3)"),
            friction=(0.9, 0.5, 1.5, "BT1950 (soft metals on themselves, about 1 and above); DUBBEL (steel-lead 0.5)"),
            strength=(5.5e6, "LEAD (annealed pure lead, 0.2 % proof 5.5 MPa; 11 MPa in Callister)"),
            modulus=(16e9, "LEAD (14-16 GPa)"),
        ),
        _entry(
            "balsa",
            "wood",
            density=(140.0, 100.0, 250.0, "MSM (140 kg/m^3); WH2010 (balsa, range of the species)"),
            friction=(0.4, 0.25, 0.65, "MARKS (wood on wood, dry, 0.25-0.5); DUBBEL (0.40-0.65)"),
            strength=(14.9e6, "WH2010 (compression parallel to the grain, 14.9 MPa; BG2015 linear in density)"),
            modulus=(3.4e9, "WH2010 (3.4 GPa; BG2015 linear in density)"),
        ),
    )
}


def get_material(name: str) -> Material:
    """The library entry ``name`` (one line naming the valid names when it is not one).

    Examples
    --------
    >>> get_material("steel").friction
    0.74
    """
    try:
        return MATERIALS[name]
    except (KeyError, TypeError):
        raise BlastscaleInputError(
            f"material = {name!r} is not in the materials library: valid values are {', '.join(MATERIALS)}"
        ) from None


def material_density(name: str) -> float:
    """Nominal density [kg/m^3] of a library material.

    Parameters
    ----------
    name : str
        A key of :data:`MATERIALS` (e.g. ``"marble"``, ``"balsa"``).

    Returns
    -------
    float
        Density [kg/m^3].

    Examples
    --------
    >>> material_density("balsa") / 2000.0   # the paper's gamma for a balsa model
    0.07
    """
    return get_material(name).density


def prototype_material(density: float, friction: float, name: str | None = None) -> Material:
    """The prototype's material: the library entry ``name`` or, without one, the stone or masonry
    entry (:data:`PROTOTYPE_KINDS`) nearest in density (the first in library order on a tie), with
    the scenario's own density [kg/m^3] and friction [-] in place of the nominal ones (their sources
    then say so). Its strength and modulus are the library's.

    Examples
    --------
    >>> m = prototype_material(2000.0, 0.7)   # the paper's block
    >>> m.name, m.density, m.compressive_strength_Pa / 1e6
    ('tuff', 2000.0, 20.0)
    >>> prototype_material(2700.0, 0.7, "marble").name
    'marble'
    """
    if name is None:
        cands = [m for m in MATERIALS.values() if m.kind in PROTOTYPE_KINDS]
        base = min(cands, key=lambda m: abs(m.density - density))
        how = f"nearest library stone or masonry by density ({base.density:g} kg/m^3)"
    else:
        base, how = get_material(name), "named"
    return replace(
        base,
        density=float(density),
        density_low=min(base.density_low, float(density)),
        density_high=max(base.density_high, float(density)),
        density_source=f"the scenario's ({how})",
        friction=float(friction),
        friction_low=min(base.friction_low, float(friction)),
        friction_high=max(base.friction_high, float(friction)),
        friction_source="the scenario's",
    )


def specimen_material(name: str | None, prototype: Material) -> Material:
    """The specimen's material: the library entry ``name``, or the prototype's own (``prototype``) for
    None or ``"same"`` (the planner's name for it)."""
    return prototype if name in (None, "same") else get_material(name)


def friction_card_line(material: Material, prototype_friction: float | None = None, label: str | None = None) -> str:
    """The test card's friction line of a specimen made of ``material``: its nominal joint friction [-]
    with the range its sources give, the prototype's friction it stands for, and the instruction to
    measure it by a tilt test (mu = tan of the tilt angle at the first slip of one piece on another of
    the same finish). ``label`` names the pair (default ``"NAME on NAME"``).

    Examples
    --------
    >>> print(friction_card_line(MATERIALS["lead"], 0.7))  # doctest: +NORMALIZE_WHITESPACE
    friction: lead on lead 0.9 nominal (0.5-1.5), the prototype's 0.7: measure by tilt test (mu = tan of
    the tilt angle at the first slip, on the specimen's own joint finish)
    """
    m = material
    pair = label or f"{m.name} on {m.name}"
    proto = "" if prototype_friction is None else f", the prototype's {prototype_friction:.3g}"
    return (
        f"friction: {pair} {m.friction:.3g} nominal ({m.friction_low:.3g}-{m.friction_high:.3g}){proto}: measure by "
        f"tilt test (mu = tan of the tilt angle at the first slip, on the specimen's own joint finish)"
    )
