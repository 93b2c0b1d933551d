"""``blastscale critical`` and ``blastscale capacity``: the planar block's capacity under blast, by the
first-swing energy criterion after the pulse (docs/capacity.md).

Units at this edge: lengths in m, density in kg/m^3, charge in kg TNT, the slenderness angle in degrees
(``--alpha-deg``); results are SI (kg, m, Pa, Pa s).
"""

from __future__ import annotations

from typing import Optional

import numpy as np
import typer
from rich.table import Table

from .. import __version__
from .._validate import BlastscaleInputError
from ..blast.parameters import blast_parameters
from ..blast.parameters import model_for_burst
from ..study.memory import check_budget
from ..sweeps.grids import parse_grid
from . import blast_flags as bf
from . import options as opt
from ._output import activity, console, fmt_value, one_line_warnings, print_json, print_written, save_figure, table
from ._app import app
from .options import block_from_options, check_plot_path
from .rocking import RESTITUTION_HELP, block_inputs


def opt_extrapolate():
    """The ``--extrapolate`` option of the capacity commands."""
    return typer.Option(
        False, "--extrapolate", help="Search beyond the blast fits' valid range of Z (5x each way; warns)."
    )


@app.command("critical")
def critical_cmd(
    height: float = opt.HEIGHT,
    width: Optional[float] = opt.WIDTH,
    alpha_deg: Optional[float] = opt.ALPHA_DEG,
    depth: float = opt.DEPTH,
    density: float = opt.DENSITY,
    standoff: Optional[float] = typer.Option(None, "--standoff", help="Stand-off R \\[m]: find the critical charge."),
    charge: Optional[float] = typer.Option(
        None, "--charge", help="Charge W \\[kg TNT]: find the critical stand-off instead."
    ),
    pulse_shape: str = opt.PULSE,
    restitution: Optional[float] = typer.Option(
        None, "--restitution", help=RESTITUTION_HELP + " (does not affect the first excursion)"
    ),
    extrapolate: bool = opt_extrapolate(),
    scale: Optional[float] = typer.Option(
        None, "--scale", help="Geometric scale lambda \\[-]: also give the model's charge for the critical scenario."
    ),
    density_ratio: float = opt.DENSITY_RATIO,
    gravity: float = opt.GRAVITY,
    blast_model: str = opt.MODEL,
    burst: str = bf.BURST,
    clearing: bool = bf.CLEARING,
    negative_phase: bool = bf.NEGATIVE_PHASE,
    negative_phase_model: Optional[str] = bf.NEGATIVE_PHASE_MODEL,
    plot: Optional[str] = typer.Option(
        None, "--plot", help="Write the P-I overturning diagram (with the critical point) to this image file."
    ),
    as_json: bool = typer.Option(False, "--json", help="Print one JSON object instead of a table."),
) -> None:
    """Critical charge at a stand-off (largest charge without overturning), or with --charge the
    critical stand-off: the first-swing energy criterion after the pulse (docs/capacity.md),
    searched from the structure's own scale (any size, lab specimens included)."""
    from ..analysis.planar import critical_of, planar_system

    block = block_from_options(height, width, alpha_deg, depth, density, required=True)
    check_plot_path(plot)
    bf.check_burst_flag(burst)
    lm = bf.load_model_from_flags(clearing, None, None, negative_phase, block, negative_phase_model)
    fit = model_for_burst(blast_model, burst).name
    if (standoff is None) == (charge is None):
        raise BlastscaleInputError(
            f"standoff = {standoff}, charge = {charge}: give exactly one of --standoff (m, finds the critical charge) "
            "or --charge (kg, finds the critical stand-off)"
        )
    system = planar_system(block, gravity, restitution)
    with one_line_warnings(), activity("searching the critical scenario", quiet=as_json):
        res = critical_of(
            system,
            standoff=standoff,
            charge=charge,
            pulse_shape=pulse_shape,
            blast_model=fit,
            extrapolate=extrapolate,
            load_model=lm,
        )
    out = {"inputs": block_inputs(block, pulse_shape=pulse_shape, blast_model=blast_model, gravity_m_s2=gravity)}
    out.update(res.to_dict())
    out["blast_model"] = blast_model  # the family asked for; the fit used is in load_model
    bp = blast_parameters(res.charge_kg, res.standoff_m, fit, extrapolate=extrapolate)
    out["critical_blast"] = {
        "scaled_distance_m_per_kg13": bp.scaled_distance,
        "reflected_pressure_Pa": bp.reflected_pressure,
        "reflected_impulse_Pa_s": bp.reflected_impulse,
        "positive_duration_s": bp.positive_duration,
    }
    if lm is not None and lm.negative_phase and standoff is not None:
        from ..analysis.planar import negative_phase_uncertainty_of

        with one_line_warnings(), activity("the critical charge under each negative-phase model", quiet=as_json):
            out["negative_phase_uncertainty"] = negative_phase_uncertainty_of(
                system, standoff, lm, pulse_shape=pulse_shape, blast_model=fit, extrapolate=extrapolate
            )
    out["impulsive_critical_impulse_Pa_s"] = system.critical_impulse
    out["uplift_pressure_Pa"] = system.uplift_pressure
    if scale is not None:
        from ..similitude.design import design_model

        with one_line_warnings():
            d = design_model(
                res.charge_kg,
                res.standoff_m,
                scale,
                density_ratio,
                blast_model=blast_model,
                geometry=block,
                gravity=gravity,
                extrapolate=extrapolate,
                burst=burst,
                load_model=lm,
            )
        out["model_experiment"] = {
            "scale": scale,
            "density_ratio": density_ratio,
            "critical_charge_kg": d.specimen_charge_kg,
            "standoff_m": d.specimen_standoff_m,
        }
    if plot:
        from ..plots.rocking import plot_pi_diagram
        from ..analysis.planar import pi_diagram_of

        with activity("computing the P-I diagram", quiet=as_json):
            # the curve for the pulse shape searched (impulsive: the triangular curve, whose
            # high-pressure end is the impulsive limit)
            if pulse_shape == "friedlander":
                pi = pi_diagram_of(system, n=30, shape="friedlander", decay=bp.pulse("friedlander").decay)
            else:
                pi = pi_diagram_of(system, n=30)

        def build():
            import matplotlib.pyplot as plt

            fig, ax = plt.subplots(figsize=(6, 4.5), layout="constrained")
            plot_pi_diagram(pi, ax=ax)
            ax.plot(
                [bp.reflected_impulse],
                [bp.reflected_pressure],
                "o",
                color="C3",
                label=f"critical: {res.charge_kg:.4g} kg at {res.standoff_m:.4g} m",
            )
            ax.legend(fontsize=8)
            return fig

        save_figure(build, plot)
        out["plot"] = plot
    if as_json:
        print_json(out, engine="planar")
        return
    key, unit = ("critical_charge_kg", "kg") if res.searched == "charge" else ("critical_standoff_m", "m")
    rows = [
        (key.replace("_kg", "").replace("_m", "").replace("_", " "), f"{out[key]:.6g}", unit),
        ("charge W", f"{res.charge_kg:.6g}", "kg"),
        ("stand-off R", f"{res.standoff_m:.6g}", "m"),
        ("scaled distance Z", f"{bp.scaled_distance:.6g}", "m/kg^(1/3)"),
        ("reflected impulse at the critical point", f"{bp.reflected_impulse:.6g}", "Pa s"),
        ("impulsive-limit critical impulse", f"{system.critical_impulse:.6g}", "Pa s"),
        ("simulations", str(res.evaluations), ""),
    ]
    if scale is not None:
        rows.append(
            (f"model charge (lambda = {scale:g})", f"{out['model_experiment']['critical_charge_kg']:.6g}", "kg")
        )
    for m, v in out.get("negative_phase_uncertainty", {}).items():
        if isinstance(v, dict):  # the model uncertainty of the suction
            rows.append(
                (
                    f"critical charge, negative phase {m}",
                    f"{v['critical_charge_kg']:.6g} (x{v['over_positive_phase_only']:.3g})",
                    "kg",
                )
            )
    console.print(
        table(f"Critical scenario: {block.height:g} x {block.width:.4g} m block ({blast_model}, {pulse_shape})", rows)
    )
    if plot:
        print_written(plot)


