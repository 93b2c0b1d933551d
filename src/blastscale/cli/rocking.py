"""``blastscale rock``: planar rocking under blast (paper Eq. eom); ``critical`` and ``capacity`` are in
:mod:`.capacity`.

Units at this edge: lengths in m, density in kg/m^3, charge in kg TNT, times in s, the
slenderness angle in degrees (``--alpha-deg``); results are SI (rad, rad/s, s, kg, m).
"""

from __future__ import annotations

import math
from typing import Optional

import typer

from ..blast.load_model import load_model_record
from ..similitude.factors import to_specimen
from ..study.engines import load_model_of
from ..study.study import Study
from . import blast_flags as bf, options as opt
from ._app import app
from ._output import activity, console, fmt_value, table
from .flags import flags_named, scenario_from_flags
from .steps import SIMILARITY_TITLE, BlockFlags, add_figure, answer, scale_keys

RESTITUTION_HELP = "Coefficient of restitution e on the angular velocity at impacts \\[-], in \\[0, 1] (default Housner's 1 - 1.5 sin^2 alpha)."


def _summary_rows(s: dict) -> list[tuple[str, str, str]]:
    return [
        ("collapsed", fmt_value(s["collapsed"]), ""),
        ("max |rotation|", fmt_value(s["max_rotation_rad"]), "rad"),
        ("overturn (tipping) time", fmt_value(s["collapse_time_s"]), "s"),
        ("first impact time", fmt_value(s["first_impact_time_s"]), "s"),
        ("impacts", str(s["n_impacts"]), ""),
    ]


def _load_model_record(result) -> dict:
    """Which load model produced a Study's planar result (prototype and, with a design, model)."""

    sc, d = result.scenario, result.design
    lm = load_model_of(sc, result.structure) if d is None else d.load_model  # the design's, with a design
    proto = load_model_record(result.blast.blast_model, result.blast.burst, lm)
    if d is None:
        return {"prototype": proto}
    return {
        "prototype": proto,
        "model": load_model_record(d.specimen.blast_model, d.specimen.burst, d.specimen_load_model),
    }


def block_inputs(block, **kw) -> dict:
    """The ``inputs`` record of a command's JSON: the block's height, width, depth [m], density [kg/m^3] and
    slenderness angle [rad], then ``kw`` (the command's other inputs, keys with their unit)."""
    d = {
        "height_m": block.height,
        "width_m": block.width,
        "depth_m": block.depth,
        "density_kg_m3": block.density,
        "alpha_rad": block.alpha,
    }
    d.update(kw)
    return d


@app.command("rock")
def rock_cmd(
    height: float = opt.HEIGHT,
    width: Optional[float] = opt.WIDTH,
    alpha_deg: Optional[float] = opt.ALPHA_DEG,
    depth: float = opt.DEPTH,
    density: float = opt.DENSITY,
    charge: float = opt.CHARGE,
    standoff: float = opt.STANDOFF,
    duration: float = opt.DURATION,
    pulse_shape: str = opt.PULSE,
    restitution: Optional[float] = typer.Option(None, "--restitution", help=RESTITUTION_HELP),
    scale: Optional[float] = opt.SCALE,
    density_ratio: float = opt.DENSITY_RATIO,
    gravity_ratio: float = opt.GRAVITY_RATIO,
    gravity: float = opt.GRAVITY,
    blast_model: str = opt.MODEL,
    burst: str = bf.BURST,
    clearing: bool = bf.CLEARING,
    negative_phase: bool = bf.NEGATIVE_PHASE,
    negative_phase_model: Optional[str] = bf.NEGATIVE_PHASE_MODEL,
    samples: int = typer.Option(
        opt._SIMULATION["samples"].default, "--samples", help="Sampling times for the comparison and the plot \\[-]."
    ),
    plot: Optional[str] = typer.Option(
        None, "--plot", help="Write theta(t), theta_dot(t) and the phase portrait to this image file."
    ),
    as_json: bool = opt.JSON,
) -> None:
    """Rocking response of a rigid block to a blast: overturning, its time, the first impact.

    The reflected pulse at the stand-off loads the front face uniformly (paper Method A,
    Eq. eom). With --scale the model experiment is designed with the paper's general law,
    simulated, up-scaled to prototype units and compared with the prototype.
    """

    flags = BlockFlags(height, width, alpha_deg, depth, density)
    block = flags.block(plot)
    bf.check_burst_flag(burst)
    sc = scenario_from_flags(
        structure=flags.structure_keys(),
        blast={
            "charge_kg": charge,
            "standoff_m": standoff,
            "blast_model": blast_model,
            "pulse_shape": pulse_shape,
            "burst": burst,
            "clearing": clearing,
            "negative_phase": negative_phase,
            **bf.negative_phase_model_key(negative_phase, negative_phase_model),
        },
        scale=scale_keys(scale, density_ratio, gravity_ratio),
        simulation={
            "engine": "planar",
            "duration_s": duration,
            "samples": samples,
            "gravity_m_s2": gravity,
            "restitution": restitution,
            "critical_charge": False,
        },
    )
    inputs = block_inputs(
        block,
        charge_kg=charge,
        standoff_m=standoff,
        duration_s=duration,
        pulse_shape=pulse_shape,
        blast_model=blast_model,
        restitution=restitution,
        gravity_m_s2=gravity,
        scale=scale,
        density_ratio=density_ratio if scale is not None else None,
        gravity_ratio=gravity_ratio if scale is not None else None,
    )
    with flags_named(), activity("simulating the rocking response", quiet=as_json):
        result = Study(sc).run()
    out = _rock_output(result, block, inputs)
    add_figure(out, lambda: _rocking_figure(result), plot)
    answer(out, as_json=as_json, engine="planar", plot=plot, tables=lambda: _print_tables(result, block, out))


