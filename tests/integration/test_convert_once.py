"""Convert once (issue #14): one default Study designs the specimen once and evaluates each
system's blast once; every load (planar pulses, 3D Methods A/B/C, the arrival-spread similarity)
is built from the design's BlastParameters, never recomputed.

Counted at run time by wrapping the functions where they are looked up (every loaded
``blastscale`` module holding a reference, so a new import site is counted too).
"""

from __future__ import annotations

import ast
import sys
import warnings
from collections import Counter
from pathlib import Path

import numpy as np
import pytest

import blastscale.blast.parameters as parameters
import blastscale.sim3d.contact as contact_module
import blastscale.sim3d.load_methods as load_methods
import blastscale.similitude.design as design_module
import blastscale.similitude.specimen as specimen_module
from blastscale.analysis import compare, systems, upscale
from blastscale.analysis.capacity import model_capacity_curve
from blastscale.blast.load_model import LoadModel
from blastscale.rocking import RockingSystem
from blastscale.scenario import Scenario
from blastscale.sim3d.contact import ContactSettings
from blastscale.similitude import design_model, factors
from blastscale.similitude.effects import BlastSimilarityWarning
from blastscale.structures import MultiDrumColumn, RectangularBlock, from_spec
from blastscale.study import Study, StudyPlan


def _wrap_everywhere(monkeypatch, original, counter):
    """Replace ``original`` in every loaded blastscale module that holds it by a counting wrapper;
    ``counter`` receives (caller module, whether the inputs are scalars, charge, stand-off)."""

    def counting(*args, **kw):
        caller = sys._getframe(1).f_globals.get("__name__", "?")
        charge = args[0] if args else kw.get("charge")
        standoff = args[1] if len(args) > 1 else kw.get("standoff")
        scalar = np.ndim(charge) == 0 and np.ndim(standoff) == 0
        counter.append((caller, scalar, float(charge) if scalar else None, float(standoff) if scalar else None))
        return original(*args, **kw)

    name = original.__name__
    for mod_name, mod in list(sys.modules.items()):
        if mod_name.startswith("blastscale") and getattr(mod, name, None) is original:
            monkeypatch.setattr(mod, name, counting)


def test_one_default_study_designs_once_and_evaluates_each_systems_blast_once(monkeypatch, patch_everywhere):
    """``Scenario.default()`` (the paper's block, 50 kg at 2 m, lambda = 1/200; engine "both":
    planar and 3D, Method A; the critical charge on), shortened to 0.3 s.

    * ``design_model``: exactly 1 call (the Study's design).
    * ``blast_parameters`` of a system's own charge and stand-off: 1 per system (the design's
      ``prototype`` and ``model``), within the issue's bound of 2; the planar pulses, the 3D
      loads and the arrival-spread similarity reuse them (before: 6 such calls, 2 of them for
      the 3D loads and 2 more for rebuilding both loads in the arrival-spread similarity).
    * ``make_load``: 2 calls (one per system), each given the design's own BlastParameters.
    * The critical-charge search evaluates the blast fits at the *trial* charges of its root
      finder, all stand-off cases at once, through ``blast_parameters_unchecked`` (its inputs are
      checked once, at the search's entry): one vectorised call per evaluation, on arrays. These are
      not the study's systems (they are the search for a different charge), so they are counted
      apart and asserted to be exactly that: array calls from the search and nothing else.
    """
    designs: list = []
    blasts: list = []
    loads: list = []
    _wrap_everywhere(monkeypatch, design_module.design_model, designs)
    _wrap_everywhere(monkeypatch, parameters.blast_parameters, blasts)
    searched: list = []
    _wrap_everywhere(monkeypatch, parameters.blast_parameters_unchecked, searched)
    real_make_load = load_methods.make_load

    def counting_make_load(method, structure, blast, **kw):
        loads.append(blast)
        return real_make_load(method, structure, blast, **kw)

    patch_everywhere(load_methods, "make_load", counting_make_load)
    from blastscale.study import engines

    engines._critical_charge.cache_clear()  # the critical charge is memoised per process: search it here
    sc = Scenario.default().with_values({"duration_s": 0.3})
    assert sc.simulation.engine == "both" and sc.simulation.critical_charge and sc.scale is not None
    r = Study(sc).run()
    r.summary()  # the summary (3D similarity and arrival spreads included) builds nothing more
    assert r.planar is not None and r.response3d is not None and r.critical is not None

    assert len(designs) == 1, designs

    d = r.design
    systems = {
        (d.prototype.charge_kg, d.prototype.standoff_m): "prototype",
        (d.specimen.charge_kg, d.specimen.standoff_m): "model",
    }
    per_system = Counter(systems.get((w, R), f"other {w} kg at {R} m") for _, scalar, w, R in blasts if scalar)
    assert per_system == {"prototype": 1, "model": 1}, (per_system, blasts)
    assert all(n <= 2 for n in per_system.values())  # the acceptance bound

    # the 3D engine builds one load per system, from the design's own BlastParameters objects (the
    # arrival-spread similarity reads those loads)
    assert len(loads) == 2 and loads[0] is d.prototype and loads[1] is d.specimen

    assert all(scalar for _, scalar, *_ in blasts), blasts  # blast_parameters: the two systems only
    searched = [c for c in searched if c[0] != "blastscale.blast.parameters"]  # not blast_parameters' own
    assert searched and all(caller == "blastscale.rocking.swing" and not scalar for caller, scalar, *_ in searched)
    assert len(searched) == r.critical.evaluations  # one vectorised call per first-swing evaluation (6 here)


