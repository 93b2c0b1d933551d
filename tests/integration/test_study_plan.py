"""The Study over a plan resolved once (issue #34, Deliver 1), counted: the plan carries the engine settings as
frozen typed objects (the 3D path with the design's load models); analysis takes (systems, settings), with no
``**dict`` settings; no module memo keyed by ``id()``; no scenario written back from a design to get into the
Study (the fired test, the calibrations and the planner enter from the design or the candidate)."""

from __future__ import annotations

import ast
import dataclasses
from pathlib import Path

import pytest

import blastscale
from blastscale.analysis.systems import Settings3D, System3D, Systems3D
from blastscale.planning.odds import Tolerances, specimen_members
from blastscale.scenario import Scenario
from blastscale.study import Study
from blastscale.study.engines import EnsembleSettings, PlanarSettings

SRC = Path(blastscale.__file__).resolve().parent


def _trees(*parts):
    for part in parts:
        for path in sorted((SRC / part).rglob("*.py")) if (SRC / part).is_dir() else [SRC / part]:
            yield path.relative_to(SRC).as_posix(), ast.parse(path.read_text())


def test_the_plan_carries_typed_frozen_settings_and_the_designs_load_models():
    sc = Scenario.default().with_values(
        {"engine": "both", "duration_s": 0.05, "blast.clearing": True, "ensemble_members": 2, "critical_charge": False}
    )
    plan = Study(sc).check()
    d = plan.design
    assert isinstance(plan.planar, PlanarSettings) and isinstance(plan.settings3d, Settings3D)
    assert isinstance(plan.ensemble, EnsembleSettings) and plan.ensemble.members == 2
    proto, spec = plan.systems3d.prototype, plan.systems3d.specimen
    assert isinstance(proto, System3D) and isinstance(spec, System3D) and plan.systems3d.design is d
    # one load model per system, the design's (before: the 3D path built a third of its own)
    assert proto.load_model is d.load_model and spec.load_model is d.specimen_load_model
    assert plan.planar.load_model is d.load_model
    assert spec.structure is d.specimen_structure and spec.contact is d.specimen_contact
    assert spec.duration == d.specimen_duration and spec.gravity == d.specimen_gravity and spec.blast is d.specimen
    for obj, field in (
        (plan, "scenario"),
        (plan.planar, "duration"),
        (plan.settings3d, "load"),
        (proto, "duration"),
        (plan.ensemble, "members"),
    ):
        with pytest.raises(dataclasses.FrozenInstanceError):
            setattr(obj, field, None)
    assert plan.size.contacts == plan.contacts >= 1 and plan.size is plan.size  # the size, said once


def test_analysis_takes_systems_and_settings_no_dict_settings():
    """No ``**kwargs`` parameter and no ``**`` splat of settings in the 3D analysis functions."""
    found = []
    for name, tree in _trees(
        "analysis/systems.py", "analysis/prototype3d.py", "analysis/structure3d.py", "analysis/ensemble.py"
    ):
        for node in ast.walk(tree):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)) and node.args.kwarg is not None:
                found.append(f"{name}:{node.lineno} **{node.args.kwarg.arg}")
            if isinstance(node, ast.Call) and any(k.arg is None for k in node.keywords):
                found.append(f"{name}:{node.lineno} call with **")
    assert found == [], found


def test_no_module_memo_keyed_by_id():
    """No ``id(...)`` anywhere in the library (memos are keyed on frozen values or carried by the objects)."""
    found = [
        f"{name}:{node.lineno}"
        for name, tree in _trees(".")
        for node in ast.walk(tree)
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id == "id"
    ]
    assert found == [], found


def test_no_scenario_written_back_to_get_into_the_study():
    """study, fired and planning build no Scenario from a dict and derive no variant by ``with_values`` (the
    plan's ``best_scenario``, a file for the user, is the one scenario the planner writes: ``design_scenario``)."""
    found = []
    for name, tree in _trees("study", "fired", "planning"):
        for node in ast.walk(tree):
            if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute):
                if node.func.attr in ("from_dict", "with_values") and name != "study/result.py":
                    found.append(f"{name}:{node.lineno} {node.func.attr}")
    assert found == [f"planning/plan3d.py:{_line_of('planning/plan3d.py', 'from_dict')} from_dict"], found
    assert not (SRC / "study" / "specimen.py").exists()


def _line_of(name: str, attr: str) -> int:
    tree = ast.parse((SRC / name).read_text())
    return next(n.lineno for n in ast.walk(tree) if isinstance(n, ast.Call) and getattr(n.func, "attr", None) == attr)


def test_a_design_run_is_the_studys_own_specimen_run():
    """``Study.from_design`` gives the specimen run of the scaled study bit for bit (planar: the same system, from
    the design, with no scenario in between); under the design's charge and stand-off given again (the blast
    parameters recomputed) to 1e-9."""
    sc = Scenario.default().with_values({"engine": "planar", "duration_s": 0.2, "critical_charge": False})
    study = Study(sc)
    r = study.run()
    d = study.check().design
    alone = Study.from_design(sc, d).run()
    assert alone.design is None and alone.structure is d.specimen_structure
    assert alone.planar.prototype.max_rotation == r.planar.model.max_rotation
    given = Study.from_design(sc, d, charge_kg=d.specimen_charge_kg, standoff_m=d.specimen_standoff_m).run()
    assert given.planar.prototype.max_rotation == pytest.approx(r.planar.model.max_rotation, rel=1e-9)
    proto = Study.from_design(sc, d, system="prototype").run()
    assert proto.planar.prototype.max_rotation == r.planar.prototype.max_rotation


def test_the_ensembles_members_are_typed_draws_of_the_design():
    sc = Scenario.default()
    d = Study(sc).check().design
    a = specimen_members(sc, d, Tolerances(charge=0.05, standoff_m=0.001, density=0.02, friction=0.05), 4, seed=3)
    b = specimen_members(sc, d, Tolerances(charge=0.05, standoff_m=0.001, density=0.02, friction=0.05), 4, seed=3)
    assert a == b and len({m.charge_kg for m in a}) == 4
    assert all(isinstance(m.density_factor, float) for m in a)


def test_systems_of_a_bare_design_need_its_structure():
    from blastscale._validate import BlastscaleInputError
    from blastscale.similitude import design_model

    with pytest.raises(BlastscaleInputError, match="structure = None"):
        Systems3D.of_design(design_model(250.0, 10.0, 1 / 100))
