"""The cost of a contact per step, measured (issue #40 item 6): CPU time per step after the load of stack-bonded
walls (block-model files, 100 kg at 10 m, 1/20), from two durations of one structure differenced (the
once-per-run work cancels), against the estimate's per-step cost under a blast (:func:`blastscale.study.memory.step_seconds`:
``CONTACT_STEP_SECONDS`` x u x max(1, u / ``CONTACT_STEP_UNITS``)^``CONTACT_STEP_EXPONENT``, u = bodies +
contacts); reported as ratios. Measured 28 Nov 2026 (one core's CPU time, MuJoCo 4.0.0, loaded 2-core machine):
u = 70, 290, 590, 1170: 3.4, 9.8, 11.3, 14.6 us per body or contact; since side joints engage at the collision depth
(issue #39, the same day, load 1-2): 3.75, 10.95, 5.63 us at u = 70, 290, 1180. Not a test:
``python benchmarks/bench_contact_cost.py [--json] [COURSESxUNITS:D1:D2 ...]`` (default 5x5:0.1:1 10x10:0.01:0.2
20x20:0.1:0.2; about 4 min of CPU).
"""

from __future__ import annotations

import json
import sys
import tempfile
import time
import warnings
from pathlib import Path

from bench_estimate import block_file

from blastscale.scenario import load_scenario
from blastscale.sim3d.integrate import SETTLE_TIME_CONSTANTS, step_factor_after_load
from blastscale.study import Study, memory

DEFAULT = ["5x5:0.1:1", "10x10:0.01:0.2", "20x20:0.1:0.2"]


def wall(folder: Path, courses: int, units: int):
    f = block_file(folder / f"w{courses}x{units}.json", courses, units)
    toml = folder / f"w{courses}x{units}.toml"
    toml.write_text(
        f'title = "stack-bonded wall"\n[structure]\nkind = "assembly"\nfile = "{f.name}"\n'
        "[blast]\ncharge_kg = 100.0\nstandoff_m = 10.0\n[scale]\nlength = 0.05\n"
        '[simulation]\nengine = "3d"\nduration_s = 0.01\n'
    )
    return load_scenario(toml)


def measure(base, d1: float, d2: float) -> dict:
    """CPU seconds per step after the load, from runs of ``d1`` and ``d2`` simulated seconds."""
    Study(base.with_values({"simulation.duration_s": 0.002})).run()  # kernels compiled, caches warm
    cpu, steps = {}, {}
    for d in (d1, d2):
        sc = base.with_values({"simulation.duration_s": d})
        plan = Study(sc).check()
        c, nb = plan.contact, len(plan.structure.bodies)
        steps[d] = 2 * (
            d / (c.timestep * step_factor_after_load(c, nb)) + SETTLE_TIME_CONSTANTS * c.time_constant / c.timestep
        )
        t = time.process_time()
        Study(sc).run()
        cpu[d] = time.process_time() - t
    u = nb + memory.contacts_of(plan.structure)
    measured = (cpu[d2] - cpu[d1]) / (steps[d2] - steps[d1])
    estimated = memory.step_seconds(u)
    return {
        "bodies": nb,
        "units": u,
        "measured_us_per_unit": 1e6 * measured / u,
        "estimate_over_measured": estimated / measured,
    }


def main():
    warnings.simplefilter("ignore")
    cases = [a for a in sys.argv[1:] if not a.startswith("--")] or DEFAULT
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for case in cases:
            size, d1, d2 = case.split(":")
            courses, units = map(int, size.split("x"))
            rows.append(measure(wall(Path(tmp), courses, units), float(d1), float(d2)))
            print(json.dumps(rows[-1]), file=sys.stderr, flush=True)
    if "--json" in sys.argv:
        print(json.dumps(rows, indent=2))
    else:
        for r in rows:
            print(
                f"{r['bodies']:5d} bodies  u {r['units']:6d}  {r['measured_us_per_unit']:6.2f} us  estimate/measured {r['estimate_over_measured']:.2f}"
            )


if __name__ == "__main__":
    main()
