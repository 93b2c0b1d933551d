"""Cost of assemblies on the 3D engine (issue 16): wall-seconds per simulated second for stack-bonded
walls of 10, 50 and 200 blocks (dense vs sparse constraint Jacobian, Newton), against the 10-drum square
column; and the arch's 5 s gravity run. Not a test: ``python benchmarks/bench_assemblies.py [--json]``.
"""

from __future__ import annotations

import dataclasses
import json
import sys
import time

import mujoco

from blastscale.sim3d.contact import reference_contact
from blastscale.sim3d.model import structure_scene
from blastscale.sim3d.reference import to_reference
from blastscale.structures import MultiDrumColumn, wall

SIM_SECONDS = 0.2


def cost(structure, jacobian, seconds=SIM_SECONDS):
    """Wall seconds per simulated second of ``structure`` at rest (reference units, 0.25 ms steps)."""
    ref = to_reference(structure, 10.0 / float(structure.describe()["height_m"]))
    cs = dataclasses.replace(reference_contact(ref), jacobian=jacobian)
    m = structure_scene(ref, cs).mj_model
    d = mujoco.MjData(m)
    mujoco.mj_step(m, d, int(0.05 / m.opt.timestep))  # settle first
    n = int(seconds / m.opt.timestep)
    t = time.perf_counter()
    mujoco.mj_step(m, d, n)
    return (time.perf_counter() - t) / seconds


def main():
    rows = {"column_10_drums_dense": cost(MultiDrumColumn("square"), "dense")}
    for n, (c, u) in ((10, (2, 5)), (50, (5, 10)), (200, (20, 10))):
        w = wall(length_m=5.0, height_m=2.5, thickness_m=0.5, courses=c, units_per_course=u, bond="stack")
        rows[f"wall_{n}_blocks_sparse"] = cost(w, "sparse")
        if n <= 50:
            rows[f"wall_{n}_blocks_dense"] = cost(w, "dense")
    rows["wall_200_over_column_10"] = rows["wall_200_blocks_sparse"] / rows["column_10_drums_dense"]
    if "--json" in sys.argv:
        print(json.dumps(rows, indent=2))
    else:
        for k, v in rows.items():
            print(f"{k:32s} {v:8.3f}")


if __name__ == "__main__":
    main()
