"""Read the stored motion of a result folder (``histories.nc``, group ``sim3d``; ``summary.json``) for replay
and animation: :func:`read_motion`. A folder that cannot give it is one line naming it and why."""

from __future__ import annotations

import json
from pathlib import Path

from .._validate import BlastscaleInputError
from ..sim3d.replay import motion_of

__all__ = ["read_motion"]


def read_motion(folder, name: str = "RESULT_DIR"):
    """The :class:`~blastscale.sim3d.replay.Motion` of a result folder and what the drawing needs.

    Returns
    -------
    (Motion, dict)
        The motion (prototype units, prototype time) and ``title``, ``standoff_m`` (None under gravity alone),
        ``charge_kg``.
    """
    import xarray as xr

    p = Path(folder)
    nc = p / "histories.nc"
    if not p.is_dir():
        raise BlastscaleInputError(
            f"{name} = {str(folder)!r} is not a folder: give a result folder (blastscale run --out)"
        )
    if not nc.is_file():
        raise BlastscaleInputError(f"{name} = {str(folder)!r} is not a blastscale result folder: no histories.nc")
    try:
        tree = xr.open_datatree(nc)
    except (OSError, ValueError) as exc:
        raise BlastscaleInputError(f"{name} = {str(folder)!r}: histories.nc cannot be read ({exc})") from None
    with tree:
        if "sim3d" not in tree.children:
            raise BlastscaleInputError(
                f"{name} = {str(folder)!r} holds no 3D run: nothing moves in 3D (run with "
                'simulation.engine = "3d" or "both")'
            )
        ds = tree["sim3d"].to_dataset().load()
    if "body_position" not in ds:
        raise BlastscaleInputError(
            f"{name} = {str(folder)!r} was written before results kept the motion: run it again with this version"
        )
    info = {"title": str(tree.attrs.get("title", "")), "standoff_m": None, "charge_kg": None}
    try:
        proto = json.loads((p / "summary.json").read_text())["experiment"]["prototype"]
        if proto.get("charge_kg"):  # a charge of 0 is gravity alone: no charge to draw
            info.update(standoff_m=proto.get("standoff_m"), charge_kg=proto.get("charge_kg"))
    except (OSError, ValueError, KeyError, TypeError):
        pass  # drawn without the charge
    return motion_of(ds), info
