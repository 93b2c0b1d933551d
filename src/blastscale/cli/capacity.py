"""``blastscale critical`` and ``blastscale capacity``: a structure's capacity under blast (docs/capacity.md).

One command for every structure. A block (given by its flags, or a scenario whose structure is a block) is
judged by the first-swing energy criterion after the pulse (planar, exact and fast); any other structure (a
scenario: column, wall, arch, portal, block model), or a block with ``--engine 3d``, by bisection on ensembles
of 3D runs (:mod:`blastscale.sweeps.capacity3d`: the charge at which the collapse probability crosses 50 %,
with its interval).

Units at this edge: lengths in m, density in kg/m^3, charge in kg TNT, the slenderness angle in degrees
(``--alpha-deg``); results are SI (kg, m, Pa, Pa s).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import List, Optional

import numpy as np
import typer
from rich.table import Table

from .. import __version__
from .._validate import BlastscaleInputError
from ..blast.parameters import blast_parameters, model_for_burst
from ..structures.from_spec import from_spec, is_block
from ..study.memory import check_budget
from ..sweeps.grids import parse_grid, parse_number
from . import blast_flags as bf, options as opt
from ._app import app
from ._output import activity, console, fmt_value, one_line_warnings, table
from .flags import SET_VALUES
from .options import check_plot_path
from .rocking import RESTITUTION_HELP, block_inputs
from .steps import BlockFlags, add_figure, answer, read_scenario

SCENARIO_ARG = typer.Argument(
    None,
    help="Scenario TOML file of any structure (a column, a wall, ...: 3D ensembles); without it, the block of the flags.",
)
ENGINE = typer.Option(
    None,
    "--engine",
    help="planar (a block: first-swing criterion) or 3d (any structure: bisection on 3D ensembles); "
    "default: planar for a block, 3d otherwise.",
)
MEMBERS = typer.Option(
    None, "--members", help="3D: ensemble members per probed charge, 1-64 (default: the scenario's, else 4)."
)
BRACKET = typer.Option(
    None,
    "--bracket",
    help="3D: charges LO:HI \\[kg] bracketing the critical charge (default: searched by steps of x2).",
)
TOLERANCE = typer.Option(
    None, "--tolerance", help="3D: relative width of the final bracket HI/LO - 1 \\[-] (default 0.02)."
)
#: The flags that describe a block or its planar load: refused beside a scenario (its keys say them; --set).
_BLOCK_FLAGS = (
    "height",
    "width",
    "alpha_deg",
    "depth",
    "density",
    "pulse_shape",
    "restitution",
    "gravity",
    "blast_model",
    "burst",
    "clearing",
    "negative_phase",
    "negative_phase_model",
    "extrapolate",
)


def opt_extrapolate():
    """The ``--extrapolate`` option of the capacity commands."""
    return typer.Option(
        False, "--extrapolate", help="Search beyond the blast fits' valid range of Z (5x each way; warns)."
    )


@app.command("critical")
def critical_cmd(
    ctx: typer.Context,
    scenario: Optional[Path] = SCENARIO_ARG,
    values: List[str] = SET_VALUES,
    height: float = opt.HEIGHT,
    width: Optional[float] = opt.WIDTH,
    alpha_deg: Optional[float] = opt.ALPHA_DEG,
    depth: float = opt.DEPTH,
    density: float = opt.DENSITY,
    standoff: Optional[float] = typer.Option(None, "--standoff", help="Stand-off R \\[m]: find the critical charge."),
    charge: Optional[float] = typer.Option(
        None, "--charge", help="Charge W \\[kg TNT]: find the critical stand-off instead."
    ),
    pulse_shape: str = opt.PULSE,
    restitution: Optional[float] = typer.Option(
        None, "--restitution", help=RESTITUTION_HELP + " (does not affect the first excursion)"
    ),
    extrapolate: bool = opt_extrapolate(),
    scale: Optional[float] = typer.Option(
        None, "--scale", help="Geometric scale lambda \\[-]: also give the model's charge for the critical scenario."
    ),
    density_ratio: float = opt.DENSITY_RATIO,
    gravity: float = opt.GRAVITY,
    blast_model: str = opt.MODEL,
    burst: str = bf.BURST,
    clearing: bool = bf.CLEARING,
    negative_phase: bool = bf.NEGATIVE_PHASE,
    negative_phase_model: Optional[str] = bf.NEGATIVE_PHASE_MODEL,
    plot: Optional[str] = typer.Option(
        None, "--plot", help="Write the P-I overturning diagram (with the critical point) to this image file."
    ),
    engine: Optional[str] = ENGINE,
    members: Optional[int] = MEMBERS,
    bracket: Optional[str] = BRACKET,
    tolerance: Optional[float] = TOLERANCE,
    as_json: bool = typer.Option(False, "--json", help="Print one JSON object instead of a table."),
) -> None:
    """Critical charge at a stand-off. A block: the largest charge without overturning (or with --charge the
    critical stand-off), by the first-swing energy criterion after the pulse, searched from the structure's own
    scale (any size, lab specimens included). Any structure (a scenario): the charge at which the collapse
    probability (a body fell) crosses 50 %, with its interval, by bisection on 3D ensembles (docs/capacity.md)."""
    from ..analysis.planar import planar_system

    sc = _scenario_of(ctx, scenario, values)
    if _engine_of(sc, engine) == "3d":
        three_d = ThreeD(members, _bracket_of(bracket), tolerance)
        return _critical_3d(sc, standoff, charge, three_d, plot, as_json)
    _planar_only(members, bracket, tolerance)
    given = _PlanarFlags(
        pulse_shape,
        blast_model,
        extrapolate,
        gravity,
        restitution,
        burst,
        clearing,
        negative_phase,
        negative_phase_model,
    )
    block, f = _planar_block(sc, BlockFlags(height, width, alpha_deg, depth, density), plot, given)
    if sc is not None and standoff is None and charge is None:
        standoff = sc.blast.standoff_m
    bf.check_burst_flag(f.burst)
    lm = bf.load_model_from_flags(f.clearing, None, None, f.negative_phase, block, f.negative_phase_model)
    fit = model_for_burst(f.blast_model, f.burst).name
    search = CriticalSearch(f.pulse_shape, f.blast_model, f.burst, fit, f.extrapolate, lm)
    _check_one_target(standoff, charge)
    system = planar_system(block, f.gravity, f.restitution)
    res = _search_critical(system, standoff, charge, search, as_json)
    inputs = block_inputs(block, pulse_shape=f.pulse_shape, blast_model=f.blast_model, gravity_m_s2=f.gravity)
    out = {"inputs": inputs}
    out.update(res.to_dict())
    out["blast_model"] = f.blast_model  # the family asked for; the fit used is in load_model
    bp = blast_parameters(res.charge_kg, res.standoff_m, fit, extrapolate=f.extrapolate)
    out["critical_blast"] = _critical_blast(bp)
    if lm is not None and lm.negative_phase and standoff is not None:
        out["negative_phase_uncertainty"] = _negative_phase_uncertainty(system, standoff, search, as_json)
    out["impulsive_critical_impulse_Pa_s"] = system.critical_impulse
    out["uplift_pressure_Pa"] = system.uplift_pressure
    if scale is not None:
        out["model_experiment"] = _model_experiment(res, block, search, scale, density_ratio, f.gravity)
    if plot:
        add_figure(out, _pi_figure(system, res, bp, f.pulse_shape, as_json), plot)
    answer(
        out, as_json=as_json, engine="planar", plot=plot, tables=lambda: _print_critical(out, res, bp, system, block)
    )


@dataclass(frozen=True)
class _PlanarFlags:
    """A block's planar load and motion, by the flags or by a block scenario's keys that say them: the pulse
    shape, the blast family, whether to search past the fits' range of Z, gravity [m/s^2], the restitution
    [-] (None: the block's impact model), then, for ``critical`` alone, the burst, the clearing, the negative
    phase and its model (None: not a flag of the command)."""

    pulse_shape: str
    blast_model: str
    extrapolate: bool
    gravity: float
    restitution: Optional[float]
    burst: Optional[str] = None
    clearing: Optional[bool] = None
    negative_phase: Optional[bool] = None
    negative_phase_model: Optional[str] = None


def _planar_block(sc, flags: BlockFlags, plot: Optional[str], given: _PlanarFlags) -> tuple:
    """The block and its planar flags (:class:`_PlanarFlags`) of the planar ``critical`` and ``capacity``: without a scenario
    (``sc`` None) the block of the geometry ``flags`` and the flags ``given``; with a block's scenario its
    structure and its keys (they are the flags). The ``--plot`` path is checked either way."""
    if sc is None:
        return flags.block(plot), given
    check_plot_path(plot)
    bl, sim = sc.blast, sc.simulation
    from_keys = _PlanarFlags(
        bl.pulse_shape,
        bl.blast_model,
        bl.extrapolate,
        sim.gravity_m_s2,
        sim.restitution,
        bl.burst,
        bl.clearing,
        bl.negative_phase,
        bl.negative_phase_model if bl.negative_phase else None,
    )
    return from_spec(sc.structure), from_keys


@dataclass(frozen=True)
class CriticalSearch:
    """What a critical search runs with: the pulse shape, the blast family asked for and its burst, the fit
    used (the family's fit for that burst), whether to search past the fits' range of Z, and the load model
    (None: the reflected pulse alone)."""

    pulse_shape: str
    blast_model: str
    burst: str
    fit: str
    extrapolate: bool
    load_model: object = None

    def kw(self) -> dict:
        """The keywords of the rocking package's critical searches."""
        return {"pulse_shape": self.pulse_shape, "blast_model": self.fit, "extrapolate": self.extrapolate}


def _check_one_target(standoff: Optional[float], charge: Optional[float]) -> None:
    if (standoff is None) == (charge is None):
        raise BlastscaleInputError(
            f"standoff = {standoff}, charge = {charge}: give exactly one of --standoff (m, finds the critical charge) "
            "or --charge (kg, finds the critical stand-off)"
        )


def _search_critical(system, standoff: Optional[float], charge: Optional[float], search: CriticalSearch, quiet: bool):
    """The critical charge at ``standoff`` [m], or the critical stand-off of ``charge`` [kg]."""
    from ..analysis.planar import critical_of

    with one_line_warnings(), activity("searching the critical scenario", quiet=quiet):
        return critical_of(system, standoff=standoff, charge=charge, **search.kw(), load_model=search.load_model)


def _critical_blast(bp) -> dict:
    """The blast at the critical point: scaled distance [m/kg^(1/3)], reflected pressure [Pa] and impulse
    [Pa s], positive-phase duration [s]."""
    return {
        "scaled_distance_m_per_kg13": bp.scaled_distance,
        "reflected_pressure_Pa": bp.reflected_pressure,
        "reflected_impulse_Pa_s": bp.reflected_impulse,
        "positive_duration_s": bp.positive_duration,
    }


def _negative_phase_uncertainty(system, standoff: float, search: CriticalSearch, quiet: bool) -> dict:
    """The critical charge at ``standoff`` [m] under each negative-phase model."""
    from ..analysis.planar import negative_phase_uncertainty_of

    with one_line_warnings(), activity("the critical charge under each negative-phase model", quiet=quiet):
        return negative_phase_uncertainty_of(system, standoff, search.load_model, **search.kw())


def _model_experiment(res, block, search: CriticalSearch, scale: float, density_ratio: float, gravity: float) -> dict:
    """The model's charge for the critical scenario, designed by the general law at ``scale``."""
    from ..similitude.design import design_model

    with one_line_warnings():
        d = design_model(
            res.charge_kg,
            res.standoff_m,
            scale,
            density_ratio,
            blast_model=search.blast_model,
            geometry=block,
            gravity=gravity,
            extrapolate=search.extrapolate,
            burst=search.burst,
            load_model=search.load_model,
        )
    return {
        "scale": scale,
        "density_ratio": density_ratio,
        "critical_charge_kg": d.specimen_charge_kg,
        "standoff_m": d.specimen_standoff_m,
    }


def _pi_figure(system, res, bp, pulse_shape: str, quiet: bool):
    """The P-I overturning diagram's figure (a function that builds it), with the critical point."""
    from ..analysis.planar import pi_diagram_of
    from ..plots.rocking import plot_pi_diagram

    with activity("computing the P-I diagram", quiet=quiet):
        # the curve for the pulse shape searched (impulsive: the triangular curve, whose
        # high-pressure end is the impulsive limit)
        if pulse_shape == "friedlander":
            pi = pi_diagram_of(system, n=30, shape="friedlander", decay=bp.pulse("friedlander").decay)
        else:
            pi = pi_diagram_of(system, n=30)

    def build():
        import matplotlib.pyplot as plt

        fig, ax = plt.subplots(figsize=(6, 4.5), layout="constrained")
        plot_pi_diagram(pi, ax=ax)
        ax.plot(
            [bp.reflected_impulse],
            [bp.reflected_pressure],
            "o",
            color="C3",
            label=f"critical: {res.charge_kg:.4g} kg at {res.standoff_m:.4g} m",
        )
        ax.legend(fontsize=8)
        return fig

    return build


def _print_critical(out: dict, res, bp, system, block) -> None:
    """The critical scenario's table."""
    key, unit = ("critical_charge_kg", "kg") if res.searched == "charge" else ("critical_standoff_m", "m")
    rows = [
        (key.replace("_kg", "").replace("_m", "").replace("_", " "), f"{out[key]:.6g}", unit),
        ("charge W", f"{res.charge_kg:.6g}", "kg"),
        ("stand-off R", f"{res.standoff_m:.6g}", "m"),
        ("scaled distance Z", f"{bp.scaled_distance:.6g}", "m/kg^(1/3)"),
        ("reflected impulse at the critical point", f"{bp.reflected_impulse:.6g}", "Pa s"),
        ("impulsive-limit critical impulse", f"{system.critical_impulse:.6g}", "Pa s"),
        ("simulations", str(res.evaluations), ""),
    ]
    me = out.get("model_experiment")
    if me is not None:
        rows.append((f"model charge (lambda = {me['scale']:g})", f"{me['critical_charge_kg']:.6g}", "kg"))
    for m, v in out.get("negative_phase_uncertainty", {}).items():
        if isinstance(v, dict):  # the model uncertainty of the suction
            rows.append(
                (
                    f"critical charge, negative phase {m}",
                    f"{v['critical_charge_kg']:.6g} (x{v['over_positive_phase_only']:.3g})",
                    "kg",
                )
            )
    i = out["inputs"]
    console.print(
        table(
            f"Critical scenario: {block.height:g} x {block.width:.4g} m block ({i['blast_model']}, {i['pulse_shape']})",
            rows,
        )
    )


@app.command("capacity")
def capacity_cmd(
    ctx: typer.Context,
    scenario: Optional[Path] = SCENARIO_ARG,
    values: List[str] = SET_VALUES,
    height: float = opt.HEIGHT,
    width: Optional[float] = opt.WIDTH,
    alpha_deg: Optional[float] = opt.ALPHA_DEG,
    depth: float = opt.DEPTH,
    density: float = opt.DENSITY,
    standoffs: str = typer.Option(
        "1:20:40:log",
        "--standoffs",
        help='Stand-offs R \\[m]: "a,b,c" or "start:stop:n" (":log" for geometric spacing).',
    ),
    charge: Optional[float] = typer.Option(
        None, "--charge", help="Charge W \\[kg TNT]: also give its safe (critical) stand-off."
    ),
    pulse_shape: str = opt.PULSE,
    restitution: Optional[float] = typer.Option(None, "--restitution", help=RESTITUTION_HELP),
    scale: Optional[float] = typer.Option(
        None, "--scale", help="Geometric scale lambda \\[-]: also the model's curve, up-scaled."
    ),
    density_ratio: float = opt.DENSITY_RATIO,
    gravity_ratio: float = opt.GRAVITY_RATIO,
    gravity: float = opt.GRAVITY,
    blast_model: str = opt.MODEL,
    extrapolate: bool = opt_extrapolate(),
    plot: Optional[str] = typer.Option(None, "--plot", help="Write the capacity curve W_c(R) to this image file."),
    engine: Optional[str] = ENGINE,
    members: Optional[int] = MEMBERS,
    bracket: Optional[str] = BRACKET,
    tolerance: Optional[float] = TOLERANCE,
    as_json: bool = opt.JSON,
) -> None:
    """Capacity curve: the critical charge W_c(R) at every stand-off and, with --charge, the safe
    stand-off of that charge; with --scale also the reduced-scale model's curve, up-scaled to
    prototype charges (paper Eq. 8). A block: first-swing energy criterion, all stand-offs at once. Any
    structure (a scenario): W_c(R) with its interval by bisection on 3D ensembles, all stand-offs in parallel,
    and the pressure-impulse diagram (docs/capacity.md)."""

    from ..analysis.planar import planar_system

    sc = _scenario_of(ctx, scenario, values)
    R = _standoff_grid(standoffs, charge)
    if _engine_of(sc, engine) == "3d":
        if charge is not None or scale is not None:
            raise BlastscaleInputError(
                "--charge and --scale apply to a block's planar capacity: the 3D capacity gives W_c(R) and the P-I diagram"
            )
        return _capacity_3d(sc, R, ThreeD(members, _bracket_of(bracket), tolerance), plot, as_json)
    _planar_only(members, bracket, tolerance)
    given = _PlanarFlags(pulse_shape, blast_model, extrapolate, gravity, restitution)
    block, f = _planar_block(sc, BlockFlags(height, width, alpha_deg, depth, density), plot, given)
    system = planar_system(block, f.gravity, f.restitution)
    kw = dict(pulse_shape=f.pulse_shape, blast_model=f.blast_model, extrapolate=f.extrapolate)
    model = None if scale is None else (scale, density_ratio, gravity_ratio)
    run = _run_capacity(system, R, kw, model, charge, as_json)
    out = {
        "inputs": block_inputs(
            block,
            pulse_shape=f.pulse_shape,
            blast_model=f.blast_model,
            gravity_m_s2=f.gravity,
            restitution=f.restitution,
            extrapolate=f.extrapolate,
        ),
        "blastscale_version": __version__,
        "method": "first-swing energy criterion after the pulse (docs/capacity.md)",
    }
    out.update(run.to_dict(charge))
    add_figure(out, lambda: _capacity_figure(run, charge), plot)
    answer(out, as_json=as_json, engine="planar", plot=plot, tables=lambda: _print_capacity(out, block, R, run, charge))


@dataclass(frozen=True)
class CapacityRun:
    """The capacity curves: the prototype's, the model's (None without ``--scale``) and the safe stand-off
    [m] of ``--charge`` (None without it)."""

    curve: object
    model: object = None
    safe_standoff_m: Optional[float] = None

    def to_dict(self, charge: Optional[float]) -> dict:
        """The curve's keys, then ``model`` (with the largest relative difference of its up-scaled critical
        charges) and ``safe_standoff``, each when computed."""
        out = self.curve.to_dict()
        if self.model is not None:
            out["model"] = self.model.to_dict()
            ratio = self.model.upscaled_charge_kg / self.curve.critical_charge_kg
            out["model"]["max_abs_relative_difference"] = (
                float(np.nanmax(np.abs(ratio - 1.0))) if np.any(np.isfinite(ratio)) else None
            )
        if charge is not None:
            out["safe_standoff"] = {"charge_kg": charge, "standoff_m": self.safe_standoff_m}
        return out


def _standoff_grid(standoffs: str, charge: Optional[float]) -> np.ndarray:
    """The stand-offs [m] of ``--standoffs``, each > 0; ``--charge`` checked too (> 0 kg)."""
    R = parse_grid(standoffs, "standoffs")
    if np.any(R <= 0):
        raise BlastscaleInputError(f"standoffs = {standoffs!r} is out of range: every stand-off must be > 0 m")
    if charge is not None and not charge > 0:
        raise BlastscaleInputError(f"charge = {charge:g} kg is out of range: must be > 0 kg")
    return R


def _run_capacity(system, R: np.ndarray, kw: dict, model, charge: Optional[float], quiet: bool) -> CapacityRun:
    """The capacity curve at the stand-offs ``R`` [m]; with ``model`` = (lambda, gamma, gravity ratio) the
    model's, up-scaled; with ``charge`` [kg] its safe stand-off. The budget is checked first."""
    from ..analysis.capacity import model_capacity_curve
    from ..analysis.planar import capacity_of, critical_of

    per = 5e-4 * (2 if model is not None else 1)  # ~0.4-0.5 ms per stand-off (README "Speed"), x2 with the model
    check_budget("--standoffs", R.size, "stand-offs", R.size * 8.0 * 40, R.size * per)
    with one_line_warnings(), activity(f"capacity at {R.size} stand-offs", quiet=quiet):
        curve = capacity_of(system, R, **kw)
        mcap = None
        if model is not None:
            mcap = model_capacity_curve(system, R, *model, **kw)
        safe = None
        if charge is not None:
            safe = critical_of(system, charge=charge, **kw).standoff_m
    return CapacityRun(curve, mcap, safe)


def _capacity_figure(run: CapacityRun, charge: Optional[float]):
    from ..plots.capacity import plot_capacity

    return plot_capacity(run.curve, run.model, charge=charge, safe_standoff=run.safe_standoff_m).figure


def _print_capacity(out: dict, block, R: np.ndarray, run: CapacityRun, charge: Optional[float]) -> None:
    """The table of critical charges per stand-off (and the model's), the time per stand-off, the safe
    stand-off."""
    mcap, i = run.model, out["inputs"]
    t = Table(
        title=f"Capacity: {block.height:g} x {block.width:.4g} m block ({i['blast_model']}, {i['pulse_shape']})",
        title_justify="left",
    )
    t.add_column("stand-off R [m]", justify="right")
    t.add_column("critical charge W_c [kg]", justify="right")
    if mcap is not None:
        t.add_column(f"model R [m] (lambda = {mcap.scale:g})", justify="right")
        t.add_column("model W_c [kg]", justify="right")
        t.add_column("up-scaled W_c [kg]", justify="right")
    for k in range(R.size):
        row = [f"{R[k]:.6g}", fmt_value(out["critical_charge_kg"][k], ".6g")]
        if mcap is not None:
            row += [
                f"{mcap.curve.standoff_m[k]:.6g}",
                fmt_value(out["model"]["critical_charge_kg"][k], ".6g"),
                fmt_value(out["model"]["upscaled_critical_charge_kg"][k], ".6g"),
            ]
        t.add_row(*row)
    console.print(t)
    console.print(f"{run.curve.seconds_per_case * 1e3:.3g} ms per stand-off")
    if charge is not None:
        console.print(
            f"safe stand-off for {charge:g} kg: {run.safe_standoff_m:.6g} m (it overturns the block closer than that)"
        )


# any structure: 3D ensembles -------------------------------------------------------------------------------


@dataclass(frozen=True)
class ThreeD:
    """The 3D search's flags: ``--members``, ``--bracket`` (LO, HI) [kg], ``--tolerance`` [-] (None: defaults)."""

    members: Optional[int] = None
    bracket: Optional[tuple] = None
    tolerance: Optional[float] = None

    def kw(self) -> dict:
        """The keywords of :func:`~blastscale.sweeps.capacity3d.critical_charges_3d` given."""
        return {
            k: v
            for k, v in (("members", self.members), ("bracket", self.bracket), ("tolerance", self.tolerance))
            if v is not None
        }


def _scenario_of(ctx: typer.Context, scenario: Optional[Path], values: List[str]):
    """The scenario of the argument with its ``--set`` values (None: the block of the flags); beside a scenario the
    block's flags are refused (its keys say them)."""
    if scenario is None:
        if values:
            raise BlastscaleInputError("--set applies to a scenario: give the scenario file (SCENARIO.toml)")
        return None
    # by the source's name: typer vendors its own click (typer._click), whose enum is not click's
    given = [n for n in _BLOCK_FLAGS if getattr(ctx.get_parameter_source(n), "name", "") == "COMMANDLINE"]
    if given:
        flag = "--" + given[0].replace("_", "-")
        raise BlastscaleInputError(
            f"{flag} describes the block of the flags: with a scenario, set its key instead (--set KEY=VALUE)"
        )
    return read_scenario(scenario, values)


def _engine_of(sc, engine: Optional[str]) -> str:
    """ "planar" or "3d": ``--engine``, else planar for a block (of the flags or a scenario's) and 3d otherwise."""
    if engine is not None and engine not in ("planar", "3d"):
        raise BlastscaleInputError(f"engine = {engine!r} is not known: valid values are planar, 3d")
    block = sc is None or is_block(from_spec(sc.structure))
    if engine == "3d" and sc is None:
        raise BlastscaleInputError("--engine 3d needs a scenario (SCENARIO.toml): its structure, contact and duration")
    if engine == "planar" and not block:
        raise BlastscaleInputError(
            f"engine = 'planar' applies to a single block: structure.kind = {sc.structure.kind!r} runs in 3D (--engine 3d)"
        )
    return engine or ("planar" if block else "3d")


def _planar_only(members, bracket, tolerance) -> None:
    """Refuse the 3D search's flags on the planar path (they would be ignored)."""
    for flag, v in (("--members", members), ("--bracket", bracket), ("--tolerance", tolerance)):
        if v is not None:
            raise BlastscaleInputError(
                f"{flag} = {v}: applies to the 3D search (a scenario's structure other than a block, or --engine 3d); "
                "a block's first-swing search needs none"
            )


def _bracket_of(text: Optional[str]) -> Optional[tuple]:
    """``--bracket LO:HI`` as (LO, HI) [kg]."""
    if text is None:
        return None
    lo, sep, hi = text.partition(":")
    if not sep:
        raise BlastscaleInputError(f"bracket = {text!r} is not LO:HI (charges in kg)")
    return parse_number(lo, "bracket", "LO"), parse_number(hi, "bracket", "HI")


def _inputs_3d(sc, three_d: ThreeD) -> dict:
    """The ``inputs`` record of a 3D capacity: the scenario, its structure and the search's settings."""
    from ..sweeps.capacity3d import DEFAULT_TOLERANCE, members_of

    sim, bl = sc.simulation, sc.blast
    return {
        "scenario": sc.title or "untitled",
        "structure_kind": sc.structure.kind,
        "members": members_of(sc, three_d.members),
        "perturbation": sim.ensemble_perturbation,
        "tolerance": DEFAULT_TOLERANCE if three_d.tolerance is None else three_d.tolerance,
        "duration_s": sim.duration_s,
        "blast_model": bl.blast_model,
        "burst": bl.burst,
        "pulse_shape": bl.pulse_shape,
        "load_method": bl.load,
    }


METHOD_3D = (
    "3D ensembles: the charge at which the collapse probability (a body fell) crosses 50 %, by bisection in ln W "
    "with a lognormal fit of the probes (docs/capacity.md)"
)


def _run_3d(sc, R: np.ndarray, three_d: ThreeD, quiet: bool) -> tuple:
    """The 3D critical charges at the stand-offs ``R`` [m], under one activity line."""
    from ..sweeps.capacity3d import DEFAULT_TOLERANCE, critical_charges_3d, members_of, planned_probes

    n = len(R)
    tol = DEFAULT_TOLERANCE if three_d.tolerance is None else three_d.tolerance
    runs = n * planned_probes(three_d.bracket, tol) * members_of(sc, three_d.members)
    size = f"{'' if three_d.bracket else 'at least '}{runs} 3D runs of {sc.simulation.duration_s:g} s"
    with one_line_warnings(), activity(f"3D critical charge at {n} stand-off{'s' * (n > 1)}: {size}", quiet=quiet):
        return critical_charges_3d(sc, R, **three_d.kw())


def _critical_3d(sc, standoff: Optional[float], charge: Optional[float], three_d: ThreeD, plot, quiet: bool) -> None:
    """``critical`` of any structure in 3D (module docstring)."""
    if charge is not None:
        raise BlastscaleInputError(
            "--charge (the critical stand-off) is a block's planar search: in 3D give --standoff (or the scenario's)"
        )
    check_plot_path(plot)
    R = sc.blast.standoff_m if standoff is None else float(standoff)
    (res,) = _run_3d(sc, np.array([R]), three_d, quiet)
    out = {"inputs": _inputs_3d(sc, three_d), "method": METHOD_3D, **res.to_dict()}
    if res.critical_charge_kg is not None:
        bl = sc.blast
        bp = blast_parameters(
            res.critical_charge_kg, R, model_for_burst(bl.blast_model, bl.burst).name, extrapolate=bl.extrapolate
        )
        out["critical_blast"] = _critical_blast(bp)
    add_figure(out, lambda: _capacity_3d_figure(sc, (res,)), plot)
    answer(out, as_json=quiet, engine="3d", plot=plot, tables=lambda: _print_3d(sc, (res,)))


def _capacity_3d(sc, R: np.ndarray, three_d: ThreeD, plot, quiet: bool) -> None:
    """``capacity`` of any structure in 3D: W_c(R) with intervals, and the P-I points (module docstring)."""
    from ..sweeps.capacity3d import pressure_impulse_points

    check_plot_path(plot)
    res = _run_3d(sc, R, three_d, quiet)
    out = {
        "inputs": _inputs_3d(sc, three_d),
        "blastscale_version": __version__,
        "method": METHOD_3D,
        "standoff_m": [float(r) for r in R],
        "critical_charge_kg": [c.critical_charge_kg for c in res],
        "interval_kg": [None if c.interval_kg is None else list(c.interval_kg) for c in res],
        "pressure_impulse": pressure_impulse_points(sc, res),
        "searches": [c.to_dict() for c in res],
    }
    add_figure(out, lambda: _capacity_3d_figure(sc, res), plot)
    answer(out, as_json=quiet, engine="3d", plot=plot, tables=lambda: _print_3d(sc, res))


def _capacity_3d_figure(sc, res):
    from ..plots.capacity import plot_capacity_3d
    from ..sweeps.capacity3d import pressure_impulse_points

    return plot_capacity_3d(res, pressure_impulse_points(sc, res)).figure


def _print_3d(sc, res) -> None:
    """The table of the 3D critical charges: per stand-off the charge, its interval and basis, the runs."""
    t = Table(
        title=f"3D critical charge: {sc.title or sc.structure.kind} (collapse probability crosses 50 %)",
        title_justify="left",
    )
    for c in ("stand-off R [m]", "critical charge W_c [kg]", "interval [kg]", "interval from", "3D runs"):
        t.add_column(c, justify="right")
    for c in res:
        iv = "-" if c.interval_kg is None else f"{c.interval_kg[0]:.5g} - {c.interval_kg[1]:.5g}"
        t.add_row(
            f"{c.standoff_m:.6g}", fmt_value(c.critical_charge_kg, ".6g"), iv, c.interval_basis or "-", str(c.runs)
        )
    console.print(t)
    for c in res:
        if c.note:
            console.print(f"R = {c.standoff_m:g} m: {c.note}")
