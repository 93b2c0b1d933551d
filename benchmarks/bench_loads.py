"""Benchmark and findings of the blast load Methods A, B and C on the paper's columns (issue 9).

Usage::

    python benchmarks/bench_loads.py [--json] [--duration 3] [--repeat 1]
    python benchmarks/bench_loads.py --paper-cases [--duration 8] [--incidence ufc closed-form] [--cases 0 1]
    python benchmarks/bench_loads.py --correction [--duration 8]

Speed: simulated seconds per wall second of the 10-drum square and circular columns (the
paper's, Kingery-Bulmash, Friedlander, 250 kg at 10 m) under Methods A, B and C, and the ratio
of each to Method A (the budget of issue 9: C <= 3 x A per simulated second).

``--paper-cases``: the paper's cases at lambda = 1/100 (general law, gamma = 1): square 250 / 500 kg
and circular 200 / 400 kg under Method B, square 250 / 500 / 750 / 1000 kg under Method C, with each
incidence model; prototype and up-scaled model outcomes, top first peaks, the similarity figures
and the arrival-time spreads, one JSON line per case (docs/face_loads.md reports them).

``--ensemble``: the circular columns under Method B (200 and 400 kg) as ensembles of 4 members per
system (load perturbed by up to 1e-6): first peaks with their spread, collapse probabilities.

``--correction``: the load-time corrections of docs/face_loads.md tested on both columns
(Method B, square 250 / 500 kg, circular 200 / 400 kg): the general-law model as designed, re-timed
(the prototype's arrival spread in model time), re-weighted (the prototype's distribution of
impulse over the faces) and both; top first peaks and differences against the prototype.
"""

from __future__ import annotations

import argparse
import json
import math
import platform
import time
import warnings

import numpy as np

from blastscale.blast import blast_parameters
from blastscale.sim3d.load_methods import arrival_spread_similarity, make_load
from blastscale.sim3d.simulate import simulate_structure
from blastscale.similitude import design_model
from blastscale.structures import MultiDrumColumn

STANDOFF = 10.0  # m, the paper's columns
SCALE = 0.01  # lambda = 1/100


def speed(duration: float = 3.0, repeat: int = 1, charge: float = 250.0) -> dict:
    """Best-of-``repeat`` simulated s per wall s for A, B, C on both columns."""
    out = {}
    for section in ("square", "circular"):
        col = MultiDrumColumn(section=section)
        res = {}
        for method in ("A", "B", "C"):
            best = math.inf
            for _ in range(repeat):
                load = make_load(method, col, blast_parameters(charge, STANDOFF))
                t0 = time.perf_counter()
                simulate_structure(col, load, duration)
                best = min(best, time.perf_counter() - t0)
            res[method] = {"simulated_s": duration, "wall_s": best, "simulated_s_per_wall_s": duration / best}
            res[method]["load_only_wall_s_per_simulated_s"] = load_only(col, load, duration)
        for method in ("B", "C"):
            res[method]["cost_vs_A"] = res[method]["wall_s"] / res["A"]["wall_s"]
        out[f"column_{section}"] = res
    return out


def load_only(structure, load, duration: float, dt: float = 2.5e-4) -> float:
    """Wall seconds the load strategy alone costs per simulated second (rest poses, the engine's
    0.25 ms step from the first arrival, called while the step starts before ``end_time`` as the
    engine does), independent of the dynamics it drives."""
    nb = len(structure.bodies)
    pos = np.array([b.com for b in structure.bodies])
    rot = np.broadcast_to(np.eye(3), (nb, 3, 3))
    t = load.first_arrival + dt * np.arange(int(duration / dt) + 1)
    t0 = time.perf_counter()
    for a, b in zip(t[:-1], t[1:]):
        if a > load.end_time:
            break
        load.step_wrenches(a, b, pos, rot)
    return (time.perf_counter() - t0) / duration


