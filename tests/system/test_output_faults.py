"""Issue #15, faults 1-5: every writer goes through blastscale.io.output. A user's folder is never replaced (even
with --force), a second writer of the same target gets one line and exit 2, an output fault (missing folder, a file
where a folder is expected, /proc, read-only, full disk) is one line naming the path, exit 2, nothing left behind,
and SIGINT / SIGTERM / SIGHUP leave no partial work (exit 130 / 143 / 129); stale partial folders of killed runs
are removed by the next run. Every interruption happens at a pause point (blastscale._hooks), never after a sleep."""

from __future__ import annotations

import errno
import os
import signal
from pathlib import Path

import pytest
from _spawn import run, spawn, wait_for_marker

from blastscale.cli import main
from blastscale.scenario import load_scenario

pytest.importorskip("zarr")

ROOT = os.geteuid() == 0  # root writes into a chmod 555 folder: the read-only fault is simulated then


def cli(capsys, *argv) -> tuple[int, str, str]:
    with pytest.raises(SystemExit) as e:
        main([str(a) for a in argv])
    cap = capsys.readouterr()
    return (e.value.code or 0), cap.out, cap.err


def one_line(err: str) -> bool:
    return err.startswith("error: ") and err.count("\n") == 1 and "Traceback" not in err


def listing(folder: Path) -> list:
    return sorted(str(p.relative_to(folder)) for p in folder.rglob("*"))


def _planar_file(folder: Path) -> Path:
    path = folder / "planar.toml"
    path.write_text(load_scenario("planar_block").with_values({"duration_s": 1.0, "critical_charge": False}).to_toml())
    return path


@pytest.fixture(scope="module", autouse=True)
def warm_kernels(tmp_path_factory):
    """The planar run once, in this process, before the tests: its compiled kernels on disk. The tests count the
    lines a run writes on stderr, and on a cold kernel cache (a fresh clone) a run also says its size ("this run:
    about 13 s (compiling kernels, first use only ...)": the compile pushes it over the announce threshold):
    without this, a test here failed or passed by whether another test had compiled the kernels before it (make
    test runs this file among the first). The size line counts the kernel modules a run loads
    (study.memory.compile_seconds); the run here searches the critical charge too, so every module is compiled,
    whatever a test's command loads. Warm: one 1 s planar run and its search, a few seconds."""
    folder = tmp_path_factory.mktemp("warm")
    warm = folder / "warm.toml"  # with the critical charge search: its batch kernel (_batch) is compiled too
    warm.write_text(load_scenario("planar_block").with_values({"duration_s": 1.0}).to_toml())
    with pytest.raises(SystemExit) as e:
        main(["run", str(warm), "--out", str(folder / "r"), "--json"])
    assert (e.value.code or 0) == 0


@pytest.fixture
def planar(tmp_path):
    """A fast planar scenario file (the shipped planar block, 1 s, no critical charge search)."""
    return _planar_file(tmp_path)


SWEEP = ["--vary", "standoff_m=2,3", "--workers", "0"]


# -- fault 1: --force never deletes a user's folder; a file as --out is refused before any work --------------------
def test_sweep_force_keeps_a_user_folder_and_refuses_a_file(capsys, tmp_path, planar):
    d = tmp_path / "d"
    d.mkdir()
    (d / "thesis.tex").write_text("x")
    code, _, err = cli(capsys, "sweep", planar, *SWEEP, "--out", d, "--force")
    assert code == 2 and one_line(err) and "is not a blastscale sweep store" in err and "even with --force" in err
    assert listing(d) == ["thesis.tex"]
    f = tmp_path / "f.zarr"
    f.write_text("x")
    before = listing(tmp_path)
    code, _, err = cli(capsys, "sweep", planar, *SWEEP, "--out", f, "--force")
    assert code == 2 and one_line(err) and "is a file, not a folder" in err
    assert listing(tmp_path) == before  # no X.parts, no X.tmp


