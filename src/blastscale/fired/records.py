"""The lab's records after the shot: pressure-gauge traces and video marker tracks (CSV), read into SI.

Format (docs/fired.md): a CSV file with a header. The first column is the time, ``time_s``, ``time_ms`` or
``time_us``, zero at the firing signal (negative times are pre-trigger), strictly increasing. Gauge files
have one column per gauge, ``NAME_Pa``, ``NAME_kPa``, ``NAME_MPa``, ``NAME_bar`` or ``NAME_psi``; track
files two per marker, ``NAME_x_mm`` and ``NAME_z_mm`` (or ``_m``, or ``_px`` with the marker's
``px_per_mm``): the marker's position in the record axes (x along the blast away from the charge, z up,
origin at the centre of the specimen's footprint at rest), not its displacement.

Every fault is one :class:`~blastscale._validate.BlastscaleInputError` line naming the file, the column
and the row (row 1 is the header). The psi factor is the exact NIST one (NIST SP 811, 2008, App. B.8).
"""

from __future__ import annotations

import csv
import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .._validate import BlastscaleInputError

__all__ = [
    "LENGTH_UNITS",
    "PRESSURE_UNITS",
    "TIME_UNITS",
    "GaugeRecord",
    "TrackRecord",
    "read_gauges",
    "read_tracks",
    "record_fault",
]

#: Time column -> factor to seconds.
TIME_UNITS = {"time_s": 1.0, "time_ms": 1e-3, "time_us": 1e-6}
#: Pressure suffix -> factor to Pa (psi: 6894.757293168 Pa, NIST SP 811 App. B.8).
PRESSURE_UNITS = {"Pa": 1.0, "kPa": 1e3, "MPa": 1e6, "bar": 1e5, "psi": 6894.757293168361}
#: Position suffix -> factor to m (``px`` is converted by the marker's ``px_per_mm``).
LENGTH_UNITS = {"m": 1.0, "mm": 1e-3, "px": None}


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


def _read_table(path) -> tuple[list[str], list[list[str]]]:
    p = Path(path)
    try:
        text = p.read_text(encoding="utf-8-sig")
    except OSError as exc:
        raise record_fault(p, "", 1, f"cannot be read ({exc.strerror or exc})") from None
    rows = [r for r in csv.reader(text.splitlines()) if any(c.strip() for c in r)]
    if not rows:
        raise record_fault(p, "", 1, "the file is empty: a header and samples expected")
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


def read_gauges(path, names: Mapping | None = None) -> GaugeRecord:
    """Read a gauge file (format: module docstring) into Pa and s.

    Parameters
    ----------
    path : str or Path
    names : collection of str, optional
        The gauges the scenario describes (``[fired.gauge.NAME]``); a column of another name is an error.

    Raises
    ------
    BlastscaleInputError
        One line naming the file, the column and the row: an empty file, no time column, an unknown unit
        suffix, a gauge without a table, a value that is not a finite number, times that do not increase.
    """
    header, rows = _read_table(path)
    parsed = []
    for j, col in enumerate(header[1:], start=1):
        name, unit = _suffix(path, col, j, PRESSURE_UNITS, "gauge")
        _known(path, col, name, names, "fired.gauge")
        parsed.append((name, unit))
    data = _numbers(path, header, rows)
    pressure = {n: data[:, j] * PRESSURE_UNITS[u] for j, (n, u) in enumerate(parsed, start=1)}
    cols = {n: header[j] for j, (n, _) in enumerate(parsed, start=1)}
    return GaugeRecord(str(path), data[:, 0], pressure, cols)


def read_tracks(path, names: Mapping | None = None, px_per_mm: Mapping[str, float] | None = None) -> TrackRecord:
    """Read a track file (format: module docstring) into m and s.

    Parameters
    ----------
    path : str or Path
    names : collection of str, optional
        The markers the scenario describes (``[fired.marker.NAME]``).
    px_per_mm : mapping of str -> float, optional
        Marker name -> image scale [px/mm], needed for ``_px`` columns.

    Raises
    ------
    BlastscaleInputError
        As :func:`read_gauges`, and for a column that is not ``NAME_x_UNIT`` / ``NAME_z_UNIT``, a ``_px``
        column without ``px_per_mm``, or a marker without its ``x`` column.
    """
    header, rows = _read_table(path)
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
