"""``Study``: one scenario from the structure to the similarity verdict (like pvlib's ModelChain).

The data flow of the method, once, in one direction::

    scenario -> structure -> model design (once) -> engines (planar rocking, 3D rigid bodies):
    prototype and model runs, the model up-scaled and compared -> StudyResult

Every choice of the scenario passes through (blast model, load method, pulse, incidence
model, scaling law, contact settings, time step, solver settings). What is built is chosen
from small registries, so that a new structure kind or engine needs no change here:

* :data:`STRUCTURE_BUILDERS` -- ``structure.kind`` -> builder(structure table) -> structure;
* :data:`ENGINES` -- ``"planar"`` (rocking, :func:`~blastscale.analysis.rocking_similarity.compare_rocking`,
  single blocks) and ``"3d"`` (MuJoCo, :func:`~blastscale.analysis.structure3d.compare_structure3d`,
  any structure), plus :data:`ENSEMBLE` (:func:`~blastscale.analysis.ensemble.ensemble_compare`)
  when ``simulation.ensemble_members >= 2``.

No CLI code: the ``blastscale run`` command and the sweeps only call :class:`Study` and read
the :class:`StudyResult`. Example (the built-in default, shortened):

>>> from blastscale.io import Scenario
>>> sc = Scenario.default().with_values({"duration_s": 0.05, "engine": "planar", "critical_charge": False})
>>> r = Study(sc).run()
>>> round(r.design.model_charge_kg * 1e6, 3)     # mg of TNT for the 1/200 model (paper: 0.233)
0.233
"""

from __future__ import annotations

import math
import time
import warnings
from dataclasses import dataclass, field, replace
from typing import Any, Callable, Optional

from ._validate import BlastscaleInputError
from .io.scenario import Scenario

__all__ = ["Study", "StudyResult", "StudyWarning", "STRUCTURE_BUILDERS", "ENGINES", "ENSEMBLE", "estimate_memory", "MEMORY_FRACTION",
           "contact_settings", "check_memory"]

class StudyWarning(UserWarning):
    """What a study noticed about its own result (load not impulsive, outcomes that disagree, an
    engine skipped, a chaotic structure compared by single trajectories)."""


#: Progress callback: ``progress(stage, done, total)`` with a short stage description.
Progress = Callable[[str, int, int], None]

#: Fraction of the available memory a study may plan to use for its histories.
MEMORY_FRACTION = 0.5


# -- structures ------------------------------------------------------------------------------
def _build_block(spec) -> Any:
    from .structures import RectangularBlock

    if spec.width_m is not None:
        return RectangularBlock(height=spec.height_m, width=spec.width_m, depth=spec.depth_m,
                                density=spec.density_kg_m3)
    return RectangularBlock.from_slenderness(spec.height_m, math.radians(spec.alpha_deg), depth=spec.depth_m,
                                             density=spec.density_kg_m3)


def _build_column(spec) -> Any:
    from .structures import MultiDrumColumn

    return MultiDrumColumn(section=spec.section, drums=spec.drums, height=spec.height_m,
                           base_width=spec.base_width_m, top_width=spec.top_width_m, sides=spec.sides,
                           density=spec.density_kg_m3)


#: structure kind -> builder(structure table of the scenario) -> structure object.
STRUCTURE_BUILDERS: dict[str, Callable[[Any], Any]] = {"block": _build_block, "column": _build_column}


def _is_block(structure) -> bool:
    from .structures import RectangularBlock

    return isinstance(structure, RectangularBlock)


# -- engines -----------------------------------------------------------------------------------
@dataclass(frozen=True)
class _Context:
    """What every engine receives: the scenario, the built prototype and the one design."""

    scenario: Scenario
    structure: Any
    design: Any


def _planar_supports(structure) -> Optional[str]:
    return None if _is_block(structure) else "planar rocking applies to a single rectangular block"


def _run_planar(ctx: _Context):
    from .analysis.rocking_similarity import compare_rocking

    sc, sim = ctx.scenario, ctx.scenario.simulation
    return compare_rocking(
        ctx.structure, sc.blast.charge_kg, sc.blast.standoff_m, sc.scale.length, ctx.design.density_ratio,
        sc.scale.gravity_ratio, pulse=sc.blast.pulse, model=sc.blast.model, law=sc.scale.law,
        duration=sim.duration_s, n_samples=sim.samples, gravity=sim.gravity_m_s2, restitution=sim.restitution,
        design=ctx.design,
    )


