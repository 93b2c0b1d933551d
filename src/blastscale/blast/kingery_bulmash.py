"""Kingery-Bulmash air-blast parameters of a hemispherical TNT surface burst (Swisdak 1994).

Kingery & Bulmash (1984) fitted polynomials in log Z to the air-blast data of TNT charges;
Swisdak (1994) refitted them in a simpler form (fewer terms, natural logarithms):

.. math::

    Y(Z) = \\exp\\left(A + B\\,\\ln Z + C\\,\\ln^2 Z + D\\,\\ln^3 Z + E\\,\\ln^4 Z
    + F\\,\\ln^5 Z + G\\,\\ln^6 Z\\right),

piecewise in the Hopkinson-Cranz scaled distance :math:`Z = R / W^{1/3}` [m/kg^(1/3)]
(charge W in kg TNT, stand-off R in m). Swisdak's *metric* tables give Y in

* kPa for the incident (side-on) and normally reflected peak overpressures P_so, P_r,
* kPa*ms/kg^(1/3) for the scaled incident and reflected impulses i_s/W^(1/3), i_r/W^(1/3),
* ms/kg^(1/3) for the scaled arrival time t_A/W^(1/3) and positive duration t_o/W^(1/3),
* m/ms (= km/s) for the shock-front velocity U.

This module keeps the coefficients in one constant, :data:`SWISDAK_1994_COEFFICIENTS`, in
those units, and :class:`KingeryBulmash` converts the results to SI (Pa, Pa*s/kg^(1/3),
s/kg^(1/3), m/s), as required by :class:`~blastscale.blast.base.BlastModel`.

Validity ranges (Z in m/kg^(1/3); the union of Swisdak's pieces for each quantity)
-------------------------------------------------------------------------------------
================================  ================  ======================
quantity                          Z range           piece boundaries
================================  ================  ======================
incident_pressure                 0.2 - 198.5       2.9, 23.8
reflected_pressure                0.06 - 40         2.0
scaled_incident_impulse           0.2 - 158.7       0.96, 2.38, 33.7
scaled_reflected_impulse          0.06 - 40         (one piece)
scaled_arrival_time               0.06 - 40         1.5
scaled_positive_duration          0.2 - 40          1.02, 2.8
shock_front_velocity              0.06 - 40         1.5
================================  ================  ======================

A point exactly on a boundary belongs to the lower piece. The pieces do not join exactly:
the largest relative jump across a boundary is 2.4 % (incident impulse at Z = 2.38), then
1.2 % and 0.9 % (positive duration at Z = 1.02 and 2.8), 0.7 % (incident pressure at
Z = 23.8, upwards), all others below 0.25 %; see ``docs/blast_models.md`` and
``tests/unit/blast/test_kingery_bulmash.py::test_piece_boundaries_join_within_published_accuracy``.

Cross-checks (``tests/unit/blast/test_kingery_bulmash.py``, ``docs/blast_models.md``)
----------------------------------------------------------------------------
* UFC 3-340-02 Fig. 2-15 (positive-phase parameters of a hemispherical TNT surface
  burst), 96 digitised points in ``tests/data/ufc_3_340_02_fig2_15.csv`` over
  Z = 0.067-38: P_so, P_r, i_s, i_r, t_A, t_o all agree within 3.4 % (largest: P_r +3.3 %
  at Z = 37.9, P_so +3.3 % at Z = 37.8).
* The paper's Appendix A fits (:mod:`blastscale.blast.masi_fits`), themselves fitted to
  Kingery-Bulmash: P_r within 7.0 %, i_r within 8.6 %, t_A within 7.6 % over Z = 0.2-20;
  t_o within 9.2 % over Z = 0.2-6.5.
* The shock-front velocity agrees with Rankine-Hugoniot applied to P_so,
  U = c0 sqrt(1 + 6 P_so / (7 p0)) with c0 = 340.3 m/s, p0 = 101325 Pa, within 4.1 %
  (Z = 0.2-40).

Coefficient provenance
----------------------
The numbers are facts from Swisdak's Tables (metric units, hemispherical surface burst). The
sign of D in the reflected-impulse polynomial is -0.01123: the highest-order coefficient of a
polynomial in ln Z is unchanged by the unit change ft/lb^(1/3) -> m/kg^(1/3) (a shift of ln Z),
and Swisdak's imperial table has D = -0.01123; with +0.01123 (as some transcriptions print it)
the fit would be 36 % below UFC Fig. 2-15 at Z = 0.067 and 2.9 times above it at Z = 38.
The metric table is also checked against Swisdak's imperial table (an independent transcription,
``tests/data/swisdak_1994_imperial.csv``): P_so, i_s, i_r agree within 0.1 %, P_r, t_o, U within
1.5 % away from the piece boundaries (``test_metric_coefficients_agree_with_swisdak_imperial_table``).

References
----------
.. [1] Swisdak, M. M. (1994). *Simplified Kingery Airblast Calculations*. Minutes of the 26th
       DoD Explosives Safety Seminar, Miami FL. NSWC Indian Head; DTIC ADA526744.
.. [2] Kingery, C. N. & Bulmash, G. (1984). *Airblast parameters from TNT spherical air burst
       and hemispherical surface burst*. Technical Report ARBRL-TR-02555, Ballistic Research
       Laboratory, Aberdeen Proving Ground.
.. [3] UFC 3-340-02 (2008). *Structures to Resist the Effects of Accidental Explosions*,
       Figure 2-15.
"""

