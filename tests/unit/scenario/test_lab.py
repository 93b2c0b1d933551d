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
    assert (lab.explosive, lab.charge_min_kg, lab.charge_max_kg) == ("tnt", 0.0, 1.0)
    # the RP-80 EBW detonator: 80 mg PETN x 1.11 + 123 mg RDX x 1.09 (impulse basis, IATG 01.80)
    assert (lab.initiator, lab.initiator_max_fraction) == ("rp-80", 0.5)
    assert lab.initiator_tnt_kg == pytest.approx(80e-6 * 1.11 + 123e-6 * 1.09, rel=1e-12)
    assert (lab.charge_tolerance, lab.standoff_tolerance_m, lab.friction_tolerance, lab.density_tolerance) == (
        0.02,
        0.001,
        0.05,
        0.02,
    )
    assert Scenario.default().lab is None


@pytest.mark.parametrize(
    "lab,words",
    [
        ({"friction_tolerance": -0.1}, "lab.friction_tolerance = -0.1 is out of range: valid range is [0, 1]"),
        ({"density_tolerance": -1.0}, "lab.density_tolerance = -1 is out of range"),
        ({"charge_min_kg": 0.5, "charge_max_kg": 0.1}, "charge_min_kg = 0.5 kg is above charge_max_kg = 0.1 kg"),
        ({"explosive": "dynamite"}, "explosive = 'dynamite' is not known"),
        ({"materials": ["granite", "cheese"]}, "lab.materials = 'cheese' is not known: valid values are same, marble"),
        ({"materials": []}, "lab.materials = [] is empty"),
        (
            {"explosives": {"x": {"pressure_factor": 0.0, "impulse_factor": 1.0}}},
            "lab.explosives.x.pressure_factor = 0 is out of range: valid range is (0, 10]",
        ),
        ({"bogus": 1}, "lab.bogus = 1 is not a known key: valid keys of [lab] are explosive"),
        ({"initiator": "no8"}, "initiator = 'no8' is not known: valid values are rp-80, rp-83, no-8, none"),
        ({"initiator_max_fraction": 0.0}, "lab.initiator_max_fraction = 0 is out of range: valid range is (0, 1]"),
        ({"initiator_max_fraction": 1.5}, "lab.initiator_max_fraction = 1.5 is out of range"),
        ({"initiator_tnt_kg": -1e-3}, "lab.initiator_tnt_kg = -0.001 is out of range"),
    ],
)
def test_bad_entries_are_one_line(lab, words):
    with pytest.raises(BlastscaleInputError) as exc:
        _with_lab(lab)
    msg = str(exc.value)
    assert "\n" not in msg and words in msg


def test_user_explosive_and_toml_round_trip(tmp_path):
    sc = _with_lab(
        {
            "explosive": "mine",
            "materials": ["balsa", "same"],
            "explosives": {"mine": {"pressure_factor": 1.25, "impulse_factor": 1.1, "source": "maker"}},
        }
    )
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


@pytest.mark.parametrize(
    "name,canonical",
    [
        ("C-4", "c-4"),
        ("c4", "c-4"),
        ("Composition C-4", "c-4"),
        ("Comp B", "composition-b"),
        ("PETN", "petn"),
        ("RDX", "rdx"),
        ("hmx", "hmx"),
        ("PE4", "pe4"),
        ("Semtex H", "semtex"),
    ],
)
def test_explosives_as_users_name_them(name, canonical):
    assert _with_lab({"explosive": name}).lab.explosive == canonical


def test_a_redefined_library_explosive_warns_in_one_line():
    with pytest.warns(UserWarning) as rec:
        lab = _with_lab({"explosive": "C4", "explosives": {"C4": {"pressure_factor": 1.2, "impulse_factor": 1.1}}}).lab
    msgs = [str(w.message) for w in rec if "redefines" in str(w.message)]
    assert len(msgs) >= 1 and "\n" not in msgs[0] and "'c-4'" in msgs[0]
    assert lab.explosive == "C4"  # the user's table, not the library's


def test_no_initiator_and_a_stated_one():
    assert _with_lab({"initiator": "none"}).lab.initiator_tnt_kg == 0.0
    assert _with_lab({"initiator_tnt_kg": 1e-3}).lab.initiator_tnt_kg == 1e-3


def test_a_new_initiator_brings_its_own_tnt_equivalent():
    """The named initiator's TNT equivalent is derived, not written back: --set lab.initiator=none gives 0, a
    stated initiator_tnt_kg stays stated, and the TOML of a default [lab] names the initiator only."""
    sc = _with_lab({})
    assert sc.with_values({"lab.initiator": "none"}).lab.initiator_tnt_kg == 0.0
    assert sc.with_values({"lab.initiator_tnt_kg": 1e-3}).lab.initiator_tnt_kg == 1e-3
    stated = _with_lab({"initiator_tnt_kg": 0.0})
    assert stated.with_values({"lab.samples": 50}).lab.initiator_tnt_kg == 0.0
    assert "initiator_tnt_kg" not in sc.to_toml() and 'initiator = "rp-80"' in sc.to_toml()


def test_a_written_scenario_names_a_source_beside_it_relative_so_the_folder_moves(tmp_path):
    """``to_toml(folder)`` (the scenario.toml of ``plan --out`` and ``run --out``): a source file next to the
    written folder (under its parent) or under it is named relative to the folder, so that the project moved
    elsewhere still reads it; the answer "no": a source elsewhere stays as given (absolute), and without a
    folder the text is as before."""
    import tomllib
    from pathlib import Path

    project = tmp_path / "project"
    (project / "sources").mkdir(parents=True)
    (project / "out" / "data").mkdir(parents=True)
    beside, under = project / "sources" / "bank.toml", project / "out" / "data" / "bank.toml"
    for f in (beside, under):
        f.write_text("# a calibrated source's file\n", encoding="utf-8")
    out = project / "out"
    for source, written in ((beside, "../sources/bank.toml"), (under, "data/bank.toml")):
        sc = _with_lab({"source": str(source)})
        assert tomllib.loads(sc.to_toml(out))["lab"]["source"] == written
        assert tomllib.loads(sc.to_toml())["lab"]["source"] == str(source)
    (out / "scenario.toml").write_text(_with_lab({"source": str(beside)}).to_toml(out), encoding="utf-8")
    moved = tmp_path / "moved"
    project.rename(moved)
    back = load_scenario(moved / "out" / "scenario.toml")
    assert Path(back.lab.source).resolve() == (moved / "sources" / "bank.toml").resolve()
    assert Path(back.lab.source).is_file()
    far = tmp_path / "elsewhere" / "bank.toml"  # not under the written folder's parent
    assert tomllib.loads(_with_lab({"source": str(far)}).to_toml(moved / "out"))["lab"]["source"] == str(far)
