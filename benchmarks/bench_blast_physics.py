"""Blast physics beyond the paper and what each effect does to similarity (issue 17, docs/blast_physics.md).

Usage::

    python benchmarks/bench_blast_physics.py --bursts          # surface vs free-air charge ratio over Z
    python benchmarks/bench_blast_physics.py --clearing        # clearing over Z, UFC vs 3S/U, the stated case
    python benchmarks/bench_blast_physics.py --stability       # critical charge and capacity with/without the negative phase
    python benchmarks/bench_blast_physics.py --block           # the paper's block, planar, lambda 1/20, 1/100, 1/200
    python benchmarks/bench_blast_physics.py --column [--duration 3] [--methods A B]   # the square column, 3D
    python benchmarks/bench_blast_physics.py --correction      # the clearing-corrected specimen charge and its cost
    python benchmarks/bench_blast_physics.py --correction-run  # ... and its first-peak ratio (column, 3D)

Each prints one JSON object per line (the numbers of docs/blast_physics.md). Every similarity case is
one Study (the library's one door): the paper's load, then clearing, the negative phase and a free-air
specimen shot (charge on a stand at the specimen's mid-height), each opted in through the scenario.
"""

from __future__ import annotations

import argparse
import json
import math
import time
import warnings

import numpy as np

from blastscale.blast import blast_parameters
from blastscale.blast.air import shock_velocity
from blastscale.blast.bursts import EQUIVALENCE_QUANTITIES, equivalent_free_air_charge_ratio
from blastscale.blast.load_model import LoadModel, front_face_clearing
from blastscale.rocking import RockingSystem, capacity_curve, critical_charge
from blastscale.scenario import Scenario
from blastscale.similitude import design_model
from blastscale.similitude.effects import clearing_corrected_charge, front_face
from blastscale.structures import MultiDrumColumn, RectangularBlock
from blastscale.study import Study

SCALES = (1 / 20, 1 / 100, 1 / 200)
BLOCK = RectangularBlock.from_slenderness(10.0, math.radians(15.0))
NEG = LoadModel(negative_phase=True)


def emit(obj: dict) -> None:
    print(json.dumps(obj, default=float), flush=True)


def bursts() -> None:
    """W_free / W_surface giving the same quantity at the same distance, over Z (measured, not 1.8)."""
    z = np.array([0.2, 0.3, 0.5, 0.7, 1.0, 1.5, 2.0, 3.0, 5.0, 7.0, 10.0, 20.0, 38.0])
    emit(
        {
            "section": "bursts",
            "Z": z.tolist(),
            **{q: np.round(equivalent_free_air_charge_ratio(z, q), 3).tolist() for q in EQUIVALENCE_QUANTITIES},
        }
    )


def clearing() -> None:
    """Cleared / uncleared impulse over Z for the paper's fronts (block 1 m x 10 m; square column
    1.65 m x 10 m) at full scale, the 1/100 specimen of the column at the same Z (Hopkinson-Cranz
    geometry), UFC's t_c against Glasstone & Dolan's 3 S / U, and the stated case of the tests."""
    for name, (w, h), W in (("block", (1.0, 10.0), 100.0), ("column", (1.65, 10.0), 250.0)):
        for lam in (1.0, 0.01):
            rows = []
            for z in (0.5, 1.0, 1.6, 2.5, 3.5, 5.0, 7.0, 10.0, 15.0):
                Wl = W * lam**3
                bp = blast_parameters(Wl, z * Wl ** (1 / 3))
                c = front_face_clearing(bp, LoadModel(True, w * lam, h * lam))
                u = float(shock_velocity(bp.incident_pressure))
                rows.append(
                    {
                        "Z": z,
                        "t_c_over_t_o": c.clearing_time / bp.positive_duration,
                        "cleared_fraction": c.impulse / c.uncleared_impulse,
                        "t_c_ufc_over_3S_over_U": c.clearing_time / (3.0 * c.clearing_distance / u),
                    }
                )
            emit({"section": "clearing", "face": name, "scale": lam, "rows": rows})
    bp = blast_parameters(1000.0, 70.0)
    c = front_face_clearing(bp, LoadModel(True, 10.0, 4.0))
    emit(
        {
            "section": "clearing_stated_case",
            "charge_kg": 1000.0,
            "standoff_m": 70.0,
            "face": [10.0, 4.0],
            **c.to_dict(),
            "t_c_glasstone_s": 3 * 4.0 / float(shock_velocity(bp.incident_pressure)),
        }
    )


