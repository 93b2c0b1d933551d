"""``blastscale run``: the result folder (complete or absent), its files, refusals, and Ctrl-C."""

import json
import os
import signal
import stat
import subprocess
import sys
import time
from pathlib import Path

import pytest
import xarray as xr
from _spawn import default_signals

from blastscale.cli import main

# the console script (as a user runs it), else the same entry point under that name
_SCRIPT = Path(sys.executable).with_name("blastscale")
BLASTSCALE = (
    [str(_SCRIPT)]
    if _SCRIPT.exists()
    else [sys.executable, "-c", "import sys; sys.argv[0] = 'blastscale'; from blastscale.cli import main; main()"]
)


def run_cli(capsys, *argv) -> tuple[int, str, str]:
    with pytest.raises(SystemExit) as e:
        main(list(argv))
    cap = capsys.readouterr()
    return (e.value.code or 0), cap.out, cap.err


def test_run_default_scenario_json(capsys, tmp_path):
    # The main job on the paper's default scenario: design (0.233 mg, paper Table, units corrected), planar
    # rocking that rocks without overturning and is similar (<= 5e-4 rad, issue #3), the critical charge
    # 79.87 kg (Friedlander, docs/design.md: 79.84-79.87), and the 3D up-scaled first peak of the block's front
    # point within 1 % (the contact is scale-consistent, docs/sim3d.md).
    out_dir = tmp_path / "run"
    code, out, err = run_cli(capsys, "run", "--json", "--out", str(out_dir))
    assert code == 0, err
    s = json.loads(out)
    assert s["design"]["model_charge_kg"] * 1e6 == pytest.approx(0.233, rel=1e-2)
    assert s["planar"]["prototype"]["collapsed"] is False
    assert s["planar"]["similarity"]["max_abs_rotation_diff_rad"] <= 5e-4
    assert s["critical"]["critical_charge_kg"] == pytest.approx(79.87, abs=0.01)
    assert s["3d"]["similarity"]["top_first_peak_ratio"] == pytest.approx(1.0, abs=0.01)
    assert {"blastscale", "numpy", "mujoco"} <= s["versions"].keys() and s["timestamp"]
    saved = json.loads((out_dir / "summary.json").read_text())
    assert saved["critical"] == s["critical"] and saved["scalars"] == s["scalars"]
    names = {p.name for p in out_dir.iterdir()}
    assert {
        "summary.json",
        "histories.nc",
        "report.html",
        "scenario.toml",
        "blast_pulses.png",
        "planar_rocking.png",
        "response_3d.png",
    } <= names
    assert "histories.csv" not in names  # only on request (run --csv): a column's is ~150 MB
    # an ordinary file and folder (the old summary.json was 0600 via tempfile)
    assert stat.S_IMODE((out_dir / "summary.json").stat().st_mode) & 0o044 == 0o044
    assert stat.S_IMODE(out_dir.stat().st_mode) & 0o055 == 0o055
    assert [p.name for p in tmp_path.iterdir()] == ["run"]  # no temporary sibling left


def test_histories_files_have_units_and_match(capsys, tmp_path):
    out_dir = tmp_path / "r"
    code, _, err = run_cli(
        capsys, "run", "--out", str(out_dir), "--duration", "0.3", "--set", "critical_charge=false", "--csv"
    )
    assert code == 0, err
    tree = xr.open_datatree(out_dir / "histories.nc")
    assert set(tree.children) == {"planar", "sim3d"}
    for node in tree.subtree:
        missing = [v for v in node.ds.variables if "units" not in node.ds[v].attrs]
        assert not missing, (node.path, missing)
    theta = tree["planar"]["rotation_y"].sel(system="prototype").values[:, 0]
    import pandas as pd

    csv = pd.read_csv(out_dir / "histories.csv")
    assert list(csv.columns) == [
        "engine",
        "system",
        "variable",
        "time_s",
        "element",
        "component",
        "member",
        "value",
        "units",
    ]
    rows = csv[(csv.engine == "planar") & (csv.system == "prototype") & (csv.variable == "rotation_y")]
    assert rows["value"].to_numpy() == pytest.approx(theta, rel=1e-9)  # CSV holds 10 significant digits
    assert set(rows["units"]) == {"rad"}


