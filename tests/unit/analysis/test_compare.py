"""The comparison contract (analysis.compare) on synthetic responses with closed-form answers."""

from __future__ import annotations

import math

import numpy as np
import pytest
import xarray as xr

from blastscale._validate import BlastscaleInputError
from blastscale.analysis.compare import align, compare_responses, first_peak, upscale_dataset
from blastscale.similitude import scaling_factors

BODIES = ["D-1", "D-2", "D-3"]
POINTS = ["P-1", "P-2", "P-3"]
COMP = ["x", "y", "z"]


def synthetic_response(t, amplitude=1.0, collapsed=False, period=2.0):
    """A response that follows the contract (docs/contracts.md, section 3): drum k moves as
    k * amplitude * sin(pi t / period) along x (first peak at t = period / 2, value k * amplitude)."""
    k = np.arange(1, len(BODIES) + 1)
    w = math.pi / period
    x = amplitude * np.sin(w * t)[:, None] * k[None, :]
    v = amplitude * w * np.cos(w * t)[:, None] * k[None, :]
    vec = lambda a: np.stack([a, 0.1 * a, 0.0 * a], axis=-1)  # noqa: E731
    n = t.size
    data = {
        "com_displacement": (("time", "body", "component"), vec(x), {"units": "m", "dimension": "length"}),
        "com_velocity": (("time", "body", "component"), vec(v), {"units": "m/s", "dimension": "velocity"}),
        "angular_velocity": (
            ("time", "body", "component"),
            vec(v)[..., ::-1],
            {"units": "rad/s", "dimension": "angular_velocity"},
        ),
        "tilt": (("time", "body"), 0.01 * x, {"units": "rad", "dimension": "angle"}),
        "point_displacement": (("time", "point", "component"), vec(x), {"units": "m", "dimension": "length"}),
        "point_velocity": (("time", "point", "component"), vec(v), {"units": "m/s", "dimension": "velocity"}),
        "n_contacts": (("time",), np.full(n, 8), {"units": "1", "dimension": "count"}),
        "delivered_impulse": (
            ("body", "component"),
            np.ones((3, 3)) * [1.0, 0.0, 0.0],
            {"units": "N s", "dimension": "momentum"},
        ),
    }
    return xr.Dataset(
        data,
        coords={"time": ("time", t, {"units": "s"}), "body": BODIES, "point": POINTS, "component": COMP},
        attrs={"collapsed": int(collapsed), "first_arrival_time_s": 0.02},
    )


def model_of(proto_t, factors, **kw):
    """The exact model of the synthetic prototype: every variable multiplied by its factor,
    times by the time factor."""
    p = synthetic_response(proto_t, **kw)
    m = p.copy(deep=True)
    for name, var in p.data_vars.items():
        f = 1.0 if var.attrs["dimension"] in ("count", "dimensionless") else getattr(factors, var.attrs["dimension"])
        m[name] = (var.dims, var.values * f, var.attrs)
    m = m.assign_coords(time=("time", proto_t * factors.time, {"units": "s"}))
    m.attrs["first_arrival_time_s"] = 0.02 * factors.time
    return p, m


@pytest.mark.parametrize("scale, gamma, sigma", [(1 / 100, 1.0, 1.0), (1 / 20, 0.07, 1.0), (1 / 50, 2.0, 30.0)])
def test_exactly_scaled_model_compares_to_zero_difference(scale, gamma, sigma):
    """A model that is the prototype times the factors (paper Tables 1-2) up-scales back to it:
    zero difference and first-peak ratio 1 up to round-off (1e-12 relative: one division by the
    factor and one linear interpolation at coinciding times)."""
    f = scaling_factors(scale, gamma, sigma)
    t = np.linspace(0.0, 4.0, 801)
    p, m = model_of(t, f)
    up = upscale_dataset(m, f)
    assert up["time"].values == pytest.approx(t, rel=1e-13, abs=1e-15)
    assert up.attrs["first_arrival_time_s"] == pytest.approx(0.02, rel=1e-13)
    assert float(up["delivered_impulse"].sel(body="D-1", component="x")) == pytest.approx(1.0, rel=1e-12)
    c = compare_responses(p, up)
    assert c["outcomes_agree"] is True and c["n_times"] == t.size
    for name, per in c["variables"].items():
        for label, r in per.items():
            assert r["max_abs_diff_rel_peak"] <= 1e-12, (name, label)
            assert r["first_peak_ratio"] == pytest.approx(1.0, abs=1e-12), (name, label)
    assert "n_contacts" not in c["variables"] and "delivered_impulse" not in c["variables"]
    assert c["variables"]["angular_velocity"]["D-1"]["component"] == "y"


def test_known_offset_gives_the_known_difference_and_peaks():
    """Model = prototype + 0.05 m on the x displacement of P-2 (its amplitude 2 m): the difference
    is 0.05 m exactly (2.5 % of the peak), the other points are untouched, the first peaks are at
    t = 1 s (sin(pi t / 2)), value k m, and the model's first peak is 2.05 m."""
    f = scaling_factors(1 / 100)
    t = np.linspace(0.0, 4.0, 401)
    p, m = model_of(t, f)
    off = m["point_displacement"].values.copy()
    off[:, 1, 0] += 0.05 * f.length
    m["point_displacement"] = (m["point_displacement"].dims, off, m["point_displacement"].attrs)
    c = compare_responses(p, upscale_dataset(m, f), variables=["point_displacement"])
    r = c["variables"]["point_displacement"]
    assert r["P-2"]["max_abs_diff"] == pytest.approx(0.05, rel=1e-10)
    assert r["P-2"]["max_abs_diff_rel_peak"] == pytest.approx(0.025, rel=1e-10)
    assert r["P-2"]["first_peak_prototype"] == pytest.approx(2.0, rel=1e-12)
    assert r["P-2"]["first_peak_time_prototype_s"] == pytest.approx(1.0, abs=1e-12)
    assert r["P-2"]["first_peak_model"] == pytest.approx(2.05, rel=1e-10)
    assert r["P-2"]["first_peak_ratio"] == pytest.approx(2.05 / 2.0, rel=1e-10)
    assert r["P-1"]["max_abs_diff"] <= 1e-12 and r["P-3"]["max_abs_diff"] <= 1e-12


