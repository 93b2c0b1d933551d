"""Explosives and their TNT equivalence, for pressure and for impulse separately.

The blast fits of :mod:`blastscale.blast` are for TNT. A charge of another explosive of mass m is
replaced by the TNT mass that produces the same peak overpressure (``m f_P``) or the same impulse
(``m f_I``): the two *equivalent load factors* of UFC 3-340-02 (2008), Table 2-1, which differ (C-4:
1.37 for pressure, 1.19 for impulse). blastscale uses each where it belongs:

* **impulse** for the specimen's charge: the general scaling law matches the impulse (paper Eq. 8),
  so the mass of the chosen explosive is the one whose *impulse* TNT equivalent equals the design's
  TNT charge, ``m = (W_TNT - W_init) / f_I``;
* **pressure** for the safety distances: the overpressure thresholds are peak pressures, so the
  charge that sets them is ``W_P = m f_P + W_init,P`` (the initiator by pressure; below).

The initiator (detonator, exploding bridgewire, primer) adds its own TNT-equivalent mass, by impulse
``W_init`` (the design's) and by pressure ``W_init,P`` (:func:`initiator_tnt_kg` of a named one: its
contents times their factors; a stated ``initiator_tnt_kg`` is both). Safety takes the **stricter
basis**: ``W_P = m f_P + max(W_init,P, W_init)`` and the safety mass
``W_S = max(W_P, W)`` (:attr:`ChargeEquivalence.tnt_equivalent_safety_kg`): the safety distances and
the licence limit never rest on the smaller equivalent. A design warns when the initiator exceeds
:data:`INITIATOR_WARNING_FRACTION` of the charge, because the initiator's own blast (and its casing's
fragments) then shape the load and its uncertainty.

The library of explosives (:data:`EXPLOSIVES`), its tables and the sources of every factor (UFC
3-340-02 (2008) Table 2-1, IATG 01.80, Meyer, Koehler & Homburg 2007, Cooper 1996, Bogosian et al. 2016):
:mod:`.explosive_library`.

Names are matched without regard to case, spaces, hyphens or underscores, with the usual aliases
(:data:`ALIASES`: "C4", "Composition C-4", "Comp B", ...). Each library entry carries its smallest
reliable charge (:mod:`.initiation`).
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from typing import Mapping, Optional

from .._validate import BlastscaleInputError, check_choice
from .explosive_library import EXPLOSIVES, Explosive
from .initiation import INITIATORS

__all__ = [
    "ChargeEquivalence",
    "INITIATOR_WARNING_FRACTION",
    "ALIASES",
    "canonical_name",
    "get_explosive",
    "charge_equivalence",
    "initiator_tnt_kg",
    "BASES",
]

#: Above this fraction of the charge's TNT equivalent (impulse basis) the initiator gets a warning.
INITIATOR_WARNING_FRACTION = 0.10

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


#: The bases of a TNT equivalence: by peak pressure, by impulse, and the stricter (larger) of the two.
BASES = ("pressure", "impulse", "strict")


def initiator_tnt_kg(name: str, basis: str = "impulse") -> float:
    """TNT-equivalent mass [kg] of the initiator ``name`` of :data:`~.initiation.INITIATORS`: the sum of
    its contents' masses times their factors for ``basis`` (``"impulse"``, ``"pressure"``, or
    ``"strict"``: the larger of the two, what safety uses).

    >>> round(initiator_tnt_kg("rp-80") * 1e6, 2), round(initiator_tnt_kg("rp-80", "pressure") * 1e6, 2)
    (222.87, 241.82)
    """
    check_choice("basis", basis, BASES)
    if basis == "strict":
        return max(initiator_tnt_kg(name, "pressure"), initiator_tnt_kg(name, "impulse"))
    attr = "impulse_factor" if basis == "impulse" else "pressure_factor"
    return float(sum(m * getattr(EXPLOSIVES[ex], attr) for ex, m in INITIATORS[name].contents))


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
        TNT equivalent of explosive + initiator for peak pressure [kg], the initiator on its stricter
        basis.
    initiator_fraction : float
        Initiator / total TNT equivalent (impulse basis) [-].
    warnings : tuple of str
    initiator_tnt_pressure_kg : float, optional
        The initiator's TNT-equivalent mass by pressure [kg] (None: as ``initiator_tnt_kg``).
    """

    explosive: Explosive
    explosive_mass_kg: float
    initiator_tnt_kg: float
    tnt_equivalent_impulse_kg: float
    tnt_equivalent_pressure_kg: float
    initiator_fraction: float
    warnings: tuple = ()
    initiator_tnt_pressure_kg: Optional[float] = None

    @property
    def tnt_equivalent_safety_kg(self) -> float:
        """The charge's TNT equivalent on the stricter basis [kg], initiator included: the larger of the
        pressure and impulse equivalents (the safety distances, the licence limit ``tnt_max_kg``)."""
        return max(self.tnt_equivalent_pressure_kg, self.tnt_equivalent_impulse_kg)

    def to_dict(self) -> dict:
        return {
            "explosive": self.explosive.name,
            "explosive_mass_kg": self.explosive_mass_kg,
            "initiator_tnt_kg": self.initiator_tnt_kg,
            "tnt_equivalent_impulse_kg": self.tnt_equivalent_impulse_kg,
            "tnt_equivalent_pressure_kg": self.tnt_equivalent_pressure_kg,
            "tnt_equivalent_safety_kg": self.tnt_equivalent_safety_kg,
            "initiator_tnt_pressure_kg": self._initiator_p,
            "pressure_factor": self.explosive.pressure_factor,
            "impulse_factor": self.explosive.impulse_factor,
            "initiator_fraction": self.initiator_fraction,
            "explosive_min_charge_kg": self.explosive.min_charge_kg,
            "min_charge_source": self.explosive.min_charge_source,
            "equivalence_source": self.explosive.source,
            "equivalence_uncertainty": self.explosive.uncertainty,
            "warnings": list(self.warnings),
        }

    @property
    def _initiator_p(self) -> float:
        return self.initiator_tnt_kg if self.initiator_tnt_pressure_kg is None else self.initiator_tnt_pressure_kg


def charge_equivalence(
    tnt_kg: float,
    explosive: "str | Explosive" = "tnt",
    initiator_tnt_kg: float = 0.0,
    custom: Optional[Mapping[str, Explosive]] = None,
    initiator_tnt_pressure_kg: Optional[float] = None,
) -> ChargeEquivalence:
    """The mass of ``explosive`` that, with the initiator, delivers the impulse of ``tnt_kg`` of TNT.

    .. math:: m = \\frac{W - W_{init}}{f_I}, \\qquad W_P = m f_P + \\max(W_{init,P}, W_{init})

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
    initiator_tnt_pressure_kg : float, optional
        The initiator's TNT-equivalent mass by pressure W_init,P [kg] (default: ``initiator_tnt_kg``);
        the pressure equivalent takes the larger of the two (the stricter basis).

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
    w0p = w0 if initiator_tnt_pressure_kg is None else float(initiator_tnt_pressure_kg)
    if not (math.isfinite(w0p) and w0p >= 0):
        raise BlastscaleInputError(
            f"initiator_tnt_pressure_kg = {initiator_tnt_pressure_kg!r} is out of range: must be >= 0 kg"
        )
    return ChargeEquivalence(
        ex, m, w0, W, m * ex.pressure_factor + max(w0p, w0), frac, tuple(notes), None if w0p == w0 else w0p
    )
