"""The result of a 3D run: :class:`Response3D`, an ``xarray.Dataset`` of the recorded response.

Dimensions ``time``, ``body``, ``point``, ``component``; units and physical ``dimension`` in every
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

__all__ = ["Response3D", "VARIABLES", "STANDS_FRACTION"]

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
    "fallen": (("body",), "1", "dimensionless", "1 when the body fell (docs/assemblies.md, the fall rule)"),
    "residual_displacement": (("body",), "m", "length", "distance of the centre of mass from its position at "
                              "time 0, at the end"),
    "residual_rotation": (("body",), "rad", "angle", "angle of the body's rotation from time 0, at the end"),
}

#: Largest displacement of any body, as a fraction of the structure's height, for which a structure under
#: gravity alone "stands" (1 mm at 10 m); more, with no body fallen, it "settles"; a body fell: "collapses".
STANDS_FRACTION = 1e-4


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
        ``stability``: "stands", "settles" or "collapses" (:data:`STANDS_FRACTION`)."""
        ds = self.dataset
        names = [str(b) for b in ds["body"].values]
        fallen = ds["fallen"].values.astype(bool)
        masses = np.array([b.mass for b in self.structure.bodies]) if self.structure is not None else np.ones(len(names))
        disp = np.linalg.norm(ds["com_displacement"].values, axis=2).max(axis=0)
        res = ds["residual_displacement"].values
        out = {
            "fallen_blocks": int(fallen.sum()),
            "fallen_mass_fraction": float(masses[fallen].sum() / masses.sum()),
            "max_residual_displacement_m": float(res.max()),
            "bodies": {n: {"delivered_impulse_Ns": [float(x) for x in ds["delivered_impulse"].values[k]],
                           "max_displacement_m": float(disp[k]), "residual_displacement_m": float(res[k]),
                           "residual_rotation_rad": float(ds["residual_rotation"].values[k]),
                           "fallen": bool(fallen[k])} for k, n in enumerate(names)},
        }
        if int(ds.attrs.get("gravity_only", 0)):
            h = float(json.loads(ds.attrs["structure"]).get("height_m", 1.0))
            out["stability"] = ("collapses" if bool(ds.attrs["collapsed"]) or fallen.any() else
                                "stands" if disp.max() <= STANDS_FRACTION * h else "settles")
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
            "points": {n: {"max_displacement_m": float(hd[:, k].max()),
                           "max_displacement_x_m": float(np.abs(pd[:, k, 0]).max()),
                           "max_velocity_m_s": float(hv[:, k].max())} for k, n in enumerate(names)},
            **self.bodies_summary(),
        }
