"""Does the specimen's joint friction keep the prototype's way of moving? Rocking vs sliding thresholds.

Rigid-body similitude requires the friction coefficient itself to be the same (pi_21 = mu, paper
Eq. 5: lambda_mu = 1). A specimen of another material has its own friction (the library's,
:mod:`blastscale.structures.materials`), so lambda_mu = mu_s / mu_p differs from 1 and the question
becomes whether the specimen still moves as the prototype does. For a rectangular block of width B
and height H (half-widths b = B/2, h = H/2, R^2 = b^2 + h^2) two closed-form thresholds decide it:

* the impulsive threshold. A horizontal impulse J on the loaded face at height z, the block pivoting on
  its far base corner: the angular momentum about the pivot gives J z = I_O omega with
  I_O = (4/3) m R^2, the centre of mass moves at omega (h, b), and the base's impulsive reactions are
  R_H = J (3 h z / (4 R^2) - 1) and R_V = J 3 b z / (4 R^2). The corner does not slip while
  |R_H| <= mu R_V, i.e. while

      mu >= mu_i = |4 R^2 - 3 h z| / (3 b z),

  and for the face's resultant at mid-height (z = h, a uniform face load) mu_i = (4 B^2 + H^2) / (3 B H);
* the static threshold mu_s = B / H = tan(alpha): a block sliding on its base is tipped by the
  friction's moment only when mu > B / H (Ishiyama 1982; Shenton 1996: rocking vs sliding initiation).

They define three regimes: ``"rocks"`` (mu >= mu_i: no slip, the planar rocking model's assumption),
``"slides and rocks"`` (B/H < mu < mu_i: slips under the pulse, then rocks), ``"slides"``
(mu <= B/H). The check passes when the specimen's friction lies in the prototype's regime. Within one
regime the planar rocking answer does not depend on mu (the 3D engine, which has friction, sees the
rest: the specimen's 3D contacts carry the specimen's friction, lambda_mu x the prototype's).

The paper's slender block (alpha = 15 deg): B / H = 0.268, mu_i = 1.60; every library material (0.4 to
1.05) lies with the stone's 0.7 in "slides and rocks". A squat block B / H = 0.6 (mu_i = 1.36): stone
(0.7) slides and rocks, balsa (0.4) slides: balsa is refused.

References: Ishiyama, Y. (1982), Motions of rigid bodies and criteria for overturning by earthquake
excitations, Earthq. Eng. Struct. Dyn. 10, 635-650; Shenton, H. W. (1996), Criteria for initiation of
slide, rock, and slide-rock rigid-body modes, J. Eng. Mech. 122(7), 690-693.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass
from typing import Optional

from .._validate import check_positive_scalar

__all__ = ["FRICTION_REGIMES", "FrictionCheck", "sliding_thresholds", "friction_regime", "friction_check"]

#: The regimes of a block under a face impulse, from the most friction to the least.
FRICTION_REGIMES = ("rocks", "slides and rocks", "slides")


def sliding_thresholds(width: float, height: float, load_height: Optional[float] = None) -> tuple:
    """(static B / H, impulsive mu_i) of a block of ``width`` B and ``height`` H [m] under a face impulse
    at ``load_height`` z [m] (default H / 2) (module docstring) [-].

    Examples
    --------
    >>> [round(x, 4) for x in sliding_thresholds(1.0, 2.0)]   # B/H = 0.5, mu_i = (4 + 4) / 6
    [0.5, 1.3333]
    """
    B, H = check_positive_scalar("width", width, "m"), check_positive_scalar("height", height, "m")
    b, h = 0.5 * B, 0.5 * H
    z = h if load_height is None else check_positive_scalar("load height", load_height, "m")
    return b / h, abs(4.0 * (b * b + h * h) - 3.0 * h * z) / (3.0 * b * z)


def friction_regime(friction: float, width: float, height: float, load_height: Optional[float] = None) -> str:
    """The regime of a block with friction ``friction`` [-] (:data:`FRICTION_REGIMES`)."""
    static, impulsive = sliding_thresholds(width, height, load_height)
    mu = float(friction)
    return "rocks" if mu >= impulsive else "slides and rocks" if mu > static else "slides"


@dataclass(frozen=True)
class FrictionCheck:
    """The friction check of a specimen against its prototype: ``ok`` (same regime), ``reason`` (one
    line), both frictions and their ratio lambda_mu, both regimes and the two thresholds [-]."""

    ok: bool
    reason: str
    prototype_friction: float
    specimen_friction: float
    friction_ratio: float
    prototype_regime: str
    specimen_regime: str
    static_threshold: float
    impulsive_threshold: float

    def to_dict(self) -> dict:
        return asdict(self)


def friction_check(
    prototype_friction: float, specimen_friction: float, width: float, height: float, load_height=None
) -> FrictionCheck:
    """Whether a specimen of friction ``specimen_friction`` moves in the regime of its prototype of friction
    ``prototype_friction`` [-], both blocks of aspect ``width`` / ``height`` (any unit: the regimes
    depend on the aspect alone; module docstring).

    Examples
    --------
    >>> print(friction_check(0.7, 0.4, 0.6, 1.0).reason)  # doctest: +NORMALIZE_WHITESPACE
    friction 0.4 (x0.571 the prototype's 0.7): the specimen slides where the prototype slides and rocks
    (thresholds: tipping B/H = 0.6, no slip under the pulse 1.36)
    >>> friction_check(0.7, 0.4, 0.268, 1.0).ok
    True
    """
    mp, ms = (
        check_positive_scalar("prototype friction", prototype_friction),
        check_positive_scalar("specimen friction", specimen_friction),
    )
    static, impulsive = sliding_thresholds(width, height, load_height)
    rp, rs = (friction_regime(m, width, height, load_height) for m in (mp, ms))
    ok = rp == rs
    reason = (
        f"friction {ms:.3g} (x{ms / mp:.3g} the prototype's {mp:.3g}): the specimen "
        + (f"{rs} as the prototype does" if ok else f"{rs} where the prototype {rp}")
        + f" (thresholds: tipping B/H = {static:.3g}, no slip under the pulse {impulsive:.3g})"
    )
    return FrictionCheck(ok, reason, mp, ms, ms / mp, rp, rs, static, impulsive)