@pytest.mark.parametrize("load", ["B", "C"])
def test_per_face_loads_take_charge_standoff_and_blast_model_from_the_design(load, monkeypatch):
    """Methods B and C evaluate the blast model at each face's distance (that is the method); the
    charge, the stand-off and the blast model come from the design's BlastParameters: the 3D
    engine and its similarity block call ``blast_parameters`` no more than the design did."""
    blasts: list = []
    _wrap_everywhere(monkeypatch, parameters.blast_parameters, blasts)
    sc = Scenario.default().with_values(
        {
            "kind": "column",
            "drums": 3,
            "height_m": 3.0,
            "top_width_m": 1.54,
            "charge_kg": 250.0,
            "standoff_m": 10.0,
            "scale.length": 0.01,
            "model": "kingery-bulmash",
            "engine": "3d",
            "load": load,
            "duration_s": 0.05,
        }
    )
    r = Study(sc).run()
    s = r.summary()["3d"]["similarity"]
    assert len(blasts) == 2, blasts  # the design's prototype and model
    assert r.response3d.settings["load_method"] == load
    # the spreads of the loads as run: three drums' faces, shock arriving over ~1 ms
    assert 1e-4 < s["arrival_spread_prototype_s"] < 1e-2 and 0 < s["arrival_spread_model_upscaled_s"] < 1e-2


# -- one specimen, built once (issue #23) ----------------------------------------------------------------------

#: The one module whose function scales a specimen (``similitude.specimen.specimen_system``), for the design,
#: a capacity curve and a 3D run given a design without its structure.
SPECIMEN = "blastscale.similitude.specimen"


def _count_function(monkeypatch, original, counter):
    """Replace ``original`` in every loaded blastscale module that holds it by a wrapper that appends
    its caller module to ``counter``."""

    def counting(*args, **kw):
        counter.append(sys._getframe(1).f_globals.get("__name__", "?"))
        return original(*args, **kw)

    for mod_name, mod in list(sys.modules.items()):
        if mod_name.startswith("blastscale") and getattr(mod, original.__name__, None) is original:
            monkeypatch.setattr(mod, original.__name__, counting)


def _count_method(monkeypatch, cls, name, counter):
    """Replace ``cls.name`` by a counting wrapper; ``counter`` receives (caller module, self, first argument)."""
    original = getattr(cls, name)

    def counting(self, *args, **kw):
        counter.append((sys._getframe(1).f_globals.get("__name__", "?"), self, args[0] if args else None))
        return original(self, *args, **kw)

    monkeypatch.setattr(cls, name, counting)


