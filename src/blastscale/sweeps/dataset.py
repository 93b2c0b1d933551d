"""A sweep's results as one ``xarray.Dataset``: one variable per scalar key over the grid axes (and
``sample``), the grid values and the draws as coordinates, units on everything, and the sweep's
description, fingerprint and versions as attributes. Built from the chunks' results, in any
order; nothing is written here (:mod:`blastscale.io.sweep_store` writes it)."""

from __future__ import annotations

import json
import time

import numpy as np

from ..units import unit_of
from .spec import SweepSpec

__all__ = ["assemble", "metadata"]


def assemble(spec: SweepSpec, chunks, meta: dict):
    """The dataset of a sweep from its chunks' results (``{"start", "stop", "values"}`` each).

    Parameters
    ----------
    spec : SweepSpec
    chunks : iterable of dict
        Every chunk of the sweep, each once.
    meta : dict
        Attributes (:func:`metadata`).

    Returns
    -------
    xarray.Dataset
    """
    import xarray as xr

    chunks = list(chunks)
    n = spec.n_cases
    data = {}
    keys = sorted({k for c in chunks for k in c["values"]})
    for k in keys:
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
                arr[c["start"]:c["stop"]] = v
        data[k] = (spec.dims, arr.reshape(spec.shape), {"units": unit_of(k)})
    coords = {a.name: (a.name, np.asarray(a.values), {"units": unit_of(a.path), "path": a.path}) for a in spec.axes}
    if spec.sampled:
        coords["sample"] = ("sample", np.arange(spec.samples))
        for s in spec.sampled:
            coords[s.name] = ("sample", spec.draws()[s.name],
                              {"units": "1" if s.relative else unit_of(s.path), "path": s.path,
                               "distribution": f"{s.distribution.kind}:{','.join(map(str, s.distribution.params))}",
                               "relative": int(s.relative)})
    return xr.Dataset(data, coords=coords, attrs=meta)


def metadata(spec: SweepSpec, chunk: int) -> dict:
    """Attributes of a sweep's dataset: its description (JSON), fingerprint, chunking, versions."""
    import platform

    import numba

    from .. import __version__

    return {
        "title": "blastscale sweep",
        "sweep": json.dumps(spec.describe(), default=str),
        "fingerprint": spec.fingerprint(),
        "chunk_size": int(chunk),
        "n_cases": spec.n_cases,
        "blastscale_version": __version__,
        "numpy_version": np.__version__,
        "numba_version": numba.__version__,
        "python_version": platform.python_version(),
        "scalars": ("outcome mode: first-swing outcomes and largest rotations of the prototype and the model "
                    "(blastscale.sweeps.outcomes.planar_outcomes)") if spec.outcomes else
                   "Study(scenario).run().scalars() per case",
        "created": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()),
    }
