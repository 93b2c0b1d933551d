"""The [lab] table: defaults, one-line errors, user-defined explosives, the TOML round trip, and the
bare keys it shares with other tables."""

import pytest

from blastscale._validate import BlastscaleInputError
from blastscale.scenario import Scenario, load_scenario
from blastscale.scenario.lab import LabSpec


def _with_lab(lab: dict) -> Scenario:
    data = Scenario.default().model_dump(exclude_none=True)
    data["lab"] = lab
    return Scenario.from_dict(data)


def test_defaults_are_stated():
    lab = _with_lab({}).lab
    assert lab == LabSpec()
    assert (lab.explosive, lab.initiator_tnt_kg, lab.charge_min_kg, lab.charge_max_kg) == ("tnt", 0.0, 0.0, 1.0)
    assert (lab.charge_tolerance, lab.standoff_tolerance_m, lab.friction_tolerance, lab.density_tolerance) == \
        (0.02, 0.001, 0.05, 0.02)
    assert Scenario.default().lab is None


@pytest.mark.parametrize("lab,words", [
    ({"friction_tolerance": -0.1}, "lab.friction_tolerance = -0.1 is out of range: valid range is [0, 1]"),
    ({"density_tolerance": -1.0}, "lab.density_tolerance = -1 is out of range"),
    ({"charge_min_kg": 0.5, "charge_max_kg": 0.1}, "charge_min_kg = 0.5 kg is above charge_max_kg = 0.1 kg"),
    ({"explosive": "dynamite"}, "explosive = 'dynamite' is not known"),
    ({"materials": ["granite", "cheese"]}, "lab.materials = 'cheese' is not known: valid values are same, marble"),
    ({"materials": []}, "lab.materials = [] is empty"),
    ({"explosives": {"x": {"pressure_factor": 0.0, "impulse_factor": 1.0}}},
     "lab.explosives.x.pressure_factor = 0 is out of range: valid range is (0, 10]"),
    ({"bogus": 1}, "lab.bogus = 1 is not a known key: valid keys of [lab] are explosive"),
])
def test_bad_entries_are_one_line(lab, words):
    with pytest.raises(BlastscaleInputError) as exc:
        _with_lab(lab)
    msg = str(exc.value)
    assert "\n" not in msg and words in msg


def test_user_explosive_and_toml_round_trip(tmp_path):
    sc = _with_lab({"explosive": "mine", "materials": ["balsa", "same"],
                    "explosives": {"mine": {"pressure_factor": 1.25, "impulse_factor": 1.1, "source": "maker"}}})
    p = tmp_path / "s.toml"
    p.write_text(sc.to_toml())
    again = load_scenario(p)
    assert again.lab == sc.lab and again.lab.explosives["mine"].impulse_factor == 1.1


def test_lab_keys_do_not_shadow_bare_keys():
    sc = _with_lab({})
    assert sc.resolve_key("samples") == "simulation.samples"
    assert sc.with_values({"samples": 101}).simulation.samples == 101
    assert sc.with_values({"lab.samples": 50}).lab.samples == 50
    assert sc.resolve_key("seed") == "lab.seed"
