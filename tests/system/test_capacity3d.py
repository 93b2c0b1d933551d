"""Capacity of any structure in 3D (issue #38.3): ``blastscale capacity SCENARIO`` of a drum column, the
critical charge at two stand-offs by bisection on 3D ensembles, checked against direct runs at +-5 %; the
P-I points against the blast fits; a bracket that brackets nothing is a "no"; a block's scenario is the same
command's planar instance, its numbers those of the block's flags.

Kept small to stay within the test budget (a few seconds): a 3 m column of two drums, 1 s runs, two members
per probe and a 4 % final bracket; the 10-drum column is benchmarks/bench_capacity3d.py (figures in
docs/capacity.md)."""

import contextlib
import io
import json

import pytest

from blastscale.blast.parameters import blast_parameters
from blastscale.cli import main
from blastscale.scenario.files import load_scenario
from blastscale.study import Study
from blastscale.sweeps.capacity3d import critical_charges_3d, planned_probes

COLUMN = """title = "two-drum column, 3 m"
[structure]
kind = "column"
drums = 2
height_m = 3.0
base_width_m = 0.5
top_width_m = 0.4
[blast]
charge_kg = 10.0
standoff_m = 3.0
[simulation]
duration_s = 1.0
"""
STANDOFFS = (3.0, 5.0)


def cli(capsys, *argv):
    with pytest.raises(SystemExit) as e:
        main([str(a) for a in argv])
    cap = capsys.readouterr()
    return (e.value.code or 0), cap.out, cap.err


@pytest.fixture(scope="module")
def column(tmp_path_factory):
    p = tmp_path_factory.mktemp("capacity3d") / "column.toml"
    p.write_text(COLUMN)
    return p


@pytest.fixture(scope="module")
def capacity(column):
    """``capacity --json`` of the column at two stand-offs (the command's own JSON)."""
    buf = io.StringIO()
    argv = [
        "capacity",
        column,
        "--standoffs",
        "3,5",
        "--members",
        2,
        "--bracket",
        "4:80",
        "--tolerance",
        0.04,
        "--json",
    ]
    with contextlib.redirect_stdout(buf), pytest.raises(SystemExit) as e:
        main([str(a) for a in argv])
    assert (e.value.code or 0) == 0
    return json.loads(buf.getvalue())


def fell(column, charge: float, standoff: float) -> bool:
    """A direct run of the study (the scenario at this charge and stand-off, 3D, no ensemble): a body fell?"""
    sc = load_scenario(column).with_values(
        {"blast.charge_kg": charge, "blast.standoff_m": standoff, "simulation.engine": "3d"}
    )
    return Study(sc).run().response3d.to_dict()["prototype"]["fallen_blocks"] > 0


def test_the_critical_charge_and_its_interval_lie_inside_the_bracket_of_direct_runs_at_5_percent(capacity, column):
    """Acceptance (issue #38): at each stand-off a direct run at 0.95 W_c stands and one at 1.05 W_c falls, and
    the interval lies inside [0.95, 1.05] W_c (the bisection's 4 % bracket)."""
    assert capacity["standoff_m"] == list(STANDOFFS)
    for R, W, iv in zip(STANDOFFS, capacity["critical_charge_kg"], capacity["interval_kg"]):
        assert W is not None and 4.0 < W < 80.0
        assert 0.95 * W <= iv[0] <= W <= iv[1] <= 1.05 * W
        assert iv[1] / iv[0] <= 1.04 + 1e-12
        assert not fell(column, 0.95 * W, R)
        assert fell(column, 1.05 * W, R)
    # farther, more charge (Hopkinson-Cranz: roughly R^3 for an impulsive load, less for a finite pulse)
    w3, w5 = capacity["critical_charge_kg"]
    assert 1.5 < w5 / w3 < (5.0 / 3.0) ** 3


def test_the_search_states_its_bracket_and_probes(capacity):
    for s in capacity["searches"]:
        assert s["initial_bracket_kg"] == [4.0, 80.0]
        first = s["probes"][:2]  # the stated bracket, probed first: stands at 4 kg, falls at 80 kg
        assert [p["charge_kg"] for p in first] == [4.0, 80.0]
        assert first[0]["fell"] == 0 and first[1]["fell"] == 2
        assert s["runs"] == 2 * len(s["probes"])
        assert len(s["probes"]) == planned_probes((4.0, 80.0), 0.04) == 9  # 2 + ceil(log2(ln 20 / ln 1.04))
        assert s["interval_basis"] in ("bisection bracket", "lognormal fit, 95 %")