def test_the_specimen_system_is_scaled_once_by_the_design(monkeypatch):
    """The paper's block with clearing and the negative phase, both engines (planar and 3D), 0.05 s:

    * the prototype structure is built once per Study (``from_spec``, by the check) and the specimen
      structure once, by the design (``structure.scaled(factors)``);
      the Study's result, the planar engine and the 3D engine read ``design.specimen_structure``;
    * ``LoadModel.scaled`` is called once (the specimen's load model, by the design): the planar
      engine, the blast effects and the 3D engine read ``design.specimen_load_model``;
    * ``ContactSettings.scaled`` by the design's factors once (the specimen's contact); the prototype's
      contact settings resolved once (``default_contact``, by the check) and handed down: no run
      derives them again (before: once more per run, for the soft-contact warning). The engine's own
      normalisation into reference units (:mod:`blastscale.sim3d.reference`, another factor: 10 m
      over the structure's height) is not the specimen's and is counted apart: at most once per run.

    Before (issue #23): the specimen block 2x (design, Study), the load model 2x here (effects, planar
    engine; and once more per sweep chunk), the contact scaled by each run of the specimen and derived
    again by each run.
    """
    built, lms, contacts, derived, prototypes, scalings = [], [], [], [], [], []
    _count_function(monkeypatch, specimen_module.specimen_system, scalings)
    _count_function(monkeypatch, contact_module.default_contact, derived)
    _count_function(monkeypatch, from_spec, prototypes)
    _count_method(monkeypatch, RectangularBlock, "scaled", built)
    _count_method(monkeypatch, LoadModel, "scaled", lms)
    _count_method(monkeypatch, ContactSettings, "scaled", contacts)
    sc = Scenario.default().with_values(
        {"duration_s": 0.05, "clearing": True, "negative_phase": True, "critical_charge": False}
    )
    study = Study(sc)
    r = study.run()
    d = r.design
    assert r.planar is not None and r.response3d is not None
    assert prototypes == ["blastscale.study.study"], prototypes  # the prototype built once, by the check
    assert scalings == ["blastscale.similitude.design"], scalings  # the one specimen system, by the design
    specimens = [c for c in built if c[2] is d.factors]
    assert [c[0] for c in specimens] == [SPECIMEN], built
    assert r.specimen_structure is d.specimen_structure is r.response3d.specimen_structure
    assert r.planar.design.specimen_block is d.specimen_structure
    assert [c[0] for c in lms] == [SPECIMEN], lms
    assert d.specimen_load_model.face_height_m == pytest.approx(d.scale * d.load_model.face_height_m, rel=1e-15)
    by_design = [c for c in contacts if c[2] is d.factors]
    assert [c[0] for c in by_design] == [SPECIMEN], contacts
    assert study.check().contact is d.contact and d.specimen_contact is not None
    assert derived == ["blastscale.study.engines"], derived  # contact_settings, in the check
    others = Counter(c[0] for c in contacts if c[2] is not d.factors)
    # the one derivation scales the 10 m reference settings to the prototype once; the engine puts each run
    # into reference units (the prototype, 10 m high, needs no scaling)
    assert set(others) <= {"blastscale.sim3d.contact", "blastscale.sim3d.reference"}, contacts
    assert others["blastscale.sim3d.contact"] == 1 and others["blastscale.sim3d.reference"] <= 2, contacts
    assert d.specimen_duration == pytest.approx(0.05 * d.factors.time, rel=1e-15)


def test_a_column_and_its_ensembles_build_one_specimen(monkeypatch):
    """Any kind: a 3-drum column on the 3D engine with 2-member ensembles (6 runs of the engine) builds
    its specimen column once and scales its contact by the design's factors once (before: once per run
    of the specimen, 3 here)."""
    built, contacts = [], []
    _count_method(monkeypatch, MultiDrumColumn, "scaled", built)
    _count_method(monkeypatch, ContactSettings, "scaled", contacts)
    sc = Scenario.default().with_values(
        {
            "kind": "column",
            "drums": 3,
            "height_m": 3.0,
            "top_width_m": 1.54,
            "charge_kg": 250.0,
            "standoff_m": 10.0,
            "scale.length": 0.01,
            "model": "kingery-bulmash",
            "engine": "3d",
            "duration_s": 0.03,
            "ensemble_members": 2,
        }
    )
    r = Study(sc).run()
    d = r.design
    assert r.ensemble is not None and isinstance(d.specimen_structure, MultiDrumColumn)
    assert [c[0] for c in built if c[2] is d.factors] == [SPECIMEN], built
    assert [c[0] for c in contacts if c[2] is d.factors] == [SPECIMEN], contacts
    assert r.specimen_structure is d.specimen_structure is r.response3d.specimen_structure


