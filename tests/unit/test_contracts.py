"""docs/contracts.md, the contracts a scan of the source can hold (the others name their own tests there).

- Section 4, scaling: every ``scaled`` method of the package has the one signature ``scaled(self, factors)``
  (a :class:`blastscale.similitude.ScalingFactors`), for structures, contact settings, pulses, load models and
  rocking systems alike.
- Section 5, files: no module outside ``blastscale.io`` writes a file: no ``write_text``, ``write_bytes``,
  ``mkdir``, ``touch``, ``to_netcdf``, ``to_zarr``, ``to_csv``, ``open`` for writing (but the null device) or
  ``savefig`` into anything but an in-memory buffer. :data:`NOT_OUTPUT` names the writes that are not output
  (a test's pause marker); :data:`BROKEN` the places that still break the contract, each with what replaces it:
  a fixed one must leave the list (the test says so), a new one fails.
"""

from __future__ import annotations

import ast
from pathlib import Path

SRC = Path(__file__).resolve().parents[2] / "src" / "blastscale"

#: Calls that write a file, by the called attribute's or function's name.
WRITERS = {"write_text", "write_bytes", "mkdir", "touch", "to_netcdf", "to_zarr", "to_csv"}

#: module: why its write is not output (it stays).
NOT_OUTPUT = {
    "_hooks.py": "the pause marker of the project's own signal tests, written only when a test asks for it",
}

#: module: the write that breaks section 5 today, and what replaces it.
BROKEN = {
    "report/reproduce.py": "stdout.txt of a gallery script (plain write_text into the claimed folder): "
    "through blastscale.io.output's write_file",
    "cli/reproduce.py": "the reproduce folder made by folder.mkdir() after io's claim: made by io.output",
}


def _modules():
    for path in sorted(SRC.rglob("*.py")):
        yield path.relative_to(SRC).as_posix(), ast.parse(path.read_text(encoding="utf-8"))


def _writes(tree) -> list[str]:
    """The calls of ``tree`` that write a file (module docstring)."""
    found = []
    for node in ast.walk(tree):
        if not isinstance(node, ast.Call):
            continue
        f = node.func
        name = f.attr if isinstance(f, ast.Attribute) else getattr(f, "id", None)
        text = ast.unparse(node)
        if name in WRITERS:
            found.append(text)
        elif name == "open" and isinstance(f, ast.Name):
            mode = (
                node.args[1] if len(node.args) > 1 else next((k.value for k in node.keywords if k.arg == "mode"), None)
            )
            is_write = isinstance(mode, ast.Constant) and any(c in str(mode.value) for c in "wax+")
            if is_write and "devnull" not in ast.unparse(node.args[0]):
                found.append(text)
        elif name == "savefig" and node.args and "buf" not in ast.unparse(node.args[0]):
            found.append(text)
    return found


def test_every_scaled_method_takes_the_factors():
    """Section 4: ``scaled(self, factors)``, nothing else (a length, a lambda or keywords would be a second
    signature)."""
    bad = []
    for rel, tree in _modules():
        for node in ast.walk(tree):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)) and node.name == "scaled":
                a = node.args
                names = [x.arg for x in a.posonlyargs + a.args]
                if names != ["self", "factors"] or a.kwonlyargs or a.vararg or a.kwarg or a.defaults:
                    bad.append(f"{rel}:{node.lineno} scaled({ast.unparse(a)})")
    assert not bad, "\n".join(bad)


def test_only_io_writes_files():
    """Section 5: the writes outside blastscale.io are the listed ones; a new one fails, a fixed one must leave
    BROKEN."""
    found = {}
    for rel, tree in _modules():
        if rel.startswith("io/") or rel in NOT_OUTPUT:
            continue
        if writes := _writes(tree):
            found[rel] = writes
    new = {k: v for k, v in found.items() if k not in BROKEN}
    fixed = sorted(set(BROKEN) - set(found))
    assert not new, f"files written outside blastscale.io (docs/contracts.md section 5): {new}"
    assert not fixed, f"{fixed} no longer write files: remove them from BROKEN"
