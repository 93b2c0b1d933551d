"""The lab's records after the shot: pressure-gauge traces and video marker tracks (CSV), read into SI.

Format (docs/fired.md): a CSV file with a header (or the first sheet of an ``.xlsx`` workbook, read when
openpyxl is installed: the ``xlsx`` extra). The first column is the time, ``time_s``, ``time_ms`` or
``time_us`` (also ``time_µs``), zero at the firing signal (negative times are pre-trigger), strictly increasing. Gauge files
have one column per gauge, ``NAME_Pa``, ``NAME_kPa``, ``NAME_MPa``, ``NAME_bar`` or ``NAME_psi``; track
files two per marker, ``NAME_x_mm`` and ``NAME_z_mm`` (or ``_m``, or ``_px`` with the marker's
``px_per_mm``): the marker's position in the record axes (x along the blast away from the charge, z up,
origin at the centre of the specimen's footprint at rest), not its displacement.

Every fault is one :class:`~blastscale._validate.BlastscaleInputError` line naming the file, the column
and the row (row 1 is the header). The psi factor is the exact NIST one (NIST SP 811, 2008, App. B.8).

Files as lab software writes them: the text is UTF-8 (with or without a byte-order mark), UTF-16 or UTF-32
with a byte-order mark (a spreadsheet's "Unicode text" export, tab-separated), or, when it is not UTF-8, the
Western single-byte encoding charset-normalizer finds (Latin-1, cp1252, cp1250). Columns are separated by
commas, or by tabs when the header has no comma. Lines starting with ``#`` are comments.

Nothing that hangs: a record must be a regular file (not a folder, a FIFO or a device) of at most
``max_bytes`` (:data:`MAX_RECORD_MB` MB unless ``[fired] max_record_mb`` raises it), checked before it is
opened; it is read to that size at most, and to :data:`MAX_RECORD_ROWS` rows.
"""

from __future__ import annotations

import codecs
import csv
import io
import itertools
import math
import os
import stat
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from charset_normalizer import from_bytes

from .._extras import require
from .._validate import BlastscaleInputError

__all__ = [
    "LENGTH_UNITS",
    "MAX_RECORD_MB",
    "MAX_RECORD_ROWS",
    "PRESSURE_UNITS",
    "TIME_UNITS",
    "GaugeRecord",
    "TrackRecord",
    "read_gauges",
    "read_tracks",
    "record_fault",
]

#: Time column -> factor to seconds (microseconds as ``us``, the micro sign ``µs`` or the Greek mu ``μs``).
TIME_UNITS = {"time_s": 1.0, "time_ms": 1e-3, "time_us": 1e-6, "time_\u00b5s": 1e-6, "time_\u03bcs": 1e-6}
#: Pressure suffix -> factor to Pa (psi: 6894.757293168 Pa, NIST SP 811 App. B.8).
PRESSURE_UNITS = {"Pa": 1.0, "kPa": 1e3, "MPa": 1e6, "bar": 1e5, "psi": 6894.757293168361}
#: Position suffix -> factor to m (``px`` is converted by the marker's ``px_per_mm``).
LENGTH_UNITS = {"m": 1.0, "mm": 1e-3, "px": None}
#: Largest value of ``[fired] max_record_mb`` [MB].
MAX_RECORD_MB_LIMIT = 10_000.0
#: Largest record file read [MB] unless ``[fired] max_record_mb`` raises it: a 2 MHz record of 8 gauges over
#: 0.2 s in CSV is about 25 MB.
MAX_RECORD_MB = 100.0
#: Most rows read from one record (a bound on every read: a spreadsheet's rows are not bounded by its bytes).
MAX_RECORD_ROWS = 5_000_000
#: Byte-order marks -> codec (UTF-32's first: its little-endian mark starts with UTF-16's).
_BOMS = (
    (codecs.BOM_UTF32_LE, "utf-32"),
    (codecs.BOM_UTF32_BE, "utf-32"),
    (codecs.BOM_UTF8, "utf-8-sig"),
    (codecs.BOM_UTF16_LE, "utf-16"),
    (codecs.BOM_UTF16_BE, "utf-16"),
)
#: The single-byte encodings a text that is not UTF-8 is tried in (charset-normalizer picks the least chaotic).
_SINGLE_BYTE = ["cp1252", "latin_1", "cp1250"]
#: What a file kind that is not a regular file is called in the messages.
_KINDS = (
    (stat.S_ISDIR, "a folder"),
    (stat.S_ISFIFO, "a FIFO (named pipe)"),
    (stat.S_ISCHR, "a character device"),
    (stat.S_ISBLK, "a block device"),
    (stat.S_ISSOCK, "a socket"),
)


