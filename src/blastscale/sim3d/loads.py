"""Blast loads on a structure's bodies: the load interface and the paper's Method A.

A load strategy turns the blast into one world wrench (force, moment about the centre of mass)
per body and per time step, from the bodies' current poses. It carries the **exact impulse** of
the pressure over the step (see :mod:`.blast_force`): the step's force is the pressure's impulse
over [t0, t1] divided by the step, so the momentum delivered does not depend on the step.

Conventions (docs/contracts.md, section 2): one time origin, the detonation (t = 0); outward face
normals; a pressure p on a face of area A pushes with ``-p A (R n_outward)`` applied at the face
centre, R the body's current rotation (body -> world).

Method A (paper, Sec. "Application to multi-drum columns"; the single block of Sec.
"Validation"): the reflected pulse at the stand-off acts on each body's front (``load_face``)
at once, uniformly and simultaneously, along the face's current normal. For a tapered square
drum the face is the slanted trapezoid; its horizontal resultant at rest is p times the
projected trapezoid ``(s0 + s1) H / 2``. For a polygonal ("circular") drum the loaded face is
the projected silhouette, diameter x height (tapered).

Methods B and C (per-face distance, arrival and incidence): :mod:`.face_loads`; every method by
name: :mod:`.load_methods`.
"""

from __future__ import annotations

from dataclasses import replace
from typing import Protocol, runtime_checkable

import numpy as np

from .._validate import BlastscaleInputError, check_finite, check_positive
from ..blast.load_model import front_face_pulse, load_model_record
from ..similitude.effects import front_face
from .blast_force import mean_pressures

__all__ = ["LoadStrategy", "MethodA", "PerturbedLoad", "check_blast", "faces_array", "method_a", "with_structure_face"]


@runtime_checkable
class LoadStrategy(Protocol):
    """What the simulator needs from a load.

    Attributes
    ----------
    first_arrival : float
        Earliest time any face is loaded [s] since detonation.
    end_time : float
        Time after which every load is zero [s] since detonation.
    """

    first_arrival: float
    end_time: float

    def step_wrenches(self, t0: float, t1: float, positions: np.ndarray, rotations: np.ndarray) -> np.ndarray:
        """World wrenches (nbody, 6): force [N] and moment about each centre of mass [N m],
        constant over [t0, t1] [s since detonation], carrying the exact impulse of the step;
        ``positions`` (nbody, 3) [m] and ``rotations`` (nbody, 3, 3) body -> world at t0."""
        ...


def faces_array(faces):
    """Centres (nface, 3) [m], outward normals (nface, 3) and areas (nface,) [m^2] of body-frame faces."""
    c = np.array([f.centre for f in faces], dtype=float).reshape(-1, 3)
    n = np.array([f.normal for f in faces], dtype=float).reshape(-1, 3)
    a = np.array([f.area for f in faces], dtype=float)
    return c, n, a


class MethodA:
    """The reflected pulse on every body's ``load_face``, uniform and simultaneous.

    Parameters
    ----------
    structure : structure
        Any structure of :mod:`blastscale.structures` (``.bodies`` with ``load_face``).
    pulse : blastscale.blast.pulses.Pulse
        Reflected pressure pulse [Pa over s], its t = 0 at the shock arrival.
    arrival_time : float
        Shock arrival time since detonation [s], >= 0 (the same for every face).
    bodies : sequence of int, optional
        Indices of the loaded bodies; default all.
    load_model : dict, optional
        The record of the load model that built ``pulse`` (:func:`blastscale.blast.load_model.load_model_record`),
        kept for :meth:`describe`.

    Notes
    -----
    The moment about the centre of mass is ``(R c) x F`` with c the face centre in the body
    frame. Exact impulse: :func:`.blast_force.mean_pressures` over [t0 - t_A, t1 - t_A].
    """

    method = "A"

    def __init__(self, structure, pulse, arrival_time: float = 0.0, bodies=None, load_model=None):
        if not hasattr(pulse, "cumulative_impulse"):
            raise BlastscaleInputError(f"pulse = {pulse!r} is not a pulse: expected a blastscale.blast.pulses.Pulse")
        if not hasattr(structure, "bodies"):
            raise BlastscaleInputError(f"structure = {structure!r} is not a structure (no .bodies)")
        ta = float(check_finite("arrival time", arrival_time, "s"))
        if ta < 0.0:
            raise BlastscaleInputError(f"arrival time = {ta:.6g} s is out of range: must be >= 0 s")
        nb = len(structure.bodies)
        idx = np.arange(nb) if bodies is None else np.asarray(bodies, dtype=int)
        if idx.size and (idx.min() < 0 or idx.max() >= nb):
            raise BlastscaleInputError(f"bodies = {list(idx)} is out of range: valid indices are 0-{nb - 1}")
        self.structure = structure
        self.pulse = pulse
        self.arrival_time = ta
        self.first_arrival = ta
        self.end_time = ta + float(pulse.duration)
        self.loaded = idx
        self.load_model = load_model
        self.nbody = nb
        self.centres, self.normals, self.areas = faces_array([structure.bodies[i].load_face for i in idx])

    def mean_pressure(self, t0: float, t1: float) -> float:
        """Mean reflected pressure over [t0, t1] [Pa] (times since detonation [s])."""
        ta = self.arrival_time
        return float(mean_pressures(self.pulse, [t0 - ta, t1 - ta])[0])

    def step_wrenches(self, t0, t1, positions, rotations) -> np.ndarray:
        """See :class:`LoadStrategy`."""
        out = np.zeros((self.nbody, 6))
        p = self.mean_pressure(t0, t1)
        if p == 0.0:
            return out
        R = np.asarray(rotations, dtype=float)[self.loaded]
        n_world = np.einsum("bij,bj->bi", R, self.normals)
        F = -p * self.areas[:, None] * n_world
        out[self.loaded, 0:3] = F
        out[self.loaded, 3:6] = np.cross(np.einsum("bij,bj->bi", R, self.centres), F)
        return out

    def delivered_impulse(self) -> np.ndarray:
        """Impulse of the whole pulse on each body at the rest pose, (nbody, 3) [N s]."""
        out = np.zeros((self.nbody, 3))
        out[self.loaded] = -self.pulse.impulse * self.areas[:, None] * self.normals
        return out

    def describe(self) -> dict:
        """Load metadata (SI keys)."""
        d = {
            "load_method": "A",
            "pulse": type(self.pulse).__name__,
            "reflected_pressure_Pa": float(self.pulse.peak),
            "reflected_impulse_Pa_s": float(self.pulse.impulse),
            "positive_duration_s": float(self.pulse.duration),
            "arrival_time_s": self.arrival_time,
        }
        if self.load_model is not None:
            d["load_model"] = self.load_model
        return d


