"""The README's commands run as written and print what it shows (issue #15 fault 8; issue #34: its sample
outputs had drifted from the code).

The README's ```console blocks have one form:

- a line starting with ``$ `` is a command, run by bash literally in an empty folder that has the checkout's
  ``.venv`` (commands run in order, in one folder: an ``init`` writes the file a later command reads); the
  lines after it, up to the next ``$ `` line or the block's end, are what it prints;
- in that printed part, a line ``...`` (or a line that starts and ends with ``...``, such as
  ``... (scaling factors table) ...``) stands for any number of lines; every other line must be the command's
  line at that place, so a part without ``...`` is the whole output. A command that shows nothing must only
  succeed. A part that starts with ``error:`` is the command's standard error, and the command must exit with
  status 2; any other part is its standard output, and the command must succeed;
- a block without ``$ `` lines lists commands without their output (``# ...`` comments after them): each
  line is run and must succeed.

What is normalised, and why (nothing else is: every printed number must be the README's):

- nothing for the width: off a terminal, the commands lay their tables and long lines out at 160 columns
  whatever the environment says (:mod:`blastscale.cli._output`), the width of the README's outputs;
- trailing spaces of each line (rich pads a table's wrapped title to the table's width);
- the standard error of a command that succeeds is not compared: it carries the progress lines (elapsed
  times) and the ``wrote DIR/ (N files, SIZE ...)`` lines, whose sizes vary with the versions and times written
  into the files.

The commands that are not cheap are not run here (:data:`NOT_CHEAP`, each with the test that runs it); every
command of the README, cheap or not, is parsed by the CLI (its flags and their values exist), without running
it. The run takes about 30 s of CPU on the project's 2-core machine.
"""

from __future__ import annotations

import os
import re
import shlex
import subprocess
import sys
from fractions import Fraction
from pathlib import Path

import pytest

README = Path(__file__).resolve().parents[2] / "README.md"

#: The environment of the commands run: figures drawn off screen.
ENV = {"MPLBACKEND": "Agg"}

#: Commands not run here, by a piece of their text: why, and where they run.
NOT_CHEAP = {
    "make ": "set-up and the whole suite (this is the suite)",
    "paper_column_square_250kg --out": "a 3D column, ~1 min (tests/system/test_column_cli.py runs it short)",
    "reproduce --out paper ": "the full paper, ~14 min (benchmarks; test_reproduce.py runs items of it)",
    "reproduce --quick": "every item shortened, ~1 min (tests/system/test_wheel.py runs it from a wheel)",
    "1000:log --vary standoff_m=1.5:6:1000": "a million cases, ~1 min (benchmarks/bench_sweeps.py)",
    "plan paper_column_square_250kg": "3 x 33 3D runs of a column, minutes (benchmarks/bench_plan.py; "
    "tests/integration/test_plan_any_structure.py runs it short)",
    "plan wall_running_bond_lambda20": "3 x 33 3D runs of a wall, minutes (tests/system/test_plan_cli.py runs it short)",
    "capacity paper_column_square_250kg": "38 3D runs of a column, ~1 min of CPU (benchmarks/bench_capacity3d.py; "
    "tests/system/test_capacity3d.py runs a short column)",
    "--samples 2000": "26,000 draws with a body per draw, ~10 s (test_fragility.py runs it with fewer draws)",
    "--samples 40 --workers 2": "200 3D runs of a column, minutes (benchmarks/bench_fragility.py; "
    "tests/integration/test_fragility_any_structure.py runs a three-drum column short)",
    "run my_scenario.toml --out mine": "a planar and a 3D block, ~10 s of CPU (tests/system/test_run.py runs the "
    "main job; tests/system/test_init_and_console.py the templates of init)",
    "run portal_lambda20 --out": "a 3D portal, ~9 s of CPU (tests/integration/test_assembly_similarity.py)",
    "--vary standoff_m=2,3,5 --out sweep.zarr": "60 Studies, ~16 s of CPU (tests/integration/test_sweeps.py)",
    "similarity-map planar_block.toml": "48 designs, ~7 s of CPU (tests/integration/test_similarity_map.py)",
    "plan my_lab.toml --out plan": "~9 s of CPU (tests/system/test_plan_cli.py: plan --out)",
}


