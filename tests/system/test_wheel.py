"""Issue #14: blastscale works from an installed wheel, outside the repository.

The wheel is built from this checkout, installed with its dependencies into a fresh virtual
environment in a temporary folder (pip's cache makes the dependencies quick), and ``blastscale
reproduce --quick`` runs there from another temporary folder: every paper scenario ships as package
data and runs, and the command says what it skipped (the figure gallery ships with the source tree,
not the wheel). Needs pip's package index, as ``make install`` does.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]

pytestmark = pytest.mark.slow


def _run(cmd, **kw):
    proc = subprocess.run(cmd, capture_output=True, text=True, **kw)
    assert proc.returncode == 0, f"{' '.join(map(str, cmd))}\n{proc.stdout[-2000:]}\n{proc.stderr[-2000:]}"
    return proc


def test_reproduce_quick_from_a_wheel_in_a_fresh_environment(tmp_path):
    from blastscale.scenario import library_names

    dist, venv, work = tmp_path / "dist", tmp_path / "venv", tmp_path / "work"
    work.mkdir()
    _run([sys.executable, "-m", "pip", "wheel", "--no-deps", "--quiet", "--wheel-dir", str(dist), str(ROOT)])
    wheel = next(dist.glob("blastscale-*.whl"))
    _run([sys.executable, "-m", "venv", str(venv)])
    py = venv / "bin" / "python"
    _run([str(py), "-m", "pip", "install", "--quiet", f"{wheel}[sim3d,io,plot]"])
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "VIRTUAL_ENV")}
    env["MPLBACKEND"] = "Agg"
    # the installed package, not this checkout's sources
    where = _run([str(py), "-c", "import blastscale; print(blastscale.__file__)"], cwd=work, env=env).stdout
    assert str(venv) in where and str(ROOT / "src") not in where
    out = work / "paper"
    proc = _run([str(venv / "bin" / "blastscale"), "reproduce", "--quick", "--out", str(out)], cwd=work, env=env,
                timeout=900)
    summary = json.loads((out / "summary.json").read_text())
    done = {item["name"] for item in summary["items"]}
    for name in (n for n in library_names() if n.startswith("paper_")):
        assert f"scenario-{name.replace('_', '-')}" in done, name
    assert (out / "report.html").is_file()
    assert "skipped: the examples/ gallery" in proc.stderr
