"""Random kills of ``blastscale run`` and ``blastscale sweep`` (issue #15): nothing lost, nothing half-written.

Each trial starts one command into a work folder that may already hold its previous result, and stops it with
SIGINT, SIGTERM or SIGKILL, either at a random pause point of ``blastscale._hooks`` (the run started,
simulating, writing; a sweep after its k-th chunk or while consolidating; an output set aside between the two
renames of a ``--force`` replacement, where only SIGKILL can land) or after a random delay (which may come
after the command has finished). Then it checks:

* the stopped command: SIGINT -> exit 130, SIGTERM -> 143, one line on stderr; no partial folder left
  (``.X.partial-*``, a chunk's temporary file) except after SIGKILL;
* the previous result, when there was one and the kill came before the commit, is still there and intact;
* the next run of the same command (``--force`` for ``run``) succeeds, leaves no partial folder, temporary
  file or lock file, and its result is intact: ``run``'s summary, report and histories open; a resumed sweep
  equals, value for value, the same sweep run uninterrupted once at the start.

Usage: ``python benchmarks/kill_runs.py [--trials 50] [--seed 0] [--json]``; about 10 s a trial on the 2-core
development machine. Figures: docs/output.md.
"""

from __future__ import annotations

import argparse
import json
import os
import random
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from collections import Counter
from pathlib import Path

BIN = Path(sys.executable).with_name("blastscale")
SWEEP_ARGS = ["--vary", "standoff_m=1.5:4:6", "--vary", "charge_kg=60,120", "--chunk", "1"]
N_CHUNKS = 12
STATUS = {signal.SIGINT: 130, signal.SIGTERM: 143}


def blastscale(args, cwd, env=None, **kw):
    return subprocess.Popen(
        [str(BIN), *map(str, args)],
        cwd=cwd,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env={**os.environ, "MPLBACKEND": "Agg", **(env or {})},
        preexec_fn=_default_signals,
        **kw,
    )


def _default_signals() -> None:
    """SIGINT and SIGHUP back to their defaults in the child (a background job or nohup starts with them
    ignored, and blastscale keeps an ignored signal ignored)."""
    for s in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP):
        signal.signal(s, signal.SIG_DFL)


def leftovers(folder: Path) -> list:
    """Partial work in a folder: partial folders, set-aside old results, temporary chunk files, lock files."""
    out = []
    for p in folder.rglob("*"):
        n = p.name
        if ".partial-" in n or ".old-" in n or n.endswith(".lock") or (n.startswith(".chunk-") and n.endswith(".tmp")):
            out.append(str(p.relative_to(folder)))
    return sorted(out)


def run_intact(folder: Path) -> bool:
    import xarray as xr

    try:
        s = json.loads((folder / "summary.json").read_text())
        xr.open_datatree(folder / "histories.nc").close()
        return "blastscale" in s["versions"] and (folder / "report.html").stat().st_size > 10_000
    except Exception:  # noqa: BLE001 - any failure to read is "not intact"
        return False


def sweep_equal(a: Path, b: Path) -> bool:
    from blastscale.io.sweep_store import open_sweep

    try:
        ta, tb = open_sweep(a), open_sweep(b)
        return [n.path for n in ta.subtree] == [n.path for n in tb.subtree] and all(
            n.ds.equals(tb[n.path].ds) for n in ta.subtree
        )
    except Exception:  # noqa: BLE001
        return False


