"""Cost against the work (issue 19), imported by ``bench_sim3d.py``: wall time per simulated second
against the number of blocks (1, 10, 50, 200), against ensemble members (1, 8, 64; serial vs parallel
threads) and against Dask workers (1, 2) on a 3D sweep, each with its ratio to the serial baseline
measured in the same run. Run alone: ``python benchmarks/bench_scale.py [--json] [--quick]``; ``--blast``: only the blast case
(``blocks.under_blast``) in CPU seconds, best of 3; ``--walls [--quick]``: only issue #41's figures (``walls.fixed_s``,
``walls.marginal_over_column``, ``walls.exponent_200_400``; :func:`walls`), which the full run also gives;
``--walls-profile``: where the cost grows from 200 to 400 blocks (:func:`walls_profile`).
"""

from __future__ import annotations

import dataclasses
import json
import math
import os
import sys
import time

import numpy as np

from blastscale._threads import available_cores
from blastscale.analysis.ensemble import ensemble_compare
from blastscale.analysis.systems import Settings3D, System3D, Systems3D
from blastscale.blast import blast_parameters
from blastscale.scenario import Scenario
from blastscale.sim3d.contact import reference_contact
from blastscale.sim3d.model import structure_scene
from blastscale.sim3d.reference import to_reference
from blastscale.structures import MultiDrumColumn, wall
from blastscale.structures.block import RectangularBlock

#: Structures of the cost-per-block figure: the paper's block, and 5 x 2.5 x 0.5 m walls (courses, units per
#: course); stack-bonded with 10, 50, 200 blocks, running-bond ones (half units at the ends) with 11, 52, 210.
WALLS = {"10": (2, 5), "50": (5, 10), "200": (20, 10)}

#: Settling before "at rest" [s of the 10 m reference]: the 20-course wall's settling transient (its largest
#: speed 1.4e-4 m/s at 0.1 s, 4.7e-6 at 0.3 s; the column's 3e-12 from 0.1 s) is over.
SETTLE_S = 0.5


def _rest_cost(structure, seconds: float, jacobian: str | None = None, settle: float = SETTLE_S) -> dict:
    """Wall s per simulated s of ``structure`` at rest (the engine's default settings in reference
    units, after ``settle`` s of settling), and MuJoCo's share of it in the constraint solve and collision."""
    import mujoco

    ref = to_reference(structure, 10.0 / float(structure.describe()["height_m"]))
    cs = reference_contact(ref)
    if jacobian is not None:
        cs = dataclasses.replace(cs, jacobian=jacobian)
    m = structure_scene(ref, cs).mj_model
    d = mujoco.MjData(m)
    mujoco.mj_step(m, d, int(settle / m.opt.timestep))
    for t in d.timer:
        t.duration, t.number = 0.0, 0
    t0 = time.perf_counter()
    mujoco.mj_step(m, d, int(seconds / m.opt.timestep))
    wall_s = (time.perf_counter() - t0) / seconds
    tm = d.timer
    step = tm[mujoco.mjtTimer.mjTIMER_STEP].duration or 1.0
    return {
        "wall_s_per_simulated_s": wall_s,
        "jacobian": cs.jacobian,
        "contacts": int(d.ncon),
        "bodies": m.nbody - 1,
        "largest_speed_m_s": float(np.abs(d.qvel).max()),
        "constraint_share": tm[mujoco.mjtTimer.mjTIMER_CONSTRAINT].duration / step,
        "collision_share": tm[mujoco.mjtTimer.mjTIMER_POS_COLLISION].duration / step,
    }


def _cpu() -> float:
    """CPU seconds of this process (user + sys): a shared machine's other work does not count."""
    return time.process_time()  # user + sys of this process, ns resolution (os.times ticks at 10 ms)


