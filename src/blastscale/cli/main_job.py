"""``blastscale run``: the main job on a scenario (the built-in default: the paper's 10 m block).

The default scenario is the paper's slender prototype block (2h = 10 m, alpha = 15 deg,
rho = 2000 kg/m^3), 50 kg TNT at 2 m, designed at lambda = 1/200 with the same material and
the paper's own blast fits (masi2021), so that ``make run`` reproduces the paper's model 2.
"""

from __future__ import annotations

import math

import typer

from ..similitude import design_model
from ..structures import RectangularBlock
from ._app import app, console, print_json
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
}


@app.command("run")
def run_cmd(
    model: str = typer.Option(DEFAULT_SCENARIO["blast_model"], "--model", help=MODEL_HELP),
    as_json: bool = typer.Option(False, "--json", help="Print one JSON object instead of tables."),
) -> None:
    """Run the main job on the built-in default scenario (the paper's 10 m block, 50 kg at 2 m, 1/200)."""
    s = DEFAULT_SCENARIO
    block = RectangularBlock.from_slenderness(
        s["height_m"], math.radians(s["alpha_deg"]), depth=s["depth_m"], density=s["density_kg_m3"]
    )
    d = design_model(
        s["charge_kg"], s["standoff_m"], s["scale"], s["density_ratio"], s["gravity_ratio"], "general", model, block
    )
    if as_json:
        print_json({"scenario": s | {"blast_model": model}, "design": d.to_dict()})
        return
    console.rule("[bold]blastscale: default scenario[/] — the paper's 10 m block, 50 kg TNT at 2 m, lambda = 1/200")
    print_design(d)
