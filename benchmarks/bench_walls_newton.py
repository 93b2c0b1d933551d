"""Where a wall under a blast spends its steps (issue #28, deliverable 4): the Newton iterations per step during
and after the load, MuJoCo's timers, and the sensitivity of the wall's response to a relative 1e-6 of the load.

``profile``: the 200-block stack-bonded wall of ``bench_scale.py`` (10 kg at 5 m, 0.25 s) and the 10-drum square
column (250 kg at 10 m, 1 s), each step recorded (iterations summed over the islands, the largest island's,
line-search evaluations, Hessian updates, contacts) by stepping MuJoCo one step at a time under the engine's own
loop; timers over the run after settling. ``ensemble``: the wall under loads x (1 + 1e-6 u), u evenly spread over
[-1, 1] (as :func:`blastscale.analysis.ensemble.ensemble_compare`), with the default settings and with
``--variant`` changes, and how far apart the members' top histories and largest displacements are.

``variants``: CPU seconds (best of 3) of solver variants, some only from the first arrival or after the load
(:func:`phased`), and of the bodies in the structure's own order instead of reverse Cuthill-McKee's. ``settled``: the wall's contacts and islands after settling, its length x (1 + 1e-6 u).

Not a test: ``python benchmarks/bench_walls_newton.py profile|ensemble|variants|settled [--members 5]
[--geometry] [--eps 1e-6] [--tolerances 1e-8,...] [--engaged 1e-5] [--settle-tolerance 1e-8]
[--settled-as-before] [--duration 0.25]`` (prints JSON).
"""

from __future__ import annotations

import json
import os
import sys
import time
import warnings
from dataclasses import replace

import mujoco
import numpy as np

import blastscale.sim3d.model as model_module
from blastscale.blast import blast_parameters
from blastscale.sim3d import make_load, simulate_structure
from blastscale.sim3d.contact import default_contact
from blastscale.sim3d.loads import PerturbedLoad
from blastscale.sim3d.reference import reference_factors
from blastscale.structures import MultiDrumColumn, wall

T = mujoco.mjtTimer
TIMERS = {
    "constraint": T.mjTIMER_CONSTRAINT,
    "collision": T.mjTIMER_POS_COLLISION,
    "make_constraint": T.mjTIMER_POS_MAKE,
    "project": T.mjTIMER_POS_PROJECT,
    "kinematics": T.mjTIMER_POS_KINEMATICS,
    "inertia": T.mjTIMER_POS_INERTIA,
    "velocity": T.mjTIMER_VELOCITY,
    "advance": T.mjTIMER_ADVANCE,
}


def _cpu() -> float:
    return time.process_time()  # user + sys of this process, ns resolution (os.times ticks at 10 ms)


def _wall(length_factor: float = 1.0):
    return wall(
        length_m=5.0 * length_factor, height_m=2.5, thickness_m=0.5, courses=20, units_per_course=10, bond="stack"
    )


def cases():
    """(name, structure, load, duration [s]) of the benchmark's blast case."""
    w = _wall()
    col = MultiDrumColumn("square")
    return [
        ("wall_200", w, make_load("A", w, blast_parameters(10.0, 5.0)), 0.25),
        ("column", col, make_load("A", col, blast_parameters(250.0, 10.0)), 1.0),
    ]


def _apply(m, d, opt) -> None:
    """Set MuJoCo options on the model (``disable`` / ``enable``: flags or-ed in; others: ``m.opt`` attributes);
    ``opt`` may be a callable ``opt(m, d)`` returning them (options by phase of the run)."""
    for k, v in (opt(m, d) if callable(opt) else opt).items():
        if k == "disable":
            m.opt.disableflags |= v
        elif k == "enable":
            m.opt.enableflags |= v
        else:
            setattr(m.opt, k, v)


