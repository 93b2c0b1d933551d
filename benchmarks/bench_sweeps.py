"""Benchmark: capacity (critical charge per case), sweep throughput (planar, 3D), Dask 1 vs 2 workers.

1. **Critical charge per case**: ``capacity_curve`` (first-swing energy criterion, all stand-offs
   at once) over ``--standoffs`` stand-offs of the paper's block (masi2021, Friedlander), and one
   scalar ``critical_charge`` call; against, in the same run, the bisection on full simulations
   (to rest, every impact; bracket [W/1.5, 1.5 W] checked, bisected in ln W to 1e-7) on a subset
   of the stand-offs: seconds per case, their ratio, and the largest relative difference.
2. **Planar cases per minute**: the compiled batch kernel alone (one 5 s simulation per case);
   ``run_sweep`` of a planar scenario (paper block, 5 s, 2001 samples, no critical charge; every
   Study scalar: one Study per case) in this process, varying charge x stand-off (a
   design per case) and varying the restitution (one design); the outcome-only rate of the
   first-swing criterion (what ``fragility`` uses, prototype only); and the sweep **outcome
   mode** (``--outcomes``: prototype and model, overturned and largest rotation, a design per
   case) over a charge x stand-off grid of ``--outcome-cases`` cases, in this process and on a
   LocalCluster of 1 and 2 workers (wall time including the cluster start and the Zarr store),
   with its ratios to the kernel alone and to the Study-equivalent path.
3. **3D cases per minute**: ``run_sweep`` of the 3D engine (paper block, short duration).
4. **1 vs 2 workers**: the same planar sweep on a ``LocalCluster`` of 1 and of 2 worker
   processes (wall time including the cluster start, and the speed-up).
5. **Outcome mode on threads** (``outcome``): the outcome mode's evaluation of ``--outcome-thread-cases``
   cases (charge x stand-off grid, ``planar_outcomes`` in this process, no store) with
   ``simulation.threads`` 1 and 2: wall and CPU seconds (best of ``--repeat``), ``threads_2.speedup``
   (1 thread / 2 threads, wall) and ``threads_2.bitwise_equal`` (every output array, NaN where
   invalid). ``--outcome-threads-only`` runs this section alone (with the load average: the speed-up
   needs two idle cores).

Usage: ``python benchmarks/bench_sweeps.py --json`` prints one JSON object.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import platform
import tempfile
import time
from pathlib import Path

import numpy as np


def bench_capacity(n: int, n_bisect: int) -> dict:
    from blastscale.rocking import RockingSystem, capacity_curve, critical_charge, critical_charge_by_bisection
    from blastscale.structures import RectangularBlock

    blk = RectangularBlock.from_slenderness(10.0, math.radians(15.0))
    system = RockingSystem.from_block(blk)
    R = np.geomspace(1.0, 6.0, n)
    capacity_curve(system, R[:2], blast_model="masi2021")  # warm the compiled kernel
    t0 = time.perf_counter()
    curve = capacity_curve(system, R, blast_model="masi2021")
    t_curve = time.perf_counter() - t0
    t0 = time.perf_counter()
    for r in (1.5, 2.0, 3.0, 4.0, 5.0):
        single = critical_charge(system, r, blast_model="masi2021")
    t_single = (time.perf_counter() - t0) / 5
    single = critical_charge(system, 2.0, blast_model="masi2021")
    idx = np.linspace(0, n - 1, n_bisect).astype(int)
    t0 = time.perf_counter()
    wb = [
        critical_charge_by_bisection(system, R[i], curve.critical_charge_kg[i], blast_model="masi2021", rel=1e-7)
        for i in idx
    ]
    t_bis = (time.perf_counter() - t0) / len(idx)
    rel = np.abs(curve.critical_charge_kg[idx] / np.array(wb) - 1.0)
    return {
        "standoffs": int(n),
        "critical_charge_ms_per_case_curve": 1e3 * t_curve / n,
        "critical_charge_ms_single_call": 1e3 * t_single,
        "critical_charge_kg_at_2m": single.charge_kg,
        "evaluations_per_case_mean": float(curve.evaluations.mean()),
        "bisection_full_simulations_ms_per_case": 1e3 * t_bis,
        "bisection_cases": int(len(idx)),
        "speedup_vs_bisection_curve": t_bis / (t_curve / n),
        "speedup_vs_bisection_single_call": t_bis / t_single,
        "max_relative_difference_vs_bisection": float(rel.max()),
        "target_ms_per_case": 2.0,
    }


def planar_spec(vary: dict, outcomes: bool = False):
    from blastscale.scenario import Scenario
    from blastscale.sweeps import SweepSpec

    base = Scenario.default().with_values({"engine": "planar", "critical_charge": False})
    return SweepSpec.build(base, vary, outcomes=outcomes)


def timed_sweep(spec, **kw) -> dict:
    from blastscale.sweeps.run import run_sweep

    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.perf_counter()
        run = run_sweep(spec, Path(tmp) / "b.zarr", **kw)
        wall = time.perf_counter() - t0
    return {
        "cases": spec.n_cases,
        "wall_s": wall,
        "compute_s": run.seconds,
        "cases_per_minute": spec.n_cases / wall * 60.0,
        "workers": run.workers,
    }


def bench_planar(n_side: int) -> dict:
    import warnings

    from blastscale.scenario import Scenario
    from blastscale.sweeps import SweepSpec
    from blastscale.sweeps.fragility import overturning_outcomes
    from blastscale.sweeps.grids import Distribution

    timed_sweep(planar_spec({"charge_kg": [40.0, 60.0]}), workers=0)  # warm up
    designs = timed_sweep(
        planar_spec({"charge_kg": np.linspace(30, 150, n_side), "standoff_m": np.linspace(1.5, 4.0, n_side)}), workers=0
    )
    shared = timed_sweep(planar_spec({"restitution": np.linspace(0.3, 0.95, n_side * n_side)}), workers=0)
    base = Scenario.default().with_values({"engine": "planar"})
    spec = SweepSpec.build(
        base,
        {"charge_kg": np.geomspace(40, 160, 20)},
        relative={"charge_kg": Distribution("lognormal", (1.0, 0.2))},
        samples=20000,
        seed=1,
    )
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        t0 = time.perf_counter()
        overturning_outcomes(spec)
        dt = time.perf_counter() - t0
    kernel = bench_kernel_only(2000)
    return {
        "kernel_only_prototype_simulations": kernel,
        "full_study_scalars_design_per_case": designs,
        "full_study_scalars_one_design": shared,
        "outcome_only_first_swing": {"cases": spec.n_cases, "wall_s": dt, "cases_per_minute": spec.n_cases / dt * 60.0},
        "target_cases_per_minute": 1e6,
    }


def bench_outcomes(n_cases: int, study_rate: float, kernel_rate: float) -> dict:
    """The sweep outcome mode over a charge (20-200 kg, geometric) x stand-off (1.5-6 m) grid of
    about ``n_cases`` cases (paper block, masi2021, lambda = 1/200: a design per case; the
    cases outside the fits are marked invalid), in this process and on 1 and 2 local workers."""
    side = max(2, round(math.sqrt(n_cases)))
    spec = planar_spec(
        {"charge_kg": np.geomspace(20, 200, side), "standoff_m": np.linspace(1.5, 6.0, side)}, outcomes=True
    )
    timed_sweep(planar_spec({"charge_kg": [40.0, 60.0]}, outcomes=True), workers=0)  # warm up
    out = {"cases": spec.n_cases, "in_process": timed_sweep(spec, workers=0)}
    for w in (1, 2):
        out[f"workers_{w}"] = timed_sweep(spec, workers=w)
    best = max(out[k]["cases_per_minute"] for k in ("in_process", "workers_1", "workers_2"))
    out.update(
        {
            "best_cases_per_minute": best,
            "speedup_2_vs_1_workers_wall": out["workers_1"]["wall_s"] / out["workers_2"]["wall_s"],
            "ratio_to_kernel_only": best / kernel_rate,
            "ratio_to_study_equivalent_path": best / study_rate,
            "target_cases_per_minute": 1e6,
        }
    )
    return out


def bench_outcome_threads(n_cases: int, repeat: int) -> dict:
    """The outcome mode's evaluation (``planar_outcomes``: design, pulse phases on the compiled kernel,
    first swings) of one chunk of about ``n_cases`` cases in this process, on 1 and 2 threads."""
    from blastscale.sweeps.outcomes import planar_outcomes

    side = max(2, int(round(math.sqrt(n_cases))))
    grid = {"charge_kg": np.geomspace(20, 200, side), "standoff_m": np.linspace(1.5, 6.0, side)}
    out, vals = {"cases": side * side, "load_average_before": os.getloadavg()}, {}
    for k in (1, 2):
        spec = outcome_spec(grid, k)
        planar_outcomes(spec, 0, min(64, spec.n_cases))  # warm (compiled kernel, blast fits)
        best, cpu = math.inf, math.inf
        for _ in range(repeat):
            c0, t0 = time.process_time(), time.perf_counter()
            vals[k] = planar_outcomes(spec, 0, spec.n_cases)
            best, cpu = min(best, time.perf_counter() - t0), min(cpu, time.process_time() - c0)
        out[f"threads_{k}"] = {"wall_s": best, "cpu_s": cpu, "cases_per_minute": spec.n_cases / best * 60.0}
    out["threads_2"]["speedup"] = out["threads_1"]["wall_s"] / out["threads_2"]["wall_s"]
    out["threads_2"]["bitwise_equal"] = all(
        np.array_equal(vals[1][key], vals[2][key], equal_nan=True) for key in vals[1]
    )
    out["load_average_after"] = os.getloadavg()
    return out


def outcome_spec(grid: dict, threads: int):
    """The outcome-mode spec of the paper's block over ``grid`` with ``simulation.threads = threads``."""
    from blastscale.scenario import Scenario
    from blastscale.sweeps import SweepSpec

    base = Scenario.default().with_values({"engine": "planar", "critical_charge": False, "threads": threads})
    return SweepSpec.build(base, grid, outcomes=True)


