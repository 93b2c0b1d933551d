"""``blastscale plan`` and ``run`` with a [lab] table from the command line: the JSON keys of the issue,
the result folder, one-line errors (exit 2) for bad [lab] entries and for a lab no design fits."""

import json
import math

import pytest

from blastscale.analysis.intervals import wilson_interval
from blastscale.cli import main

PROTOTYPE = """
[structure]
kind = "block"
height_m = 10.0
alpha_deg = 15.0
[blast]
charge_kg = 50.0
standoff_m = 2.0
blast_model = "masi2021"
[simulation]
engine = "planar"
duration_s = 3.0
"""


def cli(capsys, *argv):
    with pytest.raises(SystemExit) as e:
        main(list(argv))
    cap = capsys.readouterr()
    return (e.value.code or 0), cap.out, cap.err


def _scenario(tmp_path, lab: str, scale: str = "") -> str:
    p = tmp_path / "s.toml"
    p.write_text(PROTOTYPE + scale + "\n[lab]\n" + lab)
    return str(p)


@pytest.mark.parametrize(
    "lab,words",
    [
        ("charge_tolerance = -0.01", "lab.charge_tolerance = -0.01 is out of range: valid range is [0, 1]"),
        ("standoff_tolerance_m = -1.0", "lab.standoff_tolerance_m = -1 is out of range"),
        ("charge_min_kg = 2.0\ncharge_max_kg = 1.0", "charge_min_kg = 2 kg is above charge_max_kg = 1 kg"),
        ('explosive = "dynamite"', "explosive = 'dynamite' is not known: valid values are tnt, c-4"),
        ('initiator = "no8"', "initiator = 'no8' is not known: valid values are rp-80, rp-83, no-8, none"),
        ("initiator_max_fraction = 1.5", "lab.initiator_max_fraction = 1.5 is out of range: valid range is (0, 1]"),
        ('materials = ["marble", "unobtainium"]', "lab.materials = 'unobtainium' is not known"),
        ("seed = 1.5", "lab.seed = 1.5 has the wrong type"),
        ('bursts = ["moon"]', "lab.bursts = 'moon' is not known: valid values are surface, free-air"),
        ("bursts = []", "lab.bursts = [] is empty"),
        ("top_3d = 0", "lab.top_3d = 0 is out of range"),
        ("ensemble_3d = -1", "lab.ensemble_3d = -1 is out of range"),
    ],
)
@pytest.mark.parametrize("command", ["plan", "run"])
def test_bad_lab_entries_are_one_line_exit_2(capsys, tmp_path, lab, words, command):
    code, out, err = cli(capsys, command, _scenario(tmp_path, lab, '\n[scale]\nlength = "1/20"\n'))
    assert code == 2 and out == ""
    assert err.count("\n") == 1 and err.startswith("error:") and words in " ".join(err.split())


def test_plan_json_has_the_issues_keys(capsys, tmp_path):
    code, out, err = cli(
        capsys, "plan", _scenario(tmp_path, 'specimen_max_height_m = 0.5\nexplosive = "c-4"\nsamples = 200\n'), "--json"
    )
    assert code == 0, err
    p = json.loads(out)
    assert p["designs"] and p["rejected"]
    for d in p["designs"]:
        for key in (
            "scale",
            "material",
            "density_ratio",
            "explosive_mass_kg",
            "tnt_equivalent_kg",
            "standoff_m",
            "specimen_mass_kg",
            "safety_distances_m",
            "camera_fps",
            "p_outcome_agree",
            "p_outcome_agree_low",
            "p_outcome_agree_high",
            "explosive_min_charge_kg",
            "initiator_tnt_kg",
            "initiator_fraction",
        ):
            assert key in d
        # C-4 for the impulse, beside the default RP-80 EBW detonator's TNT equivalent
        assert d["explosive_mass_kg"] == pytest.approx(
            (d["tnt_equivalent_kg"] - d["initiator_tnt_kg"]) / 1.19, rel=1e-12
        )
        assert d["explosive_mass_kg"] >= d["explosive_min_charge_kg"] and d["initiator_fraction"] <= 0.5
        assert set(d["safety_distances_m"]) == {"34.5 kPa", "6.9 kPa", "1.03 kPa", "200 Pa", "K24", "K40", "K50"}
    assert all(r["reasons"] for r in p["rejected"])


