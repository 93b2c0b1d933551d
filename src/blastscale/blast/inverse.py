"""The blast fits inverted: the scaled distance, charge or stand-off that gives a peak pressure or an impulse.

The one inversion of the package: the fired test's effective charge (:mod:`blastscale.fired.effective`),
the surface / free-air equivalence (:mod:`blastscale.blast.bursts`), the critical loads' starting point
(:mod:`blastscale.rocking.critical`) and the up-scaling of a model's capacity curve
(:mod:`blastscale.analysis.capacity`) all call :func:`scaled_distance_for`, :func:`charge_for` or
:func:`standoff_for`.

Equation
--------
Hopkinson-Cranz (cube-root) scaling with Z = R / W^(1/3) [m/kg^(1/3)], W the TNT charge [kg], R the
stand-off [m]. A peak pressure is a function of Z alone, ``P = P_hat(Z)``; an impulse is
``i = W^(1/3) i_hat(Z) = R i_hat(Z) / Z``. Over the fits' ranges every peak and every scaled impulse falls
with Z, and so does ``i_hat(Z) / Z``, so the value ``v`` is met at one Z, the root in ``u = ln Z`` of

.. math:: f(u) = \\ln v - \\ln\\left[q(e^u)\\, s(e^u)\\right],\\qquad
          s = 1 \\text{ (peak)},\\ R / Z \\text{ (impulse at a stand-off R)},\\ W^{1/3}
          \\text{ (impulse of a charge W)},

increasing in u; it is bracketed by the fit's range of Z and found to double precision by the package's
root finder (:func:`blastscale.roots.bracketed_root`, Illinois regula falsi). Then ``W = (R / Z)^3`` or
``R = Z W^(1/3)``.

Range
-----
Z is sought within the fit's valid range of the quantity (:meth:`BlastModel.valid_range`), or within
``z_range`` when given (the critical loads use the range where every fit of :func:`blast_parameters` holds,
:func:`scaled_distance_range`); ``extrapolate=True`` widens either 5x each way (:data:`EXTRAPOLATE_WIDENING`)
and evaluates the fits outside their ranges. A value no Z of the range gives raises one line naming the
value and the values the fit gives over the range (``outside="raise"``), or gives NaN (``"nan"``) or the
nearer end of the range (``"clip"``).

Oblique faces
-------------
A quantity :class:`OnFace` (a reflected one, with its angle ``incidence_deg``) inverts the value on a face
whose outward normal makes that angle a with the direction to the charge (a gauge flush in a surface, :mod:`blastscale.fired.effective`): the
fits at Z are combined by the incidence model (:func:`blastscale.blast.incidence.oblique_values`, UFC 3-340-02
Figs. 2-193 / 2-194 by default, as the face loads of :mod:`blastscale.blast.faces`),

.. math:: P(a) = P_{so} + (P_r - P_{so})\\,\\frac{C_{r\\alpha}(a) - 1}{C_{r\\alpha}(0) - 1},\\qquad
          \\hat i(a) = \\hat i_s + (\\hat i_r - \\hat i_s)\\,g(a),

with the side-on values of :func:`blastscale.blast.faces.incident_source` (Kingery-Bulmash beside
``masi2021``), and the same root in ln Z is sought over the range where the reflected and the side-on fits
hold. a = 0 gives the normally reflected inversion exactly, a = 90 deg the side-on one. The charts cover
a in [0, 90] deg (:data:`INCIDENCE_RANGE_DEG`: a surface turned away from the charge is not charted) and
their incident pressures (Fig. 2-193: 1.38 kPa-34.5 MPa, Fig. 2-194: 4.83 kPa-41.4 MPa,
:func:`blastscale.blast.incidence.ufc_pressure_range`): an angle outside, or a root whose side-on pressure
lies outside the chart used (0 < a < 90 deg, the ``"ufc"`` model), is refused in one line naming it and the
range, whatever ``outside`` says.

Where a fit is not monotone (the Swisdak polynomials jump at their segments' ends: the incident pressure
rises by 0.6 % at Z = 23.8 m/kg^(1/3)), a value inside the jump is met at more than one Z; one of them is
returned.

Fits: Kingery & Bulmash (1984), ARBRL-TR-02555, as polynomials by Swisdak (1994), NSWC IHTR 1997 (surface
and free-air bursts; UFC 3-340-02 Figs. 2-7, 2-15); the paper's Appendix A fits (``"masi2021"``).
Scaling: Baker, W. E. et al. (1983), *Explosion Hazards and Evaluation*, ch. 2.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, replace

import numpy as np

from .._validate import BlastscaleInputError, check_choice, check_finite, check_positive
from ..roots import bracketed_root, root_of_bracket
from .base import ExtrapolationWarning
from .faces import incident_source
from .incidence import DEFAULT_INCIDENCE, check_incidence, oblique_values, ufc_pressure_range
from .parameters import DEFAULT_BLAST_MODEL, get_blast_model, valid_scaled_distance_range

__all__ = [
    "INVERTED_QUANTITIES",
    "EXTRAPOLATE_WIDENING",
    "INCIDENCE_RANGE_DEG",
    "OnFace",
    "scaled_distance_for",
    "charge_for",
    "standoff_for",
    "scaled_distance_range",
    "model_name",
    "warn_if_extrapolated",
]

#: Quantity -> (the blast model's fit, unit of the value): peaks [Pa] and impulses [Pa s].
INVERTED_QUANTITIES = {
    "reflected_pressure": ("reflected_pressure", "Pa"),
    "incident_pressure": ("incident_pressure", "Pa"),
    "reflected_impulse": ("scaled_reflected_impulse", "Pa s"),
    "incident_impulse": ("scaled_incident_impulse", "Pa s"),
}

#: Angles of incidence [deg] the oblique inversion covers (UFC 3-340-02 Figs. 2-193, 2-194: 0 = normal, 90 =
#: grazing); a face turned away from the charge is not charted.
INCIDENCE_RANGE_DEG = (0.0, 90.0)

#: Reflected quantity -> (the UFC chart its oblique value is read on, the side-on fit beside it).
_OBLIQUE = {
    "reflected_pressure": ("2-193", "incident_pressure"),
    "reflected_impulse": ("2-194", "scaled_incident_impulse"),
}

#: Widening of a range of Z with ``extrapolate=True`` (factor each side).
EXTRAPOLATE_WIDENING = 5.0

_OUTSIDE = ("raise", "nan", "clip")


def model_name(blast_model) -> str:
    """The name of a blast model given by name or as a :class:`BlastModel`."""
    return blast_model if isinstance(blast_model, str) else getattr(blast_model, "name", str(blast_model))


def scaled_distance_range(blast_model=DEFAULT_BLAST_MODEL, extrapolate: bool = False) -> tuple[float, float]:
    """The range of Z [m/kg^(1/3)] searched by the critical loads: where every fit of
    :func:`blast_parameters` holds (:func:`valid_scaled_distance_range`), shrunk by 1e-12 relative
    at each end (the fits' own checks then never see round-off beyond it), or widened
    :data:`EXTRAPOLATE_WIDENING` times each way with ``extrapolate``."""
    zlo, zhi = valid_scaled_distance_range(blast_model)
    if extrapolate:
        return zlo / EXTRAPOLATE_WIDENING, zhi * EXTRAPOLATE_WIDENING
    return zlo * (1.0 + 1e-12), zhi * (1.0 - 1e-12)


def warn_if_extrapolated(blast_model, scaled_distances, extrapolate: bool, what: str = "critical scenarios") -> None:
    """One :class:`ExtrapolationWarning` when a finite Z [m/kg^(1/3)] of ``scaled_distances`` lies outside
    the range where every fit of ``blast_model`` holds (only with ``extrapolate``: without it the fits
    raise)."""
    if extrapolate:
        zlo, zhi = valid_scaled_distance_range(blast_model)
        z = np.asarray(scaled_distances, dtype=float)
        z = z[np.isfinite(z)]
        if np.any((z < zlo) | (z > zhi)):
            warnings.warn(
                f"{what} at Z outside the {model_name(blast_model)} fits' range [{zlo:g}, {zhi:g}] m/kg^(1/3): "
                "extrapolated",
                ExtrapolationWarning,
                stacklevel=3,
            )


def scaled_distance_for(
    value,
    quantity: "str | OnFace" = "reflected_impulse",
    blast_model=DEFAULT_BLAST_MODEL,
    *,
    standoff=None,
    charge=None,
    extrapolate: bool = False,
    z_range=None,
    outside: str = "raise",
):
    """Scaled distance Z [m/kg^(1/3)] at which ``blast_model`` gives ``value`` of ``quantity``.

    Parameters
    ----------
    value : float or array_like
        The peak [Pa] or the impulse [Pa s], > 0.
    quantity : str or OnFace
        One of :data:`INVERTED_QUANTITIES`: ``"reflected_pressure"``, ``"incident_pressure"``,
        ``"reflected_impulse"``, ``"incident_impulse"``; or a reflected one on a face at an angle of incidence,
        :class:`OnFace` (module docstring, "Oblique faces").
    blast_model : str or BlastModel
        The fits (module docstring), e.g. ``"kingery-bulmash"``, ``"kingery-bulmash-free-air"``, ``"masi2021"``.
    standoff, charge : float or array_like, optional
        For an impulse, exactly one: the stand-off R [m] (``i = R i_hat(Z) / Z``) or the charge W [kg TNT]
        (``i = W^(1/3) i_hat(Z)``); a peak needs neither (given, they only broadcast).
    extrapolate : bool
        Widen the range 5x each way and evaluate the fits outside their ranges (no warning here: the
        caller reports, :func:`warn_if_extrapolated`).
    z_range : (float, float), optional
        The range of Z searched [m/kg^(1/3)]; default the fit's valid range of ``quantity``.
    outside : {"raise", "nan", "clip"}
        A value no Z of the range gives: raise :class:`BlastscaleInputError`, give NaN, or give the nearer
        end of the range (the end whose value is closer to the one asked for).

    Returns
    -------
    float or ndarray
        Z [m/kg^(1/3)], a float for scalar inputs, else an array of the broadcast shape.

    Raises
    ------
    BlastscaleInputError
        An unknown ``quantity`` or ``outside``, a fit the model lacks, a non-positive input, an impulse
        without (or with both) ``standoff`` and ``charge``, or (``outside="raise"``) a value out of reach,
        naming it and the values the fit gives over the range; an angle of incidence outside
        :data:`INCIDENCE_RANGE_DEG` or a root outside the UFC chart's incident pressures.

    Examples
    --------
    >>> from blastscale.blast import blast_parameters
    >>> bp = blast_parameters(2.0, 3.0)
    >>> round(scaled_distance_for(bp.reflected_pressure, "reflected_pressure"), 12) == round(3.0 / 2.0 ** (1 / 3), 12)
    True
    """
    face = quantity if isinstance(quantity, OnFace) else None
    quantity = face.quantity if face is not None else quantity
    fit, unit, m = _checked_quantity(quantity, blast_model, outside, standoff, charge)
    v = check_positive(quantity, value, unit)
    R = None if standoff is None else check_positive("standoff", standoff, "m")
    W = None if charge is None else check_positive("charge", charge, "kg")
    a = None if face is None else _checked_incidence(face)
    shape = np.broadcast_shapes(*(np.shape(x) for x in (v, R, W, a) if x is not None))
    v = np.broadcast_to(v, shape).astype(float).ravel()
    R = None if R is None else np.broadcast_to(R, shape).astype(float).ravel()
    W = None if W is None else np.broadcast_to(W, shape).astype(float).ravel()
    zlo, zhi = _z_bounds(m, fit, z_range, extrapolate)
    given = _Given(m, fit, unit, extrapolate, R, None if W is None else np.cbrt(W))
    if face is not None:
        given = given.on_face(face, np.cos(np.radians(np.broadcast_to(a, shape).astype(float).ravel())))
        if z_range is None:  # where the side-on fit beside it holds too
            slo, shi = _z_bounds(given.side, _OBLIQUE[quantity][1], None, extrapolate)
            zlo, zhi = max(zlo, slo), min(zhi, shi)
    ln_v = np.log(v)

    def f(idx, u):
        z = np.clip(np.exp(u), zlo, zhi)  # exp(log(hi)) may round above hi
        return ln_v[idx] - np.log(given(idx, z))

    with warnings.catch_warnings():
        if extrapolate:
            warnings.simplefilter("ignore", ExtrapolationWarning)
        u, ok = _solve_log_z(f, v.size, zlo, zhi)
        if outside == "raise" and not np.all(ok):
            k = int(np.flatnonzero(~ok)[0])
            top, bottom = given(np.array([k]), np.array([zlo])), given(np.array([k]), np.array([zhi]))
            at = "" if R is None and W is None else (f" at {R[k]:.6g} m" if R is not None else f" of {W[k]:.6g} kg")
            raise BlastscaleInputError(
                f"{quantity} = {v[k]:.6g} {unit}{at} is out of range: {m.name} gives {float(bottom[0]):.6g} to "
                f"{float(top[0]):.6g} {unit} over Z = [{zlo:g}, {zhi:g}] m/kg^(1/3)"
                + ("" if extrapolate else " (extrapolate=True widens the range 5x each way)")
            )
    z = np.clip(np.exp(u), zlo, zhi)
    if face is not None and face.incidence == "ufc":
        _check_charted(quantity, given.side, z, ok, given.cos_a, extrapolate)
    if outside == "nan":
        z = np.where(ok, z, np.nan)
    return z.reshape(shape) if shape else float(z[0])


@dataclass(frozen=True)
class OnFace:
    """A reflected quantity on a face at an angle of incidence (module docstring, "Oblique faces"): what a gauge
    flush in that face measures.

    Attributes
    ----------
    quantity : str
        ``"reflected_pressure"`` or ``"reflected_impulse"``.
    incidence_deg : float or array_like
        The angle of incidence a [deg] between the face's outward normal and the direction to the charge, in
        :data:`INCIDENCE_RANGE_DEG` (broadcast with the values).
    incidence : str
        The incidence model (:data:`blastscale.blast.incidence.INCIDENCE_MODELS`), ``"ufc"`` by default.

    Examples
    --------
    >>> from blastscale.blast.faces import face_loads
    >>> f = face_loads(0.1, [0, 0, 0], [1.0, 0, 0], [-0.8, 0.6, 0])  # a face at 36.87 deg
    >>> a = 36.86989764584402
    >>> round(charge_for(float(f.impulse), 1.0, OnFace("reflected_impulse", a)), 9)
    0.1
    """

    quantity: str
    incidence_deg: object
    incidence: str = DEFAULT_INCIDENCE


@dataclass(frozen=True)
class _Given:
    """The quantity [Pa or Pa s] the fits give at Z for the cases ``idx``: the fit ``fit`` of ``m`` (an impulse at
    the stand-off ``R`` or of the charge of cube root ``w13``); on a face (:meth:`on_face`), the face's value by the
    incidence model, with the side-on values of ``side`` (:func:`blastscale.blast.faces.incident_source`)."""

    m: object
    fit: str
    unit: str
    extrapolate: bool
    R: np.ndarray | None
    w13: np.ndarray | None
    side: object = None
    cos_a: np.ndarray | None = None
    incidence: str = DEFAULT_INCIDENCE

    def on_face(self, face: OnFace, cos_a: np.ndarray) -> "_Given":
        return replace(self, side=incident_source(self.m), cos_a=cos_a, incidence=face.incidence)

    def fitted(self, idx, z):
        """The fit at Z, as the face at its angle of incidence sees it (the normal fit without one)."""
        ex = self.extrapolate
        q = getattr(self.m, self.fit)(z, extrapolate=ex)
        if self.side is None:
            return q
        impulse = self.unit == "Pa s"
        side = getattr(self.side, "scaled_incident_impulse" if impulse else "incident_pressure")(z, extrapolate=ex)
        pso = self.side.incident_pressure(z, extrapolate=ex) if impulse else side
        pr = self.m.reflected_pressure(z, extrapolate=ex) if impulse else q
        p_face, i_face = oblique_values(self.incidence, self.cos_a[idx], pr, pso, q, side)
        return i_face if impulse else p_face

    def __call__(self, idx, z):
        q = self.fitted(idx, z)
        if self.unit != "Pa s":
            return q
        return q * (self.R[idx] / z) if self.R is not None else q * self.w13[idx]


def _checked_incidence(face: OnFace) -> np.ndarray:
    """The angle of incidence [deg] of ``face``, checked: a reflected quantity, a known model, an angle the
    charts cover (:data:`INCIDENCE_RANGE_DEG`)."""
    if face.quantity not in _OBLIQUE:
        raise BlastscaleInputError(
            f"OnFace quantity = {face.quantity!r}: an angle of incidence applies to a reflected quantity "
            f"({' or '.join(_OBLIQUE)})"
        )
    check_incidence(face.incidence)
    lo, hi = INCIDENCE_RANGE_DEG
    a = check_finite("angle of incidence", face.incidence_deg, "deg")
    bad = (a < lo) | (a > hi)
    if np.any(bad):
        raise BlastscaleInputError(
            f"angle of incidence = {float(a[bad].ravel()[0]):.4g} deg is out of range: valid range is [{lo:g}, {hi:g}] "
            "deg, what UFC 3-340-02 Figs. 2-193 and 2-194 chart (a surface turned away from the charge is not charted)"
        )
    return a


def _check_charted(quantity: str, mi, z: np.ndarray, ok: np.ndarray, cos_a: np.ndarray, extrapolate: bool) -> None:
    """Refuse a root at an oblique angle (0 < a < 90 deg) whose side-on pressure lies outside the UFC chart's
    curves (the chart's end curve would be read there: not charted)."""
    figure = _OBLIQUE[quantity][0]
    lo, hi = ufc_pressure_range(figure)
    oblique = ok & (cos_a < 1.0) & (cos_a > 0.0)
    if not np.any(oblique):
        return
    pso = np.asarray(mi.incident_pressure(z[oblique], extrapolate=extrapolate), dtype=float)
    bad = (pso < lo) | (pso > hi)
    if np.any(bad):
        k = int(np.flatnonzero(bad)[0])
        angle = float(np.degrees(np.arccos(cos_a[oblique][k])))
        raise BlastscaleInputError(
            f"side-on pressure at the face = {pso[k]:.4g} Pa (Z = {z[oblique][k]:.4g} m/kg^(1/3), angle of incidence "
            f"{angle:.3g} deg) is out of range: valid range is [{lo:.4g}, {hi:.4g}] Pa, the curves of UFC 3-340-02 "
            f"Fig. {figure}: the oblique {'impulse' if figure == '2-194' else 'peak'} is not charted there"
        )


def _checked_quantity(quantity: str, blast_model, outside: str, standoff, charge):
    """The fit's name, its unit and the blast model of an inversion of ``quantity``, checked: a known quantity
    and ``outside``, a fit the model has, and for an impulse exactly one of ``standoff`` and ``charge``."""
    check_choice("quantity", quantity, INVERTED_QUANTITIES)
    check_choice("outside", outside, _OUTSIDE)
    fit, unit = INVERTED_QUANTITIES[quantity]
    m = get_blast_model(blast_model)
    if not m.provides(fit):
        raise BlastscaleInputError(f"quantity = {quantity!r}: blast model {m.name!r} has no {fit} fit")
    if unit == "Pa s" and (standoff is None) == (charge is None):
        raise BlastscaleInputError(
            f"quantity = {quantity!r}: give the stand-off [m] or the charge [kg] the impulse is read at (one of them)"
        )
    return fit, unit, m


def _z_bounds(m, fit: str, z_range, extrapolate: bool) -> tuple[float, float]:
    """The range of Z searched [m/kg^(1/3)]: ``z_range``, else the fit's valid range (widened
    :data:`EXTRAPOLATE_WIDENING` x each way with ``extrapolate``)."""
    zlo, zhi = m.valid_range(fit) if z_range is None else (float(z_range[0]), float(z_range[1]))
    if not (0.0 < zlo < zhi and math.isfinite(zhi)):
        raise BlastscaleInputError(
            f"z_range = ({zlo!r}, {zhi!r}) m/kg^(1/3) is out of range: must be 0 < Z_min < Z_max"
        )
    if extrapolate and z_range is None:
        zlo, zhi = zlo / EXTRAPOLATE_WIDENING, zhi * EXTRAPOLATE_WIDENING
    return zlo, zhi


def _solve_log_z(f, n: int, zlo: float, zhi: float):
    """ln Z of the root of ``f(idx, ln Z)`` (decreasing in the quantity: <= 0 at Z_min, >= 0 at Z_max) for the
    ``n`` cases, bracketed by ln ``zlo`` and ln ``zhi`` (:func:`blastscale.roots.bracketed_root`); a case out of
    reach gets the nearer end. Returns ``(u, ok)``: ln Z and whether the root was bracketed."""
    every = np.arange(n)
    a, b = np.full(n, math.log(zlo)), np.full(n, math.log(zhi))
    fa, fb = f(every, a), f(every, b)
    ok = (fa <= 0.0) & (fb >= 0.0)
    u = np.where(fa > 0.0, a, b)  # out of reach: too much (the nearest Z is Z_min) or too little (Z_max)
    idx = np.flatnonzero(ok)
    if idx.size:

        def sub(j, x):
            return f(idx[j], x)

        u[idx] = root_of_bracket(*bracketed_root(sub, a[idx], b[idx], fa[idx], fb[idx])[:4])
    return u, ok


def charge_for(
    value,
    standoff,
    quantity: str = "reflected_impulse",
    blast_model=DEFAULT_BLAST_MODEL,
    *,
    extrapolate: bool = False,
    z_range=None,
    outside: str = "raise",
):
    """TNT charge W [kg] that gives ``value`` of ``quantity`` at ``standoff`` R [m]: ``W = (R / Z)^3`` with Z
    of :func:`scaled_distance_for` (same parameters; arrays broadcast, the kind given is returned).

    Used to read an effective charge from a gauge (:func:`blastscale.fired.effective_charge`, at the gauge's
    angle of incidence with a quantity :class:`OnFace`) and to
    up-scale a model's critical charge to the prototype (under the paper's general law only the impulse is
    matched, Eq. 8: the prototype charge delivers the model's impulse over ``gamma sqrt(varsigma lambda^3)``).

    Examples
    --------
    >>> from blastscale.blast import blast_parameters
    >>> round(charge_for(blast_parameters(0.002, 0.8).reflected_impulse, 0.8), 12)
    0.002
    """
    z = scaled_distance_for(
        value,
        quantity,
        blast_model,
        standoff=standoff,
        extrapolate=extrapolate,
        z_range=z_range,
        outside=outside,
    )
    return (np.asarray(standoff, dtype=float) / z) ** 3 if np.ndim(z) else float((float(standoff) / z) ** 3)


def standoff_for(
    value,
    charge,
    quantity: str = "reflected_impulse",
    blast_model=DEFAULT_BLAST_MODEL,
    *,
    extrapolate: bool = False,
    z_range=None,
    outside: str = "raise",
):
    """Stand-off R [m] at which ``charge`` W [kg TNT] gives ``value`` of ``quantity``: ``R = Z W^(1/3)`` with
    Z of :func:`scaled_distance_for` (same parameters; arrays broadcast, the kind given is returned).

    Examples
    --------
    >>> from blastscale.blast import blast_parameters
    >>> round(standoff_for(blast_parameters(0.002, 0.8).reflected_impulse, 0.002), 12)
    0.8
    """
    z = scaled_distance_for(
        value,
        quantity,
        blast_model,
        charge=charge,
        extrapolate=extrapolate,
        z_range=z_range,
        outside=outside,
    )
    return z * np.cbrt(np.asarray(charge, dtype=float)) if np.ndim(z) else float(z * np.cbrt(float(charge)))