def _rock_output(result, block, inputs: dict) -> dict:
    """The ``rock --json`` object: ``inputs``, the planar result's keys and, with a design, the model
    experiment; the prototype's restitution and the load model used."""
    planar = result.planar
    out: dict = {"inputs": inputs}
    out.update({k: v for k, v in planar.to_dict().items() if v is not None})
    d = result.design
    if d is not None:
        out["model_experiment"] = {
            "charge_kg": d.specimen_charge_kg,
            "standoff_m": d.specimen_standoff_m,
            "height_m": to_specimen(block.height, d.factors, "length"),
            "width_m": to_specimen(block.width, d.factors, "length"),
            "density_kg_m3": to_specimen(block.density, d.factors, "density"),
            "time_factor": d.factors.time,
            "angular_velocity_factor": d.factors.angular_velocity,
        }
    out["prototype"]["restitution"] = planar.prototype.restitution
    out["load_model"] = _load_model_record(result)
    return out


def _rocking_figure(result):
    """theta(t), theta_dot(t) and the phase portrait of the prototype (and the up-scaled model)."""
    from ..plots.rocking import rocking_figure

    planar = result.planar
    return rocking_figure(planar.prototype, planar if result.design is not None else None)


def _print_tables(result, block, out: dict) -> None:
    """The prototype's table and, with a model, the up-scaled model's and the similarity's."""
    i = out["inputs"]
    console.print(
        table(
            f"Prototype: {block.height:g} x {block.width:.4g} m block (alpha = {math.degrees(block.alpha):.4g} deg), "
            f"{i['charge_kg']:g} kg TNT at {i['standoff_m']:g} m ({i['blast_model']}, {i['pulse_shape']})",
            _summary_rows(out["prototype"]),
        )
    )
    if result.design is None:
        return
    me = out["model_experiment"]
    console.print(
        table(
            f"Model lambda = {i['scale']:g}, gamma = {i['density_ratio']:g}: {me['charge_kg']:.4g} kg at {me['standoff_m']:.4g} m, "
            "up-scaled to prototype units",
            _summary_rows(out["model"]),
        )
    )
    console.print(table(SIMILARITY_TITLE, _similarity_rows(out["similarity"])))


def _similarity_rows(s: dict) -> list[tuple[str, str, str]]:
    return [
        ("max |rotation difference|", f"{s['max_abs_rotation_diff_rad']:.3g}", "rad"),
        ("  up to the tipping point", f"{s['max_abs_rotation_diff_to_tipping_rad']:.3g}", "rad"),
        ("max |angular velocity difference|", f"{s['max_abs_angular_velocity_diff_rad_s']:.3g}", "rad/s"),
        ("overturn time difference (model - prototype)", fmt_value(s["collapse_time_diff_s"], ".3g"), "s"),
        (
            "fall, |theta_dot difference| / p at equal angle",
            fmt_value(s["max_fall_phase_diff_rad"], ".3g"),
            "rad",
        ),
        ("first-peak ratio model/prototype", f"{s['first_peak_ratio']:.6g}", "-"),
        ("outcomes agree", fmt_value(s["outcomes_agree"]), ""),
    ]
