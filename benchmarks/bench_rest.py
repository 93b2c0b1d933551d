"""At rest before the blast (issue #35, deliverable 5; docs/sim3d.md, "At rest before the blast").

The full-length figures the tests shorten: the semicircular arch R = 5 m, 20 voussoirs, friction 0.8 under gravity
alone for 5 s at t/R = 0.16 (residual displacement and wall time with the assemblies' defaults, impratio 20 and settling
at 1e-8; settled at the run's 1e-10; the convergence study of issue #41: impratio 10, 12, 30, 50, 100, no-slip, tolerance
1e-12, the pyramidal cone; docs/performance.md, "Assembly contact defaults"), the rest check (3 sqrt(H/g)) of t/R = 0.16, 0.12 and 0.105 over 0.25-3
natural times, and its cost on the paper's block and column. Not a test:
``python benchmarks/bench_rest.py [--json] [--quick]`` (--quick: the rest checks only).
"""

from __future__ import annotations

import dataclasses
import json
import math
import sys
import time

from blastscale.sim3d import simulate_structure
from blastscale.sim3d.contact import default_contact
from blastscale.sim3d.rest import rest_check
from blastscale.structures import MultiDrumColumn, RectangularBlock, arch


def _arch(t_over_r):
    a = arch(radius_m=5.0, thickness_m=t_over_r * 5.0, depth_m=1.0, voussoirs=20)
    return a, default_contact(a, friction=0.8)


def five_seconds(**changes) -> dict:
    """The t/R = 0.16 arch under gravity alone for 5 s with ``changes`` to its contact settings."""
    a, c = _arch(0.16)
    t = time.perf_counter()
    s = simulate_structure(a, None, 5.0, record_every=40, contact=dataclasses.replace(c, **changes)).summary()
    return {
        "settings": changes or "default",
        "residual_mm": 1e3 * s["max_residual_displacement_m"],
        "stability": s["stability"],
        "wall_s": time.perf_counter() - t,
    }


def rest_checks() -> list:
    rows = []
    for s, c, name in (
        (RectangularBlock.from_slenderness(10.0, math.radians(15)), None, "paper block"),
        (MultiDrumColumn("square"), None, "paper column"),
    ):
        t = time.perf_counter()
        r = rest_check(s, c)
        rows.append({"structure": name, **r, "wall_s": time.perf_counter() - t})
    for tr in (0.16, 0.12, 0.105):
        a, c = _arch(tr)
        for n in (0.25, 0.5, 1.0, 2.0, 3.0):
            t = time.perf_counter()
            r = rest_check(a, c, natural_times=n)
            rows.append({"structure": f"arch t/R {tr}", "natural_times": n, **r, "wall_s": time.perf_counter() - t})
    return rows


def main():
    quick = "--quick" in sys.argv
    out = {"rest_checks": rest_checks()}
    if not quick:
        out["arch_5s"] = [
            five_seconds(),
            five_seconds(settle_tolerance=1e-10),
            *(five_seconds(impratio=x) for x in (10.0, 12.0, 30.0, 50.0, 100.0)),
            five_seconds(noslip_iterations=1),
            five_seconds(tolerance=1e-12),
            five_seconds(cone="pyramidal"),
        ]
    if "--json" in sys.argv:
        print(json.dumps(out, indent=1))
        return
    for k, rows in out.items():
        print(k)
        for r in rows:
            print("  ", {q: (round(v, 6) if isinstance(v, float) else v) for q, v in r.items()})


if __name__ == "__main__":
    main()
