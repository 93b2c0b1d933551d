"""``blastscale show``: describe and draw a structure without simulating it.

``blastscale show FILE_OR_SCENARIO [--plot x.png] [--json]`` takes a scenario file (``.toml``), a
shipped scenario's name, or a block-model file (our JSON, COMPAS JSON, a mesh:
:func:`blastscale.structures.read_block_model`), builds the structure (its interfaces found by
geometry) and prints one table: kind, blocks, mass, volume, size, interfaces (between blocks and on
the ground), monitoring points, the blocks' and supports' names. ``--plot`` writes the elevation
and plan with the interfaces shaded (:func:`blastscale.plots.assembly.assembly_figure`),
``--to-compas`` the structure as a compas_dem block model
(:func:`blastscale.structures.compas_files.compas_model_data`), both through the one output mechanism
(:func:`blastscale.io.output.write_file`). A bad file or parameter is one ``error:`` line, exit
status 2, nothing written.

``blastscale show RESULT_DIR --animate FILE.gif|FILE.mp4|FILE.html [--view] [--fps] [--speed] [--magnification]``: the
result folder's stored motion (:mod:`.animate`).
"""

from __future__ import annotations

from pathlib import Path
from typing import Optional

import typer

from .._validate import BlastscaleInputError
from ..scenario.files import load_scenario
from ..structures import from_spec
from ..structures.assembly import as_assembly
from ..structures.base import rest_mass_properties
from ..structures.block_files import MESH_SUFFIXES, read_block_model
from ._app import app
from ._output import console, fmt_value, one_line_warnings, print_json, print_written, save_figure, table
from .options import check_plot_path

__all__ = ["describe_structure", "load_structure"]

_SCENARIO_SUFFIXES = (".toml",)


def load_structure(source: str, density_kg_m3: Optional[float] = None):
    """(structure, scenario or None, standoff [m] or None) of a scenario file or name, or of a
    block-model file."""

    p = Path(source)
    suffix = p.suffix.lower()
    if suffix == ".json" or suffix in MESH_SUFFIXES:
        try:
            there, regular = p.exists() or p.is_symlink(), p.is_file()
        except OSError as exc:  # a name too long
            raise BlastscaleInputError(f"FILE_OR_SCENARIO = {source!r} cannot be read: {exc.strerror}") from None
        if not regular:
            why = "not a regular file (a folder or a device)" if there else "no such file"
            raise BlastscaleInputError(f"FILE_OR_SCENARIO = {source!r} cannot be read: {why}")
        return read_block_model(p, 2000.0 if density_kg_m3 is None else density_kg_m3), None, None
    if p.exists() and suffix not in _SCENARIO_SUFFIXES:
        raise BlastscaleInputError(
            f"FILE_OR_SCENARIO = {source!r} is not a known kind of file: valid suffixes are "
            f".toml (scenario), .json, {', '.join(MESH_SUFFIXES)} (block models)"
        )
    sc = load_scenario(source)
    if density_kg_m3 is not None:
        sc = sc.with_values({"structure.density_kg_m3": density_kg_m3})
    standoff = None if sc.blast.gravity_only else sc.blast.standoff_m
    return from_spec(sc.structure), sc, standoff


def describe_structure(structure) -> dict:
    """The description ``show`` prints (SI keys): kind, blocks, mass, volume, centre of mass at rest,
    height, length, thickness (supports included), interfaces between blocks and on the ground (a support
    is the ground), their area, monitoring points, the blocks' names, the supports (fixed to the ground)
    and their names. Mass, volume and centre of mass are the sums over ``structure.bodies``, the bodies the
    engine simulates; sizes and interfaces are those of their solids (:func:`~blastscale.structures.as_assembly`)."""

    asm = as_assembly(structure)
    rest = rest_mass_properties(structure.bodies)
    d = asm.describe()
    itfs = asm.interface_details
    ground = [i for i in itfs if i.first < 0]
    joints = [i for i in itfs if i.first >= 0]
    pts = [p.name for p in structure.monitoring_points]
    return {
        "kind": str(structure.describe().get("kind", d["kind"])),
        "blocks": len(asm.blocks),
        "mass_kg": rest.mass,
        "volume_m3": rest.volume,
        "centre_of_mass_m": list(rest.centre_of_mass),
        "height_m": d["height_m"],
        "length_m": d["length_m"],
        "thickness_m": d["thickness_m"],
        "density_kg_m3": d["density_kg_m3"],
        "interfaces_between_blocks": len(joints),
        "interfaces_on_ground": len(ground),
        "interface_area_between_blocks_m2": float(sum(i.area for i in joints)),
        "contact_area_on_ground_m2": float(sum(i.area for i in ground)),
        "monitoring_points": len(pts),
        "monitoring_point_names": pts,
        "block_names": [b.name for b in asm.blocks],
        "supports": len(asm.supports),
        "support_names": [b.name for b in asm.supports],
    }


