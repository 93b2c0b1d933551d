"""Where a flat scalar key lives in a sweep store: the one mapping from the Study's dotted keys
(:meth:`StudyResult.scalars`, the outcome mode's :data:`~blastscale.sweeps.outcomes.OUTCOME_KEYS`)
to a group, an identifier name and labels on the store's extra dimensions.

A key ``section[.system][.similarity][.points.P][.sub...].leaf_unit[.i]`` goes to

* the group of its section (``planar``, ``sim3d`` for the Study's ``3d``, ``ensemble``, ``design``,
  ``experiment``, ``critical``), with a sub-group per other path part (``design/factors``,
  ``design/impulsive``); ``sweep.valid`` is the root's ``valid``;
* the name of its leaf without the unit suffix (``max_rotation_rad`` -> ``max_rotation``; a suffix that
  is no unit, ``_rel_peak``, stays), with ``units`` from :func:`blastscale.units.unit_of`;
* labels: ``system`` (``prototype`` / ``model``) from the path, ``point`` from ``points.P``, and a
  list index as ``component`` (x, y, z), ``bound`` (start, end), ``drum`` (0, 1, ...) or
  ``<name>_index``. Similarity measures (``planar.similarity.first_peak_ratio``) join their engine's
  group without a ``system``.

Keys that only say a section did not run (``design``, ``planar.model``, ``experiment.model``:
NaN placeholders of a prototype-only or a skipped engine) have no place: :func:`store_location`
returns None. :func:`select` reads a key back from a store (a variable, or a constant stored once).

>>> store_location("3d.prototype.points.P-1.max_displacement_m")[:3]
('sim3d', 'max_displacement', (('system', 'prototype'), ('point', 'P-1')))
>>> store_location("3d.model.delivered_impulse_Ns.2")[1:4]
('delivered_impulse', (('system', 'model'), ('component', 'z')), 'N s')
>>> store_location("design.factors.velocity")[:2], store_location("design") is None
(('design/factors', 'velocity'), True)
"""

from __future__ import annotations

import re
from typing import NamedTuple, Optional

import numpy as np

from ..units import SUFFIXES, unit_of

__all__ = [
    "StoreLocation",
    "store_location",
    "select",
    "GROUPS",
    "SYSTEMS",
    "LIST_DIMENSIONS",
    "CONSTANT_GROUPS",
    "VALID_NAME",
    "coordinate_attrs",
    "label_order",
]

#: Section of a flat key -> its group in the store.
GROUPS = {
    "experiment": "experiment",
    "design": "design",
    "planar": "planar",
    "critical": "critical",
    "3d": "sim3d",
    "ensemble": "ensemble",
    "verdict": "verdict",
    "damage": "damage",
}

#: Labels of the ``system`` dimension, in store order.
SYSTEMS = ("prototype", "model")

#: List-valued entries (``name.0``, ``name.1``, ...): name -> (dimension, labels; None: 0, 1, ...).
LIST_DIMENSIONS = {
    "delivered_impulse": ("component", ("x", "y", "z")),
    "time_compared": ("bound", ("start", "end")),
    "drum_heights": ("drum", None),
}

#: Groups (with their sub-groups) whose variables that do not vary over the sweep are stored once,
#: as variables without the case dimensions (with their ``units``).
CONSTANT_GROUPS = ("experiment", "design")

#: The root variable of every case's validity (the flat key ``sweep.valid``).
VALID_NAME = "valid"
_VALID_KEY = "sweep.valid"

_CONTEXT = {
    "experiment": "experiment",
    "design": "model design",
    "planar": "planar rocking",
    "critical": "critical charge of the prototype, planar",
    "sim3d": "3D engine",
    "ensemble": "3D ensemble",
    "verdict": "the similarity verdict, docs/verdict.md",
    "damage": "damage state, 0 intact, 1-3 damaged slight to severe, 4 collapse",
    "damage/ensemble/counts": "ensemble members in this damage state",
    "design/factors": "scaling factor, specimen / prototype",
    "design/impulsive": "impulsive check",
}


class StoreLocation(NamedTuple):
    """A flat key's place in a sweep store: ``group`` (``""``: the root; ``"design/factors"``),
    ``name`` (an identifier), ``labels`` (``((dimension, label), ...)``, in store order:
    ``system``, ``point``, a list dimension), ``units``, ``long_name``."""

    group: str
    name: str
    labels: tuple
    units: str
    long_name: str

    @property
    def dims(self) -> tuple:
        """The extra dimensions of the variable (after the case dimensions)."""
        return tuple(d for d, _ in self.labels)


def _strip_unit(leaf: str) -> str:
    """``leaf`` without its unit suffix (the suffix :func:`~blastscale.units.unit_of` reads); a
    dimensionless suffix that is part of the meaning (``_rel_peak``) is kept."""
    for s in SUFFIXES:  # longest first: the first match is the one unit_of uses
        if leaf.endswith(s.suffix) and len(leaf) > len(s.suffix):
            return leaf if s.dimension == "dimensionless" else leaf[: -len(s.suffix)]
    return leaf