def _is_elision(line: str) -> bool:
    return line.strip() == "..." or (line.startswith("...") and line.rstrip().endswith("..."))


def examples() -> list:
    """(command, the lines it prints in the README) of every console block, in order; the lines are None for
    a block without ``$ `` lines (module docstring)."""
    text = README.read_text(encoding="utf-8")
    out = []
    for block in re.findall(r"```console\n(.*?)```", text, flags=re.S):
        lines = block.splitlines()
        if not any(line.startswith("$ ") for line in lines):
            out += [(line.strip(), None) for line in lines if line.strip()]
            continue
        mine = []
        for line in lines:
            if line.startswith("$ "):
                mine.append((line[2:].strip(), []))
            elif mine:
                mine[-1][1].append(line)
        out += mine
    for _, shown in out:
        while shown and not shown[-1].strip():
            shown.pop()  # a blank line between two examples of a block
    return out


def commands() -> list:
    """Every command of the README's console blocks, in order."""
    return [c for c, _ in examples()]


def _cheap(cmd: str) -> bool:
    return not any(piece in cmd + " " for piece in NOT_CHEAP)


def matches(shown: list, printed: str) -> bool:
    """Whether ``printed`` is ``shown``: line by line, ``...`` for any lines, trailing spaces aside."""
    pattern = "".join(r"(?:.*\n)*?" if _is_elision(s) else re.escape(s.rstrip()) + r"\n" for s in shown)
    text = "".join(line.rstrip() + "\n" for line in printed.splitlines())
    return re.fullmatch(pattern, text) is not None


def test_the_readme_has_no_made_up_file_names():
    cmds = commands()
    assert len(cmds) >= 17
    made = [c for c in cmds if "my_scenario.toml" in c]
    # my_scenario.toml only after `blastscale init` has written it
    assert not made or "init my_scenario.toml" in made[0]


def test_the_readme_shows_outputs_in_the_documented_form():
    """At least the worked example's commands show what they print, and an elision is a line of its own."""
    shown = {c.split()[1]: s for c, s in examples() if s and c.startswith(".venv/bin/blastscale")}
    assert {"design", "blast", "rock", "critical", "block3d", "fired"} <= shown.keys(), sorted(shown)
    assert all(not s.strip().startswith("...") or _is_elision(s) for lines in shown.values() for s in lines)


def test_matches_reads_elisions():
    assert matches(["a", "...", "d"], "a\nb\nc\nd\n")
    assert matches(["...", "c"], "a  \nb\nc")
    assert not matches(["a", "c"], "a\nb\nc\n")
    assert not matches(["b"], "a\nb\n")
    assert matches(["a", "... (the rest) ..."], "a\nb\n")


def test_every_readme_command_parses():
    """Every ``blastscale`` command of the README, run here or not, names a command, flags it has and values
    they take (the CLI's parser reads them; nothing runs). A ratio given as a fraction (``--scale 1/100``) is
    read as its decimal, as the command does before parsing."""
    import typer

    from blastscale.cli import app

    group = typer.main.get_command(app)
    bad = []
    for cmd in commands():
        if not cmd.startswith(".venv/bin/blastscale "):
            continue
        args = shlex.split(cmd.split(" #")[0])[1:]
        args = [repr(float(Fraction(a))) if re.fullmatch(r"\d+/\d+", a) else a for a in args]
        name, *rest = args
        if name not in group.commands:
            bad.append(f"{cmd}: no command {name!r}")
            continue
        try:
            parent = group.context_class(group, info_name="blastscale")
            group.commands[name].make_context(name, rest, parent=parent).close()
        except typer.Exit:
            pass
        except typer.TyperException as e:  # click's usage errors: an unknown flag, a bad value
            bad.append(f"{cmd}: {e.format_message()}")
    assert not bad, "\n".join(bad)


