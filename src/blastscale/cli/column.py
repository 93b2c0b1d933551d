"""``blastscale column``: a multi-drum column under a blast in 3D (MuJoCo), prototype and model.

The flags build a :class:`~blastscale.scenario.Scenario` (engine ``3d``; no ``--scale``: the
prototype alone; ``--ensemble N``: ``simulation.ensemble_members``) and the
:class:`~blastscale.study.Study` runs it; a flag not given takes the scenario's default.
"""

from __future__ import annotations

import math
from typing import Optional

import typer

from ..analysis.intervals import odds_text
from . import options as opt
from ._app import app
from ._output import console, fmt_value, table
from .flags import scenario_from_flags
from .options import check_plot_path, scenario_default
from .steps import add_comparison_3d_figure, answer, blast_keys_3d, print_model_3d, run_checked_3d, scale_keys

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


def _column_default(key: str, unit: str = "") -> str:
    v = scenario_default("column", key)
    return f" (default {v:g}{unit})" if isinstance(v, (int, float)) else f" (default {v})"


def column_output(result, contact, incidence: Optional[str] = None, timestep: Optional[float] = None) -> dict:
    """The ``column --json`` object of a study of a column on the 3D engine: ``inputs`` (from the
    scenario; ``incidence`` and ``timestep`` as given, None for the defaults), ``structure``,
    ``prototype`` and, with a design, ``model`` (up-scaled), ``similarity`` and
    ``model_experiment``; ``ensemble`` when run."""
    sc, d = result.scenario, result.design
    out: dict = {
        "inputs": {
            "charge_kg": sc.blast.charge_kg,
            "standoff_m": sc.blast.standoff_m,
            "blast_model": sc.blast.blast_model,
            "pulse_shape": sc.blast.pulse_shape,
            "load": sc.blast.load,
            "incidence": incidence,
            "friction": sc.structure.friction,
            "duration_s": sc.simulation.duration_s,
            "timestep_s": timestep,
            "jacobian": contact.jacobian,
            "step_after_load": contact.step_after_load,
            "scale": None if d is None else d.scale,
            "density_ratio": None if d is None else d.density_ratio,
        },
        "structure": result.structure.describe(),
    }
    s = result.summary()
    out.update({k: v for k, v in s["3d"].items() if v is not None})
    if d is not None:
        out["model_experiment"] = {
            "charge_kg": d.specimen_charge_kg,
            "standoff_m": d.specimen_standoff_m,
            "structure": result.specimen_structure.describe(),
        }
    if s["ensemble"] is not None:
        out["ensemble"] = s["ensemble"]
    return out


#: The options of ``column`` alone (the shared ones are in :mod:`.options`).
SECTION = typer.Option(
    None,
    "--section",
    help="Cross-section: square or circular (a regular polygon, --sides)" + _column_default("section") + ".",
)
DRUMS = typer.Option(None, "--drums", help="Number of drums N \\[-]" + _column_default("drums") + ".")
HEIGHT = typer.Option(
    None,
    "--height",
    help="Total height of the column \\[m] (drums of equal height)" + _column_default("height_m", " m") + ".",
)
BASE_WIDTH = typer.Option(
    None,
    "--base-width",
    help="Side (square) or diameter (circular) at the base \\[m]" + _column_default("base_width_m", " m") + ".",
)
TOP_WIDTH = typer.Option(
    None,
    "--top-width",
    help="Side or diameter at the top \\[m] (linear "
    "taper; at most the base width)" + _column_default("top_width_m", " m") + ".",
)
SIDES = typer.Option(None, "--sides", help="Polygon sides of a circular drum \\[-]" + _column_default("sides") + ".")
DENSITY = typer.Option(
    None, "--density", help="Density rho \\[kg/m^3]" + _column_default("density_kg_m3", " kg/m^3, marble") + "."
)
TIMESTEP = typer.Option(
    None,
    "--timestep",
    help="Prototype time step \\[s] (default: derived from the structure's size; the model's "
    "is x sqrt(lambda)); rejected past the engine's stability bound.",
)
JACOBIAN = typer.Option(
    None,
    "--jacobian",
    help="MuJoCo constraint Jacobian: dense or sparse (2.8x faster on the square column, the same history to "
    "round-off). Default: sparse (MuJoCo 4.0.0's sparse-factorisation bug is not reached by these "
    "scenes, docs/performance.md).",
)
STEP_AFTER_LOAD = typer.Option(
    None,
    "--step-after-load",
    help="The step once every pulse has passed: double (default: twice the step, at most half the contact time "
    "constant; 1.8x faster, first peaks within 0.3 %) or same (one step throughout, as before issue #28).",
)
ENSEMBLE = typer.Option(
    None,
    "--ensemble",
    help="Also run N prototypes (and, with --scale, N models) with the load x (1 + 1e-6 u), u "
    "in [-1, 1], and report first-peak spreads, noise floor, horizon and collapse "
    "probabilities (circular columns are chaotic: compare them this way; "
    "docs/columns.md). 0 (default): off; else 2 to 64.",
)
PLOT = typer.Option(None, "--plot", help="Write the monitoring-point histories and pose snapshots to this image file.")


