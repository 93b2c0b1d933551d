"""The paper's load Methods B and C: every loaded face with its own distance, arrival and incidence.

Method B (paper, Sec. "Application to multi-drum columns"): each body's front, the face Method A
loads (``RigidBody.load_face``: the front of a box or square drum, the projected silhouette of a
polygonal drum), gets the blast of its own centre: distance to the charge, arrival time,
positive duration and angle of incidence, re-evaluated from the bodies' **current** poses every
step while the blast acts.

Method C: every exposed face of every body (front, sides, top, rear; the faces of a polygonal
drum one by one); faces in contact with a neighbour or the ground at rest (``Face.in_contact``)
carry nothing; faces turned away from the charge get the side-on pulse at their own arrival time.

Both follow the load interface of :mod:`.loads` (docs/contracts.md, section 2): one time origin, the
detonation; outward normals, a pressure p on a face pushing with ``-p S (R n)`` at the face
centre; each step's wrench carries the **exact** impulse of every face over [t0, t1]
(:class:`~blastscale.blast.face_pulses.FacePulses`). Outside [first_arrival, end_time] a step
costs nothing; inside, the faces' pulses are rebuilt from the current pose in one vectorised
call (the Friedlander decays refined by Newton from the previous step's).

The charge stands on the ground at ``(front_x - standoff, 0, 0)`` for a surface burst; a free-air
burst's charge is placed at the height of the front's mid-height (``(front_x - standoff, 0, H/2)``,
H the structure's top), as on a stand (the one frame's
:func:`~blastscale.similitude.effects.charge_position` and
:func:`~blastscale.similitude.effects.charge_height`). A load model
(:class:`~blastscale.blast.load_model.LoadModel`) adds clearing and the negative phase on every face
(:mod:`blastscale.blast.face_effects`).
"""

from __future__ import annotations

import copy
from dataclasses import replace

import numpy as np

from .._validate import BlastscaleInputError, check_positive
from ..blast.face_effects import with_effects
from ..blast.faces import face_loads_unchecked, incident_source
from ..blast.incidence import check_incidence
from ..blast.parameters import get_blast_model
from ..blast.pulses import check_pulse_shape
from ..similitude.effects import charge_height, charge_position, front_geometry
from .exposure import visible_fractions
from .loads import check_blast, faces_array

__all__ = ["FaceLoadStrategy", "load_arrival_spread", "method_b", "method_c"]

#: Margin added to the latest pulse end at rest, as a fraction of the longest positive duration:
#: the faces move by millimetres while the blast acts, shifting arrivals by microseconds.
END_MARGIN = 0.05