def test_interpolation_onto_the_prototype_grid_and_overlap():
    """The model recorded on a coarser, shifted grid: linear interpolation of a linear history
    is exact, and only the prototype's times inside the model's span are compared."""
    f = scaling_factors(1 / 4)
    tp = np.linspace(0.0, 2.0, 201)
    tm = np.linspace(0.0, 1.5, 7) * f.time  # model times, covering prototype [0, 1.5] s
    ds = lambda t, a: xr.Dataset(  # noqa: E731
        {"uplift": (("time", "body"), a[:, None], {"units": "m", "dimension": "length"})},
        coords={"time": t, "body": ["block"]},
    )
    p = ds(tp, 3.0 * tp)
    m = ds(tm, 3.0 * tm / f.time * f.length)
    pa, ma = align(p, upscale_dataset(m, f))
    assert pa["time"].values[-1] == pytest.approx(1.5, abs=1e-12) and pa.sizes["time"] == 151
    assert np.max(np.abs(ma["uplift"].values - pa["uplift"].values)) <= 1e-12
    c = compare_responses(p, upscale_dataset(m, f))
    assert c["time_compared_s"] == pytest.approx([0.0, 1.5], abs=1e-12)
    # a history growing to its end has its first peak at its largest value
    assert c["variables"]["uplift"]["block"]["first_peak_prototype"] == pytest.approx(4.5, rel=1e-12)
    assert c["outcomes_agree"] is None


def test_outcome_disagreement():
    f = scaling_factors(1 / 10)
    t = np.linspace(0.0, 2.0, 51)
    p, m = model_of(t, f)
    m.attrs["collapsed"] = 1
    c = compare_responses(p, upscale_dataset(m, f))
    assert c["outcome_prototype"] is False and c["outcome_model"] is True and c["outcomes_agree"] is False


def test_first_peak_skips_jitter_and_handles_plateaus():
    t = np.arange(10.0)
    # jitter of 1e-3 (below 10 % of the peak), then a plateau at 5 (peak), then down
    q = np.array([0.0, 1e-3, 0.0, 1.0, 5.0, 5.0, 3.0, 6.0, 2.0, 0.0])
    assert first_peak(t, q) == (4.0, 5.0)
    assert first_peak(t, -q) == (4.0, -5.0)
    assert first_peak(t, q, fraction=0.0) == (1.0, 1e-3)
    tz, qz = first_peak(t, np.zeros(10))
    assert math.isnan(tz) and qz == 0.0


def test_contract_errors_name_the_problem():
    f = scaling_factors(1 / 10)
    t = np.linspace(0.0, 1.0, 11)
    bad = xr.Dataset({"q": (("time",), t)}, coords={"time": t})
    with pytest.raises(BlastscaleInputError, match="'q' has no 'dimension'"):
        upscale_dataset(bad, f)
    bad["q"].attrs["dimension"] = "colour"
    with pytest.raises(BlastscaleInputError, match="colour"):
        upscale_dataset(bad, f)
    p, m = model_of(t, f)
    with pytest.raises(BlastscaleInputError, match="variable = 'spin'"):
        compare_responses(p, upscale_dataset(m, f), variables=["spin"])
    with pytest.raises(BlastscaleInputError, match="component"):
        compare_responses(p, upscale_dataset(m, f), components="w")
    late = m.assign_coords(time=m["time"].values + 10.0)
    with pytest.raises(BlastscaleInputError, match="overlap"):
        compare_responses(p, upscale_dataset(late, f))


def test_time_window_restricts_the_comparison():
    """An offset of 0.05 m on P-2 only after t = 3 s: compared over [0, 2.5] s it is invisible,
    over [3, 4] s it is 0.05 m; the first peak over [2, 4] s is the trough at t = 3 s (-2 m)."""
    f = scaling_factors(1 / 100)
    t = np.linspace(0.0, 4.0, 401)
    p, m = model_of(t, f)
    off = m["point_displacement"].values.copy()
    off[t >= 3.0, 1, 0] += 0.05 * f.length
    m["point_displacement"] = (m["point_displacement"].dims, off, m["point_displacement"].attrs)
    up = upscale_dataset(m, f)
    early = compare_responses(p, up, variables=["point_displacement"], end=2.5)
    late = compare_responses(p, up, variables=["point_displacement"], start=3.0)
    assert early["variables"]["point_displacement"]["P-2"]["max_abs_diff"] <= 1e-12
    assert late["variables"]["point_displacement"]["P-2"]["max_abs_diff"] == pytest.approx(0.05, rel=1e-10)
    assert early["time_compared_s"] == pytest.approx([0.0, 2.5], abs=1e-12)
    mid = compare_responses(p, up, variables=["point_displacement"], start=2.0)
    assert mid["variables"]["point_displacement"]["P-2"]["first_peak_prototype"] == pytest.approx(-2.0, rel=1e-12)
    with pytest.raises(BlastscaleInputError, match="time window"):
        compare_responses(p, up, start=5.0)
