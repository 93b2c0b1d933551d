"""Materials in the planner (issue #37, deliverable 3): lead in place of marble is refused with the rigidity
reason and granite accepted; the specimen's friction follows its material (its 3D contacts, the ensemble's
draws, the card's line), and on the planar path a friction regime other than the prototype's is refused."""

import math
import warnings

import pytest

from blastscale.planning import plan
from blastscale.planning.candidates import Candidate, material_checks
from blastscale.planning.odds import specimen_friction
from blastscale.planning.shot import specimen_friction_card
from blastscale.scenario import Scenario
from blastscale.scenario.lab import LabSpec
from blastscale.sim3d.contact import ContactSettings
from blastscale.similitude import design_model, scaling_factors
from blastscale.structures.block import RectangularBlock
from blastscale.structures.materials import MATERIALS, prototype_material
from blastscale.study import Study

#: The paper's slender block in marble (2700 kg/m^3), planar engine.
MARBLE = Scenario.default().with_values({"engine": "planar", "duration_s": 3.0, "density_kg_m3": 2700.0})


@pytest.fixture(scope="module")
def marble_plan():
    """Specimens up to 0.6 m: the Hopkinson-Cranz lead specimen (lambda = 1/17.8, 0.56 m) fits every lab
    limit; only its material can refuse it."""
    lab = LabSpec(materials=["lead", "granite"], prototype_material="marble", specimen_max_height_m=0.6, samples=20)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return plan(MARBLE, lab=lab)


def test_lead_for_marble_is_refused_with_the_rigidity_reason(marble_plan):
    """r_b = (rho_marble / rho_lead) f_marble / f_lead = (2700 / 11400) (100 / 5.5) = 4.31 > 2 (printed to 3
    digits in the reason)."""
    hc = [r for r in marble_plan.rejected if r["law"] == "hopkinson-cranz" and r["material"] == "lead"]
    assert len(hc) == 1 and hc[0]["constraints"] == ["rigidity"]  # every lab limit met: the material alone
    r_b = 2700.0 / 11400.0 * 100e6 / 5.5e6
    assert hc[0]["rigidity"]["bearing_ratio"] == pytest.approx(2700.0 / 11400.0 * 100e6 / 5.5e6, rel=1e-12)
    assert hc[0]["reasons"][0].startswith(
        f"not rigid: lead in place of marble: stress-to-strength at the pivots and joints {r_b:.3g} x the "
        "prototype's > 2"
    )
    # every general-law lead specimen at lambda >= 1/75 is refused too: impact stress-to-strength > 2
    big = [r for r in marble_plan.rejected if r["material"] == "lead" and r["scale"] >= 1 / 75]
    assert big and all("rigidity" in r["constraints"] for r in big)
    assert all(d["material"] != "lead" or d["scale"] < 1 / 75 for d in marble_plan.designs)


def test_granite_for_marble_is_accepted(marble_plan):
    """Granite at 1/20: r_b = 0.05 (2800 / 2700)(100 / 150) = 0.0346; recommended, the criterion passes it."""
    granite = [d for d in marble_plan.designs if d["material"] == "granite"]
    assert granite and all(d["rigidity"]["ok"] for d in marble_plan.designs)
    d = next(d for d in granite if d["scale_fraction"] == "1/20")
    assert d["rigidity"]["bearing_ratio"] == pytest.approx(0.05 * 2800 / 2700 * 100 / 150, rel=1e-12)
    assert d["friction_ratio"] == 1.0  # granite's 0.7 on the prototype's 0.7
    assert d["friction_regime"]["specimen_regime"] == d["friction_regime"]["prototype_regime"] == "slides and rocks"
    assert marble_plan.recommendation["design"] == 0 and marble_plan.designs[0]["material"] == "granite"
    assert marble_plan.prototype["material"] == "marble"


