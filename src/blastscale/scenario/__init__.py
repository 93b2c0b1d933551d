"""Scenario files: one blast experiment described in TOML, validated by pydantic.

A scenario names the prototype structure, the charge and its stand-off, the scales of the
model and how to simulate. Keys carry their unit in their name (``height_m``, ``charge_kg``,
``duration_s``; ratios are dimensionless); every key but the four that define the experiment
(``structure.kind``, ``blast.charge_kg``, ``blast.standoff_m``, ``scale.length``) has the
paper's default. The paper's 10 m block at 1/200::

    title = "Slender block, 50 kg TNT at 2 m, lambda = 1/200"

    [structure]
    kind = "block"          # "block" | "column"
    height_m = 10.0         # 2h
    alpha_deg = 15.0        # slenderness (or width_m, not both)
    depth_m = 1.0
    density_kg_m3 = 2000.0
    friction = 0.7          # Coulomb, tan 35 deg

    [blast]
    charge_kg = 50.0        # TNT equivalent
    standoff_m = 2.0
    blast_model = "masi2021"   # "masi2021" | "kingery-bulmash"
    load = "A"              # load method (3D): "A" | "B" | "C"
    pulse_shape = "friedlander"   # "friedlander" | "triangular" | "impulsive"

    [scale]
    length = "1/200"        # lambda (a number or a fraction)
    specimen_material = "marble"   # or density_ratio = 1.0 (gamma); default gamma = 1
    gravity_ratio = 1.0

    [simulation]
    engine = "both"         # "planar" | "3d" | "both"
    duration_s = 5.0

    [simulation.contact]    # 3D contact (optional; defaults derived from the structure)
    time_constant_s = 0.002

    [verdict]               # the similarity criterion's tolerances (optional; docs/verdict.md)
    residual = 0.2

    [damage]                # the damage states' limits (optional; docs/sweeps.md)
    severe_drift = 0.01

Unknown keys, wrong types, NaN and values out of range are refused with one line that names
the field path, the value and the valid range (:class:`~blastscale._validate.BlastscaleInputError`).
See ``docs/scenarios.md`` for every key.
"""

from .files import load_scenario
from .library import EXAMPLE_BLOCKS, TEMPLATE_KINDS, library_names, library_text, template_text
from .scenario import Scenario
from .specs import BlastSpec, ContactSpec, DamageSpec, ScaleSpec, SimulationSpec, VerdictSpec, parse_ratio
from .structure_specs import BlockSpec, ColumnSpec
from .text import to_toml

__all__ = [
    "Scenario",
    "load_scenario",
    "library_names",
    "library_text",
    "template_text",
    "TEMPLATE_KINDS",
    "EXAMPLE_BLOCKS",
    "parse_ratio",
    "to_toml",
    "BlockSpec",
    "ColumnSpec",
    "BlastSpec",
    "ScaleSpec",
    "SimulationSpec",
    "ContactSpec",
    "VerdictSpec",
    "DamageSpec",
]
