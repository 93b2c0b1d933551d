"""``blastscale fired``'s inputs checked before anything runs (issue #40 items 2-4): a record that is not a
regular file or is too large, a gauge or marker out of place, a bad ``[fired]`` value: one line, exit 2,
nothing written, and no engine imported.

The file kinds that would hang a reader (``/dev/zero``, a FIFO, a 2 GB sparse file) run in a child
interpreter that has imported the command first; each refusal is then bounded by a 2 s wait on the child's
answer (the interpreter's start, slow on a loaded machine, is not in it): a reader that hangs fails the test
instead of hanging the suite."""

from __future__ import annotations

import json
import os
import selectors
import shutil
import subprocess
import sys
from importlib.resources import files
from pathlib import Path

import pytest

import blastscale
from blastscale.cli import main

EXAMPLE = Path(str(files("blastscale.fired") / "examples"))
RECORDS = ["gauges.csv", "shot.toml", "tracks.csv"]

#: The child: imports the command, says "ready", then runs one ``blastscale`` command per line of its
#: standard input and answers each with one JSON line: the exit status, standard error, the engines imported.
CHILD = r"""
import contextlib, io, json, sys
from blastscale.cli import main
print("ready", flush=True)
for line in sys.stdin:
    err = io.StringIO()
    code = 0
    with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
        try:
            main(json.loads(line))
        except SystemExit as e:
            code = e.code or 0
    engines = sorted(m for m in ("mujoco", "numba") if m in sys.modules)
    print(json.dumps({"code": code, "err": err.getvalue(), "engines": engines}), flush=True)
"""


def _env() -> dict:
    """The environment of a child interpreter: this blastscale first on its path (the child's working folder
    is another one), no plain progress lines (a loaded machine would print one every 30 s)."""
    src = str(Path(blastscale.__file__).resolve().parents[1])
    path = os.pathsep.join([src] + [p for p in [os.environ.get("PYTHONPATH")] if p])
    return {**os.environ, "MPLBACKEND": "Agg", "BLASTSCALE_PROGRESS_SECONDS": "1e9", "PYTHONPATH": path}


def _answer(proc, limit: float) -> str:
    """The child's next line, or fail (killing it) when none comes within ``limit`` seconds."""
    sel = selectors.DefaultSelector()
    sel.register(proc.stdout, selectors.EVENT_READ)
    ready = sel.select(limit)
    sel.close()
    if not ready:
        proc.kill()
        pytest.fail(f"no answer within {limit} s: the command hangs")
    return proc.stdout.readline()


@pytest.fixture
def child(tmp_path):
    proc = subprocess.Popen(
        [sys.executable, "-c", CHILD],
        stdin=subprocess.PIPE,
        stdout=subprocess.PIPE,
        stderr=subprocess.DEVNULL,
        text=True,
        cwd=tmp_path,
        env=_env(),
    )
    assert _answer(proc, 300.0).strip() == "ready"

    def run(*argv, limit: float = 2.0) -> dict:
        proc.stdin.write(json.dumps([str(a) for a in argv]) + "\n")
        proc.stdin.flush()
        return json.loads(_answer(proc, limit))

    # the start and the command's first run (its modules imported, the scenario's model built) are not what is
    # bounded: a first refusal, of a gauge out of place, unbounded
    warm = tmp_path / "warm"
    warm.mkdir()
    assert run("fired", _copy(warm, position_m="[-1.0, 0.0, 0.0]"), limit=300.0)["code"] == 2

    yield run
    proc.stdin.close()
    try:
        proc.wait(timeout=30)
    except subprocess.TimeoutExpired:
        proc.kill()


def _copy(folder: Path, **replace) -> Path:
    """The shipped example shot in ``folder``, the last line ``KEY = ...`` of its scenario (``[fired]`` is the
    last table) replaced for each ``KEY=VALUE`` of ``replace`` (``fired__charge_kg``: ``charge_kg``)."""
    for name in RECORDS:
        shutil.copy(EXAMPLE / name, folder / name)
    sc = folder / "shot.toml"
    lines = sc.read_text().splitlines()
    for key, value in replace.items():
        k = key.split("__")[-1]
        lines[[i for i, ln in enumerate(lines) if ln.split("=")[0].strip() == k][-1]] = f"{k} = {value}"
    sc.write_text("\n".join(lines) + "\n")
    return sc


def _one_line(err: str) -> str:
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert len(lines) == 1, err
    return lines[0]