def stability() -> None:
    """The paper's claim, in numbers: critical charge and capacity curve of the 10 m block with and
    without the negative phase."""
    sysm = RockingSystem.from_block(BLOCK)
    for model in ("kingery-bulmash", "masi2021"):
        a = critical_charge(sysm, 2.0, blast_model=model).charge_kg
        b = critical_charge(sysm, 2.0, blast_model=model, load_model=NEG).charge_kg
        emit(
            {
                "section": "stability",
                "blast_model": model,
                "standoff_m": 2.0,
                "critical_charge_kg": a,
                "critical_charge_negative_phase_kg": b,
                "ratio": b / a,
            }
        )
    R = np.array([1.0, 1.5, 2.0, 3.0, 4.0, 6.0, 8.0, 10.0])
    t0 = time.perf_counter()
    c0 = capacity_curve(sysm, R).critical_charge_kg
    c1 = capacity_curve(sysm, R, load_model=NEG).critical_charge_kg
    emit(
        {
            "section": "capacity",
            "standoff_m": R.tolist(),
            "critical_charge_kg": c0.tolist(),
            "critical_charge_negative_phase_kg": c1.tolist(),
            "ratio": (c1 / c0).tolist(),
            "seconds": time.perf_counter() - t0,
        }
    )


VARIANTS = {
    "paper": {},
    "clearing": {"blast.clearing": True},
    "negative phase": {"blast.negative_phase": True},
    "free-air specimen": {"scale.specimen_burst": "free-air"},
    "negative phase, Hopkinson-Cranz": {"blast.negative_phase": True, "scale.law": "hopkinson-cranz"},
    "paper, Hopkinson-Cranz": {"scale.law": "hopkinson-cranz"},
}


def _study(base: dict, values: dict) -> dict:
    sc = Scenario.from_dict(base).with_values(values)
    if values.get("scale.specimen_burst") == "free-air":  # on a stand at the specimen's mid-height
        h = sc.structure.height_m * sc.scale.length
        sc = sc.with_values({"scale.specimen_charge_height_m": 0.5 * h})
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        t0 = time.perf_counter()
        r = Study(sc).run()
    s = r.summary()
    return s, time.perf_counter() - t0


def block(charges=(50.0, 100.0), duration: float = 5.0, variants=tuple(VARIANTS)) -> None:
    """The paper's block at 2 m, planar (first-peak ratio, outcomes) for each variant and scale."""
    for W in charges:
        for lam in SCALES:
            for name, vals in ((n, VARIANTS[n]) for n in variants):
                base = {
                    "structure": {"kind": "block", "height_m": 10.0, "alpha_deg": 15.0, "density_kg_m3": 2000.0},
                    "blast": {"charge_kg": W, "standoff_m": 2.0, "blast_model": "kingery-bulmash"},
                    "scale": {"length": lam},
                    "simulation": {"engine": "planar", "duration_s": duration, "critical_charge": False},
                }
                s, dt = _study(base, vals)
                sim = s["planar"]["similarity"]
                emit(
                    {
                        "section": "block",
                        "charge_kg": W,
                        "scale": lam,
                        "variant": name,
                        "first_peak_ratio": sim["first_peak_ratio"],
                        "prototype_collapsed": s["planar"]["prototype"]["collapsed"],
                        "model_collapsed": s["planar"]["model"]["collapsed"],
                        "outcomes_agree": sim["outcomes_agree"],
                        "notes": s["design"].get("notes", []),
                        "seconds": dt,
                    }
                )