def test_a_capacity_curve_scales_its_specimen_once(monkeypatch):
    """A capacity curve (stand-offs without a charge: no design) of the paper's 10 m block at lambda = 1/100,
    gamma = 0.5, varsigma = 2, with clearing on a 1 m x 10 m face: its specimen system comes from the one
    function that scales a specimen, called once; it scales the rocking system once (by lambda, gamma,
    varsigma) and the load model once (by lambda), and nothing else is scaled (before: the capacity built its
    specimen from lambda, gamma, varsigma itself and called ``LoadModel.scaled`` itself)."""
    scalings, rocking, blocks, lms = [], [], [], []
    _count_function(monkeypatch, specimen_module.specimen_system, scalings)
    _count_method(monkeypatch, RockingSystem, "scaled", rocking)
    _count_method(monkeypatch, RectangularBlock, "scaled", blocks)
    _count_method(monkeypatch, LoadModel, "scaled", lms)
    block = RectangularBlock(height=10.0, width=2.679491924311227, depth=1.0)
    lm = LoadModel(clearing=True, face_width_m=1.0, face_height_m=10.0)
    mcap = model_capacity_curve(block, [2.0, 3.0], 0.01, 0.5, 2.0, load_model=lm)
    assert np.all(np.isfinite(mcap.upscaled_charge_kg))
    assert scalings == ["blastscale.analysis.capacity"], scalings
    assert [c[0] for c in rocking] == [SPECIMEN], rocking
    f = rocking[0][2]
    assert (f.length, f.density, f.gravity) == (0.01, 0.5, 2.0)
    assert [(c[0], c[1]) for c in lms] == [(SPECIMEN, lm)], lms
    assert lms[0][2].length == 0.01  # scaled(factors): the design's factors, lambda among them
    assert blocks == [], blocks


def test_a_3d_run_of_a_design_without_its_specimen_scales_through_the_one_function(monkeypatch):
    """``Systems3D.of_design`` given a design made without the structure, contact and duration it runs (a user's
    ``compare_structure3d(Systems3D.of_design(design_model(W, R, lam), column))``) completes the specimen by the
    function the design uses (column x lambda, contact by the factors, duration x lambda_t), not a second path; a
    design that carries them is read as it is: nothing is scaled again (no identity tests: what the design lacks
    is what is given)."""
    col = MultiDrumColumn(drums=2, height=2.0, top_width=1.6)
    contact = ContactSettings()
    bare = design_model(250.0, 10.0, 1 / 100)
    full = design_model(250.0, 10.0, 1 / 100, geometry=col, contact=contact, duration=0.5)
    scalings, built, contacts = [], [], []
    _count_function(monkeypatch, specimen_module.specimen_system, scalings)
    _count_method(monkeypatch, MultiDrumColumn, "scaled", built)
    _count_method(monkeypatch, ContactSettings, "scaled", contacts)
    s = systems.Systems3D.of_design(full).specimen
    assert (s.structure, s.contact, s.duration) == (
        full.specimen_structure,
        full.specimen_contact,
        full.specimen_duration,
    )
    assert s.structure is full.specimen_structure and s.contact is full.specimen_contact and s.blast is full.specimen
    assert s.load_model is full.specimen_load_model
    assert built == [] and contacts == [], (built, contacts)
    s = systems.Systems3D.of_design(bare, col, contact=contact, duration=0.5).specimen
    assert scalings[-1] == "blastscale.analysis.systems", scalings
    assert [c[0] for c in built] == [SPECIMEN] and built[0][2] is bare.factors, built
    assert [c[0] for c in contacts] == [SPECIMEN] and contacts[0][2] is bare.factors, contacts
    assert s.structure.height == pytest.approx(0.02, rel=1e-15) and s.duration == pytest.approx(0.5 * 0.1, rel=1e-15)
    assert s.contact.timestep == pytest.approx(contact.timestep * 0.1, rel=1e-15) and s.blast is bare.specimen
    assert s.gravity == pytest.approx(bare.specimen_gravity, rel=1e-15)


def _definitions(name: str) -> list:
    """``module:line`` of every function defined as ``name`` and every module-level assignment to it in src/."""
    src = Path(design_module.__file__).resolve().parents[1]
    out = []
    for path in sorted(src.rglob("*.py")):
        tree = ast.parse(path.read_text())
        for node in ast.walk(tree):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)) and node.name == name:
                out.append(f"{path.relative_to(src)}:{node.lineno}")
        for node in tree.body:
            targets = node.targets if isinstance(node, ast.Assign) else [getattr(node, "target", None)]
            if any(isinstance(t, ast.Name) and t.id == name for t in targets):
                out.append(f"{path.relative_to(src)}:{node.lineno}")
    return out


