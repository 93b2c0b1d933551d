"""The size of every run said first (issue #27, deliverable 3), driven by the CLI as a user would: the estimate
line before the run starts, a block-model file over the limit refused in one line naming the limit (exit 2,
nothing written), the study's guard naming the largest structure that fits, and plain progress lines when
standard error is a file (a batch job, CI)."""

from __future__ import annotations

import json
import os
import re
import signal
import subprocess
from pathlib import Path

from _spawn import BLASTSCALE, run, spawn, wait_for_marker


def _wall_file(path: Path, courses: int, units: int) -> Path:
    """A stack-bonded wall of 0.5 x 0.25 x 0.15 m boxes as our block-model JSON."""
    blocks = [
        {"vertices": [[x, u * 0.25 + y, c * 0.15 + z] for x in (0.0, 0.5) for y in (0.0, 0.25) for z in (0.0, 0.15)]}
        for c in range(courses)
        for u in range(units)
    ]
    path.write_text(json.dumps({"blocks": blocks}))
    return path


def _scenario(folder: Path, blocks: str, duration: float) -> Path:
    p = folder / "wall.toml"
    p.write_text(
        f'[structure]\nkind = "assembly"\nfile = "{blocks}"\n[blast]\ncharge_kg = 10.0\nstandoff_m = 5.0\n'
        f'[scale]\nlength = 0.05\n[simulation]\nengine = "3d"\nduration_s = {duration}\n'
    )
    return p


def test_the_estimate_is_said_before_the_run_starts(tmp_path):
    # 22 blocks for 20 s: well over the announcing threshold (10 s or 20 MB); paused as the simulation starts,
    # so nothing is simulated: the line must already be there, and it names what the estimate is made of
    sc = _scenario(tmp_path, _wall_file(tmp_path / "w.json", 2, 11).name, 20.0)
    marker = tmp_path.parent / f"{tmp_path.name}.m"
    p = spawn(["run", sc, "--out", tmp_path / "r"], tmp_path, pause="run:simulating", marker=marker)
    wait_for_marker(p, marker)
    p.send_signal(signal.SIGTERM)
    _, err = p.communicate(timeout=60)
    lines = err.splitlines()
    assert p.returncode == 143 and lines[-1].startswith("error: terminated"), err
    m = re.fullmatch(
        r"this run: about (.+) and ([\d.]+) (MB|GB): 22 bodies, (\d+) contacts, 20 s simulated \(and [\d.]+ s at rest before the blast\), "
        r"(\d+) samples x 2 runs",
        lines[0],
    )
    assert m, err
    # 11 on the ground, 2 x 10 head joints, 11 bed joints: 42 interfaces (a count, not a fit)
    assert int(m.group(4)) == 42
    # size: 2 runs x samples x 22 x (19 + 6) doubles of histories, plus the report: >= 100 MB for 20 s
    mb = float(m.group(2)) * (1000 if m.group(3) == "GB" else 1)
    assert mb >= 2 * int(m.group(5)) * 22 * 25 * 8 / 1e6


def test_a_file_over_the_block_limit_is_refused_in_one_line(tmp_path):
    # the limit lowered to 5 blocks so that a 6-block file exceeds it (the default, 10,000, is stated in the docs)
    _wall_file(tmp_path / "w.json", 2, 3)
    sc = _scenario(tmp_path, "w.json", 0.1)
    env = {**os.environ, "MPLBACKEND": "Agg", "BLASTSCALE_MAX_BLOCKS": "5"}
    for args in (["run", sc, "--out", tmp_path / "r"], ["show", tmp_path / "w.json"]):
        p = subprocess.run(
            BLASTSCALE + [str(a) for a in args],
            capture_output=True,
            text=True,
            cwd=tmp_path,
            env=env,
            timeout=120,
            check=False,
        )
        assert p.returncode == 2 and len(p.stderr.strip().splitlines()) == 1, p.stderr
        assert (
            p.stderr.startswith("error: w.json: 6 blocks is out of range") and "valid range is <= 5 blocks" in p.stderr
        )
        assert sorted(x.name for x in tmp_path.iterdir()) == ["w.json", "wall.toml"]


def test_the_study_guard_names_the_largest_structure_that_fits(tmp_path):
    # the day of computing lowered to a third of this run's estimate: 12 blocks for 1 s do not fit; one line
    # naming the duration that fits (about 1/3 s) and the structure that fits at 1 s (about 12 / 3 = 4 bodies:
    # the cost grows about linearly with bodies and contacts), exit 2, nothing written
    from blastscale.scenario import load_scenario
    from blastscale.study import Study, estimate_seconds

    _wall_file(tmp_path / "w.json", 2, 6)
    sc = _scenario(tmp_path, "w.json", 1.0)
    s = load_scenario(sc)
    hours = estimate_seconds(s, Study(s).structure()) / 3 / 3600
    env = {**os.environ, "MPLBACKEND": "Agg", "BLASTSCALE_MAX_HOURS": repr(hours)}
    p = subprocess.run(
        BLASTSCALE + ["run", str(sc), "--out", str(tmp_path / "r")],
        capture_output=True,
        text=True,
        cwd=tmp_path,
        env=env,
        timeout=120,
        check=False,
    )
    assert p.returncode == 2 and len(p.stderr.strip().splitlines()) == 1, p.stderr
    m = re.search(
        r"simulation.duration_s = 1 s is out of range: .* valid range is <= ([\d.e-]+) s here .*"
        r"or a structure of <= (\d+) bodies at this duration",
        p.stderr,
    )
    assert m, p.stderr
    assert 0.3 <= float(m.group(1)) <= 0.34 and int(m.group(2)) == 4
    assert sorted(x.name for x in tmp_path.iterdir()) == ["w.json", "wall.toml"]


def test_progress_lines_when_stderr_is_a_file(tmp_path):
    # a batch job: stderr redirected to a file, no terminal, so no rich bar; a line every 0.2 s instead
    log = tmp_path / "log.txt"
    env = {**os.environ, "MPLBACKEND": "Agg", "BLASTSCALE_PROGRESS_SECONDS": "0.2"}
    with log.open("w") as fh:
        p = subprocess.run(
            BLASTSCALE + ["run", "--set", "simulation.engine=3d", "--set", "simulation.duration_s=1"],
            stdout=subprocess.DEVNULL,
            stderr=fh,
            cwd=tmp_path,
            env=env,
            timeout=300,
            check=False,
        )
    text = log.read_text()
    assert p.returncode == 0, text
    lines = [ln for ln in text.splitlines() if ln.startswith("progress: ")]
    assert lines, text
    assert all(re.search(r"(\(\d of \d\))?, [\d.]+ s elapsed of about [\d.]+ s$", ln) for ln in lines), lines
    assert any("3D rigid bodies" in ln for ln in lines), lines  # the stage that takes the time is named


def test_no_progress_lines_with_json(tmp_path):
    r = run(["run", "--set", "simulation.engine=planar", "--set", "simulation.duration_s=0.5", "--json"], tmp_path)
    assert r.returncode == 0 and "progress:" not in r.stderr and "this run:" not in r.stderr
