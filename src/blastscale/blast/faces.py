"""Per-face blast loads: distance, arrival time, angle of incidence, oblique pressure and impulse.

Used by the paper's Methods B and C (Sec. "Application to multi-drum columns", Appendix B):
instead of loading the whole front face at once with the reflected pulse at the stand-off
(Method A), every face gets the blast parameters of its own centre point:

* distance :math:`R_k = |\\mathbf{x}_k - \\mathbf{x}_c|` from the charge to the face centre,
  scaled distance :math:`Z_k = R_k / W^{1/3}`;
* arrival time :math:`t_{A,k} = W^{1/3}\\,\\hat t_A(Z_k)` **since detonation**, positive
  duration :math:`t_{o,k} = W^{1/3}\\,\\hat t_o(Z_k)`;
* angle of incidence :math:`a_k` between the face's **outward** unit normal
  :math:`\\mathbf{n}_k` and the unit vector from the face centre to the charge,
  :math:`\\cos a_k = -\\mathbf{n}_k \\cdot (\\mathbf{x}_k - \\mathbf{x}_c) / R_k`
  (a = 0: the face looks straight at the charge; a = 90 deg: grazing; a > 90 deg: turned away);
* peak pressure and impulse on the face from the normally reflected and the side-on values at
  Z_k, by the chosen incidence model (:mod:`.incidence`: ``"ufc"``, UFC 3-340-02 Figs.
  2-193/2-194, the default, or ``"closed-form"``, Randers-Pehrson & Bannister 1997). A face
  turned away gets the side-on pulse at its own arrival time.

A pressure p on a face pushes with ``-p * area * n_outward`` (the one sign convention of the
package). :class:`~.face_pulses.FacePulses` gives the pressure of every face at a time and the
**exact** impulse of every face over a step [t0, t1] in one vectorised call; the Friedlander
decays are solved once, on arrays, when the pulses are built (and refined by Newton from a
previous solution when the geometry moves, :meth:`FaceLoads.pulses`).

Incident values for ``masi2021``: the paper's Appendix A fits give the reflected pressure,
impulse, arrival time and duration only. Oblique faces need the side-on pressure and impulse at
the same Z; they are taken from Kingery-Bulmash (Swisdak 1994), to which the paper's fits were
themselves fitted (agreement within 7-9 %), and a :class:`MixedModelWarning` says so (once per
call site). Everything else (P_r, i_r, t_A, t_o) stays the paper's.

Limits (see ``docs/face_loads.md``): no diffraction, clearing or shadowing; the distance is the
straight (slant) distance to the face centre; the fits are those of a hemispherical surface burst.

References
----------
.. [1] Randers-Pehrson, G. & Bannister, K. A. (1997). ARL-TR-1310.
.. [2] Masi, Stefanou & Maffi-Berthier, *Scaling laws ...*, Methods A/B/C and Appendix B.
.. [3] UFC 3-340-02 (2008), Figs. 2-193 and 2-194.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np

from .._validate import BlastscaleInputError, check_finite, check_positive, check_positive_scalar
from .base import BlastModel
from .face_pulses import FacePulses
from .friedlander import MAX_IMPULSE_RATIO, friedlander_decay, friedlander_decay_newton
from .incidence import DEFAULT_INCIDENCE, check_incidence, oblique_values
from .parameters import DEFAULT_BLAST_MODEL, get_blast_model
from .pulses import check_pulse_shape

__all__ = [
    "FaceLoads",
    "face_loads",
    "face_loads_unchecked",
    "incident_source",
    "MixedModelWarning",
    "UNIT_NORMAL_TOLERANCE",
]

#: Largest accepted | |n| - 1 | for a face normal (catches non-normalised input).
UNIT_NORMAL_TOLERANCE = 1.0e-6

_INCIDENT = ("incident_pressure", "scaled_incident_impulse")


class MixedModelWarning(UserWarning):
    """Side-on values for oblique faces come from Kingery-Bulmash beside another model's reflected ones."""


