"""Issue #34: docs/design.md's layout names the code as it is. The tree in the fenced block under its
"## Layout" heading has one entry line per subpackage (``name/``) or top-level module (``name.py``; several on one
line separated by ", "), indented by two spaces, the names ending at the first run of two spaces; deeper-indented
lines continue a description. Every subpackage (a folder of ``src/blastscale`` with an ``__init__.py``) and every
top-level module but ``__init__.py`` is named there, and nothing that is not one."""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SRC = ROOT / "src" / "blastscale"
DESIGN = ROOT / "docs" / "design.md"


def layout_block() -> str:
    """The fenced block of design.md's "## Layout" section."""
    text = DESIGN.read_text(encoding="utf-8")
    section = re.search(r"^## Layout\b.*?(?=^## )", text, flags=re.S | re.M)
    assert section, "docs/design.md has no '## Layout' section"
    block = re.search(r"```\n(.*?)```", section[0], flags=re.S)
    assert block, "the layout section has no fenced block"
    return block[1]


def layout_names() -> list[str]:
    """The names of the entry lines, in order (``blast/``, ``units.py``, ...)."""
    lines = layout_block().splitlines()
    assert lines[0].strip() == "src/blastscale/", lines[0]
    names = []
    for line in lines[1:]:
        if re.match(r"^  \S", line):
            names += [n.strip() for n in re.split(r"\s{2,}", line.strip())[0].split(",")]
    return names


def code_names() -> set[str]:
    """Every subpackage (``name/``) and top-level module (``name.py``) of src/blastscale."""
    packages = {f"{p.parent.name}/" for p in SRC.glob("*/__init__.py")}
    modules = {p.name for p in SRC.glob("*.py") if p.name != "__init__.py"}
    return packages | modules


def test_the_layout_parses():
    names = layout_names()
    assert len(names) >= 20, names
    assert all(re.fullmatch(r"[a-z_0-9]+(/|\.py)", n) for n in names), names
    assert len(names) == len(set(names)), f"named twice: {sorted(n for n in names if names.count(n) > 1)}"


def test_the_layout_names_every_package_and_module_and_nothing_else():
    named, code = set(layout_names()), code_names()
    missing, gone = sorted(code - named), sorted(named - code)
    assert not missing and not gone, (
        f"docs/design.md's layout misses {missing} (in src/blastscale) and names {gone} (not in src/blastscale)"
    )


def test_the_readme_package_table_names_every_package_and_nothing_else():
    """The README's layout table (its rows' first cells: ``blastscale.NAME``) names every subpackage and
    public top-level module of src/blastscale, and nothing that is not one."""
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    section = re.search(r"^## Layout\b.*?(?=^## )", text, flags=re.S | re.M)
    assert section, "README.md has no '## Layout' section"
    cells = re.findall(r"^\| (`blastscale\..*?) \|", section[0], flags=re.M)
    named = {n for cell in cells for n in re.findall(r"`blastscale\.(\w+)`", cell)}
    code = {n.rstrip("/").removesuffix(".py") for n in code_names() if not n.startswith("_")}
    missing, gone = sorted(code - named), sorted(named - code)
    assert not missing and not gone, f"README's layout table misses {missing} and names {gone}"
