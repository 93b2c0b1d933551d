"""What a study produced: :class:`StudyResult` (scenario, structures, design, each engine's
comparison, warnings, timings) and its views (nested summary, flat scalars, histories dataset)."""

from __future__ import annotations

import copy
import math
from dataclasses import dataclass, field
from typing import Any, Callable

import numpy as np

from ..analysis.compare import upscale_dataset
from ..analysis.damage import damage_summary
from ..analysis.intervals import odds_text
from ..analysis.rocking_similarity import rocking_dataset
from ..scenario.scenario import Scenario
from .criterion import judge, structure_height

__all__ = ["StudyResult", "study_warnings"]


#: Summary keys left out of the flat scalars: per-block details, named by the blocks (names are not
#: identifiers, and a sweep's stores need a fixed layout); summary.json keeps them.
_NOT_SCALARS = ("bodies",)


def _flatten(obj: Any, prefix: str, out: dict) -> None:
    if isinstance(obj, dict):
        for k, v in obj.items():
            if k in _NOT_SCALARS:
                continue
            _flatten(v, f"{prefix}.{k}" if prefix else str(k), out)
    elif isinstance(obj, (list, tuple)):
        for i, v in enumerate(obj):
            _flatten(v, f"{prefix}.{i}", out)
    elif obj is None:
        out[prefix] = math.nan
    elif isinstance(obj, (bool, int, float)):
        out[prefix] = obj
    elif hasattr(obj, "item") and callable(obj.item):  # numpy scalar
        out[prefix] = obj.item()


