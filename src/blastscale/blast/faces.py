"""Per-face blast loads: distance, arrival time, angle of incidence, oblique pressure and impulse.

Used by the paper's Methods B and C (Sec. 5 and Appendix B): instead of loading the whole
front face at once with the reflected pulse at the stand-off (Method A), every face gets the
blast parameters of its own centre point:

* distance :math:`R_k = |\\mathbf{x}_k - \\mathbf{x}_c|` from the charge to the face centre,
  scaled distance :math:`Z_k = R_k / W^{1/3}`;
* arrival time :math:`t_{A,k} = W^{1/3}\\,\\hat t_A(Z_k)`, positive duration likewise;
* angle of incidence :math:`a_k` between the face's outward unit normal
  :math:`\\mathbf{n}_k` and the unit vector from the face centre to the charge,
  :math:`\\cos a_k = \\mathbf{n}_k \\cdot (\\mathbf{x}_c - \\mathbf{x}_k) / R_k`
  (a = 0: the face looks straight at the charge; a = 90 deg: grazing; a > 90 deg: turned away);
* peak pressure on the face from the normally reflected and the incident values at Z_k
  (Randers-Pehrson & Bannister 1997, the form used by CONWEP-type loaders),

  .. math::

      P_k = \\begin{cases}
          P_r \\cos^2 a + P_{so}\\,(1 + \\cos a - 2\\cos^2 a) & \\cos a > 0 \\\\
          P_{so} & \\cos a \\le 0,
      \\end{cases}

  and the same combination of the reflected and incident impulses for the face impulse.
  The form gives P_r at a = 0 and P_so at a = 90 deg, and is continuous there.

Limits (see ``docs/blast_models.md`` and DESIGN.md): the closed form ignores Mach
reflection; near a = 40-45 deg it is 27-40 % below the tabulated reflection coefficient of
UFC 3-340-02 Fig. 2-193. Faces turned away get the side-on values, without diffraction,
clearing or shadowing. The distance is the straight (slant) distance to the face centre; the
underlying fits are those of a hemispherical surface burst.

References
----------
.. [1] Randers-Pehrson, G. & Bannister, K. A. (1997). *Airblast loading model for DYNA2D and
       DYNA3D*. ARL-TR-1310, Army Research Laboratory.
.. [2] Masi, Stefanou & Maffi-Berthier, *Scaling laws ...*, Methods A/B/C and Appendix B.
.. [3] UFC 3-340-02 (2008), Fig. 2-193 (reflection coefficient vs angle of incidence).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .._validate import BlastscaleInputError, check_finite, check_positive, check_positive_scalar, check_range
from .base import BlastModel
from .parameters import DEFAULT_BLAST_MODEL, get_blast_model
from .pulses import Friedlander, Impulsive, Pulse, Triangular, friedlander_decay

__all__ = ["FaceLoads", "face_loads", "oblique_combination", "UNIT_NORMAL_TOLERANCE"]

#: Largest accepted | |n| - 1 | for a face normal (catches non-normalised input).
UNIT_NORMAL_TOLERANCE = 1.0e-6


def oblique_combination(reflected, incident, cos_incidence):
    """Randers-Pehrson & Bannister (1997) blend of reflected and incident values [same unit].

    .. math::

        Y(a) = Y_r \\cos^2 a + Y_{s}\\,(1 + \\cos a - 2\\cos^2 a)\\quad(\\cos a > 0),
        \\qquad Y(a) = Y_s \\quad(\\cos a \\le 0).

    Parameters
    ----------
    reflected : array_like
        Normally reflected value Y_r (pressure [Pa] or impulse [Pa*s]).
    incident : array_like
        Incident (side-on) value Y_s, same unit.
    cos_incidence : array_like
        Cosine of the angle of incidence [-], in [-1, 1].

    Returns
    -------
    ndarray or float
        Y on the face, same unit; broadcast shape of the inputs.
    """
    yr = check_range("reflected value", reflected, 0.0)
    ys = check_range("incident value", incident, 0.0)
    # [-1, 1] up to round-off of a normalised dot product
    c = check_range("cosine of the angle of incidence", cos_incidence, -1.0 - 1e-9, 1.0 + 1e-9)
    cp = np.clip(c, 0.0, 1.0)  # cos a <= 0 -> incident only (the formula gives Y_s at c = 0)
    out = yr * cp**2 + ys * (1.0 + cp - 2.0 * cp**2)
    return out if out.ndim else float(out)


@dataclass(frozen=True)
class FaceLoads:
    """Blast load on a set of faces from one charge, all SI; arrays of shape ``shape`` (one per face).

    Attributes
    ----------
    model : str
        Empirical blast model used.
    charge_kg : float
        TNT-equivalent charge W [kg].
    distance : ndarray
        Charge-to-face-centre distance R [m].
    scaled_distance : ndarray
        Z = R / W^(1/3) [m/kg^(1/3)].
    cos_incidence, angle_of_incidence : ndarray
        Cosine [-] and angle [rad] between the outward normal and the direction to the charge.
    arrival_time : ndarray
        Shock arrival time t_A [s].
    positive_duration : ndarray
        Positive-phase duration t_o [s].
    reflected_pressure, incident_pressure : ndarray
        Normally reflected P_r and side-on P_so peak overpressures at Z [Pa].
    reflected_impulse, incident_impulse : ndarray
        Positive-phase reflected and incident impulses at Z [Pa*s].
    pressure : ndarray
        Peak overpressure on the face, oblique blend (module docstring) [Pa].
    impulse : ndarray
        Positive-phase impulse on the face, same blend [Pa*s].
    area : ndarray
        Face area S [m^2].
    force_direction : ndarray, shape ``shape + (3,)``
        Unit vector of the pressure force on the face (= -outward normal).
    """

    model: str
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
    force_direction: np.ndarray

    @property
    def shape(self) -> tuple[int, ...]:
        """Shape of the face set (``()`` for a single face)."""
        return self.distance.shape

    @property
    def peak_force(self) -> np.ndarray:
        """Peak force magnitude on each face, P S [N] (acts along :attr:`force_direction`)."""
        return self.pressure * self.area

    @property
    def force_impulse(self) -> np.ndarray:
        """Impulse of the force on each face, i S [N*s] (along :attr:`force_direction`)."""
        return self.impulse * self.area

    def pulse(self, index=(), shape: str = "friedlander") -> Pulse:
        """Pressure pulse of one face (t = 0 at that face's arrival time).

        ``"friedlander"`` (peak :attr:`pressure`, duration :attr:`positive_duration`, decay
        fitted to :attr:`impulse`, paper Eq. 2), ``"triangular"`` (equal peak and impulse,
        cut at 2 i / P) or ``"impulsive"`` (Dirac of area :attr:`impulse`). ``index`` selects
        the face (an int or tuple for the face array; ``()`` for a single face).
        """
        P = float(self.pressure[index])
        i = float(self.impulse[index])
        if shape == "friedlander":
            to = float(self.positive_duration[index])
            return Friedlander(P, to, float(friedlander_decay(P, to, i)))
        if shape == "triangular":
            return Triangular(P, i)
        if shape == "impulsive":
            return Impulsive(i)
        raise BlastscaleInputError(f"pulse = {shape!r} is not known: valid values are friedlander, triangular, impulsive")


def _as_points(name: str, value) -> np.ndarray:
    arr = check_finite(name, value, "m")
    if arr.ndim == 0 or arr.shape[-1] != 3:
        raise BlastscaleInputError(f"{name} must have a last axis of length 3 (x, y, z), got shape {arr.shape}")
    return arr


def face_loads(
    charge: float,
    charge_position,
    centres,
    normals,
    areas=1.0,
    model: "str | BlastModel" = DEFAULT_BLAST_MODEL,
    *,
    extrapolate: bool = False,
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
        Outward unit normals of the faces [-] (| |n| - 1 | <= :data:`UNIT_NORMAL_TOLERANCE`),
        broadcast against ``centres``.
    areas : array_like, shape (...)
        Face areas S [m^2], > 0 (default 1, i.e. loads per unit area), broadcast.
    model : str or BlastModel
        Empirical model; it must provide the incident pressure and impulse
        (``"kingery-bulmash"``, the default; ``"masi2021"`` does not).
    extrapolate : bool
        Evaluate the fits outside their Z ranges (with an ExtrapolationWarning) instead of
        raising :class:`~blastscale._validate.OutOfRangeError`.

    Returns
    -------
    FaceLoads
        Per-face distance, Z, incidence, arrival time, duration, reflected/incident and blended
        peak pressure and impulse (equations in the module docstring), in SI.

    Raises
    ------
    BlastscaleInputError
        Wrong shapes, non-unit normals, a face centre at the charge, or a model without
        incident quantities; OutOfRangeError for Z outside a fit's range.
    """
    W = check_positive_scalar("charge", charge, "kg")
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
    m = get_blast_model(model)
    for q in ("incident_pressure", "scaled_incident_impulse"):
        if not m.provides(q):
            raise BlastscaleInputError(
                f"blast model = {m.name!r} provides no {q}, needed for oblique faces: "
                "valid models are those with incident quantities (e.g. 'kingery-bulmash')"
            )

    to_charge = xc - x
    R = np.linalg.norm(to_charge, axis=-1)
    if np.any(R <= 0.0):
        raise BlastscaleInputError("face centre distance to the charge = 0 m is out of range: must be > 0 m")
    cos_a = np.clip(np.einsum("...k,...k->...", n, to_charge) / R, -1.0, 1.0)
    w13 = float(np.cbrt(W))
    Z = R / w13

    def q(name, scale=1.0):
        return np.asarray(getattr(m, name)(Z, extrapolate=extrapolate), dtype=float) * scale

    Pr, Pso = q("reflected_pressure"), q("incident_pressure")
    ir, i_s = q("scaled_reflected_impulse", w13), q("scaled_incident_impulse", w13)
    return FaceLoads(
        model=m.name,
        charge_kg=W,
        distance=R,
        scaled_distance=Z,
        cos_incidence=cos_a,
        angle_of_incidence=np.arccos(cos_a),
        arrival_time=q("scaled_arrival_time", w13),
        positive_duration=q("scaled_positive_duration", w13),
        reflected_pressure=Pr,
        incident_pressure=Pso,
        reflected_impulse=ir,
        incident_impulse=i_s,
        pressure=np.asarray(oblique_combination(Pr, Pso, cos_a), dtype=float),
        impulse=np.asarray(oblique_combination(ir, i_s, cos_a), dtype=float),
        area=np.array(S, dtype=float),
        force_direction=-np.array(n, dtype=float),
    )
