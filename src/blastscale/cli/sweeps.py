"""``blastscale sweep``, ``blastscale fragility``, ``blastscale similarity-map``: many cases of a
scenario, on Dask, resumable (docs/sweeps.md).

Units at this edge are those of the scenario keys (SI, named in each key); grids are written
``start:stop:n[:log]`` or ``a,b,c``, distributions ``kind:p1,p2`` (``normal:mean,sd``,
``lognormal:median,beta``, ``uniform:lo,hi``, ``loguniform:lo,hi``, ``triangular:lo,mode,hi``).
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import List, Optional

import numpy as np
import typer
from rich.table import Table

from .._validate import BlastscaleInputError
from ..io.results import legacy_name
from ..io.sweep_store import open_sweep, unfinished_chunks
from ..sweeps.fragility import default_criterion, fragility
from ..sweeps.grids import parse_assignment, parse_distribution, parse_grid, parse_number
from ..sweeps.run import run_in_memory, run_sweep
from ..sweeps.similarity_map import similarity_map
from ..sweeps.spec import SweepSpec
from ._app import app
from ._output import console, console_err, count_progress, one_line_warnings, print_json, print_written, table
from ._signals import ignore_interrupts, set_interrupt_note
from .flags import SET_VALUES
from .options import check_plot_path
from .steps import add_figure, answer, read_scenario

SCENARIO_ARG = typer.Argument(None, help="Scenario TOML file (default: the built-in default scenario).")
SCHEDULER = typer.Option(None, "--scheduler", help="Address of a running Dask scheduler (e.g. tcp://127.0.0.1:8786).")
WORKERS = typer.Option(None, "--workers", help="Local worker processes (default: one per CPU; 0: in this process).")
CHUNK = typer.Option(
    None,
    "--chunk",
    help="Cases per task (default: --outcomes ~cases / (2 workers), at most 20000; planar ~cases / (4 workers), at most 2000; else 1).",
)
SEED = typer.Option(0, "--seed", help="Seed of the Monte Carlo draws (numpy default_rng).")


def _assignments(items: Optional[List[str]], option: str, parse) -> dict:

    out = {}
    for text in items or []:
        key, spec = parse_assignment(text, option)
        if key in out:
            raise BlastscaleInputError(f"{option} = {text!r}: field {key!r} is given twice")
        out[key] = parse(spec, key)
    return out


def _resume_note(out) -> None:
    """What an interrupted sweep says it kept: its finished chunks, from which the same command resumes."""

    def note() -> str:
        n = unfinished_chunks(out)
        return (
            f"{n} finished chunks kept in {out}.parts (the partial chunk removed): run the same command again to resume"
            if n
            else "no partial results left"
        )

    set_interrupt_note(note)


@app.command("sweep")
def sweep_cmd(
    scenario: Optional[Path] = SCENARIO_ARG,
    values: List[str] = SET_VALUES,
    vary: Optional[List[str]] = typer.Option(
        None, "--vary", help="FIELD=start:stop:n[:log] or FIELD=a,b,c (repeatable; cartesian grid)."
    ),
    sample: Optional[List[str]] = typer.Option(
        None, "--sample", help="FIELD=dist:params, e.g. friction=uniform:0.5,0.8 (repeatable)."
    ),
    samples: int = typer.Option(0, "--samples", help="Monte Carlo samples per grid point (with --sample)."),
    seed: int = SEED,
    out: Path = typer.Option(
        ..., "--out", help="Zarr store to write (a folder, e.g. sweep.zarr; its parent folder must exist)."
    ),
    scheduler: Optional[str] = SCHEDULER,
    workers: Optional[int] = WORKERS,
    chunk: Optional[int] = CHUNK,
    force: bool = typer.Option(
        False, "--force", help="Replace a store (or unfinished chunks) of another sweep (never anything else)."
    ),
    outcomes: bool = typer.Option(
        False,
        "--outcomes",
        help="Outcome mode (planar blocks): overturned and largest rotation of prototype and model at any time, vectorised (docs/sweeps.md).",
    ),
    as_json: bool = typer.Option(False, "--json", help="Print one JSON object instead of a table."),
) -> None:
    """Run the Study for every case of a grid (and Monte Carlo samples) of scenario fields and
    store its scalar results in a Zarr store: an xarray DataTree, a group per engine (dimensions
    named after the fields, then system, point, component). A sweep killed and run again skips
    the chunks already done. A scenario without \\[scale]: the prototype alone. With --outcomes
    (planar blocks, a \\[scale]): only the first-swing outcomes and largest rotations, about a
    million cases per minute."""

    base = read_scenario(scenario, values)
    grid = _assignments(vary, "--vary", lambda text, key: parse_grid(text, key, numeric=False))
    dists = _assignments(sample, "--sample", parse_distribution)
    if dists and samples < 1:
        raise BlastscaleInputError(f"samples = {samples} is out of range: --sample needs --samples >= 1")
    if samples and not dists:
        raise BlastscaleInputError(f"samples = {samples}: give the sampled fields with --sample FIELD=dist:params")
    spec = SweepSpec.build(base, grid, dists, samples=samples, seed=seed, outcomes=outcomes)
    bar, tick = count_progress(f"sweep: {spec.n_cases} cases", quiet=as_json)
    _resume_note(out)
    with one_line_warnings(), bar:
        run = run_sweep(spec, out, scheduler=scheduler, workers=workers, chunk=chunk, force=force, progress=tick)
    ignore_interrupts()  # the store is in place: only the printing remains
    print_written(out, f"{spec.n_cases} cases")
    res = {
        **run.to_dict(),
        "dims": list(spec.dims),
        "shape": list(spec.shape),
        "fields": {a.name: a.path for a in spec.axes} | {s.name: s.path for s in spec.sampled},
    }
    if as_json:
        print_json(res)
        return
    console.print(
        table(
            f"Sweep of {spec.n_cases} cases into {out}",
            [
                ("dimensions", " x ".join(f"{d} ({n})" for d, n in zip(spec.dims, spec.shape)) or "-", ""),
                ("chunks computed / already done", f"{run.chunks_run} / {run.chunks_skipped}", ""),
                ("computing time (cluster start/stop excluded)", f"{run.seconds:.3g}", "s"),
                (
                    "cases per minute",
                    f"{run.cases_per_minute:.4g}"
                    if run.chunks_run and math.isfinite(run.cases_per_minute)
                    else "- (nothing computed: every chunk was done)",
                    "1/min",
                ),
                ("workers", str(run.workers), ""),
            ],
        )
    )


def _uniform_range(text: str, name: str) -> tuple:
    lo, sep, hi = text.partition(":")

    if not sep:
        raise BlastscaleInputError(f"--uniform {name} = {text!r} is not lo:hi")
    return parse_number(lo, name, "lo"), parse_number(hi, name, "hi")


def _beta(text: str, name: str) -> float:

    return parse_number(text, f"--lognormal {name}", "beta")  # its range: blastscale.sweeps.fragility


@app.command("fragility")
def fragility_cmd(
    scenario: Optional[Path] = SCENARIO_ARG,
    values: List[str] = SET_VALUES,
    charges: str = typer.Option(..., "--charges", help="Charges W \\[kg TNT]: start:stop:n[:log] or a,b,c."),
    lognormal: Optional[List[str]] = typer.Option(
        None,
        "--lognormal",
        help="FIELD=beta: the field times a lognormal factor (median 1, log-sd beta); charge_kg=beta: the charge "
        "and its TNT equivalence (repeatable).",
    ),
    uniform: Optional[List[str]] = typer.Option(
        None,
        "--uniform",
        help="FIELD=lo:hi: uniform values in the field's unit: stand-off, friction, geometric tolerances (repeatable).",
    ),
    samples: int = typer.Option(1000, "--samples", help="Monte Carlo draws per charge."),
    seed: int = SEED,
    criterion: Optional[str] = typer.Option(
        None,
        "--criterion",
        help="first-swing (blocks: planar rocking, vectorised; state collapse) or damage (any structure: one Study "
        "per case, damage states slight, moderate, severe, collapse). Default: first-swing for a block, else damage.",
    ),
    out: Optional[Path] = typer.Option(
        None, "--out", help="Damage criterion: Zarr store of the underlying sweep (resumable; its parent must exist)."
    ),
    scheduler: Optional[str] = SCHEDULER,
    workers: Optional[int] = typer.Option(
        0, "--workers", help="Damage criterion: local worker processes (default 0: in this process)."
    ),
    chunk: Optional[int] = CHUNK,
    force: bool = typer.Option(False, "--force", help="Replace a store (or unfinished chunks) of another sweep."),
    plot: Optional[str] = typer.Option(None, "--plot", help="Write the fragility curves to this image file."),
    as_json: bool = typer.Option(False, "--json", help="Print one JSON object instead of a table."),
) -> None:
    """Probability that the prototype reaches each damage state against the charge, under uncertain fields,
    with a maximum-likelihood lognormal fit per state (median charge, beta, 95 % profile-likelihood bounds).
    A block: each draw decided by the first-swing energy criterion (docs/capacity.md), vectorised; any
    structure: one Study per draw (3D; on Dask with --workers, resumable with --out), judged by the damage
    states of the scenario's [damage] table (docs/sweeps.md)."""

    check_plot_path(plot)
    base = read_scenario(scenario, values)
    W = parse_grid(charges, "charges")
    given = [f for f, v in (("--out", out), ("--scheduler", scheduler), ("--workers", workers)) if v]
    if given and (criterion or default_criterion(base)) == "first-swing":
        raise BlastscaleInputError(
            f"{', '.join(given)}: the first-swing criterion runs vectorised in this process and writes no store "
            "(a million draws a minute); these options go with --criterion damage"
        )
    if out is not None:
        _resume_note(out)
    bar, tick = count_progress("fragility", quiet=as_json)

    def run(spec):  # the damage criterion's sweep, its size said first
        if not as_json:
            where = f"{workers} workers" if workers else "this process" if scheduler is None else scheduler
            console_err.print(f"fragility: {spec.n_cases} cases, one Study each, on {where}")
        if out is None:
            return run_in_memory(spec, scheduler=scheduler, workers=workers or 0, chunk=chunk, progress=tick)
        run_sweep(spec, out, scheduler=scheduler, workers=workers, chunk=chunk, force=force, progress=tick)
        return open_sweep(out)

    with one_line_warnings(), bar:
        res = fragility(
            base,
            W,
            lognormal=_assignments(lognormal, "--lognormal", _beta),
            uniform=_assignments(uniform, "--uniform", _uniform_range),
            samples=samples,
            seed=seed,
            criterion=criterion,
            run=run,
        )
    out_json = res.to_dict()
    out_json["scenario"] = base.title or "default"
    if plot:
        from ..plots.fragility import plot_fragility
        from ._output import save_figure

        save_figure(lambda: plot_fragility(res).figure, plot)
        out_json["plot"] = plot
    if as_json:
        print_json(out_json, engine="planar" if res.criterion == "first-swing" else "3d")
        return
    _print_fragility(res, samples, seed)
    if out is not None:
        print_written(out, "the underlying sweep")
    if plot:
        print_written(plot)