def record_fault(path, column: str, row, what: str) -> BlastscaleInputError:
    """The one-line error of a bad record: ``FILE: column 'C', row R: what``."""
    col = f"column {column!r}" if column else "no column"
    return BlastscaleInputError(f"{Path(path).name}: {col}, row {row}: {what}")


@dataclass(frozen=True)
class GaugeRecord:
    """Pressure-gauge traces of one file (SI).

    Attributes
    ----------
    path : str
    time_s : ndarray
        Sample times [s], zero at the firing signal.
    pressure_Pa : dict of str -> ndarray
        Gauge name -> gauge signal [Pa] (raw: the baseline is still in it).
    columns : dict of str -> str
        Gauge name -> its column header (for the messages of later checks).
    """

    path: str
    time_s: np.ndarray
    pressure_Pa: dict = field(default_factory=dict)
    columns: dict = field(default_factory=dict)


@dataclass(frozen=True)
class TrackRecord:
    """Marker tracks of one file (SI).

    Attributes
    ----------
    path : str
    time_s : ndarray
        Frame times [s], zero at the firing signal.
    position_m : dict of str -> dict of str -> ndarray
        Marker name -> axis (``"x"``, ``"z"``) -> position [m] in the record axes.
    """

    path: str
    time_s: np.ndarray
    position_m: dict = field(default_factory=dict)


def _file_fault(path, what: str) -> BlastscaleInputError:
    """A fault of the record file as a whole: ``record 'PATH': what``."""
    return BlastscaleInputError(f"record {str(path)!r}: {what}")


def _too_big(p: Path, size: str, max_bytes: int) -> BlastscaleInputError:
    return _file_fault(
        p,
        f"{size} MB, above the {max_bytes / 1e6:g} MB a record is read to: set [fired] max_record_mb (now "
        f"{max_bytes / 1e6:g}, valid range (0, {MAX_RECORD_MB_LIMIT:g}] MB) to read a larger one",
    )


