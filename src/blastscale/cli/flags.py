"""Command-line flags -> a :class:`~blastscale.scenario.Scenario`: every command that simulates
builds one and runs it through the Study, so a flag and the scenario key it sets are validated
by the same schema, and an error names the flag the user typed."""

from __future__ import annotations

import contextlib
from typing import Optional

import typer

from ..scenario import Scenario

__all__ = ["FLAG_NAMES", "SET_VALUES", "parse_set", "scenario_from_flags", "flags_named"]

#: ``--set KEY=VALUE`` (repeatable), one option object for every command that reads a scenario (run, sweep).
SET_VALUES = typer.Option(
    [],
    "--set",
    metavar="KEY=VALUE",
    show_default=False,
    help="Override a scenario value, e.g. --set blast.charge_kg=60 --set friction=0.5 (repeatable).",
)

#: Scenario field path -> the command-line flag that sets it (one-line errors name the flag).
FLAG_NAMES = {
    "structure.height_m": "--height",
    "structure.width_m": "--width",
    "structure.alpha_deg": "--alpha-deg",
    "structure.depth_m": "--depth",
    "structure.density_kg_m3": "--density",
    "structure.friction": "--friction",
    "structure.section": "--section",
    "structure.drums": "--drums",
    "structure.base_width_m": "--base-width",
    "structure.top_width_m": "--top-width",
    "structure.sides": "--sides",
    "blast.charge_kg": "--charge",
    "blast.standoff_m": "--standoff",
    "blast.blast_model": "--model",
    "blast.pulse_shape": "--pulse",
    "blast.load": "--load",
    "blast.incidence": "--incidence",
    "blast.extrapolate": "--extrapolate",
    "scale.length": "--scale",
    "scale.density_ratio": "--density-ratio",
    "scale.gravity_ratio": "--gravity-ratio",
    "scale.law": "--law",
    "simulation.duration_s": "--duration",
    "simulation.samples": "--samples",
    "simulation.gravity_m_s2": "--gravity",
    "simulation.restitution": "--restitution",
    "simulation.timestep_s": "--timestep",
    "simulation.record_every": "--record-every",
    "simulation.ensemble_members": "--ensemble",
    "simulation.threads": "--threads",
    "simulation.contact.jacobian": "--jacobian",
}


def parse_set(items: list[str]) -> dict:
    """``KEY=VALUE`` pairs of ``--set`` -> {key: value}; the value read as TOML (numbers, true/false,
    "text"), bare words as strings. Keys and values are validated by the scenario schema
    (:meth:`~blastscale.scenario.Scenario.with_values`), which names the key, its value and its range."""
    import tomllib

    from .._validate import BlastscaleInputError

    out = {}
    for item in items:
        key, sep, text = item.partition("=")
        if not sep or not key.strip():
            raise BlastscaleInputError(f"set = {item!r} is not KEY=VALUE (e.g. --set blast.charge_kg=60)")
        try:
            value = tomllib.loads(f"v = {text.strip()}")["v"]
        except tomllib.TOMLDecodeError:
            value = text.strip()
        out[key.strip()] = value
    return out


@contextlib.contextmanager
def flags_named():
    """One-line errors of the study's own checks (the size and time guard, the engine's time step) name
    the flag the user typed instead of the scenario key it sets (``--duration`` for ``simulation.duration_s``)."""
    from .._validate import BlastscaleInputError

    try:
        yield
    except BlastscaleInputError as exc:
        text = str(exc)
        for key in sorted(FLAG_NAMES, key=len, reverse=True):
            text = text.replace(key, FLAG_NAMES[key])
        if text == str(exc):
            raise
        raise BlastscaleInputError(text) from None


def _given(table: Optional[dict]) -> dict:
    """The keys of a table that a flag set (None: left to the scenario's default)."""
    return {k: v for k, v in (table or {}).items() if v is not None}


def scenario_from_flags(
    structure: dict, blast: dict, scale: Optional[dict] = None, simulation: Optional[dict] = None, title: str = ""
) -> Scenario:
    """The scenario of a command's flags (each table: scenario key -> value, None for a flag not
    given). ``scale`` None: a prototype-only scenario. Raises one line naming the flag."""
    data = {"title": title, "structure": _given(structure), "blast": _given(blast)}
    sim = _given(simulation)
    if "contact" in sim:
        sim["contact"] = _given(sim["contact"])
    data["simulation"] = sim
    if scale is not None:
        data["scale"] = _given(scale)
    return Scenario.from_dict(data, source=None, names=FLAG_NAMES)