def contact_settings(scenario: Scenario, structure=None):
    """The prototype's 3D contact settings: the engine's defaults for the structure, the
    scenario's friction, time step and every ``[simulation.contact]`` key given.

    When the time step is given without a contact time constant, the time constant is kept
    at >= 4 steps (MuJoCo needs >= 2)."""
    from .sim3d import ContactSettings
    from .sim3d.contact import time_constant_for_step

    sim = scenario.simulation
    base = ContactSettings()
    if structure is not None:  # scale-consistent defaults derived from the structure
        from .sim3d.contact import default_contact

        base = default_contact(structure, friction=scenario.structure.friction, gravity=sim.gravity_m_s2)
    given = {k: v for k, v in sim.contact.model_dump().items() if v is not None}
    names = {"time_constant_s": "time_constant", "friction_time_constant_s": "friction_time_constant",
             "impedance_width_m": "impedance_width"}
    kw = {names.get(k, k): v for k, v in given.items()}
    kw["friction"] = scenario.structure.friction
    if sim.timestep_s is not None:
        kw["timestep"] = sim.timestep_s
        if "time_constant" not in kw:
            kw["time_constant"] = time_constant_for_step(base.time_constant, sim.timestep_s)
    try:
        return replace(base, **kw)
    except BlastscaleInputError as exc:
        raise BlastscaleInputError(f"simulation.contact: {exc}") from None


def _3d_supports(structure) -> Optional[str]:
    return None  # every structure of blastscale.structures runs on the 3D engine


def _run_3d(ctx: _Context):
    from .analysis.structure3d import compare_structure3d

    sc, sim = ctx.scenario, ctx.scenario.simulation
    return compare_structure3d(ctx.structure, ctx.design, load=sc.blast.load, pulse=sc.blast.pulse,
                               incidence=sc.blast.incidence, contact=contact_settings(sc, ctx.structure),
                               duration=sim.duration_s, record_every=sim.record_every,
                               extrapolate=sc.blast.extrapolate)


def _run_ensemble(ctx: _Context):
    from .analysis.ensemble import ensemble_compare

    sc, sim = ctx.scenario, ctx.scenario.simulation
    return ensemble_compare(ctx.structure, ctx.design, n=sim.ensemble_members, perturbation=sim.ensemble_perturbation,
                            load=sc.blast.load, pulse=sc.blast.pulse, incidence=sc.blast.incidence,
                            contact=contact_settings(sc, ctx.structure), duration=sim.duration_s,
                            record_every=sim.record_every, extrapolate=sc.blast.extrapolate)


@dataclass(frozen=True)
class Engine:
    """One response engine: ``supports(structure)`` returns None or why not; ``run(ctx)``."""

    name: str
    label: str
    supports: Callable[[Any], Optional[str]]
    run: Callable[[_Context], Any]


#: engine name -> Engine. ``simulation.engine = "both"`` runs every engine that supports the structure.
ENGINES: dict[str, Engine] = {
    "planar": Engine("planar", "planar rocking: prototype and model", _planar_supports, _run_planar),
    "3d": Engine("3d", "3D rigid bodies (MuJoCo): prototype and model", _3d_supports, _run_3d),
}

#: Runs added to the 3D engine when ``simulation.ensemble_members >= 2``: perturbed-load ensembles
#: of prototype and model (chaotic structures are compared by envelopes, not single trajectories).
ENSEMBLE = Engine("ensemble", "3D ensembles under perturbed loads: prototype and model", _3d_supports, _run_ensemble)


# -- memory -----------------------------------------------------------------------------------
def estimate_memory(scenario: Scenario, structure=None) -> int:
    """An upper estimate of the memory the histories of a study need [bytes].

    3D: per system (prototype, model) one flag per time step plus, per recorded state, the
    engine's raw state (7 + 6 doubles per body), the recorded histories (about 20 doubles per
    body and per monitoring point) kept about four times (result, up-scaled copy, dataset,
    alignment). Planar: the sampled histories (a few doubles per sample) and the solver's output.
    """
    sim = scenario.simulation
    total = 0
    if sim.engine in ("planar", "both"):
        total += sim.samples * 8 * 40
    if sim.engine in ("3d", "both"):
        nb = len(getattr(structure, "bodies", ())) or 1
        dt = sim.timestep_s if sim.timestep_s is not None else 2e-4
        steps = sim.duration_s / dt
        recs = steps / sim.record_every + 1
        runs = 1 + sim.ensemble_members  # an ensemble keeps every member's point histories too
        total += runs * 2 * (steps * 1 + recs * 8 * (13 * nb + 4 * 20 * (2 * nb)))
    return int(total)


