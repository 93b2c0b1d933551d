"""Recorders and results of 3D runs (pure numpy on recorded states).

:class:`Response3D` is the result of any structure (:func:`~.simulate.simulate_structure`): an
``xarray.Dataset`` with dimensions ``time``, ``body``, ``point``, ``component`` and units and
physical ``dimension`` in every variable's attributes (:data:`VARIABLES`). A single block's
planar view (rotation about y, sliding of its supporting edge, uplift, overturning) is read from
it by :mod:`blastscale.analysis.block3d_similarity`.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field

import numpy as np

__all__ = ["Response3D", "VARIABLES", "quaternion_to_matrix", "response_from_states", "tilt_angle"]


def quaternion_to_matrix(q) -> np.ndarray:
    """Rotation matrices (..., 3, 3) from unit quaternions (..., 4) ordered (w, x, y, z)."""
    q = np.asarray(q, dtype=float)
    w, x, y, z = np.moveaxis(q, -1, 0)
    return np.stack(
        [
            np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)], -1),
            np.stack([2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)], -1),
            np.stack([2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)], -1),
        ],
        -2,
    )


def tilt_angle(R) -> np.ndarray:
    """Rotation about the pivot axis y [rad]: ``atan2(R[0, 2], R[2, 2])`` for matrices (..., 3, 3)."""
    R = np.asarray(R, dtype=float)
    return np.arctan2(R[..., 0, 2], R[..., 2, 2])


#: The variables of :attr:`Response3D.dataset`: name -> (dims, units, physical dimension, description).
VARIABLES = {
    "com_displacement": (("time", "body", "component"), "m", "length",
                         "displacement of the centre of mass from its position at time 0"),
    "com_velocity": (("time", "body", "component"), "m/s", "velocity", "velocity of the centre of mass"),
    "angular_velocity": (("time", "body", "component"), "rad/s", "angular_velocity", "angular velocity, world frame"),
    "tilt": (("time", "body"), "rad", "angle", "angle of the body z axis from the vertical"),
    "rotation_y": (("time", "body"), "rad", "angle",
                   "signed rocking angle about +y, atan2(R_xz, R_zz), positive top towards +x"),
    "point_displacement": (("time", "point", "component"), "m", "length",
                           "displacement of the monitoring point from its position at time 0"),
    "point_velocity": (("time", "point", "component"), "m/s", "velocity", "velocity of the monitoring point"),
    "n_contacts": (("time",), "1", "count", "active contact points"),
    "uplift": (("time", "body"), "m", "length", "height of the lowest base point above its rest height"),
    "delivered_impulse": (("body", "component"), "N s", "momentum", "impulse of the blast forces on each body"),
}


def _collapse(structure, pos, R, tilt) -> np.ndarray:
    """Per recorded time: did any body or sub-stack pass its toppling limit (module docstring of
    :class:`Response3D`)? ``tilt`` (n, nbody) [rad] is each body's z axis from the vertical.
    Returns the flag per time (n,)."""
    bodies = structure.bodies
    nb = len(bodies)
    masses = np.array([b.mass for b in bodies])
    top_angle = np.array([b.toppling_angle for b in bodies])
    bad = tilt > top_angle[None, :]
    # sub-stack j..N-1: its centre of mass, projected vertically onto the base plane of body j,
    # must lie within body j's base (expressed in body j's frame)
    for j in range(nb):
        com = np.einsum("k,nkc->nc", masses[j:], pos[:, j:]) / masses[j:].sum()
        rel = np.einsum("nji,nj->ni", R[:, j], com - pos[:, j])  # body frame of j (R^T v)
        down = -R[:, j, 2, :]  # world -z in body j's frame: rows of R^T are R[:, :, k]... (R^T e_z) = R[2, :]
        zb = bodies[j].base_height
        with np.errstate(divide="ignore", invalid="ignore"):
            t = (zb - rel[:, 2]) / down[:, 2]
        foot = rel + t[:, None] * down
        sx, sy = bodies[j].shape.support_radius
        out = (np.abs(foot[:, 0]) > sx) | (np.abs(foot[:, 1]) > sy) | ~np.isfinite(t) | (down[:, 2] >= 0.0)
        bad[:, j] |= out
    return bad.any(axis=1)


@dataclass(frozen=True, eq=False)
class Response3D:
    """Response of a structure of rigid bodies (MuJoCo run), as an ``xarray.Dataset``.

    Attributes
    ----------
    dataset : xarray.Dataset
        Coordinates ``time`` [s] (after the load's first arrival), ``body``, ``point``,
        ``component`` ("x", "y", "z"); variables :data:`VARIABLES`, each with ``units`` and
        ``dimension`` attributes; attributes: structure description, settings, load,
        ``first_arrival_time_s``, versions, and the collapse outcome.
    structure : object
        The structure simulated.

    Notes
    -----
    **Collapse** (``summary()["collapsed"]``): at some recorded time either a body tilts beyond
    its own toppling angle (``RigidBody.toppling_angle``, the tilt at which its centre of mass
    passes over its base edge), or the centre of mass of a sub-stack (body j and every body
    above it) projects vertically outside the base of body j (the support of the sub-stack;
    for body 0 the whole structure over its base on the ground). For one block both reduce to
    |theta| > alpha. A top displacement threshold is not used: the paper's square column under
    500 kg at 10 m sways > 1 m at the top and stands.
    """

    dataset: object
    structure: object = field(repr=False, default=None)

    @property
    def time(self) -> np.ndarray:
        """Time after first arrival [s]."""
        return self.dataset["time"].values

    @property
    def top_point(self) -> str:
        """Name of the default monitoring point of the top body (P-N)."""
        return str(self.dataset.attrs["top_point"])

    def summary(self) -> dict:
        """Scalar outcomes (strict JSON): ``collapsed``, ``collapse_time_s`` (None if not),
        ``max_top_displacement_m`` (largest horizontal displacement of the top point),
        ``max_tilt_rad``, ``delivered_impulse_Ns`` ([x, y, z] total), ``first_arrival_time_s``,
        and per point ``max_displacement_m`` (horizontal), ``max_displacement_x_m``,
        ``max_velocity_m_s`` (horizontal)."""
        ds = self.dataset
        pd = ds["point_displacement"].values
        pv = ds["point_velocity"].values
        hd = np.hypot(pd[..., 0], pd[..., 1])
        hv = np.hypot(pv[..., 0], pv[..., 1])
        names = [str(p) for p in ds["point"].values]
        top = names.index(self.top_point)
        ct = ds.attrs["collapse_time_s"]
        return {
            "collapsed": bool(ds.attrs["collapsed"]),
            "collapse_time_s": None if (isinstance(ct, str) or not math.isfinite(ct)) else float(ct),
            "max_top_displacement_m": float(hd[:, top].max()),
            "max_tilt_rad": float(ds["tilt"].values.max()),
            "delivered_impulse_Ns": [float(x) for x in ds["delivered_impulse"].values.sum(axis=0)],
            "first_arrival_time_s": float(ds.attrs["first_arrival_time_s"]),
            "points": {n: {"max_displacement_m": float(hd[:, k].max()),
                           "max_displacement_x_m": float(np.abs(pd[:, k, 0]).max()),
                           "max_velocity_m_s": float(hv[:, k].max())} for k, n in enumerate(names)},
        }


def _versions() -> dict:
    from importlib.metadata import PackageNotFoundError, version

    out = {}
    for pkg in ("blastscale", "mujoco", "numpy", "xarray"):
        try:
            out[f"version_{pkg}"] = version(pkg)
        except PackageNotFoundError:  # pragma: no cover - editable installs have metadata
            out[f"version_{pkg}"] = "unknown"
    return out


def _attr(v):
    """A NetCDF-safe attribute value (None -> "none", bool -> int, dict/list -> JSON)."""
    if v is None:
        return "none"
    if isinstance(v, bool):
        return int(v)
    if isinstance(v, (dict, list, tuple)):
        return json.dumps(v)
    return v


def response_from_states(structure, states: dict, settings: dict) -> Response3D:
    """Build the :class:`Response3D` of recorded MuJoCo states.

    Parameters
    ----------
    structure : structure
        The structure simulated (bodies in MuJoCo order, body id = index + 1).
    states : dict
        ``time`` (n,) [s], ``qpos`` (n, 7 nbody), ``qvel`` (n, 6 nbody), ``ncon`` (n,),
        ``delivered`` (nbody, 3) [N s], ``first_arrival`` [s].
    settings : dict
        Settings and load description (stored as attributes).

    Returns
    -------
    Response3D
    """
    import xarray as xr

    bodies = structure.bodies
    nb = len(bodies)
    qpos = states["qpos"].reshape(len(states["time"]), nb, 7)
    qvel = states["qvel"].reshape(len(states["time"]), nb, 6)
    pos = qpos[:, :, 0:3]
    R = quaternion_to_matrix(qpos[:, :, 3:7])  # (n, nb, 3, 3)
    omega = np.einsum("nbij,nbj->nbi", R, qvel[:, :, 3:6])
    vel = qvel[:, :, 0:3].copy()
    tilt = np.arccos(np.clip(R[:, :, 2, 2], -1.0, 1.0))
    base_z = []
    for k, b in enumerate(bodies):
        bp = b.shape.base_points()
        z = pos[:, k, None, 2] + np.einsum("nj,pj->np", R[:, k, 2, :], bp)
        base_z.append(z.min(axis=1) - (b.com[2] + bp[:, 2].min()))
    uplift = np.stack(base_z, axis=1)
    points = structure.monitoring_points
    pb = np.array([p.body for p in points], dtype=int)
    local = np.array([p.position for p in points], dtype=float).reshape(-1, 3)
    rel = np.einsum("npij,pj->npi", R[:, pb], local)
    pw = pos[:, pb] + rel
    pvel = vel[:, pb] + np.cross(omega[:, pb], rel)
    collapsed_t = _collapse(structure, pos, R, tilt)
    hit = np.flatnonzero(collapsed_t)
    time = np.asarray(states["time"], dtype=float)
    data = {
        "com_displacement": pos - pos[0],
        "com_velocity": vel,
        "angular_velocity": omega,
        "tilt": tilt,
        "rotation_y": tilt_angle(R),
        "point_displacement": pw - pw[0],
        "point_velocity": pvel,
        "n_contacts": np.asarray(states["ncon"]),
        "uplift": uplift,
        "delivered_impulse": np.asarray(states["delivered"], dtype=float),
    }
    dvars = {k: (VARIABLES[k][0], v, {"units": VARIABLES[k][1], "dimension": VARIABLES[k][2],
                                      "long_name": VARIABLES[k][3]}) for k, v in data.items()}
    top_body = nb - 1
    top_point = next((p.name for p in points if p.body == top_body), points[-1].name)
    attrs = {
        "source": "blastscale.sim3d (MuJoCo)",
        "structure": json.dumps(structure.describe()),
        "first_arrival_time_s": float(states["first_arrival"]),
        "collapsed": int(hit.size > 0),
        "collapse_time_s": float(time[hit[0]]) if hit.size else "none",
        "top_point": top_point,
        **_versions(),
    }
    attrs.update({f"setting_{k}": _attr(v) for k, v in settings.items()})
    coords = {
        "time": ("time", time, {"units": "s", "dimension": "time", "long_name": "time after the first arrival"}),
        "body": ("body", [b.name for b in bodies]),
        "point": ("point", [p.name for p in points]),
        "component": ("component", ["x", "y", "z"]),
    }
    return Response3D(xr.Dataset(dvars, coords=coords, attrs=attrs), structure)
