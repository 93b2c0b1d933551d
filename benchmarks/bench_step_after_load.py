"""Convergence study of the step after the load (issues 19 and 28, docs/performance.md): the engine's own loop
(:func:`blastscale.sim3d.integrate.integrate`) with the step after the last pulse x1, x2 (the default,
``step_after_load = "double"``) and x4, on the paper's block, its square and circular 10-drum columns (below and
above the square column's collapse threshold) and a 10-block wall. Reported per case and factor: the first peak of
the top point's x displacement and its change against x1, the outcome (collapsed), the drift at rest (largest top
displacement of the same structure under a charge 1000x smaller, Kingery-Bulmash: beyond masi2021's range), the delivered impulse (its norm) and the cost (CPU seconds,
user + sys of this process; the machine is shared). At x4 the columns' 1 ms contact falls below MuJoCo's 2 steps,
which MuJoCo clamps (a softer contact): the default caps the factor at half the contact time constant.
Not a test: ``python benchmarks/bench_step_after_load.py [--json] [--factors=1,2,4]``.
"""

from __future__ import annotations

import json
import math
import os
import sys

import numpy as np

from blastscale.analysis.compare import _first_peak
from blastscale.blast import blast_parameters
from blastscale.sim3d import integrate as integrate_module, make_load, simulate_structure
from blastscale.sim3d.contact import reference_contact
from blastscale.structures import MultiDrumColumn, wall
from blastscale.structures.block import RectangularBlock
from blastscale.study.engines import REFERENCE_RECORD_INTERVAL

CASES = {
    "block (paper, 50 kg at 2 m)": (RectangularBlock.from_slenderness(10.0, math.radians(15.0)), 50.0, 2.0, 3.0),
    "square column, 250 kg at 10 m": (MultiDrumColumn("square"), 250.0, 10.0, 4.0),
    "square column, 650 kg at 10 m": (MultiDrumColumn("square"), 650.0, 10.0, 4.0),
    "circular column, 200 kg at 10 m": (MultiDrumColumn("circular"), 200.0, 10.0, 4.0),
    "wall 10 blocks, 60 kg at 5 m": (
        wall(length_m=5.0, height_m=2.5, thickness_m=0.5, courses=2, units_per_course=5, bond="stack"),
        60.0,
        5.0,
        2.0,
    ),
}


def _cpu() -> float:
    t = os.times()
    return t.user + t.system


def run(structure, charge, standoff, T, factor, blast_model="masi2021"):
    """The engine's run (Method A, masi2021) with the step after the load x ``factor`` (not capped: x4 shows what
    the cap avoids); returns (Response3D, CPU seconds)."""
    default = integrate_module.step_factor_after_load
    integrate_module.step_factor_after_load = lambda c, nbody=2: float(factor)
    try:
        load = make_load("A", structure, blast_parameters(charge, standoff, blast_model=blast_model))
        t0 = _cpu()
        r = simulate_structure(structure, load, T, record_every=record_every(structure))
        return r, _cpu() - t0
    finally:
        integrate_module.step_factor_after_load = default


def record_every(structure) -> int:
    """The Study's recording interval (one state per millisecond of the 10 m reference: 5 steps of a block, 4 of a
    stack); the longer step fits a whole number of times between recorded states, so every step recorded means
    the same step."""
    return max(1, round(REFERENCE_RECORD_INTERVAL / reference_contact(structure).timestep))


def _top_x(ds):
    return ds["point_displacement"].sel(point=ds.attrs["top_point"], component="x").values


def study(factors=(1.0, 2.0, 4.0)) -> dict:
    out = {"load_average": os.getloadavg()[0]}
    run(CASES["block (paper, 50 kg at 2 m)"][0], 50.0, 2.0, 0.01, 1.0)  # imports and first compile outside
    for name, (st, W, R, T) in CASES.items():
        rows, base = {}, None
        for f in factors:
            r, cpu = run(st, W, R, T, f)
            ds = r.dataset
            x = _top_x(ds)
            fp = float(_first_peak(ds["time"].values, x, 0.1)[1])
            rest = run(st, W * 1e-3, R, T, f, "kingery-bulmash")[0].dataset  # Z beyond masi2021's fits
            row = {
                "first_peak_m": fp,
                "collapsed": bool(ds.attrs["collapsed"]),
                "max_rotation_rad": float(ds["tilt"].max()),
                "drift_at_rest_mm": 1e3
                * float(np.abs(rest["point_displacement"].sel(point=rest.attrs["top_point"]).values).max()),
                "delivered_impulse_Ns": float(np.linalg.norm(r.summary()["delivered_impulse_Ns"])),
                "cpu_s": cpu,
            }
            base = base or row
            row["first_peak_change"] = fp / base["first_peak_m"] - 1.0 if base["first_peak_m"] else 0.0
            row["outcome_unchanged"] = row["collapsed"] == base["collapsed"]
            row["speedup"] = base["cpu_s"] / cpu
            rows[f"x{f:g}"] = row
        out[name] = rows
    return out


if __name__ == "__main__":
    fs = next((a.split("=", 1)[1] for a in sys.argv if a.startswith("--factors=")), "1,2,4")
    res = study(tuple(float(f) for f in fs.split(",")))
    if "--json" in sys.argv:
        print(json.dumps(res, indent=2))
    else:
        print(f"load average {res.pop('load_average'):.2f}")
        for name, rows in res.items():
            for f, r in rows.items():
                print(
                    f"{name:32s} {f:3s} first peak {r['first_peak_m']:.6g} m ({r['first_peak_change']:+.2%}) "
                    f"collapsed {r['collapsed']!s:5s} drift at rest {r['drift_at_rest_mm']:.4f} mm  impulse "
                    f"{r['delivered_impulse_Ns']:.6g} N s  cpu {r['cpu_s']:.2f} s  x{r['speedup']:.2f}"
                )
