"""``blastscale block3d``: 3D rigid-body response of a single block on MuJoCo (the structure path, load A, B or C)."""

from __future__ import annotations

from typing import Optional

import typer

from .._validate import BlastscaleInputError
from ._app import app, console, fmt_value, one_line_warnings, print_json, save_figure, table
from . import options as opt
from .options import block_from_options, check_load_options, check_plot_path, contact_from_options

_SUMMARY_ROWS = (
    ("overturned", "overturned", "", ".6g"),
    ("max rotation", "max_rotation_rad", "rad", ".6g"),
    ("max sliding", "max_sliding_m", "m", ".6g"),
    ("final sliding", "final_sliding_m", "m", ".6g"),
    ("max uplift", "max_uplift_m", "m", ".3g"),
    ("peak angular velocity", "peak_angular_velocity_rad_s", "rad/s", ".6g"),
    ("peak velocity x", "peak_velocity_x_m_s", "m/s", ".6g"),
)


def _rows(summary: dict) -> list[tuple[str, str, str]]:
    return [(name, fmt_value(summary[k], fmt), u) for name, k, u, fmt in _SUMMARY_ROWS]


def _run(out, block, load, incidence, charge, standoff, scale, density_ratio, gravity_ratio, gravity, model, pulse,
         contact, duration, record_every, plot) -> None:
    """Fill ``out`` with the block's run(s) through the one structure path (every load method:
    :func:`~blastscale.analysis.systems.run_system` for the prototype alone,
    :func:`~blastscale.analysis.structure3d.compare_structure3d` with a model), the block3d keys
    from its dataset (:func:`~blastscale.analysis.block3d_similarity.block_summary`,
    :func:`~blastscale.analysis.block3d_similarity.block_similarity`)."""
    from ..analysis.block3d_similarity import block_dataset, block_similarity, block_summary
    from ..analysis.compare import upscale_dataset
    from ..analysis.structure3d import compare_structure3d, upscale_summary
    from ..analysis.systems import run_system
    from ..similitude import design_model

    design = design_model(charge, standoff, 1.0 if scale is None else scale, density_ratio, gravity_ratio,
                          model=model, gravity=gravity)
    kw = {"load": load, "pulse": pulse, "incidence": incidence, "contact": contact, "duration": duration,
          "record_every": record_every}
    if scale is None:
        proto = run_system(block, design, "prototype", **kw).response
        out["prototype"] = block_summary(proto, block)
        model_ds = None
    else:
        cmp = compare_structure3d(block, design, **kw)
        f = design.factors
        proto = cmp.prototype
        out["prototype"] = block_summary(proto, block)
        out["model"] = upscale_summary(block_summary(cmp.model, cmp.model_structure), f)
        out["similarity"] = block_similarity(
            block_dataset(proto, block), upscale_dataset(block_dataset(cmp.model, cmp.model_structure), f))
        out["model_experiment"] = {"charge_kg": design.model_charge_kg, "standoff_m": design.model_standoff_m,
                                   "height_m": block.height * scale}
        model_ds = cmp.upscaled_dataset
    if plot:
        from ..plots.column import plot_column_comparison

        save_figure(lambda: plot_column_comparison(block, proto.dataset, model_ds), plot)
        out["plot"] = plot


@app.command("block3d")
def block3d_cmd(
    height: float = opt.HEIGHT,
    width: Optional[float] = opt.WIDTH,
    alpha_deg: Optional[float] = opt.ALPHA_DEG,
    depth: float = opt.DEPTH,
    density: float = opt.DENSITY,
    charge: float = opt.CHARGE,
    standoff: float = opt.STANDOFF,
    duration: float = opt.DURATION,
    pulse: str = opt.PULSE,
    load: str = opt.LOAD,
    incidence: Optional[str] = opt.INCIDENCE,
    restitution: Optional[float] = typer.Option(
        None, "--restitution",
        help="Not applicable in 3D: restitution emerges from the inelastic contact (Housner's value is "
             "reproduced within 0.1%). Accepted for compatibility with `rock`; a value is rejected.",
    ),
    friction: float = typer.Option(0.7, "--friction", help="Coulomb friction coefficient mu \\[-] (paper: tan 35 deg)."),
    timestep: Optional[float] = typer.Option(
        None, "--timestep", help="Prototype time step \\[s] (default: derived from the block's size, 0.2 ms for a 10 m "
                                 "block; the model's is x sqrt(lambda)); the contact time constant is raised to 4 "
                                 "steps if needed; rejected past the engine's stability bound."),
    scale: Optional[float] = opt.SCALE,
    density_ratio: float = opt.DENSITY_RATIO,
    gravity_ratio: float = opt.GRAVITY_RATIO,
    gravity: float = opt.GRAVITY,
    model: str = opt.MODEL,
    record_every: int = typer.Option(5, "--record-every", help="Keep one state every N steps."),
    plot: Optional[str] = typer.Option(None, "--plot", help="Write histories and pose snapshots to this image file."),
    as_json: bool = opt.JSON,
) -> None:
    """Rocking, sliding and uplift of a rigid block under a blast (MuJoCo; the paper's Method A by default).

    Method A: the reflected pulse at the stand-off loads the whole front face at once (--load B,
    C: per face). Contact settings are derived from the block's own size; with --scale the model
    experiment is designed by the general law, run at model scale with scaled contact settings,
    up-scaled and compared with the prototype.
    """
    if restitution is not None:
        raise BlastscaleInputError(
            f"restitution = {restitution:g} is not applicable to block3d: in 3D the impact loss emerges from "
            "the inelastic contact (omit --restitution)"
        )
    block = block_from_options(height, width, alpha_deg, depth, density, required=True)
    check_load_options(load, incidence)
    check_plot_path(plot)
    contact = contact_from_options(block, friction, timestep, gravity)
    out: dict = {"inputs": {
        "height_m": block.height, "width_m": block.width, "depth_m": block.depth, "density_kg_m3": block.density,
        "charge_kg": charge, "standoff_m": standoff, "pulse": pulse, "model": model, "duration_s": duration,
        "load": load, "incidence": incidence,
        "scale": scale, "density_ratio": density_ratio if scale is not None else None,
        "gravity_ratio": gravity_ratio if scale is not None else None, "gravity_m_s2": gravity,
    }, "contact": contact.to_dict()}
    with one_line_warnings():  # e.g. friction near the pivoting threshold, blast-fit ranges
        _run(out, block, load, incidence, charge, standoff, scale, density_ratio, gravity_ratio, gravity, model, pulse,
             contact, duration, record_every, plot)
    if as_json:
        print_json(out)
        return
    console.print(table(f"Prototype: {block.height:g} x {block.width:.4g} x {block.depth:g} m block, "
                        f"{charge:g} kg TNT at {standoff:g} m ({model}, {pulse}, mu = {friction:g})", _rows(out["prototype"])))
    if scale is not None:
        console.print(table(f"Model lambda = {scale:g}, up-scaled to prototype units "
                            f"(model charge {out['model_experiment']['charge_kg']:.4g} kg)", _rows(out["model"])))
        s = out["similarity"]
        console.print(table("Similarity (prototype vs up-scaled model)", [
            ("max |rotation difference|", f"{s['max_abs_rotation_diff_rad']:.3g}", "rad"),
            ("max |sliding difference|", f"{s['max_abs_sliding_diff_m']:.3g}", "m"),
            ("max |uplift difference|", f"{s['max_abs_uplift_diff_m']:.3g}", "m"),
        ]))
    if plot:
        console.print(f"plot written to {plot}")
