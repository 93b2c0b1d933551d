"""The single block's planar view of a 3D run, and its prototype-vs-model figures.

A block is the one-body case of the structure engine (:func:`blastscale.sim3d.simulate_structure`
-> :class:`~blastscale.sim3d.Response3D`, any load method); its planar view is computed from that
response only (world frame: z up, blast towards +x; b, h the block's half-width and half-height):

* rotation theta [rad]: ``rotation_y`` of the response, ``atan2(R_xz, R_zz)``, positive when
  the top moves towards +x (rocking about the rear, +x, base edge). For planar motion it is the
  rocking angle of the paper's Eq. (eom).
* sliding [m]: x displacement of the base edge the block rests on (the +x edge when
  theta >= 0, the -x edge otherwise) from its position at time 0,

  .. math:: s = \\Delta x_G + \\sigma b (\\cos\\theta - 1) - h \\sin\\theta,\\qquad \\sigma = \\operatorname{sign}\\theta,

  exact for motion in the x-z plane (the edge at (sigma b, 0, -h) in the body frame). Pure
  rocking about a fixed edge gives zero sliding; pure translation the displacement of the block.
* uplift [m]: height of the lowest base corner above its rest height (negative values are the
  soft contact's penetration, a few micrometres at full scale); > 0 means flight.
* collapsed: the response's collapse, which for one block is |theta| > alpha = atan(b/h) (the
  centre of mass passed over a base edge; beyond it gravity drives the block down; Housner 1963).

:func:`block_dataset` gives these histories as a response dataset of the comparison contract
(:mod:`.compare`), :func:`block_summary` the ``block3d`` outcome keys, :func:`block_similarity`
the ``block3d`` similarity figures of a prototype and an up-scaled model
(:func:`~.compare.upscale_dataset`: lengths / lambda, times / lambda_t, velocities /
(lambda/lambda_t), angles unchanged, on the prototype's time grid). The runs themselves come
from :func:`~.structure3d.compare_structure3d` (prototype and model) or
:func:`~blastscale.sim3d.simulate_structure`.

Reference: Masi, Stefanou & Maffi-Berthier, *Scaling laws ...*, Sec. "FEM simulations"
(prototype vs lambda = 1/200 model, slender and non-slender blocks).
"""

from __future__ import annotations

import numpy as np

from .._validate import BlastscaleInputError
from .compare import compare_responses, upscale_dataset
from .upscale import upscale_summary

__all__ = [
    "BLOCK_VARIABLES",
    "COMPARED",
    "BLOCK_SUMMARY_KEYS",
    "BLOCK_SIMILARITY_KEYS",
    "block_dataset",
    "block_similarity",
    "block_summary",
    "block_view",
]

#: The variables of :func:`block_dataset`: name -> (units, physical dimension, description).
BLOCK_VARIABLES = {
    "rotation_y": ("rad", "angle", "rocking angle about +y, positive top towards +x"),
    "sliding": ("m", "length", "x displacement of the supporting base edge"),
    "uplift": ("m", "length", "height of the lowest base corner above its rest height"),
    "angular_velocity_y": ("rad/s", "angular_velocity", "angular velocity about +y, world frame"),
    "velocity_x": ("m/s", "velocity", "velocity x of the centre of mass"),
    "com_x": ("m", "length", "x of the centre of mass (0 at rest)"),
    "com_z": ("m", "length", "height of the centre of mass above the ground"),
}

#: The variables compared by :func:`block_similarity`.
COMPARED = ("rotation_y", "sliding", "uplift")

#: The keys of :func:`block_summary` (the ``block3d`` outcome keys), in order.
BLOCK_SUMMARY_KEYS = (
    "collapsed",
    "collapse_time_s",
    "max_rotation_rad",
    "max_sliding_m",
    "final_sliding_m",
    "max_uplift_m",
    "peak_angular_velocity_rad_s",
    "peak_velocity_x_m_s",
    "delivered_impulse_Ns",
)

