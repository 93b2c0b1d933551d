"""Record files: units into SI, and every bad record one line naming the file, the column and the row."""

from __future__ import annotations

import numpy as np
import pytest

from blastscale._validate import BlastscaleInputError
from blastscale.fired import fit_gauge, read_gauges, read_tracks


def _write(tmp_path, text, name="rec.csv"):
    p = tmp_path / name
    p.write_text(text)
    return p


def test_units_are_converted(tmp_path):
    p = _write(tmp_path, "time_ms,a_kPa,b_psi,c_bar,d_MPa,e_Pa\n-0.1,1,1,1,1,1\n0.0,2,2,2,2,2\n")
    r = read_gauges(p, names={"a", "b", "c", "d", "e"})
    np.testing.assert_allclose(r.time_s, [-1e-4, 0.0])
    assert r.pressure_Pa["a"][1] == 2000.0
    assert r.pressure_Pa["b"][0] == pytest.approx(6894.757293168361, rel=1e-15)  # NIST SP 811
    assert r.pressure_Pa["c"][0] == 1e5 and r.pressure_Pa["d"][0] == 1e6 and r.pressure_Pa["e"][0] == 1.0


def test_tracks_in_mm_m_and_px(tmp_path):
    p = _write(tmp_path, "time_us,top_x_mm,top_z_mm,foot_x_px\n0,10,500,40\n500,11,500,44\n")
    r = read_tracks(p, names={"top", "foot"}, px_per_mm={"foot": 4.0})
    np.testing.assert_allclose(r.time_s, [0.0, 5e-4])
    np.testing.assert_allclose(r.position_m["top"]["x"], [0.010, 0.011])
    np.testing.assert_allclose(r.position_m["foot"]["x"], [0.010, 0.011])


BAD_GAUGES = [
    ("", "rec.csv: no column, row 1: the file is empty"),
    ("t,a_kPa\n0,1\n", "rec.csv: column 't', row 1: the first column must be the time"),
    ("time_s,a_atm\n0,1\n", "rec.csv: column 'a_atm', row 1: unknown unit suffix '_atm'"),
    ("time_s,zz_kPa\n0,1\n", "rec.csv: column 'zz_kPa', row 1: gauge 'zz' has no [fired.gauge.zz] table"),
    ("time_s,a_kPa\n0,1\n1,nan\n", "rec.csv: column 'a_kPa', row 3: value 'nan' is not a finite number"),
    ("time_s,a_kPa\n0,1\n1,x\n", "rec.csv: column 'a_kPa', row 3: value 'x' is not a finite number"),
    ("time_s,a_kPa\n0,1\n0,2\n", "rec.csv: column 'time_s', row 3: time 0 is not above the previous 0"),
    ("time_s,a_kPa\n", "rec.csv: column 'time_s', row 2: no samples under the header"),
    ("time_s,a_kPa\n0,1\n1\n", "rec.csv: column 'a_kPa', row 3: 1 values, the header has 2 columns"),
]


BAD_TRACKS = [
    ("time_s,top_y_mm\n0,1\n", "rec.csv: column 'top_y_mm', row 1: a track column is NAME_x_UNIT"),
    ("time_s,top_x_px\n0,1\n", "rec.csv: column 'top_x_px', row 1: a _px column needs px_per_mm"),
    ("time_s,top_z_mm\n0,1\n", "rec.csv: column 'top_z_mm', row 1: marker 'top' has no x column"),
    ("time_s,top_x_in\n0,1\n", "rec.csv: column 'top_x_in', row 1: unknown unit suffix '_in'"),
    ("time_s,base_x_mm\n0,1\n", "rec.csv: column 'base_x_mm', row 1: marker 'base' has no [fired.marker.base]"),
]


@pytest.mark.parametrize(
    "read,names,text,message",
    [(read_gauges, {"a"}, *b) for b in BAD_GAUGES] + [(read_tracks, {"top"}, *b) for b in BAD_TRACKS],
)
def test_bad_records_are_one_line(tmp_path, read, names, text, message):
    with pytest.raises(BlastscaleInputError) as e:
        read(_write(tmp_path, text), names=names)
    assert str(e.value).startswith(message)
    assert "\n" not in str(e.value)


def test_too_few_samples_over_the_pulse_names_the_rows():
    """A 50 kHz record of a 0.5 ms pulse has ~25 samples over it ... at 20 kHz only ~10."""
    t = np.arange(-1e-3, 3e-3, 1 / 20e3)
    p = np.where(t > 1e-3, 6e4 * (1 - (t - 1e-3) / 5e-4) * np.exp(-(t - 1e-3) / 5e-4), 0.0)
    p = p + np.random.default_rng(0).normal(0, 100, t.size)
    with pytest.raises(
        BlastscaleInputError,
        match=r"g\.csv: column 'g1_kPa', row \d+-\d+: \d+ samples over the "
        r"pulse: at least 20",
    ):
        fit_gauge(t, p, "g1", source="g.csv", column="g1_kPa")


def test_no_pretrigger_is_one_line():
    t = np.linspace(0, 1e-3, 100)
    with pytest.raises(BlastscaleInputError, match=r"column 'g1', row 2: 0 pre-trigger samples"):
        fit_gauge(t, np.ones_like(t), "g1")
