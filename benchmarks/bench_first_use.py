"""Honest time (issue #39, deliverable 4): the size line's estimate (:func:`blastscale.study.memory.estimate_run`,
compiling on first use included: :func:`~blastscale.study.memory.compile_seconds`) against the measured time of
``blastscale run SCENARIO --out DIR`` in a fresh process, **cold** (an empty numba cache: ``NUMBA_CACHE_DIR`` a new
folder, every kernel compiled) and **warm** (the same folder again), on five structures: the default run (the
paper's block, planar and 3D), the paper's square and circular columns, the arch and a 3000-block stack-bonded wall
(a block-model file written here; 0.01 s simulated).

The estimate is of one core's work; the measured CPU time of the child (user + system, ``getrusage``) is the
fair comparison on a shared machine (the development machine: 2 cores shared by 8 engineers: the wall clock
there is 2-4 x the CPU time and says more about the neighbours than about blastscale); both are printed. Not
a test (no clocks in tests): ``python benchmarks/bench_first_use.py [--json] [--quick] [--only NAME] [--cold-only]``
(``--quick``: without the 3000-block file and the circular column; ``--cold-only``: the cold run alone, e.g.
for the 3000-block file, whose 3D-only run compiles nothing: its warm run repeats the cold one).
"""

from __future__ import annotations

import json
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from bench_estimate import wall_3000_scenario  # noqa: E402


def cases(folder: Path, quick: bool) -> list:
    from blastscale.scenario import Scenario, load_scenario

    out = [
        ("default run", Scenario.default()),
        ("square column", load_scenario("paper_column_square_250kg")),
        ("arch", load_scenario("arch_lambda20")),
    ]
    if not quick:
        out.append(("circular column (4-member ensembles)", load_scenario("paper_column_circular_200kg")))
        out.append(("3000-block file", wall_3000_scenario(folder)))
    return out


def estimate(sc, cache: Path):
    """The estimate as the run would state it with ``cache`` as numba's cache folder."""
    from numba.core import config

    from blastscale.study import Study
    from blastscale.study.memory import estimate_run

    config.CACHE_DIR = str(cache)
    plan = Study(sc).check()
    return estimate_run(sc, plan.structure, plan.contact)


def run_once(toml: Path, out: Path, cache: Path) -> tuple:
    """(CPU s, wall s) of ``blastscale run TOML --out OUT --json`` in a fresh process with ``cache``."""
    cmd = [str(Path(sys.executable).with_name("blastscale")), "run", str(toml), "--out", str(out), "--json"]
    env = {**os.environ, "MPLBACKEND": "Agg", "NUMBA_CACHE_DIR": str(cache)}
    before, t0 = resource.getrusage(resource.RUSAGE_CHILDREN), time.perf_counter()
    proc = subprocess.run(cmd, capture_output=True, text=True, env=env, check=False)
    wall, after = time.perf_counter() - t0, resource.getrusage(resource.RUSAGE_CHILDREN)
    if proc.returncode != 0:
        raise SystemExit(f"{toml}: {proc.stderr[-2000:]}")
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime), wall


def measure(name: str, sc, folder: Path) -> list:
    tag = name.split(" (")[0].replace(" ", "_")
    toml = folder / f"{tag}.toml"
    toml.write_text(sc.to_toml())
    cache = folder / f"numba_{tag}"
    rows = []
    for state in ("cold",) if "--cold-only" in sys.argv else ("cold", "warm"):
        est = estimate(sc, cache)
        cpu, wall = run_once(toml, folder / f"{tag}_{state}", cache)
        row = {
            "structure": name,
            "cache": state,
            "estimate_line": est.line(),
            "estimated_s": est.seconds,
            "estimated_compile_s": est.compile_s,
            "measured_cpu_s": cpu,
            "measured_wall_s": wall,
            "ratio_cpu": est.seconds / cpu,
            "ratio_wall": est.seconds / wall,
        }
        print(json.dumps(row), file=sys.stderr, flush=True)
        rows.append(row)
    return rows


def main():
    import warnings

    warnings.simplefilter("ignore")
    only = sys.argv[sys.argv.index("--only") + 1] if "--only" in sys.argv else None
    with tempfile.TemporaryDirectory() as tmp:
        rows = []
        for n, sc in cases(Path(tmp), "--quick" in sys.argv):
            if only is None or only in n:
                rows += measure(n, sc, Path(tmp))
    if "--json" in sys.argv:
        print(json.dumps(rows, indent=2))
        return
    for r in rows:
        print(
            f"{r['structure']:38s} {r['cache']}: estimate {r['estimated_s']:7.1f} s (compiling {r['estimated_compile_s']:4.0f} s)"
            f" / {r['measured_cpu_s']:7.1f} s CPU = {r['ratio_cpu']:.2f}; wall {r['measured_wall_s']:7.1f} s"
        )


if __name__ == "__main__":
    main()