def test_one_design_model_body_and_one_dimension_factor_in_src():
    """One ``design_model`` (no array twin, before: ``_design_arrays``), one ``dimension_factor`` and one
    ``DIMENSIONLESS`` (before: verbatim copies in analysis/compare.py and analysis/upscale.py)."""
    assert _definitions("design_model") == [
        "similitude/design.py:" + str(design_module.design_model.__code__.co_firstlineno)
    ]
    assert _definitions("_design_arrays") == []
    assert [p.split(":")[0] for p in _definitions("dimension_factor")] == ["similitude/factors.py"]
    assert [p.split(":")[0] for p in _definitions("DIMENSIONLESS")] == ["similitude/factors.py"]
    assert compare.dimension_factor is upscale.dimension_factor is factors.dimension_factor


def _load_models():
    """Every load model a design reports (clearing, negative phase, both; a free-air specimen burst; a lab
    charge height that is neither burst), on the paper's 10 m block."""
    face = {"face_width_m": 1.0, "face_height_m": 10.0}
    return {
        "paper": {},
        "clearing": {"load_model": LoadModel(clearing=True, **face)},
        "negative phase": {"load_model": LoadModel(negative_phase=True)},
        "clearing and negative phase": {"load_model": LoadModel(clearing=True, negative_phase=True, **face)},
        "free-air specimen": {"specimen_burst": "free-air"},
        "lab charge height": {"specimen_burst": "free-air", "specimen_charge_height": 0.01},
        "all": {
            "load_model": LoadModel(clearing=True, negative_phase=True, **face),
            "specimen_burst": "free-air",
            "specimen_charge_height": 0.01,
        },
    }


def _same_record(a, b, where=""):
    """Records equal: numbers to 1e-9 relative (the array design solves the law by bisection, the scalar
    one by the closed-form root: they agree to ~1e-12), everything else exactly."""
    if isinstance(a, dict):
        assert isinstance(b, dict) and list(a) == list(b), (where, a, b)
        for k in a:
            _same_record(a[k], b[k], f"{where}.{k}")
    elif isinstance(a, (int, float)) and not isinstance(a, bool):
        assert float(b) == pytest.approx(a, rel=1e-9, abs=1e-300), where
    else:
        assert a == b, (where, a, b)


@pytest.mark.parametrize("name", list(_load_models()))
def test_scalar_and_array_designs_give_the_same_effects_and_notes(name):
    """The paper's block, 84 and 50 kg at 2 m, lambda = 1/100, for every load model: the array design of
    the two cases (one body with the scalar design, before: the array path dropped ``load_model``,
    ``face`` and ``specimen_charge_height``, so the scalar design gave effects and 2 notes, the array
    design none) gives, case by case, the scalar design's effects, and every note of either case once."""
    block = RectangularBlock(height=10.0, width=2.679491924311227, depth=1.0)
    kw = _load_models()[name]
    charges = (84.0, 50.0)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", BlastSimilarityWarning)  # the notes, compared below
        scalars = [design_module.design_model(w, 2.0, 1 / 100, geometry=block, **kw) for w in charges]
        arrays = design_module.design_model(np.array(charges), 2.0, 1 / 100, geometry=block, **kw)
    notes = []
    for i, s in enumerate(scalars):
        notes += [n for n in s.notes if n not in notes]
        if s.effects is None:
            assert arrays.effects is None and not kw
            continue
        picked = _pick(arrays.effects, i)
        _same_record(s.effects, picked, name)
    assert arrays.notes == tuple(notes)
    assert bool(kw) == bool(arrays.effects)
    if "load_model" in kw:  # the load models, carried and scaled once
        assert arrays.load_model is kw["load_model"] and scalars[0].specimen_load_model == arrays.specimen_load_model
    if name == "all":  # the burst, the lab charge's height, the clearing of at least one case
        assert len(arrays.notes) >= 3 and np.all(np.isfinite(arrays.effects["clearing"]["model"]["clearing_time_s"]))


def _pick(record, i):
    """Case ``i`` of an array design's effects record (numbers as floats)."""
    if isinstance(record, dict):
        return {k: _pick(v, i) for k, v in record.items()}
    if isinstance(record, np.ndarray):
        v = record.flat[i]
        return v.item() if hasattr(v, "item") else v
    return record


def test_study_check_returns_a_named_plan():
    """``Study.check()`` is a named object (before: a 5-tuple read by index, ``study.check()[3]``)."""
    sc = Scenario.default().with_values({"duration_s": 0.05, "engine": "planar", "critical_charge": False})
    plan = Study(sc).check()
    assert isinstance(plan, StudyPlan) and not isinstance(plan, tuple)
    assert plan.design.prototype is plan.blast and plan.design.prototype_structure is plan.structure
    assert [e.name for e in plan.engines] == ["planar"] and plan.skipped == () and plan.contact is None