def _available_memory() -> int:
    """Available memory [bytes] (Linux /proc/meminfo; 4 GiB when unknown)."""
    try:
        with open("/proc/meminfo") as fh:
            for line in fh:
                if line.startswith("MemAvailable:"):
                    return int(line.split()[1]) * 1024
    except OSError:
        pass
    return 4 * 2**30


def check_memory(scenario: Scenario, structure=None) -> None:
    """Refuse, before any work, a study whose histories would not fit in memory (one line naming
    ``simulation.duration_s``, the need and the longest duration that fits)."""
    need = estimate_memory(scenario, structure)
    limit = MEMORY_FRACTION * _available_memory()
    if need > limit:
        dur = scenario.simulation.duration_s
        fits = dur * limit / need
        raise BlastscaleInputError(
            f"simulation.duration_s = {dur:g} s is out of range: its histories would need about "
            f"{need / 2**30:.3g} GiB of memory, more than {limit / 2**30:.3g} GiB ({MEMORY_FRACTION:g} of the "
            f"available memory); valid range is <= {fits:.3g} s here (or raise simulation.record_every)"
        )


# -- result -----------------------------------------------------------------------------------
def _flatten(obj: Any, prefix: str, out: dict) -> None:
    if isinstance(obj, dict):
        for k, v in obj.items():
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
    structure, model_structure : structure
        The prototype and the model specimen (lengths x lambda, density x gamma).
    design : blastscale.similitude.ModelDesign
        The model experiment: charge, stand-off, every factor, blast parameters, impulsive check.
    planar : RockingSimilarity or None
        Planar rocking comparison (blocks), when run.
    critical : CriticalResult or None
        Prototype's critical charge at the stand-off (planar), when asked for.
    response3d : object or None
        3D comparison (``.summary()`` with prototype, model, similarity), when run.
    ensemble : EnsembleComparison or None
        3D ensembles of prototype and model under perturbed loads, when asked for.
    warnings : tuple of str
        Library warnings and the study's own (not impulsive, outcomes disagree, engine skipped).
    timings : dict
        Wall time of each stage [s].
    """

    scenario: Scenario
    structure: Any
    model_structure: Any
    design: Any
    planar: Any = None
    critical: Any = None
    response3d: Any = None
    ensemble: Any = None
    warnings: tuple = ()
    timings: dict = field(default_factory=dict)
    _summary: dict = field(default_factory=dict, repr=False)  # computed once (the 3D similarity builds loads)

    # -- views -----------------------------------------------------------------------------
    def experiment(self) -> dict:
        """The model experiment to build, SI keys: structure description of the specimen,
        mass, material, density, charge and stand-off, and the prototype's for reference."""
        sc, d = self.scenario, self.design
        mat = sc.scale.model_material or ("same as the prototype" if abs(d.density_ratio - 1.0) < 1e-12
                                          else "density ratio " + format(d.density_ratio, ".6g"))
        return {
            "prototype": {**_describe(self.structure), "charge_kg": d.prototype.charge_kg,
                          "standoff_m": d.prototype.standoff_m},
            "model": {**_describe(self.model_structure), "material": mat, "charge_kg": d.model_charge_kg,
                      "standoff_m": d.model_standoff_m},
            "scale": d.scale, "density_ratio": d.density_ratio, "gravity_ratio": d.gravity_ratio, "law": d.law,
        }

    def summary(self) -> dict:
        """Nested dict of every result (JSON-ready apart from NaN/inf): ``experiment``,
        ``design``, ``planar``, ``critical``, ``3d``, ``ensemble`` (None where not run),
        ``warnings``, ``timings_s``. The scenario is under ``scenario``. Computed once (a copy
        is returned)."""
        import copy

        if not self._summary:
            self._summary.update(self._compute_summary())
        return copy.deepcopy(self._summary)

    def _compute_summary(self) -> dict:
        return {
            "scenario": self.scenario.to_dict(),
            "experiment": self.experiment(),
            "design": self.design.to_dict(),
            "planar": None if self.planar is None else self.planar.to_dict(),
            "critical": None if self.critical is None else self.critical.to_dict(),
            "3d": None if self.response3d is None else self.response3d.summary(),
            "ensemble": None if self.ensemble is None else self.ensemble.summary(),
            "warnings": list(self.warnings),
            "timings_s": dict(self.timings),
        }

    def scalars(self) -> dict:
        """Flat dict of the scalar results (dotted keys, stable for a given scenario layout):
        str -> float / int / bool; None (not applicable) -> NaN. Inputs and timings are left out."""
        s = self.summary()
        out: dict = {}
        for key in ("experiment", "design", "planar", "critical", "3d", "ensemble"):
            _flatten(s[key], key, out)
        return out

    def to_dataset(self):
        """Time histories of the prototype and the up-scaled model as one ``xarray.Dataset``.

        Each engine's variables are prefixed with its name (``planar_rotation_y``,
        ``3d_rotation``) and its dimensions too (``planar_time``, ``3d_time``); the dimension
        ``system`` = ("prototype", "model") holds the prototype and the up-scaled model, the
        model interpolated onto the prototype's times. Every variable has ``units``."""
        import xarray as xr

        parts = []
        if self.planar is not None:
            from .analysis.rocking_similarity import rocking_dataset
            from .analysis.compare import upscale_dataset

            parts.append(_system_stack("planar", rocking_dataset(self.planar.prototype),
                                       upscale_dataset(rocking_dataset(self.planar.model), self.design.factors)))
        if self.response3d is not None:
            parts.append(_system_stack("3d", self.response3d.prototype_dataset, self.response3d.upscaled_dataset))
        if self.ensemble is not None:
            parts.append(_ensemble_dataset(self.ensemble))
        ds = xr.merge(parts, combine_attrs="drop_conflicts") if parts else xr.Dataset()
        for name in ds.variables:  # labels (system, body, point, component) are dimensionless
            ds[name].attrs.setdefault("units", "1")
        ds.attrs.update({
            "title": self.scenario.title or "blastscale study",
            "source": "blastscale.study.Study",
            "scenario_toml": self.scenario.to_toml(),
            "model_results": "up-scaled to prototype units (system = model)",
        })
        return ds

    def to_netcdf(self, path) -> None:
        """Write :meth:`to_dataset` to a NetCDF file (h5netcdf engine)."""
        self.to_dataset().to_netcdf(path, engine="h5netcdf")