@dataclass(frozen=True, eq=False)
class StudyResult:
    """Everything a study produced (SI; model results up-scaled to prototype units).

    Attributes
    ----------
    scenario : Scenario
        The inputs.
    structure, specimen_structure : structure
        The prototype and the model specimen (lengths x lambda, density x gamma).
    design : blastscale.similitude.ModelDesign or None
        The model experiment: charge, stand-off, every factor, blast parameters, impulsive check
        (None for a prototype-only scenario, and then ``specimen_structure`` is None too).
    blast : BlastParameters
        The prototype's blast parameters (``design.prototype`` when there is a design).
    planar : RockingSimilarity or None
        Planar rocking comparison (blocks), when run.
    critical : CriticalResult or None
        Prototype's critical charge at the stand-off (planar), when asked for.
    response3d : object or None
        3D comparison (``.to_dict()`` with prototype, model, similarity), when run.
    ensemble : EnsembleComparison or None
        3D ensembles of prototype and model under perturbed loads, when asked for.
    warnings : tuple of str
        Library warnings and the study's own (not impulsive, outcomes disagree, engine skipped).
    timings : dict
        Wall time of each stage [s].
    """

    scenario: Scenario
    structure: Any
    specimen_structure: Any
    design: Any
    blast: Any = None
    planar: Any = None
    critical: Any = None
    response3d: Any = None
    ensemble: Any = None
    warnings: tuple = ()
    timings: dict = field(default_factory=dict)
    _summary: dict = field(default_factory=dict, repr=False)  # computed once (the 3D similarity builds loads)
    _views: dict = field(default_factory=dict, repr=False)  # views of the layers above, computed once (view)

    def view(self, name: str, compute: Callable[["StudyResult"], Any]) -> Any:
        """A view of this result that a layer above computes (e.g. the planner's test card), computed once, on
        first use, by ``compute(result)`` and carried by the result (no module memo keyed by the result)."""
        if name not in self._views:
            self._views[name] = compute(self)
        return self._views[name]

    # -- views -----------------------------------------------------------------------------
    def experiment(self) -> dict:
        """The model experiment to build, SI keys: structure description of the specimen,
        mass, material, density, charge and stand-off, and the prototype's for reference."""
        sc, d = self.scenario, self.design
        if d is None:
            return {
                "prototype": {
                    **_describe(self.structure),
                    "charge_kg": sc.blast.charge_kg,
                    "standoff_m": sc.blast.standoff_m,
                },
                "model": None,
            }
        mat = sc.scale.specimen_material or (
            "same as the prototype"
            if abs(d.density_ratio - 1.0) < 1e-12
            else "density ratio " + format(d.density_ratio, ".6g")
        )
        return {
            "prototype": {
                **_describe(self.structure),
                "charge_kg": d.prototype.charge_kg,
                "standoff_m": d.prototype.standoff_m,
            },
            "model": {
                **_describe(self.specimen_structure),
                "material": mat,
                "charge_kg": d.specimen_charge_kg,
                "standoff_m": d.specimen_standoff_m,
            },
            "scale": d.scale,
            "density_ratio": d.density_ratio,
            "gravity_ratio": d.gravity_ratio,
            "law": d.law,
        }

    def summary(self) -> dict:
        """Nested dict of every result (JSON-ready apart from NaN/inf): ``experiment``,
        ``design``, ``planar``, ``critical``, ``3d``, ``ensemble`` (None where not run),
        ``damage`` (:func:`~blastscale.analysis.damage.damage_summary`: the damage states of the prototype,
        the up-scaled model and each ensemble member), ``warnings``, ``timings_s`` and ``verdict`` (:func:`~blastscale.study.criterion.judge`). The
        scenario is under ``scenario``. Computed once (a copy is returned)."""

        return copy.deepcopy(self._cached_summary())

    def _cached_summary(self) -> dict:
        """The summary, computed on first use (read-only: callers outside get copies)."""
        if not self._summary:
            self._summary.update(self._compute_summary())
        return self._summary

    def _compute_summary(self) -> dict:
        out = {
            "scenario": self.scenario.to_dict(),
            "experiment": self.experiment(),
            "design": None if self.design is None else self.design.to_dict(),
            "planar": None if self.planar is None else self.planar.to_dict(),
            "critical": None if self.critical is None else self.critical.to_dict(),
            "3d": None if self.response3d is None else self.response3d.to_dict(),
            "ensemble": None if self.ensemble is None else self.ensemble.to_dict(),
            "warnings": list(self.warnings),
            "timings_s": dict(self.timings),
        }
        out["damage"] = damage_summary(
            out, self.scenario.damage, structure_height(out), self.ensemble
        )  # the prototype's and the up-scaled model's damage states (docs/sweeps.md)
        out["verdict"] = judge(
            out,
            self.scenario.verdict,
            structure_kind=self.scenario.structure.kind,
            circular=getattr(self.structure, "section", None) == "circular",
        )
        return out

    def scalars(self) -> dict:
        """Flat dict of the scalar results (dotted keys, stable for a given scenario layout):
        str -> float / int / bool; None (not applicable) -> NaN. Inputs and timings are left out; of the damage
        states, their levels (``damage.prototype.level``: 0 intact to 4 collapse,
        :data:`~blastscale.analysis.damage.LEVELS`) and the quantities judged; of the
        verdict, ``verdict.similar`` (NaN when nothing is compared) and ``verdict.worst_ratio`` (its worst
        quantity's error / tolerance; NaN when none)."""
        s = self._cached_summary()  # _flatten only reads it
        out: dict = {}
        for key in ("experiment", "design", "planar", "critical", "3d", "ensemble", "damage"):
            _flatten(s[key], key, out)
        v = s["verdict"]
        out["verdict.similar"] = math.nan if v["similar"] is None else bool(v["similar"])
        out["verdict.worst_ratio"] = math.nan if v["worst"] is None else float(v["worst"]["ratio"])
        return out

    def to_datatree(self):
        """Time histories of the prototype and the up-scaled specimen as an ``xarray.DataTree``.

        One group per engine (``planar``, ``sim3d``, ``ensemble``), each with its own ``time``
        dimension [s] and a ``system`` dimension: ``prototype`` and, with a design, ``model`` (the
        specimen up-scaled to prototype units and interpolated onto the prototype's times).
        Variable names are identifiers; every variable has ``units`` (UDUNITS) and ``long_name``.
        The root carries the title, the scenario (TOML) and the CF conventions."""
        import xarray as xr

        groups = {}
        if self.planar is not None:  # a 3D run alone never loads the planar kernels (numba: 0.27 s)
            up = (
                None
                if self.planar.model is None
                else upscale_dataset(rocking_dataset(self.planar.model), self.design.factors)
            )
            groups["planar"] = _system_stack(rocking_dataset(self.planar.prototype), up)
        if self.response3d is not None:
            groups["sim3d"] = _system_stack(
                self.response3d.prototype_dataset, getattr(self.response3d, "upscaled_dataset", None)
            )
        if self.ensemble is not None:
            groups["ensemble"] = _ensemble_dataset(self.ensemble)
        root = xr.Dataset(
            attrs={
                "title": self.scenario.title or "blastscale study",
                "Conventions": "CF-1.10",
                "source": "blastscale.study.Study",
                "scenario_toml": self.scenario.to_toml(),
                "model_results": (
                    "system = model: the specimen up-scaled to prototype units (x_prototype = "
                    "x_specimen / factor) on the prototype's times"
                )
                if self.design is not None
                else "prototype only (no [scale]: no specimen, no comparison)",
                "engines": ", ".join(groups) or "none",
            }
        )
        return xr.DataTree.from_dict({"/": root, **{f"/{k}": v for k, v in groups.items()}})


def _describe(structure) -> dict:
    d = dict(structure.describe()) if hasattr(structure, "describe") else {}
    if "mass_kg" not in d and hasattr(structure, "bodies"):
        d["mass_kg"] = float(sum(b.mass for b in structure.bodies))
    return d


