"""A small, cited library of material densities for choosing the model's material.

The general scaling law leaves the density ratio gamma = rho_model / rho_prototype free
(paper Sec. "Different material modeling"); a scenario may name the model's material
instead of giving gamma (``[scale] specimen_material = "balsa"``). Densities are *nominal*
values [kg/m^3]: real stone varies by quarry, so each entry carries the range its source
gives, and a test designer should weigh their own specimens.

Sources
-------
[EN1991] EN 1991-1-1:2002, Eurocode 1: Actions on structures - Part 1-1: densities, self-weight,
    imposed loads. Annex A, nominal densities of construction materials (given there as unit
    weights in kN/m^3; converted here with g = 9.81 m/s^2 and rounded).
[WH2010] Forest Products Laboratory (2010), Wood Handbook, General Technical Report FPL-GTR-190,
    USDA, ch. 5 (specific gravity of wood, balsa ~0.16 at 12 % moisture; range of the species).
[MSM] Masi, Stefanou & Maffi-Berthier, *Scaling laws for the rigid-body response of masonry
    structures under blast loads*, Sec. "Different material modeling" (balsa, 140 kg/m^3,
    gamma = 0.07 for a 2000 kg/m^3 prototype).
"""

from __future__ import annotations

from dataclasses import dataclass

from .._validate import BlastscaleInputError

__all__ = ["Material", "MATERIALS", "material_density"]


@dataclass(frozen=True)
class Material:
    """One entry of the library.

    Attributes
    ----------
    name : str
        Key used in scenario files.
    density : float
        Nominal density [kg/m^3].
    low, high : float
        Range of densities the source gives [kg/m^3].
    source : str
        Citation key (see the module docstring).
    """

    name: str
    density: float
    low: float
    high: float
    source: str


#: The density library: name -> Material (densities in kg/m^3, ranges from the cited source).
MATERIALS: dict[str, Material] = {
    m.name: m
    for m in (
        Material("marble", 2700.0, 2600.0, 2850.0, "EN1991 (marble, 28 kN/m^3 upper value)"),
        Material("limestone", 2500.0, 2040.0, 2960.0, "EN1991 (dense limestone, 20-29 kN/m^3)"),
        Material("sandstone", 2400.0, 2140.0, 2750.0, "EN1991 (sandstone, grey wacke, 21-27 kN/m^3)"),
        Material("granite", 2800.0, 2750.0, 3060.0, "EN1991 (granite, syenite, porphyry, 27-30 kN/m^3)"),
        Material("tuff", 2000.0, 1500.0, 2040.0, "EN1991 (volcanic tuff, 20 kN/m^3)"),
        Material("brick", 1900.0, 1600.0, 2100.0, "EN1991 (solid clay masonry)"),
        Material("concrete", 2400.0, 2300.0, 2450.0, "EN1991 (normal-weight concrete, 24 kN/m^3)"),
        Material("mortar", 2100.0, 1940.0, 2350.0, "EN1991 (cement mortar, 19-23 kN/m^3)"),
        Material("aluminium", 2700.0, 2700.0, 2750.0, "EN1991 (aluminium, 27 kN/m^3)"),
        Material("steel", 7850.0, 7850.0, 8000.0, "EN1991 (steel, 77-78.5 kN/m^3)"),
        Material("lead", 11400.0, 11400.0, 11600.0, "EN1991 (lead, 112-114 kN/m^3)"),
        Material("balsa", 140.0, 100.0, 250.0, "MSM (140 kg/m^3); WH2010 (balsa, range of the species)"),
    )
}


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
    try:
        return MATERIALS[name].density
    except (KeyError, TypeError):
        raise BlastscaleInputError(
            f"material = {name!r} is not in the density library: valid values are {', '.join(MATERIALS)}"
        ) from None
