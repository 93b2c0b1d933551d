"""From recorded MuJoCo states to a :class:`~.results.Response3D`: kinematics of the bodies and
monitoring points, uplift, the collapse criterion, attributes (settings, load, versions).

Pure numpy on the states :func:`~.integrate.integrate` returns (physical units).
"""

from __future__ import annotations

import json
from importlib.metadata import PackageNotFoundError, version

import numpy as np

from ..structures.base import top_monitoring_point
from .body_mesh import structure_meshes
from .results import VARIABLES, Response3D, body_heights
from .rotations import quaternion_to_matrix, tilt_angle

__all__ = ["collapse_flags", "fallen_flags", "response_from_states"]

#: The fall rule (:mod:`blastscale.structures.assembly`): a drop of the centre of mass by more than this
#: fraction of the body's own height, or a turn by more than this angle [deg], means the body fell.
FALL_DROP_FRACTION = 0.5
FALL_TILT_DEG = 45.0


def fallen_flags(structure, pos, R) -> np.ndarray:
    """Per recorded time and body: has the body fallen by then (the fall rule: its centre of mass
    below its height at time 0 by more than ``FALL_DROP_FRACTION`` of its own height, or turned from its
    orientation at time 0 by more than ``FALL_TILT_DEG``)? Cumulative over time, shape (n, nbody)."""
    drop = pos[0, :, 2][None, :] - pos[:, :, 2]
    rel = np.einsum("nbij,bkj->nbik", R, R[0])  # R(t) R(0)^T
    cos = np.clip((np.trace(rel, axis1=2, axis2=3) - 1.0) / 2.0, -1.0, 1.0)
    turned = np.arccos(cos) > np.radians(FALL_TILT_DEG)
    now = (drop > FALL_DROP_FRACTION * body_heights(structure)[None, :]) | turned
    return np.logical_or.accumulate(now, axis=0)


def collapse_flags(structure, pos, R, tilt) -> np.ndarray:
    """Per recorded time: did any body or sub-stack pass its toppling limit (the collapse
    criterion in the Notes of :class:`~.results.Response3D`)?

    Parameters
    ----------
    structure : structure
        The structure simulated.
    pos : array (n, nbody, 3)
        Centres of mass [m].
    R : array (n, nbody, 3, 3)
        Rotation matrices.
    tilt : array (n, nbody)
        Angle of each body's z axis from the vertical [rad].

    Returns
    -------
    ndarray (n,) of bool
    """
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


def _versions() -> dict:

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
    fallen_t = fallen_flags(structure, pos, R)
    if getattr(structure, "collapse_rule", None) == "fallen":  # assemblies: any block fell
        collapsed_t = fallen_t.any(axis=1)
    else:  # a block, a column: a body or a sub-stack past its toppling limit
        collapsed_t = collapse_flags(structure, pos, R, tilt)
    rel_end = np.einsum("bij,bkj->bik", R[-1], R[0])
    residual_rot = np.arccos(np.clip((np.trace(rel_end, axis1=1, axis2=2) - 1.0) / 2.0, -1.0, 1.0))
    hit = np.flatnonzero(collapsed_t)
    time = np.asarray(states["time"], dtype=float)
    vertices, faces = structure_meshes(structure)
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
        "fallen": fallen_t[-1].astype(np.int8),
        "residual_displacement": np.linalg.norm(pos[-1] - pos[0], axis=1),
        "residual_rotation": residual_rot,
        "body_position": pos,
        "body_quaternion": qpos[:, :, 3:7],
        "body_faces": faces,
        "body_vertices": vertices,
        "point_body": pb.astype(np.int32),
        "point_local_position": local,
    }
    dvars = {
        k: (VARIABLES[k][0], v, {"units": VARIABLES[k][1], "dimension": VARIABLES[k][2], "long_name": VARIABLES[k][3]})
        for k, v in data.items()
    }
    top_point = top_monitoring_point(structure).name  # the highest at rest: an arch's crown, a portal's lintel
    attrs = {
        "source": "blastscale.sim3d (MuJoCo)",
        "structure": json.dumps(structure.describe()),
        "first_arrival_time_s": float(states["first_arrival"]),
        "collapsed": int(hit.size > 0),
        "collapse_time_s": float(time[hit[0]]) if hit.size else "none",
        "top_point": top_point,
        "collapse_rule": getattr(structure, "collapse_rule", "toppling"),
        "gravity_only": int(bool(states.get("gravity_only", False))),
        **_versions(),
    }
    attrs.update({f"setting_{k}": _attr(v) for k, v in settings.items()})
    coords = {
        "time": ("time", time, {"units": "s", "dimension": "time", "long_name": "time after the first arrival"}),
        "body": ("body", [b.name for b in bodies]),
        "point": ("point", [p.name for p in points]),
        "component": ("component", ["x", "y", "z"]),
        "quaternion": ("quaternion", ["w", "x", "y", "z"]),
    }
    return Response3D(xr.Dataset(dvars, coords=coords, attrs=attrs), structure)
