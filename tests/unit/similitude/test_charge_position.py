"""One charge position (issue #36 item 4): the 3D engine's loads, the drawings of a stored motion, the test
card's layout and ``fired`` place the charge by :func:`blastscale.similitude.effects.charge_position`, in the one
frame (origin at the footprint's centre). Closed forms: ``(front_x - R, 0, h)``; h = half the top for a free-air
burst with no stand height given. Tolerance: exact (the same arithmetic)."""

from __future__ import annotations

import numpy as np
import pytest

from blastscale._validate import BlastscaleInputError
from blastscale.blast import blast_parameters
from blastscale.fired.inputs import shot_charge_height
from blastscale.scenario import Scenario
from blastscale.sim3d import make_load
from blastscale.similitude.effects import charge_height, charge_position, structure_top
from blastscale.structures import MultiDrumColumn, RectangularBlock
from blastscale.study import Study


def test_the_closed_form_and_its_faults():
    assert charge_position(-0.25, 2.0).tolist() == [-2.25, 0.0, 0.0]
    assert charge_position(-0.25, 2.0, 0.4).tolist() == [-2.25, 0.0, 0.4]
    with pytest.raises(BlastscaleInputError, match="standoff_m = 0 m is out of range: must be > 0 m"):
        charge_position(-0.25, 0.0)
    with pytest.raises(BlastscaleInputError, match="charge height = -0.1 m is out of range: must be >= 0 m"):
        charge_position(-0.25, 1.0, -0.1)


@pytest.mark.parametrize("burst", ["surface", "free-air"])
def test_the_engine_places_the_charge_by_it(burst):
    col = MultiDrumColumn(section="square")
    load = make_load("B", col, blast_parameters(250.0, 10.0, burst=burst))
    want = charge_position(col.front_x, 10.0, charge_height(col, burst))
    assert np.array_equal(load.charge_position, want)
    assert want[2] == (0.5 * structure_top(col) if burst == "free-air" else 0.0)


@pytest.mark.filterwarnings("ignore::blastscale.similitude.effects.BlastSimilarityWarning")
def test_fired_places_a_free_air_charge_where_the_engine_does():
    """A free-air specimen with no stand height given: fired's charge at half the specimen's top, as the engine
    loads it (it was on the floor); a stand height given: that height (the lab's)."""
    sc = Scenario.default().with_values({"blast.blast_model": "kingery-bulmash", "scale.specimen_burst": "free-air"})
    d = Study(sc).check().design
    st = d.specimen_structure
    assert structure_top(st) > 0.0 and shot_charge_height(sc, d) == 0.5 * structure_top(st)
    given = sc.with_values({"scale.specimen_charge_height_m": 0.025})
    assert shot_charge_height(given, Study(given).check().design) == 0.025
    assert shot_charge_height(Scenario.default(), Study(Scenario.default()).check().design) == 0.0
    block = RectangularBlock(height=1.0, width=0.5, depth=1.0)
    assert charge_height(block, "surface", None) == 0.0
