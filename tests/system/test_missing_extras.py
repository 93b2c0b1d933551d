"""Issue #23: a plain install runs the main job; a command that needs an optional extra that is not installed
says so in one line naming the extra and its install command, exit 2, no traceback, nothing written. An extra
is hidden here as a missing module is (``sys.modules[name] = None``: its import raises
``ModuleNotFoundError``), in this process where the command imports it first, else in a fresh one; the fresh
install itself is tests/system/test_wheel.py's."""

from __future__ import annotations

import os
import subprocess
import sys

import pytest

from blastscale._extras import MissingExtraError, require
from blastscale.cli import main
from blastscale.scenario import load_scenario


def cli(capsys, *argv) -> tuple[int, str, str]:
    with pytest.raises(SystemExit) as e:
        main([str(a) for a in argv])
    cap = capsys.readouterr()
    return (e.value.code or 0), cap.out, cap.err


def hide(monkeypatch, *modules):
    for m in modules:
        monkeypatch.setitem(sys.modules, m, None)


@pytest.fixture
def planar(tmp_path):
    path = tmp_path / "planar.toml"
    path.write_text(load_scenario("planar_block").with_values({"duration_s": 0.5, "critical_charge": False}).to_toml())
    return path


SWEEPS = "pip install 'blastscale[sweeps]'"


@pytest.mark.parametrize(
    "workers, hidden, module",
    [("0", ("zarr",), "zarr"), ("2", ("dask", "dask.distributed", "distributed"), "dask.distributed")],
)
def test_a_sweep_without_the_sweeps_extra_is_one_line_naming_it(
    capsys, monkeypatch, tmp_path, planar, workers, hidden, module
):
    hide(monkeypatch, *hidden)
    code, out, err = cli(
        capsys, "sweep", planar, "--vary", "standoff_m=2,3", "--workers", workers, "--out", tmp_path / "s.zarr"
    )
    assert code == 2 and out == ""
    assert err == f"error: blastscale sweep needs the 'sweeps' extra ({module} is not installed): {SWEEPS}\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["planar.toml"]  # nothing written


def without_extras(args, cwd) -> subprocess.CompletedProcess:
    """``blastscale ARGS`` in a fresh interpreter in which no extra's module can be imported (hidden before
    anything is imported: a library that looked for one earlier in this process would still believe in it)."""
    code = (
        "import sys\n"
        f"for m in {sorted(EXTRA_MODULES)!r}: sys.modules[m] = None\n"
        "sys.argv[0] = 'blastscale'\n"
        "from blastscale.cli import main\n"
        f"main({[str(a) for a in args]!r})\n"
    )
    return subprocess.run(
        [sys.executable, "-c", code],
        capture_output=True,
        text=True,
        cwd=cwd,
        timeout=600,
        env={**os.environ, "MPLBACKEND": "Agg"},
    )


EXTRA_MODULES = {"zarr", "dask", "dask.distributed", "distributed", "trimesh"}


def test_a_similarity_map_in_memory_needs_no_extra_and_its_store_does(tmp_path, planar):
    args = [
        "similarity-map",
        planar,
        "--scales",
        "0.01",
        "--density-ratios",
        "1",
        "--charges",
        "50",
        "--standoffs",
        "2",
        "--json",
    ]
    proc = without_extras(args, tmp_path)
    assert proc.returncode == 0, proc.stderr
    proc = without_extras(args + ["--out", tmp_path / "m.zarr"], tmp_path)
    assert proc.returncode == 2 and proc.stderr == (
        f"error: blastscale similarity-map needs the 'sweeps' extra (zarr is not installed): {SWEEPS}\n"
    )


def test_a_mesh_without_the_mesh_extra_is_one_line_naming_it(capsys, monkeypatch, tmp_path):
    box = tmp_path / "box.obj"
    box.write_text(
        "o B\n"
        + "".join(f"v {x} {y} {z}\n" for x in (0, 1) for y in (0, 1) for z in (0, 1))
        + "f 1 2 4 3\nf 5 7 8 6\nf 1 5 6 2\nf 3 4 8 7\nf 1 3 7 5\nf 2 6 8 4\n"
    )
    hide(monkeypatch, "trimesh")
    code, _, err = cli(capsys, "show", box)
    assert code == 2 and err == (
        "error: blastscale show needs the 'mesh' extra (trimesh is not installed): pip install 'blastscale[mesh]'\n"
    )


def test_the_main_job_needs_no_extra(tmp_path, planar):
    proc = without_extras(["run", planar, "--out", tmp_path / "r"], tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert (tmp_path / "r" / "report.html").is_file()


def test_a_library_caller_gets_the_extra_and_the_command(monkeypatch):
    hide(monkeypatch, "zarr")
    with pytest.raises(MissingExtraError) as e:
        require("zarr", "sweeps", "a sweep store")
    assert isinstance(e.value, ModuleNotFoundError) and e.value.name == "zarr" and e.value.extra == "sweeps"
    assert str(e.value) == f"a sweep store needs the 'sweeps' extra (zarr is not installed): {SWEEPS}"