def bench_kernel_only(n: int, duration: float = 5.0) -> dict:
    """One planar simulation per case (the paper's block, random charges 30-150 kg at 2-4 m,
    Friedlander, 5 s, 201 samples), compiled batch kernel alone: what a planar case costs without
    the Study's design and result dictionaries."""
    from blastscale.blast import blast_parameters
    from blastscale.blast.pulses import Friedlander
    from blastscale.rocking import RockingSolver, RockingSystem
    from blastscale.structures import RectangularBlock

    rng = np.random.default_rng(0)
    system = RockingSystem.from_block(RectangularBlock.from_slenderness(10.0, math.radians(15.0)))
    bp = blast_parameters(rng.uniform(30, 150, n), rng.uniform(2, 4, n), "masi2021")
    pulses = [Friedlander(bp.reflected_pressure[k], bp.positive_duration[k], bp.friedlander_decay[k]) for k in range(n)]
    t = np.linspace(0.0, duration, 201)
    solver = RockingSolver()
    solver.simulate_batch(system, pulses[:2], duration, t)  # warm
    t0 = time.perf_counter()
    res = solver.simulate_batch(system, pulses, duration, t)
    dt = time.perf_counter() - t0
    return {
        "cases": n,
        "duration_s": duration,
        "wall_s": dt,
        "cases_per_minute": n / dt * 60.0,
        "collapsed": int(res.collapsed.sum()),
        "processes": 1,
    }


