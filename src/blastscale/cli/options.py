"""Command-line options shared by several commands, and the geometry / output-path checks.

One ``typer.Option`` object may serve several commands. Help texts write units as ``\\[m]``:
rich would otherwise read ``[m]`` as markup and drop it from ``--help``.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Optional

import typer

from .._validate import BlastscaleInputError
from ..blast.parameters import DEFAULT_BLAST_MODEL
from ..constants import STANDARD_GRAVITY
from ..scenario.specs import SimulationSpec
from ..structures.block import RectangularBlock

#: The scenario schema's simulation settings: the CLI's defaults are the scenario's (one default per setting).
_SIMULATION = SimulationSpec.model_fields

MODEL_HELP = "Blast model: kingery-bulmash (Swisdak 1994, default) or masi2021 (the paper's Appendix A fits)."


def block_from_options(
    height: Optional[float],
    width: Optional[float],
    alpha_deg: Optional[float],
    depth: float,
    density: float,
    required: bool = False,
) -> Optional[RectangularBlock]:
    """The prototype block from CLI options (m, deg, kg/m^3), or None when no geometry is given
    (an error instead when ``required``).

    Accepts ``--height`` with ``--width``, or ``--height`` with ``--alpha-deg`` (width = height tan alpha).
    """
    if (required or height is not None) and width is None and alpha_deg is None:
        raise BlastscaleInputError(
            "--width and --alpha-deg are missing: give one of them (the block's width in m, "
            "or its slenderness in deg, in (0, 90))"
        )
    if height is None and width is None and alpha_deg is None:
        return None
    if width is not None and alpha_deg is not None:
        raise BlastscaleInputError(
            f"--width {width:g} and --alpha-deg {alpha_deg:g} are both given: give exactly "
            "one of them (width = height tan alpha)"
        )
    if alpha_deg is not None and not (0.0 < alpha_deg < 90.0):
        raise BlastscaleInputError(f"--alpha-deg = {alpha_deg:g} deg is out of range: valid range is (0, 90) deg")
    if height is None:
        raise BlastscaleInputError(
            f"--height is missing: give the block's height (m) with {'--width' if width is not None else '--alpha-deg'}"
        )
    if width is not None:
        return RectangularBlock(height=height, width=width, depth=depth, density=density)
    return RectangularBlock.from_slenderness(height, math.radians(alpha_deg), depth=depth, density=density)


#: Image formats a --plot file may have (matplotlib's common writers).
PLOT_SUFFIXES = (".png", ".pdf", ".svg", ".jpg", ".jpeg", ".eps", ".ps", ".tif", ".tiff", ".webp")


def check_plot_path(plot: Optional[str]) -> None:
    """Fail before a (long) computation when the figure cannot be written where the command says
    it is: the folder must exist, the path must not be a folder, and it must name an image file
    (matplotlib would otherwise write ``PLOT.png`` while the command reports ``PLOT``)."""
    if plot:
        from ..io.targets import check_name_lengths

        p = Path(plot).expanduser()
        check_name_lengths(p, "plot")
        if p.is_dir():
            raise BlastscaleInputError(f"plot = {plot!r} is a folder: give an image file, e.g. {str(p / 'plot.png')!r}")
        if p.suffix.lower() not in PLOT_SUFFIXES:
            raise BlastscaleInputError(
                f"plot = {plot!r} has no image extension: valid extensions are {', '.join(PLOT_SUFFIXES)} "
                f"(e.g. {plot}.png)"
            )
        from ..io.targets import Kind, check_target

        check_target(p, Kind("an image", lambda q: True, folder=False), name="plot")  # missing folder, a file


PULSE_HELP = "Pulse shape: friedlander (paper Eq. 1), triangular (Eq. 3) or impulsive (Dirac of the same impulse)."

# the block, scenario and output options shared by rock, critical and block3d
HEIGHT = typer.Option(10.0, "--height", help="Block height 2h \\[m].")
WIDTH = typer.Option(None, "--width", help="Block width 2b along the blast \\[m].")
ALPHA_DEG = typer.Option(None, "--alpha-deg", help="Slenderness angle \\[deg], in (0, 90) (instead of --width).")
DEPTH = typer.Option(
    1.0, "--depth", help="Block depth 2w across the blast \\[m] (it cancels out of the planar response)."
)
DENSITY = typer.Option(2000.0, "--density", help="Density rho \\[kg/m^3].")
CHARGE = typer.Option(..., "--charge", help="Prototype TNT-equivalent charge W \\[kg].")
STANDOFF = typer.Option(..., "--standoff", help="Prototype stand-off R \\[m].")
DURATION = typer.Option(
    _SIMULATION["duration_s"].default, "--duration", help="Simulated time after the shock arrival \\[s] (prototype)."
)
PULSE = typer.Option("friedlander", "--pulse", "--pulse-shape", help=PULSE_HELP)
SCALE = typer.Option(
    None, "--scale", help="Geometric scale lambda \\[-] (0.005 or 1/200): also design, run and up-scale the model."
)
DENSITY_RATIO = typer.Option(1.0, "--density-ratio", help="gamma = rho_model / rho_prototype \\[-].")
GRAVITY_RATIO = typer.Option(1.0, "--gravity-ratio", help="varsigma = g_model / g_prototype \\[-] (centrifuge).")
GRAVITY = typer.Option(STANDARD_GRAVITY, "--gravity", help="Prototype gravity g \\[m/s^2].")
MODEL = typer.Option(DEFAULT_BLAST_MODEL, "--model", "--blast-model", help=MODEL_HELP)
JSON = typer.Option(False, "--json", help="Print one JSON object instead of tables.")


# the options of the 3D commands (block3d, column) whose defaults are the scenario's
# (blastscale.scenario): None when not given, so that the scenario's default applies
def scenario_default(table: str, key: str):
    """The scenario schema's default of ``[table] key`` (for a help text)."""
    from ..scenario.specs import BlastSpec, SimulationSpec
    from ..scenario.structure_specs import KINDS

    model = {"blast": BlastSpec, "simulation": SimulationSpec}.get(table) or KINDS[table]
    return model.model_fields[key].default


