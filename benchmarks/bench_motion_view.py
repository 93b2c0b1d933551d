"""What the motion's drawings cost, this tree against an earlier commit (issues #39 and #41: "the column GIF in under
30 s", "the view's data written once, small", "``make run`` no slower than before the 3D view").

Two figures per tree, each in a fresh interpreter on the package of that tree (``PYTHONPATH``; the earlier commit's
``src`` exported with ``git archive``), the trees alternating, ``--repeat`` times each:

* ``view``: the interactive view of a result folder's motion as the report writes it (``report.motion.motion_html``
  of the frames ``report.motion.view_frames`` keeps at 20 per second): CPU and wall seconds in the process (the
  imports and the reading of ``histories.nc`` left out) and the page's size [bytes];
* ``gif`` (with ``--gif RESULT_DIR``, e.g. a column's): ``blastscale show RESULT_DIR --animate FILE.gif`` end to
  end, CPU seconds of the child (user + system: the steadier figure on a shared machine) and wall seconds.

Usage: ``python benchmarks/bench_motion_view.py results/default [--gif results/column] [--baseline cad6f0c]
[--repeat 3]``; prints JSON. ``--baseline`` defaults to cad6f0c (main before this work: plotly's view, the GIF
redrawn whole each frame). ``make run`` against the commit before the 3D view (c99d612~1):
``benchmarks/bench_run_end_to_end.py --baseline c99d612~1 --scenario results/default/scenario.toml``. Not a
test.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_run_end_to_end import ROOT, export_src  # noqa: E402

#: main before issues #39.1 / #41.4 (the view on plotly, the GIF redrawn whole each frame).
BASELINE = "cad6f0c"

VIEW = """
import json, sys, time
from blastscale.io.motion import read_motion
from blastscale.report.motion import motion_html, view_frames
from blastscale.similitude.effects import charge_position
motion, info = read_motion(sys.argv[1])
charge = None if info["standoff_m"] is None else charge_position(motion.front_x, info["standoff_m"])
c0, w0 = time.process_time(), time.perf_counter()
idx, _ = view_frames(motion, 20.0)
page = motion_html(motion, idx, charge, info["title"], "iso", 20.0)
print(json.dumps({"cpu_s": time.process_time() - c0, "wall_s": time.perf_counter() - w0, "bytes": len(page.encode())}))
"""


def view(src: Path, folder: str) -> dict:
    """The view of ``folder``'s motion written by the package in ``src``: CPU, wall seconds and bytes."""
    p = subprocess.run(
        [sys.executable, "-c", VIEW, folder], env={**os.environ, "PYTHONPATH": str(src)}, capture_output=True
    )
    if p.returncode != 0:
        raise RuntimeError(p.stderr.decode()[-2000:])
    return json.loads(p.stdout.decode().strip().splitlines()[-1])


def gif(src: Path, folder: str, out: Path) -> dict:
    """``show FOLDER --animate OUT`` by the package in ``src``: wall and CPU seconds of the child, bytes."""
    code = "import sys; from blastscale.cli import main; main(sys.argv[1:])"
    before, t0 = os.times(), time.perf_counter()
    p = subprocess.run(
        [sys.executable, "-c", code, "show", folder, "--animate", str(out)],
        env={**os.environ, "PYTHONPATH": str(src), "MPLBACKEND": "Agg"},
        capture_output=True,
    )
    wall, after = time.perf_counter() - t0, os.times()
    if p.returncode != 0:
        raise RuntimeError(p.stderr.decode()[-2000:])
    cpu = (after.children_user - before.children_user) + (after.children_system - before.children_system)
    return {"cpu_s": cpu, "wall_s": wall, "bytes": out.stat().st_size}


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("result", help="a result folder with a 3D run (e.g. make run's results/default)")
    ap.add_argument("--gif", default=None, help="a result folder to animate as a GIF (e.g. a column's)")
    ap.add_argument("--baseline", default=BASELINE)
    ap.add_argument("--repeat", type=int, default=3)
    a = ap.parse_args(argv)
    out: dict = {"baseline_commit": a.baseline, "load_average_before": os.getloadavg()[0]}
    with tempfile.TemporaryDirectory(prefix="bench-view-") as tmp:
        tmp = Path(tmp)
        trees = {"baseline": export_src(a.baseline, tmp / "baseline"), "this": ROOT / "src"}
        runs: dict = {k: {"view": [], "gif": []} for k in trees}
        for _ in range(a.repeat):
            for name, src in trees.items():
                runs[name]["view"].append(view(src, a.result))
                if a.gif:
                    runs[name]["gif"].append(gif(src, a.gif, tmp / f"{name}.gif"))
                print(name, runs[name]["view"][-1], runs[name]["gif"][-1:], file=sys.stderr)  # as it goes
    for name, r in runs.items():
        out[name] = {k: v for k, v in r.items() if v}
        for k, v in list(out[name].items()):
            out[name][f"{k}_median_cpu_s"] = statistics.median(x["cpu_s"] for x in v)
    out["load_average_after"] = os.getloadavg()[0]
    print(json.dumps(out, indent=1))
    return out


if __name__ == "__main__":
    main()
