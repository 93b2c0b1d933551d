"""``blastscale run``: the main job on the built-in default scenario (the paper's 10 m block).

The main job runs the whole data flow of the method on one scenario:

1. **design** the reduced-scale model (similitude, general law);
2. **planar rocking**: prototype and model, the model up-scaled, similarity measured;
3. **capacity**: the prototype's critical charge at the scenario's stand-off;
4. **3D rigid body** (MuJoCo, Method A, Coulomb friction): prototype and model, compared.

The default scenario is the paper's slender prototype block (2h = 10 m, alpha = 15 deg,
rho = 2000 kg/m^3), 50 kg TNT at 2 m, designed at lambda = 1/200 with the same material and
the paper's own blast fits (masi2021), friction 0.7 (= tan 35 deg, the paper's FE value), so
that ``make run`` reproduces the paper's model 2. ``--out DIR`` writes ``summary.json``
(inputs, versions, units, every result) and the figures; the JSON is written to a temporary
file and renamed, so an interrupted run never leaves a half-written summary.
"""

from __future__ import annotations

import json
import math
import os
import platform
import tempfile
from pathlib import Path
from typing import Optional

import typer
from rich.table import Table

from .. import __version__
from ..analysis.block3d_similarity import compare_block3d
from ..analysis.rocking_similarity import compare_rocking
from ..rocking import RockingSystem, critical_charge
from ..sim3d import ContactSettings
from ..similitude import design_model
from ..structures import RectangularBlock
from ._app import _jsonable, app, console, console_err, fmt_value, print_json, save_figure
from .loads import MODEL_HELP, print_design

#: The built-in default scenario (SI), the paper's case (a) for model 2.
DEFAULT_SCENARIO = {
    "height_m": 10.0,
    "alpha_deg": 15.0,
    "depth_m": 1.0,
    "density_kg_m3": 2000.0,
    "charge_kg": 50.0,
    "standoff_m": 2.0,
    "scale": 1.0 / 200.0,
    "density_ratio": 1.0,
    "gravity_ratio": 1.0,
    "blast_model": "masi2021",
    "pulse": "friedlander",
    "friction": 0.7,
    "duration_s": 5.0,
}

UNITS = {
    "angles": "rad",
    "angular velocities": "rad/s",
    "times": "s",
    "lengths": "m",
    "charges": "kg",
    "pressures": "Pa",
    "impulses": "Pa s",
    "model results": "up-scaled to prototype units",
}


def _write_json_atomic(path: Path, obj: dict) -> None:
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=".summary-", suffix=".json")
    with os.fdopen(fd, "w") as fh:
        json.dump(_jsonable(obj), fh, indent=2)
    os.replace(tmp, path)


def _versions() -> dict:
    import mujoco
    import numba
    import numpy
    import scipy

    return {
        "blastscale": __version__,
        "python": platform.python_version(),
        "numpy": numpy.__version__,
        "scipy": scipy.__version__,
        "numba": numba.__version__,
        "mujoco": mujoco.__version__,
    }


def _compare_table(title: str, rows: list[tuple[str, object, object, str]]) -> Table:
    t = Table(title=title, title_justify="left")
    for c in ("quantity", "prototype", "model (up-scaled)", "unit"):
        t.add_column(c, justify="left" if c in ("quantity", "unit") else "right")
    for q, p, m, u in rows:
        t.add_row(q, fmt_value(p), fmt_value(m), u)
    return t