def phased(settle: dict, run: dict, after_load: dict | None = None, load_end: float = 0.0):
    """Options by phase: ``settle`` for the settling call (the first step call on a new MjData), ``run`` from the
    first arrival, ``after_load`` once the reference time passes ``load_end`` [s] (default ``run``)."""
    seen = {}

    def opt(m, d):
        if seen.get("d") is not d:
            seen["d"] = d
            return settle
        return after_load if after_load is not None and d.time >= load_end else run

    return opt


def _with_options(orig, opt):
    def step(m, d, nstep=1):
        _apply(m, d, opt)
        orig(m, d, nstep)

    return step


def timed(structure, load, duration: float, contact=None, opt=None, repeat: int = 3) -> dict:
    """Best CPU seconds (user + sys) of ``repeat`` runs with MuJoCo options ``opt`` set on the engine's model
    (:func:`_apply`), the outcome and the top point's largest x displacement."""
    orig = mujoco.mj_step
    mujoco.mj_step = _with_options(orig, opt or {})
    best = np.inf
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            for _ in range(repeat):
                t0 = _cpu()
                r = simulate_structure(structure, load, duration, contact=contact, record_every=20)
                best = min(best, _cpu() - t0)
    finally:
        mujoco.mj_step = orig
    s = r.summary()
    return {
        "cpu_s": best,
        "collapsed": bool(s["collapsed"]),
        "fallen_blocks": s.get("fallen_blocks"),
        "top_max_x_m": float(np.max(_top(r))),
    }


def profile(structure, load, duration: float, contact=None, opt: dict | None = None) -> dict:
    """Per-step solver statistics of one run (the engine's loop, MuJoCo stepped one step at a time)."""
    rows, snap, opt = [], {}, opt or {}
    orig = mujoco.mj_step
    _, b = reference_factors(structure, 9.81)
    end = (load.end_time - load.first_arrival) * b  # reference time at which the load is over

    def step(m, d, nstep=1):
        _apply(m, d, opt)
        for _ in range(int(nstep)):
            orig(m, d)
            ni = int(d.nisland) if m.opt.disableflags & mujoco.mjtDisableBit.mjDSBL_ISLAND == 0 else 1
            ni = max(1, min(ni, len(d.solver_niter)))
            it = [int(d.solver_niter[i]) for i in range(ni)]
            nsolv = len(d.solver) // len(d.solver_niter)
            neval = nupd = 0
            for i in range(ni):
                for k in range(it[i]):
                    s = d.solver[i * nsolv + min(k, nsolv - 1)]
                    neval += int(s.neval)
                    nupd += int(s.nupdate)
            rows.append((d.time, sum(it), max(it), ni, neval, nupd, int(d.ncon), int(d.nefc), m.opt.timestep))
            snap["d"] = d

    mujoco.mj_step = step
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            simulate_structure(structure, load, duration, contact=contact, record_every=20)
    finally:
        mujoco.mj_step = orig
    a = np.array(rows)
    # the run starts where the time goes back to 0 after settling
    start = int(np.nonzero(np.diff(a[:, 0]) < 0)[0][-1]) + 1 if np.any(np.diff(a[:, 0]) < 0) else 0
    run = a[start:]
    loaded = run[:, 0] <= end + 1e-12
    d = snap["d"]
    step_t = d.timer[T.mjTIMER_STEP].duration or 1.0

    def stats(x):
        if not len(x):
            return None
        return {
            "steps": len(x),
            "iterations_per_step": float(x[:, 1].mean()),
            "largest_island_iterations_per_step": float(x[:, 2].mean()),
            "islands_per_step": float(x[:, 3].mean()),
            "line_search_evaluations_per_step": float(x[:, 4].mean()),
            "hessian_updates_per_step": float(x[:, 5].mean()),
            "contacts": float(x[:, 6].mean()),
            "constraint_rows": float(x[:, 7].mean()),
            "steps_at_iteration_cap": int(np.sum(x[:, 2] >= 100)),
        }

    return {
        "during_load": stats(run[loaded]),
        "after_load": stats(run[~loaded]),
        "whole_run": stats(run),
        "timer_share_incl_settling": {k: d.timer[v].duration / step_t for k, v in TIMERS.items()},
    }


