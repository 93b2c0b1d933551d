"""The paper's numbers that ``blastscale reproduce`` computes directly, each a list of :class:`Row`.

The geometry of the prototype and models 1, 2 (Table "Geometry parameters"), the Table "Blast loading
characteristics", the scaling factors quoted with Figures 5 and 8, and the critical charge of the slender block
at 2 m (case c): each ``compute(folder, quick)`` of an :class:`~blastscale.report.reproduce.Item`, computed with
the library (:func:`blastscale.similitude.design_model`, :func:`blastscale.rocking.critical_charge`) and put
beside the value the paper prints. Lengths, charges and ratios in the unit of each row.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Optional

from ..similitude import design_model
from ..structures import RectangularBlock
from ..blast.load_model import LoadModel

__all__ = ["Row"]


@dataclass(frozen=True)
class Row:
    """One number of the paper beside blastscale's.

    Attributes
    ----------
    quantity : str
    paper : str
        As printed (text, with its printed unit), or "" when the paper gives no number.
    ours : float or str
    unit : str
        Unit of ``ours``.
    slip : int or None
        Row of docs/paper_slips.md explaining a difference.
    """

    quantity: str
    paper: str
    ours: object
    unit: str = ""
    slip: Optional[int] = None


# -- numbers computed directly ---------------------------------------------------------------
_CHARGES = {"a": 50.0, "b": 100.0, "c": 79.8}
_PAPER_TABLE = {  # paper Table "Blast loading characteristics": (Z_p, W_m1 "mg", Z_m1, W_m2 "ug", Z_m2)
    "a": ("0.54", "1.0 mg", "0.99", "0.233 ug", "1.62"),
    "b": ("0.43", "2.06 mg", "0.78", "0.492 ug", "1.26"),
    "c": ("0.46", "1.635 mg", "0.85", "0.386 ug", "1.37"),
}


def _geometry(folder: Path, quick: bool) -> list:

    block = RectangularBlock.from_slenderness(10.0, math.radians(15.0), density=2000.0)
    rows = [Row("prototype width 2b", "2.68 m", block.width, "m")]
    for lam, tag, paper in ((1 / 20, "model 1", ("50", "13.40", "10")), (1 / 200, "model 2", ("5", "1.34", "1"))):
        d = design_model(50.0, 2.0, lam, 1.0, blast_model="masi2021", geometry=block)
        mb = d.specimen_block
        rows += [
            Row(f"{tag} height", f"{paper[0]} cm", mb.height * 100, "cm"),
            Row(f"{tag} width", f"{paper[1]} cm", mb.width * 100, "cm"),
            Row(f"{tag} stand-off", f"{paper[2]} cm", d.specimen_standoff_m * 100, "cm"),
        ]
    return rows


def _blast_loading(folder: Path, quick: bool) -> list:

    rows = []
    for case, W in _CHARGES.items():
        zp, w1, z1, w2, z2 = _PAPER_TABLE[case]
        d1 = design_model(W, 2.0, 1 / 20, 1.0, blast_model="masi2021")
        d2 = design_model(W, 2.0, 1 / 200, 1.0, blast_model="masi2021")
        rows += [
            Row(f"({case}) W_p = {W:g} kg: Z_p", zp, d1.prototype.scaled_distance, "m/kg^(1/3)"),
            Row(f"({case}) model 1 (1/20) charge", w1, d1.specimen_charge_kg * 1e3, "g", 4),
            Row(f"({case}) model 1 Z", z1, d1.specimen.scaled_distance, "m/kg^(1/3)"),
            Row(f"({case}) model 2 (1/200) charge", w2, d2.specimen_charge_kg * 1e6, "mg", 4),
            Row(f"({case}) model 2 Z", z2, d2.specimen.scaled_distance, "m/kg^(1/3)"),
        ]
    ns = design_model(2500.0, 3.0, 1 / 200, 1.0, blast_model="masi2021")
    rows.append(Row("non-slender 2500 kg at 3 m: model charge (1/200)", "14.26 mg", ns.specimen_charge_kg * 1e6, "mg"))
    return rows


def _scaling_factors(folder: Path, quick: bool) -> list:

    d = design_model(50.0, 2.0, 1 / 200, 1.0, blast_model="masi2021")
    d05 = design_model(50.0, 2.0, 1 / 200, 0.05, blast_model="masi2021")
    return [
        Row("Fig. 5: pressure ratio, lambda = 1/200, gamma = 1", "5.8 %", d.pressure_ratio * 100, "%"),
        Row("Fig. 5: impulse ratio, general law", "0.3 %", d.impulse_ratio * 100, "%", 5),
        Row("Fig. 5: impulse ratio, Hopkinson-Cranz (= lambda)", "5 %", 100 / 200, "%", 5),
        Row("Fig. 8: pressure ratio, lambda = 1/200, gamma = 0.05", "0.18 %", d05.pressure_ratio * 100, "%"),
        Row("lambda_Z at lambda = 1/200 (Fig. 5b)", "", d.scaled_distance_factor, "-"),
    ]


def _critical(folder: Path, quick: bool) -> list:
    from ..analysis.planar import critical_of  # noqa: PLC0415 -- start-up: at module top `blastscale` would load numba, scipy

    block = RectangularBlock.from_slenderness(10.0, math.radians(15.0), density=2000.0)

    c = critical_of(block, standoff=2.0, blast_model="masi2021")
    neg = critical_of(block, standoff=2.0, blast_model="masi2021", load_model=LoadModel(negative_phase=True))
    return [
        Row("critical charge at 2 m (case c)", "79.8 kg", c.charge_kg, "kg"),
        Row(
            "the same with the negative phase (the paper neglects it; docs/blast_physics.md)",
            'larger ("stabilizing")',
            neg.charge_kg,
            "kg",
        ),
    ]