@app.command("show")
def show_cmd(
    source: str = typer.Argument(
        ...,
        metavar="FILE_OR_SCENARIO",
        show_default=False,
        help="A scenario (.toml, or a shipped scenario's name) or a block-model file (.json, "
        ".obj, .stl, .ply, ...; docs/assemblies.md); with --animate, a result folder.",
    ),
    plot: Optional[Path] = typer.Option(
        None, "--plot", show_default=False, help="Write the elevation and plan, interfaces shaded (.png, .svg or .pdf)."
    ),
    density: Optional[float] = typer.Option(
        None,
        "--density",
        show_default=False,
        help="Density \\[kg/m^3] of blocks without their own (default: the scenario's, 2000 for a block-model file).",
    ),
    as_json: bool = typer.Option(False, "--json", help="Print the description as one JSON object."),
    to_compas: Optional[Path] = typer.Option(
        None,
        "--to-compas",
        show_default=False,
        help="Write the structure as a COMPAS (compas_dem) block model (.json; docs/assemblies.md).",
    ),
    animate: Optional[str] = typer.Option(
        None,
        "--animate",
        metavar="FILE.gif|FILE.mp4|FILE.html",
        show_default=False,
        help="With a result folder (blastscale run --out) as the argument: its "
        "3D motion, prototype and up-scaled model side by side.",
    ),
    view: str = typer.Option("iso", "--view", help="--animate's camera: front, side, top or iso."),
    fps: float = typer.Option(20.0, "--fps", help="--animate's frames per second of playback, in [1, 120]."),
    speed: float = typer.Option(1.0, "--speed", help="--animate's playback speed x real (prototype) time."),
    magnification: Optional[float] = typer.Option(
        None,
        "--magnification",
        show_default=False,
        help="--animate's displacement magnification, in [1, 1e4] (default: automatic, the largest motion drawn "
        "as 10 % of the height; stated on the animation).",
    ),
) -> None:
    """Describe and draw a structure (scenario or block-model file) without simulating it; animate a result
    folder's motion (--animate)."""
    if animate is not None:
        from .animate import show_animation

        return show_animation(source, animate, view, fps, speed, as_json, magnification)

    if plot is not None:
        check_plot_path(str(plot))  # before any work
    if to_compas is not None and to_compas.suffix.lower() != ".json":
        raise BlastscaleInputError(f"--to-compas = {str(to_compas)!r} has an unknown type: valid suffix is .json")
    with one_line_warnings():
        structure, sc, standoff = load_structure(source, density)
        desc = describe_structure(structure)
        if plot is not None:
            from ..plots.assembly import assembly_figure, world_points
            from ..structures.assembly import as_assembly

            title = None if sc is None or not sc.title else sc.title
            save_figure(
                lambda: assembly_figure(
                    as_assembly(structure), title=title, standoff_m=standoff, points=world_points(structure)
                ),
                plot,
            )
        if to_compas is not None:
            import json

            from ..io.output import write_file
            from ..structures.assembly import as_assembly
            from ..structures.compas_files import compas_model_data

            write_file(
                to_compas, json.dumps(compas_model_data(as_assembly(structure)), indent=1) + "\n", what="--to-compas"
            )
    if as_json:
        print_json(desc)
    else:
        _print_description(source, desc)
    for written in (plot, to_compas):
        if written is not None:
            print_written(written)


def _print_description(source: str, desc: dict) -> None:
    """The structure's description (:func:`describe_structure`) as a table."""
    names = desc["monitoring_point_names"]
    shown = ", ".join(names[:6]) + (f", ... ({len(names)})" if len(names) > 6 else "")
    rows = [
        ("kind", desc["kind"], ""),
        ("blocks", str(desc["blocks"]), ""),
        ("mass", fmt_value(desc["mass_kg"], ".5g"), "kg"),
        ("volume", fmt_value(desc["volume_m3"], ".5g"), "m^3"),
        ("density", fmt_value(desc["density_kg_m3"], ".5g"), "kg/m^3"),
        ("centre of mass (x, y, z)", ", ".join(fmt_value(x, ".4g") for x in desc["centre_of_mass_m"]), "m"),
        (
            "height x length x thickness",
            " x ".join(fmt_value(desc[k], ".4g") for k in ("height_m", "length_m", "thickness_m")),
            "m",
        ),
        ("interfaces between blocks", str(desc["interfaces_between_blocks"]), ""),
        ("  their area", fmt_value(desc["interface_area_between_blocks_m2"], ".5g"), "m^2"),
        ("interfaces on the ground", str(desc["interfaces_on_ground"]), ""),
        ("  their area", fmt_value(desc["contact_area_on_ground_m2"], ".5g"), "m^2"),
        ("monitoring points", shown, ""),
    ]
    console.print(table(f"Structure: {source}", rows))
