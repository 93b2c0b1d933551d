"""Similarity map: over a grid of (lambda, gamma, charge, stand-off), how far the up-scaled
reduced-scale model departs from the prototype, and whether the outcomes agree (planar rocking).

The paper checks its law on a handful of cases. A designer choosing the scale lambda and the model
material (gamma) for a campaign of charges and stand-offs needs the whole picture: the general
law matches the impulse only (paper Eq. 8), so the model is exact in the impulsive limit and
departs from the prototype as the pulse lasts longer relative to the model's own time scale
(``t_o p`` grows as the model shrinks: ``p ~ lambda^-1/2``), and near the overturning threshold a
tiny energy difference can flip the outcome. The map runs one sweep (:mod:`.sweeps`: one planar
or 3D Study per case; on Dask when asked) and returns, per case:

* ``error``: planar, max |theta_model_up - theta_prototype| up to the earlier tipping point [rad]
  (the rocking phase; docs/rocking.md explains why the fall is compared on its phase instead);
  3D, max |top displacement difference| relative to the prototype's peak [-],
* ``first_peak_ratio_error``: |first-peak ratio - 1|,
* ``outcomes_agree``: both overturn or both survive,
* ``model_to_p``: the model's t_o p (the a priori impulsive check of ``design_model``),
* ``model_charge_kg``, ``prototype_collapsed``,
* ``valid``: False where the model's scaled distance leaves the blast fits (no design),
* ``trustworthy``: valid and the Study's verdict similar (the one criterion,
  :func:`blastscale.study.criterion.judge`, with the scenario's ``[verdict]`` tolerances: outcomes, first
  peaks, largest displacements and residuals over the whole structure; docs/verdict.md),
* ``worst_ratio``: the verdict's worst quantity's error over its tolerance (<= 1 passes).

References: paper Secs. "Scaling laws" (Eq. 8) and "Equations of motion" (Figs. 6-9).
"""

from __future__ import annotations

import json

import numpy as np

from .._validate import check_choice
from .layout import VALID_NAME, select
from .run import run_in_memory
from .spec import SweepSpec

__all__ = ["similarity_map", "MAP_FIELDS", "ENGINE_VARIABLES"]

#: The scenario fields of the map's axes, in order.
MAP_FIELDS = ("length", "density_ratio", "charge_kg", "standoff_m")

_COMMON = {
    "model_to_p": ("design.impulsive.model_to_p", "-"),
    "prototype_to_p": ("design.impulsive.prototype_to_p", "-"),
    "model_charge_kg": ("design.model_charge_kg", "kg"),
    "model_standoff_m": ("design.model_standoff_m", "m"),
    "valid": ("sweep.valid", "-"),
    "similar": ("verdict.similar", "-"),
    "worst_ratio": ("verdict.worst_ratio", "-"),
}

#: map variable -> (Study scalar key, unit), per engine
ENGINE_VARIABLES = {
    "planar": {
        "error": ("planar.similarity.max_abs_rotation_diff_to_tipping_rad", "rad"),
        "first_peak_ratio": ("planar.similarity.first_peak_ratio", "-"),
        "outcomes_agree": ("planar.similarity.outcomes_agree", "-"),
        "prototype_collapsed": ("planar.prototype.collapsed", "-"),
        "model_collapsed": ("planar.model.collapsed", "-"),
        **_COMMON,
    },
    "3d": {
        "error": ("3d.similarity.max_abs_top_displacement_diff_rel_peak", "-"),
        "first_peak_ratio": ("3d.similarity.top_first_peak_ratio", "-"),
        "outcomes_agree": ("3d.similarity.outcomes_agree", "-"),
        "prototype_collapsed": ("3d.prototype.collapsed", "-"),
        "model_collapsed": ("3d.model.collapsed", "-"),
        **_COMMON,
    },
}


def similarity_map(
    scenario,
    scales,
    density_ratios,
    charges,
    standoffs,
    *,
    engine: str = "planar",
    run=None,
):
    """The similarity map of a scenario (module docstring).

    Parameters
    ----------
    scenario : Scenario
        The base scenario (its engine is set to ``engine``, no critical charge).
    scales, density_ratios : array_like
        lambda and gamma values [-] (non-empty 1-D).
    charges, standoffs : array_like
        Prototype charges [kg] and stand-offs [m].
    engine : {"planar", "3d"}
        Planar rocking (a block; about 2 ms per case) or the 3D engine (any structure; one Study per
        case: use a coarse grid).
    run : callable, optional
        ``run(spec) -> xarray.DataTree``: the sweep's store (e.g. the resumable store of
        :func:`blastscale.sweeps.run.run_sweep` read back by ``open_sweep``, on Dask); default
        :func:`.run.run_in_memory` in this process.

    Returns
    -------
    xarray.Dataset
        Dims ``length``, ``density_ratio``, ``charge_kg``, ``standoff_m``; the variables of
        :data:`ENGINE_VARIABLES` plus ``first_peak_ratio_error`` and ``trustworthy`` (valid and the
        Study's verdict similar); attrs ``engine``, ``tolerances`` (the ``[verdict]`` table, JSON),
        ``error_units``.
    """
    import xarray as xr

    check_choice("engine", engine, ENGINE_VARIABLES)
    grids = dict(zip(MAP_FIELDS, (scales, density_ratios, charges, standoffs)))
    values = {"engine": engine, "critical_charge": False}
    if scenario.scale is None:  # a prototype-only scenario: every case has its own scale (the map's axes)
        values.update({k: np.atleast_1d(grids[k])[0] for k in ("length", "density_ratio")})
    spec = SweepSpec.build(scenario.with_values(values), grids)
    src = (run or run_in_memory)(spec)
    out = xr.Dataset(coords={k: src[k] for k in MAP_FIELDS})
    for name, (key, unit) in ENGINE_VARIABLES[engine].items():
        try:
            v = select(src, key)
        except KeyError:  # e.g. no case valid: the engine's group is empty
            v = xr.full_like(src[VALID_NAME], np.nan, dtype=float)
        out[name] = v.drop_attrs().assign_attrs(units=unit, source=key)
    valid = out["valid"].astype(bool)
    out["first_peak_ratio_error"] = np.abs(out["first_peak_ratio"] - 1.0).assign_attrs(units="-")
    unit = out["error"].attrs["units"]
    out["trustworthy"] = (valid & (out["similar"].where(valid, 0.0) == 1)).assign_attrs(
        units="-", definition="valid, and the Study's verdict similar (docs/verdict.md)"
    )
    out.attrs.update(
        {
            "engine": engine,
            "tolerances": json.dumps(scenario.verdict.model_dump()),
            "error_units": unit,
            "error_definition": ENGINE_VARIABLES[engine]["error"][0],
            "title": f"blastscale similarity map ({engine})",
            "sweep": src.attrs.get("sweep", ""),
        }
    )
    return out
