"""Walls under a blast (issue #28, deliverable 4): the solver settings of the 200-block stack-bonded wall of
``bench_scale.py`` (5 x 2.5 x 0.5 m, 20 courses of 10, Method A, 10 kg at 5 m, 0.25 s), each measured against the
engine's default: CPU seconds of the run (user + sys; the machine is shared), the outcome (collapsed, fallen blocks)
and the top point's largest x displacement. MuJoCo flags (islands, warm start, body sleeping) are set on the scene's
model before the run. Not a test: ``python benchmarks/bench_walls_blast.py [--json] [--duration 0.25]``.
"""

from __future__ import annotations

import json
import os
import sys
import warnings
from dataclasses import replace

import mujoco
import numpy as np

import blastscale.sim3d.simulate as simulate_module
from blastscale.blast import blast_parameters
from blastscale.sim3d import make_load, simulate_structure
from blastscale.sim3d.contact import default_contact
from blastscale.structures import wall

#: name -> (ContactSettings changes, MuJoCo disable flags, MuJoCo enable flags)
VARIANTS = {
    "default": ({}, 0, 0),
    "tolerance 1e-8": ({"tolerance": 1e-8}, 0, 0),
    "tolerance 1e-6": ({"tolerance": 1e-6}, 0, 0),
    "iterations 10": ({"iterations": 10}, 0, 0),
    "impratio 1": ({"impratio": 1.0}, 0, 0),
    "pyramidal cone": ({"cone": "pyramidal"}, 0, 0),
    "islands off": ({}, int(mujoco.mjtDisableBit.mjDSBL_ISLAND), 0),
    "warm start off": ({}, int(mujoco.mjtDisableBit.mjDSBL_WARMSTART), 0),
    "sleep on": ({}, 0, int(mujoco.mjtEnableBit.mjENBL_SLEEP)),
}


def _cpu() -> float:
    t = os.times()
    return t.user + t.system


def run(structure, load, duration: float, changes: dict, disable: int, enable: int) -> dict:
    engine = simulate_module.integrate

    def integrate(scene, *a, **k):
        scene.mj_model.opt.disableflags |= disable
        scene.mj_model.opt.enableflags |= enable
        return engine(scene, *a, **k)

    simulate_module.integrate = integrate
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # an explicit contact is checked against the blast: same settings
            t0 = _cpu()
            r = simulate_structure(
                structure, load, duration, contact=replace(default_contact(structure), **changes), record_every=20
            )
            cpu = _cpu() - t0
    finally:
        simulate_module.integrate = engine
    s, ds = r.summary(), r.dataset
    top = ds["point_displacement"].sel(point=ds.attrs["top_point"], component="x").values
    return {
        "cpu_s": cpu,
        "collapsed": bool(s["collapsed"]),
        "fallen_blocks": s.get("fallen_blocks"),
        "top_max_x_m": float(np.max(top)),
    }


def study(duration: float = 0.25) -> dict:
    w = wall(length_m=5.0, height_m=2.5, thickness_m=0.5, courses=20, units_per_course=10, bond="stack")
    load = make_load("A", w, blast_parameters(10.0, 5.0))
    out = {"load_average": os.getloadavg()[0], "duration_s": duration}
    for name, (changes, disable, enable) in VARIANTS.items():
        out[name] = run(w, load, duration, changes, disable, enable)
    base = out["default"]
    for name in VARIANTS:
        out[name]["speedup"] = base["cpu_s"] / out[name]["cpu_s"]
        out[name]["top_max_x_change"] = out[name]["top_max_x_m"] / base["top_max_x_m"] - 1.0
        out[name]["outcome_unchanged"] = (out[name]["collapsed"], out[name]["fallen_blocks"]) == (
            base["collapsed"],
            base["fallen_blocks"],
        )
    return out


if __name__ == "__main__":
    dur = float(sys.argv[sys.argv.index("--duration") + 1]) if "--duration" in sys.argv else 0.25
    res = study(dur)
    if "--json" in sys.argv:
        print(json.dumps(res, indent=2))
    else:
        print(f"load average {res['load_average']:.2f}, {dur:g} s")
        for name in VARIANTS:
            r = res[name]
            print(
                f"{name:16s} cpu {r['cpu_s']:6.2f} s  x{r['speedup']:.2f}  top {r['top_max_x_m']:.5f} m "
                f"({r['top_max_x_change']:+.2%})  collapsed {r['collapsed']}  fallen {r['fallen_blocks']}"
            )