def _describe(structure) -> dict:
    d = dict(structure.describe()) if hasattr(structure, "describe") else {}
    if "mass_kg" not in d and hasattr(structure, "bodies"):
        d["mass_kg"] = float(sum(b.mass for b in structure.bodies))
    return d


def _ensemble_dataset(ens):
    """The ensemble members' x displacements, prototype and up-scaled model, as one variable."""
    import numpy as np
    import xarray as xr

    data = np.stack([ens.prototype_members, ens.model_members])  # (system, member, time, point)
    return xr.Dataset(
        {"ensemble_point_displacement_x": (("system", "ensemble_member", "ensemble_time", "ensemble_point"), data,
                                           {"units": "m", "long_name": "x displacement of the monitoring points"})},
        coords={"system": ["prototype", "model"], "ensemble_member": np.arange(data.shape[1]),
                "ensemble_load_factor": ("ensemble_member", np.asarray(ens.factors), {"units": "1"}),
                "ensemble_time": ("ensemble_time", ens.time, {"units": "s"}),
                "ensemble_point": list(ens.points)},
    )


def _system_stack(engine: str, proto, up):
    """Prototype and up-scaled model on the prototype's times, stacked along ``system``, names prefixed."""
    import numpy as np
    import xarray as xr

    t = proto["time"].values
    keep = t <= float(up["time"].values[-1]) * (1 + 1e-12)
    proto = proto.isel(time=np.flatnonzero(keep))
    up = up.drop_vars([v for v in up.data_vars if v not in proto.data_vars])
    up_on = up.interp(time=proto["time"].values, kwargs={"fill_value": "extrapolate"}) \
        if up.sizes["time"] != proto.sizes["time"] or not np.allclose(up["time"].values, proto["time"].values,
                                                                       rtol=1e-9, atol=0) \
        else up.assign_coords(time=proto["time"])
    both = xr.concat([proto[list(proto.data_vars)], up_on[list(proto.data_vars)]],
                     dim=xr.DataArray(["prototype", "model"], dims="system", name="system"),
                     coords="minimal", compat="override", combine_attrs="override")
    for name in both.data_vars:
        both[name].attrs = dict(proto[name].attrs)
        both[name].attrs.setdefault("units", "1")
    both = both.rename({v: f"{engine}_{v}" for v in both.data_vars})
    both = both.rename({d: f"{engine}_{d}" for d in list(both.dims) if d != "system"})
    for c in both.coords:
        if c.startswith(engine) and c.endswith("time"):
            both[c].attrs["units"] = "s"
    both.attrs = {}
    return both


