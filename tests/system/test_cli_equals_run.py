"""One way in (issue #14): ``rock``, ``block3d`` and ``column`` print the same figures as
``blastscale run`` on the equivalent scenario.

Each command builds a Scenario from its flags and runs the Study; ``run`` gets the same scenario
from the built-in default and ``--set`` values (or a scenario file, for a prototype-only one).
The figures they share are compared exactly (``==`` on the parsed JSON: the same computation
printed twice), so a twin path that drifts by round-off fails here.
"""

from __future__ import annotations

import json

import pytest

from blastscale.cli import main
from blastscale.scenario import Scenario


def _json(capsys, *argv) -> dict:
    with pytest.raises(SystemExit) as e:
        main(list(argv))
    out = capsys.readouterr()
    assert (e.value.code or 0) == 0, out.err
    return json.loads(out.out)


def _run(capsys, *sets: str, scenario=None) -> dict:
    args = ["run"] + ([] if scenario is None else [str(scenario)])
    for s in sets:
        args += ["--set", s]
    return _json(capsys, *args, "--json")


def _shared(a: dict, b: dict) -> list:
    """The keys both dicts have (asserted non-trivial by the callers)."""
    return [k for k in a if k in b]


def test_rock_prints_the_figures_of_run_on_the_same_scenario(capsys):
    """``rock`` on the paper's block (50 kg at 2 m, masi2021, lambda = 1/200) = ``run`` of the
    built-in default (the same block) with the planar engine alone."""
    rock = _json(
        capsys,
        "rock",
        "--height",
        "10",
        "--alpha-deg",
        "15",
        "--charge",
        "50",
        "--standoff",
        "2",
        "--model",
        "masi2021",
        "--scale",
        "0.005",
        "--duration",
        "1.5",
        "--json",
    )
    run = _run(capsys, 'simulation.engine="planar"', "simulation.critical_charge=false", "simulation.duration_s=1.5")
    assert run["3d"] is None and run["critical"] is None
    for part in ("prototype", "model", "similarity"):
        keys = _shared(rock[part], run["planar"][part])
        assert len(keys) >= 5, (part, keys)
        assert {k: rock[part][k] for k in keys} == {k: run["planar"][part][k] for k in keys}, part
    assert rock["model_experiment"]["charge_kg"] == run["experiment"]["model"]["charge_kg"]
    assert rock["model_experiment"]["standoff_m"] == run["experiment"]["model"]["standoff_m"]


def test_block3d_prints_the_figures_of_run_on_the_same_scenario(capsys):
    """``block3d`` = ``run`` with the 3D engine alone: the block's planar keys are in the study's
    ``3d`` summary, next to the structure's."""
    b3 = _json(
        capsys,
        "block3d",
        "--height",
        "10",
        "--alpha-deg",
        "15",
        "--charge",
        "50",
        "--standoff",
        "2",
        "--model",
        "masi2021",
        "--scale",
        "0.005",
        "--duration",
        "0.4",
        "--json",
    )
    run = _run(capsys, 'simulation.engine="3d"', "simulation.duration_s=0.4")
    assert run["planar"] is None
    r3 = run["3d"]
    for part in ("prototype", "model", "similarity"):
        assert set(b3[part]) <= set(r3[part]), part  # every block3d key is in the study's summary
        assert b3[part] == {k: r3[part][k] for k in b3[part]}, part
    assert {"max_rotation_rad", "max_sliding_m", "collapsed", "points"} <= set(r3["prototype"])
    assert b3["model_experiment"]["charge_kg"] == run["experiment"]["model"]["charge_kg"]


def test_block3d_without_scale_prints_the_figures_of_a_prototype_only_run(capsys, tmp_path):
    """No ``--scale``: a prototype-only scenario; ``run`` of the same scenario file (no
    ``[scale]``) gives the same prototype figures and ``model`` / ``similarity`` None."""
    sc = Scenario.from_dict(
        {
            "structure": {"kind": "block", "height_m": 10.0, "width_m": 2.0},
            "blast": {"charge_kg": 10.0, "standoff_m": 5.0, "load": "B"},
            "simulation": {"engine": "3d", "duration_s": 0.2},
        }
    )
    path = tmp_path / "proto.toml"
    path.write_text(sc.to_toml())
    b3 = _json(
        capsys,
        "block3d",
        "--height",
        "10",
        "--width",
        "2",
        "--charge",
        "10",
        "--standoff",
        "5",
        "--load",
        "B",
        "--duration",
        "0.2",
        "--json",
    )
    run = _run(capsys, scenario=path)
    assert "model" not in b3 and run["3d"]["model"] is None and run["3d"]["similarity"] is None
    assert run["design"] is None and run["experiment"]["model"] is None
    assert b3["prototype"] == {k: run["3d"]["prototype"][k] for k in b3["prototype"]}


def test_column_prints_the_figures_of_run_on_the_same_scenario(capsys):
    """``column`` (a short 3-drum square column, 250 kg at 10 m, lambda = 1/100) = ``run`` of the
    default scenario turned into that column (Kingery-Bulmash, 3D engine)."""
    col = _json(
        capsys,
        "column",
        "--drums",
        "3",
        "--height",
        "3",
        "--top-width",
        "1.54",
        "--charge",
        "250",
        "--standoff",
        "10",
        "--scale",
        "0.01",
        "--duration",
        "0.3",
        "--json",
    )
    run = _run(
        capsys,
        'structure.kind="column"',
        "structure.drums=3",
        "structure.height_m=3.0",
        "structure.top_width_m=1.54",
        "blast.charge_kg=250.0",
        "blast.standoff_m=10.0",
        'blast.model="kingery-bulmash"',
        "scale.length=0.01",
        'simulation.engine="3d"',
        "simulation.duration_s=0.3",
    )
    for part in ("prototype", "model", "similarity"):
        assert col[part] == run["3d"][part], part
    assert col["structure"] == {k: run["experiment"]["prototype"][k] for k in col["structure"]}
    assert col["model_experiment"]["charge_kg"] == run["experiment"]["model"]["charge_kg"]
