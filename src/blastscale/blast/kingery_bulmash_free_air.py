"""Kingery-Bulmash air-blast parameters of a *spherical* TNT free-air burst (UFC 3-340-02 Fig. 2-7).

A charge detonated away from any surface sends a spherical shock; the parameters of its positive
phase (side-on and normally reflected pressure and impulse, arrival time, positive duration) are
the Kingery & Bulmash (1984) spherical free-air fits, the curves of UFC 3-340-02 Fig. 2-7. They are
polynomials in ``U = K0 + K1 log10(Z)`` with Z in ft/lb^(1/3):

.. math:: \\log_{10} Y = \\sum_i C_i\\,U^i,

Y in psi (pressures), psi ms/lb^(1/3) (scaled impulses) and ms/lb^(1/3) (scaled times). The
coefficients are facts of Kingery & Bulmash (1984) as reprinted in the appendix of the CONWEP load
model (Randers-Pehrson & Bannister 1997, ARL-TR-1310); two independent public transcriptions of
them agree digit for digit (``docs/blast_physics.md`` names them). This module
keeps them in one constant, :data:`KB1984_FREE_AIR`, and converts to SI with exact factors
(1 ft = 0.3048 m, 1 lb = 0.45359237 kg, 1 psi = 6894.757293168 Pa).

The shock-front velocity of the free-air fits is not part of that set: it is Rankine-Hugoniot's
``U = c0 sqrt(1 + 6 P_so / (7 p0))`` of the fitted P_so (:func:`.air.shock_velocity`), the relation
the surface-burst fit's tabulated U follows within 4.1 % (docs/blast_models.md).

Validity ranges (Z in m/kg^(1/3), the metric ranges stated with the coefficients): every quantity
over [0.0531, 40] except the positive duration, [0.147, 40] (its first piece starts at 0.370 ft/lb^(1/3)).
Pieces: incident impulse at Z = 2 ft/lb^(1/3) (0.793 m/kg^(1/3)); positive duration at 2.24 and
5.75 ft/lb^(1/3) (0.889, 2.281 m/kg^(1/3)); a point on a boundary belongs to the lower piece.

Checks (``tests/unit/blast/test_free_air.py``, ``docs/blast_physics.md``): against 98 digitised
points of UFC Fig. 2-7 (``tests/data/ufc_3_340_02_fig2_7.csv``); the same code with Kingery &
Bulmash's *surface-burst* coefficients reproduces the Swisdak (1994) surface fit of
:mod:`.kingery_bulmash` (an independent check of the form and of the unit conversion).

References
----------
.. [1] Kingery, C. N. & Bulmash, G. (1984). *Airblast parameters from TNT spherical air burst and
       hemispherical surface burst*. ARBRL-TR-02555, Ballistic Research Laboratory.
.. [2] Randers-Pehrson, G. & Bannister, K. A. (1997). *Airblast loading model for DYNA2D and
       DYNA3D*. ARL-TR-1310, Army Research Laboratory (the CONWEP polynomials).
.. [3] UFC 3-340-02 (2008). *Structures to Resist the Effects of Accidental Explosions*, Fig. 2-7.
"""

from __future__ import annotations

import math

import numpy as np

from .air import shock_velocity
from .base import BlastModel

__all__ = ["KingeryBulmashFreeAir", "KB1984_FREE_AIR", "FREE_AIR_MODEL", "kb1984_evaluate", "Z_FT_PER_M", "KB_UNITS"]

#: Name of the spherical free-air fit (``blast_model`` of its results).
FREE_AIR_MODEL = "kingery-bulmash-free-air"

_LB13 = 0.45359237 ** (1.0 / 3.0)
#: Z [ft/lb^(1/3)] per Z [m/kg^(1/3)] (exact unit factors).
Z_FT_PER_M = (1.0 / 0.3048) * _LB13
_PSI = 6894.757293168361

#: Factor from Kingery-Bulmash's imperial unit of each quantity to SI.
KB_UNITS = {
    "incident_pressure": _PSI,  # psi -> Pa
    "reflected_pressure": _PSI,
    "scaled_incident_impulse": _PSI * 1e-3 / _LB13,  # psi ms/lb^(1/3) -> Pa s/kg^(1/3)
    "scaled_reflected_impulse": _PSI * 1e-3 / _LB13,
    "scaled_arrival_time": 1e-3 / _LB13,  # ms/lb^(1/3) -> s/kg^(1/3)
    "scaled_positive_duration": 1e-3 / _LB13,
}