def _top(r):
    ds = r.dataset
    return ds["point_displacement"].sel(point=ds.attrs["top_point"], component="x").values


def _largest_block_displacement(r):
    ds = r.dataset
    x = ds["point_displacement"].sel(component="x").values
    return float(np.max(np.abs(x)))


def head_joints_engaged(margin: float):
    """A step function that, before the first step of each run, gives the head joints (interface pairs of two bodies
    at one height) MuJoCo's ``margin`` = ``gap`` = ``margin`` [m, reference units], meant to list their contacts
    within that distance without force. An experiment, not the engine's rule, and not neutral: MuJoCo's box collider
    then reports other contacts, and the settled 200-block wall's head joints carry a lateral force of 63-75 % of
    its weight (docs/performance.md)."""
    orig, seen = mujoco.mj_step, {}

    def step(m, d, nstep=1):
        if seen.get("d") is not d:
            seen["d"] = d
            z = m.body_pos[:, 2]
            b1, b2 = m.geom_bodyid[m.pair_geom1], m.geom_bodyid[m.pair_geom2]
            head = (b1 > 0) & (b2 > 0) & (np.abs(z[b1] - z[b2]) < 1e-9)
            m.pair_margin[head] = margin
            m.pair_gap[head] = margin
        orig(m, d, nstep)

    return step


def ensemble(
    structure,
    load,
    duration: float,
    members: int,
    changes: dict,
    eps: float = 1e-6,
    geometry: bool = False,
    engaged: float = 0.0,
    opt=None,
) -> dict:
    """Members under load x (1 + eps u), u evenly over [-1, 1], with the default settings + ``changes``; with
    ``geometry`` the 200-block wall's length x (1 + eps u) instead (every block eps longer, the load the same); with
    ``engaged`` > 0 the head joints engaged within that distance (:func:`head_joints_engaged`); ``opt``: MuJoCo
    options set before every step (:func:`_apply`, e.g. :func:`phased`)."""
    tops, peaks, outs, cpu = [], [], [], []
    orig = mujoco.mj_step
    for u in np.linspace(-1.0, 1.0, members):
        s = _wall(1.0 + eps * u) if geometry else structure
        ld = load if geometry else PerturbedLoad(load, 1.0 + eps * u)
        if "tolerance" in changes:  # throughout: the settling too
            changes = {"settle_tolerance": changes["tolerance"], **changes}
        contact = replace(default_contact(s), **changes) if changes else None
        inner = head_joints_engaged(engaged) if engaged > 0.0 else orig
        mujoco.mj_step = inner if opt is None else _with_options(inner, opt)
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                t0 = _cpu()
                r = simulate_structure(s, ld, duration, contact=contact, record_every=20)
                cpu.append(_cpu() - t0)
        finally:
            mujoco.mj_step = orig
        s = r.summary()
        tops.append(_top(r))
        peaks.append(_largest_block_displacement(r))
        outs.append((bool(s["collapsed"]), s.get("fallen_blocks")))
    tops = np.array(tops)
    peak = float(np.max(np.abs(tops)))
    return {
        "changes": changes,
        "perturbation": eps,
        "members": members,
        "cpu_s": cpu,
        "outcomes": outs,
        "top_histories": tops,
        "top_max_x_m": [float(np.max(t)) for t in tops],
        "largest_point_x_m": peaks,
        "spread_top_history_over_peak": float(np.max(tops.max(axis=0) - tops.min(axis=0)) / peak),
        "spread_top_max_x_relative": float((np.max(tops.max(axis=1)) - np.min(tops.max(axis=1))) / peak),
    }