def _blast_cost(structure, charge: float, standoff: float, seconds: float, clock=time.perf_counter, repeat=1) -> float:
    """Wall s per simulated s (the engine's reference seconds, as :func:`_rest_cost`) of ``structure``
    under Method A of ``charge`` [kg] at ``standoff`` [m] for ``seconds`` of physical time; with ``clock``
    another clock (:func:`_cpu`) and the best of ``repeat`` runs."""
    from blastscale.sim3d import make_load, simulate_structure
    from blastscale.sim3d.reference import reference_factors

    load = make_load("A", structure, blast_parameters(charge, standoff))
    simulate_structure(structure, load, 0.005)  # compile and warm up
    best = math.inf
    for _ in range(repeat):
        t0 = clock()
        simulate_structure(structure, load, seconds, record_every=20)
        best = min(best, clock() - t0)
    _, b = reference_factors(structure, 9.81)
    return best / (seconds * b)


def under_blast(clock=time.perf_counter, repeat: int = 1) -> dict:
    """The column (250 kg at 10 m, 1 s) and the 200-block stack-bonded wall (10 kg at 5 m, 0.25 s) under a blast:
    cost per simulated second of each (:func:`_blast_cost`) and their ratio."""
    colb = _blast_cost(MultiDrumColumn("square"), 250.0, 10.0, 1.0, clock, repeat)
    big = _blast_cost(
        wall(length_m=5.0, height_m=2.5, thickness_m=0.5, courses=20, units_per_course=10, bond="stack"),
        10.0,
        5.0,
        0.25,
        clock,
        repeat,
    )
    return {"column_square_10_drums": colb, "200": big, "ratio_200_over_column": big / colb}


#: The walls of the cost-against-blocks exponent (issue #41): the benchmark's 200-block stack-bonded wall (20 courses
#: of 10 units, 5 x 2.5 x 0.5 m) and the same blocks in a wall twice as long (20 courses of 20, 10 x 2.5 x 0.5 m),
#: and twice as high (40 courses of 10, 5 x 5 x 0.5 m), all 10 kg at 5 m for 0.25 s.
WALL_200 = dict(length_m=5.0, height_m=2.5, thickness_m=0.5, courses=20, units_per_course=10, bond="stack")
WALL_400 = dict(WALL_200, length_m=10.0, units_per_course=20)
WALL_400_TALL = dict(WALL_200, height_m=5.0, courses=40)


def _new_wall(kw: dict):
    """A new wall object (nothing derived yet) from generator keywords."""
    return wall(**kw)


def _costs(structure, charge: float, standoff: float, seconds: float, fresh: bool) -> dict:
    """CPU s (this process) of one run of ``structure`` under Method A of ``charge`` [kg] at ``standoff`` [m]:
    ``first`` a run of one recorded interval (0.005 s) on a new object with every cache cleared (``fresh``: the fixed
    cost, geometry, model and settling, and that interval), ``short`` the same again (from the caches), ``long`` a
    run of ``seconds`` (from the caches); marginal cost per reference second = (long - short) / (reference seconds
    between them)."""
    from blastscale.sim3d import make_load, simulate_structure
    from blastscale.sim3d.reference import clear_scene_cache, reference_factors

    short = 0.005
    out = {}
    if fresh:
        clear_scene_cache()
        t0 = _cpu()
        load = make_load("A", structure, blast_parameters(charge, standoff))
        simulate_structure(structure, load, short, record_every=20)
        out["first"] = _cpu() - t0
    else:
        load = make_load("A", structure, blast_parameters(charge, standoff))
        simulate_structure(structure, load, short, record_every=20)
    t0 = _cpu()
    simulate_structure(structure, load, short, record_every=20)
    out["short"] = _cpu() - t0
    t0 = _cpu()
    r = simulate_structure(structure, load, seconds, record_every=20)
    out["long"] = _cpu() - t0
    _, b = reference_factors(structure, 9.81)
    out["marginal_per_reference_s"] = (out["long"] - out["short"]) / ((seconds - short) * b)
    s = r.summary()
    out["outcome"] = {k: s.get(k) for k in ("collapsed", "fallen_blocks", "max_residual_displacement_m")}
    return out