#: The paper's cases (section, charge [kg], method) at lambda = 1/100 and 10 m.
PAPER_CASES = (
    ("square", 250.0, "B"),
    ("square", 500.0, "B"),
    ("circular", 200.0, "B"),
    ("circular", 400.0, "B"),
    ("square", 250.0, "C"),
    ("square", 500.0, "C"),
    ("square", 750.0, "C"),
    ("square", 1000.0, "C"),
)


def paper_case(section: str, charge: float, method: str, incidence: str, duration: float = 8.0) -> dict:
    """One prototype vs model comparison (general law, lambda = 1/100, gamma = 1) as a flat dict."""
    import blastscale.sim3d as sim3d
    from blastscale.analysis.structure3d import compare_structure3d
    from blastscale.analysis.systems import Settings3D, Systems3D

    if not hasattr(sim3d, "simulate_structure"):  # the engine's export lands with issue 8
        sim3d.simulate_structure = simulate_structure
    col = MultiDrumColumn(section=section)
    design = design_model(charge, STANDOFF, SCALE)
    t0 = time.perf_counter()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        cmp = compare_structure3d(
            Systems3D.of_design(design, col, duration=duration), Settings3D(load=method, incidence=incidence)
        )
    s = cmp.to_dict()
    sim = s["similarity"]  # with the arrival spreads of the two runs' loads
    top = sim["top_point"]
    return {
        "section": section,
        "charge_kg": charge,
        "method": method,
        "incidence": incidence,
        "duration_s": duration,
        "prototype_collapsed": s["prototype"]["collapsed"],
        "model_collapsed": s["model"]["collapsed"],
        "prototype_max_top_m": s["prototype"]["max_top_displacement_m"],
        "model_max_top_m": s["model"]["max_top_displacement_m"],
        "top_first_peak_prototype_m": sim["points"][top]["first_peak_prototype_m"],
        "top_first_peak_model_m": sim["points"][top]["first_peak_model_m"],
        "top_first_peak_ratio": sim["top_first_peak_ratio"],
        "max_abs_top_displacement_diff_rel_peak": sim["max_abs_top_displacement_diff_rel_peak"],
        "outcomes_agree": sim["outcomes_agree"],
        "arrival_spread_prototype_s": sim["arrival_spread_prototype_s"],
        "arrival_spread_model_upscaled_s": sim["arrival_spread_model_upscaled_s"],
        "prototype_impulse_x_Ns": s["prototype"]["delivered_impulse_Ns"][0],
        "model_impulse_x_upscaled_Ns": s["model"]["delivered_impulse_Ns"][0],
        "wall_s": time.perf_counter() - t0,
    }


def correction(section: str, charge: float, duration: float = 8.0, incidence: str = "ufc") -> dict:
    """Method B on a column: prototype, the general-law model as designed, and the model re-timed."""
    from blastscale.analysis.compare import compare_responses, upscale_dataset

    col = MultiDrumColumn(section=section)
    d = design_model(charge, STANDOFF, SCALE)
    f = d.factors
    mcol = col.scaled(f)
    lp = make_load("B", col, d.prototype, incidence=incidence)
    proto = simulate_structure(col, lp, duration)
    lm = make_load("B", mcol, d.specimen, incidence=incidence)
    sp = arrival_spread_similarity(lp, lm, f)
    stretch = sp["arrival_spread_prototype_s"] / sp["arrival_spread_model_upscaled_s"]
    out = {"section": section, "charge_kg": charge, "incidence": incidence, "stretch": stretch, **sp}
    weights = f.impulse * lp.rest_loads.impulse / lm.rest_loads.impulse
    out["impulse_weights"] = weights.tolist()
    # load-time corrections (FaceLoadStrategy.corrected): re-timed = the prototype's arrival spread in
    # model time (a delay per face); re-weighted = the prototype's distribution of impulse over the faces
    variants = (
        ("as_designed", lm),
        ("retimed", lm.corrected(stretch)),
        ("reweighted", lm.corrected(1.0, weights)),
        ("retimed_reweighted", lm.corrected(stretch, weights)),
    )
    for name, load in variants:
        mod = simulate_structure(mcol, load, duration * f.time)
        cmp = compare_responses(proto.dataset, upscale_dataset(mod.dataset, f), variables=("point_displacement",))
        top = str(proto.dataset["point"].values[-1])
        v = cmp["variables"]["point_displacement"][top]
        out[name] = {
            "top_first_peak_prototype_m": v["first_peak_prototype"],
            "top_first_peak_model_m": v["first_peak_model"],
            "top_first_peak_ratio": v["first_peak_ratio"],
            "max_abs_top_diff_rel_peak": v["max_abs_diff_rel_peak"],
            "prototype_collapsed": proto.summary()["collapsed"],
            "model_collapsed": mod.summary()["collapsed"],
            "model_impulse_x_upscaled_Ns": float(mod.summary()["delivered_impulse_Ns"][0] / f.momentum),
            "prototype_impulse_x_Ns": float(proto.summary()["delivered_impulse_Ns"][0]),
        }
    return out