#: Kingery & Bulmash (1984) spherical free-air coefficients (ARL-TR-1310 appendix, imperial units):
#: ``quantity -> ((upper log10 Z_ft of the piece, (K0, K1), (C0, C1, ...)), ...)``, pieces in
#: increasing Z (the last upper bound inf); ``log10 Y = sum C_i U^i``, ``U = K0 + K1 log10 Z_ft``.
KB1984_FREE_AIR: dict = {
    "incident_pressure": (
        (
            math.inf,
            (-0.756579301809, 1.35034249993),
            (
                1.77284970457,
                -1.69012801396,
                0.00804973591951,
                0.336743114941,
                -0.00516226351334,
                -0.0809228619888,
                -0.00478507266747,
                0.00793030472242,
                0.0007684469735,
            ),
        ),
    ),
    "reflected_pressure": (
        (
            math.inf,
            (-0.756579301809, 1.35034249993),
            (
                2.39106134946,
                -2.21400538997,
                0.035119031446,
                0.657599992109,
                0.0141818951887,
                -0.243076636231,
                -0.0158699803158,
                0.0492741184234,
                0.00227639644004,
                -0.00397126276058,
            ),
        ),
    ),
    "scaled_arrival_time": (
        (
            math.inf,
            (-0.80501734056, 1.37407043777),
            (
                -0.0423733936826,
                1.36456871214,
                -0.0570035692784,
                -0.182832224796,
                0.0118851436014,
                0.0432648687627,
                -0.0007997367834,
                -0.00436073555033,
            ),
        ),
    ),
    "scaled_reflected_impulse": (
        (
            math.inf,
            (-0.757659920369, 1.37882996018),
            (1.60579280091, -0.903118886091, 0.101771877942, -0.0242139751146),
        ),
    ),
    "scaled_incident_impulse": (
        (
            0.30103,
            (1.04504877747, 3.24299066475),
            (1.43534136453, -0.443749377691, 0.168825414684, 0.0348138030308, -0.010435192824),
        ),
        (
            math.inf,
            (-2.67912519532, 2.30629231803),
            (
                0.599008468099,
                -0.40463292088,
                -0.0142721946082,
                0.00912366316617,
                -0.0006750681404,
                -0.00800863718901,
                0.00314819515931,
                0.00152044783382,
                -0.0007470265899,
            ),
        ),
    ),
    "scaled_positive_duration": (
        (
            0.350248,
            (0.209440059933, 5.11588554305),
            (
                -0.801052722864,
                0.164953518069,
                0.127788499497,
                0.00291430135946,
                0.00187957449227,
                0.0173413962543,
                0.00269739758043,
                -0.00361976502798,
                -0.00100926577934,
            ),
        ),
        (
            0.7596678,
            (-5.06778493835, 9.2996288611),
            (
                0.115874238335,
                -0.0297944268969,
                0.0306329542941,
                0.018340557407,
                -0.0173964666286,
                -0.00106321963576,
                0.0056206003128,
                0.0001618217499,
                -0.0006860188944,
            ),
        ),
        (
            math.inf,
            (-4.39590184126, 3.1524725264),
            (
                0.50659210403,
                0.0967031995552,
                -0.00801302059667,
                0.00482705779732,
                0.00187587272287,
                -0.00246738509321,
                -0.000841116668,
                0.0006193291052,
            ),
        ),
    ),
}

_ZMIN, _ZMAX = 0.0531, 40.0  # m/kg^(1/3): 0.134-100.8 ft/lb^(1/3)


def kb1984_evaluate(pieces, z_m) -> np.ndarray:
    """Kingery-Bulmash polynomial of ``pieces`` (the form of :data:`KB1984_FREE_AIR`) at Z [m/kg^(1/3)],
    in the fit's imperial unit (no range check): the piece is chosen by log10 Z_ft (a point on a
    boundary belongs to the lower piece), then ``10 ** sum(C_i U^i)``, ``U = K0 + K1 log10 Z_ft``."""
    zl = np.log10(np.asarray(z_m, dtype=float) * Z_FT_PER_M)
    out = np.empty_like(zl)
    lower = -np.inf
    for upper, (k0, k1), coefs in pieces:
        sel = (zl > lower) & (zl <= upper)
        if np.any(sel):
            out[sel] = np.polynomial.polynomial.polyval(k0 + k1 * zl[sel], coefs)
        lower = upper
    return 10.0**out


class KingeryBulmashFreeAir(BlastModel):
    """Kingery-Bulmash spherical free-air burst (``"kingery-bulmash-free-air"``, module docstring).

    Everything in SI: P_so, P_r [Pa]; i_s/W^(1/3), i_r/W^(1/3) [Pa s/kg^(1/3)]; t_A/W^(1/3),
    t_o/W^(1/3) [s/kg^(1/3)]; U [m/s] (Rankine-Hugoniot of P_so). Chosen by ``burst = "free-air"``
    (:func:`blastscale.blast.parameters.model_for_burst`), not by a ``blast_model`` name.

    References: Kingery & Bulmash (1984); Randers-Pehrson & Bannister (1997), ARL-TR-1310;
    UFC 3-340-02 (2008) Fig. 2-7.
    """

    name = FREE_AIR_MODEL
    burst = "free-air"
    family = "kingery-bulmash"
    ranges = {q: (_ZMIN, _ZMAX) for q in KB1984_FREE_AIR}
    ranges["scaled_positive_duration"] = (0.147, _ZMAX)  # 0.370 ft/lb^(1/3)
    ranges["shock_front_velocity"] = (_ZMIN, _ZMAX)

    def _raw(self, quantity: str, z: np.ndarray) -> np.ndarray:
        if quantity == "shock_front_velocity":
            return np.asarray(shock_velocity(self._raw("incident_pressure", z)), dtype=float)
        return kb1984_evaluate(KB1984_FREE_AIR[quantity], z) * KB_UNITS[quantity]
