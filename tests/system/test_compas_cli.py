"""COMPAS block models on the command line (issue 23, deliverable 4): ``blastscale show`` of a file
written by compas_dem (tests/data/compas_dem_arch_rotated.json, see
tests/unit/structures/test_compas_files.py) gives the rotated arch's extents, its supports and its
names; ``show --to-compas FILE`` writes the structure back as a COMPAS block model, which reads back
to the same description; a bad target is one ``error:`` line, exit status 2, nothing written."""

import json
from pathlib import Path

import pytest

from blastscale.cli import main

DATA = Path(__file__).resolve().parents[1] / "data" / "compas_dem_arch_rotated.json"


def cli(capsys, *argv):
    with pytest.raises(SystemExit) as e:
        main([str(a) for a in argv])
    cap = capsys.readouterr()
    return (e.value.code or 0), cap.out, cap.err


def test_show_json_of_a_rotated_compas_arch_with_supports_and_names(capsys):
    code, out, err = cli(capsys, "show", DATA, "--json")
    assert code == 0, err
    d = json.loads(out)
    # the model turned 90 deg about z: the 4.6 m span (5 m with the abutments) along y, the 0.5 m depth along x;
    # 2.7 m = 0.4 m (the voussoirs' own transformation) + 2.3 m (the crown's extrados)
    assert (d["height_m"], d["length_m"], d["thickness_m"]) == pytest.approx((2.7, 5.0, 0.5), abs=1e-12)
    assert d["blocks"] == 4 and d["block_names"] == ["V1", "V4", "V2", "V3"]
    assert d["supports"] == 2 and d["support_names"] == ["abutment-W", "abutment-E"]
    assert d["interfaces_on_ground"] == 2  # the springers on the abutments
    assert d["monitoring_point_names"] == d["block_names"]


def test_show_to_compas_round_trips(capsys, tmp_path):
    out_file = tmp_path / "back.json"
    code, _, err = cli(capsys, "show", DATA, "--to-compas", out_file)
    assert code == 0, err
    assert "wrote" in err and json.loads(out_file.read_text())["dtype"] == "compas_dem.models/BlockModel"
    first = json.loads(cli(capsys, "show", DATA, "--json")[1])
    again = json.loads(cli(capsys, "show", out_file, "--json")[1])
    assert again.keys() == first.keys()
    for k, v in first.items():  # the same blocks: every number to 1e-12 (m, kg, m^2), every name
        assert again[k] == (pytest.approx(v, rel=1e-12, abs=1e-12) if isinstance(v, float) else v), k


def test_show_to_compas_of_a_shipped_scenario(capsys, tmp_path):
    code, _, err = cli(capsys, "show", "paper_column_square_250kg", "--to-compas", tmp_path / "col.json")
    assert code == 0, err
    d = json.loads(cli(capsys, "show", tmp_path / "col.json", "--json")[1])
    assert d["blocks"] == 10 and d["supports"] == 0 and d["height_m"] == pytest.approx(10.0, rel=1e-12)


@pytest.mark.parametrize(
    "target, word", [("back.txt", "valid suffix is .json"), ("no/such/dir/back.json", "--to-compas")]
)
def test_bad_to_compas_targets_are_one_line_exit_2_nothing_written(capsys, tmp_path, target, word):
    code, _, err = cli(capsys, "show", DATA, "--to-compas", tmp_path / target)
    assert code == 2 and word in err and len(err.strip().splitlines()) == 1
    assert list(tmp_path.iterdir()) == []
