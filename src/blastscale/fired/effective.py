"""The effective charge: the TNT mass that explains a measured impulse (or peak) at the measured distance.

The blast model's fits are inverted at the gauge's distance R (Hopkinson-Cranz scaling, Baker et al. 1983):
the peak ``P(Z)`` and the impulse ``i = W^(1/3) i_hat(Z) = R i_hat(Z) / Z`` both fall monotonically with
Z = R / W^(1/3) over the fits' ranges, so each has one root in Z (:func:`blastscale.blast.inverse.charge_for`,
the package's one inversion of the fits), and ``W = (R / Z)^3``. A reflected gauge (flush in a surface) is read
against the load of a face at its angle of incidence a (the normal of its surface against the direction to
the charge, :func:`blastscale.fired.inputs.gauge_incidence`): the reflected and side-on fits combined by the
scenario's incidence model, UFC 3-340-02 Fig. 2-193 (peak) and Fig. 2-194 (impulse) by default, as the face
loads combine them (:mod:`blastscale.blast.incidence`); a = 0 is the normally reflected value. A side-on gauge
is read against the incident fits (Kingery-Bulmash, Swisdak 1994; UFC 3-340-02 Fig. 2-15 / 2-7). The explosive's TNT equivalence follows from the weighed mass m and the initiator's
TNT equivalent: ``f = (W_eff - W_init) / m`` (UFC 3-340-02 Table 2-1's definition, per basis).
"""

from __future__ import annotations

import math
import warnings

import numpy as np

from .._validate import BlastscaleInputError, check_choice, check_positive_scalar
from ..blast.faces import MixedModelWarning, face_loads
from ..blast.incidence import DEFAULT_INCIDENCE
from ..blast.inverse import OnFace, charge_for
from ..blast.parameters import blast_parameters, model_for_burst

__all__ = ["GAUGE_KINDS", "effective_charge", "predicted_at", "tnt_equivalence"]

#: Gauge kind -> (pressure fit, scaled impulse fit) of the blast model.
GAUGE_KINDS = {
    "reflected": ("reflected_pressure", "scaled_reflected_impulse"),
    "side-on": ("incident_pressure", "scaled_incident_impulse"),
}

#: Gauge kind -> (peak, impulse) as :func:`blastscale.blast.inverse.charge_for` names them.
_INVERTED = {
    "reflected": ("reflected_pressure", "reflected_impulse"),
    "side-on": ("incident_pressure", "incident_impulse"),
}


def _quantity(kind: str, basis: str) -> str:
    check_choice("gauge kind", kind, GAUGE_KINDS)
    check_choice("basis", basis, ("impulse", "pressure"))
    return GAUGE_KINDS[kind][basis == "impulse"]