def check_blast(blast):
    """``blast`` itself when it is the :class:`~blastscale.blast.BlastParameters` of one charge and
    stand-off (a load is built from a system's blast parameters, never from a charge recomputed);
    one-line error otherwise."""
    if not hasattr(blast, "pulse") or not hasattr(blast, "charge_kg") or not hasattr(blast, "arrival_time"):
        raise BlastscaleInputError(
            f"blast = {type(blast).__name__} is not blast parameters: give blastscale.blast.blast_parameters(W, R) "
            "or a design's prototype / model"
        )
    if np.ndim(blast.charge_kg) != 0:
        raise BlastscaleInputError(
            f"blast parameters of shape {np.shape(blast.charge_kg)}: a load needs one charge and one stand-off"
        )
    return blast


def method_a(
    structure, blast, *, pulse_shape="friedlander", incidence="ufc", extrapolate=False, load_model=None
) -> MethodA:
    """Method A from a system's blast parameters (:class:`~blastscale.blast.BlastParameters`): the
    reflected pulse of shape ``pulse_shape`` at the stand-off, arriving at ``blast.arrival_time``
    (normal incidence; ``incidence`` does not apply). With a ``load_model``
    (:class:`~blastscale.blast.load_model.LoadModel`) the pulse is cleared on the structure's front
    (:func:`~blastscale.similitude.effects.front_face`: the lowest body's front width, the top's
    height) and followed by the negative phase (``extrapolate`` lets its calibration run outside its range)."""
    bp = check_blast(blast)
    if load_model is None or load_model.is_paper:
        return MethodA(structure, bp.pulse(pulse_shape), arrival_time=float(bp.arrival_time))

    lm = with_structure_face(load_model, structure)
    return MethodA(
        structure,
        front_face_pulse(bp, pulse_shape, lm, extrapolate=extrapolate),
        arrival_time=float(bp.arrival_time),
        load_model=load_model_record(bp.blast_model, bp.burst, lm),
    )


def with_structure_face(load_model, structure):
    """``load_model`` with the structure's front as its clearing face when it has none
    (:func:`~blastscale.similitude.effects.front_face`)."""

    if not load_model.clearing or load_model.face_width_m is not None:
        return load_model

    w, h = front_face(structure)
    return replace(load_model, face_width_m=w, face_height_m=h)


class PerturbedLoad:
    """A load strategy whose wrenches are those of ``load`` times ``factor`` (the same arrival
    and end times): a relative perturbation of the blast of ``factor - 1``.

    Parameters
    ----------
    load : LoadStrategy
        The load to perturb.
    factor : float
        Multiplier of every wrench [-], > 0.
    """

    def __init__(self, load, factor: float):
        self.load = load
        self.factor = float(check_positive("load factor", factor))
        self.first_arrival = load.first_arrival
        self.end_time = load.end_time

    def step_wrenches(self, t0, t1, positions, rotations):
        """``factor`` x the wrapped load's wrenches (nbody, 6) [N, N m]."""
        return self.factor * np.asarray(self.load.step_wrenches(t0, t1, positions, rotations))

    def __getattr__(self, name):  # other helpers (delivered_impulse, ...) of the wrapped load
        return getattr(self.__dict__["load"], name)
