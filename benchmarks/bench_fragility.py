"""Benchmark: a column's fragility per damage state (issue #38), ``--charges`` x ``--samples`` 3D cases on a
Dask ``LocalCluster`` of ``--workers`` single-threaded processes, into a resumable Zarr store.

The paper's square column (ten 1 m marble drums, 10 m; ``paper_column_square_250kg``), the prototype alone (the
fragility drops ``[scale]``), ``--duration`` s after the arrival; charges ``--charges`` (kg TNT at 10 m) times a
lognormal factor of log-deviation 0.2 (the charge and its TNT equivalence), friction uniform 0.6-0.8. Reported:
the wall time of the whole command path (``fragility()`` with ``run_sweep``: the cluster's start and stop, the
store and the fits included) and the sweep's own computing time, cases per minute, the counts and fits per state,
the load average before and after (the development machine is shared: the wall time depends on it).

Usage: ``python benchmarks/bench_fragility.py --json`` (defaults: 5 charges x 40 draws = 200 cases, 2 workers).
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import tempfile
import time
import tomllib
from pathlib import Path

import numpy as np


def bench(charges: list, samples: int, workers: int, duration: float) -> dict:
    from blastscale.scenario import Scenario
    from blastscale.scenario.library import library_text
    from blastscale.sweeps.fragility import fragility
    from blastscale.sweeps.run import run_sweep

    sc = Scenario.from_dict(tomllib.loads(library_text("paper_column_square_250kg"))).with_values(
        {"duration_s": duration}
    )
    runs = {}
    with tempfile.TemporaryDirectory() as d:
        store = Path(d) / "fragility.zarr"

        def run(spec):
            runs["sweep"] = run_sweep(spec, store, workers=workers)
            from blastscale.io.sweep_store import open_sweep

            return open_sweep(store)

        load0, t0, c0 = os.getloadavg(), time.perf_counter(), time.process_time()
        res = fragility(
            sc,
            np.asarray(charges, dtype=float),
            lognormal={"charge_kg": 0.2},
            uniform={"friction": (0.6, 0.8)},
            samples=samples,
            seed=1,
            run=run,
        )
        wall, cpu_main = time.perf_counter() - t0, time.process_time() - c0
    sw = runs["sweep"]
    return {
        "cases": int(len(charges) * samples),
        "workers": workers,
        "duration_s": duration,
        "wall_s": wall,
        "main_process_cpu_s": cpu_main,
        "sweep_compute_s": sw.seconds,
        "cases_per_minute": sw.cases_per_minute,
        "states": {n: st.to_dict() for n, st in res.states.items()},
        "charge_kg": res.charge_kg.tolist(),
        "load_average_before": load0,
        "load_average_after": os.getloadavg(),
    }


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--charges", default="100,250,500,1000,2000", help="charges [kg TNT], comma-separated")
    ap.add_argument("--samples", type=int, default=40, help="draws per charge")
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--duration", type=float, default=3.0, help="simulated time after the arrival [s]")
    ap.add_argument("--json", action="store_true")
    a = ap.parse_args(argv)
    out = bench([float(x) for x in a.charges.split(",")], a.samples, a.workers, a.duration)
    out["machine"] = {"cpus": os.cpu_count(), "python": platform.python_version(), "platform": platform.platform()}
    if a.json:
        print(json.dumps(out, indent=2, default=str))
    else:
        print(
            f"column fragility, {out['cases']} cases on {out['workers']} workers: {out['wall_s']:.1f} s wall "
            f"({out['cases_per_minute']:.3g} cases/min computing); load average {out['load_average_before']} -> "
            f"{out['load_average_after']}"
        )
        for n, st in out["states"].items():
            print(f"  {n}: {st['exceeded']} of {st['trials']}, median {st['median_charge_kg']} kg, beta {st['beta']}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