def column(
    charge: float = 250.0, standoff: float = 10.0, duration: float = 3.0, methods=("A", "B"), variants=tuple(VARIANTS)
) -> None:
    """The paper's square column, 3D (top first-peak ratio, outcomes) for each variant and scale."""
    for method in methods:
        for lam in SCALES:
            for name, vals in ((n, VARIANTS[n]) for n in variants):
                base = {
                    "structure": {"kind": "column", "section": "square"},
                    "blast": {
                        "charge_kg": charge,
                        "standoff_m": standoff,
                        "blast_model": "kingery-bulmash",
                        "load": method,
                    },
                    "scale": {"length": lam},
                    "simulation": {"engine": "3d", "duration_s": duration, "critical_charge": False},
                }
                s, dt = _study(base, vals)
                sim = s["3d"]["similarity"]
                emit(
                    {
                        "section": "column",
                        "charge_kg": charge,
                        "standoff_m": standoff,
                        "method": method,
                        "scale": lam,
                        "variant": name,
                        "top_first_peak_ratio": sim["top_first_peak_ratio"],
                        "prototype_collapsed": s["3d"]["prototype"]["collapsed"],
                        "model_collapsed": s["3d"]["model"]["collapsed"],
                        "notes": s["design"].get("notes", []),
                        "seconds": dt,
                    }
                )


def correction() -> None:
    """Can the general law be corrected for clearing? The specimen charge whose cleared impulse scales
    (at the design's stand-off), for the column's front at 30 m (where clearing acts) and at 10 m, and
    what it costs (the charge, the scaled distance, the peak and the duration it moves)."""
    col = MultiDrumColumn(section="square")
    w, h = front_face(col)
    lm = LoadModel(True, w, h)
    for W, R in ((250.0, 30.0), (1000.0, 40.0), (250.0, 10.0)):
        for lam in SCALES:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                d = design_model(W, R, lam, load_model=lm, face=(w, h))
                c = d.effects["clearing"]
                try:
                    fix = clearing_corrected_charge(d, lm)
                except Exception as exc:  # noqa: BLE001 - reported
                    fix = {"error": str(exc)}
            emit(
                {
                    "section": "correction",
                    "prototype_charge_kg": W,
                    "standoff_m": R,
                    "scale": lam,
                    "cleared_fraction_prototype": c["prototype"]["cleared_over_uncleared_impulse"],
                    "cleared_fraction_model": c["model"]["cleared_over_uncleared_impulse"],
                    **fix,
                }
            )


def correction_run(charge: float = 1000.0, standoff: float = 40.0, duration: float = 3.0) -> None:
    """The corrected specimen charge in 3D (Method A, the square column with clearing on both systems):
    top first-peak ratio as designed and with the clearing-corrected charge."""
    from dataclasses import replace

    from blastscale.analysis.structure3d import compare_structure3d
    from blastscale.analysis.systems import Settings3D, Systems3D

    col = MultiDrumColumn(section="square")
    w, h = front_face(col)
    lm = LoadModel(True, w, h)
    for lam in SCALES:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            d = design_model(charge, standoff, lam, load_model=lm, face=(w, h))
            fix = clearing_corrected_charge(d, lm)
            dc = replace(d, specimen=blast_parameters(fix["charge_kg"], d.specimen_standoff_m))
            out = {}
            for tag, des in (("as designed", d), ("corrected", dc)):
                # the design's load models (clearing on each system's front, the specimen's lambda times the prototype's)
                cmp = compare_structure3d(Systems3D.of_design(des, col, duration=duration), Settings3D(load="A"))
                out[tag] = cmp.similarity()["top_first_peak_ratio"]
        emit(
            {
                "section": "correction_run",
                "charge_kg": charge,
                "standoff_m": standoff,
                "scale": lam,
                "charge_ratio": fix["charge_ratio"],
                "first_peak_ratio_as_designed": out["as designed"],
                "first_peak_ratio_corrected": out["corrected"],
            }
        )


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    for flag in ("bursts", "clearing", "stability", "block", "column", "correction", "correction-run"):
        ap.add_argument(f"--{flag}", action="store_true")
    ap.add_argument("--duration", type=float, default=3.0, help="column runs [s] (prototype time)")
    ap.add_argument("--methods", nargs="+", default=["A", "B"])
    ap.add_argument("--charge", type=float, default=250.0)
    ap.add_argument("--standoff", type=float, default=10.0)
    ap.add_argument("--variants", nargs="+", default=list(VARIANTS), choices=list(VARIANTS))
    a = ap.parse_args()
    if a.bursts:
        bursts()
    if a.clearing:
        clearing()
    if a.stability:
        stability()
    if a.block:
        block(variants=tuple(a.variants))
    if a.column:
        column(a.charge, a.standoff, a.duration, tuple(a.methods), tuple(a.variants))
    if a.correction:
        correction()
    if a.correction_run:
        correction_run(duration=a.duration)


if __name__ == "__main__":
    main()
