"""``blastscale column``: a multi-drum column under a blast in 3D (MuJoCo), prototype and model."""

from __future__ import annotations

import math
from typing import Optional

import typer

from .._validate import BlastscaleInputError, check_positive
from . import options as opt
from ._app import app, console, fmt_value, one_line_warnings, print_json, save_figure, table
from .options import check_load_options, check_plot_path, contact_from_options

_SUMMARY_ROWS = (
    ("collapsed", "collapsed", "", ".6g"),
    ("max top displacement", "max_top_displacement_m", "m", ".4g"),
)


def _rows(summary: dict) -> list[tuple[str, str, str]]:
    rows = [(name, fmt_value(summary.get(k), fmt), u) for name, k, u, fmt in _SUMMARY_ROWS]
    imp = summary.get("delivered_impulse_Ns")
    if imp is not None:
        rows.append(("delivered impulse x, y, z", ", ".join(f"{v:.4g}" for v in imp), "N s"))
    for name, p in summary.get("points", {}).items():
        rows.append((f"{name} max displacement", fmt_value(p.get("max_displacement_m"), ".4g"), "m"))
    return rows


@app.command("column")
def column_cmd(
    section: str = typer.Option("square", "--section", help="Cross-section: square or circular (a regular polygon, --sides)."),
    drums: int = typer.Option(10, "--drums", help="Number of drums N \\[-]."),
    height: float = typer.Option(10.0, "--height", help="Total height of the column \\[m] (drums of equal height)."),
    base_width: float = typer.Option(1.65, "--base-width", help="Side (square) or diameter (circular) at the base \\[m]."),
    top_width: float = typer.Option(1.28, "--top-width", help="Side or diameter at the top \\[m] (linear taper; at most the base width)."),
    sides: int = typer.Option(32, "--sides", help="Polygon sides of a circular drum \\[-]."),
    density: float = typer.Option(2700.0, "--density", help="Density rho \\[kg/m^3] (marble 2700)."),
    friction: float = typer.Option(0.7, "--friction", help="Coulomb friction coefficient mu at every joint \\[-] (paper: tan 35 deg)."),
    charge: float = opt.CHARGE,
    standoff: float = opt.STANDOFF,
    model: str = opt.MODEL,
    pulse: str = opt.PULSE,
    load: str = opt.LOAD,
    incidence: Optional[str] = opt.INCIDENCE,
    scale: Optional[float] = opt.SCALE,
    density_ratio: float = opt.DENSITY_RATIO,
    duration: float = typer.Option(8.0, "--duration", help="Simulated time after the first arrival \\[s] (prototype)."),
    timestep: Optional[float] = typer.Option(
        None, "--timestep", help="Prototype time step \\[s] (default: derived from the structure's size; the model's "
                                 "is x sqrt(lambda)); rejected past the engine's stability bound."),
    jacobian: str = typer.Option(
        "dense", "--jacobian",
        help="MuJoCo constraint Jacobian: dense (default) or sparse (2.8x faster on the square column, the same "
             "history to round-off; opt-in because of a reported MuJoCo 4.0.0 bug, docs/sim3d.md)."),
    record_every: int = typer.Option(4, "--record-every", help="Keep one state every N steps."),
    ensemble: int = typer.Option(
        0, "--ensemble", help="With --scale: also run N prototypes and N models with the load x (1 + 1e-6 u), u in "
                              "[-1, 1], and report first-peak spreads, noise floor, horizon and collapse probabilities "
                              "(circular columns are chaotic: compare them this way; docs/columns.md). 0: off."),
    plot: Optional[str] = typer.Option(None, "--plot", help="Write the monitoring-point histories and pose snapshots to this image file."),
    as_json: bool = opt.JSON,
) -> None:
    """Rocking, wobbling, sliding and collapse of a multi-drum column under a blast (MuJoCo).

    The defaults are the paper's column (Sec. 6): 10 drums of 1 m, 1.65 -> 1.28 m, marble,
    friction 0.7. With --scale the model experiment is designed by the general law, run at its
    own size with scale-consistent contact settings, up-scaled and compared with the prototype
    per monitoring point (P-1 at the base drum's front face ... P-N at the top drum's).
    """
    from ..analysis.structure3d import compare_structure3d
    from ..sim3d import simulate_structure
    from ..sim3d.load_methods import make_load
    from ..similitude import design_model
    from ..structures import MultiDrumColumn

    col = MultiDrumColumn(section=section, drums=drums, height=height, base_width=base_width, top_width=top_width,
                          sides=sides, density=density)
    check_load_options(load, incidence)
    check_plot_path(plot)
    check_positive("duration", duration, "s")
    if isinstance(ensemble, bool) or ensemble < 0 or ensemble == 1 or (ensemble and scale is None):
        raise BlastscaleInputError(
            f"ensemble = {ensemble} is out of range: valid values are 0 (off) or >= 2 members, with --scale")
    contact = contact_from_options(col, friction, timestep, jacobian=jacobian)
    inc = {} if incidence is None else {"incidence": incidence}
    out: dict = {"inputs": {
        "charge_kg": charge, "standoff_m": standoff, "model": model, "pulse": pulse, "load": load,
        "incidence": incidence, "friction": friction, "duration_s": duration, "timestep_s": timestep, "jacobian": jacobian,
        "scale": scale, "density_ratio": density_ratio if scale is not None else None,
    }, "structure": col.describe()}
    with one_line_warnings():
        if scale is None:
            ld = make_load(load, col, charge_kg=charge, standoff_m=standoff, blast_model=model, pulse=pulse, **inc)
            proto = simulate_structure(col, ld, duration, contact=contact, record_every=record_every)
            out["prototype"] = proto.summary()
            proto_ds, model_ds = proto.dataset, None
        else:
            design = design_model(charge, standoff, scale, density_ratio, model=model)
            cmp = compare_structure3d(col, design, load=load, pulse=pulse, incidence=incidence, contact=contact,
                                      duration=duration, record_every=record_every)
            out.update(cmp.summary())
            out["model_experiment"] = {
                "charge_kg": design.model_charge_kg, "standoff_m": design.model_standoff_m,
                "structure": cmp.model_structure.describe(),
            }
            proto_ds, model_ds = cmp.prototype_dataset, cmp.upscaled_dataset
            if ensemble:
                from ..analysis.ensemble import ensemble_compare

                ens = ensemble_compare(col, design, n=ensemble, load=load, pulse=pulse, incidence=incidence,
                                       contact=contact, duration=duration, record_every=record_every)
                out["ensemble"] = ens.summary()
    if plot:
        from ..plots.column import plot_column_comparison

        save_figure(lambda: plot_column_comparison(col, proto_ds, model_ds), plot)
        out["plot"] = plot
    if as_json:
        print_json(out)
        return
    title = (f"Prototype: {col.drums}-drum {section} column, {height:g} m, {base_width:g} -> {top_width:g} m; "
             f"{charge:g} kg TNT at {standoff:g} m ({model}, {pulse}, load {load}, mu = {friction:g})")
    console.print(table(title, _rows(out["prototype"])))
    if scale is not None:
        console.print(table(f"Model lambda = {scale:g}, up-scaled to prototype units (model charge "
                            f"{out['model_experiment']['charge_kg']:.4g} kg)", _rows(out["model"])))
        s = out["similarity"]
        rows = [
            ("outcomes agree", fmt_value(s["outcomes_agree"]), ""),
            (f"first-peak ratio at the top ({s['top_point']})", fmt_value(s["top_first_peak_ratio"], ".4f"), "-"),
            ("max |top displacement difference|", fmt_value(s["max_abs_top_displacement_diff_m"], ".3g"), "m"),
        ]
        for name, p in s["points"].items():
            rows.append((f"{name}: first-peak ratio / max |diff| rel. peak",
                         f"{fmt_value(p['first_peak_ratio'], '.4f')} / "
                         f"{fmt_value(p['max_abs_displacement_diff_rel_peak'], '.3g')}", "-"))
        console.print(table("Similarity (prototype vs up-scaled model, x displacement)", rows))
        if "ensemble" in out:
            e = out["ensemble"]
            top = e["points"][s["top_point"]]
            console.print(table(f"Ensembles of {e['n_members']} (load x (1 +- {e['perturbation']:g})), top point", [
                ("first peak, prototype mean / spread", f"{top['first_peak_prototype_mean_m']:.4g} / "
                                                       f"{top['first_peak_prototype_spread_m']:.2g}", "m"),
                ("first peak, model mean / spread", f"{top['first_peak_model_mean_m']:.4g} / "
                                                   f"{top['first_peak_model_spread_m']:.2g}", "m"),
                ("noise floor (prototype spread / peak)", fmt_value(top["noise_floor_rel_peak"], ".3g"), "-"),
                ("horizon (spread > 5 % of the peak; - never)",
                 fmt_value(top["horizon_prototype_s"] if math.isfinite(top["horizon_prototype_s"]) else None, ".3g"),
                 "s"),
                ("collapse probability, prototype / model",
                 f"{e['collapse_probability_prototype']:.2f} / {e['collapse_probability_model']:.2f}", "-"),
            ]))
    if plot:
        console.print(f"plot written to {plot}")