@pytest.mark.skipif(not hasattr(os, "mkfifo") or not Path("/dev/zero").exists(), reason="POSIX file kinds")
def test_a_device_a_fifo_a_folder_and_a_sparse_giant_are_one_line_at_once(child, tmp_path):
    os.mkfifo(tmp_path / "fifo.csv")
    (tmp_path / "folder.csv").mkdir()
    with open(tmp_path / "sparse.csv", "wb") as f:  # 2 GB, no block written
        f.truncate(2 * 10**9)
    cases = [
        ("/dev/zero", "is a character device, not a regular file"),
        (tmp_path / "fifo.csv", "is a FIFO (named pipe), not a regular file"),
        (tmp_path / "folder.csv", "is a folder, not a regular file"),
        (tmp_path / "sparse.csv", "2000 MB, above the 100 MB a record is read to: set [fired] max_record_mb"),
    ]
    shot = tmp_path / "shot"
    shot.mkdir()
    for path, why in cases:
        for key in ("gauges", "tracks"):
            sc = _copy(shot, **{key: json.dumps(str(path))})
            r = child("fired", sc, "--out", shot / "res")
            assert r["code"] == 2, r
            line = _one_line(r["err"])
            assert line.startswith(f"error: record {str(path)!r}: ") and why in line, line
            assert r["engines"] == [], r  # refused before the engines load
            assert sorted(p.name for p in shot.iterdir()) == RECORDS  # nothing written


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="POSIX FIFOs")
def test_a_fifo_as_the_scenario_is_one_line_at_once(child, tmp_path):
    os.mkfifo(tmp_path / "shot.toml")
    r = child("fired", tmp_path / "shot.toml")
    assert r["code"] == 2 and "cannot be read: not a file (a folder, a FIFO or a device)" in _one_line(r["err"]), r


GEOMETRY = [
    (
        {"position_m": "[-0.3, 0.0, 0.05]"},
        "error: [fired.gauge.g1] position_m = [-0.3, 0.0, 0.05] is behind the charge (x -0.3 m < the charge's x "
        "-0.166987 m = front -0.0669873 m - stand-off 0.1 m)",
    ),
    (
        {"position_m": "[5.0, 0.0, 0.05]"},
        "error: [fired.gauge.g1] position_m = [5.0, 0.0, 0.05] is 4.93 m from the specimen: a gauge stands within 1 m",
    ),
    (
        {"point_m": "[10.0, 0.0, 0.5]"},
        "error: [fired.marker.top] point_m = [10.0, 0.0, 0.5] is not on any body: 9.93 m from the nearest "
        "('block'), 9.93 m from the specimen; a marker is on a body within 0.025 m",
    ),
    (
        {"point_m": "[0.0, 0.0, 0.6]"},  # 0.1 m above the block's top
        "error: [fired.marker.top] point_m = [0.0, 0.0, 0.6] is not on any body: 0.1 m from the nearest",
    ),
]


@pytest.mark.parametrize("replace, message", GEOMETRY)
def test_a_gauge_or_marker_out_of_place_is_one_line_exit_2_nothing_written(capsys, tmp_path, replace, message):
    sc = _copy(tmp_path, **replace)
    with pytest.raises(SystemExit) as e:
        main(["fired", str(sc), "--out", str(tmp_path / "res")])
    err = capsys.readouterr().err
    assert e.value.code == 2
    assert _one_line(err).startswith(message), err
    assert sorted(p.name for p in tmp_path.iterdir()) == RECORDS


def test_the_geometry_rules_pass_the_example_and_points_on_the_faces(tmp_path):
    """The shipped example's gauge (flush in the front face) and markers on the block's faces and corners pass;
    the charge's own plane is not behind it."""
    from blastscale.fired.inputs import shot_inputs
    from blastscale.scenario import load_scenario

    for point in ("[0.0, 0.0, 0.5]", "[-0.0669873, 0.025, 0.0]", "[0.0669873, -0.025, 0.5]", "[0.0, 0.0, 0.52]"):
        assert shot_inputs(load_scenario(_copy(tmp_path, point_m=point))).tracks is not None
    # a side-on (pencil) gauge beside the charge, in its plane (a reflected one there needs its normal: #36)
    beside = _copy(tmp_path, position_m="[-0.166987, 0.3, 0.05]", kind='"side-on"')
    assert shot_inputs(load_scenario(beside)).gauges is not None


REFUSED = [
    ({"fired__charge_kg": "nan"}, "fired.charge_kg = nan is not a finite number"),
    ({"fired__standoff_m": "-0.1"}, "fired.standoff_m = -0.1"),
    ({"position_m": "[-0.3, 0.0, 0.05]"}, "is behind the charge"),
    ({"gauges": '"/dev/zero"'}, "is a character device"),
]


@pytest.mark.parametrize("replace, message", REFUSED)
def test_a_bad_value_is_refused_before_the_engines_are_imported(tmp_path, replace, message):
    """Issue #40 item 4, measured by what is imported, not by the clock: neither MuJoCo nor numba (the engines'
    compiler) is loaded when a bad ``[fired]`` value or record is refused."""
    sc = _copy(tmp_path, **replace)
    code = (
        "import sys\n"
        "from blastscale.cli import main\n"
        "try:\n"
        f"    main(['fired', {str(sc)!r}])\n"
        "except SystemExit as e:\n"
        "    print(e.code)\n"
        "print(sorted(m for m in ('mujoco', 'numba') if m in sys.modules))\n"
    )
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=_env(), timeout=300)
    assert r.stdout.splitlines() == ["2", "[]"], (r.stdout, r.stderr)
    assert message in _one_line(r.stderr), r.stderr