def _vs(ref: dict, other: dict) -> dict:
    """How far ``other``'s members are from ``ref``'s envelope: the largest distance of a member's top history
    outside the envelope, over the reference peak, and the change of the members' mean top maximum."""
    lo, hi = ref["top_histories"].min(axis=0), ref["top_histories"].max(axis=0)
    peak = float(np.max(np.abs(ref["top_histories"])))
    out = np.maximum(other["top_histories"] - hi, lo - other["top_histories"]).clip(min=0.0)
    diff = np.abs(other["top_histories"] - ref["top_histories"])  # member by member (same load factor)
    return {
        "outside_reference_envelope_over_peak": float(out.max() / peak),
        "member_by_member_top_history_over_peak": float(diff.max() / peak),
        "mean_top_max_x_change": float(np.mean(other["top_max_x_m"]) / np.mean(ref["top_max_x_m"]) - 1.0),
    }


def variants(load_end: float) -> dict:
    """name -> MuJoCo options (a dict, or :func:`phased` options) of the variants measured on the wall: each against
    the default before issue #28's deliverable 4 (settling at the run's tolerance, 1e-10) but for the engine's
    default (an assembly settles at 1e-8) and tolerance 1e-8 throughout."""
    dis = mujoco.mjtDisableBit
    tol, before = {"tolerance": 1e-8}, {"tolerance": 1e-10}

    def both(opt: dict):  # settling as before, ``opt`` throughout
        return phased({**before, **opt}, opt)

    return {
        "default": phased(before, {}),
        "the engine's default (settling at 1e-8)": {},
        "tolerance 1e-8": tol,
        "tolerance 1e-8 while settling only": phased(tol, before),
        "tolerance 1e-8 from the first arrival": phased(before, tol),
        "tolerance 1e-8 after the load": phased(before, {}, tol, load_end),
        "ls_iterations 10": both({"ls_iterations": 10}),
        "ls_iterations 10 from the first arrival": phased(before, {"ls_iterations": 10}),
        "ls_iterations 20": both({"ls_iterations": 20}),
        "ls_tolerance 0.1": both({"ls_tolerance": 0.1}),
        "warm start off": both({"disable": int(dis.mjDSBL_WARMSTART)}),
    }


def _lateral_force_share(m, d) -> float:
    """The normal forces of the contacts with a horizontal normal (head joints) over the structure's weight [-]."""
    f, lateral = np.zeros(6), 0.0
    for i in range(d.ncon):
        if abs(d.contact.frame[i, 2]) < 0.5:
            mujoco.mj_contactForce(m, d, i, f)
            lateral += f[0]
    return lateral / float(np.sum(m.body_mass) * np.linalg.norm(m.opt.gravity))


def settled(tolerances=(1e-10, 1e-8), eps: float = 1e-6, members: int = 5, engaged: float = 1e-5) -> dict:
    """The wall after settling (before the first arrival), its length x (1 + eps u): contacts, contacts with a
    horizontal normal (head joints), islands, the head joints' normal force over the weight, for each solver
    tolerance and with the head joints engaged (:func:`head_joints_engaged`)."""
    out, orig = {}, mujoco.mj_step
    for tol in (*tolerances, "engaged"):
        rows = []
        for u in np.linspace(-1.0, 1.0, members):
            s, first = _wall(1.0 + eps * u), []
            inner = orig  # engaged: settled at 1e-10, as the tolerances' rows
            if tol == "engaged":
                inner = _with_options(head_joints_engaged(engaged), phased({"tolerance": 1e-10}, {}))

            def step(m, d, nstep=1):
                inner(m, d, nstep)
                if not first:
                    head = int(np.sum(np.abs(d.contact.frame[: d.ncon, 2]) < 0.5))
                    first.append((int(d.ncon), head, int(d.nisland), _lateral_force_share(m, d)))

            mujoco.mj_step = step
            try:
                ld = make_load("A", s, blast_parameters(10.0, 5.0))
                c = None if tol == "engaged" else replace(default_contact(s), tolerance=tol, settle_tolerance=tol)
                simulate_structure(s, ld, 5e-4, contact=c)
            finally:
                mujoco.mj_step = orig
            keys = ("contacts", "head_joint", "islands", "head_joint_force_over_weight")
            rows.append({"length_factor_minus_1": eps * u, **dict(zip(keys, first[0]))})
        out[f"tolerance {tol:g}" if tol != "engaged" else f"head joints engaged within {engaged:g} m"] = rows
    return out


