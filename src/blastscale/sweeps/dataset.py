"""A sweep's results as one ``xarray.DataTree``: a group per engine or section (``planar``,
``sim3d``, ``ensemble``, ``design``, ``experiment``, ``critical``) whose variables span the case
grid (the varied fields, then ``sample``) and, where the key has them, ``system``, ``point`` and a
list dimension (``component``, ...; :mod:`.layout` places every flat key); the case validity
``valid``, the grid values and the draws at the root, with the sweep's description, fingerprint and
versions. Inputs that do not vary over the sweep (the ``experiment`` and ``design`` groups'
constant variables) are stored once, as variables without the case dimensions (0-d, or on their
``system``, ``point`` or list dimension), each with its ``units`` (CF conventions); label coordinates
(strings: ``system``, ``point``, ``component``) carry no ``units``. Built from the chunks' results,
in any order; nothing is written here (:func:`.run.run_sweep` has :mod:`blastscale.io.sweep_store` write it)."""

from __future__ import annotations

import json
import platform
import time

import numpy as np

from .. import __version__
from .._code import code_fingerprint
from ..units import unit_of
from .layout import CONSTANT_GROUPS, VALID_NAME, coordinate_attrs, label_order, store_location
from .outcomes import VALID_KEY
from .spec import SweepSpec

__all__ = ["assemble", "metadata", "STORE_VERSION"]

#: Layout version of a sweep store (root attribute ``store_version``): 3, the DataTree of groups with its
#: constants as variables (2: the same with constants as group attributes ``NAME`` and ``NAME_units``).
STORE_VERSION = 3


def _flat_arrays(spec: SweepSpec, chunks) -> dict:
    """Flat key -> array over the cases (bool or int where every case has a value of that kind,
    else float with NaN where a case has none)."""
    chunks = list(chunks)
    n = spec.n_cases
    out = {}
    for k in sorted({k for c in chunks for k in c["values"]}):
        vals = [None if c["values"].get(k) is None else np.asarray(c["values"][k]) for c in chunks]
        kinds = {v.dtype.kind for v in vals if v is not None}
        if kinds == {"b"} and all(v is not None for v in vals):
            arr = np.empty(n, dtype=bool)
        elif kinds <= {"i", "u", "b"} and all(v is not None for v in vals):
            arr = np.empty(n, dtype=np.int64)
        elif kinds <= {"i", "u", "b", "f"}:
            arr = np.full(n, np.nan)
        else:
            continue  # not a number (never produced by scalars())
        for c, v in zip(chunks, vals):
            if v is not None:
                arr[c["start"] : c["stop"]] = v
        out[k] = arr
    return out


def _variables(flat: dict) -> dict:
    """(group, name) -> {"loc": a StoreLocation, "keys": {labels: array}} (placeholders dropped)."""
    found: dict = {}
    for key, arr in flat.items():
        if key == VALID_KEY:
            continue
        loc = store_location(key)
        if loc is None:
            continue
        var = found.setdefault((loc.group, loc.name), {"loc": loc, "keys": {}})
        if var["loc"].dims != loc.dims or loc.labels in var["keys"]:
            raise ValueError(f"key = {key!r}: {loc.group}/{loc.name} {loc.labels} is taken by another key")
        var["keys"][loc.labels] = arr
    return found


def _constant(data: np.ndarray, valid: np.ndarray) -> bool:
    """Whether every valid case has the same values (NaN equal to NaN)."""
    rows = data.reshape(valid.size, -1)[valid.ravel()]
    if rows.shape[0] == 0:
        return False
    same = (rows == rows[0]) | (np.isnan(rows) & np.isnan(rows[0]) if rows.dtype.kind == "f" else False)
    return bool(np.all(same))