def _ensemble_dataset(ens):
    """The ensemble members' x displacements, prototype and (with a design) up-scaled model
    (system, member, time, point); and the motion of the median and the worst member (case, system, ...)."""
    import xarray as xr

    members = [ens.prototype_members] + ([] if ens.model_members is None else [ens.model_members])
    data = np.stack(members)
    out = xr.Dataset(
        {
            "point_displacement_x": (
                ("system", "member", "time", "point"),
                data,
                {"units": "m", "long_name": "x displacement of the monitoring point"},
            )
        },
        coords={
            "system": ("system", ["prototype", "model"][: len(members)], {"units": "1"}),
            "member": ("member", np.arange(data.shape[1]), {"units": "1"}),
            "load_factor": (
                "member",
                np.asarray(ens.factors),
                {"units": "1", "long_name": "factor on the member's blast load"},
            ),
            "time": ("time", ens.time, {"units": "s", "long_name": "time since detonation (prototype)"}),
            "point": ("point", list(ens.points), {"units": "1"}),
        },
    )
    motion = getattr(ens, "motion", None)
    if motion is not None:  # the median and the worst members' motion (EnsembleComparison.motion)
        motion = motion.assign_coords(time=out["time"])
        for name in motion.data_vars:
            motion[name].attrs = {k: v for k, v in motion[name].attrs.items() if k in ("units", "long_name")}
            motion[name].attrs.setdefault("units", "1")
        out = xr.merge([out, motion], compat="override", combine_attrs="override")
        for label in ("case", "quaternion", "body", "component"):
            out[label].attrs.setdefault("units", "1")
    return out


def _system_stack(proto, up=None):
    """Prototype and (when given) the up-scaled specimen on the prototype's times, stacked along
    ``system``; every variable with ``units`` and ``long_name``, labels dimensionless."""
    import xarray as xr

    names = list(proto.data_vars)
    if up is None:
        parts, labels = [proto[names]], ["prototype"]
    else:
        t = proto["time"].values
        keep = t <= float(up["time"].values[-1]) * (1 + 1e-12)
        proto = proto.isel(time=np.flatnonzero(keep))
        up = up[[v for v in up.data_vars if v in names]]
        same = up.sizes["time"] == proto.sizes["time"] and np.allclose(
            up["time"].values, proto["time"].values, rtol=1e-9, atol=0
        )
        up_on = (
            up.assign_coords(time=proto["time"])
            if same
            else up.interp(time=proto["time"].values, kwargs={"fill_value": "extrapolate"})
        )
        parts, labels = [proto[names], up_on[names]], ["prototype", "model"]
    both = xr.concat(
        parts,
        dim=xr.DataArray(labels, dims="system", name="system"),
        coords="minimal",
        compat="override",
        combine_attrs="override",
    )
    for name in both.data_vars:
        attrs = {k: v for k, v in proto[name].attrs.items() if k in ("units", "long_name", "dimension")}
        attrs.setdefault("units", "1")
        attrs.setdefault("long_name", name.replace("_", " "))
        both[name].attrs = attrs
    both["time"].attrs.update(units="s", long_name="time since detonation (prototype)")
    both["system"].attrs.update(long_name="prototype, or the specimen up-scaled to prototype units")
    for label in both.coords:  # labels (system, body, point, component) are dimensionless
        both[label].attrs.setdefault("units", "1")
    both.attrs = {}
    return both


def _is_circular(cmp) -> bool:
    return getattr(getattr(cmp, "structure", None), "section", None) == "circular"


def study_warnings(design, results: dict, skipped: list, summary: dict, scenario=None) -> list:
    """The study's own warnings, in words for the report (the 3D and ensemble figures read from
    the study's ``summary``, computed once)."""
    out = list(skipped)
    if scenario is not None and scenario.blast.gravity_only and scenario.scale is not None:
        out.append("gravity alone (no charge): no specimen is designed, the [scale] table is not used")
    imp = None if design is None else design.impulsive
    if imp is not None and not imp.impulsive:
        out.append(
            f"the load is not impulsive (t_o p = {imp.prototype_ratio:.3g} prototype, {imp.model_ratio:.3g} "
            f"model, threshold {imp.threshold:g}): the general law's similarity is not guaranteed"
        )
    planar = results.get("planar")
    if planar is not None and planar.outcomes_agree is False:
        out.append("planar rocking: prototype and model outcomes disagree (one overturns, the other does not)")
    ens = results.get("ensemble")
    if ens is None and results.get("3d") is not None and _is_circular(results["3d"]):
        out.append(
            "circular drums wobble chaotically: one trajectory after the first impact means little; compare "
            "first peaks, or set simulation.ensemble_members >= 2 for envelopes and collapse probabilities"
        )
    if ens is not None and summary["ensemble"]["collapse_probability_model"] is not None:
        e = summary["ensemble"]
        if (e["collapse_probability_prototype"] > 0) != (e["collapse_probability_model"] > 0):
            n = int(e["n_members"])
            pp, pm = (round(e[f"collapse_probability_{s}"] * n) for s in ("prototype", "model"))
            out.append(f"ensembles: collapse {odds_text(pp, n)} (prototype) vs {odds_text(pm, n)} (model)")
    s = summary["3d"]
    if s is not None:
        p, m = s.get("prototype") or {}, s.get("model") or {}
        for key in ("collapsed",):
            if key in p and key in m and bool(p[key]) != bool(m[key]):
                out.append(f"3D: prototype and model disagree on '{key}' ({p[key]} vs {m[key]})")
    return out
