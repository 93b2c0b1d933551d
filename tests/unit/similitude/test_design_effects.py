"""Designs whose specimen is shot with another burst type, and the blast effects a design reports
for both systems (clearing, negative phase, lab burst) with its 5 % notes."""

import math
import warnings

import numpy as np
import pytest

from blastscale.blast import blast_parameters
from blastscale.blast.load_model import LoadModel, front_face_clearing
from blastscale.similitude import design_model
from blastscale.similitude.effects import BlastSimilarityWarning, clearing_corrected_charge, front_face, front_geometry
from blastscale.structures import MultiDrumColumn, RectangularBlock

BLOCK = RectangularBlock.from_slenderness(10.0, math.radians(15.0))


def test_defaults_are_the_papers_design_exactly():
    a = design_model(84.0, 2.0, 1 / 100, geometry=BLOCK)
    b = design_model(84.0, 2.0, 1 / 100, geometry=BLOCK, burst="surface", specimen_burst=None, load_model=LoadModel())
    assert a == b and a.effects is None and a.notes == ()


@pytest.mark.parametrize("law, gam", [("general", 1.0), ("hopkinson-cranz", None)])
def test_a_free_air_specimen_delivers_the_required_impulse(law, gam):
    with pytest.warns(BlastSimilarityWarning, match="free-air burst"):
        d = design_model(84.0, 2.0, 1 / 100, gam, law=law, geometry=BLOCK, specimen_burst="free-air")
    assert d.specimen.burst == "free-air" and d.specimen.blast_model == "kingery-bulmash-free-air"
    assert d.impulse_ratio == pytest.approx(d.factors.impulse, rel=1e-9)
    same = design_model(84.0, 2.0, 1 / 100, gam, law=law, geometry=BLOCK)
    # the free-air specimen needs a larger charge than the surface one (~1.8 x for the same impulse)
    assert 1.5 < d.specimen_charge_kg / same.specimen_charge_kg < 2.2
    if law == "hopkinson-cranz":
        assert d.scaled_distance_factor != 1.0


def test_arrays_of_a_free_air_specimen_equal_the_scalar_designs():
    W = np.array([50.0, 84.0, 120.0])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", BlastSimilarityWarning)
        arr = design_model(W, 2.0, 1 / 100, specimen_burst="free-air")
        one = [design_model(w, 2.0, 1 / 100, specimen_burst="free-air").specimen_charge_kg for w in W]
    np.testing.assert_allclose(arr.specimen_charge_kg, one, rtol=1e-9)


def test_effects_of_both_systems_and_their_notes():
    lm = LoadModel(clearing=True, face_width_m=1.0, face_height_m=10.0, negative_phase=True)
    with pytest.warns(BlastSimilarityWarning, match="negative phase"):
        d = design_model(84.0, 2.0, 1 / 100, geometry=BLOCK, load_model=lm)
    e = d.effects
    assert set(e) >= {"load_model", "clearing", "negative_phase"}
    c = e["clearing"]
    for side in ("prototype", "model"):
        assert c[side]["clearing_time_over_positive_duration"] == pytest.approx(
            c[side]["clearing_time_s"] / c[side]["positive_duration_s"], rel=1e-12
        )
    # the specimen's face is lambda times the prototype's
    assert e["load_model"]["model"]["face_width_m"] == pytest.approx(0.01)
    n = e["negative_phase"]
    assert n["model"]["negative_over_positive_impulse"] > 1.5 * n["prototype"]["negative_over_positive_impulse"]
    assert any("negative phase" in x for x in d.notes)
    assert d.to_dict()["blast_effects"] == e and d.to_dict()["notes"] == list(d.notes)


def test_lab_charge_height_warns_when_neither():
    with pytest.warns(BlastSimilarityWarning, match="neither a surface nor a free-air"):
        d = design_model(84.0, 2.0, 1 / 100, geometry=BLOCK, specimen_burst="free-air", specimen_charge_height=0.002)
    assert d.effects["lab_burst"]["kind"] == "neither"


def test_clearing_corrected_charge_restores_the_cleared_impulse():
    """A narrow face (a 1.3 cm wide specimen of a 1.3 m wide pier, lambda = 1/100): the corrected
    charge makes the cleared impulse scale exactly; the price is a larger charge."""
    lm = LoadModel(clearing=True, face_width_m=1.3, face_height_m=10.0)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", BlastSimilarityWarning)
        d = design_model(250.0, 10.0, 1 / 100, load_model=lm, face=(1.3, 10.0))
    fix = clearing_corrected_charge(d, lm)
    bp = blast_parameters(fix["charge_kg"], d.specimen_standoff_m)
    got = front_face_clearing(bp, lm.scaled(d.factors)).impulse
    want = front_face_clearing(d.prototype, lm).impulse * d.factors.impulse
    assert got == pytest.approx(want, rel=1e-9)
    assert fix["charge_ratio"] == pytest.approx(fix["charge_kg"] / d.specimen_charge_kg)


def test_clearing_corrected_charge_reads_the_specimen_load_model_from_the_design():
    """The specimen's load model is the design's (scaled once, by it): another prototype load model (a
    2 m wide face instead of the design's 1.3 m) is refused with one line naming it, rather than scaled
    here a second time."""
    from blastscale._validate import BlastscaleInputError

    lm = LoadModel(clearing=True, face_width_m=1.3, face_height_m=10.0)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", BlastSimilarityWarning)
        d = design_model(250.0, 10.0, 1 / 100, load_model=lm, face=(1.3, 10.0))
    assert clearing_corrected_charge(d) == clearing_corrected_charge(
        d, LoadModel(clearing=True, face_width_m=1.3, face_height_m=10.0)
    )
    with pytest.raises(BlastscaleInputError, match="load model = .* is not the design's"):
        clearing_corrected_charge(d, LoadModel(clearing=True, face_width_m=2.0, face_height_m=10.0))


def test_front_geometry_of_block_and_column():
    assert front_face(BLOCK) == pytest.approx((BLOCK.depth, BLOCK.height))
    w, top = front_geometry(MultiDrumColumn(section="square"))
    assert (
        top == pytest.approx(10.0) and w[0] == pytest.approx(1.65, rel=0.02) and w[-1] == pytest.approx(1.28, rel=0.03)
    )
    w, _ = front_geometry(MultiDrumColumn(section="circular"))
    assert w[0] == pytest.approx(1.65, rel=0.02)