def test_existing_folder_refused_then_replaced_with_force(capsys, tmp_path):
    out_dir = tmp_path / "r"
    args = [
        "run",
        "--out",
        str(out_dir),
        "--duration",
        "0.1",
        "--set",
        "engine=planar",
        "--set",
        "critical_charge=false",
    ]
    assert run_cli(capsys, *args)[0] == 0
    first = (out_dir / "summary.json").read_text()
    code, _, err = run_cli(capsys, *args)
    assert code == 2 and "exists: refused (give --force to replace it)" in err and err.count("\n") == 1
    assert (out_dir / "summary.json").read_text() == first
    assert run_cli(capsys, *args, "--force", "--charge", "60")[0] == 0
    assert json.loads((out_dir / "summary.json").read_text())["scenario"]["blast"]["charge_kg"] == 60.0
    assert sorted(p.name for p in tmp_path.iterdir()) == ["r"]


@pytest.mark.parametrize("case", ["file", "parent_is_file", "not_a_result_folder", "huge_duration", "bad_set"])
def test_refusals_are_one_line_exit_2_nothing_written(capsys, tmp_path, case):
    target = tmp_path / "out"
    extra = []
    if case == "file":
        target.write_text("x")
    elif case == "parent_is_file":
        (tmp_path / "f").write_text("x")
        target = tmp_path / "f" / "out"
    elif case == "not_a_result_folder":
        target.mkdir()
        (target / "thesis.tex").write_text("x")
        extra = ["--force"]
    elif case == "huge_duration":
        extra = ["--duration", "1e5"]  # ~260 GiB of histories at the default 0.2 ms step
    else:
        extra = ["--set", "blast.charge_kg"]
    before = sorted(p.name for p in tmp_path.rglob("*"))
    code, _, err = run_cli(capsys, "run", "--out", str(target), *extra)
    assert code == 2 and err.startswith("error: ") and err.count("\n") == 1, err
    assert "Traceback" not in err
    assert sorted(p.name for p in tmp_path.rglob("*")) == before


def test_extrapolation_hint_names_the_scenario_key(capsys, tmp_path):
    code, _, err = run_cli(capsys, "run", "--set", "blast.standoff_m=100", "--charge", "1")
    assert code == 2 and "blast.extrapolate = true" in err and "CLI --extrapolate" not in err


def _wait_for(pred, timeout: float) -> bool:
    t0 = time.monotonic()
    while time.monotonic() - t0 < timeout:
        if pred():
            return True
        time.sleep(0.02)
    return False


@pytest.mark.parametrize("moment", ["started", "simulating", "writing"])
def test_ctrl_c_exits_130_one_line_no_partial_folder(tmp_path, moment):
    """Ctrl-C at three moments of `run`: no folder left, exit 130, one line. The run pauses at the moment
    (blastscale._hooks: it writes a marker file and waits) and the signal is sent once the marker is
    there, so the interruption always happens where the test says (no race with the clock)."""
    out_dir, marker = tmp_path / "r", tmp_path.parent / f"{tmp_path.name}.marker"
    env = {**os.environ, "BLASTSCALE_PAUSE_AT": f"run:{moment}", "BLASTSCALE_PAUSE_MARKER": str(marker)}
    proc = subprocess.Popen(
        BLASTSCALE + ["run", "--out", str(out_dir), "--duration", "0.2"],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        cwd=tmp_path,
        env=env,
        preexec_fn=default_signals,
    )
    assert _wait_for(marker.exists, 120), proc.communicate()[1]
    if moment != "started":  # the temporary folder exists: a partial result is on disk
        assert any(p.name.startswith(".r.partial-") for p in tmp_path.iterdir())
    proc.send_signal(signal.SIGINT)
    out, err = proc.communicate(timeout=60)
    assert proc.returncode == 130, err
    assert err.strip() == "error: interrupted (Ctrl-C): no partial results left"
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("exc", [OSError(28, "No space left on device"), KeyboardInterrupt()])
def test_output_folder_leaves_nothing_when_writing_fails(tmp_path, exc):
    from blastscale._validate import BlastscaleInputError
    from blastscale.io.results import output_folder

    expected = BlastscaleInputError if isinstance(exc, OSError) else KeyboardInterrupt
    with pytest.raises(expected):
        with output_folder(tmp_path / "r") as tmp:
            (tmp / "summary.json").write_text("{}")
            raise exc
    assert list(tmp_path.iterdir()) == []


