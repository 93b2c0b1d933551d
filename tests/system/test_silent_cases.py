"""Issue #27, deliverables 4 and 5: every silent case is an error naming both values or a documented rule with one
warning line (conflicting --set, a flag and a --set, a --set replacing the key it excludes, a model larger than the
prototype, non-decimal and overflowing numbers, an infinite face, flags nothing runs on), and messages name the field
and the value given, never an internal name or a Python repr. Each case through the command line."""

from __future__ import annotations

import json

import pytest

from blastscale.cli import main
from blastscale.scenario import load_scenario


def cli(capsys, *argv) -> tuple[int, str, str]:
    with pytest.raises(SystemExit) as e:
        main([str(a) for a in argv])
    cap = capsys.readouterr()
    return (e.value.code or 0), cap.out, cap.err


def one_line(err: str) -> bool:
    return err.startswith("error: ") and err.count("\n") == 1 and "Traceback" not in err


@pytest.fixture
def planar(tmp_path):
    path = tmp_path / "planar.toml"
    path.write_text(load_scenario("planar_block").with_values({"duration_s": 0.2, "critical_charge": False}).to_toml())
    return path


@pytest.mark.parametrize(
    "sets, words",
    [
        (["charge_kg=20", "charge_kg=30"], "set = 'charge_kg=20' and 'charge_kg=30' set charge_kg twice: give it once"),
        (
            ["charge_kg=20", "blast.charge_kg=30"],
            "set = 'charge_kg=20' and 'blast.charge_kg=30' both set blast.charge_kg",
        ),
        (["charge_kg=0x10"], "set = 'charge_kg=0x10': '0x10' is not a decimal number (TOML reads it as 16)"),
        (["charge_kg=0o20"], "'0o20' is not a decimal number (TOML reads it as 16)"),
        (["charge_kg=1e309"], "set = 'charge_kg=1e309': 1e309 overflows a number"),
        (["charge_kg=inf"], "blast.charge_kg = inf is not a finite number"),
        (["height_m=1e308"], "structure.height_m = 1e+308 is out of range: valid range is (0, 1000] m"),
    ],
)
def test_conflicting_or_odd_set_values_are_one_line(capsys, tmp_path, planar, sets, words):
    argv = ["run", planar, "--out", tmp_path / "r"] + [a for s in sets for a in ("--set", s)]
    code, _, err = cli(capsys, *argv)
    assert code == 2 and one_line(err) and words in err, err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["planar.toml"]


def test_a_flag_and_a_set_for_the_same_key_name_both_values(capsys, tmp_path, planar):
    code, _, err = cli(capsys, "run", planar, "--charge", "20", "--set", "charge_kg=30", "--out", tmp_path / "r")
    assert code == 2 and one_line(err) and "--charge 20 and --set charge_kg=30 both set blast.charge_kg" in err
    code, _, err = cli(
        capsys,
        "sweep",
        planar,
        "--set",
        "charge_kg=1",
        "--set",
        "blast.charge_kg=2",
        "--vary",
        "standoff_m=2,3",
        "--out",
        tmp_path / "s.zarr",
    )
    assert code == 2 and one_line(err) and "'charge_kg=1' and 'blast.charge_kg=2' both set blast.charge_kg" in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["planar.toml"]


def test_a_set_replacing_the_key_it_excludes_warns_once(capsys, tmp_path, planar):
    code, out, err = cli(capsys, "run", planar, "--set", "width_m=2", "--out", tmp_path / "r", "--json")
    assert code == 0, err
    assert (
        err.count(
            "warning: structure.width_m = 2 replaces the scenario's structure.alpha_deg = 15 (they "
            "exclude each other: the value on the command line is kept)"
        )
        == 1
    ), err
    sc = load_scenario(tmp_path / "r" / "scenario.toml")
    assert sc.structure.width_m == 2.0 and sc.structure.alpha_deg is None


def test_a_model_larger_than_the_prototype_warns(capsys):
    code, out, err = cli(capsys, "design", "--charge", "50", "--standoff", "2", "--scale", "2", "--json")
    assert code == 0 and "warning: scale = 2 > 1: the specimen is 2 times larger than the prototype" in err
    # the stand-off scales with the length, R_m = lambda R, either way
    assert json.loads(out)["model_standoff_m"] == pytest.approx(4.0, rel=1e-12)


@pytest.mark.parametrize("value", ["inf", "1e308", "nan", "0"])
def test_an_infinite_or_overflowing_face_is_refused(capsys, value):
    code, _, err = cli(
        capsys, "blast", "--charge", "1", "--standoff", "5", "--clearing", "--face-width", "2", "--face-height", value
    )
    assert code == 2 and one_line(err) and "--face-height = " in err and "valid range is (0, 1000] m" in err, err
    assert "overflow" not in err


def test_flags_that_nothing_runs_on_warn(capsys, tmp_path):
    f = tmp_path / "p.toml"
    f.write_text(load_scenario("planar_block").to_toml() + "\n[lab]\nsamples = 200\n")
    code, _, err = cli(capsys, "plan", f, "--scheduler", "tcp://127.0.0.1:1", "--json")
    assert (
        code == 0
        and "warning: --scheduler tcp://127.0.0.1:1 not used: the plan runs on Dask only for its 3D "
        "ensemble, and lab.ensemble_3d = 0"
        in err
    ), err


@pytest.mark.parametrize(
    "argv, words",
    [
        (["rock", "--charge", "50", "--standoff", "2"], "--width and --alpha-deg are missing: give one of them"),
        (["rock", "--charge", "50", "--standoff", "2", "--alpha-deg", "95"], "--alpha-deg = 95 deg is out of range"),
        (
            ["rock", "--charge", "50", "--standoff", "2", "--alpha-deg", "15", "--width", "2"],
            "--width 2 and --alpha-deg 15 are both given",
        ),
        (["fragility", "planar_block", "--charges=-10,50"], "charges = [-10, 50] is out of range (-10 kg)"),
    ],
)
def test_the_first_error_is_the_real_one_and_no_internal_words(capsys, argv, words):
    code, _, err = cli(capsys, *argv)
    assert code == 2 and one_line(err) and words in err, err
    assert "None" not in err and "array(" not in err and "with_values" not in err


def test_a_huge_block_is_out_of_range_not_zero_volume(capsys, tmp_path):
    f = tmp_path / "huge.json"
    f.write_text(
        json.dumps({"blocks": [{"vertices": [[x, y, z] for x in (0, 1e308) for y in (0, 1e308) for z in (0, 1e308)]}]})
    )
    code, _, err = cli(capsys, "show", f)
    assert code == 2 and one_line(err) and "vertex coordinate 1e+308 m: out of range" in err, err


def test_rerunning_a_finished_sweep_prints_no_nan(capsys, tmp_path, planar):
    pytest.importorskip("zarr")
    argv = ["sweep", planar, "--vary", "standoff_m=2,3", "--workers", "0", "--out", tmp_path / "s.zarr"]
    assert cli(capsys, *argv)[0] == 0
    code, out, err = cli(capsys, *argv)
    assert code == 0 and "nan" not in out and "nothing computed" in out, out + err