# -- the orchestrator -----------------------------------------------------------------------
class Study:
    """Design the model of a scenario, run the engines, compare (``Study(scenario).run()``).

    Parameters
    ----------
    scenario : Scenario
        The experiment (see :mod:`blastscale.io.scenario`).
    """

    def __init__(self, scenario: Scenario):
        if not isinstance(scenario, Scenario):
            raise BlastscaleInputError(f"scenario must be a Scenario, got {type(scenario).__name__}")
        self.scenario = scenario
        self._checked = None  # (structure, engines, skipped, design) once checked: the design runs once

    def structure(self):
        """The prototype structure, built by the registry entry of its kind."""
        kind = self.scenario.structure.kind
        if kind not in STRUCTURE_BUILDERS:
            raise BlastscaleInputError(
                f"structure.kind = {kind!r} is not known: valid values are {', '.join(STRUCTURE_BUILDERS)}")
        return STRUCTURE_BUILDERS[kind](self.scenario.structure)

    def engines(self, structure) -> tuple[list[Engine], list[str]]:
        """The engines to run and the reasons for those skipped (``engine = "both"``); a single
        engine asked for that does not support the structure is an error."""
        asked = self.scenario.simulation.engine
        names = list(ENGINES) if asked == "both" else [asked]
        run, skipped = [], []
        for n in names:
            why = ENGINES[n].supports(structure)
            if why is None:
                run.append(ENGINES[n])
            elif asked == "both":
                skipped.append(f"{n} engine skipped: {why}")
            else:
                raise BlastscaleInputError(
                    f"simulation.engine = {asked!r} is not available for a {self.scenario.structure.kind}: {why}")
        if not run:
            raise BlastscaleInputError(
                f"structure.kind = {self.scenario.structure.kind!r} cannot be simulated here: {'; '.join(skipped)}")
        members = self.scenario.simulation.ensemble_members
        if members >= 2:
            if not any(e.name == "3d" for e in run):
                raise BlastscaleInputError(f"simulation.ensemble_members = {members} needs the 3D engine: valid "
                                           "simulation.engine values are \"3d\" or \"both\" (or 0 members)")
            run.append(ENSEMBLE)
        return run, skipped

    def design(self, structure=None):
        """The model experiment (:func:`~blastscale.similitude.design_model`), once per study."""
        from .similitude import design_model

        sc = self.scenario
        structure = self.structure() if structure is None else structure
        return design_model(
            sc.blast.charge_kg, sc.blast.standoff_m, sc.scale.length, sc.density_ratio, sc.scale.gravity_ratio,
            sc.scale.law, sc.blast.model, structure if _is_block(structure) else None,
            gravity=sc.simulation.gravity_m_s2, extrapolate=sc.blast.extrapolate,
        )

    def check(self):
        """Everything that can be checked before simulating: the structure, the engines, the
        design (blast fits' ranges, scale range) and the memory. Returns (structure, engines,
        skipped, design)."""
        if self._checked is None:
            structure = self.structure()
            engines, skipped = self.engines(structure)
            check_memory(self.scenario, structure)
            self._checked = (structure, engines, skipped, self.design(structure))
        return self._checked

    def run(self, progress: Optional[Progress] = None) -> StudyResult:
        """Run the study.

        Parameters
        ----------
        progress : callable, optional
            ``progress(stage, done, total)``, called before each stage and once at the end.

        Returns
        -------
        StudyResult
        """
        sc = self.scenario
        timings: dict = {}
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            t0 = time.perf_counter()
            structure, engines, skipped, d = self.check()
            want_critical = sc.simulation.critical_charge and any(e.name == "planar" for e in engines)
            total = 1 + len(engines) + int(want_critical)
            step = 1
            timings["design"] = time.perf_counter() - t0
            results: dict = {}
            ctx = _Context(sc, structure, d)
            for eng in engines:
                _tell(progress, eng.label, step, total)
                t0 = time.perf_counter()
                results[eng.name] = eng.run(ctx)
                timings[eng.name] = time.perf_counter() - t0
                step += 1
            crit = None
            if want_critical:
                _tell(progress, "critical charge of the prototype (planar)", step, total)
                t0 = time.perf_counter()
                crit = _critical(sc, structure)
                timings["critical"] = time.perf_counter() - t0
                step += 1
            _tell(progress, "done", total, total)
            partial = StudyResult(scenario=sc, structure=structure, model_structure=structure.scaled(d.scale,
                                                                                                    d.density_ratio),
                                  design=d,
                                  planar=results.get("planar"), critical=crit, response3d=results.get("3d"),
                                  ensemble=results.get("ensemble"))
            summary = partial._compute_summary()  # inside the capture: its warnings are the study's
        notes = _study_warnings(d, results, skipped, summary)
        lib = []
        for w in caught:
            msg = " ".join(str(w.message).split())
            if msg not in lib:
                lib.append(msg)
                warnings.warn_explicit(w.message, w.category, w.filename, w.lineno)  # still seen by callers
        for note in notes:
            warnings.warn(note, StudyWarning, stacklevel=2)
        summary.update(warnings=list(lib + notes), timings_s=dict(timings))
        return replace(partial, warnings=tuple(lib + notes), timings=timings, _summary=summary)


