"""Convert once (issue #14): one default Study designs the specimen once and evaluates each
system's blast once; every load (planar pulses, 3D Methods A/B/C, the arrival-spread similarity)
is built from the design's BlastParameters, never recomputed.

Counted at run time by wrapping the functions where they are looked up (every loaded
``blastscale`` module holding a reference, so a new import site is counted too).
"""

from __future__ import annotations

import sys
from collections import Counter

import numpy as np
import pytest

import blastscale.blast.parameters as parameters
import blastscale.sim3d.load_methods as load_methods
import blastscale.similitude.design as design_module
from blastscale.scenario import Scenario
from blastscale.study import Study


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


def test_one_default_study_designs_once_and_evaluates_each_systems_blast_once(monkeypatch):
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

    monkeypatch.setattr(load_methods, "make_load", counting_make_load)
    from blastscale.study import engines

    engines._critical_charge.cache_clear()  # the critical charge is memoised per process: search it here
    sc = Scenario.default().with_values({"duration_s": 0.3})
    assert sc.simulation.engine == "both" and sc.simulation.critical_charge and sc.scale is not None
    r = Study(sc).run()
    r.summary()  # the summary (3D similarity and arrival spreads included) builds nothing more
    assert r.planar is not None and r.response3d is not None and r.critical is not None

    assert len(designs) == 1, designs

    d = r.design
    systems = {(d.prototype.charge_kg, d.prototype.standoff_m): "prototype",
               (d.specimen.charge_kg, d.specimen.standoff_m): "model"}
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
    sc = Scenario.default().with_values({
        "kind": "column", "drums": 3, "height_m": 3.0, "top_width_m": 1.54, "charge_kg": 250.0, "standoff_m": 10.0,
        "scale.length": 0.01, "model": "kingery-bulmash", "engine": "3d", "load": load, "duration_s": 0.05})
    r = Study(sc).run()
    s = r.summary()["3d"]["similarity"]
    assert len(blasts) == 2, blasts  # the design's prototype and model
    assert r.response3d.settings["load_method"] == load
    # the spreads of the loads as run: three drums' faces, shock arriving over ~1 ms
    assert 1e-4 < s["arrival_spread_prototype_s"] < 1e-2 and 0 < s["arrival_spread_model_upscaled_s"] < 1e-2
