"""A 1000-block facade under a blast, one simulated second (issue #41, deliverable 3).

The facade: a running-bond wall 10 m long, 5 m high, 0.3 m thick, 40 courses of 25 units (0.4 x 0.125 x 0.3 m
blocks, half units at the ends of every other course: 1020 blocks), Method A of 10 kg TNT at 10 m, 1 s after the
first arrival, the engine's default settings. Figures: CPU seconds of this process (user + sys) and wall seconds,
split into the fixed cost (a new structure: geometry, interfaces, model, settling; a 0.005 s run) and the run of
1 s (from the caches), the peak resident memory (``ru_maxrss``), and per step the Newton iterations (summed over the
islands), islands, contacts and constraint rows, read after every step of the engine's own loop (MuJoCo stepped
one step at a time; the same states). Not a test: ``python benchmarks/bench_facade.py [--duration 1.0]`` (prints
JSON; say the machine's load with the figures).
"""

from __future__ import annotations

import json
import os
import resource
import sys
import time

import mujoco
import numpy as np

from blastscale.blast import blast_parameters
from blastscale.sim3d import make_load, simulate_structure
from blastscale.structures import wall

#: The facade's generator keywords.
FACADE = dict(length_m=10.0, height_m=5.0, thickness_m=0.3, courses=40, units_per_course=25, bond="running")
#: The blast: charge [kg TNT] and standoff [m].
CHARGE_KG, STANDOFF_M = 10.0, 10.0


def _cpu() -> float:
    return time.process_time()


def _stepping_stats():
    """Replace ``mujoco.mj_step`` by one that steps one step at a time and records, after each, the Newton
    iterations summed over the islands, the islands, the contacts and the constraint rows; returns (rows, restore)."""
    rows = []
    orig = mujoco.mj_step

    def step(m, d, nstep=1):
        for _ in range(int(nstep)):
            orig(m, d)
            ni = max(1, min(int(d.nisland), len(d.solver_niter)))
            rows.append((float(d.time), int(np.sum(d.solver_niter[:ni])), ni, int(d.ncon), int(d.nefc)))
            if len(rows) % 500 == 0:  # progress on stderr: reference time, CPU s so far
                print(
                    f"step {len(rows)}: t = {d.time:.4f} s (reference), CPU {_cpu():.1f} s", file=sys.stderr, flush=True
                )

    mujoco.mj_step = step

    def restore():
        mujoco.mj_step = orig

    return rows, restore


def facade(duration: float = 1.0) -> dict:
    w = wall(**FACADE)
    t0, c0 = time.perf_counter(), _cpu()
    load = make_load("A", w, blast_parameters(CHARGE_KG, STANDOFF_M))
    simulate_structure(w, load, 0.005, record_every=20)
    fixed = {"cpu_s": _cpu() - c0, "wall_s": time.perf_counter() - t0}
    rows, restore = _stepping_stats()
    try:
        t0, c0 = time.perf_counter(), _cpu()
        r = simulate_structure(w, load, duration, record_every=20)
        run = {"cpu_s": _cpu() - c0, "wall_s": time.perf_counter() - t0}
    finally:
        restore()
    a = np.array(rows)
    s = r.summary()
    return {
        "blocks": len(w.bodies),
        "facade": FACADE,
        "charge_kg": CHARGE_KG,
        "standoff_m": STANDOFF_M,
        "duration_s": duration,
        "fixed": fixed,
        "run": run,
        "total_cpu_s": fixed["cpu_s"] + run["cpu_s"],
        "max_rss_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0,
        "steps": len(a),
        "newton_iterations_per_step": float(a[:, 1].mean()),
        "newton_iterations_p99": float(np.percentile(a[:, 1], 99)),
        "islands_per_step": float(a[:, 2].mean()),
        "contacts_per_step": float(a[:, 3].mean()),
        "constraint_rows_per_step": float(a[:, 4].mean()),
        "outcome": {k: s.get(k) for k in ("collapsed", "fallen_blocks", "stability")},
        "load_average": os.getloadavg(),
    }


def main() -> None:
    dur = float(sys.argv[sys.argv.index("--duration") + 1]) if "--duration" in sys.argv else 1.0
    print(json.dumps(facade(dur), indent=1))


if __name__ == "__main__":
    main()
