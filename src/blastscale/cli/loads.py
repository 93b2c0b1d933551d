"""``blastscale blast`` and ``blastscale design``: blast parameters and model design."""

from __future__ import annotations

import math
from typing import Optional

import typer
from rich.table import Table

from .._validate import BlastscaleInputError, check_range
from ..blast.faces import face_loads
from ..blast.incidence import DEFAULT_INCIDENCE, INCIDENCE_MODELS, check_incidence
from ..blast.load_model import front_face_clearing, front_face_negative, load_model_record
from ..blast.parameters import DEFAULT_BLAST_MODEL, blast_parameters
from ..similitude.design import design_model
from . import blast_flags as bf
from ._app import app
from ._output import console, fmt_value, one_line_warnings, print_json, styled, table
from .options import MODEL_HELP, block_from_options


@app.command("blast")
def blast_cmd(
    charge: float = typer.Option(..., "--charge", help="TNT-equivalent charge W \\[kg]."),
    standoff: float = typer.Option(..., "--standoff", help="Stand-off distance R \\[m]."),
    blast_model: str = typer.Option(DEFAULT_BLAST_MODEL, "--model", "--blast-model", help=MODEL_HELP),
    extrapolate: bool = typer.Option(False, "--extrapolate", help="Evaluate fits outside their range (warns)."),
    incidence_deg: Optional[float] = typer.Option(
        None,
        "--incidence-deg",
        help="Angle of incidence of a face \\[deg], 0 (facing the charge) to 180: adds the "
        "face's peak pressure and impulse.",
    ),
    incidence: str = typer.Option(
        DEFAULT_INCIDENCE, "--incidence", help=f"Angle-of-incidence model: {' or '.join(INCIDENCE_MODELS)}."
    ),
    burst: str = bf.BURST,
    clearing: bool = bf.CLEARING,
    face_width: Optional[float] = bf.FACE_WIDTH,
    face_height: Optional[float] = bf.FACE_HEIGHT,
    negative_phase: bool = bf.NEGATIVE_PHASE,
    negative_phase_model: Optional[str] = bf.NEGATIVE_PHASE_MODEL,
    as_json: bool = typer.Option(False, "--json", help="Print one JSON object instead of a table."),
) -> None:
    """Blast parameters of a burst of W kg TNT at R m (hemispherical surface burst unless --burst
    free-air; with --clearing and --negative-phase the front face's cleared pulse and suction; SI)."""

    check_incidence(incidence)
    bf.check_burst_flag(burst)
    lm = bf.load_model_from_flags(
        clearing, face_width, face_height, negative_phase, negative_phase_model=negative_phase_model
    )
    with one_line_warnings():
        b = blast_parameters(charge, standoff, blast_model, extrapolate=extrapolate, burst=burst)
        face = (
            None
            if incidence_deg is None
            else oblique_face(charge, standoff, incidence_deg, b.blast_model, incidence, extrapolate)
        )
        cl = front_face_clearing(b, lm)
        i_pos = cl.impulse if cl is not None else b.reflected_impulse
        neg = front_face_negative(b, lm, extrapolate=extrapolate, positive_impulse=i_pos)
    effects = {**(cl.to_dict() if cl is not None else {}), **(neg.to_dict() if neg is not None else {})}
    if neg is not None:  # positive minus suction: >= 0 (the suction is bounded by the positive impulse)
        effects["net_reflected_impulse_Pa_s"] = float(i_pos - neg.impulse)
    if as_json:
        print_json(
            {**b.to_dict(), **(face or {}), **effects, "load_model": load_model_record(b.blast_model, b.burst, lm)}
        )
        return
    rows = [
        ("scaled distance Z", f"{b.scaled_distance:.6g}", "m/kg^(1/3)"),
        ("reflected peak pressure P_ro", f"{b.reflected_pressure:.6g}", "Pa"),
        ("reflected impulse i_ro", f"{b.reflected_impulse:.6g}", "Pa s"),
        ("arrival time t_A", f"{b.arrival_time:.6g}", "s"),
        ("positive duration t_o", f"{b.positive_duration:.6g}", "s"),
        ("incident peak pressure P_so", fmt_value(b.incident_pressure), "Pa"),
        ("incident impulse i_so", fmt_value(b.incident_impulse), "Pa s"),
        ("shock-front velocity U", fmt_value(b.shock_front_velocity), "m/s"),
        ("Friedlander decay d", f"{b.friedlander_decay:.6g}", "-"),
    ]
    if face is not None:
        rows += [
            (f"face at {incidence_deg:g} deg ({incidence}): peak pressure", f"{face['face_pressure_Pa']:.6g}", "Pa"),
            (f"face at {incidence_deg:g} deg ({incidence}): impulse", f"{face['face_impulse_Pa_s']:.6g}", "Pa s"),
        ]
    if cl is not None:
        rows += [
            (f"clearing time t_c ({lm.face_width_m:g} x {lm.face_height_m:g} m face)", f"{cl.clearing_time:.6g}", "s"),
            ("t_c / t_o", f"{cl.clearing_time / b.positive_duration:.6g}", "-"),
            ("cleared impulse (UFC: the smaller of cleared and uncleared)", f"{cl.impulse:.6g}", "Pa s"),
        ]
    if neg is not None:
        rows += [
            ("negative phase: peak suction P_r-", f"{neg.pressure:.6g}", "Pa"),
            ("negative phase: impulse i_r-", f"{neg.impulse:.6g}", "Pa s"),
            ("negative phase: duration t_o-", f"{neg.duration:.6g}", "s"),
            ("net reflected impulse (positive - suction)", f"{effects['net_reflected_impulse_Pa_s']:.6g}", "Pa s"),
        ]
        if neg.bounded:
            rows.append((f"suction impulse bounded by the positive one ({neg.model})", "yes", ""))
    console.print(table(f"Blast: {charge:g} kg TNT at {standoff:g} m ({b.blast_model}, {b.burst} burst)", rows))


