"""No test asserts on the clock (issue #40 item 5): a suite that fails on a busy machine blocks every change.

Complexity is checked by counting operations or comparing sizes; timing belongs in ``benchmarks/`` (ratios to a
baseline measured in the same run). Checked with ``ast`` on every test file: no ``assert`` whose expression
reads a clock (``time.perf_counter``, ``time.time``, ``time.monotonic``, ``time.process_time``, their ``_ns``
forms, ``timeit.default_timer``), directly or through a variable computed from one in the same function (``t0 =
time.perf_counter()``, ``elapsed = time.perf_counter() - t0``, ``assert elapsed < 20``). A clock may still bound
a wait that keeps a hang from hanging the suite (``tests/system/_spawn.py``), outside an assertion.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

TESTS = Path(__file__).resolve().parents[1]
CLOCKS = {"perf_counter", "time", "monotonic", "process_time", "thread_time", "default_timer"}
CLOCK_MODULES = {"time", "timeit"}


def _clock_names(tree: ast.Module) -> set[str]:
    """Names bound to a clock function by ``from time import perf_counter [as pc]``."""
    out = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and node.module in CLOCK_MODULES:
            for a in node.names:
                if a.name.removesuffix("_ns") in CLOCKS:
                    out.add(a.asname or a.name)
    return out


def _reads_clock(node: ast.AST, direct: set[str], tainted: set[str]) -> bool:
    """Whether ``node`` calls a clock or reads a variable computed from one."""
    for n in ast.walk(node):
        if isinstance(n, ast.Call):
            f = n.func
            if (
                isinstance(f, ast.Attribute)
                and f.attr.removesuffix("_ns") in CLOCKS
                and isinstance(f.value, ast.Name)
                and f.value.id in CLOCK_MODULES
            ):
                return True
            if isinstance(f, ast.Name) and f.id in direct:
                return True
        if isinstance(n, ast.Name) and n.id in tainted:
            return True
    return False


def _targets(node: ast.AST) -> list[str]:
    if isinstance(node, ast.Assign):
        targets = node.targets
    elif isinstance(node, (ast.AugAssign, ast.AnnAssign, ast.NamedExpr)):
        targets = [node.target]
    else:
        return []
    return [n.id for t in targets for n in ast.walk(t) if isinstance(n, ast.Name)]


def _own_nodes(scope: ast.AST) -> list[ast.AST]:
    """The nodes of a module or function, not those of the functions defined in it (their own scopes)."""
    out, todo = [], list(ast.iter_child_nodes(scope))
    while todo:
        n = todo.pop()
        out.append(n)
        if not isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda)):
            todo.extend(ast.iter_child_nodes(n))
    return out


def clock_assertions(source: str) -> list[int]:
    """Line numbers of the ``assert`` statements of ``source`` that read a clock (module docstring)."""
    tree = ast.parse(source)
    direct = _clock_names(tree)
    scopes = [tree] + [n for n in ast.walk(tree) if isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef))]
    lines = set()
    for scope in scopes:
        tainted: set[str] = set()
        nodes = _own_nodes(scope)
        assigns = [n for n in nodes if _targets(n)]
        while True:  # to a fixed point: a variable computed from a tainted one is tainted
            more = {t for a in assigns if _reads_clock(a.value, direct, tainted) for t in _targets(a)} - tainted
            if not more:
                break
            tainted |= more
        lines |= {n.lineno for n in nodes if isinstance(n, ast.Assert) and _reads_clock(n, direct, tainted)}
    return sorted(lines)


@pytest.mark.parametrize(
    "source, lines",
    [
        ("import time\nt = time.perf_counter()\nf()\nelapsed = time.perf_counter() - t\nassert elapsed < 20\n", [5]),
        ("import time\ndef f():\n    t0 = time.monotonic()\n    assert time.monotonic() - t0 < 30.0\n", [4]),
        ("from time import perf_counter as pc\nassert pc() > 0\n", [2]),
        ("import time\ndeadline = time.time() + 60\nwhile True:\n    assert time.time() < deadline\n", [4]),
        ("import time\nt = time.process_time_ns()\nx = [t]\nassert x\n", [4]),
        # allowed: a clock that bounds a wait outside any assertion; the same names unrelated in another function
        ("import time\ndef a():\n    t = time.time()\n    return t\ndef b():\n    t = 3\n    assert t == 3\n", []),
        ("import time\nwhile time.monotonic() < 5:\n    time.sleep(0.1)\nassert done\n", []),
    ],
)
def test_the_check_finds_clock_assertions(source, lines):
    assert clock_assertions(source) == lines


def test_no_test_asserts_on_the_clock():
    found = {
        f"{p.relative_to(TESTS)}:{line}": None
        for p in sorted(TESTS.rglob("*.py"))
        for line in clock_assertions(p.read_text(encoding="utf-8"))
    }
    assert not found, f"assertions on elapsed time (count operations instead; time in benchmarks/): {list(found)}"