def test_infeasible_lab_is_one_line(capsys, tmp_path):
    code, out, err = cli(capsys, "plan", _scenario(tmp_path, "space_radius_m = 0.01\nsamples = 20\n"))
    assert code == 2 and err.count("\n") == 1
    assert "space_radius_m = 0.01 cannot be met" in " ".join(err.split())


def test_plan_out_writes_the_best_design_and_its_card(capsys, tmp_path):
    out_dir = tmp_path / "plan"
    code, out, err = cli(
        capsys, "plan", _scenario(tmp_path, "specimen_max_height_m = 0.5\nsamples = 200\n"), "--out", str(out_dir)
    )
    assert code == 0, err
    plan = json.loads((out_dir / "plan.json").read_text())
    summary = json.loads((out_dir / "summary.json").read_text())
    best = plan["designs"][0]
    card = summary["test_card"]
    assert card["explosive_mass_kg"] == pytest.approx(best["explosive_mass_kg"], rel=1e-12)
    assert card["safety_distances_m"] == pytest.approx(best["safety_distances_m"], rel=1e-12)
    assert card["standoff_m"] == pytest.approx(best["standoff_m"], rel=1e-12)
    html = (out_dir / "report.html").read_text()
    assert '<section id="plan">' in html and '<section id="test_card">' in html
    assert 'id="fig-plan_candidates"' in html  # every candidate, scale against charge, the Pareto front
    assert (out_dir / "plan_candidates.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert any(d["pareto"] for d in plan["designs"]) and all(d["pareto"] is not None for d in plan["designs"])
    assert "[lab]" in (out_dir / "scenario.toml").read_text()
    # the written scenario runs again to the same card
    code, out, err = cli(capsys, "run", str(out_dir / "scenario.toml"), "--json")
    assert code == 0, err
    assert json.loads(out)["test_card"]["p_outcome_agree"] == card["p_outcome_agree"]


@pytest.mark.parametrize(
    "scale,lab,words",
    [
        # 1/40: 0.10 g TNT in all, of which the RP-80 is 0.223 g: the initiator alone is more than the charge
        (
            '"1/40"',
            "samples = 20\n",
            [
                "the initiator alone (0.0002229 kg TNT) delivers more than the design's whole charge",
                "initiator_max_fraction = 0.5",
            ],
        ),
        # 1/40 without an initiator: 0.10 g of TNT, below its 0.724 g minimum reliable charge
        ('"1/40"', 'initiator = "none"\nsamples = 20\n', ["below its minimum reliable charge 0.0007238 kg"]),
    ],
)
def test_run_at_a_chosen_scale_warns_of_an_unfireable_shot_and_completes(capsys, tmp_path, scale, lab, words):
    code, out, err = cli(capsys, "run", _scenario(tmp_path, lab, f"\n[scale]\nlength = {scale}\n"), "--json")
    assert code == 0, err
    card = json.loads(out)["test_card"]
    flat = " ".join(err.split())
    for w in words:
        assert "warning: test card: " in flat and w in flat
        assert any(w in x for x in card["warnings"])
    assert card["explosive_min_charge_kg"] == pytest.approx(7.238e-4, rel=1e-3)
    assert card["initiator_max_fraction"] == 0.5


def test_a_redefined_library_explosive_warns_once_in_one_line(capsys, tmp_path):
    lab = (
        'explosive = "C4"\nsamples = 20\nspecimen_max_height_m = 0.5\n[lab.explosives.C4]\npressure_factor = 1.3\n'
        "impulse_factor = 1.2\n"
    )
    code, out, err = cli(capsys, "plan", _scenario(tmp_path, lab), "--json")
    assert code == 0, err
    lines = [x for x in err.splitlines() if "redefines" in x]
    assert len(lines) == 1 and lines[0].startswith("warning: lab.explosives.C4 redefines the library's explosive 'c-4'")
    assert all(d["explosive"] == "C4" for d in json.loads(out)["designs"])


ARCH = """
[structure]
kind = "arch"
radius_m = 2.5
thickness_m = 0.5
depth_m = 1.0
voussoirs = 9
[blast]
charge_kg = 20.0
standoff_m = 6.0
[scale]
length = "1/10"
[simulation]
engine = "3d"
duration_s = 0.1
[lab]
materials = ["same"]
"""


def test_run_of_an_arch_with_a_lab_gives_its_card(capsys, tmp_path):
    """Was: 'Assembly' object has no attribute 'height' after the whole simulation. The build gives the
    bounding box (lambda x the prototype's: the crown voussoir's extrados corners at (R + t/2) cos(10 deg) =
    2.708 m high for 9 voussoirs over 180 deg; 1 m along the blast) and one voussoir."""
    s = tmp_path / "arch.toml"
    s.write_text(ARCH + "ensemble_3d = 2\n")
    code, out, err = cli(capsys, "run", str(s), "--out", str(tmp_path / "o"))
    assert code == 0, err
    card = json.loads((tmp_path / "o" / "summary.json").read_text())["test_card"]
    o3 = card["odds_3d"]
    assert o3["members"] == 2  # the 3D ensemble of an arch's specimen (was: blocks only)
    # no planar path: the card's odds are the 3D ensemble's, with their Wilson interval (was: "-")
    assert (card["p_outcome_agree"], card["p_outcome_agree_low"], card["p_outcome_agree_high"]) == (
        o3["p_outcome_agree"],
        *wilson_interval(o3["agree_count"], 2),
    )
    html = (tmp_path / "o" / "report.html").read_text()
    assert f"(95 %, {o3['agree_count']} of 2)" in html  # the card row "outcome agrees ... (3D ensemble)"
    b = card["build"]
    assert b["kind"] == "arch" and b["height_m"] == pytest.approx(0.275 * math.cos(math.pi / 18), rel=1e-9)
    assert b["width_m"] == pytest.approx(0.1, rel=1e-9) and b["unit"]["bodies"] == 9
    u = b["unit"]
    assert u["size_x_m"] == pytest.approx(0.1, rel=1e-6) and max(u["size_y_m"], u["size_z_m"]) < 0.1
    assert b["unit"]["mass_kg"] == pytest.approx(b["mass_kg"] / 9, rel=1e-9)


def test_plan_of_a_wall_from_the_command_line(capsys, tmp_path):
    s = tmp_path / "wall.toml"
    s.write_text(
        ARCH.replace(
            'kind = "arch"\nradius_m = 2.5\nthickness_m = 0.5\ndepth_m = 1.0\nvoussoirs = 9',
            'kind = "wall"\nlength_m = 2.0\nheight_m = 1.0\nthickness_m = 0.5\ncourses = 2\nunits_per_course = 2',
        ).replace('[scale]\nlength = "1/10"\n', "")
        + "ensemble_3d = 2\ntop_3d = 1\n"
    )
    code, out, err = cli(capsys, "plan", str(s), "--json")
    assert code == 0, err
    p = json.loads(out)
    d = next(x for x in p["designs"] if "screening rank 1 (lab.top_3d = 1)" in (x.get("chosen_3d_for") or []))
    assert d["odds_3d"]["members"] == 2 and d["burst"] == "surface" and d["charge_height_m"] == 0.0
    assert p["prototype"]["kind"] == "wall" and any(x["pareto"] for x in p["designs"])
