"""The specimen under a given load, through the Study: the prediction (designed load) and the refit (as fired).

The design carries the specimen system (structure, density, gravity, duration, contact, each scaled once);
:func:`specimen_scenario` writes it as a prototype-only scenario (no ``[scale]``: the specimen *is* the
system simulated) under a charge and stand-off of the caller's, and :func:`simulate_specimen` runs it
through :class:`~blastscale.study.Study`, the one door, with the design's specimen structure itself (every
kind, a block-model file's ``assembly`` included: nothing is rebuilt from the table). The designed load (the design's specimen charge and
stand-off) gives the prediction (``predicted_*``); the effective charge at the measured stand-off gives the
refit (``refit_*``). Both follow the same path, so that they differ only by the load.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from .._validate import BlastscaleInputError
from ..scenario import Scenario
from ..study import Study
from .outcome import pose_marker_history
from .tracks import block_marker_displacement, first_peak

__all__ = ["OUTCOMES", "SpecimenRun", "marker_history", "simulate_specimen", "specimen_scenario"]

#: The outcome words (the engines' ``collapsed`` flag in words).
OUTCOMES = {False: "stands", True: "collapsed"}
#: Contact keys that are times (x lambda_t) and lengths (x lambda) when the specimen is written out.
_CONTACT_TIMES = ("time_constant_s", "friction_time_constant_s")
_CONTACT_LENGTHS = ("impedance_width_m",)


def specimen_scenario(
    scenario: Scenario, design, charge_kg: float, standoff_m: float, engine: str | None = None
) -> Scenario:
    """The design's specimen as a prototype-only scenario under ``charge_kg`` [kg TNT] at ``standoff_m`` [m].

    Every length of the structure table (keys ``*_m``) x lambda, its density x gamma; gravity x varsigma;
    duration, time step and contact times x lambda_t, contact widths x lambda; the specimen's burst. An
    ``assembly`` keeps its file (an absolute path, prototype units): the table then names the prototype's
    geometry, and the structure simulated is the design's specimen (:func:`simulate_specimen`)."""
    f = design.factors
    data = scenario.to_dict()
    st = dict(data["structure"])
    if st.get("kind") == "assembly":
        st["file"] = str(Path(st["file"]).resolve())
    for k, v in list(st.items()):
        if k.endswith("_m") and isinstance(v, (int, float)) and not isinstance(v, bool):
            st[k] = float(v) * f.length
    st["density_kg_m3"] = float(st["density_kg_m3"]) * f.density
    sim = dict(data["simulation"])
    sim["gravity_m_s2"] = float(design.specimen_gravity)
    sim["duration_s"] = float(design.specimen_duration)
    sim["critical_charge"] = False
    if engine is not None:
        sim["engine"] = engine
    if sim.get("timestep_s") is not None:
        sim["timestep_s"] = float(sim["timestep_s"]) * f.time
    contact = dict(sim.get("contact") or {})
    for k in _CONTACT_TIMES:
        if contact.get(k) is not None:
            contact[k] = float(contact[k]) * f.time
    for k in _CONTACT_LENGTHS:
        if contact.get(k) is not None:
            contact[k] = float(contact[k]) * f.length
    sim["contact"] = contact
    blast = dict(data["blast"])
    blast.update(
        charge_kg=float(charge_kg),
        standoff_m=float(standoff_m),
        burst=scenario.scale.specimen_burst or scenario.blast.burst,
    )
    out = {"title": f"specimen of: {scenario.title}", "structure": st, "blast": blast, "simulation": sim}
    return Scenario.from_dict(out, source="specimen")


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
        The Study's result of the specimen scenario.
    """

    charge_kg: float
    standoff_m: float
    arrival_time_s: float
    result: Any

    @property
    def rocking(self):
        """The planar run (RockingResult) or None."""
        p = self.result.planar
        return None if p is None else p.prototype

    @property
    def collapsed(self) -> bool:
        r = self.rocking
        if r is not None:
            return bool(r.collapsed)
        s = (self.result.summary().get("3d") or {}).get("prototype") or {}
        return bool(s.get("collapsed", False))


def simulate_specimen(
    scenario: Scenario, design, charge_kg: float, standoff_m: float, engine: str | None = None
) -> SpecimenRun:
    """The specimen under ``charge_kg`` [kg TNT] at ``standoff_m`` [m], through the Study."""
    sc = specimen_scenario(scenario, design, charge_kg, standoff_m, engine)
    r = Study(sc, structure=design.specimen_structure).run()
    return SpecimenRun(float(charge_kg), float(standoff_m), float(r.blast.arrival_time), r)


def marker_history(run: SpecimenRun, point_m) -> dict:
    """A marker's simulated history and first peak: ``t`` [s after firing], ``ux``, ``uz`` [m],
    ``first_peak_m``, ``first_peak_time_s``, ``max_displacement_m``.

    Planar (a block): the marker's displacement at the solver's first peak angle (an event of the solver, not
    a sample). 3D (any kind): the marker's point fixed on the body whose rest centre of mass is nearest to it,
    moved by that body's recorded pose (position and orientation: translation, rocking and the turn out of the
    blast's plane; :func:`~.outcome.pose_marker_history`); the first peak by :func:`~.tracks.first_peak` on the
    recorded history (unsmoothed)."""
    r = run.rocking
    x0, z0 = float(point_m[0]), float(point_m[2])
    if r is None:
        return _marker_history_3d(run, np.asarray(point_m, dtype=float))
    b = run.result.structure.b
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
    resp = run.result.response3d
    if resp is None:
        raise BlastscaleInputError("the re-simulation ran no engine with marker histories (planar or 3d)")
    ds = resp.prototype.dataset
    ux, uz = pose_marker_history(ds, run.result.structure, point)
    t = np.asarray(ds["time"].values) + run.arrival_time_s
    largest = float(np.max(np.abs(ux)))
    pk = first_peak(t, ux, noise=1e-3 * largest, smooth=False)
    return {
        "t": t,
        "ux": ux,
        "uz": uz,
        "first_peak_m": pk.first_peak_m,
        "first_peak_time_s": pk.first_peak_time_s,
        "max_displacement_m": largest,
    }