class FaceLoadStrategy:
    """Per-face blast load on a structure (Methods B and C), a :class:`~.loads.LoadStrategy`.

    Parameters
    ----------
    structure : structure
        Any structure of :mod:`blastscale.structures`.
    faces : sequence of (int, Face)
        The loaded faces: body index and face (body frame, outward normal).
    charge_kg : float
        TNT-equivalent charge W [kg].
    charge_position : array_like (3,)
        Charge centre, world frame [m].
    blast_model : str
        "kingery-bulmash" or "masi2021" (side-on values then from Kingery-Bulmash, warned).
    pulse_shape : str
        "friedlander", "triangular" or "impulsive".
    incidence : str
        "ufc" or "closed-form".
    extrapolate : bool
        Use the blast fits outside their Z ranges (with a warning).
    method : str
        Label ("B", "C" or a user name) for metadata.
    load_model : LoadModel, optional
        Clearing (each face's width: its body's front width; height: the structure's top,
        :func:`blastscale.similitude.effects.front_geometry`) and the negative phase; None: the paper's.

    Attributes
    ----------
    first_arrival : float
        Earliest arrival over the loaded faces at rest [s] since detonation.
    end_time : float
        Latest pulse end at rest plus a margin of 5 % of the longest positive duration [s].
    rest_loads : blastscale.blast.faces.FaceLoads
        The faces' blast parameters at the rest pose.
    """

    def __init__(
        self,
        structure,
        faces,
        *,
        charge_kg,
        charge_position,
        blast_model="kingery-bulmash",
        pulse_shape="friedlander",
        incidence="ufc",
        extrapolate=False,
        method="B",
        load_model=None,
        visible=None,
    ):
        if not hasattr(structure, "bodies"):
            raise BlastscaleInputError(f"structure = {structure!r} is not a structure (no .bodies)")
        if not faces:
            raise BlastscaleInputError("faces = () is out of range: at least one loaded face is needed")
        self.W = float(check_positive("charge", charge_kg, "kg"))
        self.charge_position = np.asarray(charge_position, dtype=float).reshape(3)
        self.shape = check_pulse_shape(pulse_shape)
        self.incidence = check_incidence(incidence)
        self.blast_model = get_blast_model(blast_model)
        self.incident_model = incident_source(self.blast_model)
        self.extrapolate = bool(extrapolate)
        self.method = str(method)
        self.structure = structure
        self.nbody = len(structure.bodies)
        self.body = np.array([b for b, _ in faces], dtype=int)
        self.centres, self.normals, self.areas = faces_array([f for _, f in faces])
        self.labels = tuple(f.label for _, f in faces)
        self.load_model = None if load_model is None or load_model.is_paper else load_model
        self._effects = {}
        if self.load_model is not None:
            self._effects["negative"] = self.load_model.negative_phase
            self._effects["negative_model"] = self.load_model.negative_phase_model
            self._effects["burst"] = getattr(self.blast_model, "burst", "surface")
            if self.load_model.clearing:
                widths, top = front_geometry(structure)
                self._effects["widths"], self._effects["height"] = widths[self.body], top
        self.visible = None if visible is None or np.all(np.asarray(visible) == 1.0) else np.asarray(visible, float)
        pos0 = np.array([b.com for b in structure.bodies], dtype=float)
        rot0 = np.broadcast_to(np.eye(3), (self.nbody, 3, 3))
        self.rest_loads = self.face_loads_at(pos0, rot0)
        rest = self.rest_loads.pulses(self.shape)
        rest = self._with_effects(rest, self.rest_loads)
        self._rest = rest
        self._decay = rest.decay
        self.first_arrival = float(self.rest_loads.arrival_time.min())
        self.end_time = rest.end_time + END_MARGIN * float(self.rest_loads.positive_duration.max())
        self.arrival_shift = np.zeros(self.body.size)
        self.weights = np.ones(self.body.size)

    def corrected(self, stretch: float = 1.0, weights=None) -> "FaceLoadStrategy":
        """A copy corrected at load time (the corrections tested in ``docs/face_loads.md``).

        Parameters
        ----------
        stretch : float
            Arrival times stretched about the first, ``t_A,k -> t_A,0 + stretch (t_A,k - t_A,0)``
            (a delay per face) [-], > 0.
        weights : array_like (nface,), optional
            Each face's pulse (pressure and impulse) multiplied by its weight [-], > 0.

        Returns
        -------
        FaceLoadStrategy
        """

        out = copy.copy(self)
        ta = self.rest_loads.arrival_time
        out.arrival_shift = (ta - ta.min()) * (float(check_positive("stretch", stretch)) - 1.0)
        out.weights = (
            np.ones(self.body.size)
            if weights is None
            else np.broadcast_to(check_positive("face weights", weights), (self.body.size,)).astype(float)
        )
        out.end_time = self.end_time + float(out.arrival_shift.max())
        out.method = f"{self.method} (corrected)"
        return out

    def _with_effects(self, pulses, loads):
        """The load model's clearing and negative phase on ``pulses`` (unchanged without one)."""
        return with_effects(pulses, loads, **self._effects) if self._effects else pulses

    # ------------------------------------------------------------------ geometry
    def world_faces(self, positions, rotations):
        """World face centres (nface, 3) [m] and outward normals (nface, 3) at the given poses."""
        R = np.asarray(rotations, dtype=float)[self.body]
        x = np.asarray(positions, dtype=float)[self.body] + np.einsum("fij,fj->fi", R, self.centres)
        return x, np.einsum("fij,fj->fi", R, self.normals)

    def face_loads_at(self, positions, rotations):
        """:class:`~blastscale.blast.faces.FaceLoads` of the loaded faces at the given poses."""
        x, n = self.world_faces(positions, rotations)
        fl = face_loads_unchecked(
            self.blast_model,
            self.incident_model,
            self.incidence,
            self.W,
            self.charge_position,
            x,
            n,
            self.areas,
            self.extrapolate,
        )
        if self.visible is None:
            return fl
        v = self.visible  # the hidden fraction of a face sees the side-on pulse (.exposure)
        return replace(
            fl,
            pressure=v * fl.pressure + (1.0 - v) * fl.incident_pressure,
            impulse=v * fl.impulse + (1.0 - v) * fl.incident_impulse,
        )

    # --------------------------------------------------------------- interface
    def step_wrenches(self, t0, t1, positions, rotations) -> np.ndarray:
        """World wrenches (nbody, 6) carrying each face's exact impulse over [t0, t1] [s since detonation]."""
        out = np.zeros((self.nbody, 6))
        if t1 <= self.first_arrival or t0 >= self.end_time:
            return out
        fl = self.face_loads_at(positions, rotations)
        fp = fl.pulses(self.shape, decay_guess=self._decay)
        self._decay = fp.decay
        fp = self._with_effects(fp, fl)
        if np.any(self.arrival_shift):
            fp = replace(fp, arrival_time=fp.arrival_time + self.arrival_shift)
        di = fp.impulse_between(t0, t1) * self.weights
        if not np.any(di):
            return out
        R = np.asarray(rotations, dtype=float)[self.body]
        F = -(di * self.areas / (t1 - t0))[:, None] * fl.normal
        M = np.cross(np.einsum("fij,fj->fi", R, self.centres), F)
        for k in range(3):
            out[:, k] = np.bincount(self.body, F[:, k], self.nbody)
            out[:, 3 + k] = np.bincount(self.body, M[:, k], self.nbody)
        return out

    def face_impulses(self) -> np.ndarray:
        """Impulse vector of each loaded face at rest, -i S n, shape (nface, 3) [N s] (with a load
        model: the net impulse of the cleared pulse and the negative phase)."""
        fl = self.rest_loads
        if self._effects:
            i = self._rest.cumulative_impulse(self._rest.end_time + 1.0)
            return -(self.weights * i * fl.area)[:, None] * fl.normal
        return -(self.weights * fl.impulse * fl.area)[:, None] * fl.normal

    def delivered_impulse(self) -> np.ndarray:
        """Impulse of the whole blast on each body at the rest pose, (nbody, 3) [N s]."""
        fi = self.face_impulses()
        return np.stack([np.bincount(self.body, fi[:, k], self.nbody) for k in range(3)], axis=1)

    @property
    def arrival_spread(self) -> float:
        """First to last arrival over the loaded faces at rest [s]."""
        ta = self.rest_loads.arrival_time
        return float(ta.max() - ta.min())

    def describe(self) -> dict:
        """Load metadata (SI keys)."""
        fl = self.rest_loads
        return {
            "load_method": self.method,
            "pulse": self.shape,
            "incidence": self.incidence,
            "blast_model": self.blast_model.name,
            "incident_values_from": self.incident_model.name,
            "charge_kg": self.W,
            "charge_position_m": self.charge_position.tolist(),
            "loaded_faces": int(self.body.size),
            "first_arrival_s": self.first_arrival,
            "arrival_spread_s": self.arrival_spread,
            "end_time_s": self.end_time,
            "max_face_pressure_Pa": float(fl.pressure.max()),
            "max_angle_of_incidence_deg": float(np.degrees(fl.angle_of_incidence.max())),
            **({} if self.load_model is None else {"load_model": self.load_model.to_dict()}),
        }


