"""A ``blastscale run`` end to end, this tree against an earlier commit (issue #28: "a run of the paper's square
column at least 1.3x faster end to end than today, same machine, same run").

The earlier commit's ``src`` is exported (``git archive``) into a temporary folder; both trees run the same command
with the same interpreter and packages (``PYTHONPATH`` names the tree), alternately, ``--repeat`` times each after
one warm-up run each (numba and the OS file cache warm for both). Reported per tree: wall seconds and CPU seconds
(user + system of the child process) of each run, their medians, and the ratios earlier / this tree; with the load
average before and after (on a shared machine the CPU seconds are the steadier figure).

Usage: ``python benchmarks/bench_run_end_to_end.py [--baseline 134b4d8] [--scenario paper_column_square_250kg]
[--repeat 3] [--json]``. ``--baseline`` defaults to the commit of the state when issue #28 was filed (134b4d8, the
last commit of 2026-11-24). The scenario is a library name or a TOML path. Not a test.
"""

from __future__ import annotations

import argparse
import io
import json
import os
import statistics
import subprocess
import sys
import tarfile
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
#: main when issue #28 was filed (the last commit of 2026-11-24).
ISSUE_28_BASELINE = "134b4d8"


def export_src(commit: str, into: Path) -> Path:
    """``src`` of ``commit`` written under ``into`` (git archive); returns the folder to put on PYTHONPATH."""
    tar = subprocess.run(["git", "-C", str(ROOT), "archive", commit, "src"], capture_output=True, check=True).stdout
    with tarfile.open(fileobj=io.BytesIO(tar)) as t:
        t.extractall(into, filter="data")
    return into / "src"


def one_run(src: Path, scenario: str, out: Path) -> dict:
    """One ``blastscale run SCENARIO --out OUT --force`` on the package in ``src``: wall and CPU seconds."""
    env = {**os.environ, "PYTHONPATH": str(src)}
    code = "import sys; from blastscale.cli import main; main(sys.argv[1:])"
    before = os.times()
    t0 = time.perf_counter()
    p = subprocess.run(
        [sys.executable, "-c", code, "run", scenario, "--out", str(out), "--force"], env=env, capture_output=True
    )
    wall = time.perf_counter() - t0
    after = os.times()
    if p.returncode != 0:
        raise RuntimeError(f"run on {src} failed ({p.returncode}): {p.stderr.decode()[-2000:]}")
    cpu = (after.children_user - before.children_user) + (after.children_system - before.children_system)
    return {"wall_s": wall, "cpu_s": cpu}


def scenario_path(name: str) -> str:
    """A library scenario's file (its name without .toml) or the path given."""
    lib = ROOT / "src" / "blastscale" / "scenario" / "library" / f"{name}.toml"
    return str(lib if lib.exists() else Path(name).resolve())


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--baseline", default=ISSUE_28_BASELINE, help="the earlier commit (default: issue #28's)")
    ap.add_argument("--scenario", default="paper_column_square_250kg", help="library name or TOML path")
    ap.add_argument("--repeat", type=int, default=3, help="timed runs of each tree (alternating)")
    ap.add_argument("--json", action="store_true", help="print JSON only")
    a = ap.parse_args(argv)
    scenario = scenario_path(a.scenario)
    trees = {"baseline": None, "this": ROOT / "src"}
    out: dict = {"scenario": scenario, "baseline_commit": a.baseline, "load_average_before": os.getloadavg()}
    with tempfile.TemporaryDirectory(prefix="bench-e2e-") as tmp:
        tmp = Path(tmp)
        trees["baseline"] = export_src(a.baseline, tmp / "baseline")
        runs: dict = {k: [] for k in trees}
        for name, src in trees.items():  # warm-up: compiled kernels, file cache
            one_run(src, scenario, tmp / f"out-warm-{name}")
        for _ in range(a.repeat):
            for name, src in trees.items():
                runs[name].append(one_run(src, scenario, tmp / f"out-{name}"))
    for name, rs in runs.items():
        out[name] = {
            "runs": rs,
            "median_wall_s": statistics.median(r["wall_s"] for r in rs),
            "median_cpu_s": statistics.median(r["cpu_s"] for r in rs),
        }
    out["speedup_wall"] = out["baseline"]["median_wall_s"] / out["this"]["median_wall_s"]
    out["speedup_cpu"] = out["baseline"]["median_cpu_s"] / out["this"]["median_cpu_s"]
    out["load_average_after"] = os.getloadavg()
    if a.json:
        print(json.dumps(out, indent=2))
    else:
        b, t = out["baseline"], out["this"]
        print(
            f"{Path(scenario).stem}: {a.baseline} {b['median_wall_s']:.2f} s wall / {b['median_cpu_s']:.2f} s CPU, "
            f"this tree {t['median_wall_s']:.2f} / {t['median_cpu_s']:.2f}: x{out['speedup_wall']:.2f} wall, "
            f"x{out['speedup_cpu']:.2f} CPU (medians of {a.repeat}; load {out['load_average_before'][0]:.2f} -> "
            f"{out['load_average_after'][0]:.2f})"
        )
    return 0


if __name__ == "__main__":
    sys.exit(main())