def walls(pairs: int = 3) -> dict:
    """Issue #41's figures of the walls, CPU seconds of this process, measured interleaved (the column, the 200-block
    wall, the 400-block walls long and tall, again ``pairs`` times; medians): ``fixed_s`` the 200-block wall's fixed
    cost (a new wall object, caches cleared: geometry, interfaces, model, settling; minus the same short run from
    the caches), ``marginal_over_column`` (the wall's marginal CPU s per reference second under its blast, 10 kg at
    5 m, over the square column's, 250 kg at 10 m), ``exponent_200_400`` = log2 of the marginal cost of the wall twice
    as long (:data:`WALL_400`) over the 200-block wall's, ``exponent_200_400_tall`` the same for the wall twice as
    high (:data:`WALL_400_TALL`)."""
    col = MultiDrumColumn("square")
    rows = {"column": [], "200": [], "400": [], "400_tall": []}
    for _ in range(pairs):
        rows["column"].append(_costs(col, 250.0, 10.0, 1.0, fresh=False))
        rows["200"].append(_costs(_new_wall(WALL_200), 10.0, 5.0, 0.25, fresh=True))
        rows["400"].append(_costs(_new_wall(WALL_400), 10.0, 5.0, 0.25, fresh=True))
        rows["400_tall"].append(_costs(_new_wall(WALL_400_TALL), 10.0, 5.0, 0.25, fresh=True))

    def med(key, what):
        return float(np.median([r[what] for r in rows[key]]))

    marginal = {k: med(k, "marginal_per_reference_s") for k in rows}
    fixed = [r["first"] - r["short"] for r in rows["200"]]
    return {
        "fixed_s": float(np.median(fixed)),
        "fixed_s_runs": fixed,
        "first_run_s": med("200", "first"),
        "cached_short_run_s": med("200", "short"),
        "fixed_s_400": float(np.median([r["first"] - r["short"] for r in rows["400"]])),
        "marginal_cpu_s_per_reference_s": marginal,
        "marginal_over_column": marginal["200"] / marginal["column"],
        "marginal_over_column_runs": [
            a["marginal_per_reference_s"] / c["marginal_per_reference_s"] for a, c in zip(rows["200"], rows["column"])
        ],
        "exponent_200_400": math.log2(marginal["400"] / marginal["200"]),
        "exponent_200_400_tall": math.log2(marginal["400_tall"] / marginal["200"]),
        "walls": {"200": WALL_200, "400": WALL_400, "400_tall": WALL_400_TALL},
        "outcomes": {k: rows[k][-1]["outcome"] for k in rows},
        "clock": "CPU s (user + sys) of this process; medians of the interleaved runs",
        "load_average": os.getloadavg(),
    }


def walls_profile() -> dict:
    """Where the cost grows from 200 to 400 blocks (issue #41, deliverable 2): for each wall of :func:`walls` under
    10 kg at 5 m for 0.25 s, the per-step solver statistics after the load (``bench_walls_newton.profile``: Newton
    iterations summed over the islands and in the largest, islands, contacts, constraint rows) and the profile of the
    interface graph in the engine's body order (:func:`blastscale.sim3d.collision.profile`: the band the Newton
    solver's factorisation fills)."""
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import bench_walls_newton as bw

    from blastscale.sim3d import make_load
    from blastscale.sim3d.collision import _graph, body_order, profile

    out = {}
    for name, kw in (("200", WALL_200), ("400", WALL_400), ("400_tall", WALL_400_TALL)):
        w = wall(**kw)
        n = len(w.bodies)
        p = profile(body_order(w.interfaces, n), _graph(w.interfaces, n))
        prof = bw.profile(w, make_load("A", w, blast_parameters(10.0, 5.0)), 0.25)
        a = prof["after_load"]
        out[name] = {
            "bodies": n,
            "interfaces": len(w.interfaces),
            "profile": p,
            "profile_per_body": p / n,
            "contacts_per_body": a["contacts"] / n,
            "after_load": a,
            "during_load": prof["during_load"],
        }
    return out