def _raw_bytes(p: Path, max_bytes: int) -> bytes:
    """The file's bytes, after checking that it is a regular file of at most ``max_bytes``: opened without
    blocking (a FIFO's open would wait for a writer) and checked on the open file (what was opened is what is
    read); read to ``max_bytes`` + 1 at most (a file that grows meanwhile)."""
    try:
        fd = os.open(p, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_BINARY", 0))
    except OSError as exc:
        raise record_fault(p, "", 1, f"cannot be read ({exc.strerror or exc})") from None
    st = os.fstat(fd)
    if not stat.S_ISREG(st.st_mode) or st.st_size > max_bytes:
        os.close(fd)
        if st.st_size > max_bytes and stat.S_ISREG(st.st_mode):
            raise _too_big(p, f"{st.st_size / 1e6:.4g}", max_bytes)
        kind = next((name for test, name in _KINDS if test(st.st_mode)), "not a regular file")
        raise _file_fault(p, f"is {kind}, not a regular file: give the CSV or .xlsx file the lab's software wrote")
    with open(fd, "rb", closefd=True) as f:
        try:
            raw = f.read(max_bytes + 1)
        except OSError as exc:
            raise record_fault(p, "", 1, f"cannot be read ({exc.strerror or exc})") from None
    if len(raw) > max_bytes:  # it grew while read
        raise _too_big(p, "more than", max_bytes)
    return raw


def _decode(p: Path, raw: bytes) -> str:
    """The text of a record file: by its byte-order mark, else UTF-8, else the single-byte encoding that
    charset-normalizer finds among :data:`_SINGLE_BYTE`."""
    for bom, codec in _BOMS:
        if raw.startswith(bom):
            try:
                return raw.decode(codec)
            except UnicodeDecodeError as exc:
                raise _file_fault(
                    p, f"starts with a {codec} byte-order mark but is not {codec} text (byte {exc.start})"
                )
    try:
        return raw.decode("utf-8")
    except UnicodeDecodeError:
        pass
    best = from_bytes(raw, cp_isolation=_SINGLE_BYTE).best() if b"\x00" not in raw else None
    if best is None:
        raise _file_fault(
            p, "not text in UTF-8, UTF-16 with a byte-order mark or a Western single-byte encoding: save it as CSV"
        )
    return str(best)


def _xlsx_rows(p: Path, raw: bytes) -> list[list[str]]:
    """The first sheet's rows as text (numbers as their shortest repr: the same floats as a CSV's), trailing
    empty cells dropped, at most :data:`MAX_RECORD_ROWS` + 1 rows."""
    openpyxl = require("openpyxl", "xlsx", "a spreadsheet record (.xlsx)")
    try:
        book = openpyxl.load_workbook(io.BytesIO(raw), read_only=True, data_only=True)
    except Exception as exc:  # a damaged or foreign zip: openpyxl raises zipfile's, KeyError, ValueError ...
        raise _file_fault(p, f"is not a readable .xlsx workbook ({type(exc).__name__}: {exc})") from None
    try:
        rows = []
        for r in book.worksheets[0].iter_rows(max_row=MAX_RECORD_ROWS + 2, values_only=True):
            cells = ["" if v is None else repr(v) if isinstance(v, float) else str(v) for v in r]
            while cells and cells[-1] == "":
                cells.pop()
            rows.append(cells)
    finally:
        book.close()
    return rows


def _text_rows(text: str):
    """The rows of a record's text (comment lines dropped), lazily: the caller bounds how many it takes."""
    lines = (ln for ln in io.StringIO(text, newline=None) if not ln.lstrip().startswith("#"))
    head = next((ln for ln in io.StringIO(text, newline=None) if ln.strip() and not ln.lstrip().startswith("#")), "")
    return csv.reader(lines, delimiter="\t" if "," not in head and "\t" in head else ",")


def _read_table(path, max_bytes: int) -> tuple[list[str], list[list[str]]]:
    p = Path(path)
    raw = _raw_bytes(p, max_bytes)
    if raw.startswith(b"PK\x03\x04"):  # a zip: an .xlsx workbook, whatever its name
        table = _xlsx_rows(p, raw)
    elif raw.startswith(b"\xd0\xcf\x11\xe0"):  # OLE2: Excel 97-2003
        raise _file_fault(p, "is an Excel 97-2003 .xls workbook: save it as .xlsx or CSV")
    else:
        table = _text_rows(_decode(p, raw))
    rows = list(itertools.islice((r for r in table if any(c.strip() for c in r)), MAX_RECORD_ROWS + 2))
    if not rows:
        raise record_fault(p, "", 1, "the file is empty: a header and samples expected")
    if len(rows) > MAX_RECORD_ROWS + 1:
        raise record_fault(p, "", MAX_RECORD_ROWS + 2, f"more than {MAX_RECORD_ROWS} samples: not a record file")
    header = [c.strip() for c in rows[0]]
    if header[0] not in TIME_UNITS:
        raise record_fault(p, header[0], 1, f"the first column must be the time: {', '.join(TIME_UNITS)}")
    if len(rows) < 2:
        raise record_fault(p, header[0], 2, "no samples under the header")
    return header, rows[1:]


def _numbers(path, header: list[str], rows: list[list[str]]) -> np.ndarray:
    out = np.empty((len(rows), len(header)))
    for i, r in enumerate(rows):
        if len(r) != len(header):
            raise record_fault(
                path,
                header[min(len(r), len(header) - 1)],
                i + 2,
                f"{len(r)} values, the header has {len(header)} columns",
            )
        for j, cell in enumerate(r):
            try:
                v = float(cell)
            except ValueError:
                v = math.nan
            if not math.isfinite(v):
                raise record_fault(path, header[j], i + 2, f"value {cell.strip()!r} is not a finite number")
            out[i, j] = v
    t = out[:, 0] * TIME_UNITS[header[0]]
    bad = np.flatnonzero(np.diff(t) <= 0)
    if bad.size:
        k = int(bad[0]) + 1
        raise record_fault(
            path,
            header[0],
            k + 2,
            f"time {rows[k][0].strip()} is not above the previous {rows[k - 1][0].strip()}: times must increase",
        )
    out[:, 0] = t
    return out


def _suffix(path, col: str, j: int, units: Mapping, what: str) -> tuple[str, str]:
    name, sep, unit = col.rpartition("_")
    if not sep or not name or unit not in units:
        raise record_fault(
            path,
            col,
            1,
            f"unknown unit suffix {('_' + unit) if sep else col!r} for a {what} "
            f"column: valid suffixes are {', '.join('_' + u for u in units)}",
        )
    return name, unit


def _known(path, col: str, name: str, names, table: str) -> None:
    if names is not None and name not in names:
        raise record_fault(
            path,
            col,
            1,
            f"{table.split('.')[-1]} {name!r} has no [{table}.{name}] table in the "
            f"scenario (known: {', '.join(names) or 'none'})",
        )


def read_gauges(path, names: Mapping | None = None, *, max_mb: float = MAX_RECORD_MB) -> GaugeRecord:
    """Read a gauge file (format: module docstring) into Pa and s.

    Parameters
    ----------
    path : str or Path
    names : collection of str, optional
        The gauges the scenario describes (``[fired.gauge.NAME]``); a column of another name is an error.
    max_mb : float
        Largest file read [MB] (``[fired] max_record_mb``).

    Raises
    ------
    BlastscaleInputError
        One line naming the file, the column and the row: an empty file, no time column, an unknown unit
        suffix, a gauge without a table, a value that is not a finite number, times that do not increase;
        one line naming the file: not a regular file, larger than ``max_mb``, not text in a known encoding.
    MissingExtraError
        An ``.xlsx`` workbook without openpyxl (the ``xlsx`` extra).
    """
    header, rows = _read_table(path, int(max_mb * 1e6))
    parsed = []
    for j, col in enumerate(header[1:], start=1):
        name, unit = _suffix(path, col, j, PRESSURE_UNITS, "gauge")
        _known(path, col, name, names, "fired.gauge")
        parsed.append((name, unit))
    data = _numbers(path, header, rows)
    pressure = {n: data[:, j] * PRESSURE_UNITS[u] for j, (n, u) in enumerate(parsed, start=1)}
    cols = {n: header[j] for j, (n, _) in enumerate(parsed, start=1)}
    return GaugeRecord(str(path), data[:, 0], pressure, cols)


def read_tracks(
    path,
    names: Mapping | None = None,
    px_per_mm: Mapping[str, float] | None = None,
    *,
    max_mb: float = MAX_RECORD_MB,
) -> TrackRecord:
    """Read a track file (format: module docstring) into m and s.

    Parameters
    ----------
    path : str or Path
    names : collection of str, optional
        The markers the scenario describes (``[fired.marker.NAME]``).
    px_per_mm : mapping of str -> float, optional
        Marker name -> image scale [px/mm], needed for ``_px`` columns.
    max_mb : float
        Largest file read [MB] (``[fired] max_record_mb``).

    Raises
    ------
    BlastscaleInputError
        As :func:`read_gauges`, and for a column that is not ``NAME_x_UNIT`` / ``NAME_z_UNIT``, a ``_px``
        column without ``px_per_mm``, or a marker without its ``x`` column.
    """
    header, rows = _read_table(path, int(max_mb * 1e6))
    parsed = []
    for col in header[1:]:
        stem, unit = _suffix(path, col, 0, LENGTH_UNITS, "track")
        name, sep, axis = stem.rpartition("_")
        if not sep or axis not in ("x", "z") or not name:
            raise record_fault(path, col, 1, "a track column is NAME_x_UNIT or NAME_z_UNIT (x along the blast, z up)")
        _known(path, col, name, names, "fired.marker")
        if unit == "px":
            scale = (px_per_mm or {}).get(name)
            if scale is None or not (math.isfinite(scale) and scale > 0):
                raise record_fault(
                    path, col, 1, f"a _px column needs px_per_mm > 0 in [fired.marker.{name}] (got {scale!r})"
                )
            factor = 1e-3 / scale
        else:
            factor = LENGTH_UNITS[unit]
        parsed.append((name, axis, factor))
    data = _numbers(path, header, rows)
    pos: dict = {}
    for j, (name, axis, factor) in enumerate(parsed, start=1):
        pos.setdefault(name, {})[axis] = data[:, j] * factor
    for j, (name, _, _) in enumerate(parsed, start=1):
        if "x" not in pos[name]:
            raise record_fault(
                path,
                header[j],
                1,
                f"marker {name!r} has no x column (NAME_x_mm): the horizontal position is what is compared",
            )
    return TrackRecord(str(path), data[:, 0], pos)