#: The keys of :func:`block_similarity` (the ``block3d`` similarity keys), in order.
BLOCK_SIMILARITY_KEYS = (
    "max_abs_rotation_diff_rad",
    "max_abs_sliding_diff_m",
    "max_abs_uplift_diff_m",
    "first_peak_rotation_ratio",
    "outcomes_agree",
)


def _block_of(result, block):
    """The block simulated: ``block`` if given, else the response's own structure."""
    block = getattr(result, "structure", None) if block is None else block
    if block is None or not hasattr(block, "b") or not hasattr(block, "h") or len(block.bodies) != 1:
        raise BlastscaleInputError(f"block = {block!r} is not a RectangularBlock: the planar view needs one block")
    return block


def _planar_histories(result, block) -> dict:
    """The planar histories and outcome of a block's :class:`~blastscale.sim3d.Response3D`
    (module docstring), SI, in the run's own units."""
    if not hasattr(result, "dataset") or not hasattr(result, "summary"):
        raise BlastscaleInputError(f"result = {type(result).__name__} is not a Response3D (blastscale.sim3d)")
    block = _block_of(result, block)
    ds = result.dataset
    th = ds["rotation_y"].values[:, 0]
    dx = ds["com_displacement"].sel(component="x").values[:, 0]
    dz = ds["com_displacement"].sel(component="z").values[:, 0]
    side = np.where(th >= 0.0, 1.0, -1.0)
    summ = result.summary()
    rest = block.bodies[0].com
    return {
        "time": ds["time"].values,
        "rotation_y": th,
        "sliding": dx + side * block.b * (np.cos(th) - 1.0) - block.h * np.sin(th),
        "uplift": ds["uplift"].values[:, 0],
        "angular_velocity_y": ds["angular_velocity"].sel(component="y").values[:, 0],
        "velocity_x": ds["com_velocity"].sel(component="x").values[:, 0],
        "com_x": rest[0] + dx,
        "com_z": rest[2] + dz,
        "collapsed": bool(summ["collapsed"]),
        "collapse_time_s": summ.get("collapse_time_s"),
        "delivered_impulse_Ns": summ.get("delivered_impulse_Ns"),
    }


def block_dataset(result, block=None):
    """A single-block run's planar histories as a response dataset of the comparison contract.

    Parameters
    ----------
    result : Response3D
        The block's run, in its own units (any load method).
    block : RectangularBlock, optional
        The block simulated (b, h of the supporting edge); default ``result.structure``.

    Returns
    -------
    xarray.Dataset
        Coordinates ``time`` [s], ``body`` = ["block"]; variables :data:`BLOCK_VARIABLES`, each
        (time, body) with ``units``, ``dimension`` and ``long_name``; attribute ``collapsed``
        (0/1). No attribute carries a unit: :func:`~.compare.upscale_dataset` scales variables
        only (draw a pose with the block itself, :func:`blastscale.plots.sim3d.plot_snapshots`).
    """
    import xarray as xr

    block = _block_of(result, block)
    h = _planar_histories(result, block)
    data = {
        name: (
            ("time", "body"),
            np.asarray(h[name], dtype=float)[:, None],
            {"units": u, "dimension": dim, "long_name": text},
        )
        for name, (u, dim, text) in BLOCK_VARIABLES.items()
    }
    return xr.Dataset(
        data,
        coords={"time": ("time", np.asarray(h["time"], dtype=float), {"units": "s"}), "body": ["block"]},
        attrs={"collapsed": int(h["collapsed"]), "source": "blastscale.sim3d (MuJoCo), block"},
    )