def _print_fragility(res, samples: int, seed: int) -> None:
    """The counts per charge and state, and each state's lognormal fit."""
    t = Table(title=f"Fragility ({samples} draws per charge, seed {seed}, {res.criterion})", title_justify="left")
    t.add_column("charge W [kg]", justify="right")
    for name in res.states:
        said = "overturns" if res.criterion == "first-swing" else f"reaches {name}"
        t.add_column(f"{said}: n (P)", justify="right")
    t.add_column("draws", justify="right")
    first = next(iter(res.states.values()))
    for j, w in enumerate(res.charge_kg):
        cells = [f"{st.exceeded[j]} ({st.probability[j]:.3f})" for st in res.states.values()]
        t.add_row(f"{w:.6g}", *cells, str(first.trials[j]))
    console.print(t)
    for name, st in res.states.items():
        f = st.fit
        if f is None:
            console.print(f"{name}: no transition in the charge range: no lognormal fit (widen --charges)")
        elif f.beta is None:
            console.print(f"{name}: lognormal fit: not bounded: {f.note}")
        else:
            console.print(
                f"{name}: lognormal fit: median {f.median_charge_kg:.6g} kg (95 %: {f.median_ci_kg[0]:.6g} - "
                f"{f.median_ci_kg[1]:.6g}), beta {f.beta:.4g} (95 %: {f.beta_ci[0]:.4g} - {f.beta_ci[1]:.4g})"
                + (f"; {f.note}" if f.note else "")
            )


