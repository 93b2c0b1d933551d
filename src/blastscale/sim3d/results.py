"""The result of a 3D run: :class:`Response3D`, an ``xarray.Dataset`` of the recorded response.

Dimensions ``time``, ``body``, ``point``, ``component`` (and ``quaternion``, ``vertex``, ``face``,
``corner`` for the stored motion, :data:`MOTION_VARIABLES`); units and physical ``dimension`` in every
variable's attributes (:data:`VARIABLES`). Built from the recorded states by
:func:`~.record.response_from_states`. A single block's planar view (rotation about y, sliding
of its supporting edge, uplift, overturning) is read from it by
:mod:`blastscale.analysis.block3d_similarity`; files are written by
:func:`blastscale.io.histories.write_netcdf`.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field

import numpy as np

__all__ = [
    "Response3D",
    "VARIABLES",
    "MOTION_VARIABLES",
    "STANDS_FRACTION",
    "REST_SPEED_FRACTION",
    "REST_WINDOW_FRACTION",
    "final_speed_rel",
    "stability_of",
    "body_heights",
]

#: The variables of :attr:`Response3D.dataset`: name -> (dims, units, physical dimension, description).
VARIABLES = {
    "com_displacement": (
        ("time", "body", "component"),
        "m",
        "length",
        "displacement of the centre of mass from its position at time 0",
    ),
    "com_velocity": (("time", "body", "component"), "m/s", "velocity", "velocity of the centre of mass"),
    "angular_velocity": (("time", "body", "component"), "rad/s", "angular_velocity", "angular velocity, world frame"),
    "tilt": (("time", "body"), "rad", "angle", "angle of the body z axis from the vertical"),
    "rotation_y": (
        ("time", "body"),
        "rad",
        "angle",
        "signed rocking angle about +y, atan2(R_xz, R_zz), positive top towards +x",
    ),
    "point_displacement": (
        ("time", "point", "component"),
        "m",
        "length",
        "displacement of the monitoring point from its position at time 0",
    ),
    "point_velocity": (("time", "point", "component"), "m/s", "velocity", "velocity of the monitoring point"),
    "n_contacts": (("time",), "1", "count", "active contact points"),
    "uplift": (("time", "body"), "m", "length", "height of the lowest base point above its rest height"),
    "delivered_impulse": (("body", "component"), "N s", "momentum", "impulse of the blast forces on each body"),
    "fallen": (("body",), "1", "dimensionless", "1 when the body fell (docs/assemblies.md, the fall rule)"),
    "residual_displacement": (
        ("body",),
        "m",
        "length",
        "distance of the centre of mass from its position at time 0, at the end",
    ),
    "residual_rotation": (("body",), "rad", "angle", "angle of the body's rotation from time 0, at the end"),
    # the motion, for replay and drawing (docs/motion.md): poses at every recorded time
    "body_position": (
        ("time", "body", "component"),
        "m",
        "length",
        "world position of the body frame's origin (the centre of mass)",
    ),
    "body_quaternion": (
        ("time", "body", "quaternion"),
        "1",
        "dimensionless",
        "orientation of the body frame, unit quaternion (w, x, y, z), body to world",
    ),
    "body_vertices": (
        ("body", "vertex", "component"),
        "m",
        "length",
        "vertices of the body's solid in its frame (NaN past its own count)",
    ),
    "body_faces": (
        ("body", "face", "corner"),
        "1",
        "count",
        "outward triangles of the body's surface, indices into body_vertices (-1 past its own count)",
    ),
    "point_body": (("point",), "1", "count", "index of the body carrying the monitoring point"),
    "point_local_position": (("point", "component"), "m", "length", "monitoring point in its body's frame"),
}

#: The variables that store the motion itself (poses, surfaces, where the points sit on their bodies):
#: a result folder replays and draws from them (:mod:`blastscale.sim3d.replay`); not histories to tabulate.
MOTION_VARIABLES = (
    "body_position",
    "body_quaternion",
    "body_vertices",
    "body_faces",
    "point_body",
    "point_local_position",
)

#: Stability under gravity alone (:func:`stability_of`): a structure at rest whose largest residual
#: displacement of a centre of mass is at most this fraction of its height "stands" (5 mm at 5 m);
#: more, at rest and no block fallen: "settles". Chosen above the soft contacts' compliance (the
#: semicircular arches of docs/assemblies.md, t/R 0.12-0.14, drift 0.6-0.8 mm in 5 s: 1.5e-4 H).
STANDS_FRACTION = 1e-3
#: At rest: the largest speed of any block (centre-of-mass speed plus angular speed x half its
#: height) over the last :data:`REST_WINDOW_FRACTION` of the run below this fraction of
#: sqrt(g H) (0.7 mm/s at 5 m). The engine's soft contacts creep at ~2e-5 sqrt(g H) on the standing
#: arches; a collapsing arch already moves at ~1e-2 sqrt(g H) 0.2 s into its fall.
REST_SPEED_FRACTION = 1e-4
#: The closing fraction of the run over which "at rest" is judged.
REST_WINDOW_FRACTION = 0.1


def body_heights(structure) -> np.ndarray:
    """Each body's own height at rest [m] (``structure.heights`` when it has one per body, else twice
    the depth of its base below its centre of mass)."""
    bodies = structure.bodies
    h = getattr(structure, "heights", None)
    if h is not None and len(h) == len(bodies):
        return np.asarray(h, dtype=float)
    return np.array([-2.0 * b.base_height for b in bodies])


def final_speed_rel(ds, heights, structure_height: float, gravity: float) -> float:
    """The largest speed of any body over the run's last :data:`REST_WINDOW_FRACTION`, over sqrt(g H) [-]: a body's
    speed is its centre of mass's plus its angular speed times half its own height ``heights`` [m] (the fastest
    point of a rocking block); H = ``structure_height`` [m], g = ``gravity`` [m/s^2]. The one rest-speed figure
    of :func:`stability_of` and of the at-rest check (:func:`blastscale.sim3d.rest.rest_state`)."""
    speed = (
        np.linalg.norm(ds["com_velocity"].values, axis=2)
        + np.linalg.norm(ds["angular_velocity"].values, axis=2) * 0.5 * np.asarray(heights)[None, :]
    )
    n = speed.shape[0]
    return float(speed[min(int((1.0 - REST_WINDOW_FRACTION) * n), n - 1) :].max() / np.sqrt(gravity * structure_height))


def stability_of(ds, heights, structure_height: float, gravity: float) -> tuple:
    """The outcome of a run under gravity alone, with the two figures it rests on.

    Rule (docs/assemblies.md): **collapses** when a block fell (the fall rule); otherwise **stands**
    when it is at rest at the end (largest block speed over the last :data:`REST_WINDOW_FRACTION` of
    the run, v_k = |v_com| + |omega| h_k / 2, below :data:`REST_SPEED_FRACTION` sqrt(g H)) and
    every residual displacement is at most :data:`STANDS_FRACTION` H; **settles** when at rest with
    a larger residual displacement; **moving** when neither at rest nor fallen by the end (undecided:
    run longer).

    Parameters
    ----------
    ds : xarray.Dataset
        :attr:`Response3D.dataset`.
    heights : array (nbody,)
        Each block's own height [m].
    structure_height : float
        H [m].
    gravity : float
        g [m/s^2].

    Returns
    -------
    (str, float, float)
        The outcome, the final speed over sqrt(g H) [-], the largest residual displacement over H [-].
    """
    h = max(float(structure_height), 1e-300)
    fallen = ds["fallen"].values.astype(bool)
    v_rel = final_speed_rel(ds, heights, h, gravity)
    d_rel = float(ds["residual_displacement"].values.max() / h)
    if bool(ds.attrs["collapsed"]) or fallen.any():
        return "collapses", v_rel, d_rel
    if v_rel > REST_SPEED_FRACTION:
        return "moving", v_rel, d_rel
    return ("stands" if d_rel <= STANDS_FRACTION else "settles"), v_rel, d_rel


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

    def bodies_summary(self) -> dict:
        """Per body and for the structure: ``fallen_blocks``, ``fallen_mass_fraction``,
        ``max_residual_displacement_m``, ``bodies`` {name: ``delivered_impulse_Ns`` [x, y, z],
        ``max_displacement_m`` (largest distance of its centre of mass from time 0),
        ``residual_displacement_m``, ``residual_rotation_rad``, ``fallen``}; under gravity alone also
        ``stability``: "stands", "settles", "collapses" or "moving" (:func:`stability_of`), with
        ``final_speed_rel_sqrt_gh`` and ``max_residual_displacement_rel_height`` [-], its two figures."""
        ds = self.dataset
        names = [str(b) for b in ds["body"].values]
        fallen = ds["fallen"].values.astype(bool)
        masses = (
            np.array([b.mass for b in self.structure.bodies]) if self.structure is not None else np.ones(len(names))
        )
        disp = np.linalg.norm(ds["com_displacement"].values, axis=2).max(axis=0)
        res = ds["residual_displacement"].values
        out = {
            "fallen_blocks": int(fallen.sum()),
            "fallen_mass_fraction": float(masses[fallen].sum() / masses.sum()),
            "max_residual_displacement_m": float(res.max()),
            "bodies": {
                n: {
                    "delivered_impulse_Ns": [float(x) for x in ds["delivered_impulse"].values[k]],
                    "max_displacement_m": float(disp[k]),
                    "residual_displacement_m": float(res[k]),
                    "residual_rotation_rad": float(ds["residual_rotation"].values[k]),
                    "fallen": bool(fallen[k]),
                }
                for k, n in enumerate(names)
            },
        }
        if int(ds.attrs.get("gravity_only", 0)):
            h = float(json.loads(ds.attrs["structure"]).get("height_m", 1.0))
            g = float(ds.attrs.get("setting_gravity_m_s2", 9.80665))
            hk = body_heights(self.structure) if self.structure is not None else np.full(len(names), h)
            out["stability"], out["final_speed_rel_sqrt_gh"], out["max_residual_displacement_rel_height"] = (
                stability_of(ds, hk, h, g)
            )
        return out

    def summary(self) -> dict:
        """Scalar outcomes (strict JSON): ``collapsed``, ``collapse_time_s`` (None if not),
        ``max_top_displacement_m`` (largest horizontal displacement of the top point),
        ``max_rotation_rad``, ``delivered_impulse_Ns`` ([x, y, z] total), ``first_arrival_time_s``,
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
            "max_rotation_rad": float(ds["tilt"].values.max()),
            "delivered_impulse_Ns": [float(x) for x in ds["delivered_impulse"].values.sum(axis=0)],
            "first_arrival_time_s": float(ds.attrs["first_arrival_time_s"]),
            "points": {
                n: {
                    "max_displacement_m": float(hd[:, k].max()),
                    "max_displacement_x_m": float(np.abs(pd[:, k, 0]).max()),
                    "max_velocity_m_s": float(hv[:, k].max()),
                }
                for k, n in enumerate(names)
            },
            **self.bodies_summary(),
        }