def store_location(key: str) -> Optional[StoreLocation]:
    """The place of a flat scalar key in a sweep store (module docstring), None for a key that
    only marks a section as not run.

    Parameters
    ----------
    key : str
        A key of ``StudyResult.scalars()`` or of the outcome mode (``planar.prototype.max_rotation_rad``).

    Returns
    -------
    StoreLocation or None

    Raises
    ------
    ValueError
        A key of an unknown section, or a leaf that is not an identifier once its unit is
        stripped (a key the store cannot name: the layout must learn it).
    """
    if key == _VALID_KEY:
        return StoreLocation(
            "",
            VALID_NAME,
            (),
            "1",
            "the Study ran the case (False: refused, e.g. a model scaled distance outside the "
            "blast fits; its other values are NaN)",
        )
    section, *rest = key.split(".")
    if section not in GROUPS:
        raise ValueError(
            f"key = {key!r}: section {section!r} has no group in a sweep store (known: {', '.join(GROUPS)})"
        )
    index = int(rest.pop()) if rest and rest[-1].isdigit() else None
    if not rest or rest[-1] in SYSTEMS + ("similarity", "points"):
        return None  # "design", "planar.model", "3d.similarity": the placeholder of a part not run
    system = point = None
    similarity = False
    sub: list = []
    parts, leaf = rest[:-1], rest[-1]
    i = 0
    while i < len(parts):
        p = parts[i]
        if p in SYSTEMS and system is None:
            system = p
        elif p == "similarity":
            similarity = True
        elif p == "points" and i + 1 < len(parts):
            i += 1
            point = parts[i]
        else:
            sub.append(p)
        i += 1
    name = _strip_unit(leaf)
    if not name.isidentifier() or not all(s.isidentifier() for s in sub):
        raise ValueError(f"key = {key!r}: {name!r} is not an identifier")
    labels = []
    if system is not None:
        labels.append(("system", system))
    if point is not None:
        labels.append(("point", point))
    if index is not None:
        dim, names = LIST_DIMENSIONS.get(name, (f"{name}_index", None))
        if names is not None and index >= len(names):
            raise ValueError(f"key = {key!r}: index {index} is beyond the {dim} labels {names}")
        labels.append((dim, index if names is None else names[index]))
    group = "/".join([GROUPS[section], *sub])
    context = _CONTEXT.get(group, group.replace("/", ", "))
    long_name = f"{name.replace('_', ' ')} ({context}{', model vs prototype' if similarity else ''})"
    return StoreLocation(group, name, tuple(labels), unit_of(leaf), long_name)


def label_order(dim: str, labels) -> list:
    """The labels of a store dimension in store order: ``system`` prototype then model, the list
    dimensions as their table, ``point`` naturally (P-2 before P-10), others sorted."""
    labels = set(labels)
    if dim == "system":
        return [s for s in SYSTEMS if s in labels]
    table = {d: names for d, names in LIST_DIMENSIONS.values() if names is not None}
    if dim in table:
        return [s for s in table[dim] if s in labels] + sorted(labels - set(table[dim]), key=str)
    return sorted(labels, key=lambda s: [int(t) if t.isdigit() else t for t in re.split(r"(\d+)", str(s))])


def coordinate_attrs(dim: str, group: str, labels=()) -> dict:
    """``long_name`` of a store dimension's labels in a group, and ``units`` ("1") where the labels are
    numbers (``drum`` 0, 1, ...); labels that are strings (``system``, ``point``, ``component``) have
    no units (CF conventions: ``units`` is for quantities)."""
    specimen = (
        "the specimen as built (model scale)"
        if group.split("/")[0] in CONSTANT_GROUPS
        else "the specimen up-scaled to prototype units"
    )
    names = {
        "system": f"prototype, or {specimen}",
        "point": "monitoring point",
        "component": "Cartesian component",
        "bound": "start or end of the interval",
        "drum": "drum index",
    }
    attrs = {"long_name": names.get(dim, dim.replace("_", " "))}
    return attrs if any(isinstance(lab, str) for lab in labels) else {"units": "1", **attrs}


def select(tree, key: str):
    """A flat key's values over the case grid, read back from a sweep store.

    Parameters
    ----------
    tree : xarray.DataTree
        A sweep store (:func:`blastscale.io.sweep_store.open_sweep`, or the tree of a sweep run
        in memory).
    key : str
        A flat key (``planar.prototype.max_rotation_rad``, ``design.model_charge_kg``).

    Returns
    -------
    xarray.DataArray
        Over the case dimensions; a constant (a value stored once, without the case dimensions) is
        broadcast over them, NaN where the case is not valid.

    Raises
    ------
    KeyError
        A key the store does not hold.
    """
    import xarray as xr

    loc = store_location(key)
    node = None
    if loc is not None:
        try:
            node = tree[loc.group] if loc.group else tree
        except KeyError:
            node = None
    if node is None:
        raise KeyError(f"{key!r} is not in this sweep store")
    valid = tree[VALID_NAME]
    if loc.name not in node.data_vars:
        raise KeyError(f"{key!r} is not in this sweep store")
    da = node[loc.name].sel(dict(loc.labels)).drop_vars(list(loc.dims), errors="ignore").rename(key)
    if set(valid.dims) <= set(da.dims):
        return da
    # a constant, stored once: broadcast over the cases, NaN where a case is not valid
    da = xr.DataArray(np.full(valid.shape, da.values), dims=valid.dims, coords=valid.coords, name=key, attrs=da.attrs)
    return da if bool(valid.all()) else da.where(valid)
