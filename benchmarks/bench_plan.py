"""Benchmark: ``plan`` of the paper's square 10-drum column (250 kg TNT at 10 m, masi2021, Method A,
8 s) with ``lab.top_3d = 3`` and ``lab.ensemble_3d = 32``: the screening, then for each of the three
best screened designs the prototype-vs-specimen 3D comparison and 32 ensemble members on native
threads in this process (``--workers N``: on N local Dask workers). Issue #24's target: within 15
minutes on a 2-core machine.

Prints the wall time of the whole plan and of each stage (from the planner's progress calls), the
best design and its ``odds_3d``; ``--duration`` shortens the simulated time, ``--members`` and
``--top`` change the ensemble (for a quick look; the target is the defaults).

Usage: ``python benchmarks/bench_plan.py --json``
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import time
from pathlib import Path

LIBRARY = Path(__file__).resolve().parents[1] / "src" / "blastscale" / "scenario" / "library"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--json", action="store_true", help="print one JSON object")
    ap.add_argument("--duration", type=float, default=None, help="simulated time [s] (default: the scenario's, 8 s)")
    ap.add_argument("--members", type=int, default=32)
    ap.add_argument("--top", type=int, default=3)
    ap.add_argument("--workers", type=int, default=0)
    a = ap.parse_args()

    from blastscale.planning import plan
    from blastscale.scenario import load_scenario
    from blastscale.scenario.lab import LabSpec

    sc = load_scenario(LIBRARY / "paper_column_square_250kg.toml")
    if a.duration is not None:
        sc = sc.with_values({"duration_s": a.duration})
    lab = LabSpec(top_3d=a.top, ensemble_3d=a.members)
    stages: dict = {}
    t0 = time.perf_counter()

    def progress(stage, done, total):
        name = "screening" if stage.startswith("designing") else "3D stage" if stage.startswith("3D") else stage
        stages.setdefault(name, time.perf_counter() - t0)  # when the stage began

    p = plan(sc, lab=lab, workers=a.workers, progress=progress)
    wall = time.perf_counter() - t0
    b = p.designs[0]
    out = {
        "benchmark": "plan of the paper's square 10-drum column",
        "top_3d": a.top,
        "ensemble_3d": a.members,
        "duration_s": sc.simulation.duration_s,
        "workers": a.workers,
        "wall_s": wall,
        "screening_done_s": stages.get("3D stage"),
        "designs": len(p.designs),
        "rejected": len(p.rejected),
        "best": {
            k: b[k]
            for k in (
                "law",
                "scale_fraction",
                "material",
                "burst",
                "explosive",
                "explosive_mass_kg",
                "standoff_m",
                "p_outcome_agree",
                "predicted_first_peak_error",
                "similarity_error",
                "safety_radius_m",
                "pareto",
                "odds_3d",
                "verdict",
                "chosen_3d_for",
            )
        },
        "recommendation": p.recommendation,
        "designs_3d": sum(1 for d in p.designs if d.get("simulated_by") == "3d"),
        "cpu_count": os.cpu_count(),
        "python": platform.python_version(),
        "target_s": 900.0,
    }
    if a.json:
        print(json.dumps(out, indent=1))
    else:
        print(
            f"plan of the column: {wall:.1f} s (target 900 s); best {b['scale_fraction']} {b['material']}, "
            f"P(outcome agrees) {b['p_outcome_agree']}"
        )
        print(p.recommendation["line"])


if __name__ == "__main__":
    main()
