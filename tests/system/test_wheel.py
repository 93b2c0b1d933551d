"""Issues #14 and #23: blastscale works from an installed wheel, outside the repository, and a plain install
(no extras) runs the main job.

The wheel is built from this checkout and installed WITHOUT extras into a fresh virtual environment in a
temporary folder (pip's cache makes the dependencies quick; needs pip's package index, as ``make install``
does). The environment is made without pip of its own and this environment's pip installs into it
(``pip --python``), without compiling the installed files to bytecode (``--no-compile``; Python compiles what
it imports): 16 s instead of 88 s on the project's 2-core machine, and the same files and dependencies in it.
There, from another temporary folder: ``blastscale run --out r`` (the default scenario, both engines) exits 0
and writes the report; a command that needs an extra (``sweep``: Zarr, Dask) says so in one line, exit 2; and
``blastscale reproduce --quick`` runs every paper scenario shipped as package data and says what it skipped
(the figure gallery ships with the source tree, not the wheel).
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


def _run(cmd, expect: int = 0, **kw):
    proc = subprocess.run(cmd, capture_output=True, text=True, **kw)
    assert proc.returncode == expect, f"{' '.join(map(str, cmd))}\n{proc.stdout[-2000:]}\n{proc.stderr[-2000:]}"
    return proc


@pytest.fixture(scope="module")
def plain_install(tmp_path_factory):
    """(blastscale console script, python, environment, work folder) of a fresh environment holding the
    wheel installed without extras."""
    tmp = tmp_path_factory.mktemp("wheel")
    dist, venv, work = tmp / "dist", tmp / "venv", tmp / "work"
    work.mkdir()
    _run([sys.executable, "-m", "pip", "wheel", "--no-deps", "--quiet", "--wheel-dir", str(dist), str(ROOT)])
    wheel = next(dist.glob("blastscale-*.whl"))
    # this checkout's sources off the path (with a build's src/blastscale.egg-info there, pip would take
    # blastscale for installed and skip the wheel)
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "VIRTUAL_ENV")}
    env["MPLBACKEND"] = "Agg"
    _run([sys.executable, "-m", "venv", "--without-pip", str(venv)], env=env)
    py = venv / "bin" / "python"
    # no extras: what `pip install blastscale` gets (the wheel's dependencies resolved by pip, into the venv)
    pip = [sys.executable, "-m", "pip", "--python", str(py), "--disable-pip-version-check"]
    _run([*pip, "install", "--quiet", "--no-compile", str(wheel)], cwd=work, env=env, timeout=1200)
    # the installed package, not this checkout's sources; and no extra's module came with the core
    where = _run([str(py), "-c", "import blastscale; print(blastscale.__file__)"], cwd=work, env=env).stdout
    assert str(venv) in where and str(ROOT / "src") not in where
    for module in ("zarr", "dask", "trimesh"):
        _run([str(py), "-c", f"import {module}"], expect=1, cwd=work, env=env)
    return venv / "bin" / "blastscale", py, env, work


def test_a_plain_install_runs_the_main_job(plain_install):
    blastscale, _, env, work = plain_install
    _run([str(blastscale), "run", "--out", "r"], cwd=work, env=env, timeout=900)
    out = work / "r"
    assert (out / "report.html").is_file() and (out / "histories.nc").is_file()
    summary = json.loads((out / "summary.json").read_text())
    assert summary["planar"] is not None and summary["3d"] is not None  # both engines ran
    # a command that needs an extra: one line naming it and its install command, nothing written
    proc = _run([str(blastscale), "sweep", "--vary", "standoff_m=2,3", "--out", "s.zarr"], expect=2, cwd=work, env=env)
    assert proc.stderr == (
        "error: blastscale sweep needs the 'sweeps' extra (zarr is not installed): pip install 'blastscale[sweeps]'\n"
    )
    assert not (work / "s.zarr").exists()


def test_reproduce_quick_from_a_wheel_in_a_fresh_environment(plain_install):
    from blastscale.scenario import library_names

    blastscale, _, env, work = plain_install
    out = work / "paper"
    proc = _run([str(blastscale), "reproduce", "--quick", "--out", str(out)], cwd=work, env=env, timeout=900)
    summary = json.loads((out / "summary.json").read_text())
    done = {item["name"] for item in summary["items"]}
    for name in (n for n in library_names() if n.startswith("paper_")):
        assert f"scenario-{name.replace('_', '-')}" in done, name
    assert (out / "report.html").is_file()
    assert "skipped: the examples/ gallery" in proc.stderr
