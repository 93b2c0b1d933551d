"""Cohesion instead of a line meter (issue #34, Deliver 4): functions are bounded by ruff's complexity,
argument and statement rules (C901, PLR0913, PLR0915 with the thresholds of pyproject.toml's
``[tool.ruff.lint.mccabe]`` and ``[tool.ruff.lint.pylint]``) against a ratchet, by the count of functions
over 100 lines (each one named with its reason in docs/design.md), and by the count of private names
imported between sibling modules.

The ratchet, tests/data/cohesion_ratchet.json, lists today's offenders as (file, function, rule). A new
offender fails, even in a file that already has one; an entry that no longer offends fails too, so the list
only shrinks: remove the entry when you fix the function (after a merge or a rename:
``python tests/unit/test_cohesion.py --write-ratchet``, then review the diff). ``make test``'s ruff check keeps
its own rule set.
"""

from __future__ import annotations

import ast
import json
import re
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

#: Most functions over 100 lines (end_lineno - lineno + 1 > 100), each named in docs/design.md.
MAX_LONG_FUNCTIONS = 11
#: Most private names (``_x``, not ``__x``) imported between sibling modules (``from .mod import _x`` or
#: ``from . import _mod``).
MAX_PRIVATE_SIBLING_IMPORTS = 10
#: A function is long above this many lines.
LONG = 100
#: The rules the ratchet bounds.
RULES = ("C901", "PLR0913", "PLR0915")

ROOT = Path(__file__).resolve().parents[2]
SRC = ROOT / "src" / "blastscale"
RATCHET = ROOT / "tests" / "data" / "cohesion_ratchet.json"
DESIGN = ROOT / "docs" / "design.md"
RUFF = Path(sys.executable).parent / "ruff"


def _modules():
    return sorted(SRC.rglob("*.py"))


def _rel(path: Path) -> str:
    return path.resolve().relative_to(SRC).as_posix()


def _functions(tree: ast.AST):
    """(qualified name, node) of every function in ``tree``, methods and nested functions included."""
    out = []

    def walk(node, prefix):
        for child in ast.iter_child_nodes(node):
            if isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
                name = f"{prefix}{child.name}"
                if not isinstance(child, ast.ClassDef):
                    out.append((name, child))
                walk(child, name + ".")
            else:
                walk(child, prefix)

    walk(tree, "")
    return out


def _ruff_offenders() -> set[tuple[str, str, str]]:
    """(file under src/blastscale, function's qualified name, rule) of every C901/PLR0913/PLR0915 finding."""
    if not RUFF.exists():
        pytest.skip(f"ruff not found next to the interpreter ({RUFF})")
    proc = subprocess.run(
        [str(RUFF), "check", str(SRC), "--select", ",".join(RULES), "--output-format", "json", "--no-cache"],
        capture_output=True,
        text=True,
        cwd=ROOT,
    )
    assert proc.returncode in (0, 1), proc.stderr
    trees: dict[str, dict[int, str]] = {}
    found = set()
    for item in json.loads(proc.stdout):
        path = Path(item["filename"])
        rel = _rel(path)
        if rel not in trees:
            tree = ast.parse(path.read_text(encoding="utf-8"))
            trees[rel] = {node.lineno: name for name, node in _functions(tree)}
        row = item["location"]["row"]
        assert row in trees[rel], f"{rel}:{row}: {item['code']} not at a function's `def` line"
        found.add((rel, trees[rel][row], item["code"]))
    return found


def _ratchet():
    data = json.loads(RATCHET.read_text(encoding="utf-8"))
    return data, {tuple(entry) for entry in data["offenders"]}


def test_ruff_thresholds_are_the_ratchets():
    """The thresholds in pyproject.toml are those the ratchet was taken with: raising one would hide offenders."""
    lint = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["tool"]["ruff"]["lint"]
    data, _ = _ratchet()
    assert lint["mccabe"]["max-complexity"] <= data["thresholds"]["max-complexity"]
    assert lint["pylint"]["max-args"] <= data["thresholds"]["max-args"]
    assert lint["pylint"]["max-statements"] <= data["thresholds"]["max-statements"]
    assert not set(RULES) & set(lint.get("ignore", [])), "the ratchet's rules must not be ignored"