def blocks(quick: bool = False) -> dict:
    """Cost against the number of blocks at rest, default settings: 1 (the paper's block), stack-bonded walls
    of 10, 50, 200 blocks and running-bond walls of 11, 52, 210; the 10-drum square column beside them; ratios
    to the 10-block walls and to the column; and, unless quick, the column (250 kg at 10 m) and the 200-block
    stack-bonded wall (10 kg at 5 m) under a blast."""
    secs = 0.1 if quick else 0.2
    rows = {"1": _rest_cost(RectangularBlock.from_slenderness(10.0, math.radians(15.0)), secs)}
    for bond in ("stack", "running"):
        for n, (c, u) in WALLS.items():
            r = _rest_cost(
                wall(length_m=5.0, height_m=2.5, thickness_m=0.5, courses=c, units_per_course=u, bond=bond), secs
            )
            rows[n if bond == "stack" else f"{r['bodies']}_running"] = r
    column = _rest_cost(MultiDrumColumn("square"), secs)
    w = {k: v["wall_s_per_simulated_s"] for k, v in rows.items()}
    col = column["wall_s_per_simulated_s"]
    out = {
        "wall_s_per_simulated_s": w,
        "detail": rows,
        "column_square_10_drums": column,
        "ratio_200_over_10": w["200"] / w["10"],
        "ratio_200_over_column": w["200"] / col,
        "ratio_210_running_over_11_running": w["210_running"] / w["11_running"],
        "ratio_210_running_over_column": w["210_running"] / col,
    }
    if not quick:
        out["under_blast"] = under_blast()
    return out


def ensemble(quick: bool = False) -> dict:
    """The circular column's prototype ensemble (200 kg at 10 m) with 1, 8 (and 64 unless quick) members:
    serial (threads = 1) and on every core, the same members (bitwise), the speed-up."""
    col = MultiDrumColumn("circular")
    bp = blast_parameters(200.0, 10.0)
    dur = 0.5 if quick else 1.0
    ensemble_compare(Systems3D(System3D(col, bp, duration=0.01)), n=2, threads=1)  # imports outside the timing
    out = {"threads": available_cores(), "duration_s": dur}
    for n in (8,) if quick else (8, 64):
        d = dur if n <= 8 else dur / 4
        systems, settings = Systems3D(System3D(col, bp, duration=d)), Settings3D(record_every=4)
        t0 = time.perf_counter()
        s = ensemble_compare(systems, settings, n=n, perturbation=1e-6, threads=1)
        ts = time.perf_counter() - t0
        t0 = time.perf_counter()
        p = ensemble_compare(systems, settings, n=n, perturbation=1e-6)
        tp = time.perf_counter() - t0
        out[f"members_{n}"] = {
            "duration_s": d,
            "serial_wall_s": ts,
            "parallel_wall_s": tp,
            "speedup": ts / tp,
            "wall_s_per_member_simulated_s": tp / (n * d),
            "identical": bool(np.array_equal(s.prototype_members, p.prototype_members)),
        }
    t0 = time.perf_counter()
    ensemble_compare(Systems3D(System3D(col, bp, duration=dur)), n=2, threads=1)
    out["members_1"] = {"duration_s": dur, "wall_s_per_member_simulated_s": (time.perf_counter() - t0) / (2 * dur)}
    return out


def sweep3d(quick: bool = False) -> dict:
    """A 3D sweep (the square column, prototype only, 4 charges, 0.5 s each; threads = 1 per case so
    that the workers alone share the cores) on 1 and 2 local Dask workers (the cluster's start and stop
    not counted), and in this process on every core (threads)."""
    from blastscale.sweeps import SweepSpec
    from blastscale.sweeps.cases import evaluate_chunk
    from blastscale.sweeps.runner import run_chunks

    base = Scenario.from_dict(
        {
            "structure": {"kind": "column", "section": "square"},
            "blast": {"charge_kg": 250.0, "standoff_m": 10.0},
            "simulation": {"engine": "3d", "duration_s": 0.3 if quick else 0.6, "critical_charge": False, "threads": 1},
        }
    )
    spec = SweepSpec.build(base, {"charge_kg": [150.0, 200.0, 250.0, 300.0, 350.0, 400.0]})
    payload = spec.to_payload()
    todo = [(i, i, i + 1) for i in range(spec.n_cases)]
    out = {}
    warm = SweepSpec.build(base.with_values({"duration_s": 0.01}), {"charge_kg": [250.0]}).to_payload()
    for nw in (1, 2):
        from dask.distributed import Client, LocalCluster

        with (
            LocalCluster(
                n_workers=nw, threads_per_worker=1, processes=True, host="127.0.0.1", dashboard_address=None
            ) as cluster,
            Client(cluster) as client,
        ):
            client.run(evaluate_chunk, warm, 0, 1)  # imports and first compile in every worker, not timed
            got: dict = {}
            _, secs = run_chunks(payload, todo, got.__setitem__, scheduler=cluster.scheduler_address)
        out[f"workers_{nw}"] = {"wall_s": secs}
    out["workers_2"]["speedup"] = out["workers_1"]["wall_s"] / out["workers_2"]["wall_s"]
    spec_t = SweepSpec.build(
        base.with_values({"threads": available_cores()}), {"charge_kg": [150.0, 200.0, 250.0, 300.0, 350.0, 400.0]}
    )
    t0 = time.perf_counter()
    run_chunks(spec_t.to_payload(), [(0, 0, spec.n_cases)], lambda i, r: None, workers=0)
    secs = time.perf_counter() - t0
    out["in_process_threads"] = {
        "threads": available_cores(),
        "wall_s": secs,
        "speedup_vs_workers_1": out["workers_1"]["wall_s"] / secs,
    }
    return out