@app.command("run")
def run_cmd(
    model: str = typer.Option(DEFAULT_SCENARIO["blast_model"], "--model", help=MODEL_HELP),
    charge: float = typer.Option(DEFAULT_SCENARIO["charge_kg"], "--charge", help="Prototype charge W \\[kg]."),
    friction: float = typer.Option(DEFAULT_SCENARIO["friction"], "--friction", help="Coulomb friction mu \\[-] (3D)."),
    duration: float = typer.Option(DEFAULT_SCENARIO["duration_s"], "--duration", help="Simulated time \\[s]."),
    out: Optional[Path] = typer.Option(None, "--out", help="Folder for summary.json and figures."),
    as_json: bool = typer.Option(False, "--json", help="Print one JSON object instead of tables."),
) -> None:
    """Run the main job on the default scenario: design, planar rocking, critical charge, 3D."""
    s = DEFAULT_SCENARIO | {"blast_model": model, "charge_kg": charge, "friction": friction, "duration_s": duration}
    block = RectangularBlock.from_slenderness(
        s["height_m"], math.radians(s["alpha_deg"]), depth=s["depth_m"], density=s["density_kg_m3"]
    )
    if out is not None:
        out.mkdir(parents=True, exist_ok=True)
    common = dict(model=model, pulse=s["pulse"], duration=duration)
    status = console_err.status("designing the model ...")
    with status:
        d = design_model(s["charge_kg"], s["standoff_m"], s["scale"], s["density_ratio"], s["gravity_ratio"],
                         "general", model, block)
        status.update("planar rocking: prototype and model ...")
        rock = compare_rocking(block, s["charge_kg"], s["standoff_m"], s["scale"], s["density_ratio"], **common)
        status.update("critical charge (planar) ...")
        crit = critical_charge(RockingSystem.from_block(block), s["standoff_m"], pulse=s["pulse"], model=model)
        status.update("3D rigid body (MuJoCo): prototype and model ...")
        b3 = compare_block3d(block, s["charge_kg"], s["standoff_m"], s["scale"], density_ratio=s["density_ratio"],
                             contact=ContactSettings(friction=friction), **common)
    result = {
        "scenario": s,
        "units": UNITS,
        "versions": _versions(),
        "design": d.to_dict(),
        "rocking": rock.to_dict(),
        "critical": crit.to_dict(),
        "block3d": b3.summary(),
    }
    if out is not None:
        status = console_err.status("writing figures ...")
        with status:
            from ..plots.rocking import rocking_figure
            from ..plots.sim3d import plot_comparison

            save_figure(lambda: rocking_figure(rock.prototype, similarity=rock), out / "rocking.png")
            save_figure(lambda: plot_comparison(b3.prototype, b3.model_upscaled), out / "block3d.png")
            _write_json_atomic(out / "summary.json", result)
    if as_json:
        print_json(result)
        return
    console.rule("[bold]blastscale: default scenario[/] — the paper's 10 m block, "
                 f"{s['charge_kg']:g} kg TNT at {s['standoff_m']:g} m, lambda = 1/{1 / s['scale']:g}")
    print_design(d)
    rp, rm, rs = (result["rocking"][k] for k in ("prototype", "model", "similarity"))
    console.print(_compare_table(f"Planar rocking ({s['pulse']} pulse, {duration:g} s)", [
        ("overturned", rp["overturned"], rm["overturned"], ""),
        ("max angle", rp["max_angle_rad"], rm["max_angle_rad"], "rad"),
        ("first impact time", rp["first_impact_time_s"], rm["first_impact_time_s"], "s"),
        ("overturn time", rp["overturn_time_s"], rm["overturn_time_s"], "s"),
    ]))
    console.print(f"similarity: max |angle difference| {rs['max_abs_angle_diff_rad']:.3g} rad, peak ratio "
                  f"{rs['peak_ratio']:.6f}, outcomes agree: {rs['outcomes_agree']}")
    if rp["overturned"] and rm["overturned"]:
        # after tipping, equal-time differences measure the tipping-time shift times the fall speed;
        # the meaningful figures are up to tipping and along the fall at equal angle (docs/rocking.md)
        console.print(f"  up to tipping {rs['max_abs_angle_diff_to_tipping_rad']:.3g} rad; tipping time shift "
                      f"{rs['overturn_time_diff_s']:.3g} s; fall at equal angle {rs['max_fall_phase_diff_rad']:.3g} rad")
    console.print(f"critical charge at {s['standoff_m']:g} m (planar, {s['pulse']}): "
                  f"[bold]{crit.charge_kg:.4g} kg[/] ({crit.evaluations} simulations)")
    bs = result["block3d"]
    bp, bm, bsim = bs["prototype"], bs["model"], bs["similarity"]
    console.print(_compare_table(f"3D rigid body, MuJoCo (friction {friction:g}, Method A)", [
        ("overturned", bp["overturned"], bm["overturned"], ""),
        ("max rotation", bp["max_rotation_rad"], bm["max_rotation_rad"], "rad"),
        ("max sliding", bp["max_sliding_m"], bm["max_sliding_m"], "m"),
        ("final sliding", bp["final_sliding_m"], bm["final_sliding_m"], "m"),
        ("max uplift", bp["max_uplift_m"], bm["max_uplift_m"], "m"),
    ]))
    console.print("similarity: " + ", ".join(
        f"{k} {v:.3g}" if isinstance(v, float) else f"{k} {v}" for k, v in bsim.items()))
    if out is not None:
        console.print(f"wrote {out / 'summary.json'}, {out / 'rocking.png'}, {out / 'block3d.png'}")
