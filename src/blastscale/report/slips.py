"""The paper's known slips (docs/paper_slips.md), with the rule that says when one applies.

Each :class:`Slip` has the number of its row in ``docs/paper_slips.md``, a one-line statement
of what the printed paper says and what blastscale does, and ``applies(scenario, design)``:
whether a reader of a report for that scenario should know it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

__all__ = ["Slip", "SLIPS", "applicable_slips"]


@dataclass(frozen=True)
class Slip:
    """One known slip of the paper.

    Attributes
    ----------
    number : int
        Row of docs/paper_slips.md.
    where : str
        Where in the paper.
    text : str
        What is printed and what blastscale does instead (one sentence).
    applies : callable
        ``applies(scenario, design) -> bool``.
    """

    number: int
    where: str
    text: str
    applies: Callable


def _masi(sc, d) -> bool:
    return sc.blast.blast_model == "masi2021"


def _near(x: float, y: float, rel: float = 1e-3) -> bool:
    return abs(x - y) <= rel * abs(y)


def _scaled(sc, d) -> bool:
    """A specimen is designed (the slips of the scaling law concern it)."""
    return sc.scale is not None


def _paper_scale(sc, d) -> bool:
    return _scaled(sc, d) and any(_near(sc.scale.length, v) for v in (1 / 20, 1 / 200))


def _block(sc, d) -> bool:
    return sc.structure.kind == "block"


def _non_slender(sc, d) -> bool:
    s = sc.structure
    if s.kind != "block":
        return False
    alpha = s.alpha_deg if s.alpha_deg is not None else math.degrees(math.atan(s.width_m / s.height_m))
    return abs(alpha - 35.0) < 0.5 or (s.width_m is not None and _near(s.width_m, 3.5) and _near(s.height_m, 10.0))


def _sliding(sc, d) -> bool:
    return _block(sc, d) and _near(sc.blast.charge_kg, 2500.0) and _near(sc.blast.standoff_m, 3.0)


#: The slips, in the order of docs/paper_slips.md.
SLIPS: tuple[Slip, ...] = (
    Slip(
        1,
        "Appendix A units",
        "the fits' units are not stated: P_ro in MPa, i_rw in MPa ms/kg^(1/3), t_Aw and "
        "t_ow in ms/kg^(1/3) reproduce the paper",
        _masi,
    ),
    Slip(
        2,
        "Appendix A, t_ow",
        "the duration fit holds only for Z <= ~6.5 m/kg^(1/3); blastscale refuses it above unless extrapolate = true",
        _masi,
    ),
    Slip(
        3,
        "Appendix A, t_ow below Z = 0.18",
        "the constant does not join its own formula (6.7 % jump); used only with extrapolate = true",
        lambda sc, d: _masi(sc, d) and sc.blast.extrapolate,
    ),
    Slip(
        4,
        'Table "Blast loading characteristics"',
        "model charges printed in mg (lambda = 1/20) and ug "
        "(1/200) are in g and mg: the mantissas are right, the units off by 1000",
        _paper_scale,
    ),
    Slip(
        5,
        "Text near Fig. 5",
        'the model impulse percentages "0.3 %" and "5 %" at lambda = 1/200 are 10x '
        "the law's gamma lambda^(3/2) = 0.035 % and lambda = 0.5 %",
        lambda sc, d: _scaled(sc, d) and _near(sc.scale.length, 1 / 200),
    ),
    Slip(
        6,
        "Eq. (3), triangular pulse",
        "the triangle must end at 2 i_ro / P_ro, not t_o, to carry the impulse",
        lambda sc, d: sc.blast.pulse_shape == "triangular",
    ),
    Slip(
        7,
        "Tables 1 and 2",
        "the linear and angular acceleration factors are swapped: linear acceleration "
        "scales as varsigma, angular acceleration as varsigma / lambda",
        _scaled,
    ),
    Slip(
        8,
        "Eq. for lambda_t",
        "lambda_t = sqrt(lambda / varsigma), not sqrt(varsigma lambda) (identical for varsigma = 1)",
        lambda sc, d: _scaled(sc, d) and not _near(sc.scale.gravity_ratio, 1.0),
    ),
    Slip(
        9,
        '"pi_23 << 1" as the impulsive criterion',
        "not literally true (peak force >> weight); the "
        "meaningful check is t_o p << 1, reported in the impulsive check",
        _scaled,
    ),
    Slip(
        10,
        'FE section, "first impact at 1.3 ms"',
        "the prototype's first impact is at about 1.38 s",
        lambda sc, d: _block(sc, d) and _near(sc.structure.height_m, 10.0),
    ),
    Slip(
        11,
        'Sec. "Non-slender blocks" geometry',
        "2h = 10 m with 2b = 3.5 m gives alpha = 19.3 deg, while alpha = 35 deg needs 2b = 7.0 m: both readings exist",
        _non_slender,
    ),
    Slip(
        12,
        'Sec. "Non-slender blocks", sliding "approximately 1 m"',
        "momentum balance (and MuJoCo) give a "
        "much longer slide for 2500 kg at 3 m (5.6 m to 22 m depending on the geometry reading)",
        _sliding,
    ),
    Slip(13, "density units", 'printed "kg m^-1/3"; densities are in kg/m^3', lambda sc, d: True),
)


def applicable_slips(scenario, design=None) -> list[Slip]:
    """The slips a report for ``scenario`` should mention."""
    return [s for s in SLIPS if s.applies(scenario, design)]