def effective_charge(
    measured: float,
    distance_m: float,
    kind: str = "reflected",
    basis: str = "impulse",
    blast_model="kingery-bulmash",
    burst: str = "surface",
    incidence_deg: float = 0.0,
    incidence: str = DEFAULT_INCIDENCE,
) -> float:
    """TNT charge W [kg] whose ``basis`` ("impulse" [Pa s] or "pressure" [Pa]) at ``distance_m`` [m] equals
    ``measured`` under ``blast_model`` (a ``kind`` "reflected" or "side-on" gauge; the ``burst`` of the lab
    charge); a reflected gauge at the angle of incidence ``incidence_deg`` [deg] (0: facing the charge) by the
    ``incidence`` model (module docstring). Beside ``masi2021`` (no side-on fits) an oblique gauge reads the
    Kingery-Bulmash side-on values at the same Z, as the face loads do.

    Raises
    ------
    BlastscaleInputError
        When no charge within the fit's range of Z gives the measured value (one line with that range); an
        angle of incidence or a side-on pressure outside what the UFC charts cover.

    Examples
    --------
    >>> from blastscale.blast import blast_parameters
    >>> bp = blast_parameters(0.002, 0.8)
    >>> round(effective_charge(bp.reflected_impulse, 0.8), 6), round(effective_charge(
    ...     bp.reflected_pressure, 0.8, basis="pressure"), 6)
    (0.002, 0.002)
    """
    q = _quantity(kind, basis)
    v = check_positive_scalar(f"measured {basis}", measured, "Pa s" if basis == "impulse" else "Pa")
    R = check_positive_scalar("gauge distance", distance_m, "m")
    m = model_for_burst(blast_model, burst)
    if not m.provides(q):
        raise BlastscaleInputError(
            f"gauge kind = {kind!r}: blast model {m.name!r} has no {q} fit (use a "
            "reflected gauge or blast model kingery-bulmash)"
        )
    oblique = kind == "reflected" and incidence_deg != 0.0
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", MixedModelWarning)  # the convention is stated above and in docs/fired.md
        q = _INVERTED[kind][basis == "impulse"]
        W = charge_for(v, R, OnFace(q, incidence_deg, incidence) if oblique else q, m, outside="nan")
    if not math.isfinite(W):
        lo, hi = m.valid_range(q)
        unit = "Pa s" if basis == "impulse" else "Pa"
        at = f" at {incidence_deg:.3g} deg" if oblique else ""
        raise BlastscaleInputError(
            f"measured {basis} = {v:.4g} {unit} at {R:.4g} m{at} is outside what {m.name} gives over its range Z = "
            f"[{lo:g}, {hi:g}] m/kg^(1/3) ({_value(m, q, hi, R, basis):.4g} to {_value(m, q, lo, R, basis):.4g} "
            f"{unit} facing the charge): check the gauge, its kind and its position"
        )
    return W


def _value(m, q: str, z: float, R: float, basis: str) -> float:
    """The fit ``q`` at Z [m/kg^(1/3)], as an impulse at R [m] for ``basis`` "impulse"."""
    f = float(getattr(m, q)(z))
    return f * R / z if basis == "impulse" else f


def predicted_at(
    charge_kg: float,
    distance_m: float,
    kind: str = "reflected",
    blast_model="kingery-bulmash",
    burst: str = "surface",
    incidence_deg: float = 0.0,
    incidence: str = DEFAULT_INCIDENCE,
) -> tuple[float, float, float]:
    """(peak [Pa], impulse [Pa s], arrival [s]) of ``charge_kg`` of TNT at ``distance_m`` for a ``kind`` gauge (a
    reflected one at the angle of incidence ``incidence_deg`` [deg]: the face load of
    :func:`blastscale.blast.faces.face_loads`, the model the effective charge inverts)."""
    _quantity(kind, "impulse")
    bp = blast_parameters(charge_kg, distance_m, blast_model, burst=burst)
    if kind == "reflected" and incidence_deg != 0.0:
        a = math.radians(incidence_deg)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", MixedModelWarning)
            f = face_loads(
                charge_kg,
                [0.0, 0.0, 0.0],
                [distance_m, 0.0, 0.0],
                [-math.cos(a), math.sin(a), 0.0],
                blast_model=model_for_burst(blast_model, burst),
                incidence=incidence,
            )
        return float(f.pressure), float(f.impulse), float(bp.arrival_time)
    if kind == "reflected":
        return float(bp.reflected_pressure), float(bp.reflected_impulse), float(bp.arrival_time)
    if bp.incident_pressure is None or bp.incident_impulse is None:
        raise BlastscaleInputError(f"gauge kind = 'side-on': blast model {bp.blast_model!r} has no incident fits")
    return float(bp.incident_pressure), float(bp.incident_impulse), float(bp.arrival_time)


def tnt_equivalence(effective_tnt_kg, explosive_mass_kg: float, initiator_tnt_kg: float = 0.0):
    """The explosive's TNT equivalence [-] implied by an effective charge: ``(W_eff - W_init) / m``."""
    m = check_positive_scalar("charge_kg (as weighed)", explosive_mass_kg, "kg")
    return (np.asarray(effective_tnt_kg, dtype=float) - float(initiator_tnt_kg)) / m
