"""Record files as lab software writes them (issue #40 item 1): the encodings, the spreadsheet, the microsecond
suffixes; and the size bound's key (item 2)."""

from __future__ import annotations

import codecs
import sys
from importlib.resources import files
from pathlib import Path

import numpy as np
import pytest

from blastscale._extras import MissingExtraError
from blastscale._validate import BlastscaleInputError
from blastscale.fired import read_gauges, read_tracks
from blastscale.scenario import load_scenario

EXAMPLE = Path(str(files("blastscale.fired") / "examples"))

#: A gauge file's text as a data-acquisition program writes it: comments with a degree sign and a micro sign,
#: the time in microseconds (the micro sign); cp1252's has a dash, a character Latin-1 does not have.
GAUGE_HEAD = "# gauge g1, 20 \u00b0C, sampled every 0.5 \u00b5s\n"
CP1252_HEAD = "# gauge g1 \u2013 20 \u00b0C \u2013 0.5 \u00b5s\n"


def _gauge_text(head: str = GAUGE_HEAD) -> str:
    body = (EXAMPLE / "gauges.csv").read_text().replace("time_us", "time_\u00b5s", 1)
    return head + body


def _track_text() -> str:
    return "# video 2000 fps, \u00b0 calibrated\n" + (EXAMPLE / "tracks.csv").read_text()


def _encoded(text: str, encoding: str) -> bytes:
    """``text`` in ``encoding``; ``utf-16-le+bom`` and ``utf-16-be+bom``: with their byte-order mark."""
    if encoding == "utf-16-le+bom":
        return codecs.BOM_UTF16_LE + text.encode("utf-16-le")
    if encoding == "utf-16-be+bom":
        return codecs.BOM_UTF16_BE + text.encode("utf-16-be")
    return text.encode(encoding)


ENCODINGS = ["utf-8-sig", "utf-16-le+bom", "utf-16-be+bom", "utf-16", "latin-1", "cp1252"]


@pytest.mark.parametrize("encoding", ENCODINGS)
def test_a_gauge_file_in_any_lab_encoding_reads_as_the_utf8_one(tmp_path, encoding):
    ref = tmp_path / "utf8.csv"
    ref.write_bytes(_gauge_text().encode("utf-8"))
    head = CP1252_HEAD if encoding == "cp1252" else GAUGE_HEAD  # a character only cp1252 has
    f = tmp_path / "g.csv"
    f.write_bytes(_encoded(_gauge_text(head), encoding))
    a, b = read_gauges(ref, names={"g1"}), read_gauges(f, names={"g1"})
    assert a.time_s.size == b.time_s.size > 1000
    np.testing.assert_allclose(b.time_s, a.time_s, rtol=1e-12, atol=0)
    np.testing.assert_allclose(b.pressure_Pa["g1"], a.pressure_Pa["g1"], rtol=1e-12, atol=0)
    assert b.columns == {"g1": "g1_kPa"}


@pytest.mark.parametrize("encoding", ENCODINGS)
def test_a_track_file_in_any_lab_encoding_reads_as_the_utf8_one(tmp_path, encoding):
    ref = tmp_path / "utf8.csv"
    ref.write_bytes(_track_text().encode("utf-8"))
    f = tmp_path / "t.csv"
    f.write_bytes(_encoded(_track_text(), encoding))
    a, b = read_tracks(ref, names={"top"}), read_tracks(f, names={"top"})
    assert a.time_s.size == b.time_s.size > 100
    np.testing.assert_allclose(b.time_s, a.time_s, rtol=1e-12, atol=0)
    for axis in ("x", "z"):
        np.testing.assert_allclose(b.position_m["top"][axis], a.position_m["top"][axis], rtol=1e-12, atol=0)


def test_a_spreadsheets_unicode_text_export_reads(tmp_path):
    """Excel's "Unicode text": UTF-16 LE with its byte-order mark, tab-separated."""
    ref = tmp_path / "utf8.csv"
    ref.write_text(_gauge_text(), encoding="utf-8")
    f = tmp_path / "g.txt"
    f.write_bytes(_encoded(_gauge_text().replace(",", "\t"), "utf-16-le+bom"))
    a, b = read_gauges(ref, names={"g1"}), read_gauges(f, names={"g1"})
    np.testing.assert_array_equal(b.time_s, a.time_s)
    np.testing.assert_array_equal(b.pressure_Pa["g1"], a.pressure_Pa["g1"])