def block_summary(result, block=None) -> dict:
    """The ``block3d`` outcome keys of a block run (:class:`~blastscale.sim3d.Response3D`, SI, its
    own units): ``collapsed``, ``collapse_time_s`` (None when it stands), ``max_rotation_rad``,
    ``max_sliding_m``, ``final_sliding_m``, ``max_uplift_m``, ``peak_angular_velocity_rad_s``,
    ``peak_velocity_x_m_s``, ``delivered_impulse_Ns`` ([x, y, z]). ``block`` defaults to
    ``result.structure``."""
    h = _planar_histories(result, block)
    return {
        "collapsed": bool(h["collapsed"]),
        "collapse_time_s": h["collapse_time_s"],
        "max_rotation_rad": float(np.max(np.abs(h["rotation_y"]))),
        "max_sliding_m": float(np.max(np.abs(h["sliding"]))),
        "final_sliding_m": float(h["sliding"][-1]),
        "max_uplift_m": float(np.max(h["uplift"])),
        "peak_angular_velocity_rad_s": float(np.max(np.abs(h["angular_velocity_y"]))),
        "peak_velocity_x_m_s": float(np.max(np.abs(h["velocity_x"]))),
        "delivered_impulse_Ns": h["delivered_impulse_Ns"],
    }


def block_similarity(prototype_ds, upscaled_ds) -> dict:
    """The block3d ``similarity`` block of two block histories in prototype units.

    .. math:: \\Delta_q = \\max_{t_k} |q_p(t_k) - q_m^{up}(t_k)|

    with the up-scaled history interpolated linearly onto the prototype's times t_k (where
    they overlap), by :func:`~.compare.compare_responses`. Velocities are not compared: during
    the pulse they rise over the blast's own duration, whose model/prototype ratio differs
    from lambda_t.

    Parameters
    ----------
    prototype_ds : xarray.Dataset
        :func:`block_dataset` of the prototype run [SI, prototype units].
    upscaled_ds : xarray.Dataset
        :func:`block_dataset` of the model run up-scaled by :func:`~.compare.upscale_dataset`.

    Returns
    -------
    dict
        ``max_abs_rotation_diff_rad`` [rad], ``max_abs_sliding_diff_m`` [m],
        ``max_abs_uplift_diff_m`` [m], ``first_peak_rotation_ratio`` [-] (up-scaled model /
        prototype first rocking peak) and ``outcomes_agree`` (both overturn or neither).
    """
    c = compare_responses(prototype_ds, upscaled_ds, variables=list(COMPARED), outcome="collapsed")
    v = c["variables"]
    return {
        "max_abs_rotation_diff_rad": v["rotation_y"]["block"]["max_abs_diff"],
        "max_abs_sliding_diff_m": v["sliding"]["block"]["max_abs_diff"],
        "max_abs_uplift_diff_m": v["uplift"]["block"]["max_abs_diff"],
        "first_peak_rotation_ratio": v["rotation_y"]["block"].get("first_peak_ratio"),
        "outcomes_agree": c.get("outcomes_agree"),
    }


def block_view(prototype, block=None, model=None, specimen_block=None, factors=None) -> dict:
    """The block's planar view of a prototype run and, when given, of its specimen's run: the
    ``block3d`` keys.

    Parameters
    ----------
    prototype : Response3D
        The prototype block's run [SI].
    block : RectangularBlock, optional
        The prototype block (default ``prototype.structure``).
    model : Response3D, optional
        The specimen's run, in its own units.
    specimen_block : RectangularBlock, optional
        The specimen block (default ``model.structure``).
    factors : ScalingFactors, optional
        Specimen / prototype factors (needed with ``model``).

    Returns
    -------
    dict
        ``prototype``: :func:`block_summary`; ``model``: the specimen's, up-scaled to prototype units
        (:func:`~.upscale.upscale_summary`); ``similarity``: :func:`block_similarity` of the
        prototype and the up-scaled specimen (both None without ``model``).
    """

    out = {"prototype": block_summary(prototype, block), "model": None, "similarity": None}
    if model is not None:
        if factors is None:
            raise BlastscaleInputError("factors = None: the specimen's run needs the design's factors to be up-scaled")
        out["model"] = upscale_summary(block_summary(model, specimen_block), factors)
        out["similarity"] = block_similarity(
            block_dataset(prototype, block), upscale_dataset(block_dataset(model, specimen_block), factors)
        )
    return out