def bench_3d(n: int, duration: float) -> dict:
    from blastscale.scenario import Scenario
    from blastscale.sweeps import SweepSpec

    base = Scenario.default().with_values({"engine": "3d", "critical_charge": False, "duration_s": duration})
    spec = SweepSpec.build(base, {"charge_kg": np.linspace(30, 120, n)})
    timed_sweep(SweepSpec.build(base, {"charge_kg": [50.0]}), workers=0)  # warm up (MuJoCo, kernels)
    out = timed_sweep(spec, workers=0)
    out["duration_s"] = duration
    return out


def bench_workers(n_side: int) -> dict:
    spec = planar_spec({"charge_kg": np.linspace(30, 150, n_side), "standoff_m": np.linspace(1.5, 4.0, n_side)})
    one = timed_sweep(spec, workers=1)
    two = timed_sweep(spec, workers=2)
    return {
        "cases": spec.n_cases,
        "one_worker": one,
        "two_workers": two,
        "speedup_wall": one["wall_s"] / two["wall_s"],
        "speedup_compute": one["compute_s"] / two["compute_s"],
    }


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--standoffs", type=int, default=200, help="stand-offs of the capacity curve")
    ap.add_argument("--bisect", type=int, default=10, help="stand-offs also bisected on full simulations")
    ap.add_argument("--side", type=int, default=20, help="planar sweep grid side (side^2 cases)")
    ap.add_argument("--cases3d", type=int, default=4)
    ap.add_argument("--duration3d", type=float, default=1.0, help="3D simulated time per case [s]")
    ap.add_argument("--outcome-cases", type=int, default=1_000_000, help="cases of the outcome-mode sweep")
    ap.add_argument(
        "--outcome-thread-cases", type=int, default=40_000, help="cases of the outcome mode on 1 and 2 threads"
    )
    ap.add_argument("--repeat", type=int, default=3, help="repetitions of the thread comparison (best kept)")
    ap.add_argument("--outcome-threads-only", action="store_true", help="run the outcome-mode thread comparison alone")
    ap.add_argument("--json", action="store_true")
    a = ap.parse_args(argv)
    if a.outcome_threads_only:
        out = {
            "outcome": bench_outcome_threads(a.outcome_thread_cases, a.repeat),
            "machine": {"cpus": os.cpu_count(), "python": platform.python_version(), "platform": platform.platform()},
        }
        o = out["outcome"]
        print(
            json.dumps(out, indent=2)
            if a.json
            else f"outcome mode, {o['cases']} cases: 2 threads x{o['threads_2']['speedup']:.3g} over 1, bitwise equal "
            f"{o['threads_2']['bitwise_equal']} (load average {o['load_average_before']})"
        )
        return 0
    out = {
        "capacity": bench_capacity(a.standoffs, a.bisect),
        "planar": bench_planar(a.side),
        "3d": bench_3d(a.cases3d, a.duration3d),
        "load_average_before_outcomes": os.getloadavg(),
        "workers": bench_workers(a.side),
    }
    p = out["planar"]
    out["outcome"] = bench_outcome_threads(a.outcome_thread_cases, a.repeat)
    out["outcomes"] = bench_outcomes(
        a.outcome_cases,
        p["full_study_scalars_design_per_case"]["cases_per_minute"],
        p["kernel_only_prototype_simulations"]["cases_per_minute"],
    )
    out["machine"] = {
        "cpus": os.cpu_count(),
        "python": platform.python_version(),
        "platform": platform.platform(),
        "load_average_end": os.getloadavg(),
    }
    if a.json:
        print(json.dumps(out, indent=2))
    else:
        c, p = out["capacity"], out["planar"]
        print(
            f"critical charge: {c['critical_charge_ms_per_case_curve']:.3g} ms/case (curve), "
            f"{c['critical_charge_ms_single_call']:.3g} ms (one call); bisection on full simulations "
            f"{c['bisection_full_simulations_ms_per_case']:.3g} ms/case; max rel. diff {c['max_relative_difference_vs_bisection']:.2g}"
        )
        print(
            f"planar: {p['full_study_scalars_design_per_case']['cases_per_minute']:.4g} cases/min (design per case), "
            f"{p['full_study_scalars_one_design']['cases_per_minute']:.4g} (one design), outcome only "
            f"{p['outcome_only_first_swing']['cases_per_minute']:.4g}"
        )
        print(
            f"3D: {out['3d']['cases_per_minute']:.4g} cases/min; 1 vs 2 workers: x{out['workers']['speedup_wall']:.3g}"
        )
        o = out["outcomes"]
        print(
            f"outcome mode, {o['cases']} cases: {o['in_process']['cases_per_minute']:.4g} cases/min in process, "
            f"{o['workers_1']['cases_per_minute']:.4g} (1 worker), {o['workers_2']['cases_per_minute']:.4g} (2 workers)"
        )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