def main() -> None:
    args = sys.argv[1:]
    dur = float(args[args.index("--duration") + 1]) if "--duration" in args else None
    out = {"load_average": os.getloadavg()}
    if "profile" in args:
        for name, s, ld, d in cases():
            t0 = _cpu()
            out[name] = profile(s, ld, dur or d)
            out[name]["cpu_s_instrumented"] = _cpu() - t0
            if name == "wall_200":
                out["wall_200 settled at 1e-10 (before)"] = profile(
                    s, ld, dur or d, opt=phased({"tolerance": 1e-10}, {})
                )
    if "ensemble" in args:
        n = int(args[args.index("--members") + 1]) if "--members" in args else 5
        tol = [float(x) for x in args[args.index("--tolerances") + 1].split(",")] if "--tolerances" in args else []
        name, s, ld, d = cases()[0]
        geo = "--geometry" in args
        eps = float(args[args.index("--eps") + 1]) if "--eps" in args else 1e-6
        before = phased({"tolerance": 1e-10}, {}) if "--settled-as-before" in args else None
        ref = ensemble(s, ld, dur or d, n, {}, eps, geo, opt=before)
        out["default" if before is None else "default before (settling at 1e-10)"] = ref
        for t in tol:
            e = ensemble(s, ld, dur or d, n, {"tolerance": t}, eps, geo)
            e["vs_default"] = _vs(ref, e)
            out[f"tolerance {t:g}"] = e
        if "--settle-tolerance" in args:
            t = float(args[args.index("--settle-tolerance") + 1])
            e = ensemble(s, ld, dur or d, n, {}, eps, geo, opt=phased({"tolerance": t}, {"tolerance": 1e-10}))
            e["vs_default"] = _vs(ref, e)
            out[f"tolerance {t:g} while settling only"] = e
        if "--engaged" in args:
            margin = float(args[args.index("--engaged") + 1])
            e = ensemble(s, ld, dur or d, n, {}, eps, geo, margin, opt=before)
            e["vs_default"] = _vs(ref, e)
            out[f"head joints engaged within {margin:g} m"] = e
        for e in out.values():
            if isinstance(e, dict) and "top_histories" in e:
                e.pop("top_histories")
    if "variants" in args:
        name, s, ld, d = cases()[0]
        _, b = reference_factors(s, 9.81)
        for k, opt in variants((ld.end_time - ld.first_arrival) * b).items():
            out[k] = {**timed(s, ld, dur or d, None, opt), "load_average": os.getloadavg()[0]}
            out[k]["top_max_x_change"] = out[k]["top_max_x_m"] / out["default"]["top_max_x_m"] - 1.0
            out[k]["speedup"] = out["default"]["cpu_s"] / out[k]["cpu_s"]
            print(k, json.dumps(out[k]), file=sys.stderr, flush=True)
        # the bodies in the structure's own order (course by course) instead of reverse Cuthill-McKee's
        rcm = model_module.body_order
        model_module.body_order = lambda interfaces, n: np.arange(n)
        try:
            opt = phased({"tolerance": 1e-10}, {})
            out["natural body order"] = {**timed(s, ld, dur or d, None, opt), "load_average": os.getloadavg()[0]}
        finally:
            model_module.body_order = rcm
        r = out["natural body order"]
        r["top_max_x_change"] = r["top_max_x_m"] / out["default"]["top_max_x_m"] - 1.0
        r["speedup"] = out["default"]["cpu_s"] / r["cpu_s"]
        print("natural body order", json.dumps(r), file=sys.stderr, flush=True)
    if "settled" in args:
        out["settled"] = settled()
    out["load_average_end"] = os.getloadavg()
    print(json.dumps(out, indent=1, default=str))


if __name__ == "__main__":
    main()
