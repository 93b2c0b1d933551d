"""The scenarios that ship with blastscale (package data, ``scenario/library/*.toml``): the paper's
cases (``paper_*``) and a planar block for quick studies (``planar_block``), by name, so that an installed wheel runs them as a source checkout does
(``blastscale run paper_column_square_250kg``, ``blastscale reproduce``)."""

from __future__ import annotations

from importlib import resources

from .._validate import BlastscaleInputError

__all__ = ["library_names", "library_text", "library_source", "TEMPLATE_KINDS", "template_text", "EXAMPLE_BLOCKS"]

#: Structure kinds with a commented scenario template (``blastscale init --kind KIND``).
TEMPLATE_KINDS = ("block", "column", "wall", "arch", "portal", "assembly")

_FOLDER = "library"


def _files():
    return resources.files(__package__).joinpath(_FOLDER)


def library_names() -> list[str]:
    """The names of the shipped scenarios (file stems), sorted."""
    return sorted(p.name[:-5] for p in _files().iterdir() if p.name.endswith(".toml"))


def library_text(name: str) -> str:
    """The TOML text of the shipped scenario ``name`` (with or without ``.toml``)."""
    stem = name[:-5] if name.endswith(".toml") else name
    return _files().joinpath(f"{stem}.toml").read_text(encoding="utf-8")


#: The example block model that ``init --kind assembly`` writes beside its scenario (our JSON, metres, z up):
#: a 1 m cube under a 1 m cube, a pier of two blocks.
EXAMPLE_BLOCKS = {
    "blocks": [
        {"name": f"B{i + 1}", "vertices": [[x, y, z + i] for x in (0.0, 1.0) for y in (-0.5, 0.5) for z in (0.0, 1.0)]}
        for i in range(2)
    ]
}


def template_text(kind: str, blocks: str = "blocks.json") -> str:
    """The commented scenario template of a structure kind (package data ``scenario/templates/KIND.toml``:
    every key a new user sets, with its unit and range); ``blocks``: the block-model file an ``assembly``
    template names."""

    if kind not in TEMPLATE_KINDS:
        raise BlastscaleInputError(f"kind = {kind!r} is not a template: valid kinds are {', '.join(TEMPLATE_KINDS)}")
    text = resources.files(__package__).joinpath("templates", f"{kind}.toml").read_text(encoding="utf-8")
    return text.replace("{blocks}", blocks)


def library_source(name: str) -> str:
    """Where a shipped scenario comes from, for messages and reports (``blastscale:NAME``)."""
    stem = name[:-5] if name.endswith(".toml") else name
    return f"blastscale:{stem}"
