"""``blastscale block3d``: 3D rigid-body response of a single block on MuJoCo (the structure path, load A, B or C).

The flags build a :class:`~blastscale.scenario.Scenario` (engine ``3d``; no ``--scale``: the
prototype alone) and the :class:`~blastscale.study.Study` runs it; ``--json`` is formatted from
the study's result (its ``3d`` summary carries the block's planar keys).
"""

from __future__ import annotations

from typing import Optional

import typer

from .._validate import BlastscaleInputError
from ..analysis.block3d_similarity import BLOCK_SIMILARITY_KEYS, BLOCK_SUMMARY_KEYS
from ..similitude.factors import to_specimen
from . import options as opt
from ._app import app
from ._output import console, fmt_value, table
from .flags import scenario_from_flags
from .steps import (
    SIMILARITY_TITLE,
    BlockFlags,
    add_comparison_3d_figure,
    answer,
    blast_keys_3d,
    print_model_3d,
    run_checked_3d,
    scale_keys,
)

_SUMMARY_ROWS = (
    ("collapsed", "collapsed", "", ".6g"),
    ("max rotation", "max_rotation_rad", "rad", ".6g"),
    ("max sliding", "max_sliding_m", "m", ".6g"),
    ("final sliding", "final_sliding_m", "m", ".6g"),
    ("max uplift", "max_uplift_m", "m", ".3g"),
    ("peak angular velocity", "peak_angular_velocity_rad_s", "rad/s", ".6g"),
    ("peak velocity x", "peak_velocity_x_m_s", "m/s", ".6g"),
)


def _rows(summary: dict) -> list[tuple[str, str, str]]:
    return [(name, fmt_value(summary[k], fmt), u) for name, k, u, fmt in _SUMMARY_ROWS]


def block3d_output(result, contact, incidence: Optional[str] = None) -> dict:
    """The ``block3d --json`` object of a study of a block on the 3D engine: ``inputs`` (from the
    scenario; ``incidence`` as given, None for the default), ``contact`` (the prototype's contact
    settings), ``prototype`` and, with a design, ``model`` (up-scaled), ``similarity`` and
    ``model_experiment``: the block's planar keys of the study's ``3d`` summary."""

    sc, block, d = result.scenario, result.structure, result.design
    scale = None if d is None else d.scale
    out: dict = {
        "inputs": {
            "height_m": block.height,
            "width_m": block.width,
            "depth_m": block.depth,
            "density_kg_m3": block.density,
            "charge_kg": sc.blast.charge_kg,
            "standoff_m": sc.blast.standoff_m,
            "pulse_shape": sc.blast.pulse_shape,
            "blast_model": sc.blast.blast_model,
            "duration_s": sc.simulation.duration_s,
            "load": sc.blast.load,
            "incidence": incidence,
            "scale": scale,
            "density_ratio": None if d is None else d.density_ratio,
            "gravity_ratio": None if d is None else d.gravity_ratio,
            "gravity_m_s2": sc.simulation.gravity_m_s2,
        },
        "contact": contact.to_dict(),
    }
    s3 = result.summary()["3d"]
    out["prototype"] = {k: s3["prototype"][k] for k in BLOCK_SUMMARY_KEYS}
    if d is not None:
        out["model"] = {k: s3["model"][k] for k in BLOCK_SUMMARY_KEYS}
        out["similarity"] = {k: s3["similarity"][k] for k in BLOCK_SIMILARITY_KEYS}
        out["model_experiment"] = {
            "charge_kg": d.specimen_charge_kg,
            "standoff_m": d.specimen_standoff_m,
            "height_m": to_specimen(block.height, d.factors, "length"),
        }
    return out