def plot(out: dict, path: str) -> None:
    """The cost figure of docs/performance.md from a ``bench_sim3d.py --json`` output."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(1, 3, figsize=(12, 3.6))
    b = out["blocks"]["wall_s_per_simulated_s"]
    for bond, keys in (
        ("stack bond", [k for k in b if k.isdigit()]),
        ("running bond", [k for k in b if "running" in k]),
    ):
        ax[0].loglog([int(k.split("_")[0]) for k in keys], [b[k] for k in keys], "o-", label=bond)
    ax[0].axhline(
        out["blocks"]["column_square_10_drums"]["wall_s_per_simulated_s"],
        ls="--",
        c="gray",
        label="10-drum square column",
    )
    ax[0].set(xlabel="blocks", ylabel="wall s per simulated s", title="at rest, default settings")
    ax[0].legend()
    e = out["ensemble"]
    ks = [k for k in e if k.startswith("members_") and "speedup" in e[k]]
    ax[1].bar([k.split("_")[1] for k in ks], [e[k]["speedup"] for k in ks])
    ax[1].axhline(e["threads"], ls="--", c="gray", label=f"{e['threads']} cores")
    ax[1].set(xlabel="ensemble members (circular column)", ylabel="speed-up vs serial", title="parallel members")
    ax[1].legend()
    s = out["sweep3d"]
    ax[2].bar(
        ["1 worker", "2 workers", "in process,\nthreads"],
        [1.0, s["workers_2"]["speedup"], s["in_process_threads"]["speedup_vs_workers_1"]],
    )
    ax[2].set(ylabel="speed-up vs 1 worker", title="3D sweep (square column)")
    fig.suptitle(f"mujoco {out.get('mujoco', '?')}, load average {out.get('load_average', float('nan')):.2f}")
    fig.tight_layout()
    fig.savefig(path, dpi=90)


def main() -> None:
    """``--plot OUT.json PNG``: the figure from a saved run; else run and print JSON."""
    if "--plot" in sys.argv:
        i = sys.argv.index("--plot")
        with open(sys.argv[i + 1]) as f:
            plot(json.load(f), sys.argv[i + 2])
        return
    if "--blast" in sys.argv:  # the blast case alone, in CPU seconds, best of 3 (a shared machine)
        blast = {"under_blast": under_blast(_cpu, 3), "clock": "CPU s (user + sys), best of 3"}
        print(json.dumps({"blocks": blast, "load_average": os.getloadavg()}, indent=2))
        return
    if "--walls-profile" in sys.argv:  # issue #41: where the cost grows
        print(json.dumps({"walls_profile": walls_profile()}, indent=2))
        return
    if "--walls" in sys.argv:  # issue #41's figures alone
        print(json.dumps({"walls": walls(1 if "--quick" in sys.argv else 3)}, indent=2))
        return
    quick = "--quick" in sys.argv
    out = {
        "blocks": blocks(quick),
        "walls": walls(1 if quick else 3),
        "ensemble": ensemble(quick),
        "sweep3d": sweep3d(quick),
    }
    print(json.dumps(out, indent=2))


if __name__ == "__main__":
    main()