def trial(rng: random.Random, work: Path, scenario: Path, reference: Path, kind: str) -> dict:
    out = work / ("r" if kind == "run" else "s.zarr")
    workers = rng.choice([0, 2]) if kind == "sweep" else 0
    args = (
        ["run", scenario, "--out", out, "--force"]
        if kind == "run"
        else ["sweep", scenario, *SWEEP_ARGS, "--workers", workers, "--out", out]
    )
    had = out.exists()
    sig = rng.choice([signal.SIGINT, signal.SIGTERM, signal.SIGKILL])
    points = (
        ["run:started", "run:simulating", "run:writing"] + (["output:between-renames"] if had else [])
        if kind == "run"
        else [f"sweep:chunks={k}" for k in range(1, N_CHUNKS + 1)] + ["sweep:consolidating"]
    )
    how = rng.choice(["pause", "delay"])
    env, marker = {}, work.parent / f"{work.name}.marker"
    marker.unlink(missing_ok=True)
    point = None
    if how == "pause":
        point = rng.choice(points)
        if point == "output:between-renames":
            sig = signal.SIGKILL  # the signals are held there: only kill -9 lands
        env = {"BLASTSCALE_PAUSE_AT": point, "BLASTSCALE_PAUSE_MARKER": str(marker)}
    t0 = time.monotonic()
    p = blastscale(args, work, env, start_new_session=True)
    if how == "pause":
        while not marker.exists() and p.poll() is None and time.monotonic() - t0 < 300:
            time.sleep(0.01)
        reached = marker.exists()
    else:
        delay = rng.uniform(0.0, 6.0 if kind == "run" else 8.0)
        while p.poll() is None and time.monotonic() - t0 < delay:
            time.sleep(0.01)
        reached = True
    finished = p.poll() is not None
    if not finished:  # a terminal's Ctrl-C reaches the whole group; SIGTERM/SIGKILL the command (timeout, kill)
        if sig == signal.SIGINT:
            os.killpg(p.pid, sig)
        else:
            os.kill(p.pid, sig)
    _, err = p.communicate(timeout=300)
    # a signal that lands after the result is in place ("wrote ..." printed) stops only the interpreter's exit
    finished = finished or ("\nwrote " in "\n" + err and sig in STATUS)
    rec = {
        "kind": kind,
        "workers": workers,
        "signal": signal.Signals(sig).name,
        "how": how,
        "point": point,
        "reached": reached,
        "completed_before_kill": finished and p.returncode == 0,
        "exit": p.returncode,
        "had_previous": had,
    }
    problems = []
    if not finished:
        if sig in STATUS:
            if p.returncode != STATUS[sig] and p.returncode != 0:
                problems.append(f"exit {p.returncode}, expected {STATUS[sig]}")
            if p.returncode != 0 and (err.count("\n") != 1 or not err.startswith("error: ")):
                problems.append(f"stderr not one line: {err[-300:]!r}")
            if leftovers(work):
                problems.append(f"left after {rec['signal']}: {leftovers(work)}")
        else:
            rec["left_by_kill_9"] = len(leftovers(work))
    if kind == "run" and had and (p.returncode != 0) and not out.exists():
        rec["previous_set_aside"] = True  # kill -9 between the renames: the next run puts it back first
    elif kind == "run" and had and not run_intact(out):
        problems.append("the previous result is damaged")
    nxt = blastscale(args, work)
    _, nerr = nxt.communicate(timeout=600)
    if nxt.returncode != 0:
        problems.append(f"next run failed: {nerr[-300:]!r}")
    if leftovers(work):
        problems.append(f"left after the next run: {leftovers(work)}")
    if kind == "run" and not run_intact(out):
        problems.append("the next run's result is not intact")
    if kind == "sweep":
        rec["resumed_equal"] = sweep_equal(out, reference)
        if not rec["resumed_equal"]:
            problems.append("the resumed sweep differs from the uninterrupted one")
        shutil.rmtree(out, ignore_errors=True)  # the next sweep trial starts from nothing
    rec["problems"] = problems
    rec["seconds"] = time.monotonic() - t0
    return rec


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--trials", type=int, default=50)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--json", action="store_true")
    a = ap.parse_args()
    from blastscale.scenario import Scenario

    rng = random.Random(a.seed)
    base = Path(tempfile.mkdtemp(prefix="blastscale-kills-"))
    work = base / "work"
    work.mkdir()
    scenario = base / "scenario.toml"  # the paper's block, both engines, short: ~3 s a run, 12 planar sweep cases
    scenario.write_text(Scenario.default().with_values({"duration_s": 0.5}).to_toml())
    reference = base / "reference.zarr"
    ref = blastscale(["sweep", scenario, *SWEEP_ARGS, "--workers", 0, "--out", reference], base)
    assert ref.wait() == 0, ref.stderr.read()
    records = []
    t0 = time.monotonic()
    for i in range(a.trials):
        rec = trial(rng, work, scenario, reference, "run" if i % 2 == 0 else "sweep")
        records.append(rec)
        if not a.json:
            print(
                f"{i + 1:3d} {rec['kind']:5s} w{rec['workers']} {rec['signal']:7s} {rec['how']:5s} "
                f"{str(rec['point']):24s} exit {rec['exit']:4d} {'OK' if not rec['problems'] else rec['problems']}",
                flush=True,
            )
    summary = {
        "trials": len(records),
        "seconds": time.monotonic() - t0,
        "by_signal": dict(Counter(r["signal"] for r in records)),
        "by_kind": dict(Counter(r["kind"] for r in records)),
        "by_moment": dict(Counter(r["point"] or "random delay" for r in records)),
        "completed_before_the_kill": sum(r["completed_before_kill"] for r in records),
        "exit_statuses": dict(Counter(str(r["exit"]) for r in records)),
        "kill_9_left_partial_work": sum(1 for r in records if r.get("left_by_kill_9")),
        "previous_result_set_aside_then_restored": sum(1 for r in records if r.get("previous_set_aside")),
        "sweeps_resumed_equal": sum(1 for r in records if r.get("resumed_equal")),
        "sweeps": sum(1 for r in records if r["kind"] == "sweep"),
        "trials_with_problems": [r for r in records if r["problems"]],
        "python": sys.version.split()[0],
    }
    shutil.rmtree(base, ignore_errors=True)
    print(json.dumps(summary if a.json else {k: v for k, v in summary.items()}, indent=2))
    sys.exit(1 if summary["trials_with_problems"] else 0)


if __name__ == "__main__":
    main()
