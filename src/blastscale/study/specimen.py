"""A design's specimen written as a prototype-only scenario: the one place that does it.

The design carries the specimen system (structure, density, gravity, duration, contact; each scaled once by
:func:`blastscale.similitude.specimen.specimen_system`). What runs the specimen as a system of its own (the
planner's 3D Monte Carlo ensembles, which perturb the scenario's fields; the fired test's prediction and refit)
needs it as a scenario without ``[scale]``: :func:`specimen_scenario` writes that scenario from the design, under
the design's specimen charge and stand-off or a load of the caller's.

Its ``[structure]`` table describes the design's specimen: a block's dimensions are the design's specimen block's;
a generator's lengths (every ``*_m`` key) are the prototype's x lambda and its density x gamma (the generators
are linear in their lengths: the structure built from the table is the design's specimen, checked in
tests/integration/test_plan_any_structure.py); a block-model file's specimen blocks are written as our JSON into
a folder of the caller's, or, without one, the prototype's file is named (absolute path) and the caller hands
the design's ``specimen_structure`` to the Study (``Study(scenario, structure=...)``). Contact settings the
scenario gives explicitly are scaled like the engine scales them (times x lambda_t, widths x lambda); the time
step likewise; the duration and gravity are the design's.
"""

from __future__ import annotations

import json
import warnings
from pathlib import Path
from typing import Optional

import numpy as np

from .._validate import BlastscaleInputError
from ..scenario.scenario import Scenario

__all__ = ["specimen_scenario"]

#: Contact keys that are times (x lambda_t) and lengths (x lambda) when the specimen is written out.
CONTACT_TIMES = ("time_constant_s", "friction_time_constant_s")
CONTACT_LENGTHS = ("impedance_width_m",)


def _structure_table(scenario: Scenario, design, folder: Optional[Path]) -> dict:
    """The ``[structure]`` table of the design's specimen (module docstring)."""
    spec, st = design.specimen_structure, scenario.structure
    if st.kind == "block":
        return {
            "kind": "block",
            "height_m": spec.height,
            "width_m": spec.width,
            "depth_m": spec.depth,
            "density_kg_m3": spec.density,
            "friction": st.friction,
        }
    lam, gam = float(design.factors.length), float(design.density_ratio)
    if st.kind != "assembly":
        data = st.model_dump(exclude_none=True)
        out = {k: (v * lam if k.endswith("_m") and isinstance(v, float) else v) for k, v in data.items()}
        out["density_kg_m3"] = st.density_kg_m3 * gam
        return out
    if folder is None:
        return {**st.model_dump(exclude_none=True), "file": str(Path(st.file).resolve())}
    if spec.supports:
        raise BlastscaleInputError(
            f"structure.file = {st.file!r}: a block model with supports has no 3D ensemble "
            "here (the specimen file cannot carry them)"
        )
    dens = {b.density for b in spec.blocks}
    blocks = [
        {
            "name": b.name,
            "vertices": np.asarray(b.points).tolist(),
            **({} if len(dens) == 1 else {"density_kg_m3": b.density}),
        }
        for b in spec.blocks
    ]
    path = Path(folder) / "specimen_blocks.json"
    path.write_text(json.dumps({"blocks": blocks}), encoding="utf-8")
    return {
        "kind": "assembly",
        "file": str(path),
        "friction": st.friction,
        "density_kg_m3": float(next(iter(dens))) if len(dens) == 1 else st.density_kg_m3 * gam,
    }


def specimen_scenario(
    scenario: Scenario,
    design,
    *,
    charge_kg: Optional[float] = None,
    standoff_m: Optional[float] = None,
    engine: Optional[str] = None,
    folder: Optional[Path] = None,
) -> Scenario:
    """The design's specimen as a prototype-only scenario (module docstring).

    Parameters
    ----------
    scenario : Scenario
        The prototype's scenario the design was made from.
    design : ModelDesign
        Its design (:func:`blastscale.similitude.design_model`, carrying the specimen system).
    charge_kg, standoff_m : float, optional
        The specimen's load: TNT charge [kg] and stand-off [m]; default the design's specimen charge and stand-off.
    engine : str, optional
        ``simulation.engine`` of the specimen's scenario; default the prototype's.
    folder : Path, optional
        Where a block-model file's specimen blocks are written (a folder the caller keeps while the scenario runs).

    Returns
    -------
    Scenario
        Without ``[scale]`` and ``[lab]``; ``simulation.critical_charge`` off.
    """
    d, f = design, design.factors
    data = scenario.model_dump(mode="json", exclude_none=True)
    sim = dict(data["simulation"])
    sim.update(duration_s=float(d.specimen_duration), gravity_m_s2=float(d.specimen_gravity), critical_charge=False)
    if engine is not None:
        sim["engine"] = engine
    if sim.get("timestep_s") is not None:
        sim["timestep_s"] = float(sim["timestep_s"]) * f.time
    contact = dict(sim.get("contact") or {})
    for k in CONTACT_TIMES:
        if contact.get(k) is not None:
            contact[k] = float(contact[k]) * f.time
    for k in CONTACT_LENGTHS:
        if contact.get(k) is not None:
            contact[k] = float(contact[k]) * f.length
    sim["contact"] = contact
    burst = getattr(d.specimen, "burst", None) or (scenario.scale and scenario.scale.specimen_burst)
    blast = {
        **data["blast"],
        "charge_kg": float(d.specimen_charge_kg if charge_kg is None else charge_kg),
        "standoff_m": float(d.specimen_standoff_m if standoff_m is None else standoff_m),
        "burst": burst or scenario.blast.burst,
    }
    out = {
        "title": f"specimen of: {scenario.title}",
        "structure": _structure_table(scenario, d, folder),
        "blast": blast,
        "simulation": sim,
    }
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the prototype's scenario already warned about its own choices
        return Scenario.from_dict(out, source="specimen")
