"""Burst types: a charge on the ground (hemispherical surface burst) or away from it (spherical free-air
burst), the fit of each, how they compare, and whether a charge at a given height is either.

* ``"surface"`` (the paper's): the charge lies on the ground, which reflects the shock at once; the
  hemispherical surface-burst fits (Kingery-Bulmash, Swisdak 1994; or the paper's Appendix A fits).
* ``"free-air"``: the charge is far enough from every surface that the ground reflection reaches the
  target after the positive phase; the spherical free-air fits (Kingery-Bulmash 1984, UFC 3-340-02
  Fig. 2-7; :mod:`.kingery_bulmash_free_air`). The paper's fits have no free-air form.

A surface burst of W is often equated with a free-air burst of about 1.8 W (UFC 3-340-02 Sec. 2-13:
a perfectly reflecting ground would double the charge, cratering and heating take some of it);
:func:`equivalent_free_air_charge_ratio` measures the ratio over Z for each quantity instead of
assuming it (``docs/blast_physics.md`` tabulates it): 1.79-1.82 for the impulses, 1.29-2.12 for the peak
pressures. The safety envelope (:mod:`.safety`, ``SURFACE_BURST_FACTOR`` = 1.8) takes the lab charge
as a surface burst, the conservative case for a charge near the floor (the far field of a charge on a
low stand is a ground burst's too), whatever burst the design assumes for the specimen's face.

A charge on a stand at height H_c above the floor is *neither* when the floor's reflection reaches
the loaded face within the positive phase: the face then sees two shocks. :func:`lab_burst` compares
the delay of the reflected shock (image charge at -H_c, free-air arrival times along both paths, the
face's mid-height as the target point) with the positive duration there: a delay of at least t_o is
a free-air burst, one within :data:`SURFACE_DELAY_FRACTION` of t_o a surface burst (the two shocks
merge within the first tenth of the pulse; our criterion, not UFC's), anything between neither.

References
----------
.. [1] UFC 3-340-02 (2008), Sec. 2-13 and Figs. 2-7, 2-15.
.. [2] Kingery, C. N. & Bulmash, G. (1984). ARBRL-TR-02555.
.. [3] Baker, W. E. (1973). *Explosions in Air*, ch. 6 (image charge of a reflecting ground).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .._validate import BlastscaleInputError, check_choice, check_positive, check_positive_scalar
from .inverse import charge_for, scaled_distance_for
from .parameters import get_blast_model

__all__ = [
    "equivalent_free_air_charge_ratio",
    "LabBurst",
    "lab_burst",
    "SURFACE_DELAY_FRACTION",
    "EQUIVALENCE_QUANTITIES",
]

#: A charge counts as a surface burst when the floor's reflection arrives within this fraction of
#: the positive duration (our criterion, module docstring).
SURFACE_DELAY_FRACTION = 0.1

#: Quantities compared by :func:`equivalent_free_air_charge_ratio` (scaled impulses are compared as
#: impulses at the same distance).
EQUIVALENCE_QUANTITIES = (
    "incident_pressure",
    "reflected_pressure",
    "scaled_incident_impulse",
    "scaled_reflected_impulse",
)


def equivalent_free_air_charge_ratio(scaled_distance, quantity: str = "incident_pressure") -> np.ndarray:
    """W_free / W_surface: the free-air charge that gives, at the same distance, the same ``quantity``
    as a surface burst at scaled distance Z (Kingery-Bulmash fits of both).

    With ``Z_f = Z k^(-1/3)`` the free-air burst's scaled distance, ``k`` solves
    ``P_f(Z_f) = P_s(Z)`` for a pressure and ``i_f(Z_f) Z / Z_f = i_s(Z)`` for a scaled impulse
    (impulses at the same distance: ``i = W^(1/3) i_hat``). Constant 2 would be a perfectly
    reflecting ground; UFC 3-340-02 Sec. 2-13 uses 1.8.

    Parameters
    ----------
    scaled_distance : float or array_like
        Z of the surface burst [m/kg^(1/3)], inside the surface fit's range of ``quantity``.
    quantity : str
        One of :data:`EQUIVALENCE_QUANTITIES`.

    Returns
    -------
    float or ndarray
        k [-] (NaN where the free-air fit's range holds no solution).
    """
    check_choice("quantity", quantity, EQUIVALENCE_QUANTITIES)
    z = np.atleast_1d(check_positive("scaled distance Z", scaled_distance, "m/kg^(1/3)")).astype(float)
    surf, free = get_blast_model("kingery-bulmash"), get_blast_model("kingery-bulmash-free-air")
    target = getattr(surf, quantity)(z)
    # a scaled impulse is the impulse of 1 kg at the distance Z: the free-air charge that gives it there
    inverted = quantity.removeprefix("scaled_")
    if quantity.startswith("scaled"):
        k = charge_for(target, z, inverted, free, outside="nan")
    else:
        k = (z / scaled_distance_for(target, inverted, free, outside="nan")) ** 3
    return k if np.ndim(scaled_distance) else float(k[0])


@dataclass(frozen=True)
class LabBurst:
    """Whether a charge at a height above a reflecting floor loads a face as a surface or a free-air burst.

    Attributes
    ----------
    kind : str
        ``"surface"``, ``"free-air"`` or ``"neither"`` (module docstring).
    charge_height_m, target_height_m : float
        Height of the charge's centre and of the target point (the face's mid-height) [m].
    reflection_delay_s : float
        Arrival of the floor's reflection after the direct shock at the target point [s].
    positive_duration_s : float
        Positive duration of the direct shock there [s].
    """

    kind: str
    charge_height_m: float
    target_height_m: float
    reflection_delay_s: float
    positive_duration_s: float

    @property
    def delay_ratio(self) -> float:
        """Reflection delay over the positive duration [-]."""
        return self.reflection_delay_s / self.positive_duration_s

    def to_dict(self) -> dict:
        return {
            "kind": self.kind,
            "charge_height_m": self.charge_height_m,
            "target_height_m": self.target_height_m,
            "reflection_delay_s": self.reflection_delay_s,
            "positive_duration_s": self.positive_duration_s,
            "delay_over_positive_duration": self.delay_ratio,
        }


def lab_burst(
    charge: float, standoff: float, charge_height: float, face_height: float, *, extrapolate: bool = False
) -> LabBurst:
    """Classify a charge ``charge`` [kg] at ``charge_height`` [m] above the floor, ``standoff`` [m]
    (horizontal) from a face ``face_height`` [m] tall standing on the floor (module docstring).

    The direct path runs from the charge to the face's mid-height, the reflected one from the
    image charge at ``-charge_height``; both arrival times and the direct positive duration are the
    free-air fit's. A charge on the floor (height 0) is a surface burst.
    """
    W = check_positive_scalar("charge", charge, "kg")
    R = check_positive_scalar("standoff", standoff, "m")
    H = check_positive_scalar("face height", face_height, "m")
    hc = float(charge_height)
    if not (math.isfinite(hc) and hc >= 0.0):
        raise BlastscaleInputError(f"charge height = {charge_height!r} m is out of range: must be >= 0 m")
    ht = 0.5 * H
    if hc == 0.0:
        return LabBurst("surface", 0.0, ht, 0.0, float("nan"))
    m = get_blast_model("kingery-bulmash-free-air")
    w13 = W ** (1.0 / 3.0)
    d = math.hypot(R, hc - ht)
    r = math.hypot(R, hc + ht)
    ta = m.scaled_arrival_time(np.array([d, r]) / w13, extrapolate=extrapolate) * w13
    to = float(m.scaled_positive_duration(d / w13, extrapolate=extrapolate)) * w13
    delay = float(ta[1] - ta[0])
    kind = "free-air" if delay >= to else ("surface" if delay <= SURFACE_DELAY_FRACTION * to else "neither")
    return LabBurst(kind, hc, ht, delay, to)