def _tell(progress: Optional[Progress], stage: str, done: int, total: int) -> None:
    if progress is not None:
        progress(stage, done, total)


def _critical(sc: Scenario, structure):
    from .rocking import RockingSystem, critical_charge

    sim = sc.simulation
    system = RockingSystem.from_block(structure, sim.gravity_m_s2, sim.restitution)
    return critical_charge(system, sc.blast.standoff_m, pulse=sc.blast.pulse, model=sc.blast.model,
                           extrapolate=sc.blast.extrapolate)


def _is_circular(cmp) -> bool:
    return getattr(getattr(cmp, "structure", None), "section", None) == "circular"


def _study_warnings(design, results: dict, skipped: list, summary: dict) -> list:
    """The study's own warnings, in words for the report (the 3D and ensemble figures read from
    the study's ``summary``, computed once)."""
    out = list(skipped)
    imp = design.impulsive
    if imp is not None and not imp.impulsive:
        out.append(f"the load is not impulsive (t_o p = {imp.prototype_ratio:.3g} prototype, {imp.model_ratio:.3g} "
                   f"model, threshold {imp.threshold:g}): the general law's similarity is not guaranteed")
    planar = results.get("planar")
    if planar is not None and not planar.outcomes_agree:
        out.append("planar rocking: prototype and model outcomes disagree (one overturns, the other does not)")
    ens = results.get("ensemble")
    if ens is None and results.get("3d") is not None and _is_circular(results["3d"]):
        out.append("circular drums wobble chaotically: one trajectory after the first impact means little; compare "
                   "first peaks, or set simulation.ensemble_members >= 2 for envelopes and collapse probabilities")
    if ens is not None:
        e = summary["ensemble"]
        if (e["collapse_probability_prototype"] > 0) != (e["collapse_probability_model"] > 0):
            out.append(f"ensembles: collapse probability {e['collapse_probability_prototype']:.2g} (prototype) vs "
                       f"{e['collapse_probability_model']:.2g} (model)")
    s = summary["3d"]
    if s is not None:
        p, m = s.get("prototype", {}), s.get("model", {})
        for key in ("overturned", "collapsed"):
            if key in p and key in m and bool(p[key]) != bool(m[key]):
                out.append(f"3D: prototype and model disagree on '{key}' ({p[key]} vs {m[key]})")
    return out
