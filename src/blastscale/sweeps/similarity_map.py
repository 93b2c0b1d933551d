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
* ``trustworthy``: valid, outcomes agree and ``error <= tolerance`` (default 5e-4 rad planar, the
  acceptance level of the paper's comparisons; 5 % 3D).

References: paper Secs. "Scaling laws" (Eq. 8) and "Equations of motion" (Figs. 6-9).
"""

from __future__ import annotations

from typing import Optional

import numpy as np

from .._validate import check_choice, check_positive
from .layout import VALID_NAME, select
from .run import run_in_memory
from .spec import SweepSpec

__all__ = ["similarity_map", "MAP_FIELDS", "DEFAULT_TOLERANCE", "ENGINE_VARIABLES"]

#: The scenario fields of the map's axes, in order.
MAP_FIELDS = ("length", "density_ratio", "charge_kg", "standoff_m")

#: Error below which an agreeing model is called trustworthy, per engine: planar, the angle error
#: [rad] (the paper's acceptance level); 3d, the top-displacement difference relative to the
#: prototype's peak [-].
DEFAULT_TOLERANCE = {"planar": 5e-4, "3d": 0.05}

_COMMON = {
    "model_to_p": ("design.impulsive.model_to_p", "-"),
    "prototype_to_p": ("design.impulsive.prototype_to_p", "-"),
    "model_charge_kg": ("design.model_charge_kg", "kg"),
    "model_standoff_m": ("design.model_standoff_m", "m"),
    "valid": ("sweep.valid", "-"),
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
    tolerance: Optional[float] = None,
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
    tolerance : float, optional
        Error below which an agreeing model counts as trustworthy (default
        :data:`DEFAULT_TOLERANCE`: 5e-4 rad planar, 0.05 relative 3D).
    run : callable, optional
        ``run(spec) -> xarray.DataTree``: the sweep's store (e.g. the resumable store of
        :func:`blastscale.sweeps.run.run_sweep` read back by ``open_sweep``, on Dask); default
        :func:`.run.run_in_memory` in this process.

    Returns
    -------
    xarray.Dataset
        Dims ``length``, ``density_ratio``, ``charge_kg``, ``standoff_m``; the variables of
        :data:`ENGINE_VARIABLES` plus ``first_peak_ratio_error`` and ``trustworthy``; attrs
        ``engine``, ``tolerance``, ``error_units``.
    """
    import xarray as xr

    check_choice("engine", engine, ENGINE_VARIABLES)
    tolerance = DEFAULT_TOLERANCE[engine] if tolerance is None else float(check_positive("tolerance", tolerance))
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
    agree = out["outcomes_agree"].where(valid, False).astype(bool)
    out["first_peak_ratio_error"] = np.abs(out["first_peak_ratio"] - 1.0).assign_attrs(units="-")
    unit = out["error"].attrs["units"]
    out["trustworthy"] = (valid & agree & (out["error"] <= tolerance)).assign_attrs(
        units="-", definition=f"valid, outcomes agree, error <= {tolerance:g} {unit}"
    )
    out.attrs.update(
        {
            "engine": engine,
            "tolerance": float(tolerance),
            "error_units": unit,
            "error_definition": ENGINE_VARIABLES[engine]["error"][0],
            "title": f"blastscale similarity map ({engine})",
            "sweep": src.attrs.get("sweep", ""),
        }
    )
    return out