def test_a_scenario_without_scale_runs_the_prototype_alone(capsys, tmp_path):
    """Issue #14: [scale] is optional. Without it there is no design and no comparison: the summary
    says so (design, model and similarity null), the histories hold the prototype only, and the
    report says it is a prototype-only study."""
    path = tmp_path / "proto.toml"
    path.write_text(
        'title = "prototype only"\n[structure]\nkind = "block"\n[blast]\ncharge_kg = 50.0\n'
        'standoff_m = 2.0\n[simulation]\nengine = "planar"\nduration_s = 1.0\n'
    )
    out_dir = tmp_path / "out"
    code, out, err = run_cli(capsys, "run", str(path), "--out", str(out_dir), "--json")
    assert code == 0, err
    s = json.loads(out)
    assert s["design"] is None and s["experiment"]["model"] is None
    assert s["planar"]["model"] is None and s["planar"]["similarity"] is None
    assert s["planar"]["prototype"]["max_rotation_rad"] > 0 and s["critical"]["critical_charge_kg"] > 50
    tree = xr.open_datatree(out_dir / "histories.nc")
    assert list(tree["planar"]["system"].values) == ["prototype"]
    html = (out_dir / "report.html").read_text()
    assert "Prototype only" in html and "<th>model (up-scaled)</th>" not in html


def test_a_3d_run_never_loads_the_planar_kernels(tmp_path):
    """A 3D-only run (a short column) writes its whole result folder without importing numba or the planar
    rocking kernels (0.27 s of a column run's start-up, issue #28; the rocking package's Python front loads no
    numba since issue #34: the kernels come with the first solve); a planar run does load them (the check can
    fail)."""
    code = (
        "import sys\nfrom blastscale.cli import main\n"
        "try:\n    main(sys.argv[1:])\nexcept SystemExit as e:\n    assert not e.code, e.code\n"
        "print(sorted(m for m in ('numba', 'blastscale.rocking.kernel') if m in sys.modules))\n"
    )
    sc = tmp_path / "c.toml"
    loaded = {}
    for engine in ("3d", "planar"):
        structure = '[structure]\nkind = "column"\ndrums = 3\n' if engine == "3d" else '[structure]\nkind = "block"\n'
        sc.write_text(
            f'{structure}[blast]\ncharge_kg = 100.0\nstandoff_m = 5.0\n[scale]\nlength = "1/20"\n[simulation]\nengine = "{engine}"\nduration_s = 0.1\n'
        )
        p = subprocess.run(
            [sys.executable, "-c", code, "run", str(sc), "--out", str(tmp_path / engine)],
            capture_output=True,
            text=True,
            timeout=300,
        )
        assert p.returncode == 0, p.stderr
        assert (tmp_path / engine / "report.html").exists()
        loaded[engine] = p.stdout.strip().splitlines()[-1]
    assert loaded == {"3d": "[]", "planar": "['blastscale.rocking.kernel', 'numba']"}


def test_a_command_runs_with_the_cli_collector_thresholds_then_restores_them(capsys, monkeypatch):
    """``main`` sets GC_THRESHOLDS while a command runs (the collector's full passes were 0.35 s of a column run)
    and puts back the caller's thresholds afterwards, also when the command fails."""
    import gc

    import blastscale.cli as cli

    before = gc.get_threshold()
    seen = []
    for argv in (["design", "--charge", "50", "--standoff", "2", "--scale", "1/20"], ["design", "--charge", "-1"]):
        gc.set_threshold(701, 11, 9)
        try:
            code, _, _ = run_cli(capsys, *argv)
            seen.append((code, gc.get_threshold()))
        finally:
            gc.set_threshold(*before)
    assert [c for c, _ in seen] == [0, 2] and all(t == (701, 11, 9) for _, t in seen)
    during = []
    monkeypatch.setattr(cli, "app", lambda args, prog_name: during.append(gc.get_threshold()))
    cli.main(["design"])
    assert during == [cli.GC_THRESHOLDS] and cli.GC_THRESHOLDS[0] > 700 and gc.get_threshold() == before
