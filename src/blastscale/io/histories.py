"""NetCDF files of response histories (a ``Response3D.dataset``, a comparison's ``to_dataset()``).

Written as every result file of :mod:`.results` is: into a temporary sibling
(``.<name>.partial``) renamed into place, so a reader never sees a half-written file and a failed
write leaves nothing behind. The engines (:mod:`blastscale.sim3d`, :mod:`blastscale.rocking`)
build datasets and write no files.
"""

from __future__ import annotations

import os
from pathlib import Path

__all__ = ["write_netcdf"]


def write_netcdf(dataset, path: "str | Path", engine: str = "h5netcdf") -> Path:
    """Write an ``xarray.Dataset`` to NetCDF atomically.

    Parameters
    ----------
    dataset : xarray.Dataset
        E.g. ``Response3D.dataset`` (units and dimensions in the variables' attributes).
    path : str or Path
        The file to write (replaced if it exists).
    engine : str
        xarray's NetCDF engine (``h5netcdf``: NetCDF4/HDF5, a dependency of ``blastscale[io]``).

    Returns
    -------
    Path
        ``path``.
    """
    path = Path(path)
    tmp = path.with_name(f".{path.name}.partial")  # the temporary sibling of results.write_atomic
    try:
        dataset.to_netcdf(tmp, engine=engine)
        os.replace(tmp, path)
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise
    return path