def oblique_face(
    charge: float, standoff: float, angle_deg: float, blast_model: str, incidence: str, extrapolate: bool = False
) -> dict:
    """Peak pressure [Pa] and impulse [Pa*s] on a face at ``standoff`` [m] whose outward normal makes
    ``angle_deg`` [deg] (0-180) with the direction to the charge, by the incidence model ``incidence``."""
    a = math.radians(float(check_range("incidence angle", angle_deg, 0.0, 180.0, "deg")))
    f = face_loads(
        charge,
        [0.0, 0.0, 0.0],
        [standoff, 0.0, 0.0],
        [-math.cos(a), math.sin(a), 0.0],
        blast_model=blast_model,
        incidence=incidence,
        extrapolate=extrapolate,
    )
    return {
        "incidence_model": incidence,
        "angle_of_incidence_deg": float(angle_deg),
        "face_pressure_Pa": float(f.pressure),
        "face_impulse_Pa_s": float(f.impulse),
    }


def print_design(d) -> None:
    """Human-readable design tables (prototype vs model, factors, impulsive check)."""
    t = Table(
        title=f"Model design: law {d.law}, lambda = {d.scale:.6g}, gamma = {d.density_ratio:.6g}, "
        f"gravity ratio = {d.gravity_ratio:.6g} ({d.prototype.blast_model})",
        title_justify="left",
    )
    for c in ("quantity", "prototype", "model", "model/prototype", "required", "unit"):
        t.add_column(c, justify="left" if c in ("quantity", "unit") else "right")
    p, m, f = d.prototype, d.specimen, d.factors
    t.add_row("charge W", f"{p.charge_kg:.6g}", f"{m.charge_kg:.6g}", f"{f.charge:.6g}", "", "kg")
    t.add_row("stand-off R", f"{p.standoff_m:.6g}", f"{m.standoff_m:.6g}", f"{d.scale:.6g}", "", "m")
    t.add_row(
        "scaled distance Z",
        f"{p.scaled_distance:.6g}",
        f"{m.scaled_distance:.6g}",
        f"{d.scaled_distance_factor:.6g}",
        "",
        "m/kg^(1/3)",
    )
    t.add_row(
        "reflected pressure",
        f"{p.reflected_pressure:.6g}",
        f"{m.reflected_pressure:.6g}",
        f"{d.pressure_ratio:.6g}",
        f"{f.pressure:.6g}",
        "Pa",
    )
    t.add_row(
        "reflected impulse",
        f"{p.reflected_impulse:.6g}",
        f"{m.reflected_impulse:.6g}",
        f"{d.impulse_ratio:.6g}",
        f"{f.impulse:.6g}",
        "Pa s",
    )
    t.add_row(
        "positive duration",
        f"{p.positive_duration:.6g}",
        f"{m.positive_duration:.6g}",
        f"{d.duration_ratio:.6g}",
        f"{f.time:.6g}",
        "s",
    )
    t.add_row(
        "arrival time",
        f"{p.arrival_time:.6g}",
        f"{m.arrival_time:.6g}",
        f"{m.arrival_time / p.arrival_time:.6g}",
        "",
        "s",
    )
    console.print(t)
    console.print(styled((d.root_note, "dim")))
    ft = table(
        "Scaling factors: model / prototype, each a ratio of like quantities (dimensionless)",
        [(k, fmt_value(v), "-") for k, v in f.to_dict().items()],
    )
    console.print(ft)
    if d.impulsive is not None:
        i = d.impulsive
        verdict = ("impulsive", "green") if i.impulsive else ("NOT impulsive: similarity is not guaranteed", "red")
        console.print(
            styled(
                f"Impulsive check t_o*p: prototype {i.prototype_ratio:.3g}, model {i.model_ratio:.3g} "
                f"(threshold {i.threshold:g}) -> ",
                verdict,
            )
        )
    if d.effects is not None:
        print_effects(d.effects)