@app.command("similarity-map")
def similarity_map_cmd(
    scenario: Optional[Path] = SCENARIO_ARG,
    values: List[str] = SET_VALUES,
    scales: str = typer.Option(
        "0.005,0.01,0.05,0.1,0.5", "--scales", help="lambda values \\[-]: a,b,c or start:stop:n[:log]."
    ),
    density_ratios: str = typer.Option("0.1,0.3,1,3", "--density-ratios", help="gamma values \\[-]."),
    charges: str = typer.Option("50,100", "--charges", help="Prototype charges W \\[kg TNT]."),
    standoffs: str = typer.Option("2,4", "--standoffs", help="Prototype stand-offs R \\[m]."),
    engine: str = typer.Option(
        "planar", "--engine", help="planar (rocking, ~2 ms per case) or 3d (MuJoCo, one Study per case: a coarse grid)."
    ),
    out: Optional[Path] = typer.Option(
        None, "--out", help="Zarr store of the underlying sweep (resumable; its parent folder must exist)."
    ),
    scheduler: Optional[str] = SCHEDULER,
    workers: Optional[int] = typer.Option(0, "--workers", help="Local worker processes (default 0: in this process)."),
    chunk: Optional[int] = CHUNK,
    plot: Optional[str] = typer.Option(None, "--plot", help="Write the map (one panel per charge and stand-off)."),
    as_json: bool = typer.Option(False, "--json", help="Print one JSON object instead of a table."),
) -> None:
    """Where in (lambda, gamma, charge, stand-off) the up-scaled model is trustworthy: the Study's verdict
    (the one criterion, its tolerances the scenario's [verdict] table: --set verdict.peak=0.05; docs/verdict.md),
    its worst ratio, its error against the prototype (planar rocking or 3D) and whether the outcomes agree
    (docs/sweeps.md)."""

    check_plot_path(plot)
    base = read_scenario(scenario, values)
    grids = _map_grids(scales, density_ratios, charges, standoffs)
    bar, tick = count_progress(f"similarity map ({engine})", quiet=as_json)
    if out is not None:
        _resume_note(out)
    with one_line_warnings(), bar:
        run = _map_runner(out, scheduler, workers, chunk, tick)
        ds = similarity_map(base, *grids, engine=engine, run=run)
    res = _map_output(ds, engine)
    add_figure(res, lambda: _map_figure(ds), plot)
    answer(res, as_json=as_json, engine=engine, plot=plot, tables=lambda: _print_map(res, ds, out))