@pytest.mark.parametrize("suffix", ["us", "\u00b5s", "\u03bcs"])
def test_microseconds_as_us_or_the_micro_sign(tmp_path, suffix):
    f = tmp_path / "g.csv"
    f.write_text(f"time_{suffix},g1_kPa\n-1,1\n0.5,2\n", encoding="utf-8")
    np.testing.assert_array_equal(read_gauges(f, names={"g1"}).time_s, [-1e-6, 0.5e-6])


def test_binary_is_one_line(tmp_path):
    f = tmp_path / "g.csv"
    f.write_bytes(bytes(range(256)) * 8)
    with pytest.raises(BlastscaleInputError, match=r"not text in UTF-8, UTF-16") as e:
        read_gauges(f, names={"g1"})
    assert "\n" not in str(e.value)


def test_an_old_excel_workbook_is_refused_naming_the_format(tmp_path):
    f = tmp_path / "g.csv"
    f.write_bytes(b"\xd0\xcf\x11\xe0\xa1\xb1\x1a\xe1" + b"\x00" * 512)
    with pytest.raises(BlastscaleInputError, match=r"is an Excel 97-2003 \.xls workbook: save it as \.xlsx or CSV"):
        read_gauges(f, names={"g1"})


def _workbook(path: Path, text: str) -> None:
    """``text`` (a CSV's) as the first sheet of a workbook: the header as text, the samples as numbers."""
    openpyxl = pytest.importorskip("openpyxl")
    book = openpyxl.Workbook()
    lines = [ln.split(",") for ln in text.splitlines() if not ln.startswith("#")]
    book.active.append(lines[0])
    for cells in lines[1:]:
        book.active.append([float(c) for c in cells])
    book.save(path)


@pytest.mark.parametrize("name", ["g.xlsx", "g.csv"])  # an .xlsx given as a CSV too
def test_a_workbook_reads_as_the_csv(tmp_path, name):
    ref = tmp_path / "utf8.csv"
    ref.write_text(_gauge_text(), encoding="utf-8")
    f = tmp_path / name
    _workbook(f, _gauge_text())
    a, b = read_gauges(ref, names={"g1"}), read_gauges(f, names={"g1"})
    np.testing.assert_array_equal(b.time_s, a.time_s)
    np.testing.assert_array_equal(b.pressure_Pa["g1"], a.pressure_Pa["g1"])


def test_a_workbook_without_openpyxl_names_the_extra(tmp_path, monkeypatch):
    f = tmp_path / "g.xlsx"
    f.write_bytes(b"PK\x03\x04" + b"\x00" * 64)
    monkeypatch.setitem(sys.modules, "openpyxl", None)
    with pytest.raises(MissingExtraError) as e:
        read_gauges(f, names={"g1"})
    assert e.value.extra == "xlsx" and "pip install 'blastscale[xlsx]'" in str(e.value)


def test_a_damaged_workbook_is_one_line(tmp_path):
    pytest.importorskip("openpyxl")
    f = tmp_path / "g.xlsx"
    f.write_bytes(b"PK\x03\x04" + b"\x00" * 64)
    with pytest.raises(BlastscaleInputError, match=r"is not a readable \.xlsx workbook") as e:
        read_gauges(f, names={"g1"})
    assert "\n" not in str(e.value)


def test_a_file_above_the_bound_names_the_key_and_its_range(tmp_path):
    f = tmp_path / "g.csv"
    f.write_text(_gauge_text(), encoding="utf-8")
    with pytest.raises(BlastscaleInputError) as e:
        read_gauges(f, names={"g1"}, max_mb=0.01)
    msg = str(e.value)
    assert "MB, above the 0.01 MB a record is read to" in msg
    assert "[fired] max_record_mb (now 0.01, valid range (0, 10000] MB)" in msg
    assert read_gauges(f, names={"g1"}, max_mb=1.0).time_s.size > 1000  # raised: read


@pytest.mark.parametrize("value, shown", [("0", "0"), ("-1.0", "-1"), ("20000", "20000")])
def test_the_bound_key_names_its_value_and_range(tmp_path, value, shown):
    text = (EXAMPLE / "shot.toml").read_text().replace("[fired]\n", f"[fired]\nmax_record_mb = {value}\n", 1)
    f = tmp_path / "shot.toml"
    f.write_text(text)
    with pytest.raises(BlastscaleInputError) as e:
        load_scenario(f)
    msg = str(e.value)
    assert "fired.max_record_mb" in msg and shown in msg and "(0, 10000]" in msg, msg
