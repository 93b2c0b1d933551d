"""The size of every run said first (issue #27, deliverable 3): the estimate printed before a run
(:func:`blastscale.study.memory.estimate_run`) against the measured time and size of the same run, on
structures from 1 to 3000 bodies: the paper's block, the 10-drum square column, running-bond walls of 22, 55
and 210 blocks, and a 3000-block stack-bonded wall written as a block-model file by this script. Each run is
``blastscale run SCENARIO --out DIR`` in a fresh process (report, histories, figures); short
simulated times (the 3000-block wall 0.01 s). Not a test:
``python benchmarks/bench_estimate.py [--json] [--quick]`` (``--quick``: without the 3000-block file).
"""

from __future__ import annotations

import json
import sys
import tempfile
import time
from pathlib import Path

from blastscale.io.output import tree_size
from blastscale.scenario import Scenario, load_scenario
from blastscale.study import Study
from blastscale.study.memory import estimate_run
from blastscale.units import format_size


def wall_3000_scenario(folder):
    """The 3000-block stack-bonded wall (50 x 60 blocks, a block-model file written in ``folder``) under 100 kg
    at 10 m, 3D only, 0.01 s simulated, as a loaded scenario."""
    from blastscale.scenario import load_scenario

    f = block_file(folder / "wall_3000.json", 50, 60)
    toml = folder / "wall_3000.toml"
    toml.write_text(
        f'title = "3000-block file"\n[structure]\nkind = "assembly"\nfile = "{f.name}"\n'
        "[blast]\ncharge_kg = 100.0\nstandoff_m = 10.0\n[scale]\nlength = 0.05\n"
        '[simulation]\nengine = "3d"\nduration_s = 0.01\n'
    )
    return load_scenario(toml)


def block_file(path: Path, courses: int, units: int, unit_m=(0.5, 0.25, 0.15)) -> Path:
    """A stack-bonded wall of ``courses`` x ``units`` boxes (thickness along x, length along y) as our JSON."""
    tx, ly, hz = unit_m
    blocks = [
        {
            "name": f"B{c * units + u + 1}",
            "vertices": [[x, u * ly + y, c * hz + z] for x in (0.0, tx) for y in (0.0, ly) for z in (0.0, hz)],
        }
        for c in range(courses)
        for u in range(units)
    ]
    path.write_text(json.dumps({"blocks": blocks}))
    return path


def cases(folder: Path, quick: bool) -> list:
    base = {"simulation.engine": "3d", "simulation.critical_charge": False}
    wall = load_scenario("wall_running_bond_lambda20")
    out = [
        ("paper block", Scenario.default().with_values({**base, "simulation.duration_s": 1.0})),
        (
            "10-drum square column",
            load_scenario("paper_column_square_250kg").with_values({**base, "simulation.duration_s": 0.5}),
        ),
        ("running-bond wall 22", wall.with_values({"simulation.duration_s": 0.3})),
        (
            "running-bond wall 55",
            wall.with_values(
                {
                    "structure.courses": 10,
                    "structure.units_per_course": 5,
                    "structure.height_m": 3.0,
                    "simulation.duration_s": 0.1,
                }
            ),
        ),
        (
            "running-bond wall 210",
            wall.with_values(
                {
                    "structure.courses": 20,
                    "structure.units_per_course": 10,
                    "structure.length_m": 8.0,
                    "structure.height_m": 4.0,
                    "simulation.duration_s": 0.05,
                }
            ),
        ),
    ]
    if not quick:
        out.append(("stack-bonded wall file 3000", wall_3000_scenario(folder)))
    return out


def measure(name: str, sc, folder: Path) -> dict:
    """Estimate here, then ``blastscale run SCENARIO --out DIR`` as a user runs it (a fresh process: start-up and
    imports included); its time measured both ways: wall clock and the child's CPU time (the estimate is of one
    core's work: on a shared machine the CPU time is the fair comparison)."""
    import os
    import resource
    import subprocess

    study = Study(sc)
    plan = study.check()
    est = estimate_run(sc, plan.structure, plan.contact)
    tag = name.replace(" ", "_")
    toml = folder / f"{tag}.toml"
    toml.write_text(sc.to_toml())
    out = folder / tag
    cmd = [str(Path(sys.executable).with_name("blastscale")), "run", str(toml), "--out", str(out), "--json"]
    before, t0 = resource.getrusage(resource.RUSAGE_CHILDREN), time.perf_counter()
    proc = subprocess.run(cmd, capture_output=True, text=True, env={**os.environ, "MPLBACKEND": "Agg"}, check=False)
    seconds, after = time.perf_counter() - t0, resource.getrusage(resource.RUSAGE_CHILDREN)
    if proc.returncode != 0:
        raise SystemExit(f"{name}: {proc.stderr}")
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    size = tree_size(out)
    row = {
        "structure": name,
        "bodies": est.bodies,
        "contacts": est.contacts,
        "duration_s": est.duration_s,
        "samples": est.samples,
        "estimate_line": est.line(),
        "estimated_s": est.seconds,
        "measured_s": seconds,
        "measured_cpu_s": cpu,
        "time_ratio": est.seconds / cpu,
        "wall_ratio": est.seconds / seconds,
        "estimated_bytes": est.result_bytes,
        "measured_bytes": size,
        "size_ratio": est.result_bytes / size,
    }
    print(json.dumps(row), file=sys.stderr, flush=True)
    return row


def main():
    import warnings

    warnings.simplefilter("ignore")
    with tempfile.TemporaryDirectory() as tmp:
        rows = [measure(n, sc, Path(tmp)) for n, sc in cases(Path(tmp), "--quick" in sys.argv)]
    if "--json" in sys.argv:
        print(json.dumps(rows, indent=2))
        return
    for r in rows:
        print(
            f"{r['structure']:30s} {r['bodies']:5d} bodies {r['contacts']:6d} contacts  time {r['estimated_s']:8.1f} "
            f"est / {r['measured_cpu_s']:8.1f} s CPU ({r['time_ratio']:.2f}), {r['measured_s']:8.1f} s wall  size "
            f"{format_size(r['estimated_bytes'])} est / {format_size(r['measured_bytes'])} ({r['size_ratio']:.2f})"
        )


if __name__ == "__main__":
    main()