def _map_grids(scales: str, density_ratios: str, charges: str, standoffs: str) -> list:
    """The four axes of the map: lambda, gamma [-], charges [kg TNT], stand-offs [m]."""
    return [
        parse_grid(t, n)
        for t, n in (
            (scales, "scales"),
            (density_ratios, "density-ratios"),
            (charges, "charges"),
            (standoffs, "standoffs"),
        )
    ]


def _map_runner(out: Optional[Path], scheduler: Optional[str], workers: Optional[int], chunk: Optional[int], tick):
    """How the map's sweep runs: in memory, or into the (resumable) store ``out``."""

    def run(spec):
        if out is None:
            return run_in_memory(spec, scheduler=scheduler, workers=workers or 0, chunk=chunk, progress=tick)
        run_sweep(spec, out, scheduler=scheduler, workers=workers, chunk=chunk, progress=tick)
        return open_sweep(out)

    return run


def _map_output(ds, engine: str) -> dict:
    """The ``similarity-map --json`` object: the axes, the counts and each map's values (NaN for invalid)."""
    res = {
        "dims": {k: ds[k].values.tolist() for k in ("length", "density_ratio", "charge_kg", "standoff_m")},
        "engine": engine,
        "tolerances": json.loads(ds.attrs["tolerances"]),
        "error_units": ds.attrs["error_units"],
        "error_definition": legacy_name(ds.attrs["error_definition"]),  # deprecated: the key's old name
        "error_key": ds.attrs["error_definition"],
        "n_cases": int(ds["valid"].size),
        "n_valid": int(ds["valid"].sum()),
        "n_outcomes_agree": int((ds["outcomes_agree"].where(ds["valid"].astype(bool), False).astype(bool)).sum()),
        "n_trustworthy": int(ds["trustworthy"].sum()),
    }
    for name in (
        "error",
        "first_peak_ratio_error",
        "outcomes_agree",
        "trustworthy",
        "worst_ratio",
        "valid",
        "model_to_p",
        "model_charge_kg",
    ):
        v = ds[name].values
        res[name] = np.where(np.isfinite(v.astype(float)), v, np.nan).tolist() if v.dtype.kind == "f" else v.tolist()
    return res


def _map_figure(ds):
    from ..plots.similarity_map import plot_similarity_map

    return plot_similarity_map(ds)


def _print_map(res: dict, ds, out: Optional[Path]) -> None:
    """The map's counts and its largest error; the store written."""
    unit = res["error_units"]
    console.print(
        table(
            f"Similarity map ({res['engine']}, up-scaled model vs prototype)",
            [
                ("cases", str(res["n_cases"]), ""),
                ("valid designs (model Z inside the blast fits)", str(res["n_valid"]), ""),
                ("outcomes agree", str(res["n_outcomes_agree"]), ""),
                ("trustworthy (the verdict: similar; docs/verdict.md)", str(res["n_trustworthy"]), ""),
                ("largest error where valid", f"{float(np.nanmax(ds['error'].values)):.3g}", unit),
            ],
        )
    )
    if out is not None:
        print_written(out, "the underlying sweep")
