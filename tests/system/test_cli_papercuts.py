"""CLI papercuts found when the tool was tried as a new user would (issue 10, item 5)."""

import json
import re

import pytest

from blastscale import __version__
from blastscale.cli import main


def cli(capsys, *argv):
    with pytest.raises(SystemExit) as e:
        main(list(argv))
    cap = capsys.readouterr()
    return (e.value.code or 0), cap.out, cap.err


def test_version(capsys):
    code, out, _ = cli(capsys, "--version")
    assert code == 0 and out.strip() == f"blastscale {__version__}"


@pytest.mark.parametrize("command", ["run", "rock", "critical", "block3d", "design", "blast", "reproduce", "show"])
def test_flags_are_shown_without_a_value_type(capsys, command):
    code, out, _ = cli(capsys, command, "--help")
    assert code == 0
    assert "<bool>" not in out
    assert re.search(r"--json\s", out) or command == "reproduce"


def test_run_help_names_one_default_per_option(capsys):
    # before: --model said "kingery-bulmash (... default)" while its default was masi2021
    code, out, _ = cli(capsys, "run", "--help")
    text = " ".join(out.split())
    assert "default: the scenario's" in text and "kingery-bulmash (Swisdak 1994, default)" not in text
    assert "masi2021, friction 0.7" in text  # the built-in scenario, named once


@pytest.mark.parametrize("value", ["1/200", "0.005"])
def test_scale_accepts_fractions(capsys, value):
    code, out, err = cli(
        capsys, "design", "--charge", "50", "--standoff", "2", "--scale", value, "--model", "masi2021", "--json"
    )
    assert code == 0, err
    assert json.loads(out)["scale"] == 0.005
    code, out, err = cli(
        capsys,
        "design",
        "--charge",
        "50",
        "--standoff",
        "2",
        f"--scale={value}",
        "--density-ratio",
        "7/100",
        "--model",
        "masi2021",
        "--json",
    )
    assert code == 0 and json.loads(out)["density_ratio"] == pytest.approx(0.07, rel=1e-12)


def test_bad_fraction_is_still_a_one_line_error(capsys):
    code, _, err = cli(capsys, "design", "--charge", "50", "--standoff", "2", "--scale", "1/0")
    assert code == 2 and err.count("\n") == 1 and "--scale" in err


@pytest.mark.parametrize("command", ["rock", "block3d"])  # `run`: tests/test_run.py
def test_no_command_suggests_a_flag_it_lacks(capsys, command):
    args = {
        "rock": ["--charge", "1", "--standoff", "100", "--alpha-deg", "15"],
        "block3d": ["--charge", "1", "--standoff", "100", "--alpha-deg", "15"],
    }[command]
    code, _, err = cli(capsys, command, *args, "--model", "masi2021")
    assert code == 2 and err.count("\n") == 1, err
    has_flag = "--extrapolate" in cli(capsys, command, "--help")[1]
    if has_flag:
        assert "CLI --extrapolate" in err, err
    else:  # before: "CLI --extrapolate", an option these commands do not have
        assert "CLI --extrapolate" not in err and f"`{command}` has no --extrapolate" in err, err


def test_blast_still_suggests_its_own_extrapolate(capsys):
    code, _, err = cli(capsys, "blast", "--charge", "1", "--standoff", "100", "--model", "masi2021")
    assert code == 2 and "CLI --extrapolate" in err


def test_scaling_factor_table_gives_no_units_to_ratios(capsys):
    code, out, _ = cli(capsys, "design", "--charge", "50", "--standoff", "2", "--scale", "0.005")
    assert code == 0
    table = out[out.index("Scaling factors") :]
    lines = [ln for ln in table.splitlines() if ln.startswith("│")]
    assert len(lines) >= 15 and all(ln.rstrip("│ ").endswith("-") for ln in lines), lines[:3]


@pytest.mark.parametrize("plot,message", [(".", "is a folder"), ("fig", "has no image extension")])
def test_plot_path_is_the_file_written(capsys, tmp_path, plot, message):
    target = str(tmp_path) if plot == "." else str(tmp_path / plot)
    code, _, err = cli(capsys, "rock", "--alpha-deg", "15", "--charge", "50", "--standoff", "2", "--plot", target)
    assert code == 2 and message in err and err.count("\n") == 1
    assert list(tmp_path.iterdir()) == []  # before: matplotlib wrote fig.png and the CLI printed "fig"
