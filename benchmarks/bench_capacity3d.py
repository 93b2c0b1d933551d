"""The 3D critical charge of the paper's 10-drum column at two stand-offs, checked by direct runs at +-5 %
(issue #38's acceptance; docs/capacity.md, "Any structure: 3D").

The scenario ``paper_column_square_250kg`` (square drums, 10 m, 1.65 -> 1.28 m, marble, Method A,
Kingery-Bulmash, Friedlander, 8 s runs; its [scale] is not used), searched from its 250 kg by steps of x2 and
bisection to a 2 % bracket, ``--members`` per probe (the square column is not chaotic: its members agree, and
the interval is the bracket); with ``--circular`` the circular column (chaotic: the members differ near the
threshold, and the interval is the lognormal fit's). Then a direct run of the Study (no ensemble) at 0.95 and
1.05 times each critical charge: it must stand at the first and collapse (a body fell) at the second.
Reported: critical charges, intervals, probes, runs, CPU seconds (user + sys, this process and its threads; the
machine is shared) and wall seconds.

Not a test: ``python benchmarks/bench_capacity3d.py [--json] [--standoffs=10,15] [--members=2] [--circular]``.
"""

from __future__ import annotations

import json
import os
import sys
import time

from blastscale.scenario.files import load_scenario
from blastscale.study import Study
from blastscale.sweeps.capacity3d import critical_charges_3d


def _cpu() -> float:
    t = os.times()
    return t.user + t.system


def _arg(name: str, default: str) -> str:
    return next((a.split("=", 1)[1] for a in sys.argv[1:] if a.startswith(f"--{name}=")), default)


def fell(sc, charge: float, standoff: float) -> bool:
    """A direct run of the Study at this charge and stand-off (3D, prototype alone, no ensemble): a body fell?"""
    s = sc.with_values({"blast.charge_kg": charge, "blast.standoff_m": standoff, "simulation.engine": "3d"})
    s = s.model_copy(update={"scale": None})
    return Study(s).run().response3d.to_dict()["prototype"]["fallen_blocks"] > 0


def main() -> dict:
    name = "paper_column_circular_200kg" if "--circular" in sys.argv else "paper_column_square_250kg"
    sc = load_scenario(name)
    R = [float(x) for x in _arg("standoffs", "10,15").split(",")]
    members = int(_arg("members", "2"))
    c0, t0 = _cpu(), time.perf_counter()
    res = critical_charges_3d(
        sc, R, members=members, progress=lambda k, r: print(f"round {r}: {k} runs", file=sys.stderr, flush=True)
    )
    c1, t1 = _cpu(), time.perf_counter()
    out = {"scenario": name, "members": members, "search_cpu_s": c1 - c0, "search_wall_s": t1 - t0, "standoffs": []}
    for c in res:
        d = c.to_dict()
        W = c.critical_charge_kg
        if W is not None:
            d["direct_0.95"] = {"charge_kg": 0.95 * W, "fell": fell(sc, 0.95 * W, c.standoff_m)}
            d["direct_1.05"] = {"charge_kg": 1.05 * W, "fell": fell(sc, 1.05 * W, c.standoff_m)}
            d["interval_inside_5_percent"] = bool(0.95 * W <= c.interval_kg[0] and c.interval_kg[1] <= 1.05 * W)
        out["standoffs"].append(d)
    out["total_cpu_s"] = _cpu() - c0
    out["total_wall_s"] = time.perf_counter() - t0
    return out


if __name__ == "__main__":
    result = main()
    if "--json" in sys.argv:
        print(json.dumps(result, indent=1))
    else:
        for d in result["standoffs"]:
            print(
                f"R = {d['standoff_m']:g} m: W_c = {d['critical_charge_kg']} kg, interval {d['interval_kg']} "
                f"({d['interval_basis']}), {d['runs']} runs; direct 0.95 W_c fell: {d.get('direct_0.95')}, "
                f"1.05 W_c fell: {d.get('direct_1.05')}"
            )
        print(f"search: {result['search_cpu_s']:.1f} s CPU, {result['search_wall_s']:.1f} s wall")