def test_the_pressure_impulse_points_are_the_blast_at_the_critical_charges(capacity):
    pi = capacity["pressure_impulse"]
    for R, W, p, i in zip(
        STANDOFFS, capacity["critical_charge_kg"], pi["reflected_pressure_Pa"], pi["reflected_impulse_Pa_s"]
    ):
        bp = blast_parameters(W, R, "kingery-bulmash")  # the scenario's default blast model and surface burst
        assert p == pytest.approx(bp.reflected_pressure, rel=1e-12)
        assert i == pytest.approx(bp.reflected_impulse, rel=1e-12)
    # farther stand-off, the collapse needs a larger impulse at a lower pressure (the P-I curve's shape)
    assert pi["reflected_impulse_Pa_s"][1] > pi["reflected_impulse_Pa_s"][0]


def test_a_bracket_that_brackets_nothing_is_a_no(column):
    """The answer must be "no": at 1-2 kg every member stands at both ends: no critical charge, the reason said."""
    (res,) = critical_charges_3d(load_scenario(column), [3.0], bracket=(1.0, 2.0), members=1)
    assert res.critical_charge_kg is None and res.interval_kg is None
    assert "does not bracket" in res.note and res.runs == 2


def test_a_block_scenario_is_the_planar_instance_of_the_same_command(capsys, tmp_path):
    """A block's scenario gives the numbers of the block's flags (the first-swing criterion, unchanged)."""
    p = tmp_path / "block.toml"
    p.write_text(
        '[structure]\nkind = "block"\nheight_m = 10.0\nalpha_deg = 15.0\n[blast]\nblast_model = "masi2021"\ncharge_kg = 50.0\nstandoff_m = 2.0\n'
    )
    code, out, err = cli(capsys, "critical", p, "--standoff", "2", "--json")
    assert code == 0, err
    by_scenario = json.loads(out)
    code, out, err = cli(
        capsys, "critical", "--height", "10", "--alpha-deg", "15", "--density", "2000", "--model", "masi2021",
        "--standoff", "2", "--json",
    )  # fmt: skip
    assert code == 0, err
    by_flags = json.loads(out)
    assert by_scenario["critical_charge_kg"] == by_flags["critical_charge_kg"]  # bitwise
    assert by_scenario["critical_charge_kg"] == pytest.approx(79.87, abs=0.01)  # paper: 79.8 kg
    code, _, err = cli(capsys, "critical", p, "--height", "5", "--json")
    assert code == 2 and "--height" in err and "--set" in err
    code, _, err = cli(capsys, "critical", p, "--members", "3", "--json")  # the 3D search's flag, not ignored
    assert code == 2 and "--members" in err and "3D" in err


def test_a_block_scenario_gives_its_keys_to_both_planar_commands(capsys, tmp_path):
    """``critical`` and ``capacity`` read a block's scenario by one helper: its keys (restitution, gravity, the
    negative phase, the stand-off) give the numbers of the same flags, bitwise; a different key, different
    numbers (the answer "no": the keys are not ignored)."""
    p = tmp_path / "block.toml"
    keys = (
        '[structure]\nkind = "block"\nheight_m = 10.0\nalpha_deg = 15.0\n[blast]\ncharge_kg = 50.0\nstandoff_m = 2.0\n'
    )
    p.write_text(keys + "negative_phase = true\n[simulation]\nrestitution = 0.6\ngravity_m_s2 = 9.5\n")
    block = ["--height", "10", "--alpha-deg", "15", "--density", "2000", "--restitution", "0.6", "--gravity", "9.5"]
    by = {}
    for name, argv in (
        ("scenario", ["capacity", p, "--standoffs", "2,4"]),
        ("flags", ["capacity", *block, "--standoffs", "2,4"]),
        ("critical scenario", ["critical", p]),  # the scenario's stand-off
        ("critical flags", ["critical", *block, "--standoff", "2", "--negative-phase"]),
        ("critical other", ["critical", p, "--set", "blast.negative_phase=false"]),
    ):
        code, out, err = cli(capsys, *argv, "--json")
        assert code == 0, err
        by[name] = json.loads(out)
    assert by["scenario"]["critical_charge_kg"] == by["flags"]["critical_charge_kg"]
    assert by["scenario"]["inputs"] == by["flags"]["inputs"] and by["scenario"]["inputs"]["restitution"] == 0.6
    crit, flags = by["critical scenario"], by["critical flags"]
    assert crit["critical_charge_kg"] == flags["critical_charge_kg"] and crit["standoff_m"] == 2.0
    assert crit["negative_phase_uncertainty"] == flags["negative_phase_uncertainty"]
    assert "negative_phase_uncertainty" not in by["critical other"]
