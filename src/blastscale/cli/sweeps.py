"""``blastscale sweep``, ``blastscale fragility``, ``blastscale similarity-map``: many cases of a
scenario, on Dask, resumable (docs/sweeps.md).

Units at this edge are those of the scenario keys (SI, named in each key); grids are written
``start:stop:n[:log]`` or ``a,b,c``, distributions ``kind:p1,p2`` (``normal:mean,sd``,
``lognormal:median,beta``, ``uniform:lo,hi``, ``loguniform:lo,hi``, ``triangular:lo,mode,hi``).
"""

from __future__ import annotations

from pathlib import Path
from typing import List, Optional

import typer

from .._validate import BlastscaleInputError
from ._app import app, console, console_err, one_line_warnings, print_json, table

SCENARIO_ARG = typer.Argument(None, help="Scenario TOML file (default: the built-in default scenario).")
SCHEDULER = typer.Option(None, "--scheduler", help="Address of a running Dask scheduler (e.g. tcp://127.0.0.1:8786).")
WORKERS = typer.Option(None, "--workers", help="Local worker processes (default: one per CPU; 0: in this process).")
CHUNK = typer.Option(None, "--chunk", help="Cases per task (default: planar ~cases / (4 workers), at most 2000; else 1).")
SEED = typer.Option(0, "--seed", help="Seed of the Monte Carlo draws (numpy default_rng).")


def _scenario(path: Optional[Path]):
    from ..io.scenario import Scenario, load_scenario

    return Scenario.default() if path is None else load_scenario(path)


def _assignments(items: Optional[List[str]], option: str, parse) -> dict:
    from ..analysis.grids import parse_assignment

    out = {}
    for text in items or []:
        key, spec = parse_assignment(text, option)
        if key in out:
            raise BlastscaleInputError(f"{option} = {text!r}: field {key!r} is given twice")
        out[key] = parse(spec, key)
    return out


def _progress_bar(label: str):
    """A rich progress bar on stderr and its ``(done, total)`` callback."""
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn, TimeRemainingColumn

    bar = Progress(TextColumn(label), BarColumn(), MofNCompleteColumn(), TimeElapsedColumn(), TimeRemainingColumn(),
                   console=console_err, transient=True)
    task = bar.add_task(label, total=None)

    def tick(done: int, total: int) -> None:
        bar.update(task, completed=done, total=total)

    return bar, tick


@app.command("sweep")
def sweep_cmd(
    scenario: Optional[Path] = SCENARIO_ARG,
    vary: Optional[List[str]] = typer.Option(None, "--vary", help="FIELD=start:stop:n[:log] or FIELD=a,b,c (repeatable; cartesian grid)."),
    sample: Optional[List[str]] = typer.Option(None, "--sample", help="FIELD=dist:params, e.g. friction=uniform:0.5,0.8 (repeatable)."),
    samples: int = typer.Option(0, "--samples", help="Monte Carlo samples per grid point (with --sample)."),
    seed: int = SEED,
    out: Path = typer.Option(..., "--out", help="Zarr store to write (a folder, e.g. sweep.zarr)."),
    scheduler: Optional[str] = SCHEDULER,
    workers: Optional[int] = WORKERS,
    chunk: Optional[int] = CHUNK,
    force: bool = typer.Option(False, "--force", help="Replace a store (or unfinished chunks) of another sweep."),
    as_json: bool = typer.Option(False, "--json", help="Print one JSON object instead of a table."),
) -> None:
    """Run the Study for every case of a grid (and Monte Carlo samples) of scenario fields and
    store its scalar results in a Zarr store (coordinates named after the fields). A sweep
    killed and run again skips the chunks already done."""
    from ..analysis.grids import parse_distribution, parse_grid
    from ..analysis.sweeps import SweepSpec, run_sweep

    base = _scenario(scenario)
    grid = _assignments(vary, "--vary", parse_grid)
    dists = _assignments(sample, "--sample", parse_distribution)
    if dists and samples < 1:
        raise BlastscaleInputError(f"samples = {samples} is out of range: --sample needs --samples >= 1")
    if samples and not dists:
        raise BlastscaleInputError(f"samples = {samples}: give the sampled fields with --sample FIELD=dist:params")
    spec = SweepSpec.build(base, grid, dists, samples=samples, seed=seed)
    bar, tick = _progress_bar(f"sweep: {spec.n_cases} cases")
    with one_line_warnings(), bar:
        run = run_sweep(spec, out, scheduler=scheduler, workers=workers, chunk=chunk, force=force, progress=tick)
    res = {**run.to_dict(), "dims": list(spec.dims), "shape": list(spec.shape),
           "fields": {a.name: a.path for a in spec.axes} | {s.name: s.path for s in spec.sampled}}
    if as_json:
        print_json(res)
        return
    console.print(table(f"Sweep of {spec.n_cases} cases into {out}", [
        ("dimensions", " x ".join(f"{d} ({n})" for d, n in zip(spec.dims, spec.shape)) or "-", ""),
        ("chunks computed / already done", f"{run.chunks_run} / {run.chunks_skipped}", ""),
        ("wall time", f"{run.seconds:.3g}", "s"),
        ("cases per minute", f"{run.cases_per_minute:.4g}", "1/min"),
        ("workers", str(run.workers), ""),
    ]))