def test_force_replaces_a_sweep_store_of_another_sweep(capsys, tmp_path, planar):
    out = tmp_path / "s.zarr"
    assert cli(capsys, "sweep", planar, *SWEEP, "--out", out)[0] == 0
    code, _, err = cli(capsys, "sweep", planar, "--vary", "standoff_m=2,4", "--workers", "0", "--out", out)
    assert code == 2 and "already holds another sweep" in err or "exists" in err
    code, _, err = cli(capsys, "sweep", planar, "--vary", "standoff_m=2,4", "--workers", "0", "--out", out, "--force")
    assert code == 0 and f"wrote {out}/ (" in err and " kB" in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["planar.toml", "s.zarr"]


# -- fault 2: a second writer of the same target ---------------------------------------------------------------
@pytest.mark.parametrize("command", ["run", "sweep"])
def test_a_second_writer_gets_one_line_and_the_first_finishes(capsys, tmp_path, planar, command):
    out, marker = tmp_path / ("r" if command == "run" else "s.zarr"), tmp_path.parent / f"{tmp_path.name}.m"
    args = [command, planar, "--out", out] + (SWEEP if command == "sweep" else [])
    first = spawn(args, tmp_path, pause="run:simulating" if command == "run" else "sweep:chunks=1", marker=marker)
    wait_for_marker(first, marker)
    code, _, err = cli(capsys, *args, *(["--force"] if command == "run" else []))
    assert code == 2 and one_line(err) and "is being written by another blastscale process (pid" in err
    first.send_signal(signal.SIGTERM)  # the first one is stopped cleanly (a pause ends by a signal)
    _, ferr = first.communicate(timeout=60)
    assert first.returncode == 143 and ferr.startswith("error: terminated (SIGTERM): ") and ferr.count("\n") == 1
    if command == "run":
        assert sorted(p.name for p in tmp_path.iterdir()) == ["planar.toml"]
    else:  # the finished chunk is kept to resume from, said in the line; the next run resumes and cleans up
        assert "1 finished chunks kept in" in ferr
        r = run([command, *args[1:]], tmp_path)
        assert r.returncode == 0, r.stderr
        assert sorted(p.name for p in tmp_path.iterdir()) == ["planar.toml", "s.zarr"]


# -- fault 4: output faults, every writer ---------------------------------------------------------------------
WRITERS = {
    "run": lambda out, sc: ["run", sc, "--out", out],
    "sweep": lambda out, sc: ["sweep", sc, *SWEEP, "--out", out],
    "similarity-map": lambda out, sc: [
        "similarity-map",
        sc,
        "--scales",
        "0.01",
        "--density-ratios",
        "1",
        "--charges",
        "50",
        "--standoffs",
        "2",
        "--out",
        out,
    ],
    "reproduce": lambda out, sc: ["reproduce", "--only", "table-geometry", "--out", out],
    "init": lambda out, sc: ["init", f"{out}.toml"],
    "plan": lambda out, sc: ["plan", sc, "--out", out],
    "plot": lambda out, sc: [
        "fragility",
        sc,
        "--charges",
        "40,80",
        "--lognormal",
        "charge_kg=0.2",
        "--samples",
        "10",
        "--plot",
        f"{out}.png",
    ],
}


@pytest.mark.parametrize("writer", sorted(WRITERS))
@pytest.mark.parametrize("fault", ["missing parent", "parent is a file", "proc"])
def test_output_faults_are_one_line_exit_2_nothing_left(capsys, tmp_path, planar, writer, fault):
    work = tmp_path / "work"
    work.mkdir()
    if fault == "missing parent":
        out, word = work / "nope" / "x", "does not exist"
    elif fault == "parent is a file":
        (work / "f").write_text("x")
        out, word = work / "f" / "x", "is a file"
    else:
        out, word = Path("/proc/blastscale-x"), "cannot be written"
    code, _, err = cli(capsys, *WRITERS[writer](out, planar))
    assert code == 2 and one_line(err) and word in err and str(out) in err, err
    assert listing(work) == ([] if fault != "parent is a file" else ["f"])