def ensembles(n: int = 4, duration: float = 8.0, incidence: str = "ufc") -> list:
    """Circular columns under Method B (200 and 400 kg), ``n`` members per system with the load
    perturbed by up to 1e-6: first peaks with their spreads and collapse probabilities."""
    from blastscale.analysis.ensemble import ensemble_compare
    from blastscale.analysis.systems import Settings3D, Systems3D

    out = []
    for charge in (200.0, 400.0):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            e = ensemble_compare(
                Systems3D.of_design(
                    design_model(charge, STANDOFF, SCALE), MultiDrumColumn(section="circular"), duration=duration
                ),
                Settings3D(load="B", incidence=incidence),
                n=n,
            )
        s = e.to_dict()
        top = list(s["points"])[-1]
        out.append(
            {
                "charge_kg": charge,
                "n": n,
                "collapse_probability_prototype": s["collapse_probability_prototype"],
                "collapse_probability_model": s["collapse_probability_model"],
                "top": s["points"][top],
            }
        )
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--json", action="store_true")
    ap.add_argument("--duration", type=float, default=None)
    ap.add_argument("--repeat", type=int, default=1)
    ap.add_argument("--paper-cases", action="store_true")
    ap.add_argument("--incidence", nargs="+", default=["ufc", "closed-form"])
    ap.add_argument("--cases", nargs="*", type=int, default=None, help="indices into PAPER_CASES")
    ap.add_argument("--correction", action="store_true")
    ap.add_argument("--ensemble", action="store_true", help="circular columns, Method B, 4 perturbed members")
    args = ap.parse_args()
    if args.ensemble:
        for row in ensembles(duration=args.duration or 8.0):
            print(json.dumps(row), flush=True)
        return
    if args.correction:
        for section, charge in (("square", 250.0), ("square", 500.0), ("circular", 200.0), ("circular", 400.0)):
            print(json.dumps(correction(section, charge, args.duration or 8.0)), flush=True)
        return
    if args.paper_cases:
        idx = range(len(PAPER_CASES)) if args.cases is None else args.cases
        for inc in args.incidence:
            for i in idx:
                print(json.dumps(paper_case(*PAPER_CASES[i], inc, args.duration or 8.0)), flush=True)
        return
    res = {"speed": speed(args.duration or 3.0, args.repeat), "python": platform.python_version()}
    if args.json:
        print(json.dumps(res, indent=1))
        return
    for col, r in res["speed"].items():
        for m, v in r.items():
            extra = f", {v['cost_vs_A']:.2f} x A" if "cost_vs_A" in v else ""
            print(f"{col:16s} Method {m}: {v['simulated_s_per_wall_s']:.3f} simulated s per wall s{extra}")


if __name__ == "__main__":
    main()
