"""``blastscale plan`` judges its designs by the one similarity criterion (issue #35): an arch and a circular
column (shortened: 0.3 s of prototype time, two ensemble members, one screening leader, one material) never rank
first a design their own report (``plan --out``: summary.json's ``verdict``) rejects; a strict ``[verdict]`` table
(peak = 1e-6) rejects every design, and one line says so, naming the closest design and the binding quantity."""

import html
import json
from pathlib import Path

import pytest

from blastscale.cli import main
from blastscale.planning import plan
from blastscale.scenario import Scenario, load_scenario
from blastscale.scenario.lab import LabSpec

LIB = Path(__file__).resolve().parents[2] / "src" / "blastscale" / "scenario" / "library"
LAB = '\n[lab]\nmaterials = ["same"]\nensemble_3d = 2\ntop_3d = 1\nspecimen_max_height_m = 1.0\n'
ARCH = """
[structure]
kind = "arch"
radius_m = 2.5
thickness_m = 0.5
depth_m = 1.0
voussoirs = 9
density_kg_m3 = 2400.0
[blast]
charge_kg = 20.0
standoff_m = 6.0
[simulation]
engine = "3d"
duration_s = 0.3
"""


def _plan_out(capsys, tmp_path, text: str) -> tuple:
    s = tmp_path / "s.toml"
    s.write_text(text)
    with pytest.raises(SystemExit) as e:
        main(["plan", str(s), "--out", str(tmp_path / "o")])
    cap = capsys.readouterr()
    assert (e.value.code or 0) == 0, cap.err
    o = tmp_path / "o"
    return json.loads((o / "plan.json").read_text()), json.loads((o / "summary.json").read_text()), cap.out, o


def _never_recommends_what_its_report_rejects(p: dict, summary: dict, out: str, folder) -> None:
    first, rec, v = p["designs"][0], p["recommendation"], summary["verdict"]
    assert first["verdict"]["line"] == v["line"]  # the report's verdict is the plan's, word for word
    assert first["verdict"]["similar"] == v["similar"]
    assert (rec["design"] == 0) == (v["similar"] is True)  # recommended iff its own report passes it
    judged = [d["verdict"]["similar"] for d in p["designs"] if d["verdict"] is not None]
    assert judged == sorted(judged, key=lambda s: s is not True)  # every passing design before every other
    flat = lambda t: " ".join(html.unescape(t).split())  # the console wraps its lines; the report escapes
    assert flat(rec["line"]) in flat(out) and flat(v["line"]) in flat((folder / "report.html").read_text())
    assert flat(rec["line"]) in flat((folder / "report.html").read_text())
    if rec["design"] is None:
        assert rec["line"].startswith("No design passes the similarity criterion") and "Closest design" in out
    else:
        assert rec["line"].startswith("Recommended: ") and "Recommended design:" in out


@pytest.mark.slow
def test_plan_of_an_arch_never_recommends_what_its_report_rejects(capsys, tmp_path):
    p, summary, out, o = _plan_out(capsys, tmp_path, ARCH + LAB)
    _never_recommends_what_its_report_rejects(p, summary, out, o)
    assert summary["scenario"]["structure"]["kind"] == "arch"


@pytest.mark.slow
def test_plan_of_a_circular_column_never_recommends_what_its_report_rejects(capsys, tmp_path):
    text = (LIB / "paper_column_circular_200kg.toml").read_text()
    text = text.replace("duration_s = 8.0", "duration_s = 0.3").replace("ensemble_members = 4", "ensemble_members = 2")
    assert "duration_s = 0.3" in text and "ensemble_members = 2" in text
    p, summary, out, o = _plan_out(capsys, tmp_path, text + LAB)
    _never_recommends_what_its_report_rejects(p, summary, out, o)
    assert summary["ensemble"] is not None  # chaotic drums: judged between ensembles, in the plan and its report


@pytest.mark.slow
@pytest.mark.parametrize("kind", ["arch", "circular column"])
def test_a_strict_verdict_rejects_every_design_and_says_so_in_one_line(kind):
    """peak = 1e-6: no up-scaled first peak is within a millionth of the prototype's; nothing is recommended."""
    if kind == "arch":
        sc = Scenario.from_dict({**_toml(ARCH), "verdict": {"peak": 1e-6}}, source="test")
    else:
        sc = load_scenario(LIB / "paper_column_circular_200kg.toml").with_values(
            {"duration_s": 0.3, "ensemble_members": 0, "verdict.peak": 1e-6}
        )
    p = plan(sc, lab=LabSpec(materials=["same"], ensemble_3d=2, top_3d=1, specimen_max_height_m=1.0))
    rec = p.recommendation
    judged = [d for d in p.designs if d["verdict"] is not None]
    assert judged and all(d["verdict"]["similar"] is False for d in judged)
    assert rec["design"] is None and rec["closest"] == 0 and rec["binding_quantity"] == "first peak"
    ratios = [d["verdict"]["worst"]["ratio"] for d in judged]
    assert rec["binding_ratio"] == min(ratios) > 1.0
    d = p.designs[0]
    assert rec["line"].startswith(
        f"No design passes the similarity criterion ([verdict]; {len(judged)} judged): the closest is "
        f"{d['law']} law, lambda = {d['scale_fraction']}, {d['material']} (first peak at "
    )
    assert "; the binding quantity: first peak" in rec["line"] and rec["line"].count("\n") == 0


def _toml(text: str) -> dict:
    import tomllib

    return tomllib.loads(text)
