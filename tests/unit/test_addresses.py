"""One address per name (issue #34): a name is imported from the module that defines it.

Counted over ``src/blastscale`` with :mod:`ast` (no import of the package):

- a *re-export* is a name a module imports from another blastscale module and lists in its ``__all__``, or
  imports and never uses: allowed only in a package ``__init__`` (the package's public API, for users);
- a *second-home import* is ``from blastscale.A import n`` (or the relative form) where ``A`` does not define
  ``n`` but imports it from elsewhere: never inside the library, package ``__init__`` files included;
- private names imported between sibling modules are counted (and bounded) by tests/unit/test_cohesion.py.
"""

from __future__ import annotations

import ast
from pathlib import Path

SRC = Path(__file__).resolve().parents[2] / "src"


def _string_annotations(tree):
    """The expressions of the annotations written as strings (``x: "Clearing | None"``)."""
    notes = []
    for n in ast.walk(tree):
        if isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef)):
            args = n.args.posonlyargs + n.args.args + n.args.kwonlyargs + [n.args.vararg, n.args.kwarg]
            notes += [a.annotation for a in args if a is not None] + [n.returns]
        elif isinstance(n, ast.AnnAssign):
            notes.append(n.annotation)
    out = []
    for note in notes:
        for c in ast.walk(note) if note is not None else ():
            if isinstance(c, ast.Constant) and isinstance(c.value, str):
                try:
                    out.append(ast.parse(c.value, mode="eval"))
                except SyntaxError:
                    pass
    return out


def _literal_or_none(node):
    """The value of a literal ``__all__``, or None when it is computed (a lazy package derives it)."""
    try:
        return list(ast.literal_eval(node))
    except ValueError:
        return None


class _Module:
    def __init__(self, path: Path):
        rel = path.relative_to(SRC).with_suffix("").parts
        self.is_pkg = rel[-1] == "__init__"
        self.name = ".".join(rel[:-1] if self.is_pkg else rel)
        self.package = self.name if self.is_pkg else self.name.rpartition(".")[0]
        self.tree = ast.parse(path.read_text(encoding="utf-8"))
        self.defs, self.imports, self.all, self.lazy = set(), {}, None, {}
        self._top(self.tree.body)
        if self.all is None and self.lazy:  # `__all__ = list(_HOMES)`: the names the lazy package maps
            self.all = list(self.lazy)
        self.used = {n.id for n in ast.walk(self.tree) if isinstance(n, ast.Name) and not isinstance(n.ctx, ast.Store)}
        self.used |= {n.id for s in _string_annotations(self.tree) for n in ast.walk(s) if isinstance(n, ast.Name)}

    def resolve(self, node: ast.ImportFrom) -> str:
        if node.level == 0:
            return node.module or ""
        base = self.package.split(".")
        base = base[: len(base) - (node.level - 1)]
        return ".".join(base) + ("." + node.module if node.module else "")

    def _top(self, body) -> None:
        for st in body:
            if isinstance(st, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
                self.defs.add(st.name)
            elif isinstance(st, (ast.Assign, ast.AnnAssign, ast.AugAssign)):
                for t in st.targets if isinstance(st, ast.Assign) else [st.target]:
                    for n in ast.walk(t):
                        if isinstance(n, ast.Name):
                            self.defs.add(n.id)
                            if n.id == "__all__" and st.value is not None:
                                # a literal list, or a lazy package's `list(_HOMES)` (its keys, below)
                                self.all = _literal_or_none(st.value)
                            elif n.id == "_HOMES" and self.is_pkg:  # a lazy package: name -> submodule
                                self.lazy = ast.literal_eval(st.value)
            elif isinstance(st, ast.ImportFrom):
                for a in st.names:
                    self.imports[a.asname or a.name] = (self.resolve(st), a.name)
            elif isinstance(st, (ast.If, ast.Try, ast.With)):
                for part in (st.body, getattr(st, "orelse", []), getattr(st, "finalbody", [])):
                    self._top(part)
                for h in getattr(st, "handlers", []):
                    self._top(h.body)


MODULES = {m.name: m for m in map(_Module, sorted((SRC / "blastscale").rglob("*.py")))}


def _home(module: str, name: str):
    """The blastscale module that defines ``name`` reached through ``module`` (None: a submodule, an outside
    library or unknown)."""
    m = MODULES.get(module)
    if m is None or f"{module}.{name}" in MODULES:
        return None
    if name in m.defs:
        return module
    if name in m.lazy:
        return _home(f"{module}.{m.lazy[name]}", name)
    if name in m.imports:
        src, orig = m.imports[name]
        return _home(src, orig) if src.startswith("blastscale") else None
    return None


def test_no_module_but_a_package_init_reexports_a_name():
    found = []
    for m in MODULES.values():
        if m.is_pkg:
            continue
        for bound, (src, orig) in m.imports.items():
            home = _home(src, orig) if src.startswith("blastscale") else None
            if home is not None and ((m.all is not None and bound in m.all) or bound not in m.used):
                found.append(f"{m.name}.{bound} (defined in {home})")
    assert not found, found


def test_the_library_imports_every_name_from_its_defining_module():
    found = []
    for m in MODULES.values():
        for node in ast.walk(m.tree):
            if isinstance(node, ast.ImportFrom) and m.resolve(node).startswith("blastscale"):
                src = m.resolve(node)
                for a in node.names:
                    home = _home(src, a.name)
                    if home is not None and home != src:
                        found.append(f"{m.name}:{node.lineno}: {a.name} from {src}, defined in {home}")
    assert not found, found