from __future__ import annotations

import numpy as np

from .base import BlastModel

__all__ = ["KingeryBulmash", "SWISDAK_1994_COEFFICIENTS", "SWISDAK_1994_UNITS", "piece_boundaries"]

#: Swisdak (1994) metric coefficients, hemispherical TNT surface burst.
#: ``quantity -> ((Z_lo, Z_hi, (A, B, C, D, E, F, G)), ...)``, pieces in increasing Z,
#: Z in m/kg^(1/3); the polynomial is in the natural logarithm of Z and gives
#: ln(Y) with Y in the units of :data:`SWISDAK_1994_UNITS`. Missing trailing
#: coefficients are zero.
SWISDAK_1994_COEFFICIENTS: dict[str, tuple[tuple[float, float, tuple[float, ...]], ...]] = {
    "incident_pressure": (
        (0.2, 2.9, (7.2106, -2.1069, -0.3229, 0.1117, 0.0685)),
        (2.9, 23.8, (7.5938, -3.0523, 0.40977, 0.0261, -0.01267)),
        (23.8, 198.5, (6.0536, -1.4066)),
    ),
    "reflected_pressure": (
        (0.06, 2.0, (9.006, -2.6893, -0.6295, 0.1011, 0.29255, 0.13505, 0.019736)),
        (2.0, 40.0, (8.8396, -1.733, -2.64, 2.293, -0.8232, 0.14247, -0.0099)),
    ),
    "scaled_incident_impulse": (
        (0.2, 0.96, (5.522, 1.117, 0.6, -0.292, -0.087)),
        (0.96, 2.38, (5.465, -0.308, -1.464, 1.362, -0.432)),
        (2.38, 33.7, (5.2749, -0.4677, -0.2499, 0.0588, -0.00554)),
        (33.7, 158.7, (5.9825, -1.062)),
    ),
    "scaled_reflected_impulse": ((0.06, 40.0, (6.7853, -1.3466, 0.101, -0.01123)),),
    "scaled_arrival_time": (
        (0.06, 1.5, (-0.7604, 1.8058, 0.1257, -0.0437, -0.0310, -0.00669)),
        (1.5, 40.0, (-0.7137, 1.5732, 0.5561, -0.4213, 0.1054, -0.00929)),
    ),
    "scaled_positive_duration": (
        (0.2, 1.02, (0.5426, 3.2299, -1.5931, -5.9667, -4.0815, -0.9149)),
        (1.02, 2.8, (0.5440, 2.7082, -9.7354, 14.3425, -9.7791, 2.8535)),
        (2.8, 40.0, (-2.4608, 7.1639, -5.6215, 2.2711, -0.44994, 0.03486)),
    ),
    "shock_front_velocity": (
        (0.06, 1.5, (0.1794, -0.956, -0.0866, 0.109, 0.0699, 0.01218)),
        (1.5, 40.0, (0.2597, -1.326, 0.3767, 0.0396, -0.0351, 0.00432)),
    ),
}

