"""The fixed cost of a 3D run paid once (issue #41, deliverable 1): the reference structure, the compiled model and
the settled state are cached (sim3d/reference.py, sim3d/integrate.py) and a run from the cache gives bitwise the
states of a run without it; a structure and its exactly scaled specimen share one model and one settling; another
structure or other settings never do; a scenario table builds one structure object (structures/from_spec.py)."""

import dataclasses
import gc
import weakref

import numpy as np
import pytest

from blastscale.blast import blast_parameters
from blastscale.sim3d import make_load, simulate_structure
from blastscale.sim3d.contact import default_contact
from blastscale.sim3d.reference import _REFERENCES_ATTR, clear_scene_cache, reference_scene
from blastscale.similitude import scaling_factors
from blastscale.structures import wall
from blastscale.structures.from_spec import from_spec

KW = dict(length_m=3.0, height_m=2.0, thickness_m=0.4, courses=4, units_per_course=3)  # 14 blocks, running bond


def _x(r):
    return r.dataset["point_displacement"].values


@pytest.fixture(scope="module")
def runs():
    """The same wall and load run three times: new (caches cleared), again (from the caches), and with the caches
    cleared once more (everything rebuilt)."""
    w = wall(**KW)
    load = make_load("A", w, blast_parameters(5.0, 5.0))
    clear_scene_cache()
    first = simulate_structure(w, load, 0.1, record_every=20)
    again = simulate_structure(w, load, 0.1, record_every=20)
    clear_scene_cache()
    rebuilt = simulate_structure(w, load, 0.1, record_every=20)
    return w, first, again, rebuilt


def test_a_run_from_the_cache_gives_bitwise_the_states_of_a_new_run(runs):
    _, first, again, rebuilt = runs
    assert np.abs(_x(first)).max() > 1e-3  # the wall moves: a comparison that can fail
    assert np.array_equal(_x(first), _x(again))  # exact: MuJoCo's whole settled data is copied
    assert np.array_equal(_x(first), _x(rebuilt))


def test_a_structure_and_its_exactly_scaled_specimen_share_the_model_and_its_settling(runs):
    w = runs[0]
    model = w.scaled(scaling_factors(0.25, 1.0))
    clear_scene_cache()
    s1, (a1, _) = reference_scene(w, None, 9.81)
    s2, (a2, _) = reference_scene(model, None, 9.81)
    assert a2 == pytest.approx(4.0 * a1, rel=1e-12)
    assert s1.xml == s2.xml and s1.settled is s2.settled  # one model, one settled state
    assert s1.mj_model is not s2.mj_model  # each run its own copy (the loop changes its step)


def test_another_geometry_or_other_settings_never_share(runs):
    w = runs[0]
    longer = wall(**dict(KW, length_m=3.0 * (1 + 1e-6)))  # 1e-6 longer: another model (the knife edge of a wall)
    s1, _ = reference_scene(w, None, 9.81)
    s2, _ = reference_scene(longer, None, 9.81)
    c = dataclasses.replace(default_contact(w), friction=0.6)
    s3, _ = reference_scene(w, c, 9.81)
    assert s1.xml != s2.xml and s1.settled is not s2.settled
    assert s3.settled is not s1.settled


def test_the_cache_forgets_a_structure_that_is_gone():
    """The reference structure is carried by its structure object (no module memo): it goes with it."""
    w = wall(**dict(KW, courses=2))
    reference_scene(w, None, 9.81)
    refs = getattr(w, _REFERENCES_ATTR)
    assert len(refs) == 1
    gone = weakref.ref(next(iter(refs.values())))
    del w, refs
    gc.collect()
    assert gone() is None


def test_one_scenario_table_builds_one_structure_object():
    from blastscale.scenario import Scenario

    spec = Scenario.from_dict({"structure": {"kind": "wall", "courses": 3, "units_per_course": 2}}).structure
    other = Scenario.from_dict({"structure": {"kind": "wall", "courses": 3, "units_per_course": 3}}).structure
    assert from_spec(spec) is from_spec(spec.model_copy())
    assert from_spec(other) is not from_spec(spec)