@app.command("column")
def column_cmd(
    section: Optional[str] = SECTION,
    drums: Optional[int] = DRUMS,
    height: Optional[float] = HEIGHT,
    base_width: Optional[float] = BASE_WIDTH,
    top_width: Optional[float] = TOP_WIDTH,
    sides: Optional[int] = SIDES,
    density: Optional[float] = DENSITY,
    friction: Optional[float] = opt.FRICTION_3D,
    charge: float = opt.CHARGE,
    standoff: float = opt.STANDOFF,
    blast_model: Optional[str] = opt.MODEL_3D,
    pulse_shape: Optional[str] = opt.PULSE_3D,
    load: Optional[str] = opt.LOAD,
    incidence: Optional[str] = opt.INCIDENCE,
    scale: Optional[float] = opt.SCALE,
    density_ratio: float = opt.DENSITY_RATIO,
    duration: Optional[float] = opt.DURATION_3D,
    timestep: Optional[float] = TIMESTEP,
    jacobian: Optional[str] = JACOBIAN,
    step_after_load: Optional[str] = STEP_AFTER_LOAD,
    record_every: Optional[int] = opt.RECORD_EVERY,
    ensemble: Optional[int] = ENSEMBLE,
    threads: Optional[int] = opt.THREADS,
    plot: Optional[str] = PLOT,
    as_json: bool = opt.JSON,
) -> None:
    """Rocking, wobbling, sliding and collapse of a multi-drum column under a blast (MuJoCo).

    The defaults are the paper's column (Sec. 6): 10 drums of 1 m, 1.65 -> 1.28 m, marble,
    friction 0.7. With --scale the model experiment is designed by the general law, run at its
    own size with scale-consistent contact settings, up-scaled and compared with the prototype
    per monitoring point (P-1 at the base drum's front face ... P-N at the top drum's).
    """

    check_plot_path(plot)
    sc = scenario_from_flags(
        structure={
            "kind": "column",
            "section": section,
            "drums": drums,
            "height_m": height,
            "base_width_m": base_width,
            "top_width_m": top_width,
            "sides": sides,
            "density_kg_m3": density,
            "friction": friction,
        },
        blast=blast_keys_3d(charge, standoff, blast_model, pulse_shape, load, incidence),
        scale=scale_keys(scale, density_ratio),
        simulation={
            "engine": "3d",
            "duration_s": duration,
            "timestep_s": timestep,
            "record_every": record_every,
            "ensemble_members": ensemble,
            "threads": threads,
            "critical_charge": False,
            "contact": {"jacobian": jacobian},
            "step_after_load": step_after_load,
        },
    )
    result, contact = run_checked_3d(sc, as_json)
    out = column_output(result, contact, incidence, timestep)
    add_comparison_3d_figure(out, result, result.response3d.prototype_dataset, plot)
    answer(out, as_json=as_json, engine="3d", plot=plot, tables=lambda: _print_tables(result, out, scale))


def _print_tables(result, out: dict, scale: Optional[float]) -> None:
    """The prototype's table; with a model, the up-scaled model's and the similarity's; the ensembles'."""
    col, sc = result.structure, result.scenario
    b = sc.blast
    title = (
        f"Prototype: {col.drums}-drum {col.section} column, {col.height:g} m, {col.base_width:g} -> "
        f"{col.top_width:g} m; {b.charge_kg:g} kg TNT at {b.standoff_m:g} m ({b.blast_model}, {b.pulse_shape}, load {b.load}, "
        f"mu = {sc.structure.friction:g})"
    )
    console.print(table(title, _rows(out["prototype"])))
    if scale is not None:
        print_model_3d(scale, out, _rows(out["model"]))
        console.print(table("Similarity (prototype vs up-scaled model, x displacement)", _similarity_rows(out)))
    if "ensemble" in out:
        _print_ensemble(out["ensemble"], result.ensemble.top_point, scale is not None)


def _similarity_rows(out: dict) -> list[tuple[str, str, str]]:
    """The similarity's rows: the outcomes, the top point's figures, then each monitoring point's."""
    s = out["similarity"]
    rows = [
        ("outcomes agree", fmt_value(s["outcomes_agree"]), ""),
        (f"first-peak ratio at the top ({s['top_point']})", fmt_value(s["top_first_peak_ratio"], ".4f"), "-"),
        ("max |top displacement difference|", fmt_value(s["max_abs_top_displacement_diff_m"], ".3g"), "m"),
    ]
    for name, p in s["points"].items():
        rows.append(
            (
                f"{name}: first-peak ratio / max |diff| rel. peak",
                f"{fmt_value(p['first_peak_ratio'], '.4f')} / "
                f"{fmt_value(p['max_abs_displacement_diff_rel_peak'], '.3g')}",
                "-",
            )
        )
    return rows


def _print_ensemble(e: dict, top_point: str, with_model: bool) -> None:
    top = e["points"][top_point]
    horizon = top["horizon_prototype_s"]
    rows = [
        (
            "first peak, prototype mean / spread",
            f"{top['first_peak_prototype_mean_m']:.4g} / {top['first_peak_prototype_spread_m']:.2g}",
            "m",
        )
    ]
    if with_model:
        rows.append(
            (
                "first peak, model mean / spread",
                f"{top['first_peak_model_mean_m']:.4g} / {top['first_peak_model_spread_m']:.2g}",
                "m",
            )
        )
    rows += [
        ("noise floor (prototype spread / peak)", fmt_value(top["noise_floor_rel_peak"], ".3g"), "-"),
        (
            "horizon (spread > 5 % of the peak; - never)",
            fmt_value(horizon if math.isfinite(horizon) else None, ".3g"),
            "s",
        ),
        (
            "collapse probability, prototype / model" if with_model else "collapse probability, prototype",
            _collapse_odds(e, "prototype") + (f" / {_collapse_odds(e, 'model')}" if with_model else ""),
            "-",
        ),
    ]
    console.print(
        table(f"Ensembles of {e['n_members']} (load x (1 +- {e['perturbation']:g})), top point ({top_point})", rows)
    )


def _collapse_odds(e: dict, system: str) -> str:
    """An ensemble's collapse probability of ``system`` in words with its Wilson interval (k of n members)."""
    n = int(e["n_members"])
    return odds_text(round(e[f"collapse_probability_{system}"] * n), n)
