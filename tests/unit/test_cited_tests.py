"""Every test a reader is sent to exists (issue #23): the test paths cited in ``src/`` (docstrings and
comments), ``docs/``, the README and the newest section of the CHANGELOG (``tests/.../test_x.py``, with
``::test_name`` where a test is named) are files of ``tests/``, and each named test is a function
defined in its file. The tests moved to ``tests/unit``, ``tests/integration`` and ``tests/system``
(issue #14) left 24 citations pointing at ``tests/test_x.py``; this keeps the next move honest."""

from __future__ import annotations

import ast
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]

#: A cited test: ``tests/<folders>/test_x.py`` and an optional ``::test_name`` (a parametrised test's
#: ``[id]`` is not part of the name).
CITATION = re.compile(r"\btests/(?:[A-Za-z0-9_]+/)*[A-Za-z0-9_]+\.py(?:::([A-Za-z_][A-Za-z0-9_]*))?")


def newest_changelog_section(text: str) -> str:
    """The CHANGELOG from its first ``## `` heading up to the next one (the section being written)."""
    parts = re.split(r"^## ", text, flags=re.MULTILINE)
    return parts[1] if len(parts) > 1 else ""


def cited_sources() -> dict:
    """Where citations are looked for: name (relative path) -> text."""
    files = sorted((ROOT / "src").rglob("*.py")) + sorted((ROOT / "docs").rglob("*.md")) + [ROOT / "README.md"]
    out = {str(p.relative_to(ROOT)): p.read_text(encoding="utf-8") for p in files}
    out["CHANGELOG.md (newest section)"] = newest_changelog_section((ROOT / "CHANGELOG.md").read_text(encoding="utf-8"))
    return out


def defined_functions(path: Path) -> set:
    """Names of the functions (and methods) a test file defines."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    return {n.name for n in ast.walk(tree) if isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef))}


def stale_citations(sources: dict, root: Path = ROOT) -> list:
    """``(source, line, citation, why)`` for every citation whose file or named test does not exist."""
    out = []
    for name, text in sources.items():
        for m in CITATION.finditer(text):
            line = text.count("\n", 0, m.start()) + 1
            path = root / m.group(0).split("::")[0]
            if not path.is_file():
                out.append((name, line, m.group(0), "no such file"))
            elif m.group(1) and m.group(1) not in defined_functions(path):
                out.append((name, line, m.group(0), f"no test {m.group(1)} in the file"))
    return out


def test_every_cited_test_path_and_test_name_exists():
    sources = cited_sources()
    n = sum(len(CITATION.findall(t)) for t in sources.values())
    # 50 citations today (7 naming a test): far fewer means the search broke, not that the docs got better
    assert n >= 40, f"only {n} citations found: is the pattern still right?"
    stale = stale_citations(sources)
    assert not stale, "stale test citations:\n" + "\n".join(f"{s}:{ln}: {c} ({why})" for s, ln, c, why in stale)


def test_a_stale_path_and_a_stale_test_name_are_caught():
    """The check itself: a moved file, a renamed test and a good citation, on this very file."""
    here = Path(__file__).relative_to(ROOT).as_posix()
    text = (
        f"see tests/test_kingery_bulmash.py and\n`{here}::test_no_such_test`, and "
        f"{here}::test_a_stale_path_and_a_stale_test_name_are_caught."
    )
    got = stale_citations({"doc.md": text})
    assert got == [
        ("doc.md", 1, "tests/test_kingery_bulmash.py", "no such file"),
        ("doc.md", 2, f"{here}::test_no_such_test", "no test test_no_such_test in the file"),
    ]
    assert newest_changelog_section("# C\n\n## New\nx tests/a.py\n## Old\ny tests/b.py\n") == "New\nx tests/a.py\n"