def test_planar_friction_regime_refuses_balsa_on_a_squat_block():
    """B/H = 0.6: the stone prototype (0.7) slides and rocks, balsa (0.4) only slides; steel (0.74) keeps the
    regime. On the paper's slender block (B/H = 0.268) balsa keeps it."""
    proto = prototype_material(2000.0, 0.7)
    squat = RectangularBlock(height=1.0, width=0.6, depth=0.5, density=2000.0)
    f = scaling_factors(0.05, MATERIALS["balsa"].density / 2000.0)
    rig, fr = material_checks(Candidate("general", 0.05, "balsa", f.density), f, proto, squat)
    assert (
        rig.ok and not fr.ok and fr.reason.startswith("friction 0.4 (x0.571 the prototype's 0.7): the specimen slides")
    )
    assert material_checks(Candidate("general", 0.05, "steel", 3.925), f, proto, squat)[1].ok
    slender = RectangularBlock(height=10.0, width=10.0 * math.tan(math.radians(15.0)), depth=1.0, density=2000.0)
    assert material_checks(Candidate("general", 0.05, "balsa", f.density), f, proto, slender)[1].ok
    assert material_checks(Candidate("general", 0.05, "balsa", f.density), f, proto, None)[1] is None  # 3D: not here


def test_the_specimens_friction_follows_its_material():
    """lambda_mu = mu_lead / mu_prototype = 0.9 / 0.7: in the design's factors, its specimen's 3D contacts
    (0.9 exactly), the 3D ensemble's nominal draw and the card's line; the prototype's own material: 1."""
    sc = Scenario.default().with_values({"scale.density_ratio": None, "scale.specimen_material": "lead"})
    assert sc.friction_ratio == pytest.approx(0.9 / 0.7, rel=1e-15)
    d = Study(sc).design()
    assert d.factors.friction == pytest.approx(0.9 / 0.7, rel=1e-15)
    assert specimen_friction(sc, d) == pytest.approx(0.9, rel=1e-15)
    dc = design_model(
        50.0, 2.0, 0.05, blast_model="masi2021", contact=ContactSettings(friction=0.7), friction_ratio=9 / 7
    )
    assert dc.specimen_contact.friction == pytest.approx(0.9, rel=1e-15) and dc.contact.friction == 0.7
    card = specimen_friction_card(sc, LabSpec())
    assert (card["pair"], card["nominal"], card["low"], card["high"], card["prototype"]) == (
        "lead on lead",
        0.9,
        0.5,
        1.5,
        0.7,
    )
    assert card["line"].startswith(
        "friction: lead on lead 0.9 nominal (0.5-1.5), the prototype's 0.7: measure by tilt test"
    )
    same = Scenario.default()
    assert same.friction_ratio == 1.0 and Study(same).design().factors.friction == 1.0
    assert "the prototype's material on itself 0.7" in specimen_friction_card(same, LabSpec())["line"]


def test_the_card_of_a_chosen_lead_specimen_says_it_is_not_rigid():
    """A scale the user chose (not the planner's): the card's build carries the rigidity check, and a failing
    one is among its warnings. Lead for marble under Hopkinson-Cranz: r_b = 4.31 (as the planner's); the
    prototype's own material at 1/20: r_b = r_d = 0.05, r_i = sqrt(0.05)."""
    from blastscale.planning.shot import specimen_rigidity

    lead = MARBLE.with_values(
        {
            "scale.law": "hopkinson-cranz",
            "scale.length": (2700.0 / 11400.0) ** 2,  # lambda = 1 / gamma^2
            "scale.density_ratio": None,
            "scale.specimen_material": "lead",
        }
    )
    lab = LabSpec(prototype_material="marble")
    r = specimen_rigidity(lead, Study(lead).design(), lab)
    assert not r.ok and r.bearing_ratio == pytest.approx(2700.0 / 11400.0 * 100 / 5.5, rel=1e-9)
    same = MARBLE.with_values({"scale.length": 0.05})
    s = specimen_rigidity(same, Study(same).design(), lab)
    assert s.ok and s.bearing_ratio == pytest.approx(0.05, rel=1e-12)
    assert s.impact_ratio == pytest.approx(math.sqrt(0.05), rel=1e-12)
