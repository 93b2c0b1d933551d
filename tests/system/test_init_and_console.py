"""Issue #15, faults 6-8 and 10: `blastscale init` and the shipped planar block; user text printed literally
(no console markup, no emoji codes); the one size and time guard of every command that simulates, naming the
flag and the valid range; progress only on a terminal and not with --json; reproduce states its cost first."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from blastscale.cli import main
from blastscale.scenario import TEMPLATE_KINDS, load_scenario, template_text


def cli(capsys, *argv) -> tuple[int, str, str]:
    with pytest.raises(SystemExit) as e:
        main([str(a) for a in argv])
    cap = capsys.readouterr()
    return (e.value.code or 0), cap.out, cap.err


# -- init ------------------------------------------------------------------------------------------------------
@pytest.mark.parametrize("kind", TEMPLATE_KINDS)
def test_init_writes_a_template_that_loads_and_refuses_to_overwrite(capsys, tmp_path, kind):
    f = tmp_path / "mine.toml"
    code, out, err = cli(capsys, "init", "--kind", kind, f)
    assert code == 0 and f.read_text() == template_text(kind, "mine_blocks.json") and f"wrote {f} (" in err, err
    assert " kB" in err or " B" in err
    assert load_scenario(f).structure.kind == kind and f"blastscale run {f} --out" in out
    assert template_text(kind).count("#") > 15  # commented: every key says its unit or its choices
    f.write_text(f.read_text() + "# my note\n")
    code, _, err = cli(capsys, "init", f)
    assert code == 2 and "exists: refused (give --force to replace it)" in err and "# my note" in f.read_text()
    code, _, _ = cli(capsys, "init", "--from", "planar_block", f, "--force")
    assert code == 0 and load_scenario(f) == load_scenario("planar_block")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["mine.toml"] + (
        ["mine_blocks.json"] if kind == "assembly" else []
    )


def test_init_never_replaces_what_is_not_a_toml_file(capsys, tmp_path):
    (tmp_path / "notes.toml").write_text("not = [toml")
    code, _, err = cli(capsys, "init", tmp_path / "notes.toml", "--force")
    assert code == 2 and "is not a scenario file blastscale wrote: refused, even with --force" in err
    (tmp_path / "d.toml").mkdir()
    code, _, err = cli(capsys, "init", tmp_path / "d.toml", "--force")
    assert code == 2 and "is a folder" in err
    code, _, err = cli(capsys, "init", "--from", "no_such", tmp_path / "x.toml")
    assert code == 2 and "valid names are" in err and "planar_block" in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["d.toml", "notes.toml"]


def test_the_planar_block_is_planar_and_its_outcome_sweep_runs(capsys, tmp_path):
    sc = load_scenario("planar_block")
    assert sc.simulation.engine == "planar" and sc.structure.kind == "block" and sc.scale is not None
    code, out, err = cli(
        capsys,
        "sweep",
        "planar_block.toml",
        "--vary",
        "charge_kg=20:200:30:log",
        "--vary",
        "standoff_m=1.5:6:30",
        "--outcomes",
        "--workers",
        "0",
        "--out",
        tmp_path / "o.zarr",
        "--json",
    )
    assert code == 0 and json.loads(out)["n_cases"] == 900, err


# -- literal console text --------------------------------------------------------------------------------------
def test_a_title_with_markup_and_emoji_codes_is_printed_as_written(capsys, tmp_path):
    title = "block [model 2] :100: [/b] [bold]x"
    f = tmp_path / "t.toml"
    f.write_text(
        load_scenario("planar_block")
        .with_values({"duration_s": 0.5, "critical_charge": False})
        .to_toml()
        .replace('title = "', f'title = "{title} ', 1)
    )
    code, out, err = cli(capsys, "run", f, "--out", tmp_path / "r")
    assert code == 0, err
    assert title in out and "💯" not in out and "Traceback" not in err
    assert title in (tmp_path / "r" / "report.html").read_text()  # the page escapes it as HTML


@pytest.mark.parametrize(
    "argv, literal",
    [
        (["capacity", "--alpha-deg", "15", "--standoffs", "1:100:0"], "'1:100:0'"),
        (["sweep", "--vary", "charge_kg=[/b]:2:3", "--out", "x.zarr"], "[/b]"),
        (["run", "no[/b]such:100:.toml"], "no[/b]such:100:.toml"),
    ],
)
def test_user_text_in_error_messages_is_literal(capsys, tmp_path, monkeypatch, argv, literal):
    monkeypatch.chdir(tmp_path)
    code, _, err = cli(capsys, *argv)
    assert code == 2 and err.startswith("error: ") and err.count("\n") == 1 and literal in err, err
    assert "💯" not in err and "BlastscaleInputError" not in err and "array(" not in err


# -- the size and time guard -----------------------------------------------------------------------------------
@pytest.mark.parametrize(
    "argv, words",
    [
        (
            ["block3d", "--alpha-deg", "15", "--charge", "50", "--standoff", "2", "--timestep", "1e-9"],
            "--timestep = 1e-09 s is out of range: it would need about",
        ),
        (
            ["block3d", "--alpha-deg", "15", "--charge", "50", "--standoff", "2", "--duration", "1e5"],
            "--duration = 100000 s is out of range",
        ),
        (
            ["column", "--charge", "250", "--standoff", "10", "--duration", "1e4"],
            "--duration = 10000 s is out of range",
        ),
        (
            [
                "sweep",
                "planar_block",
                "--vary",
                "charge_kg=10:200:100000",
                "--vary",
                "standoff_m=2:5:100000",
                "--out",
                "big.zarr",
            ],
            "cases = 1e+10 is out of range",
        ),
        (
            ["sweep", "planar_block", "--vary", "charge_kg=10:200:100000000", "--out", "big.zarr"],
            "valid range is [1, 1e+07]",
        ),
        (
            ["fragility", "--charges", "40:160:13", "--lognormal", "charge_kg=0.2", "--samples", "1000000000"],
            "samples = 1e+09 is out of range",
        ),
    ],
)
def test_every_command_that_simulates_is_guarded(capsys, tmp_path, monkeypatch, argv, words):
    monkeypatch.chdir(tmp_path)
    code, _, err = cli(capsys, *argv)
    assert code == 2 and err.count("\n") == 1 and words in err and "valid range is" in err, err
    assert list(tmp_path.iterdir()) == []


def test_a_long_job_is_refused_by_its_time_estimate(capsys, tmp_path, monkeypatch):
    """The time limit (BLASTSCALE_MAX_HOURS): a sweep of 100 3D column Studies fits in memory but not in 1 h."""
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("BLASTSCALE_MAX_HOURS", "0.01")
    code, _, err = cli(
        capsys,
        "sweep",
        "paper_column_square_250kg",
        "--vary",
        "charge_kg=100:300:100",
        "--workers",
        "1",
        "--out",
        "c.zarr",
    )
    assert code == 2 and "of computing, more than 36 s (BLASTSCALE_MAX_HOURS raises the limit)" in err, err


# -- progress: on a terminal only, never with --json -----------------------------------------------------------
def test_progress_shows_on_a_terminal_and_not_with_json(monkeypatch):
    from blastscale.cli import _output

    monkeypatch.setattr(type(_output.console_err), "is_terminal", property(lambda self: True))
    assert _output.show_progress() is True and _output.show_progress(quiet=True) is False
    monkeypatch.setattr(type(_output.console_err), "is_terminal", property(lambda self: False))
    assert _output.show_progress() is False


# -- reproduce says what it will cost before it starts ---------------------------------------------------------
def test_reproduce_states_its_time_and_size_first(capsys, tmp_path):
    code, _, err = cli(
        capsys, "reproduce", "--only", "table-geometry", "--only", "scaling-factors", "--out", tmp_path / "p"
    )
    assert code == 0
    first = err.splitlines()[0]
    assert first.startswith("reproduce: 2 of 2 items to make, about ") and " kB" in first or " MB" in first
    assert "--quick makes every item in about" in first
    assert err.splitlines()[-1].startswith(f"wrote {tmp_path / 'p'}/ (")
    code, _, err = cli(capsys, "reproduce", "--only", "table-geometry", "--out", tmp_path / "p")
    assert code == 0 and err.splitlines()[0] == "reproduce: 0 of 1 items to make (every one is done)"
    (tmp_path / "mine").mkdir()
    (tmp_path / "mine" / "report.html").write_text("my own page")
    code, _, err = cli(capsys, "reproduce", "--only", "table-geometry", "--out", tmp_path / "mine")
    assert code == 2 and "is not a blastscale reproduce folder" in err
    assert (tmp_path / "mine" / "report.html").read_text() == "my own page"
    assert Path(tmp_path / "p" / "summary.json").is_file()
