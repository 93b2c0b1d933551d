"""The steps the simulating commands share: read a scenario with its ``--set`` overrides, turn a block's and a
3D blast's flags into scenario keys, run a checked 3D study under its progress bar, write a figure, claim a
result folder and answer (one JSON object, or the tables and the written files).

Each command's body is then its own steps in order: parse the flags, build the scenario, run, print.
"""

from __future__ import annotations

import contextlib
from dataclasses import dataclass
from typing import Callable, Iterator, Optional

from ..io.results import output_folder
from ..scenario.files import load_scenario
from ..scenario.scenario import Scenario
from ..study.study import Study
from ._output import (
    console,
    console_err,
    one_line_warnings,
    print_json,
    print_written,
    save_figure,
    stage_progress,
    table,
)
from ._progress import announce_run
from ._signals import ignore_interrupts, raise_if_interrupted
from .flags import flags_named, scenario_with
from .options import block_from_options, check_plot_path

#: The title of the table that compares the prototype with the up-scaled model.
SIMILARITY_TITLE = "Similarity (prototype vs up-scaled model)"


@dataclass(frozen=True)
class BlockFlags:
    """A block's geometry flags: ``--height`` [m] with ``--width`` [m] or ``--alpha-deg`` [deg], ``--depth``
    [m], ``--density`` [kg/m^3]."""

    height: float
    width: Optional[float]
    alpha_deg: Optional[float]
    depth: float
    density: float

    def block(self, plot: Optional[str] = None):
        """The checked :class:`~blastscale.structures.RectangularBlock`; ``plot``, a ``--plot`` path, checked
        too (before any long computation)."""
        block = block_from_options(self.height, self.width, self.alpha_deg, self.depth, self.density, required=True)
        check_plot_path(plot)
        return block

    def structure_keys(self, **extra) -> dict:
        """The scenario's ``[structure]`` keys of these flags (a block), then ``extra``."""
        return {
            "kind": "block",
            "height_m": self.height,
            "width_m": self.width,
            "alpha_deg": self.alpha_deg,
            "depth_m": self.depth,
            "density_kg_m3": self.density,
            **extra,
        }


def blast_keys_3d(
    charge: float,
    standoff: float,
    blast_model: Optional[str],
    pulse_shape: Optional[str],
    load: Optional[str],
    incidence: Optional[str],
) -> dict:
    """The scenario's ``[blast]`` keys of the 3D commands' flags: ``--charge`` [kg TNT], ``--standoff`` [m],
    ``--model``, ``--pulse``, ``--load`` (A, B, C) and ``--incidence`` (None: the scenario's defaults)."""
    return dict(
        charge_kg=charge,
        standoff_m=standoff,
        blast_model=blast_model,
        pulse_shape=pulse_shape,
        load=load,
        incidence=incidence,
    )


def scale_keys(scale: Optional[float], density_ratio: float, gravity_ratio: Optional[float] = None) -> dict | None:
    """The scenario's ``[scale]`` keys of ``--scale``, ``--density-ratio`` and (when the command has it)
    ``--gravity-ratio``; None without ``--scale`` (the prototype alone)."""
    if scale is None:
        return None
    keys = {"length": scale, "density_ratio": density_ratio}
    if gravity_ratio is not None:
        keys["gravity_ratio"] = gravity_ratio
    return keys


def read_scenario(path, values: list[str], flags: Optional[dict] = None) -> Scenario:
    """The scenario file at ``path`` (None: the built-in default) with the ``--set KEY=VALUE`` overrides
    ``values`` and the command's own ``flags`` (scenario path -> value, None: not given)."""
    with one_line_warnings():  # e.g. a [lab.explosives] table that redefines a library explosive
        sc = Scenario.default() if path is None else load_scenario(path)
    with one_line_warnings():  # a --set that replaces the key it excludes (width_m beside the file's alpha_deg)
        return scenario_with(sc, values, flags)


def run_checked_3d(sc: Scenario, quiet: bool):
    """Check a 3D scenario's study (a step past the stability bound, too long or too large: one line, before
    any run), say its size, then run it under a progress bar; returns ``(result, contact settings)``."""
    study = Study(sc)
    with one_line_warnings():  # e.g. friction near the pivoting threshold, blast-fit ranges
        with flags_named():  # a step past the stability bound, too long or too large: before any run
            contact = study.check().contact
        expected = announce_run(study, console_err, quiet=quiet)  # its size, before it starts
        with stage_progress(quiet=quiet, expected_s=expected) as tell:
            result = study.run(progress=tell)
    return result, contact


def add_figure(out: dict, build: Callable, plot: Optional[str]) -> None:
    """Write the figure ``build()`` makes to ``plot`` (nothing without ``--plot``) and name it in ``out``."""
    if plot:
        save_figure(build, plot)
        out["plot"] = plot


def add_comparison_3d_figure(out: dict, result, prototype_dataset, plot: Optional[str]) -> None:
    """The 3D commands' ``--plot``: the prototype's and the up-scaled model's histories and poses."""

    def build():
        from ..plots.column import plot_column_comparison

        return plot_column_comparison(result.structure, prototype_dataset, result.response3d.upscaled_dataset)

    add_figure(out, build, plot)


def print_model_3d(scale: float, out: dict, rows: list) -> None:
    """The 3D commands' table of the up-scaled model."""
    console.print(
        table(
            f"Model lambda = {scale:g}, up-scaled to prototype units "
            f"(model charge {out['model_experiment']['charge_kg']:.4g} kg)",
            rows,
        )
    )


def answer(out: dict, *, as_json: bool, tables: Callable[[], None], plot=None, engine: str | None = None) -> None:
    """A command's answer: ``out`` as one JSON object (``--json``), or its tables (``tables()``) and the
    line naming the figure written."""
    if as_json:
        print_json(out, engine=engine)
        return
    tables()
    if plot:
        print_written(plot)


@contextlib.contextmanager
def result_folder(out, force: bool, markers: Optional[tuple] = None) -> Iterator:
    """The partial folder to write a command's results into, renamed to ``out`` on success
    (:func:`blastscale.io.results.output_folder`); an interrupt before the rename leaves nothing, one after it
    is ignored (the folder is in place)."""
    kw = {} if markers is None else {"markers": markers}
    with output_folder(out, force, before_commit=raise_if_interrupted, after_commit=ignore_interrupts, **kw) as tmp:
        yield tmp
