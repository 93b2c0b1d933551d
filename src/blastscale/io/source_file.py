"""Source files (SOURCE.toml): a calibrated blast source read and written (docs/planning.md, "Sources").

The tables are :func:`blastscale.blast.sources.source_to_dict`'s (``[source]``, ``[equivalence.impulse]``,
``[equivalence.pressure]``, ``[units]``); a file is written at once (:func:`blastscale.io.output.write_file`:
a temporary sibling renamed into place, nothing half-written), with a comment block saying what wrote it and,
for a synthetic calibration, that it is not a real source.
"""

from __future__ import annotations

import functools
import tomllib
from pathlib import Path

import tomli_w

from .._validate import BlastscaleInputError
from ..blast.sources import CalibratedSource, source_from_dict, source_to_dict
from .output import write_file

__all__ = ["read_toml", "read_source", "source_text", "write_source"]


def source_text(source: CalibratedSource, written_by: str = "blastscale source calibrate") -> str:
    """The source file's text (TOML): a comment header, then the tables."""
    head = [
        f"# A calibrated blast source, written by `{written_by}` (docs/planning.md, 'Sources').",
        "# W = tnt_kg_at_reference * (control / reference)^exponent [kg TNT], by impulse and by peak pressure,",
        f"# read against blast model {source.blast_model!r} ({source.burst} burst); units in [units].",
    ]
    if source.synthetic:
        head.append("# SYNTHETIC: made-up shots with a known law (the example and test set): not a real source.")
    return "\n".join(head) + "\n\n" + tomli_w.dumps(source_to_dict(source))


def write_source(path, source: CalibratedSource) -> Path:
    """Write ``source`` to ``path`` at once (module docstring)."""
    return write_file(path, source_text(source), what="--out")


def read_toml(path, what: str) -> dict:
    """The TOML file ``path`` as a dict (UTF-8, a byte-order mark allowed): a source file or a calibration set
    (``what`` names it in the one-line error of an unreadable file; a syntax error names the file)."""
    p = Path(path)
    try:
        text = p.read_text(encoding="utf-8-sig")
    except OSError as exc:
        raise BlastscaleInputError(f"{what} {str(p)!r}: cannot be read ({exc.strerror or exc})") from None
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise BlastscaleInputError(f"{p.name}: TOML syntax error: {exc}") from None


@functools.lru_cache(maxsize=16)
def _read(path: str, mtime_ns: int, size: int) -> CalibratedSource:
    return source_from_dict(read_toml(path, "source file"), Path(path).name)


def read_source(path) -> CalibratedSource:
    """The :class:`~blastscale.blast.sources.CalibratedSource` of the source file ``path`` (read once per version
    of the file: the planner asks for it per candidate).

    Raises
    ------
    BlastscaleInputError
        No such file, a TOML error, a missing or bad key (one line naming the file and the key).
    """
    p = Path(path)
    try:
        st = p.stat()
    except OSError as exc:
        raise BlastscaleInputError(
            f"[lab] source = {str(path)!r}: cannot be read ({exc.strerror or exc}); give the file written by "
            "`blastscale source calibrate` (relative paths: relative to the scenario file)"
        ) from None
    return _read(str(p.resolve()), st.st_mtime_ns, st.st_size)