@app.command("capacity")
def capacity_cmd(
    height: float = opt.HEIGHT,
    width: Optional[float] = opt.WIDTH,
    alpha_deg: Optional[float] = opt.ALPHA_DEG,
    depth: float = opt.DEPTH,
    density: float = opt.DENSITY,
    standoffs: str = typer.Option(
        "1:20:40:log",
        "--standoffs",
        help='Stand-offs R \\[m]: "a,b,c" or "start:stop:n" (":log" for geometric spacing).',
    ),
    charge: Optional[float] = typer.Option(
        None, "--charge", help="Charge W \\[kg TNT]: also give its safe (critical) stand-off."
    ),
    pulse_shape: str = opt.PULSE,
    restitution: Optional[float] = typer.Option(None, "--restitution", help=RESTITUTION_HELP),
    scale: Optional[float] = typer.Option(
        None, "--scale", help="Geometric scale lambda \\[-]: also the model's curve, up-scaled."
    ),
    density_ratio: float = opt.DENSITY_RATIO,
    gravity_ratio: float = opt.GRAVITY_RATIO,
    gravity: float = opt.GRAVITY,
    blast_model: str = opt.MODEL,
    extrapolate: bool = opt_extrapolate(),
    plot: Optional[str] = typer.Option(None, "--plot", help="Write the capacity curve W_c(R) to this image file."),
    as_json: bool = opt.JSON,
) -> None:
    """Capacity curve: the critical charge W_c(R) at every stand-off and, with --charge, the safe
    stand-off of that charge; with --scale also the reduced-scale model's curve, up-scaled to
    prototype charges (paper Eq. 8). First-swing energy criterion, all stand-offs at once."""

    from ..analysis.capacity import model_capacity_curve
    from ..analysis.planar import capacity_of, critical_of, planar_system

    block = block_from_options(height, width, alpha_deg, depth, density, required=True)
    check_plot_path(plot)
    R = parse_grid(standoffs, "standoffs")
    if np.any(R <= 0):
        raise BlastscaleInputError(f"standoffs = {standoffs!r} is out of range: every stand-off must be > 0 m")
    if charge is not None and not charge > 0:
        raise BlastscaleInputError(f"charge = {charge:g} kg is out of range: must be > 0 kg")
    system = planar_system(block, gravity, restitution)
    kw = dict(pulse_shape=pulse_shape, blast_model=blast_model, extrapolate=extrapolate)

    per = 5e-4 * (2 if scale is not None else 1)  # ~0.4-0.5 ms per stand-off (README "Speed"), x2 with the model
    check_budget("--standoffs", R.size, "stand-offs", R.size * 8.0 * 40, R.size * per)
    with one_line_warnings(), activity(f"capacity at {R.size} stand-offs", quiet=as_json):
        curve = capacity_of(system, R, **kw)
        mcap = None
        if scale is not None:
            mcap = model_capacity_curve(system, R, scale, density_ratio, gravity_ratio, **kw)
        safe = None
        if charge is not None:
            safe = critical_of(system, charge=charge, **kw).standoff_m

    out = {
        "inputs": block_inputs(
            block,
            pulse_shape=pulse_shape,
            blast_model=blast_model,
            gravity_m_s2=gravity,
            restitution=restitution,
            extrapolate=extrapolate,
        ),
        "blastscale_version": __version__,
        "method": "first-swing energy criterion after the pulse (docs/capacity.md)",
    }
    out.update(curve.to_dict())
    if mcap is not None:
        out["model"] = mcap.to_dict()
        ratio = mcap.upscaled_charge_kg / curve.critical_charge_kg
        out["model"]["max_abs_relative_difference"] = (
            float(np.nanmax(np.abs(ratio - 1.0))) if np.any(np.isfinite(ratio)) else None
        )
    if charge is not None:
        out["safe_standoff"] = {"charge_kg": charge, "standoff_m": safe}
    if plot:
        from ..plots.capacity import plot_capacity

        save_figure(lambda: plot_capacity(curve, mcap, charge=charge, safe_standoff=safe).figure, plot)
        out["plot"] = plot
    if as_json:
        print_json(out, engine="planar")
        return

    t = Table(
        title=f"Capacity: {block.height:g} x {block.width:.4g} m block ({blast_model}, {pulse_shape})",
        title_justify="left",
    )
    t.add_column("stand-off R [m]", justify="right")
    t.add_column("critical charge W_c [kg]", justify="right")
    if mcap is not None:
        t.add_column(f"model R [m] (lambda = {scale:g})", justify="right")
        t.add_column("model W_c [kg]", justify="right")
        t.add_column("up-scaled W_c [kg]", justify="right")
    for k in range(R.size):
        row = [f"{R[k]:.6g}", fmt_value(out["critical_charge_kg"][k], ".6g")]
        if mcap is not None:
            row += [
                f"{mcap.curve.standoff_m[k]:.6g}",
                fmt_value(out["model"]["critical_charge_kg"][k], ".6g"),
                fmt_value(out["model"]["upscaled_critical_charge_kg"][k], ".6g"),
            ]
        t.add_row(*row)
    console.print(t)
    console.print(f"{curve.seconds_per_case * 1e3:.3g} ms per stand-off")
    if charge is not None:
        console.print(f"safe stand-off for {charge:g} kg: {safe:.6g} m (it overturns the block closer than that)")
    if plot:
        print_written(plot)
