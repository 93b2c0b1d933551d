"""Command-line flags -> a :class:`~blastscale.scenario.Scenario`: every command that simulates
builds one and runs it through the Study, so a flag and the scenario key it sets are validated
by the same schema, and an error names the flag the user typed."""

from __future__ import annotations

import contextlib
import math
import re
import sys
import tomllib
import warnings
from typing import Optional

import typer

from .._validate import BlastscaleInputError
from ..scenario.scenario import EXCLUSIVE_KEYS, Scenario

__all__ = ["FLAG_NAMES", "SET_VALUES", "parse_set", "scenario_with", "scenario_from_flags", "flags_named"]

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
    "simulation.step_after_load": "--step-after-load",
}


def parse_set(items: list[str]) -> dict:
    """``KEY=VALUE`` pairs of ``--set`` -> {key: value}; the value read as TOML (numbers, true/false,
    "text"), bare words as strings. Keys and values are validated by the scenario schema
    (:meth:`~blastscale.scenario.Scenario.with_values`), which names the key, its value and its range."""

    out, items_of = {}, {}
    for item in items:
        key, sep, text = item.partition("=")
        if not sep or not key.strip():
            raise BlastscaleInputError(f"set = {item!r} is not KEY=VALUE (e.g. --set blast.charge_kg=60)")
        if _NON_DECIMAL.match(text.strip()):
            raise BlastscaleInputError(
                f"set = {item!r}: {text.strip()!r} is not a decimal number (TOML reads it "
                f"as {tomllib.loads(f'v = {text.strip()}')['v']}): give the number in decimal"
            )
        try:
            value = tomllib.loads(f"v = {text.strip()}")["v"]
        except tomllib.TOMLDecodeError:
            value = text.strip()
        if isinstance(value, float) and math.isinf(value) and "inf" not in text:
            raise BlastscaleInputError(
                f"set = {item!r}: {text.strip()} overflows a number (the largest is "
                f"{sys.float_info.max:.4g}); give a finite value"
            )
        if key.strip() in out:
            raise BlastscaleInputError(
                f"set = {items_of[key.strip()]!r} and {item!r} set {key.strip()} twice: give it once"
            )
        out[key.strip()], items_of[key.strip()] = value, item
    return out


#: A hexadecimal, octal or binary TOML integer (``0x10`` reads 16): refused in ``--set``, where it is a slip.
_NON_DECIMAL = re.compile(r"^[+-]?0[xXoObB][0-9A-Fa-f_]+$")


def value_as_typed(value) -> str:
    """A value as the user would type it (TOML-like: no Python repr; a validation message's quoted value is
    :func:`blastscale.scenario.messages.value_in_message`)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    return value if isinstance(value, str) else format(value, "g") if isinstance(value, float) else str(value)


def scenario_with(sc: Scenario, values: list[str], flags: Optional[dict] = None) -> Scenario:
    """``sc`` with the ``--set KEY=VALUE`` overrides and the command's own flags (scenario path -> value, None:
    not given). A key set twice (``--set charge_kg=20 --set blast.charge_kg=30``, or a flag and a ``--set``) is
    refused in one line naming both values; a key that replaces the scenario's value of the key it excludes
    (``width_m`` beside the file's ``alpha_deg``) says so in one warning line."""

    given = parse_set(values)
    resolved: dict = {}
    said: dict = {}
    for key, value in given.items():
        path = _path(sc, key)
        if path in resolved:
            raise BlastscaleInputError(
                f"set = '{said[path]}={value_as_typed(resolved[path])}' and '{key}={value_as_typed(value)}' "
                f"both set {path}: give it once"
            )
        resolved[path], said[path] = value, key
    for path, value in (flags or {}).items():
        if value is None:
            continue
        if path in resolved:
            raise BlastscaleInputError(
                f"{FLAG_NAMES.get(path, path)} {value_as_typed(value)} and --set {said[path]}="
                f"{value_as_typed(resolved[path])} both set {path}: give one of them"
            )
        resolved[path] = value
    for path in resolved:
        other = EXCLUSIVE_KEYS.get(path)
        if other and other not in resolved:
            old = _current(sc, other)
            if old is not None:
                warnings.warn(
                    f"{path} = {value_as_typed(resolved[path])} replaces the scenario's "
                    f"{other} = {value_as_typed(old)} "
                    "(they exclude each other: the value on the command line is kept)",
                    stacklevel=2,
                )
    return sc.with_values(resolved) if resolved else sc


def _path(sc: Scenario, key: str) -> str:
    try:
        return sc.resolve_key(key)
    except Exception:  # an unknown key or a new kind's: with_values says what is wrong with it
        return key


def _current(sc: Scenario, path: str):
    node = sc
    for part in path.split("."):
        node = getattr(node, part, None)
        if node is None:
            return None
    return node


@contextlib.contextmanager
def flags_named():
    """One-line errors of the study's own checks (the size and time guard, the engine's time step) name
    the flag the user typed instead of the scenario key it sets (``--duration`` for ``simulation.duration_s``)."""

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