@pytest.mark.slow
@pytest.mark.skipif(not (Path(sys.executable).parent / "blastscale").exists(), reason="needs the console script")
def test_the_readme_commands_print_what_it_shows(tmp_path):
    venv = Path(sys.executable).parent.parent
    (tmp_path / ".venv").symlink_to(venv, target_is_directory=True)
    env = {**os.environ, **ENV}
    ran, compared = [], []
    for cmd, shown in examples():
        if not _cheap(cmd):
            continue
        proc = subprocess.run(["bash", "-c", cmd], cwd=tmp_path, capture_output=True, text=True, env=env, timeout=300)
        error = bool(shown) and shown[0].startswith("error:")
        if error:
            assert proc.returncode == 2, f"{cmd}\n{proc.stderr}"
        else:
            assert proc.returncode == 0, f"{cmd}\n{proc.stderr[-2000:]}"
        if shown:
            printed = proc.stderr if error else proc.stdout
            assert matches(shown, printed), (
                f"{cmd}\nthe README shows:\n" + "\n".join(shown) + f"\nit prints:\n{printed}"
            )
            compared.append(cmd)
        ran.append(cmd)
    assert len(ran) >= 12 and len(compared) >= 8, (ran, compared)


#: .toml arguments of the docs' commands that are neither shipped nor written by an earlier `init`: why.
DOCS_FILES_DESCRIBED = {
    "bad.toml": "docs/scenarios.md: an illustration of the error lines, one per kind of mistake",
    "lab05.toml": "docs/planning.md: its content is given in the text above the command",
    "arch_lab.toml": "docs/planning.md: its content is the TOML block above the command",
    "wall.toml": "docs/assemblies.md: its content is the TOML block above the command",
    "source.toml": "docs/planning.md: the source file the `source calibrate` command above it writes",
    "wires_lab.toml": "docs/planning.md: the paper's block with [lab] source, described above the command",
}


def test_the_docs_commands_name_real_commands_and_files():
    """Every `blastscale COMMAND` in the README's and docs' code blocks is a command of the CLI, and every
    scenario file it reads is shipped, written by an earlier `blastscale init` of the same page, an upper-case
    placeholder or described on the page (DOCS_FILES_DESCRIBED). Cheap: nothing is run."""
    import typer

    from blastscale.cli import app
    from blastscale.scenario import library_names

    commands = {c.name for c in typer.main.get_command(app).commands.values()}
    shipped = set(library_names())
    bad = []
    for page in [README, *sorted((README.parent / "docs").glob("*.md"))]:
        made = set()
        for block in re.findall(r"```(?:console|bash|sh)?\n(.*?)```", page.read_text(encoding="utf-8"), flags=re.S):
            for line in block.splitlines():
                m = re.match(r"^\s*(?:\$ )?(?:\.venv/bin/)?blastscale (\S+)(.*)$", line)
                if not m or m[1].startswith("-"):
                    continue
                sub, rest = m[1], m[2].split("#")[0].split()
                if sub not in commands:
                    bad.append(f"{page.name}: {line.strip()} (no command {sub!r})")
                files = [a for a in rest if a.endswith(".toml") and not a.startswith("-")]
                if sub == "init":
                    made.update(files)
                    continue
                for f in files:
                    if (
                        f[:-5] in shipped
                        or f in made
                        or f.split("/")[-1].isupper()
                        or f.startswith("DIR")
                        or "SCENARIO" in f
                        or f in DOCS_FILES_DESCRIBED
                    ):
                        continue
                    bad.append(f"{page.name}: {line.strip()} ({f} is not shipped nor written by an earlier init)")
    assert not bad, "\n".join(bad)
