"""``blastscale fired``: the shipped example end to end, its ``--json`` keys, the result folder, and every bad
record of issue #25 item 2 as one line, exit status 2, nothing written."""

from __future__ import annotations

import json
import shutil
from importlib.resources import files
from pathlib import Path

import pytest

from blastscale.cli import main

EXAMPLE = Path(str(files("blastscale.fired") / "examples"))


def cli(capsys, *argv):
    with pytest.raises(SystemExit) as e:
        main(list(argv))
    cap = capsys.readouterr()
    return e.value.code, cap.out, cap.err


def _copy(tmp_path) -> Path:
    for name in ("shot.toml", "gauges.csv", "tracks.csv"):
        shutil.copy(EXAMPLE / name, tmp_path / name)
    return tmp_path / "shot.toml"


def test_example_json_has_the_issues_keys(capsys):
    code, out, err = cli(capsys, "fired", "example_shot", "--json")
    assert code in (0, None), err
    s = json.loads(out)["as_fired"]
    for k in (
        "effective_charge_tnt_kg",
        "effective_charge_from_pressure_tnt_kg",
        "gauges",
        "markers",
        "prototype_markers",
        "verdict",
        "similarity_verdict",
    ):
        assert k in s
    # fired 18 % over its design: the specimen's first peak 38 % over the prototype's under the design's event
    v = s["similarity_verdict"]
    assert v["similar"] is False and v["worst"]["quantity"] == "first peak" and v["worst"]["where"] == "planar"
    g = s["gauges"]["g1"]
    for k in (
        "peak_pressure_Pa",
        "impulse_Pa_s",
        "arrival_time_s",
        "positive_duration_s",
        "decay",
        "predicted_peak_pressure_Pa",
        "predicted_impulse_Pa_s",
        "incidence_deg",
        "drift_Pa_per_s",
        "ci95_impulse_Pa_s",
    ):
        assert isinstance(g[k], float)
    # the gauge is flush in the front face 5 cm up, the charge on the floor 0.1 m away: 26.6 deg (issue #36)
    assert g["incidence_deg"] == pytest.approx(26.565, abs=1e-3) and g["warnings"] == []
    m = s["markers"]["top"]
    for k in ("first_peak_m", "first_peak_time_s", "predicted_first_peak_m", "refit_first_peak_m"):
        assert isinstance(m[k], float)
    assert m["outcome_measured"] == m["outcome_refit"] == "stands"
    p = s["prototype_markers"]["top"]
    assert p["first_peak_p05_m"] < p["first_peak_m"] < p["first_peak_p95_m"]
    # the example was fired 15 % over the design (docs/fired.md): seen within 5 %
    assert s["charge_ratio_impulse"] == pytest.approx(1.15, rel=0.05)


def test_out_writes_the_folder(capsys, tmp_path):
    out = tmp_path / "res"
    code, _, err = cli(capsys, "fired", str(_copy(tmp_path)), "--out", str(out))
    assert code in (0, None), err
    names = sorted(p.name for p in out.iterdir())
    assert names == sorted(
        ["summary.json", "scenario.toml", "report.html", "fired_gauge_g1.png", "fired_marker_top.png"]
    )
    s = json.loads((out / "summary.json").read_text())
    assert "blastscale" in s["versions"] and s["as_fired"]["verdict"].startswith("As fired: ")
    assert "As fired" in (out / "report.html").read_text()


BAD = [
    ("gauges.csv", lambda t: "", "gauges.csv: no column, row 1: the file is empty"),
    ("gauges.csv", lambda t: t.replace("g1_kPa", "g1_atm", 1), "gauges.csv: column 'g1_atm', row 1: unknown unit"),
    ("gauges.csv", lambda t: t.replace("g1_kPa", "g9_kPa", 1), "gauges.csv: column 'g9_kPa', row 1: gauge 'g9' has no"),
    (
        "gauges.csv",
        lambda t: t.replace("\n-499.5,271.504", "\n-499.5,nan", 1),
        "gauges.csv: column 'g1_kPa', row 3: value 'nan'",
    ),
    (
        "gauges.csv",
        lambda t: t.replace("\n-499.5,", "\n-500,", 1),
        ("gauges.csv: column 'time_us', row 3: time -500 is not above the previous -500"),
    ),
    ("tracks.csv", lambda t: t.replace("top_z_mm", "top_z_in", 1), "tracks.csv: column 'top_z_in', row 1: unknown"),
    (
        "tracks.csv",
        lambda t: t.replace("top_x_mm", "side_x_mm", 1),
        ("tracks.csv: column 'side_x_mm', row 1: marker 'side' has no"),
    ),
]


@pytest.mark.parametrize("name,spoil,message", BAD)
def test_bad_records_are_one_line_exit_2_nothing_written(capsys, tmp_path, name, spoil, message):
    sc = _copy(tmp_path)
    f = tmp_path / name
    f.write_text(spoil(f.read_text()))
    out = tmp_path / "res"
    code, _stdout, err = cli(capsys, "fired", str(sc), "--out", str(out))
    assert code == 2
    lines = [ln for ln in err.strip().splitlines() if ln]
    assert len(lines) == 1 and message in lines[0], err
    assert not out.exists() and sorted(p.name for p in tmp_path.iterdir()) == ["gauges.csv", "shot.toml", "tracks.csv"]


def test_interrupted_write_leaves_nothing(patch_everywhere, tmp_path):
    """A fault after the first file is written (here: the second write raises) removes the partial folder:
    neither the result folder nor a partial one is left (io.results.output_folder)."""
    from blastscale.io import results

    real, calls = results.write_atomic, []

    def failing(path, data):
        calls.append(path)
        if len(calls) == 2:
            raise RuntimeError("disk gone")
        real(path, data)

    patch_everywhere(results, "write_atomic", failing)
    sc = _copy(tmp_path)
    with pytest.raises(RuntimeError, match="disk gone"):
        main(["fired", str(sc), "--out", str(tmp_path / "res")])
    assert len(calls) == 2
    assert sorted(p.name for p in tmp_path.iterdir()) == ["gauges.csv", "shot.toml", "tracks.csv"]


def test_calibrate_friction_on_a_block_is_one_line_exit_2_nothing_written(capsys, tmp_path):
    """The example shot is a block: friction does not enter its planar model; refused before any simulation."""
    sc = _copy(tmp_path)
    out = tmp_path / "res"
    code, _stdout, err = cli(capsys, "fired", str(sc), "--calibrate", "friction", "--out", str(out))
    lines = [ln for ln in err.strip().splitlines() if ln]
    assert code == 2 and len(lines) == 1 and "calibrate = 'friction' does not apply to a block" in lines[0], err
    assert not out.exists()