def test_no_new_complexity_argument_or_statement_offender():
    """Every C901/PLR0913/PLR0915 offender is on the ratchet, and every ratchet entry still offends."""
    _, allowed = _ratchet()
    found = _ruff_offenders()
    new = sorted(found - allowed)
    fixed = sorted(allowed - found)
    assert not new, "new offenders (split the function along its steps, or pass a small dataclass):\n" + "\n".join(
        f"  {f}: {fn} ({rule})" for f, fn, rule in new
    )
    assert not fixed, (
        "fixed or renamed: remove these entries from tests/data/cohesion_ratchet.json (the list only shrinks):\n"
        + "\n".join(f'  ["{f}", "{fn}", "{rule}"],' for f, fn, rule in fixed)
    )


def test_ratchet_is_sorted_and_unique():
    data, allowed = _ratchet()
    entries = [tuple(e) for e in data["offenders"]]
    assert len(entries) == len(allowed), "duplicate ratchet entries"
    assert entries == sorted(entries), "keep tests/data/cohesion_ratchet.json sorted"


def _long_functions() -> dict[str, int]:
    out = {}
    for path in _modules():
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for node in ast.walk(tree):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                n = node.end_lineno - node.lineno + 1
                if n > LONG:
                    out[f"{_rel(path)}:{node.name}"] = n
    return out


def _documented_long_functions() -> set[str]:
    """The `path:function` names in docs/design.md's section "Functions over 100 lines"."""
    text = DESIGN.read_text(encoding="utf-8")
    match = re.search(r"^## Functions over 100 lines\n(.*?)(?=^## |\Z)", text, flags=re.S | re.M)
    assert match, 'docs/design.md has no section "## Functions over 100 lines"'
    return set(re.findall(r"`([\w/]+\.py:\w+)`", match.group(1)))


def test_long_functions_are_few_and_justified():
    long = _long_functions()
    documented = _documented_long_functions()
    undocumented = sorted(set(long) - documented)
    assert not undocumented, (
        'functions over 100 lines not named in docs/design.md "Functions over 100 lines" (split them along '
        "their steps, or name them there with the reason):\n"
        + "\n".join(f"  {name} ({long[name]} lines)" for name in undocumented)
    )
    assert len(long) <= MAX_LONG_FUNCTIONS, (
        f"{len(long)} functions over {LONG} lines (most {MAX_LONG_FUNCTIONS}):\n"
        + ("\n".join(f"  {name} ({n})" for name, n in sorted(long.items(), key=lambda kv: -kv[1])))
    )


def _private_sibling_imports() -> list[str]:
    out = []
    for path in _modules():
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for node in ast.walk(tree):
            if isinstance(node, ast.ImportFrom) and node.level == 1:
                for alias in node.names:
                    if alias.name.startswith("_") and not alias.name.startswith("__"):
                        out.append(f"{_rel(path)}:{node.lineno}: from .{node.module or ''} import {alias.name}")
    return out


def test_few_private_names_imported_between_siblings():
    found = _private_sibling_imports()
    assert len(found) <= MAX_PRIVATE_SIBLING_IMPORTS, (
        f"{len(found)} private names imported between sibling modules (most {MAX_PRIVATE_SIBLING_IMPORTS}): "
        "make the helper public in its package, or merge the modules:\n" + "\n".join(f"  {line}" for line in found)
    )


def _write_ratchet() -> None:
    """Rewrite tests/data/cohesion_ratchet.json from today's offenders, one entry a line, sorted.

    For a merge or a rename only (``python tests/unit/test_cohesion.py --write-ratchet``): review the diff, which
    may lose entries or rename them, never gain one."""
    lint = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["tool"]["ruff"]["lint"]
    thresholds = {
        "max-complexity": lint["mccabe"]["max-complexity"],
        "max-args": lint["pylint"]["max-args"],
        "max-statements": lint["pylint"]["max-statements"],
    }
    entries = [json.dumps(list(e)) for e in sorted(_ruff_offenders())]
    lines = [
        "{",
        f'  "thresholds": {json.dumps(thresholds)},',
        '  "offenders": [',
        ",\n".join(f"    {e}" for e in entries),
    ]
    RATCHET.write_text("\n".join([*lines, "  ]", "}"]) + "\n", encoding="utf-8")


if __name__ == "__main__":
    if sys.argv[1:] != ["--write-ratchet"]:
        sys.exit("usage: python tests/unit/test_cohesion.py --write-ratchet")
    _write_ratchet()