#: Units of Y in Swisdak's metric tables and the factor that converts them to SI.
SWISDAK_1994_UNITS: dict[str, tuple[str, float]] = {
    "incident_pressure": ("kPa", 1.0e3),  # -> Pa
    "reflected_pressure": ("kPa", 1.0e3),  # -> Pa
    "scaled_incident_impulse": ("kPa*ms/kg^(1/3)", 1.0),  # -> Pa*s/kg^(1/3) (1e3 * 1e-3)
    "scaled_reflected_impulse": ("kPa*ms/kg^(1/3)", 1.0),  # -> Pa*s/kg^(1/3)
    "scaled_arrival_time": ("ms/kg^(1/3)", 1.0e-3),  # -> s/kg^(1/3)
    "scaled_positive_duration": ("ms/kg^(1/3)", 1.0e-3),  # -> s/kg^(1/3)
    "shock_front_velocity": ("m/ms", 1.0e3),  # -> m/s
}


def piece_boundaries(quantity: str) -> tuple[float, ...]:
    """Interior boundaries [m/kg^(1/3)] between Swisdak's pieces for ``quantity`` (may be empty)."""
    pieces = SWISDAK_1994_COEFFICIENTS[quantity]
    return tuple(hi for (_, hi, _) in pieces[:-1])


def _swisdak(quantity: str, z: np.ndarray) -> np.ndarray:
    """Evaluate Swisdak's piecewise fit for ``quantity`` at Z [m/kg^(1/3)], in SI.

    Each Z uses the piece whose interval contains it (a boundary point belongs to the lower
    piece); Z below the first or above the last piece uses that end piece (extrapolation,
    reached only through ``extrapolate=True`` of the public methods).
    """
    pieces = SWISDAK_1994_COEFFICIENTS[quantity]
    inner = np.asarray(piece_boundaries(quantity), dtype=float)
    idx = np.searchsorted(inner, z, side="left")
    L = np.log(z)
    expo = np.empty_like(L)
    for k, (_, _, coefs) in enumerate(pieces):
        sel = idx == k
        if np.any(sel):
            # polyval takes coefficients lowest order first: A + B L + C L^2 + ...
            expo[sel] = np.polynomial.polynomial.polyval(L[sel], coefs)
    return np.exp(expo) * SWISDAK_1994_UNITS[quantity][1]


class KingeryBulmash(BlastModel):
    """Kingery-Bulmash hemispherical surface burst, Swisdak (1994) coefficients (``"kingery-bulmash"``).

    All seven quantities of :class:`~blastscale.blast.base.BlastModel` are provided, each with
    its own validity range (:attr:`ranges`, Z in m/kg^(1/3)):

    .. math::

        Y(Z) = \\exp\\Big(\\sum_{k=0}^{6} c_k \\ln^k Z\\Big)

    with the piecewise coefficients :data:`SWISDAK_1994_COEFFICIENTS`, converted to SI:
    P_r, P_so [Pa]; i_r/W^(1/3), i_s/W^(1/3) [Pa*s/kg^(1/3)]; t_A/W^(1/3), t_o/W^(1/3)
    [s/kg^(1/3)]; U [m/s]. Outside a range the methods raise
    :class:`~blastscale._validate.OutOfRangeError` unless ``extrapolate=True`` (then the end
    piece is evaluated and an :class:`~blastscale.blast.base.ExtrapolationWarning` emitted).

    Examples
    --------
    >>> kb = KingeryBulmash()
    >>> round(kb.incident_pressure(1.0) / 1e3)  # kPa at Z = 1 m/kg^(1/3)
    1354

    References
    ----------
    Swisdak (1994), DTIC ADA526744; Kingery & Bulmash (1984), ARBRL-TR-02555;
    UFC 3-340-02 (2008) Fig. 2-15. See the module docstring.
    """

    name = "kingery-bulmash"
    ranges = {q: (p[0][0], p[-1][1]) for q, p in SWISDAK_1994_COEFFICIENTS.items()}

    def _raw(self, quantity: str, z: np.ndarray) -> np.ndarray:
        return _swisdak(quantity, z)
