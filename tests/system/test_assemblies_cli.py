"""The assemblies on the command line (issue 16): ``blastscale show`` (one table, JSON, the drawing
written through blastscale.io), and every bad file or bad generator parameter as one ``error:`` line,
exit status 2, nothing written (neither ``show --plot`` nor ``run --out``)."""

import json

import pytest

from blastscale.cli import main

WALL = '[structure]\nkind = "wall"\ncourses = 4\nunits_per_course = 3\n[blast]\ncharge_kg = 2.0\nstandoff_m = 4.0\n'


def cli(capsys, *argv):
    with pytest.raises(SystemExit) as e:
        main([str(a) for a in argv])
    cap = capsys.readouterr()
    return (e.value.code or 0), cap.out, cap.err


def _box(name, x0, x1, y0, y1, z0, z1):
    return {"name": name, "vertices": [[x, y, z] for x in (x0, x1) for y in (y0, y1) for z in (z0, z1)]}


def test_show_a_scenario_prints_one_table_and_writes_the_drawing(capsys, tmp_path):
    sc = tmp_path / "wall.toml"
    sc.write_text(WALL)
    code, out, err = cli(capsys, "show", sc, "--plot", tmp_path / "wall.png")
    assert code == 0, err
    assert "blocks" in out and "14" in out and "12000" in out  # 4 x 3 x 0.5 m x 2000 kg/m^3
    assert "interfaces between blocks" in out and "monitoring points" in out
    assert (tmp_path / "wall.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["wall.png", "wall.toml"]  # no partial file left


def test_show_json_of_a_block_model_file_and_a_shipped_scenario(capsys, tmp_path):
    p = tmp_path / "two.json"
    p.write_text(json.dumps({"blocks": [_box("A", 0, 1, 0, 1, 0, 1), _box("B", 0, 1, 0, 1, 1, 2)]}))
    code, out, _ = cli(capsys, "show", p, "--json", "--density", "2500")
    d = json.loads(out)
    assert code == 0 and d["blocks"] == 2 and d["mass_kg"] == pytest.approx(5000.0, rel=1e-12)
    assert d["interfaces_between_blocks"] == 1 and d["interfaces_on_ground"] == 1
    assert d["interface_area_between_blocks_m2"] == pytest.approx(1.0, rel=1e-12)
    assert d["monitoring_point_names"] == ["A", "B"]
    code, out, _ = cli(capsys, "show", "paper_column_square_250kg", "--json")
    d = json.loads(out)
    assert code == 0 and d["blocks"] == 10 and d["interfaces_between_blocks"] == 9 and d["monitoring_points"] == 10
    code, out, _ = cli(capsys, "show", "paper_block_50kg_lambda20", "--json")
    d = json.loads(out)  # the paper's 10 m block, alpha 15 deg, 1 m deep, 2000 kg/m^3
    assert code == 0 and d["blocks"] == 1 and d["interfaces_on_ground"] == 1 and d["interfaces_between_blocks"] == 0
    assert d["mass_kg"] == pytest.approx(2000.0 * 10.0 * 10.0 * 0.2679491924311227, rel=1e-9)


BAD_SCENARIOS = [
    ('kind = "wall"\ncourses = 0', "courses"),
    ('kind = "wall"\nthickness_m = -0.1', "thickness_m"),
    ('kind = "arch"\nthickness_m = 0.0', "thickness_m"),
    ('kind = "arch"\nthickness_m = -0.2', "thickness_m"),
    ('kind = "arch"\nembrace_deg = 400.0\npier_height_m = 1.0', "embrace_deg"),
    ('kind = "arch"\nembrace_deg = 120.0', "pier_height_m"),
    ('kind = "portal"\nspan_m = 0.0', "span_m"),
    ('kind = "portal"\ndrums = 0', "drums"),
]


@pytest.mark.parametrize("table, word", BAD_SCENARIOS)
def test_bad_generator_parameters_are_one_line_exit_2_nothing_written(capsys, tmp_path, table, word):
    sc = tmp_path / "bad.toml"
    sc.write_text(f"[structure]\n{table}\n")
    for args in (("show", sc, "--plot", tmp_path / "x.png"), ("run", sc, "--out", tmp_path / "res")):
        code, out, err = cli(capsys, *args)
        assert code == 2 and err.startswith("error:") and len(err.strip().splitlines()) == 1, err
        assert word in err
        assert sorted(p.name for p in tmp_path.iterdir()) == ["bad.toml"]  # nothing written


def _l_shape():
    """An L-shaped prism with its faces (non-convex: its hull is 17 % larger)."""
    xy = [(0, 0), (2, 0), (2, 1), (1, 1), (1, 2), (0, 2)]
    v = [[x, y, 0.0] for x, y in xy] + [[x, y, 1.0] for x, y in xy]
    faces = [[5, 4, 3, 2, 1, 0], [6, 7, 8, 9, 10, 11]] + [[k, (k + 1) % 6, (k + 1) % 6 + 6, k + 6] for k in range(6)]
    return {"name": "L", "vertices": v, "faces": faces}


BAD_FILES = [
    ({"blocks": [_l_shape()]}, "is not convex"),
    ({"blocks": [{"name": "E", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]]}]}, "'E' is empty"),
    ({"blocks": []}, "block"),
    ({"blocks": [{"name": "F", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]]}]}, "F"),  # zero volume
    ({"blocks": [_box("A", 0, 1000, 0, 500, 0, 300)]}, "millimetres"),
    ({"blocks": [_box("A", 0, 1, 0, 1, 0, 1), _box("B", 0.5, 1.5, 0, 1, 0, 1)]}, "overlap"),
    ({"blocks": [_box("A", 0, 1, 0, 1, 0, 1), _box("B", 0, 1, 0, 1, 2, 3)]}, "'B'"),  # floating
]


