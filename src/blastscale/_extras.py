"""Optional extras: which import belongs to which, and the one line a command says when one is missing.

A plain ``pip install blastscale`` runs the default job (``blastscale run``: both engines, the result
files, the report); what it does not need is an extra (pyproject.toml): ``sweeps`` (Zarr sweep stores,
Dask workers), ``mesh`` (block models from OBJ/STL/PLY meshes) and ``xlsx`` (lab records as .xlsx workbooks). Every import of an extra's module goes
through :func:`require`, which raises :class:`MissingExtraError` naming the extra and its install command;
the CLI prints it as one line (``error: blastscale sweep needs the 'sweeps' extra (zarr is not installed):
pip install 'blastscale[sweeps]'``), exit 2, no traceback.
"""

from __future__ import annotations

import importlib
from types import ModuleType
from typing import Optional

__all__ = ["EXTRAS", "MissingExtraError", "require", "extra_of", "install_command", "missing_extra_message"]

#: Top-level module -> the extra that installs it.
EXTRAS = {"zarr": "sweeps", "dask": "sweeps", "distributed": "sweeps", "trimesh": "mesh", "openpyxl": "xlsx"}


def install_command(extra: str) -> str:
    """``pip install 'blastscale[EXTRA]'``."""
    return f"pip install 'blastscale[{extra}]'"


def missing_extra_message(who: str, extra: str, module: str) -> str:
    """``WHO needs the 'EXTRA' extra (MODULE is not installed): pip install 'blastscale[EXTRA]'``."""
    return f"{who} needs the '{extra}' extra ({module} is not installed): {install_command(extra)}"


class MissingExtraError(ModuleNotFoundError):
    """A module of an optional extra is not installed; ``extra`` names the extra, ``name`` the module."""

    def __init__(self, extra: str, module: str, what: str):
        self.extra, self.what = extra, what
        super().__init__(missing_extra_message(what, extra, module), name=module)


def extra_of(exc: BaseException) -> Optional[str]:
    """The extra that provides the module an ``ImportError`` could not find (None: not an extra's)."""
    if isinstance(exc, MissingExtraError):
        return exc.extra
    name = getattr(exc, "name", None)
    return EXTRAS.get(name.split(".")[0]) if isinstance(exc, ImportError) and name else None


def require(module: str, extra: str, what: str) -> ModuleType:
    """Import ``module`` of the optional ``extra``, or raise :class:`MissingExtraError`.

    Parameters
    ----------
    module : str
        Dotted module name (``"zarr"``, ``"dask.distributed"``).
    extra : str
        The extra of pyproject.toml that installs it.
    what : str
        What needs it, for a library caller's message (``"a sweep store"``); the CLI names its command.

    Examples
    --------
    >>> require("math", "none", "a test").pi > 3
    True
    """
    try:
        return importlib.import_module(module)
    except ImportError as exc:
        raise MissingExtraError(extra, getattr(exc, "name", None) or module, what) from exc
