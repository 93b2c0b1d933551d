"""Prototype vs reduced-scale model of a single block in 3D (MuJoCo), up-scaled and compared.

The model experiment is designed with :func:`blastscale.similitude.design_model` (charge and
stand-off from the scaling law), the model block is ``block.scaled(lambda, gamma)``, the
contact settings are ``contact.scaled(lambda, lambda_t)`` with lambda_t the time factor, and
gravity is ``varsigma g``. Both runs use the paper's Method A load. The block's planar
histories are written as response datasets (:func:`block_dataset`), up-scaled and compared with
the package's one comparison contract (:mod:`.compare`: lengths / lambda, times / lambda_t,
velocities / (lambda/lambda_t), angles unchanged, on the prototype's time grid).

Two views of the same engine path: :func:`block_summary`, :func:`block_dataset` and
:func:`block_similarity` read the block3d figures from any run's ``Response3D`` (the ``block3d``
command runs every load method through :func:`~.structure3d.compare_structure3d`), and
:func:`compare_block3d` keeps the planar recorders of :class:`~blastscale.sim3d.Block3DResult`
(pivot-edge sliding in the body frame, the blast momentum sum |F| dt, up-scaling of the planar
histories) for library users of the Method A block.

Reference: Masi, Stefanou & Maffi-Berthier, *Scaling laws ...*, Sec. "FEM simulations"
(prototype vs lambda = 1/200 model, slender and non-slender blocks).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .._validate import BlastscaleInputError
from ..blast.parameters import DEFAULT_BLAST_MODEL
from ..sim3d.contact import ContactSettings
from ..sim3d.results import Block3DResult
from ..sim3d.simulate import Block3DSimulator
from ..structures.block import STANDARD_GRAVITY, RectangularBlock
from .compare import compare_responses, upscale_dataset

__all__ = ["Block3DComparison", "block_dataset", "block_similarity", "block_summary", "compare_block3d"]

#: Block variable -> (Block3DResult attribute, units, dimension) of :func:`block_dataset`.
_BLOCK_VARIABLES = {
    "rotation_y": ("rotation", "rad", "angle"),
    "sliding": ("sliding", "m", "length"),
    "uplift": ("uplift", "m", "length"),
}


def _planar_histories(result, block) -> dict:
    """time, rotation, sliding, uplift, angular velocity about y, velocity x and the outcome of a
    block run: a :class:`Block3DResult`, or a :class:`~blastscale.sim3d.Response3D` of the block
    (any load method), whose sliding of the supporting base edge is then
    ``dx_com + s b (cos theta - 1) - h sin theta`` (s = sign of theta; exact for motion in the
    x-z plane, as Block3DResult's)."""
    if hasattr(result, "rotation"):
        return {"time": result.time, "rotation_y": result.rotation, "sliding": result.sliding,
                "uplift": result.uplift, "omega_y": result.angular_velocity, "velocity_x": result.velocity_x,
                "overturned": result.overturned, "overturn_time_s": result.overturn_time,
                "delivered_impulse_Ns": result.summary().get("delivered_impulse_Ns")}
    if block is None:
        raise BlastscaleInputError("block = None: a Response3D needs its RectangularBlock (half-width, half-height)")
    ds = result.dataset
    th = ds["rotation_y"].values[:, 0]
    dx = ds["com_displacement"].sel(component="x").values[:, 0]
    side = np.where(th >= 0.0, 1.0, -1.0)
    summ = result.summary()
    return {"time": ds["time"].values, "rotation_y": th,
            "sliding": dx + side * block.b * (np.cos(th) - 1.0) - block.h * np.sin(th),
            "uplift": ds["uplift"].values[:, 0], "omega_y": ds["angular_velocity"].sel(component="y").values[:, 0],
            "velocity_x": ds["com_velocity"].sel(component="x").values[:, 0],
            "overturned": bool(summ["collapsed"]), "overturn_time_s": summ.get("collapse_time_s"),
            "delivered_impulse_Ns": summ.get("delivered_impulse_Ns")}


def block_dataset(result, block: RectangularBlock | None = None):
    """A single-block run's planar histories as a response dataset of the comparison contract.

    Parameters
    ----------
    result : Block3DResult or Response3D
        A run, in its own units (a Response3D of the block from any load method).
    block : RectangularBlock, optional
        The block simulated (needed for a Response3D: the supporting edge's sliding).

    Returns
    -------
    xarray.Dataset
        Coordinates ``time`` [s], ``body`` = ["block"]; variables ``rotation_y`` [rad]
        (dimension ``angle``), ``sliding`` and ``uplift`` [m] (``length``), each (time, body);
        attribute ``overturned`` (0/1).
    """
    import xarray as xr

    h = _planar_histories(result, block)
    data = {name: (("time", "body"), np.asarray(h[name], dtype=float)[:, None], {"units": u, "dimension": dim})
            for name, (_, u, dim) in _BLOCK_VARIABLES.items()}
    return xr.Dataset(data, coords={"time": ("time", np.asarray(h["time"], dtype=float), {"units": "s"}),
                                    "body": ["block"]},
                      attrs={"overturned": int(h["overturned"]), "source": "blastscale.sim3d (MuJoCo), block"})


def block_summary(result, block: RectangularBlock | None = None) -> dict:
    """The ``block3d`` outcome keys of a block run (Block3DResult or Response3D, SI): ``overturned``,
    ``overturn_time_s``, ``max_rotation_rad``, ``max_sliding_m``, ``final_sliding_m``,
    ``max_uplift_m``, ``peak_angular_velocity_rad_s``, ``peak_velocity_x_m_s``,
    ``delivered_impulse_Ns`` ([x, y, z]); a Block3DResult's own ``summary()``."""
    if isinstance(result, Block3DResult):
        return result.summary()
    h = _planar_histories(result, block)
    return {
        "overturned": bool(h["overturned"]),
        "overturn_time_s": h["overturn_time_s"],
        "max_rotation_rad": float(np.max(np.abs(h["rotation_y"]))),
        "max_sliding_m": float(np.max(np.abs(h["sliding"]))),
        "final_sliding_m": float(h["sliding"][-1]),
        "max_uplift_m": float(np.max(h["uplift"])),
        "peak_angular_velocity_rad_s": float(np.max(np.abs(h["omega_y"]))),
        "peak_velocity_x_m_s": float(np.max(np.abs(h["velocity_x"]))),
        "delivered_impulse_Ns": h["delivered_impulse_Ns"],
    }


def _figures(comparison: dict) -> dict:
    """The block3d ``similarity`` figures of a :func:`~.compare.compare_responses` dict of two
    :func:`block_dataset` s (outcome ``overturned``)."""
    v = comparison["variables"]
    return {
        "max_abs_rotation_diff_rad": v["rotation_y"]["block"]["max_abs_diff"],
        "max_abs_sliding_diff_m": v["sliding"]["block"]["max_abs_diff"],
        "max_abs_uplift_diff_m": v["uplift"]["block"]["max_abs_diff"],
        "first_peak_rotation_ratio": v["rotation_y"]["block"].get("first_peak_ratio"),
        "outcomes_agree": comparison.get("outcomes_agree"),
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
    return _figures(compare_responses(prototype_ds, upscaled_ds, variables=list(_BLOCK_VARIABLES),
                                      outcome="overturned"))


@dataclass(frozen=True, eq=False)
class Block3DComparison:
    """Result of :func:`compare_block3d`.

    Attributes
    ----------
    design : blastscale.similitude.ModelDesign
        The designed model experiment (charges, stand-offs, factors).
    prototype : Block3DResult
        Prototype run.
    model : Block3DResult
        Model run, in model units.
    model_upscaled : Block3DResult
        Model run in prototype units.
    differences : dict
        The three ``max_abs_*_diff`` figures of :func:`block_similarity` (prototype vs up-scaled model).
    comparison : dict
        The contract's full comparison (:func:`~.compare.compare_responses` of
        :func:`block_dataset`): first peaks, differences relative to the peak, outcomes.
    """

    design: object
    prototype: Block3DResult
    model: Block3DResult
    model_upscaled: Block3DResult
    differences: dict
    comparison: dict = None

    def summary(self) -> dict:
        """``prototype`` and ``model`` (up-scaled) outcomes and the ``similarity`` block
        (:func:`block_similarity`'s keys)."""
        from .structure3d import upscale_summary

        return {
            "prototype": self.prototype.summary(),
            "model": upscale_summary(self.model.summary(), self.design.factors),
            "similarity": {**self.differences, **(_figures(self.comparison) if self.comparison else {})},
        }


def compare_block3d(
    block: RectangularBlock,
    charge: float,
    standoff: float,
    scale: float,
    *,
    density_ratio: float | None = 1.0,
    gravity_ratio: float = 1.0,
    law: str = "general",
    model: str = DEFAULT_BLAST_MODEL,
    pulse: str = "friedlander",
    contact: ContactSettings | None = None,
    duration: float = 5.0,
    gravity: float = STANDARD_GRAVITY,
    record_every: int = 1,
    blast_mode: str = "auto",
    design=None,
) -> Block3DComparison:
    """Run a block and its reduced-scale model in 3D and compare them in prototype units.

    Parameters
    ----------
    block : RectangularBlock
        Prototype block.
    charge, standoff : float
        Prototype charge W [kg TNT] and stand-off R [m].
    scale : float
        Geometric scale lambda [-].
    density_ratio : float or None
        gamma [-]; None with ``law="hopkinson-cranz"`` (that law imposes 1/sqrt(varsigma lambda)).
    gravity_ratio : float
        varsigma [-].
    law : {"general", "hopkinson-cranz"}
        Scaling law used to design the model charge.
    model : str
        Blast model (``"kingery-bulmash"``, ``"masi2021"``).
    pulse : {"friedlander", "triangular", "impulsive"}
        Pulse shape (the same for both).
    contact : ContactSettings, optional
        Prototype contact settings; the model uses ``contact.scaled(lambda, lambda_t)``. None
        (default): the engine's scale-consistent defaults for each block
        (:func:`~blastscale.sim3d.contact.default_contact`, mu = 0.7).
    duration : float
        Prototype simulated time [s]; the model runs ``duration * lambda_t``.
    gravity : float
        Prototype gravity [m/s^2].
    record_every : int
        Recording interval in steps (the same at both scales, so the grids coincide).
    blast_mode : str
        See :class:`~blastscale.sim3d.simulate.Block3DSimulator`.
    design : blastscale.similitude.ModelDesign, optional
        A design made beforehand (a caller that designs once, e.g. :class:`blastscale.study.Study`);
        it then replaces the design from ``charge`` ... ``gravity``, which must describe the same scenario.

    Returns
    -------
    Block3DComparison
    """
    from ..similitude import design_model

    design = design if design is not None else design_model(
        charge,
        standoff,
        scale,
        density_ratio=density_ratio,
        gravity_ratio=gravity_ratio,
        law=law,
        model=model,
        geometry=block,
        gravity=gravity,
    )
    f = design.factors
    model_block = block.scaled(f.length, f.density)
    proto_sim = Block3DSimulator(contact, gravity, record_every, blast_mode=blast_mode)
    model_sim = Block3DSimulator(None if contact is None else contact.scaled(f.length, f.time), gravity * f.gravity,
                                 record_every, blast_mode=blast_mode)
    proto = proto_sim.run(block, design.prototype.pulse(pulse), duration)
    mod = model_sim.run(model_block, design.model.pulse(pulse), duration * f.time)
    up = mod.upscaled(f.length, f.time, f.momentum)  # the planar view, for summaries and plots
    pds, uds = block_dataset(proto), upscale_dataset(block_dataset(mod), f)
    cmp = compare_responses(pds, uds, variables=list(_BLOCK_VARIABLES), outcome="overturned")
    diffs = {k: v for k, v in _figures(cmp).items() if k.startswith("max_abs_")}
    return Block3DComparison(design, proto, mod, up, diffs, cmp)