@pytest.mark.parametrize("writer", ["run", "sweep", "similarity-map", "reproduce", "init", "plot", "plan"])
def test_a_read_only_folder_is_one_line(capsys, tmp_path, planar, writer, monkeypatch):
    ro = tmp_path / "ro"
    ro.mkdir()
    if ROOT:  # chmod does not stop root: every file or folder created in ro/ fails as on a read-only mount

        def guard(real):
            def call(path, *a, **k):
                if str(path).startswith(str(ro)):
                    raise OSError(errno.EROFS, os.strerror(errno.EROFS), str(path))
                return real(path, *a, **k)

            return call

        monkeypatch.setattr(os, "open", guard(os.open))
        monkeypatch.setattr(os, "mkdir", guard(os.mkdir))
    else:
        ro.chmod(0o555)
    try:
        code, _, err = cli(capsys, *WRITERS[writer](ro / "x", planar))
    finally:
        ro.chmod(0o755)
    assert code == 2 and one_line(err) and str(ro / "x") in err and ("ead-only" in err or "ermission" in err), err
    assert listing(ro) == []


@pytest.mark.parametrize("writer", ["run", "sweep"])
def test_a_full_disk_is_one_line_and_leaves_nothing(capsys, tmp_path, planar, writer, monkeypatch, patch_everywhere):
    """ENOSPC in the middle of writing (the histories of a run; a chunk of a sweep): one line, no partial folder,
    no temporary file."""
    import numpy as np

    import blastscale.io.histories as hist

    def full(*a, **k):
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))

    if writer == "run":
        patch_everywhere(hist, "write_netcdf", lambda tree, path, **k: (Path(path).write_bytes(b"x" * 10), full()))
    else:
        monkeypatch.setattr(np, "savez", lambda fh, **k: (fh.write(b"x" * 10), full()))
    out = tmp_path / "out"
    code, _, err = cli(capsys, *WRITERS[writer](out, planar))
    assert code == 2 and one_line(err) and "no space left on the device" in err and str(out) in err, err
    assert listing(tmp_path) == ["planar.toml"]


def test_a_full_disk_at_the_write_itself_names_the_output_not_a_temporary_file(capsys, tmp_path, planar, monkeypatch):
    """ENOSPC from the operating system's write of a result file (summary.json, histories.nc: every file of a
    result folder is serialised in memory and written as plain bytes, so HDF5 never meets the full disk): one
    line naming --out as given, no partial folder."""
    real = os.fdopen

    class Full:
        def __init__(self, fh):
            self.fh = fh

        def __enter__(self):
            return self

        def __exit__(self, *a):
            self.fh.close()

        def write(self, data):
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))

    monkeypatch.setattr(os, "fdopen", lambda fd, *a, **k: Full(real(fd, *a, **k)))
    code, _, err = cli(capsys, "run", planar, "--out", tmp_path / "r")
    assert code == 2 and err == f"error: out = {str(tmp_path / 'r')!r} cannot be written: no space left on the device\n"
    assert listing(tmp_path) == ["planar.toml"]


@pytest.mark.parametrize("command", ["sweep", "plan"])
def test_force_never_replaces_a_user_folder(capsys, tmp_path, planar, command):
    d = tmp_path / "d"
    d.mkdir()
    (d / "thesis.tex").write_text("x")
    args = [command, planar, "--out", d, "--force"] + (SWEEP if command == "sweep" else [])
    code, _, err = cli(capsys, *args)
    assert code == 2 and one_line(err) and "even with --force" in err
    assert listing(d) == ["thesis.tex"]


# -- fault 5: signals -------------------------------------------------------------------------------------------
@pytest.mark.parametrize(
    "sig, status, words", [(signal.SIGTERM, 143, "terminated (SIGTERM)"), (signal.SIGHUP, 129, "hung up (SIGHUP)")]
)
def test_sigterm_and_sighup_while_writing_leave_nothing(tmp_path, planar, sig, status, words):
    marker = tmp_path.parent / f"{tmp_path.name}.m"
    p = spawn(["run", planar, "--out", tmp_path / "r"], tmp_path, pause="run:writing", marker=marker)
    wait_for_marker(p, marker)
    assert any(x.name.startswith(".r.partial-") for x in tmp_path.iterdir())  # a partial folder is on disk
    p.send_signal(sig)
    _, err = p.communicate(timeout=60)
    assert p.returncode == status and err == f"error: {words}: no partial results left\n"
    assert sorted(x.name for x in tmp_path.iterdir()) == ["planar.toml"]