@dataclass(frozen=True)
class FaceLoads:
    """Blast load on a set of faces from one charge, all SI; arrays of shape ``shape`` (one per face).

    Attributes
    ----------
    blast_model : str
        Empirical blast model used (its reflected values; see the module docstring for masi2021).
    incidence : str
        Incidence model (``"ufc"`` or ``"closed-form"``).
    charge_kg : float
        TNT-equivalent charge W [kg].
    distance : ndarray
        Charge-to-face-centre distance R [m].
    scaled_distance : ndarray
        Z = R / W^(1/3) [m/kg^(1/3)].
    cos_incidence, angle_of_incidence : ndarray
        Cosine [-] and angle [rad] between the outward normal and the direction to the charge.
    arrival_time : ndarray
        Shock arrival time t_A [s] since detonation.
    positive_duration : ndarray
        Positive-phase duration t_o [s].
    reflected_pressure, incident_pressure : ndarray
        Normally reflected P_r and side-on P_so peak overpressures at Z [Pa].
    reflected_impulse, incident_impulse : ndarray
        Positive-phase reflected and incident impulses at Z [Pa*s].
    pressure : ndarray
        Peak overpressure on the face by the incidence model [Pa].
    impulse : ndarray
        Positive-phase impulse on the face by the incidence model [Pa*s].
    area : ndarray
        Face area S [m^2].
    normal : ndarray, shape ``shape + (3,)``
        Outward unit normal of each face [-]; the force pushes along ``-normal``.
    """

    blast_model: str
    incidence: str
    charge_kg: float
    distance: np.ndarray
    scaled_distance: np.ndarray
    cos_incidence: np.ndarray
    angle_of_incidence: np.ndarray
    arrival_time: np.ndarray
    positive_duration: np.ndarray
    reflected_pressure: np.ndarray
    incident_pressure: np.ndarray
    reflected_impulse: np.ndarray
    incident_impulse: np.ndarray
    pressure: np.ndarray
    impulse: np.ndarray
    area: np.ndarray
    normal: np.ndarray

    @property
    def shape(self) -> tuple[int, ...]:
        """Shape of the face set (``()`` for a single face)."""
        return self.distance.shape

    @property
    def force_direction(self) -> np.ndarray:
        """Unit vector of the pressure force on each face (= -outward normal)."""
        return -self.normal

    @property
    def peak_force(self) -> np.ndarray:
        """Peak force magnitude on each face, P S [N] (acts along :attr:`force_direction`)."""
        return self.pressure * self.area

    @property
    def force_impulse(self) -> np.ndarray:
        """Impulse of the force on each face, i S [N*s] (along :attr:`force_direction`)."""
        return self.impulse * self.area

    def total_impulse(self) -> np.ndarray:
        """Vector sum of the face impulses, -sum i S n [N*s], shape (3,)."""
        return -np.einsum("...,...k->k", self.impulse * self.area, self.normal)

    def pulses(self, shape: str = "friedlander", decay_guess=None) -> FacePulses:
        """The faces' pulses at their own arrival times (arrays flattened to (nface,)).

        Parameters
        ----------
        shape : str
            ``"friedlander"`` (peak :attr:`pressure`, duration :attr:`positive_duration`,
            decay fitted to :attr:`impulse`, paper Eq. 2), ``"triangular"`` (equal peak and
            impulse, cut at 2 i / P) or ``"impulsive"`` (Dirac of area :attr:`impulse`).
        decay_guess : ndarray, optional
            Friedlander decays of a nearby geometry (e.g. the previous time step), shape
            (nface,): the decays are then refined by vectorised Newton iterations instead of
            solved from scratch.

        Returns
        -------
        FacePulses
        """
        check_pulse_shape(shape)
        ta = self.arrival_time.ravel()
        P = self.pressure.ravel()
        i = self.impulse.ravel()
        zero = np.zeros_like(P)
        if shape == "impulsive":
            return FacePulses(shape, ta, np.full_like(P, np.inf), zero, zero, i)
        if shape == "triangular":
            return FacePulses(shape, ta, P, 2.0 * i / P, zero, i)
        to = self.positive_duration.ravel()
        k = i / (P * to)
        if np.any(k >= MAX_IMPULSE_RATIO):  # the cold solver names the failing ratio
            friedlander_decay(P, to, i)
        if decay_guess is None:
            with warnings.catch_warnings():
                # k >= 1/2 (a negative decay) happens on side-on faces at small Z; the pulse is
                # still monotone (friedlander_decay documents it), so no warning per face
                warnings.simplefilter("ignore")
                d = np.asarray(friedlander_decay(P, to, i), dtype=float).reshape(P.shape)
        else:
            d = friedlander_decay_newton(k, decay_guess)
        return FacePulses(shape, ta, P, to, d, i)