def print_effects(e: dict) -> None:
    """The design's blast effects, prototype against model (clearing, negative phase, lab burst)."""
    rows = []
    lm = e["load_model"]
    rows.append(("burst", lm["prototype"]["burst"], lm["model"]["burst"], ""))
    if "clearing" in e:
        c = e["clearing"]
        for label, key, unit in (
            ("clearing time t_c", "clearing_time_s", "s"),
            ("t_c / t_o", "clearing_time_over_positive_duration", "-"),
            ("uncleared impulse", "uncleared_impulse_Pa_s", "Pa s"),
            ("cleared impulse", "cleared_impulse_Pa_s", "Pa s"),
            ("cleared / uncleared", "cleared_over_uncleared_impulse", "-"),
        ):
            rows.append((label, fmt_value(c["prototype"][key]), fmt_value(c["model"][key]), unit))
    if "negative_phase" in e:
        n = e["negative_phase"]
        for label, key, unit in (
            ("negative impulse i_r-", "negative_impulse_Pa_s", "Pa s"),
            ("negative / positive impulse", "negative_over_positive_impulse", "-"),
        ):
            rows.append((label, fmt_value(n["prototype"][key]), fmt_value(n["model"][key]), unit))
    t = Table(title="Blast effects the scaling law does not match (prototype vs model)", title_justify="left")
    for c in ("quantity", "prototype", "model", "unit"):
        t.add_column(c, justify="left" if c in ("quantity", "unit") else "right")
    for r in rows:
        t.add_row(*r)
    console.print(t)
    if "lab_burst" in e:
        lb = e["lab_burst"]
        console.print(
            f"lab charge at {lb['charge_height_m']:.4g} m: {lb['kind']} burst (floor reflection "
            f"{lb['delay_over_positive_duration']:.3g} positive durations after the shock)"
        )


@app.command("design")
def design_cmd(
    charge: float = typer.Option(..., "--charge", help="Prototype TNT-equivalent charge W \\[kg]."),
    standoff: float = typer.Option(..., "--standoff", help="Prototype stand-off R \\[m]."),
    scale: float = typer.Option(..., "--scale", help="Geometric scale lambda = model/prototype \\[-], e.g. 0.005."),
    density_ratio: Optional[float] = typer.Option(
        None, "--density-ratio", help="gamma = rho_model/rho_prototype \\[-] (default 1; imposed by hopkinson-cranz)."
    ),
    gravity_ratio: float = typer.Option(1.0, "--gravity-ratio", help="g_model/g_prototype \\[-]."),
    law: str = typer.Option("general", "--law", help="general (paper Eq. 8) or hopkinson-cranz."),
    blast_model: str = typer.Option(DEFAULT_BLAST_MODEL, "--model", "--blast-model", help=MODEL_HELP),
    height: Optional[float] = typer.Option(None, "--height", help="Prototype block height 2h \\[m]."),
    width: Optional[float] = typer.Option(None, "--width", help="Prototype block width 2b \\[m]."),
    alpha_deg: Optional[float] = typer.Option(None, "--alpha-deg", help="Slenderness angle \\[deg] (with --height)."),
    depth: float = typer.Option(1.0, "--depth", help="Prototype block depth 2w \\[m] (cancels)."),
    density: float = typer.Option(2000.0, "--density", help="Prototype density \\[kg/m^3]."),
    extrapolate: bool = typer.Option(False, "--extrapolate", help="Evaluate fits outside their range (warns)."),
    burst: str = bf.BURST,
    specimen_burst: Optional[str] = bf.SPECIMEN_BURST,
    specimen_charge_height: Optional[float] = bf.SPECIMEN_CHARGE_HEIGHT,
    clearing: bool = bf.CLEARING,
    face_width: Optional[float] = bf.FACE_WIDTH,
    face_height: Optional[float] = bf.FACE_HEIGHT,
    negative_phase: bool = bf.NEGATIVE_PHASE,
    negative_phase_model: Optional[str] = bf.NEGATIVE_PHASE_MODEL,
    as_json: bool = typer.Option(False, "--json", help="Print one JSON object instead of tables."),
) -> None:
    """Design the reduced-scale model: model charge and stand-off, every factor, impulsive check
    (and, with --clearing, --negative-phase or another --specimen-burst, what they do to each system)."""
    block = block_from_options(height, width, alpha_deg, depth, density)
    bf.check_burst_flag(burst)
    bf.check_burst_flag(specimen_burst, "--specimen-burst")
    lm = bf.load_model_from_flags(clearing, face_width, face_height, negative_phase, block, negative_phase_model)
    if density_ratio is None and law == "general":
        density_ratio = 1.0
    face = None if lm is None or not lm.clearing else (lm.face_width_m, lm.face_height_m)
    if specimen_charge_height is not None and face is None and block is None:
        raise BlastscaleInputError(
            "--specimen-charge-height needs the prototype's face: give the block (--height ...) "
            "or --clearing with --face-width and --face-height"
        )
    with one_line_warnings():
        d = design_model(
            charge,
            standoff,
            scale,
            density_ratio,
            gravity_ratio,
            law,
            blast_model,
            block,
            extrapolate=extrapolate,
            burst=burst,
            specimen_burst=specimen_burst,
            load_model=lm,
            face=face,
            specimen_charge_height=specimen_charge_height,
        )
    if as_json:
        print_json(d.to_dict())
    else:
        print_design(d)
