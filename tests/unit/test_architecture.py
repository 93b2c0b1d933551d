"""The architecture is checked, not hoped for (issue #14): the layers and the absence of cycles are
import-linter contracts (pyproject.toml, run by ``make test`` and here); this file adds what
import-linter does not check: no package imports another package's private names or modules. Cohesion is
bounded per function (tests/unit/test_cohesion.py: ruff's complexity, argument and statement rules with a
ratchet, functions over 100 lines named), not by a module line count (issue #34)."""

from __future__ import annotations

import ast
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[2] / "src" / "blastscale"

#: The modules private to blastscale as a whole and shared by every subpackage (validation, test pause points,
#: the thread share, the compiled kernels' cache keys, the code's fingerprint, optional extras).
SHARED_PRIVATE = {
    "blastscale._validate",
    "blastscale._hooks",
    "blastscale._threads",
    "blastscale._jit",
    "blastscale._code",
    "blastscale._extras",
}


def _module_name(path: Path) -> str:
    rel = path.relative_to(SRC.parent).with_suffix("")
    parts = list(rel.parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def _imports(path: Path):
    """(imported module, imported names) of every ``from ... import`` and ``import`` in a module,
    relative imports resolved."""
    mod = _module_name(path)
    pkg = mod if path.name == "__init__.py" else mod.rsplit(".", 1)[0]
    tree = ast.parse(path.read_text())
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            if node.level:
                base = pkg.split(".")
                base = base[: len(base) - (node.level - 1)]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module or ""
            yield node.lineno, target, [a.name for a in node.names]
        elif isinstance(node, ast.Import):
            for a in node.names:
                yield node.lineno, a.name, []


def _top(module: str) -> str:
    parts = module.split(".")
    return ".".join(parts[:2]) if len(parts) > 1 else module


def test_no_package_imports_another_packages_private_names():
    bad = []
    for path in SRC.rglob("*.py"):
        mod = _module_name(path)
        for line, target, names in _imports(path):
            if not target.startswith("blastscale") or _top(target) == _top(mod) or target in SHARED_PRIVATE:
                continue
            private_module = any(p.startswith("_") and not p.startswith("__") for p in target.split(".")[1:])
            private_names = [n for n in names if n.startswith("_") and not n.startswith("__")]
            if private_module or private_names:
                bad.append(f"{path.relative_to(SRC)}:{line}: from {target} import {', '.join(names)}")
    assert not bad, "\n".join(bad)


def test_import_linter_contracts_are_kept():
    exe = shutil.which("lint-imports", path=str(Path(sys.executable).parent))
    if exe is None:
        pytest.skip("import-linter is not installed (pip install -e '.[dev]')")
    proc = subprocess.run([exe, "--no-cache"], capture_output=True, text=True, cwd=SRC.parents[1])
    assert proc.returncode == 0, proc.stdout[-3000:]


def test_every_document_the_code_cites_exists():
    """Issue #14: docs/... references in the source, the tests and the docs resolve (DESIGN.md and
    CONTRACTS.md were once cited 40 times and existed nowhere)."""
    import re

    root = SRC.parents[1]
    cited = set()
    for path in (
        list(SRC.rglob("*.py"))
        + list((root / "tests").rglob("*.py"))
        + list((root / "docs").glob("*.md"))
        + [root / "README.md"]
    ):
        for name in re.findall(r"docs/([A-Za-z0-9_\-]+\.(?:md|png))", path.read_text()):
            cited.add(name)
    missing = sorted(n for n in cited if not (root / "docs" / n).exists())
    assert cited and not missing, missing


def _layers_config() -> tuple:
    """(layer index of every module named in the layers contract, the contracts) from pyproject.toml."""
    import tomllib

    contracts = tomllib.loads((SRC.parents[1] / "pyproject.toml").read_text())["tool"]["importlinter"]["contracts"]
    layers = next(c for c in contracts if c["type"] == "layers")
    level = {m.strip(): i for i, layer in enumerate(layers["layers"]) for m in layer.split("|")}
    return level, contracts


def test_io_is_a_store_below_the_sweeps_and_the_study():
    """Issue #34: the sweeps own the sweep and io is their store, below them: the layers contract puts io beside
    scenario and analysis (under study, under sweeps; its name says so), a forbidden contract names the rule,
    and no io module imports the sweeps or the Study."""
    level, contracts = _layers_config()
    order = ("blastscale.sweeps", "blastscale.study", "blastscale.io", "blastscale.rocking")
    assert [level[m] for m in order] == sorted(level[m] for m in order) and len({level[m] for m in order}) == 4
    assert level["blastscale.io"] == level["blastscale.scenario"] == level["blastscale.analysis"]
    name = next(c for c in contracts if c["type"] == "layers")["name"]
    assert "sweeps > study > scenario | analysis | io >" in name, name
    assert any(
        c["type"] == "forbidden"
        and c["source_modules"] == ["blastscale.io"]
        and {"blastscale.sweeps", "blastscale.study"} <= set(c["forbidden_modules"])
        for c in contracts
    )
    up = [
        f"{path.relative_to(SRC)}:{line}: {target}"
        for path in (SRC / "io").rglob("*.py")
        for line, target, _ in _imports(path)
        if _top(target) in ("blastscale.sweeps", "blastscale.study")
    ]
    assert not up, up