def _as_points(name: str, value) -> np.ndarray:
    arr = check_finite(name, value, "m")
    if arr.ndim == 0 or arr.shape[-1] != 3:
        raise BlastscaleInputError(f"{name} must have a last axis of length 3 (x, y, z), got shape {arr.shape}")
    return arr


def incident_source(blast_model: "str | BlastModel") -> BlastModel:
    """The model that supplies side-on values next to ``blast_model``: itself, or Kingery-Bulmash
    (with a :class:`MixedModelWarning`) when ``blast_model`` has no incident fits (``masi2021``)."""
    m = get_blast_model(blast_model)
    if all(m.provides(q) for q in _INCIDENT):
        return m
    warnings.warn(
        f"blast model {m.name!r} has no side-on fits: oblique faces use Kingery-Bulmash side-on pressure and "
        f"impulse at the same Z beside {m.name!r}'s reflected values, arrival times and durations",
        MixedModelWarning,
        stacklevel=3,
    )
    return get_blast_model("kingery-bulmash")


def face_loads(
    charge: float,
    charge_position,
    centres,
    normals,
    areas=1.0,
    blast_model: "str | BlastModel" = DEFAULT_BLAST_MODEL,
    *,
    incidence: str = DEFAULT_INCIDENCE,
    extrapolate: bool = False,
    incident_model: "BlastModel | None" = None,
) -> FaceLoads:
    """Blast load on each face from a charge ``charge`` [kg TNT] at ``charge_position`` [m].

    Parameters
    ----------
    charge : float
        TNT-equivalent charge W [kg], > 0.
    charge_position : array_like, shape (3,)
        Charge centre [m].
    centres : array_like, shape (..., 3)
        Face centre points [m].
    normals : array_like, shape (..., 3)
        OUTWARD unit normals of the faces [-] (| |n| - 1 | <= :data:`UNIT_NORMAL_TOLERANCE`),
        broadcast against ``centres``.
    areas : array_like, shape (...)
        Face areas S [m^2], > 0 (default 1, i.e. loads per unit area), broadcast.
    blast_model : str or BlastModel
        Empirical model (``"kingery-bulmash"``, the default, or ``"masi2021"``: its side-on
        values then come from Kingery-Bulmash, module docstring).
    incidence : str
        Incidence model, ``"ufc"`` (default) or ``"closed-form"`` (:mod:`.incidence`).
    extrapolate : bool
        Evaluate the fits outside their Z ranges (with an ExtrapolationWarning) instead of
        raising :class:`~blastscale._validate.OutOfRangeError`.
    incident_model : BlastModel, optional
        Source of the side-on values (default: :func:`incident_source` of ``blast_model``; pass it to
        skip the check and its warning in a loop).

    Returns
    -------
    FaceLoads
        Per-face distance, Z, incidence, arrival time, duration, reflected/incident and oblique
        peak pressure and impulse, in SI.

    Raises
    ------
    BlastscaleInputError
        Wrong shapes, non-unit normals, a face centre at the charge, an unknown incidence model;
        OutOfRangeError for Z outside a fit's range.
    """
    W = check_positive_scalar("charge", charge, "kg")
    check_incidence(incidence)
    xc = _as_points("charge position", charge_position)
    if xc.shape != (3,):
        raise BlastscaleInputError(f"charge position must have shape (3,), got {xc.shape}")
    x = _as_points("face centres", centres)
    n = _as_points("face normals", normals)
    try:
        shape = np.broadcast_shapes(x.shape[:-1], n.shape[:-1], np.shape(areas))
    except ValueError as exc:
        raise BlastscaleInputError(
            f"face centres {x.shape}, normals {n.shape} and areas {np.shape(areas)} do not broadcast"
        ) from exc
    S = np.broadcast_to(check_positive("face area", areas, "m^2"), shape)
    x = np.broadcast_to(x, shape + (3,))
    n = np.broadcast_to(n, shape + (3,))
    nlen = np.linalg.norm(n, axis=-1)
    if np.any(np.abs(nlen - 1.0) > UNIT_NORMAL_TOLERANCE):
        bad = float(nlen[np.abs(nlen - 1.0) > UNIT_NORMAL_TOLERANCE].ravel()[0])
        raise BlastscaleInputError(
            f"face normal length = {bad:.6g} is out of range: normals must be unit vectors "
            f"(| |n| - 1 | <= {UNIT_NORMAL_TOLERANCE:g})"
        )
    m = get_blast_model(blast_model)
    mi = incident_source(m) if incident_model is None else incident_model
    return face_loads_unchecked(
        m, mi, incidence, W, xc, x, np.array(n, dtype=float), np.array(S, dtype=float), extrapolate
    )


