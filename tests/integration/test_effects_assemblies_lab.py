"""Clearing, the negative phase and the burst type on main's assemblies (walls, arches, portals) and with
the test plan: a wall's front clears as one face, a front with openings is refused in one line, the
free-air charge of Methods B and C stands at half the structure's top, the planner refuses a load model
it does not search, and the test card places a free-air lab charge on its stand."""

import math

import numpy as np
import pytest

from blastscale._validate import BlastscaleInputError
from blastscale.blast import blast_parameters
from blastscale.blast.explosives import get_explosive
from blastscale.blast.load_model import LoadModel
from blastscale.cli import main
from blastscale.planning.card import study_test_card
from blastscale.report.card import card_section
from blastscale.scenario import Scenario
from blastscale.sim3d import make_load
from blastscale.similitude.effects import front_face, front_geometry, structure_top
from blastscale.structures import arch, wall
from blastscale.structures.generators import portal
from blastscale.study import Study

WALL = wall(length_m=3.0, height_m=2.0, thickness_m=0.4, courses=4, units_per_course=3)


def test_a_walls_front_clears_as_one_face_of_its_length_and_height():
    widths, top = front_geometry(WALL)
    assert widths.shape == (len(WALL.bodies),)
    assert np.allclose(widths, 3.0, rtol=1e-12) and top == pytest.approx(2.0, rel=1e-12)
    assert front_face(WALL) == pytest.approx((3.0, 2.0), rel=1e-12)
    cleared = make_load("C", WALL, blast_parameters(5.0, 20.0), load_model=LoadModel(clearing=True))
    assert cleared.describe()["load_model"]["clearing"] is True


@pytest.mark.parametrize("structure", [arch(), portal()], ids=["arch", "portal"])
def test_a_front_with_openings_is_refused_in_one_line(structure):
    for method in "ABC":
        with pytest.raises(BlastscaleInputError) as e:
            make_load(method, structure, blast_parameters(5.0, 5.0), load_model=LoadModel(clearing=True))
        assert "\n" not in str(e.value) and "blast.clearing = true" in str(e.value) and "openings" in str(e.value)
    # the negative phase and a free-air burst need no face: they run
    bp = blast_parameters(5.0, 5.0, burst="free-air")
    for method in "BC":
        ld = make_load(method, structure, bp, load_model=LoadModel(negative_phase=True))
        assert ld.charge_position[2] == pytest.approx(0.5 * structure_top(structure), rel=1e-12)


def test_arch_scenario_designs_without_clearing_and_refuses_it_with_exit_2(tmp_path, capsys):
    data = Scenario.default().model_dump(exclude_none=True)
    data["structure"] = {"kind": "arch"}
    data["blast"].update(charge_kg=5.0, standoff_m=5.0, blast_model="kingery-bulmash")
    sc = Scenario.from_dict({**data, "simulation": {"engine": "3d"}})
    assert Study(sc).design() is not None  # the lab-burst check reads the top, not a clearing face
    f = tmp_path / "arch.toml"
    f.write_text(
        '[structure]\nkind = "arch"\n[blast]\ncharge_kg = 5.0\nstandoff_m = 5.0\nclearing = true\n'
        '[scale]\nlength = 0.1\n[simulation]\nengine = "3d"\nduration_s = 0.05\n'
    )
    with pytest.raises(SystemExit) as e:
        main(["run", str(f), "--out", str(tmp_path / "out")])
    assert e.value.code == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("error:") and "\n" not in err and "openings" in err
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize(
    "values",
    [
        {"blast.negative_phase": True},
        {"blast.clearing": True},
        {"blast.burst": "free-air", "blast.blast_model": "kingery-bulmash"},
    ],
)
def test_the_planner_plans_the_scenarios_load_model(values):
    """Refused before issue #24 (deliverable 3): every candidate is now designed under the scenario's load
    model; clearing and the negative phase leave the planar kernels (the 3D stage, not run here: screening)."""
    from blastscale.planning.planner import screen
    from blastscale.planning.shot import DEFAULT_LAB

    sc = Scenario.default().with_values({"engine": "planar", **values})
    planar, evs, _ = screen(sc, DEFAULT_LAB)
    ok = [e for e in evs if not e.violations]
    assert ok and planar == ("blast.burst" in values)
    d = ok[0].design
    assert d.load_model.clearing == values.get("blast.clearing", False)
    assert d.load_model.negative_phase == values.get("blast.negative_phase", False)
    assert d.prototype.burst == values.get("blast.burst", "surface")
    assert d.specimen.burst == "surface"  # lab.bursts' default: the lab's charge on its floor (the law matches the
    # reflected impulse across the bursts, docs/blast_physics.md section 5)


def test_the_test_card_puts_a_free_air_lab_charge_on_its_stand():
    data = (
        Scenario.default()
        .with_values(
            {
                "duration_s": 1.0,
                "engine": "planar",
                "blast.blast_model": "kingery-bulmash",
                "scale.specimen_burst": "free-air",
                "scale.specimen_charge_height_m": 0.025,
            }
        )
        .model_dump(exclude_none=True)
    )
    data["lab"] = {"explosive": "tnt", "samples": 20, "seed": 1}
    res = Study(Scenario.from_dict(data)).run()
    card = study_test_card(res)
    assert card["burst"] == "free-air" and card["charge_height_m"] == 0.025
    lay = card["layout"]
    # the one frame (origin at the specimen's footprint centre): the stand-off in front of the front face
    front = res.design.specimen_structure.front_x
    assert lay["specimen_front_x_m"] == front and front < 0.0
    assert lay["charge"] == pytest.approx([front - card["standoff_m"], 0.0, 0.025], abs=1e-15)
    assert lay["specimen_centre"] == pytest.approx([0.0, 0.0, 0.0], abs=1e-12)
    m = card["explosive_mass_kg"]
    # a sphere of the explosive's mass (a surface charge is a hemisphere of the same mass)
    rho = get_explosive("tnt").density_kg_m3
    assert lay["charge_radius_m"] == pytest.approx((3.0 * m / (4.0 * math.pi * rho)) ** (1 / 3), rel=1e-12)
    html = card_section(res)
    assert "on a stand: free-air burst" in html and "sphere" in html and "on the floor: surface burst" not in html
    lb = res.design.effects["lab_burst"]
    assert lb["charge_height_m"] == 0.025
    if lb["kind"] != "free-air":
        assert any("not the free-air burst" in n for n in card["warnings"])


@pytest.mark.parametrize("key", ["clearing", "negative_phase"])
def test_gravity_alone_refuses_a_load_model_in_one_line(key):
    data = Scenario.default().model_dump(exclude_none=True)
    data["blast"] = {"charge_kg": 0.0, key: True}
    with pytest.raises(BlastscaleInputError) as e:
        Scenario.from_dict(data)
    assert "\n" not in str(e.value) and f"blast.{key} = true needs a charge" in str(e.value)
