"""Benchmark: compiled batched rocking solver vs scipy ``solve_ivp`` (DOP853) on the same cases.

Runs ``--cases`` (default 1000) mixed cases -- random rectangular blocks (height 1-20 m,
alpha 8-30 deg, density 1500-2700 kg/m^3), charges 5-500 kg TNT at 2-8 m (paper's
Appendix A fits, ``masi2021``), Friedlander / triangular / impulsive / tabulated pulses, some
rocking and some overturning -- once with ``RockingSolver.simulate_batch`` (rtol 1e-10,
atol 1e-12) and once with the scipy reference path (``simulate_reference``: DOP853, rtol
1e-10, atol 1e-12, impact / tipping / lying-down events), in the same process, and compares
the angles at ``--samples`` common times per case. Also times one critical-charge search
(paper block, 2 m, Friedlander pulse).

That ``speedup`` is against blastscale's own reference path (a general event loop: lift-off, rest,
lying down, tabulated breakpoints). ``plain_scipy`` measures, in the same run, against the script a
researcher would write (:func:`plain_scipy_rocking`: ``solve_ivp`` DOP853, impact and tipping
events, Housner's restitution, no blastscale code; the same rtol 1e-10, atol 1e-12): the paper's
block (10 m, alpha 15 deg, 2000 kg/m^3) under ``--charges`` (default 200) Friedlander pulses of
20-120 kg TNT at 2 m (masi2021; the pulse parameters are computed beforehand and handed over as
numbers) for 5 s, sampled every 10 ms, both stopping at the tipping point; blastscale on one
thread (``RockingSolver(threads=1).simulate_batch``). It reports ``speedup_vs_plain_scipy`` (best of
``--repeat`` for blastscale, one run of the script), the agreement (largest difference of the
samples up to the tipping point and of the first peaks [rad], outcomes) and the load average (timings on a shared machine
are noisy; CPU seconds are given beside the wall seconds).

Usage: ``python benchmarks/bench_rocking.py --json`` prints one JSON object with ``cases``,
``blastscale_s``, ``scipy_s``, ``speedup``, ``max_abs_diff_rad``, ``plain_scipy`` (and more);
``--plain-only`` runs the plain-script comparison alone. The numba compile/cache-load time is
measured separately (``compile_s``) and not counted in ``blastscale_s``.
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
        bp = blast_parameters(
            math.exp(rng.uniform(math.log(5.0), math.log(500.0))), rng.uniform(2.0, 8.0), blast_model="masi2021"
        )
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


def plain_scipy_rocking(height, width, depth, density, p_r, t_o, decay, duration, t_eval, rtol, atol, g=9.81):
    """The planar rocking of a rectangular block under a Friedlander pulse as a researcher would
    script it with scipy alone (no blastscale code): paper Eq. (eq:eom) in physical time,
    ``J_o theta'' = -m g r sin(s alpha - theta) + S P(t) r cos(s alpha - theta)``, DOP853 with an
    impact event (theta = 0: Housner's restitution ``e = 1 - 1.5 sin^2 alpha`` on the angular
    velocity, the other pivot) and a tipping event (|theta| = alpha: stop, overturned), the pulse end
    a segment boundary; the first peak from the root of theta_dot on the dense output.

    Returns ``(theta at t_eval [rad], first peak [rad], tipped)``."""
    from scipy.integrate import solve_ivp
    from scipy.optimize import brentq

    b, h = width / 2.0, height / 2.0
    m = density * width * height * depth
    r = math.hypot(b, h)
    alpha = math.atan2(b, h)
    J = 4.0 / 3.0 * m * r * r
    S = height * depth
    e = 1.0 - 1.5 * math.sin(alpha) ** 2
    p = math.sqrt(m * g * r / J)

    def load(t):
        return p_r * (1.0 - t / t_o) * math.exp(-decay * t / t_o) if t < t_o else 0.0

    th_s = np.full(t_eval.size, np.nan)
    t, y, s = 0.0, [0.0, 0.0], 1.0
    first_peak, tipped = math.nan, False
    while t < duration:

        def rhs(tt, yy, s=s):
            a = s * alpha - yy[0]
            return [yy[1], (-m * g * r * math.sin(a) + S * load(tt) * r * math.cos(a)) / J]

        def impact(tt, yy):
            return yy[0]

        def tip(tt, yy, s=s):
            return yy[0] - s * alpha

        impact.terminal, impact.direction = True, -s
        tip.terminal, tip.direction = True, s
        sol = solve_ivp(
            rhs,
            (t, t_o if t < t_o else duration),
            y,
            method="DOP853",
            rtol=rtol,
            atol=atol,
            events=[impact, tip],
            dense_output=True,
        )
        k = (t_eval >= t) & (t_eval <= sol.t[-1])
        if k.any():
            th_s[k] = sol.sol(t_eval[k])[0]
        if math.isnan(first_peak) and t >= t_o and sol.y[1, 0] * sol.y[1, -1] < 0.0:
            dense = sol.sol
            first_peak = float(dense(brentq(lambda x, dense=dense: dense(x)[1], sol.t[0], sol.t[-1], xtol=1e-14))[0])
        t, y = float(sol.t[-1]), [float(sol.y[0, -1]), float(sol.y[1, -1])]
        if sol.t_events[1].size:  # past the tipping point: overturned, stop there
            tipped = True
            th_s[t_eval > t] = y[0]
            break
        if sol.t_events[0].size:  # impact
            w = e * float(sol.y_events[0][0][1])
            if abs(w) < 1e-8 * p:  # at rest
                th_s[t_eval > t] = 0.0
                break
            y, s = [0.0, w], -s
    return th_s, first_peak, tipped


def bench_plain(n: int, repeat: int, duration: float = 5.0) -> dict:
    """blastscale (one thread) against :func:`plain_scipy_rocking` on the paper's block under n
    charges (module docstring)."""
    from blastscale.blast import blast_parameters
    from blastscale.blast.pulses import Friedlander
    from blastscale.rocking import RockingSolver
    from blastscale.structures.block import RectangularBlock

    blk = RectangularBlock.from_slenderness(10.0, math.radians(15.0), density=2000.0)
    W = np.geomspace(20.0, 120.0, n)
    bp = blast_parameters(W, 2.0, blast_model="masi2021")
    P, to, d = bp.reflected_pressure, bp.positive_duration, bp.friedlander_decay
    pulses = [Friedlander(P[k], to[k], d[k]) for k in range(n)]
    t = np.linspace(0.0, duration, round(duration / 0.01) + 1)
    solver = RockingSolver(rtol=1e-10, atol=1e-12, threads=1)
    solver.simulate_batch(blk, pulses[:2], duration, t, stop_at_overturn=True)  # compile or load the cache
    load_before = os.getloadavg()
    fast, cpu = math.inf, math.inf
    for _ in range(repeat):
        c0, t0 = time.process_time(), time.perf_counter()
        res = solver.simulate_batch(blk, pulses, duration, t, stop_at_overturn=True)
        fast, cpu = min(fast, time.perf_counter() - t0), min(cpu, time.process_time() - c0)
    c0, t0 = time.process_time(), time.perf_counter()
    plain = [
        plain_scipy_rocking(blk.height, blk.width, blk.depth, blk.density, P[k], to[k], d[k], duration, t, 1e-10, 1e-12)
        for k in range(n)
    ]
    plain_s, plain_cpu = time.perf_counter() - t0, time.process_time() - c0
    th = np.array([x[0] for x in plain])
    fp = np.array([x[1] for x in plain])
    tipped = np.array([x[2] for x in plain])
    rock = ~tipped & ~res.collapsed
    return {
        "cases": n,
        "duration_s": duration,
        "samples_per_case": t.size,
        "charges_kg": [float(W[0]), float(W[-1])],
        "standoff_m": 2.0,
        "threads": 1,
        "tolerances": {"rtol": 1e-10, "atol": 1e-12},
        "blastscale_s": fast,
        "blastscale_cpu_s": cpu,
        "plain_scipy_s": plain_s,
        "plain_scipy_cpu_s": plain_cpu,
        "speedup_vs_plain_scipy": plain_s / fast,
        "speedup_vs_plain_scipy_cpu": plain_cpu / cpu,
        "max_abs_diff_rad": float(np.max(np.abs(th - res.theta)[np.isfinite(res.theta)])),  # (NaN after a stop)
        "first_peak_max_abs_diff_rad": float(np.max(np.abs(fp[rock] - res.first_peak_angle[rock]))),
        "outcomes_agree": int((tipped == res.collapsed).sum()),
        "overturned_cases": int(tipped.sum()),
        "steps_total": int(res.n_steps.sum()),
        "load_average_before": load_before,
        "load_average_after": os.getloadavg(),
    }


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--cases", type=int, default=1000)
    ap.add_argument("--duration", type=float, default=4.0, help="simulated time per case [s]")
    ap.add_argument("--samples", type=int, default=201, help="common sampling times per case")
    ap.add_argument("--seed", type=int, default=2021)
    ap.add_argument("--charges", type=int, default=200, help="charges of the plain-script comparison")
    ap.add_argument("--repeat", type=int, default=3, help="repetitions of the blastscale batch (best kept)")
    ap.add_argument("--plain-only", action="store_true", help="run the plain-script comparison alone")
    ap.add_argument("--json", action="store_true", help="print one JSON object")
    args = ap.parse_args(argv)
    if args.plain_only:
        out = {"plain_scipy": bench_plain(args.charges, args.repeat)}
        print(
            json.dumps(out, indent=2)
            if args.json
            else "\n".join(f"{k:>32}: {v}" for k, v in out["plain_scipy"].items())
        )
        return 0

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

    plain = bench_plain(args.charges, args.repeat)
    out = {
        "cases": len(blocks),
        "blastscale_s": fast_s,
        "scipy_s": scipy_s,
        "speedup": scipy_s / fast_s,
        "speedup_vs_plain_scipy": plain["speedup_vs_plain_scipy"],
        "plain_scipy": plain,
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