def _groups(spec: SweepSpec, flat: dict, valid: np.ndarray) -> dict:
    """group path -> (data variables, coordinates); a constant of a constant group
    (:data:`~.layout.CONSTANT_GROUPS`, the same values in every valid case) without the case dimensions."""
    shape, case_dims = spec.shape, spec.dims
    groups: dict = {}
    variables = _variables(flat)
    labels_of: dict = {}
    for (group, _), var in variables.items():
        for labels in var["keys"]:
            for dim, lab in labels:
                labels_of.setdefault((group, dim), set()).add(lab)
    for (group, name), var in sorted(variables.items()):
        loc = var["loc"]
        g = groups.setdefault(group, ({}, {}))
        coords = {d: label_order(d, labels_of[(group, d)]) for d in loc.dims}
        extra = tuple(len(coords[d]) for d in loc.dims)
        arrays = list(var["keys"].values())
        full = len(var["keys"]) == int(np.prod(extra, dtype=int))
        kinds = {a.dtype.kind for a in arrays}
        dtype = bool if full and kinds == {"b"} else np.int64 if full and kinds <= {"i", "u", "b"} else float
        data = np.full(shape + extra, np.nan) if dtype is float else np.empty(shape + extra, dtype=dtype)
        for labels, a in var["keys"].items():
            data[(Ellipsis, *(coords[d].index(lab) for d, lab in labels))] = a.reshape(shape) if shape else a[0]
        for d in loc.dims:
            g[1][d] = (d, coords[d], coordinate_attrs(d, group, coords[d]))
        attrs = {"units": loc.units, "long_name": loc.long_name}
        # stored once, without the case dimensions (unless named like one: xarray refuses a 0-d variable
        # named like a dimension of its dataset)
        if group.split("/")[0] in CONSTANT_GROUPS and name not in case_dims and _constant(data, valid):
            g[0][name] = (loc.dims, data.reshape((valid.size,) + extra)[int(np.argmax(valid.ravel()))], attrs)
        else:
            g[0][name] = (case_dims + loc.dims, data, attrs)
    return groups


def _case_coordinates(spec: SweepSpec) -> dict:
    """The grid values (on their dimensions) and the draws (on ``sample``), with units and long names."""
    coords = {
        a.name: (
            a.name,
            np.asarray(a.values),
            {"units": unit_of(a.path), "path": a.path, "long_name": f"{a.path} (grid)"},
        )
        for a in spec.axes
    }
    if spec.sampled:
        coords["sample"] = ("sample", np.arange(spec.samples), {"units": "1", "long_name": "Monte Carlo sample"})
        for s in spec.sampled:
            coords[s.name] = (
                "sample",
                spec.draws()[s.name],
                {
                    "units": "1" if s.relative else unit_of(s.path),
                    "path": s.path,
                    "distribution": f"{s.distribution.kind}:{','.join(map(str, s.distribution.params))}",
                    "relative": int(s.relative),
                    "long_name": f"{'factor on ' if s.relative else ''}{s.path} (draws)",
                },
            )
    return coords


def assemble(spec: SweepSpec, chunks, meta: dict):
    """The store of a sweep (module docstring) from its chunks' results.

    Parameters
    ----------
    spec : SweepSpec
    chunks : iterable of dict
        Every chunk of the sweep (``{"start", "stop", "values": {flat key: values}}``), each once.
    meta : dict
        Root attributes (:func:`metadata`).

    Returns
    -------
    xarray.DataTree
    """
    import xarray as xr

    flat = _flat_arrays(spec, chunks)
    valid = np.asarray(flat.get(VALID_KEY, np.ones(spec.n_cases)), dtype=bool).reshape(spec.shape)
    vloc = store_location(VALID_KEY)
    root = xr.Dataset(
        {VALID_NAME: (spec.dims, valid, {"units": vloc.units, "long_name": vloc.long_name})},
        coords=_case_coordinates(spec),
        attrs=meta,
    )
    nodes = {"/": root}
    for path, (data, coords) in _groups(spec, flat, valid).items():
        nodes[f"/{path}"] = xr.Dataset(data, coords=coords)
    return xr.DataTree.from_dict(nodes)


def metadata(spec: SweepSpec, chunk: int) -> dict:
    """Root attributes of a sweep's store: its description (JSON), fingerprint, chunking, versions."""

    import numba

    return {
        "title": "blastscale sweep",
        "Conventions": "CF-1.10",
        "store_version": STORE_VERSION,
        "sweep": json.dumps(spec.describe(), default=str),
        "fingerprint": spec.fingerprint(),
        "chunk_size": int(chunk),
        "n_cases": spec.n_cases,
        "blastscale_version": __version__,
        "blastscale_code": code_fingerprint(),
        "numpy_version": np.__version__,
        "numba_version": numba.__version__,
        "python_version": platform.python_version(),
        "scalars": (
            "outcome mode: first-swing outcomes and largest rotations of the prototype and the model "
            "(blastscale.sweeps.outcomes.planar_outcomes)"
        )
        if spec.outcomes
        else "Study(scenario).run().scalars() per case",
        "groups": "one per engine or section; system = prototype or model (the specimen: as built in experiment "
        "and design, up-scaled to prototype units in the engines); constants of experiment and design "
        "are variables without the case dimensions, with units",
        "created": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()),
    }
