"""Convergence study of a longer time step after the load (issue 19, docs/performance.md): the engine's
loop (settle, load steps at the default step), then the free motion with the step x ``factor`` (the
contact time constant kept >= 2 steps, MuJoCo's bound), against the default run. Not a test:
``python benchmarks/bench_step_after_load.py [--json]``.
"""

from __future__ import annotations

import json
import math
import sys
import time

import numpy as np

from blastscale.analysis.compare import _first_peak
from blastscale.blast import blast_parameters
from blastscale.sim3d import make_load
from blastscale.sim3d.contact import default_contact
from blastscale.sim3d.model import structure_scene
from blastscale.sim3d.reference import reference_factors, reference_settings, to_reference
from blastscale.sim3d.record import response_from_states
from blastscale.structures import MultiDrumColumn, wall
from blastscale.structures.block import RectangularBlock

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


def run(structure, charge, standoff, T, factor, every_s=1e-3):
    """States of the engine's loop with the step x ``factor`` once the load has ended (force mode)."""
    import mujoco

    a, b = reference_factors(structure, 9.81)
    c = reference_settings(None, structure, a, b)
    scene = structure_scene(to_reference(structure, a), c)
    m, d = scene.mj_model, mujoco.MjData(scene.mj_model)
    load = make_load("A", structure, blast_parameters(charge, standoff, blast_model="masi2021"))
    dt, nb = c.timestep, len(structure.bodies)
    mujoco.mj_step(m, d, int(math.ceil(20 * c.time_constant / dt - 1e-9)))
    d.qvel[:] = 0.0
    d.time = 0.0
    t, fF, fM = 0.0, a**4 / b**2, a**5 / b**2
    rec = {"time": [], "qpos": [], "qvel": [], "ncon": []}

    def keep():
        rec["time"].append(t)
        rec["qpos"].append(d.qpos.copy())
        rec["qvel"].append(d.qvel.copy())
        rec["ncon"].append(d.ncon)

    mujoco.mj_forward(m, d)
    keep()
    t0 = time.perf_counter()
    while load.first_arrival + t <= load.end_time:
        tp = load.first_arrival + t
        W = load.step_wrenches(tp, tp + dt / b, d.xipos[1:] / a, d.xmat[1:].reshape(nb, 3, 3))
        d.xfrc_applied[1:, 0:3], d.xfrc_applied[1:, 3:6] = W[:, 0:3] * fF, W[:, 3:6] * fM
        mujoco.mj_step(m, d)
        t += dt / b
        keep()
    d.xfrc_applied[:] = 0.0
    m.opt.timestep = dt * factor
    per = max(1, round(every_s * b / m.opt.timestep))
    while t < T:
        mujoco.mj_step(m, d, per)
        t += per * m.opt.timestep / b
        keep()
    wall_s = time.perf_counter() - t0
    n = len(rec["time"])
    qpos = np.array(rec["qpos"]).reshape(n, nb, 7)
    qvel = np.array(rec["qvel"]).reshape(n, nb, 6)
    qpos[:, :, 0:3] /= a
    qvel[:, :, 0:3] *= b / a
    qvel[:, :, 3:6] *= b
    st = {
        "time": np.array(rec["time"]),
        "qpos": qpos.reshape(n, -1),
        "qvel": qvel.reshape(n, -1),
        "ncon": np.array(rec["ncon"]),
        "delivered": np.zeros((nb, 3)),
        "first_arrival": load.first_arrival,
    }
    return response_from_states(structure, st, {}), wall_s


def study(factors=(1.0, 1.5, 2.0)) -> dict:
    out = {}
    for name, (st, W, R, T) in CASES.items():
        rows = {}
        base = None
        tc, dt = default_contact(st).time_constant, default_contact(st).timestep
        for f in factors:
            if tc < 2 * f * dt * (1 - 1e-12):
                continue
            r, w = run(st, W, R, T, f)
            ds = r.dataset
            top = ds.attrs["top_point"]
            x = ds["point_displacement"].sel(point=top, component="x").values
            fp = _first_peak(ds["time"].values, x, 0.1)[1]
            row = {
                "first_peak_m": float(fp),
                "collapsed": int(ds.attrs["collapsed"]),
                "max_rotation_rad": float(ds["tilt"].max()),
                "wall_s": w,
            }
            if base is None:
                base = row
            row["first_peak_change"] = row["first_peak_m"] / base["first_peak_m"] - 1.0 if base["first_peak_m"] else 0.0
            row["outcome_unchanged"] = row["collapsed"] == base["collapsed"]
            row["speedup"] = base["wall_s"] / w
            rows[f"x{f:g}"] = row
        out[name] = rows
    return out


if __name__ == "__main__":
    res = study()
    if "--json" in sys.argv:
        print(json.dumps(res, indent=2))
    else:
        for name, rows in res.items():
            for f, r in rows.items():
                print(
                    f"{name:34s} step {f:5s} first peak {r['first_peak_m']:.6g} m ({r['first_peak_change']:+.2%}) "
                    f"collapsed {r['collapsed']} max tilt {r['max_rotation_rad']:.4f} rad  x{r['speedup']:.2f}"
                )
