"""The scenarios that ship with blastscale (package data, ``scenario/library/*.toml``): the paper's
cases (``paper_*``) and a planar block for quick studies (``planar_block``), by name, so that an installed wheel runs them as a source checkout does
(``blastscale run paper_column_square_250kg``, ``blastscale reproduce``)."""

from __future__ import annotations

from importlib import resources
from .._validate import BlastscaleInputError

__all__ = ["library_names", "library_text", "library_source", "TEMPLATE_KINDS", "template_text"]

#: Structure kinds with a commented scenario template (``blastscale init --kind KIND``).
TEMPLATE_KINDS = ("block", "column")

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


def template_text(kind: str) -> str:
    """The commented scenario template of a structure kind (package data ``scenario/templates/KIND.toml``:
    every key a new user sets, with its unit and range)."""

    if kind not in TEMPLATE_KINDS:
        raise BlastscaleInputError(f"kind = {kind!r} is not a template: valid kinds are {', '.join(TEMPLATE_KINDS)}")
    return resources.files(__package__).joinpath("templates", f"{kind}.toml").read_text(encoding="utf-8")


def library_source(name: str) -> str:
    """Where a shipped scenario comes from, for messages and reports (``blastscale:NAME``)."""
    stem = name[:-5] if name.endswith(".toml") else name
    return f"blastscale:{stem}"
