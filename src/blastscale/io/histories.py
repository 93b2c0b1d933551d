"""Files of response histories: NetCDF (a ``Response3D.dataset``, a study's DataTree with one group
per engine) and the tidy CSV of a study's histories (flat, for spreadsheets).

Written as every result file of :mod:`.results` is: into a unique temporary sibling
(``.<name>.partial-*``) renamed into place, so a reader never sees a half-written file and a failed
write leaves nothing behind. The engines (:mod:`blastscale.sim3d`, :mod:`blastscale.rocking`)
build datasets and write no files.
"""

from __future__ import annotations

import math
from pathlib import Path

from ..sim3d.results import MOTION_VARIABLES
from .results import write_atomic

__all__ = ["write_netcdf", "histories_tidy", "write_histories_csv"]


def write_netcdf(dataset, path: "str | Path", engine: str = "h5netcdf") -> Path:
    """Write an ``xarray.Dataset`` or ``xarray.DataTree`` (NetCDF-4 groups) to NetCDF atomically.

    Parameters
    ----------
    dataset : xarray.Dataset or xarray.DataTree
        E.g. ``Response3D.dataset``, or a study's :meth:`~blastscale.study.StudyResult.to_datatree`
        (units and dimensions in the variables' attributes).
    path : str or Path
        The file to write (replaced if it exists).
    engine : str
        xarray's NetCDF engine (``h5netcdf``: NetCDF4/HDF5, a dependency of ``blastscale[io]``).

    Returns
    -------
    Path
        ``path``.
    """
    # serialised in memory first, then written as plain bytes: HDF5 writing straight to a full disk
    # fails inside its finalisers (tracebacks it prints itself, then a crash), a plain write fails cleanly
    data = dataset.to_netcdf(None, engine=engine)
    write_atomic(path, bytes(data))
    return path


def histories_tidy(tree):
    """The histories of a study as a tidy table (one value per row), flat for spreadsheets.

    Columns: ``engine`` (the group: planar, sim3d, ensemble), ``system`` (prototype / model
    up-scaled), ``variable``, ``time_s``, ``element`` (body or monitoring point, "" when none),
    ``component`` ("" when none), ``member`` (ensemble member, "" when none), ``value`` and ``units``.
    The stored motion (poses, surfaces: :data:`blastscale.sim3d.results.MOTION_VARIABLES`) is left out:
    it is for replaying and drawing, and stays in the NetCDF file.

    Parameters
    ----------
    tree : xarray.DataTree
        :meth:`blastscale.study.StudyResult.to_datatree`.

    Returns
    -------
    pandas.DataFrame
    """
    import pandas as pd

    frames = []
    for node in tree.subtree:
        engine = node.name if node.parent is not None else ""
        for var, da in node.ds.data_vars.items():
            if var in MOTION_VARIABLES:
                continue
            df = da.to_dataframe(name="value").reset_index()
            ren = {
                d: {"time": "time_s", "component": "component", "member": "member"}.get(d, "element")
                for d in da.dims
                if d != "system"
            }
            df = df.rename(columns=ren)
            for col, empty in (("element", ""), ("component", ""), ("member", ""), ("time_s", math.nan)):
                if col not in df:  # e.g. totals have no time, single runs no member
                    df[col] = empty
            df["engine"], df["variable"], df["units"] = engine, var, da.attrs.get("units", "1")
            frames.append(df[_TIDY_COLUMNS])
    return pd.concat(frames, ignore_index=True) if frames else pd.DataFrame(columns=_TIDY_COLUMNS)


_TIDY_COLUMNS = ["engine", "system", "variable", "time_s", "element", "component", "member", "value", "units"]


def write_histories_csv(tree, path: "str | Path") -> None:
    """Write :func:`histories_tidy` of ``tree`` as CSV, atomically."""
    write_atomic(path, histories_tidy(tree).to_csv(index=False, float_format="%.10g"))