def load_arrival_spread(load) -> float:
    """First to last shock arrival over the faces a built load strategy loads [s] (0 for Method A, whose
    load has no spread); the planner's estimate from blast parameters alone is
    :func:`blastscale.planning.plan3d.front_arrival_spread`."""
    return float(getattr(load, "arrival_spread", 0.0))


def _charge_at(structure, bp) -> np.ndarray:
    """The charge's centre [m] for blast parameters ``bp``: the one frame's
    (:func:`~blastscale.similitude.effects.charge_position`), at its burst's height (module docstring)."""
    burst = getattr(bp, "burst", "surface")
    return charge_position(structure.front_x, bp.standoff_m, charge_height(structure, burst))


def _face_load(
    structure, faces, blast, pulse_shape, incidence, extrapolate, method, load_model=None, visible=None
) -> FaceLoadStrategy:
    """The per-face load of a system's blast parameters: the charge, stand-off and blast model are
    ``blast``'s; each face's blast is evaluated at its own distance (that is the method)."""
    bp = check_blast(blast)
    return FaceLoadStrategy(
        structure,
        faces,
        charge_kg=bp.charge_kg,
        charge_position=_charge_at(structure, bp),
        blast_model=bp.blast_model,
        pulse_shape=pulse_shape,
        incidence=incidence,
        extrapolate=extrapolate,
        method=method,
        load_model=load_model,
        visible=visible,
    )


def method_b(
    structure, blast, *, pulse_shape="friedlander", incidence="ufc", extrapolate=False, load_model=None
) -> FaceLoadStrategy:
    """Method B: each body's front (``load_face``) with its own distance, arrival, duration and
    incidence, for the charge, stand-off and blast model of ``blast``
    (:class:`~blastscale.blast.BlastParameters`); ``load_model`` adds clearing and the negative phase."""
    faces = [(i, b.load_face) for i, b in enumerate(structure.bodies)]
    return _face_load(structure, faces, blast, pulse_shape, incidence, extrapolate, "B", load_model)


def method_c(
    structure, blast, *, pulse_shape="friedlander", incidence="ufc", extrapolate=False, load_model=None
) -> FaceLoadStrategy:
    """Method C: every exposed face (``in_contact`` False; a partly covered face on its exposed area) of
    every body, each with its own blast, for the charge, stand-off and blast model of ``blast``
    (:class:`~blastscale.blast.BlastParameters`); ``load_model`` adds clearing and the negative phase.
    A face towards the charge but hidden from it behind another body (:mod:`.exposure`, ray cast) is
    shadowed: it sees the side-on pulse, as a face turned away does, not the reflected one (a partly
    hidden face: weighted by its visible fraction)."""

    faces = [(i, f) for i, b in enumerate(structure.bodies) for f in b.faces if not f.in_contact and f.area > 0.0]
    bp = check_blast(blast)
    seen = visible_fractions(structure, faces, _charge_at(structure, bp))
    return _face_load(structure, faces, blast, pulse_shape, incidence, extrapolate, "C", load_model, seen)
