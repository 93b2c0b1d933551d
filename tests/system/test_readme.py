"""Issue #15, fault 8: the README's commands run as written. Every command of its ```console blocks (a line
starting with "$ ", or every line of a block without one) is run by bash, literally, in an empty folder that has
the checkout's .venv, except the few that are not cheap (listed with the reason). A command whose printed output
in the README starts with "error:" must fail with exit 2 and that very line; every other must succeed."""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

README = Path(__file__).resolve().parents[2] / "README.md"

#: Commands not run here, by a piece of their text: why.
NOT_CHEAP = {
    "make ": "set-up and the whole suite (this is the suite)",
    "paper_column_square_250kg --out": "a 3D column, ~1 min (tests/system/test_column_cli.py runs it short)",
    "column --section square --charge 250": "a 3D column, ~40 s (tests/system/test_column_cli.py runs it short)",
    "reproduce --out paper ": "the full paper, ~15 min (benchmarks; test_reproduce.py runs items of it)",
    "reproduce --quick": "every item shortened, ~1 min (tests/system/test_wheel.py runs it from a wheel)",
    "1000:log --vary standoff_m=1.5:6:1000": "a million cases, ~1 min (benchmarks/bench_sweeps.py)",
    "--samples 2000": "26,000 draws with a body per draw, ~10 s (test_fragility.py runs it with fewer draws)",
}


def commands() -> list:
    """(command, expected error line or None) of every console block, in order."""
    text = README.read_text(encoding="utf-8")
    out = []
    for block in re.findall(r"```console\n(.*?)```", text, flags=re.S):
        lines = block.splitlines()
        if any(line.startswith("$ ") for line in lines):
            for i, line in enumerate(lines):
                if line.startswith("$ "):
                    nxt = lines[i + 1] if i + 1 < len(lines) else ""
                    out.append((line[2:].strip(), nxt if nxt.startswith("error:") else None))
        else:
            out += [(line.strip(), None) for line in lines if line.strip()]
    return out


def _cheap(cmd: str) -> bool:
    return not any(piece in cmd + " " for piece in NOT_CHEAP)


def test_the_readme_has_no_made_up_file_names():
    cmds = [c for c, _ in commands()]
    assert len(cmds) >= 17
    made = [c for c in cmds if "my_scenario.toml" in c]
    # my_scenario.toml only after `blastscale init` has written it
    assert not made or "init my_scenario.toml" in made[0]


@pytest.mark.skipif(not (Path(sys.executable).parent / "blastscale").exists(), reason="needs the console script")
def test_the_readme_commands_run_as_written(tmp_path):
    venv = Path(sys.executable).parent.parent
    (tmp_path / ".venv").symlink_to(venv, target_is_directory=True)
    env = {**os.environ, "MPLBACKEND": "Agg"}
    ran = []
    for cmd, error in commands():
        if not _cheap(cmd):
            continue
        proc = subprocess.run(["bash", "-c", cmd], cwd=tmp_path, capture_output=True, text=True, env=env, timeout=300)
        if error is None:
            assert proc.returncode == 0, f"{cmd}\n{proc.stderr[-2000:]}"
        else:
            assert proc.returncode == 2 and proc.stderr.strip() == error.strip(), f"{cmd}\n{proc.stderr}"
        ran.append(cmd)
    assert len(ran) >= 13, ran


#: .toml arguments of the docs' commands that are neither shipped nor written by an earlier `init`: why.
DOCS_FILES_DESCRIBED = {
    "bad.toml": "docs/scenarios.md: an illustration of the error lines, one per kind of mistake",
    "lab05.toml": "docs/planning.md: its content is given in the text above the command",
    "wall.toml": "docs/assemblies.md: its content is the TOML block above the command",
}


def test_the_docs_commands_name_real_commands_and_files():
    """Every `blastscale COMMAND` in the README's and docs' code blocks is a command of the CLI, and every
    scenario file it reads is shipped, written by an earlier `blastscale init` of the same page, an upper-case
    placeholder or described on the page (DOCS_FILES_DESCRIBED). Cheap: nothing is run."""
    from blastscale.cli import app
    from blastscale.scenario import library_names

    import typer

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