def test_kill_9_leaves_a_partial_folder_that_the_next_run_removes(capsys, tmp_path, planar):
    marker = tmp_path.parent / f"{tmp_path.name}.m"
    p = spawn(["run", planar, "--out", tmp_path / "r"], tmp_path, pause="run:writing", marker=marker)
    wait_for_marker(p, marker)
    p.kill()
    p.communicate()
    left = sorted(x.name for x in tmp_path.iterdir())
    assert any(n.startswith(".r.partial-") for n in left) and ".r.lock" in left  # what kill -9 cannot clean
    # another run in the same folder removes the dead writer's partial folder (its pid is dead) ...
    assert cli(capsys, "run", planar, "--out", tmp_path / "other")[0] == 0
    assert sorted(x.name for x in tmp_path.iterdir()) == [".r.lock", "other", "planar.toml"]
    # ... and the next run into the same folder takes over the lock and leaves nothing else
    assert cli(capsys, "run", planar, "--out", tmp_path / "r")[0] == 0
    assert sorted(x.name for x in tmp_path.iterdir()) == ["other", "planar.toml", "r"]


def test_ctrl_c_on_a_two_worker_sweep_is_one_line_and_resumes(tmp_path, planar):
    """Ctrl-C at a terminal reaches the whole process group (the Dask workers too): one line, exit 130, the
    finished chunks kept, and the same command resumes to the uninterrupted store."""
    from blastscale.io.sweep_store import open_sweep

    marker = tmp_path.parent / f"{tmp_path.name}.m"
    args = [
        "sweep",
        planar,
        "--vary",
        "standoff_m=1.5:4:6",
        "--chunk",
        "1",
        "--workers",
        "2",
        "--out",
        tmp_path / "s.zarr",
    ]
    p = spawn(args, tmp_path, pause="sweep:chunks=2", marker=marker, group=True)
    wait_for_marker(p, marker)
    os.killpg(p.pid, signal.SIGINT)
    _, err = p.communicate(timeout=120)
    assert p.returncode == 130, err
    assert err.count("\n") == 1 and err.startswith("error: interrupted (Ctrl-C): ") and "chunks kept" in err, err
    r = run(args, tmp_path)
    assert r.returncode == 0, r.stderr
    assert (
        run(
            ["sweep", planar, "--vary", "standoff_m=1.5:4:6", "--workers", "0", "--out", tmp_path / "one.zarr"],
            tmp_path,
        ).returncode
        == 0
    )
    a, b = open_sweep(tmp_path / "s.zarr"), open_sweep(tmp_path / "one.zarr")
    assert [n.path for n in a.subtree] == [n.path for n in b.subtree]
    for node in a.subtree:  # every value bit for bit (the chunking, an attribute, differs)
        assert node.ds.equals(b[node.path].ds), node.path
    assert sorted(x.name for x in tmp_path.iterdir()) == ["one.zarr", "planar.toml", "s.zarr"]


def test_kill_9_between_the_two_renames_of_a_replacement_loses_nothing(capsys, tmp_path, planar):
    """--force sets the old result aside, then renames the new one into place; a kill -9 between the two (the only
    signal that lands there) leaves neither at `r`: the next command puts the old result back first."""
    assert cli(capsys, "run", planar, "--out", tmp_path / "r")[0] == 0
    old = (tmp_path / "r" / "summary.json").read_text()
    marker = tmp_path.parent / f"{tmp_path.name}.m"
    p = spawn(
        ["run", planar, "--out", tmp_path / "r", "--force"], tmp_path, pause="output:between-renames", marker=marker
    )
    wait_for_marker(p, marker)
    p.kill()
    p.communicate()
    assert not (tmp_path / "r").exists() and any(x.name.startswith(".r.old-") for x in tmp_path.iterdir())
    code, _, err = cli(capsys, "run", planar, "--out", tmp_path / "r")
    assert code == 2 and "exists: refused (give --force to replace it)" in err  # the old result is back
    assert (tmp_path / "r" / "summary.json").read_text() == old
    assert sorted(x.name for x in tmp_path.iterdir()) == ["planar.toml", "r"]