LOAD = typer.Option(
    None,
    "--load",
    help="Load method: A (the paper's Method A: uniform, simultaneous reflected pulse on "
    "the front faces); B, C: per-face distance, arrival and incidence "
    f"(docs/face_loads.md). Default {scenario_default('blast', 'load')}.",
)
INCIDENCE = typer.Option(
    None,
    "--incidence",
    help="Angle-of-incidence model of loads B and C (default "
    f"{scenario_default('blast', 'incidence')}; see "
    "blastscale.blast.incidence).",
)
MODEL_3D = typer.Option(None, "--model", "--blast-model", help=MODEL_HELP)
PULSE_3D = typer.Option(
    None, "--pulse", "--pulse-shape", help=f"{PULSE_HELP} Default {scenario_default('blast', 'pulse_shape')}."
)
DURATION_3D = typer.Option(
    None,
    "--duration",
    help="Simulated time after the shock arrival \\[s] (prototype; default "
    f"{scenario_default('simulation', 'duration_s'):g} s, the "
    "scenario's).",
)
FRICTION_3D = typer.Option(
    None,
    "--friction",
    help="Coulomb friction coefficient mu \\[-] at every contact (default "
    f"{scenario_default('block', 'friction'):g} = tan 35 deg, the "
    "paper's).",
)
THREADS = typer.Option(
    None,
    "--threads",
    min=1,
    help="Threads of one process: 3D runs in flight at once "
    "(ensemble members, the 3D cases of a sweep chunk), planar "
    "batches (outcome mode, fragility) split over them (default: "
    "the cores this process may use, divided by the local Dask "
    "workers). Results do not depend on it.",
)
RECORD_EVERY = typer.Option(
    None,
    "--record-every",
    help="Keep one state every N steps (default: one state per "
    "millisecond of the 10 m reference structure, 5 steps for a "
    "block and 4 for a drum stack, at any size).",
)
