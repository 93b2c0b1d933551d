"""Clearing and the negative phase on every face of Methods B and C (:class:`~.face_pulses.FacePulses`).

* **Clearing** (UFC 3-340-02 Sec. 2-15.3.2, :mod:`.clearing`) on the faces that look at the charge
  (``cos a > 0``): each face relieves with its own peak pressure and impulse (the incidence model's),
  its own side-on values at its Z, the width of its body's front and the height of the structure's
  top (the front is one face from the ground to the top, relieved from its vertical edges and the
  top). Faces turned away keep their side-on pulse: UFC's side and rear loads are other procedures,
  not modelled here.
* **Negative phase** (:mod:`.negative_phase`) on every loaded face, at its own Z, after its own
  positive phase: the reflected values blended toward half of them (the acoustic side-on limit)
  with the weight of the face's positive impulse between side-on and reflected,
  ``w = (i - i_s) / (i_r - i_s)`` (:func:`.negative_phase.oblique_negative`), then bounded by the face's own
  positive impulse (the net impulse is never negative, :func:`.negative_phase.bounded_by_positive`).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from .clearing import clearing
from .negative_phase import NEGATIVE_PHASE_MODEL, bounded_by_positive, face_negative_phase, oblique_negative

__all__ = ["with_effects"]


def with_effects(
    pulses,
    loads,
    *,
    widths=None,
    height=None,
    negative: bool = False,
    burst: str = "surface",
    negative_model: str = NEGATIVE_PHASE_MODEL,
):
    """``pulses`` (:class:`~.face_pulses.FacePulses` of ``loads``, a :class:`~.faces.FaceLoads`) with
    clearing (when ``widths`` (nface,) [m] and ``height`` [m] are given) and the negative phase.

    Returns
    -------
    FacePulses
        The same pulses where no effect applies (a copy with the effects' arrays).
    """
    fl = loads
    kw = {}
    if widths is not None:
        P, i = fl.pressure.ravel(), fl.impulse.ravel()
        c = clearing(
            P,
            i,
            fl.incident_pressure.ravel(),
            fl.incident_impulse.ravel(),
            np.asarray(widths, dtype=float),
            np.broadcast_to(float(height), P.shape),
        )
        front = fl.cos_incidence.ravel() > 0.0
        cl = np.asarray(c.cleared) & front
        t1, p1, t2 = (np.asarray(x, dtype=float) for x in c.knots)
        kw.update(
            cleared=cl,
            clear_t1=np.where(cl, t1, 1.0),
            clear_p1=np.where(cl, p1, 0.0),
            clear_t2=np.where(cl, t2, 1.0),
            impulse=np.where(cl, c.cleared_impulse, pulses.impulse),
        )
    if negative:
        z = fl.scaled_distance.ravel()
        ir, i_s = fl.reflected_impulse.ravel(), fl.incident_impulse.ravel()
        neg = face_negative_phase(
            z,
            np.full(z.shape, float(fl.charge_kg)),
            burst,
            reflected_pressure=fl.reflected_pressure.ravel(),
            reflected_impulse=ir,
            positive_duration=fl.positive_duration.ravel(),
            model=negative_model,
        )
        with np.errstate(invalid="ignore", divide="ignore"):
            w = np.where(ir > i_s, (fl.impulse.ravel() - i_s) / (ir - i_s), 1.0)
        neg = bounded_by_positive(oblique_negative(neg, w), kw.get("impulse", np.asarray(pulses.impulse).ravel()))
        start = fl.positive_duration.ravel() if pulses.kind == "impulsive" else pulses.duration
        if "cleared" in kw:
            start = np.where(kw["cleared"], kw["clear_t2"], start)
        kw.update(
            neg_peak=np.asarray(neg.pressure, dtype=float),
            neg_start=np.asarray(start, dtype=float),
            neg_duration=np.asarray(neg.duration, dtype=float),
        )
    return replace(pulses, **kw) if kw else pulses