@pytest.mark.parametrize("data, word", BAD_FILES)
def test_bad_block_model_files_are_one_line_exit_2_nothing_written(capsys, tmp_path, data, word):
    f = tmp_path / "bad.json"
    f.write_text(json.dumps(data))
    sc = tmp_path / "bad.toml"
    sc.write_text('[structure]\nkind = "assembly"\nfile = "bad.json"\n')
    for args in (("show", f, "--plot", tmp_path / "x.png"), ("run", sc, "--out", tmp_path / "res")):
        code, out, err = cli(capsys, *args)
        assert code == 2 and err.startswith("error:") and len(err.strip().splitlines()) == 1, err
        assert word in err, err
        assert sorted(p.name for p in tmp_path.iterdir()) == ["bad.json", "bad.toml"]


@pytest.mark.parametrize(
    "args, word",
    [
        (("nosuch.json",), "no such file"),
        (("nosuch_scenario",), "cannot be read"),
        (("WALL", "--plot", "out.gif"), "valid extensions are .png"),
        (("WALL", "--plot", "nofolder/out.png"), "does not exist"),
        (("notes.txt",), "not a known kind of file"),
    ],
)
def test_show_bad_arguments_are_one_line(capsys, tmp_path, monkeypatch, args, word):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "wall.toml").write_text(WALL)
    (tmp_path / "notes.txt").write_text("hello")
    before = sorted(p.name for p in tmp_path.iterdir())
    code, out, err = cli(capsys, "show", *[("wall.toml" if a == "WALL" else a) for a in args])
    assert code == 2 and err.startswith("error:") and len(err.strip().splitlines()) == 1 and word in err, err
    assert sorted(p.name for p in tmp_path.iterdir()) == before


def test_gravity_alone_run_says_stands_by_the_stated_rule(capsys, tmp_path):
    sc = tmp_path / "g.toml"
    sc.write_text('[structure]\nkind = "wall"\ncourses = 3\nunits_per_course = 2\n[simulation]\nduration_s = 0.2\n')
    code, out, err = cli(capsys, "run", sc, "--out", tmp_path / "res", "--json")
    assert code == 0, err
    p = json.loads(out)["3d"]["prototype"]
    assert p["stability"] == "stands" and p["final_speed_rel_sqrt_gh"] < 1e-4
    assert p["max_residual_displacement_rel_height"] <= 1e-3
    html = (tmp_path / "res" / "report.html").read_text()
    assert 'Under gravity alone the structure <span class="ok">stands</span>' in html
    assert "1e-4 sqrt(g H)" in html and "1e-3 of the height H" in html
    assert (tmp_path / "res" / "assembly.png").is_file() and (tmp_path / "res" / "snapshots_3d.png").is_file()