@app.command("block3d")
def block3d_cmd(
    height: float = opt.HEIGHT,
    width: Optional[float] = opt.WIDTH,
    alpha_deg: Optional[float] = opt.ALPHA_DEG,
    depth: float = opt.DEPTH,
    density: float = opt.DENSITY,
    charge: float = opt.CHARGE,
    standoff: float = opt.STANDOFF,
    duration: Optional[float] = opt.DURATION_3D,
    pulse_shape: Optional[str] = opt.PULSE_3D,
    load: Optional[str] = opt.LOAD,
    incidence: Optional[str] = opt.INCIDENCE,
    restitution: Optional[float] = typer.Option(
        None,
        "--restitution",
        help="Not applicable in 3D: restitution emerges from the inelastic contact (Housner's value is "
        "reproduced within 0.1%). Accepted for compatibility with `rock`; a value is rejected.",
    ),
    friction: Optional[float] = opt.FRICTION_3D,
    timestep: Optional[float] = typer.Option(
        None,
        "--timestep",
        help="Prototype time step \\[s] (default: derived from the block's size, 0.2 ms for a 10 m "
        "block; the model's is x sqrt(lambda)); the contact time constant is raised to 4 "
        "steps if needed; rejected past the engine's stability bound.",
    ),
    scale: Optional[float] = opt.SCALE,
    density_ratio: float = opt.DENSITY_RATIO,
    gravity_ratio: float = opt.GRAVITY_RATIO,
    gravity: float = opt.GRAVITY,
    blast_model: Optional[str] = opt.MODEL_3D,
    record_every: Optional[int] = opt.RECORD_EVERY,
    plot: Optional[str] = typer.Option(None, "--plot", help="Write histories and pose snapshots to this image file."),
    as_json: bool = opt.JSON,
) -> None:
    """Rocking, sliding and uplift of a rigid block under a blast (MuJoCo; the paper's Method A by default).

    Method A: the reflected pulse at the stand-off loads the whole front face at once (--load B,
    C: per face). Contact settings are derived from the block's own size; with --scale the model
    experiment is designed by the general law, run at model scale with scaled contact settings,
    up-scaled and compared with the prototype.
    """

    _check_restitution(restitution)
    flags = BlockFlags(height, width, alpha_deg, depth, density)
    flags.block(plot)
    sc = scenario_from_flags(
        structure=flags.structure_keys(friction=friction),
        blast=blast_keys_3d(charge, standoff, blast_model, pulse_shape, load, incidence),
        scale=scale_keys(scale, density_ratio, gravity_ratio),
        simulation={
            "engine": "3d",
            "duration_s": duration,
            "gravity_m_s2": gravity,
            "timestep_s": timestep,
            "record_every": record_every,
            "critical_charge": False,
        },
    )
    result, contact = run_checked_3d(sc, as_json)
    out = block3d_output(result, contact, incidence)
    add_comparison_3d_figure(out, result, result.response3d.prototype.dataset, plot)
    answer(out, as_json=as_json, engine="3d", plot=plot, tables=lambda: _print_tables(result, out, scale))


def _check_restitution(restitution: Optional[float]) -> None:
    """``--restitution`` is accepted for compatibility with ``rock`` but has no value in 3D."""
    if restitution is not None:
        raise BlastscaleInputError(
            f"restitution = {restitution:g} is not applicable to block3d: in 3D the impact loss emerges from "
            "the inelastic contact (omit --restitution)"
        )


def _print_tables(result, out: dict, scale: Optional[float]) -> None:
    """The prototype's table and, with a model, the up-scaled model's and the similarity's."""
    block, sc = result.structure, result.scenario
    b = sc.blast
    console.print(
        table(
            f"Prototype: {block.height:g} x {block.width:.4g} x {block.depth:g} m block, "
            f"{b.charge_kg:g} kg TNT at {b.standoff_m:g} m ({b.blast_model}, {b.pulse_shape}, "
            f"mu = {sc.structure.friction:g})",
            _rows(out["prototype"]),
        )
    )
    if scale is None:
        return
    print_model_3d(scale, out, _rows(out["model"]))
    s = out["similarity"]
    console.print(
        table(
            SIMILARITY_TITLE,
            [
                ("max |rotation difference|", f"{s['max_abs_rotation_diff_rad']:.3g}", "rad"),
                ("max |sliding difference|", f"{s['max_abs_sliding_diff_m']:.3g}", "m"),
                ("max |uplift difference|", f"{s['max_abs_uplift_diff_m']:.3g}", "m"),
            ],
        )
    )
