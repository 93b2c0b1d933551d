"""Benchmark: compiled batched rocking solver vs scipy ``solve_ivp`` (DOP853) on the same cases.

Runs ``--cases`` (default 1000) mixed cases -- random rectangular blocks (height 1-20 m,
alpha 8-30 deg, density 1500-2700 kg/m^3), charges 5-500 kg TNT at 2-8 m (paper's
Appendix A fits, ``masi2021``), Friedlander / triangular / impulsive / tabulated pulses, some
rocking and some overturning -- once with ``RockingSolver.simulate_batch`` (rtol 1e-10,
atol 1e-12) and once with the scipy reference path (``simulate_reference``: DOP853, rtol
1e-10, atol 1e-12, impact / tipping / lying-down events), in the same process, and compares
the angles at ``--samples`` common times per case. Also times one critical-charge search
(paper block, 2 m, Friedlander pulse).

Usage: ``python benchmarks/bench_rocking.py --json`` prints one JSON object with ``cases``,
``blastscale_s``, ``scipy_s``, ``speedup``, ``max_abs_diff_rad`` (and more). The numba
compile/cache-load time is measured separately (``compile_s``) and not counted in
``blastscale_s``.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import platform
import sys
import time

import numpy as np


def make_cases(n: int, seed: int):
    from blastscale.blast import Tabulated, blast_parameters
    from blastscale.structures.block import RectangularBlock

    rng = np.random.default_rng(seed)
    blocks, pulses, kinds = [], [], []
    shapes = ("friedlander", "triangular", "impulsive", "tabulated")
    for k in range(n):
        blk = RectangularBlock.from_slenderness(
            rng.uniform(1.0, 20.0), math.radians(rng.uniform(8.0, 30.0)), density=rng.uniform(1500.0, 2700.0)
        )
        bp = blast_parameters(math.exp(rng.uniform(math.log(5.0), math.log(500.0))), rng.uniform(2.0, 8.0), blast_model="masi2021")
        shape = shapes[k % 4]
        if shape == "tabulated":  # the Friedlander pulse sampled at 16 points
            f = bp.pulse("friedlander")
            t = np.linspace(0.0, f.duration, 16)
            pulse = Tabulated(t, f.pressure(t))
        else:
            pulse = bp.pulse(shape)
        blocks.append(blk)
        pulses.append(pulse)
        kinds.append(shape)
    return blocks, pulses, kinds


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--cases", type=int, default=1000)
    ap.add_argument("--duration", type=float, default=4.0, help="simulated time per case [s]")
    ap.add_argument("--samples", type=int, default=201, help="common sampling times per case")
    ap.add_argument("--seed", type=int, default=2021)
    ap.add_argument("--json", action="store_true", help="print one JSON object")
    args = ap.parse_args(argv)

    from blastscale.rocking import RockingSolver, critical_charge, simulate_reference
    from blastscale.structures.block import RectangularBlock

    blocks, pulses, kinds = make_cases(args.cases, args.seed)
    t_eval = np.linspace(0.0, args.duration, args.samples)
    solver = RockingSolver(rtol=1e-10, atol=1e-12)

    t0 = time.perf_counter()
    solver.simulate_batch(blocks[:4], pulses[:4], args.duration, t_eval)  # compile or load the cache
    compile_s = time.perf_counter() - t0

    t0 = time.perf_counter()
    batch = solver.simulate_batch(blocks, pulses, args.duration, t_eval)
    fast_s = time.perf_counter() - t0

    t0 = time.perf_counter()
    refs = [
        simulate_reference(b, p, args.duration, t_eval=t_eval, rtol=1e-10, atol=1e-12, method="DOP853")
        for b, p in zip(blocks, pulses)
    ]
    scipy_s = time.perf_counter() - t0

    ref_theta = np.array([r.theta_eval for r in refs])
    diff = np.abs(batch.theta - ref_theta)
    worst = int(np.argmax(np.max(diff, axis=1)))
    ref_over = np.array([r.collapsed for r in refs])

    paper_block = RectangularBlock.from_slenderness(10.0, math.radians(15.0))
    critical_charge(paper_block, 2.0, blast_model="masi2021")  # warm the blast-model cache
    t0 = time.perf_counter()
    crit = critical_charge(paper_block, 2.0, blast_model="masi2021")
    crit_s = time.perf_counter() - t0

    out = {
        "cases": len(blocks),
        "blastscale_s": fast_s,
        "scipy_s": scipy_s,
        "speedup": scipy_s / fast_s,
        "max_abs_diff_rad": float(diff.max()),
        "worst_case": {"index": worst, "pulse": kinds[worst], "collapsed": bool(batch.collapsed[worst])},
        "overturned_cases": int(batch.collapsed.sum()),
        "rocking_cases": int((~batch.collapsed).sum()),
        "outcomes_agree": int((batch.collapsed == ref_over).sum()),
        "impacts_total": int(batch.n_impacts.sum()),
        "steps_total": int(batch.n_steps.sum()),
        "pulse_mix": {k: kinds.count(k) for k in sorted(set(kinds))},
        "duration_s": args.duration,
        "samples_per_case": args.samples,
        "tolerances": {"rtol": 1e-10, "atol": 1e-12, "scipy_method": "DOP853"},
        "compile_s": compile_s,
        "critical_charge_search_s": crit_s,
        "critical_charge_kg": crit.charge_kg,
        "critical_charge_simulations": crit.evaluations,
        "machine": {"python": platform.python_version(), "cpus": os.cpu_count(), "processor": platform.processor()},
    }
    if args.json:
        print(json.dumps(out, indent=2))
    else:
        for k, v in out.items():
            print(f"{k:>28}: {v}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
