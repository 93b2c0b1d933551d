"""What a study produced: :class:`StudyResult` (scenario, structures, design, each engine's
comparison, warnings, timings) and its views (nested summary, flat scalars, histories dataset)."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

from ..scenario import Scenario

__all__ = ["StudyResult"]


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
            from ..analysis.rocking_similarity import rocking_dataset
            from ..analysis.compare import upscale_dataset

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