def face_loads_unchecked(
    blast_model, incident_model, incidence, charge, charge_position, centres, normals, areas, extrapolate
) -> FaceLoads:
    """:func:`face_loads` without its input checks, for callers that re-evaluate the same faces
    at new positions many times (the faces of moving bodies, :mod:`blastscale.sim3d.face_loads`).

    Computes the distances :math:`R = |\\mathbf{x}_c - \\mathbf{x}|` and the cosines of incidence
    :math:`\\cos a = \\mathbf{n} \\cdot (\\mathbf{x}_c - \\mathbf{x}) / R` (module docstring), then the
    blast parameters at :math:`Z = R / W^{1/3}` and the oblique values; only R > 0 is checked.

    Parameters
    ----------
    blast_model : BlastModel
        Empirical model of the reflected values, arrival times and durations (already resolved,
        :func:`~blastscale.blast.get_blast_model`).
    incident_model : BlastModel
        Source of the side-on values (:func:`incident_source` of ``blast_model``).
    incidence : str
        Incidence model, already checked (``"ufc"`` or ``"closed-form"``).
    charge : float
        TNT-equivalent charge W [kg], > 0.
    charge_position : ndarray, shape (3,)
        Charge centre [m].
    centres : ndarray, shape (..., 3)
        Face centre points [m].
    normals : ndarray, shape (..., 3)
        Outward unit normals of the faces [-], same shape as ``centres``.
    areas : ndarray, shape (...)
        Face areas S [m^2], > 0, the shape of the face set.
    extrapolate : bool
        Evaluate the fits outside their Z ranges (with an ExtrapolationWarning).

    Returns
    -------
    FaceLoads

    Raises
    ------
    BlastscaleInputError
        If a face centre is at the charge (R = 0); OutOfRangeError for Z outside a fit's range.
    """
    to_charge = charge_position - centres
    R = np.linalg.norm(to_charge, axis=-1)
    if np.any(R <= 0.0):
        raise BlastscaleInputError("face centre distance to the charge = 0 m is out of range: must be > 0 m")
    cos_a = np.einsum("...k,...k->...", normals, to_charge) / R
    return _evaluate(blast_model, incident_model, incidence, charge, R, cos_a, areas, normals, extrapolate)


def _evaluate(m, mi, incidence, W, R, cos_a, S, n, extrapolate) -> FaceLoads:
    """FaceLoads from distances R [m] and cosines (no input checks: the callers made them)."""
    cos_a = np.clip(cos_a, -1.0, 1.0)
    w13 = float(np.cbrt(W))
    Z = R / w13

    def q(src, name, scale=1.0):
        return np.asarray(getattr(src, name)(Z, extrapolate=extrapolate), dtype=float) * scale

    Pr, Pso = q(m, "reflected_pressure"), q(mi, "incident_pressure")
    ir, i_s = q(m, "scaled_reflected_impulse", w13), q(mi, "scaled_incident_impulse", w13)
    P, i = oblique_values(incidence, cos_a, Pr, Pso, ir, i_s)
    return FaceLoads(
        blast_model=m.name,
        incidence=incidence,
        charge_kg=W,
        distance=R,
        scaled_distance=Z,
        cos_incidence=cos_a,
        angle_of_incidence=np.arccos(cos_a),
        arrival_time=q(m, "scaled_arrival_time", w13),
        positive_duration=q(m, "scaled_positive_duration", w13),
        reflected_pressure=Pr,
        incident_pressure=Pso,
        reflected_impulse=ir,
        incident_impulse=i_s,
        pressure=np.asarray(P, dtype=float),
        impulse=np.asarray(i, dtype=float),
        area=S,
        normal=n,
    )
