"""The specimen under a given load, through the Study: the prediction (designed load) and the refit (as fired).

The design carries the specimen system (structure, density, gravity, duration, load model, each scaled once);
:func:`simulate_specimen` runs it alone under a charge and stand-off of the caller's through the Study's entry from
a design (:meth:`blastscale.study.Study.from_design`, the one door: no scenario is written to get back in; every
kind, a block-model file's ``assembly`` included). The designed load (the design's specimen charge and stand-off)
gives the prediction (``predicted_*``); the effective charge at the measured stand-off gives the refit
(``refit_*``). Both follow the same path, so that they differ only by the load; :mod:`.shot` runs each with the
prototype under the design's event beside it (``compare=True``): the prediction is then the design's own study
(its verdict: the similarity error of the designed event, :mod:`.event`), the refit the shot's.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from .._validate import BlastscaleInputError
from ..scenario.scenario import Scenario
from ..study.study import Study
from .outcome import pose_marker_history
from .tracks import block_marker_displacement, history_first_peak

__all__ = ["OUTCOMES", "SpecimenRun", "marker_history", "simulate_specimen"]

#: The outcome words (the engines' ``collapsed`` flag in words).
OUTCOMES = {False: "stands", True: "collapsed"}


@dataclass(frozen=True)
class SpecimenRun:
    """One simulation of the specimen (SI; times after the firing signal).

    Attributes
    ----------
    charge_kg, standoff_m : float
        The load: TNT charge [kg] and stand-off [m].
    arrival_time_s : float
        The shock's arrival at the front face [s] (the simulation's time zero).
    result : StudyResult
        The Study's result (:meth:`~blastscale.study.Study.from_design`): the specimen run alone, or, when
        ``compared``, the prototype under the design's event and the specimen under this load, compared (its
        summary's ``verdict``: the shot's similarity verdict).
    compared : bool
        Whether ``result`` compares both systems (the specimen is then its ``model``).
    """

    charge_kg: float
    standoff_m: float
    arrival_time_s: float
    result: Any
    compared: bool = False

    @property
    def rocking(self):
        """The specimen's planar run (RockingResult) or None."""
        p = self.result.planar
        return None if p is None else (p.model if self.compared else p.prototype)

    @property
    def structure(self):
        """The specimen's structure."""
        return self.result.specimen_structure if self.compared else self.result.structure

    @property
    def response3d(self):
        """The specimen's 3D run (Response3D, in its own units) or None."""
        r = self.result.response3d
        return None if r is None else (r.model if self.compared else r.prototype)

    @property
    def collapsed(self) -> bool:
        r = self.rocking
        if r is not None:
            return bool(r.collapsed)
        s = (self.result.summary().get("3d") or {}).get("model" if self.compared else "prototype") or {}
        return bool(s.get("collapsed", False))


def simulate_specimen(
    scenario: Scenario,
    design,
    charge_kg: float,
    standoff_m: float,
    engine: str | None = None,
    *,
    friction: float | None = None,
    restitution: float | None = None,
    compare: bool = False,
) -> SpecimenRun:
    """The specimen under ``charge_kg`` [kg TNT] at ``standoff_m`` [m], through the Study's entry from a design
    (:meth:`~blastscale.study.Study.from_design`; ``scenario``: the prototype's engine settings, ``engine``
    default its own; ``friction`` and ``restitution`` [-] when not the scenario's: a calibration's trials).
    ``compare``: the Study of both systems (``system = "both"``: the prototype under the design's event, the
    specimen under this load, compared; its summary's ``verdict`` is the shot's)."""
    kw = {} if compare else {"friction": friction, "restitution": restitution}
    study = Study.from_design(
        scenario,
        design,
        system="both" if compare else "specimen",
        charge_kg=charge_kg,
        standoff_m=standoff_m,
        engine=engine,
        **kw,
    )
    r = study.run()
    arrival = (r.design.specimen if compare else r.blast).arrival_time
    return SpecimenRun(float(charge_kg), float(standoff_m), float(arrival), r, compare)


def marker_history(run: SpecimenRun, point_m) -> dict:
    """A marker's simulated history and first peak: ``t`` [s after firing], ``ux``, ``uz`` [m],
    ``first_peak_m``, ``first_peak_time_s``, ``max_displacement_m``.

    Planar (a block): the marker's displacement at the solver's first peak angle (an event of the solver, not
    a sample). 3D (any kind): the marker's point fixed on the body whose solid at rest carries it
    (:func:`~.outcome.marker_body`), moved by that body's recorded pose (position and orientation: translation, rocking and the turn out of the
    blast's plane; :func:`~.outcome.pose_marker_history`); the first peak by :func:`~.tracks.history_first_peak` on the
    recorded history (unsmoothed)."""
    r = run.rocking
    x0, z0 = float(point_m[0]), float(point_m[2])
    if r is None:
        return _marker_history_3d(run, np.asarray(point_m, dtype=float))
    b = run.structure.b
    t = r.t_eval if r.t_eval is not None else r.t
    th = r.theta_eval if r.theta_eval is not None else r.theta
    ux, uz = block_marker_displacement(th, x0, z0, b)
    fp = fpt = None
    if r.peak_angles.size:
        fp = float(block_marker_displacement(r.peak_angles[0], x0, z0, b)[0])
        fpt = float(r.peak_times[0]) + run.arrival_time_s
    return {
        "t": np.asarray(t) + run.arrival_time_s,
        "ux": ux,
        "uz": uz,
        "first_peak_m": fp,
        "first_peak_time_s": fpt,
        "max_displacement_m": float(np.max(np.abs(ux))),
    }


def _marker_history_3d(run: SpecimenRun, point: np.ndarray) -> dict:
    resp = run.response3d
    if resp is None:
        raise BlastscaleInputError("the re-simulation ran no engine with marker histories (planar or 3d)")
    ds = resp.dataset
    ux, uz = pose_marker_history(ds, run.structure, point)
    t = np.asarray(ds["time"].values) + run.arrival_time_s
    largest = float(np.max(np.abs(ux)))
    pk = history_first_peak(t, ux, noise=1e-3 * largest)
    return {
        "t": t,
        "ux": ux,
        "uz": uz,
        "first_peak_m": pk.first_peak_m,
        "first_peak_time_s": pk.first_peak_time_s,
        "max_displacement_m": largest,
    }
