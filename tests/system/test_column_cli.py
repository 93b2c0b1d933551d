"""CLI `column` (JSON keys, similarity per point, one-line errors with status 2), a short column
run through compare_structure3d, and the column plots."""

from __future__ import annotations

import json
import math

import matplotlib
import numpy as np
import pytest

matplotlib.use("Agg")

from blastscale.cli import main  # noqa: E402

#: a short, small column keeps the CLI tests fast: 3 drums of 1 m (the paper's taper over 3 m)
SHORT = ["--drums", "3", "--height", "3", "--top-width", "1.54", "--duration", "0.25", "--record-every", "8"]
SUMMARY_KEYS = {"collapsed", "max_top_displacement_m", "delivered_impulse_Ns", "points"}


def run(capsys, *argv):
    with pytest.raises(SystemExit) as e:
        main(list(argv))
    return e.value.code, capsys.readouterr()


@pytest.fixture(scope="module")
def short_comparison():
    """The paper's square column, 250 kg at 10 m, and its 1/100 model: the first swing (0.7 s of
    prototype time; the first peak is at ~0.5 s)."""
    from blastscale.analysis.structure3d import compare_structure3d
    from blastscale.analysis.systems import Settings3D, Systems3D
    from blastscale.similitude import design_model
    from blastscale.structures import MultiDrumColumn

    systems = Systems3D.of_design(design_model(250.0, 10.0, 1 / 100), MultiDrumColumn(), duration=0.7)
    return compare_structure3d(systems, Settings3D(record_every=8))


def test_column_json_prototype_model_similarity(capsys, tmp_path):
    png = tmp_path / "col.png"
    code, out = run(
        capsys, "column", *SHORT, "--charge", "250", "--standoff", "10", "--scale", "0.01", "--plot", str(png), "--json"
    )
    assert code in (0, None), out.err
    d = json.loads(out.out)
    assert SUMMARY_KEYS <= d["prototype"].keys() and SUMMARY_KEYS <= d["model"].keys()
    assert set(d["prototype"]["points"]) == {"P-1", "P-2", "P-3"}
    assert "max_displacement_m" in d["prototype"]["points"]["P-1"]
    assert len(d["prototype"]["delivered_impulse_Ns"]) == 3
    s = d["similarity"]
    assert {"top_first_peak_ratio", "max_abs_top_displacement_diff_m", "outcomes_agree", "points"} <= s.keys()
    assert {"first_peak_ratio", "max_abs_displacement_diff_m"} <= s["points"]["P-3"].keys()
    # Method A under the general law: the model's up-scaled blast momentum equals the prototype's
    # (impulse factor gamma lambda^1.5 x area factor lambda^2 = momentum factor): 1e-6 relative
    # (round-off of the design's solved scaled distance, ~1e-13, and of the sums)
    assert d["model"]["delivered_impulse_Ns"][0] == pytest.approx(d["prototype"]["delivered_impulse_Ns"][0], rel=1e-6)
    assert abs(d["prototype"]["delivered_impulse_Ns"][1]) <= 1e-9 * d["prototype"]["delivered_impulse_Ns"][0]
    assert s["outcomes_agree"] is True
    assert png.stat().st_size > 10_000


def test_column_without_scale_is_the_prototype_only(capsys):
    code, out = run(
        capsys,
        "column",
        *SHORT,
        "--section",
        "circular",
        "--sides",
        "16",
        "--charge",
        "200",
        "--standoff",
        "10",
        "--json",
    )
    assert code in (0, None), out.err
    d = json.loads(out.out)
    assert SUMMARY_KEYS <= d["prototype"].keys() and "model" not in d and "similarity" not in d
    assert d["structure"]["section"] == "circular" and d["structure"]["sides"] == 16


def test_column_ensemble_option(capsys):
    code, out = run(
        capsys,
        "column",
        *SHORT,
        "--section",
        "circular",
        "--sides",
        "16",
        "--charge",
        "200",
        "--standoff",
        "10",
        "--scale",
        "0.01",
        "--ensemble",
        "2",
        "--json",
    )
    assert code in (0, None), out.err
    e = json.loads(out.out)["ensemble"]
    assert e["n_members"] == 2 and e["perturbation"] == 1e-6
    assert {
        "first_peak_prototype_mean_m",
        "first_peak_model_spread_m",
        "noise_floor_rel_peak",
        "horizon_prototype_s",
    } <= e["points"]["P-3"].keys()
    assert 0.0 <= e["collapse_probability_prototype"] <= 1.0
    assert e["collapse_probability_prototype_low"] <= e["collapse_probability_prototype"]
    assert e["collapse_probability_prototype"] <= e["collapse_probability_prototype_high"]
    assert e["points"]["P-3"]["first_peak_model_p05_m"] <= e["points"]["P-3"]["first_peak_model_p95_m"]


def test_column_ensemble_of_the_prototype_alone(capsys):
    """Without --scale the ensemble is the prototype's (a prototype-only scenario through the
    Study): its figures, the model's None, no model or similarity block; the table says so."""
    argv = (
        "column",
        *SHORT,
        "--section",
        "circular",
        "--sides",
        "16",
        "--charge",
        "200",
        "--standoff",
        "10",
        "--ensemble",
        "2",
    )
    code, out = run(capsys, *argv, "--json")
    assert code in (0, None), out.err
    d = json.loads(out.out)
    assert "model" not in d and "similarity" not in d and d["inputs"]["scale"] is None
    e = d["ensemble"]
    assert e["n_members"] == 2 and 0.0 <= e["collapse_probability_prototype"] <= 1.0
    assert e["collapse_probability_model"] is None
    top = e["points"]["P-3"]
    assert top["first_peak_prototype_mean_m"] > 0 and top["first_peak_model_mean_m"] is None
    code, out = run(capsys, *argv)
    assert code in (0, None), out.err
    assert "collapse probability, prototype" in out.out and "model mean" not in out.out
    assert "of 2)" in out.out  # the collapse odds in words, k of 2 members with their interval


def test_column_tables(capsys):
    code, out = run(capsys, "column", *SHORT, "--charge", "250", "--standoff", "10", "--scale", "0.01")
    assert code in (0, None), out.err
    assert "first-peak ratio at the top (P-3)" in out.out and "P-1 max displacement" in out.out


@pytest.mark.parametrize(
    "argv, words",
    [
        (["--drums", "0"], ["--drums", "0", "[1, 200]"]),
        (["--base-width", "-1"], ["--base-width", "-1", "(0, 100] m"]),
        (["--base-width", "nan"], ["--base-width", "nan"]),
        (["--top-width", "nan"], ["--top-width", "nan"]),
        (["--top-width", "2.0"], ["top width", "2", "1.65"]),
        (["--section", "hexagonal"], ["section", "hexagonal", "square, circular"]),
        (["--section", "circular", "--sides", "3"], ["--sides = 3", "[8, 256]"]),
        (["--timestep", "0.5"], ["timestep", "0.5", "valid range"]),
        (["--timestep", "-1e-3"], ["--timestep", "-0.001", "(0, 0.1] s"]),
        (["--load", "Z"], ["load", "'Z'", "A"]),
        (["--incidence", "guess"], ["incidence", "guess", "ufc"]),
        (["--density", "0"], ["--density", "0", "(0, 25000] kg/m^3"]),
        (["--scale", "-0.01"], ["scale", "-0.01"]),
        (["--scale", "0.01", "--ensemble", "1"], ["--ensemble", "1", "2 to 64"]),
        (["--ensemble", "-1"], ["--ensemble", "-1", "[0, 64]"]),
    ],
)
def test_column_bad_input_exits_2_with_one_line(capsys, argv, words):
    code, out = run(capsys, "column", "--charge", "250", "--standoff", "10", "--duration", "0.05", *argv)
    assert code == 2
    msg = out.err.strip()
    assert "Traceback" not in msg and len(msg.splitlines()) == 1 and msg.startswith("error:"), msg
    for w in words:
        assert w in msg, (w, msg)


def test_block3d_gains_delivered_impulse_and_load_options(capsys):
    code, out = run(
        capsys,
        "block3d",
        "--width",
        "2",
        "--charge",
        "10",
        "--standoff",
        "5",
        "--model",
        "masi2021",
        "--duration",
        "0.05",
        "--load",
        "A",
        "--json",
    )
    assert code in (0, None), out.err
    d = json.loads(out.out)
    imp = d["prototype"]["delivered_impulse_Ns"]
    assert len(imp) == 3 and imp[0] > 0 and abs(imp[1]) <= 1e-9 * imp[0]
    code, out = run(capsys, "block3d", "--width", "2", "--charge", "10", "--standoff", "5", "--load", "Q")
    assert code == 2 and "load = 'Q'" in out.err


def test_short_column_comparison_through_the_contract(short_comparison):
    """The paper's square column, 250 kg at 10 m, lambda = 1/100, first swing. The general law
    matches the impulse only (paper Eq. 8): the model's pulse, up-scaled, is shorter than the
    prototype's, so the ~13 ms during which friction and the joints act under load differ; the
    up-scaled first peak at the top is 0.43 % above the prototype's (measured; docs/design.md: within
    0.4 %), lower drums more (P-1 +2.6 %: the base drum's motion is small and sliding-dominated).
    Asserted: top first peak within 1 %, every point's first peak within 5 %, every point's
    x displacement within 5 % of its peak over the swing, outcomes agree."""
    c = short_comparison
    s = c.similarity()
    assert s["outcomes_agree"] is True and s["top_point"] == "P-10"
    assert s["top_first_peak_ratio"] == pytest.approx(1.0, abs=1e-2)
    for name, p in s["points"].items():
        assert p["first_peak_ratio"] == pytest.approx(1.0, abs=5e-2), name
        assert p["max_abs_displacement_diff_rel_peak"] <= 5e-2, name
        assert 0.45 <= p["first_peak_time_s"] <= 0.56, name  # the first swing peaks at ~0.5 s
    # the up-scaled model's time grid ends at the prototype's; velocities compared after the load
    assert s["time_compared_s"][1] == pytest.approx(0.7, rel=1e-6)
    assert 0.005 < s["load_end_s"] < 0.05
    ds = c.to_dataset()
    assert list(ds["system"].values) == ["prototype", "model"]
    assert ds["point_displacement"].dims[0] == "system" and "upscaled" not in ds.attrs


def test_comparison_dataset_round_trips_through_netcdf(short_comparison, tmp_path):
    import xarray as xr

    ds = short_comparison.to_dataset()
    path = tmp_path / "cmp.nc"
    ds.to_netcdf(path)
    with xr.open_dataset(path) as back:
        assert back["point_displacement"].attrs["dimension"] == "length"
        assert back.attrs["top_first_peak_ratio"] == pytest.approx(ds.attrs["top_first_peak_ratio"], rel=0)
        assert back.attrs["factor_length"] == pytest.approx(0.01, rel=1e-12)
        np.testing.assert_array_equal(back["point_displacement"].values, ds["point_displacement"].values)


def test_upscale_summary_by_unit_suffix():
    from blastscale.analysis.upscale import upscale_summary
    from blastscale.similitude import scaling_factors

    f = scaling_factors(1 / 100)
    s = {
        "collapsed": True,
        "max_top_displacement_m": 0.01,
        "delivered_impulse_Ns": [2.0, 0.0, 0.0],
        "points": {"P-1": {"max_displacement_m": 0.001, "max_velocity_m_s": 0.1, "n_impacts": 3}},
        "max_rotation_rad": 0.1,
        "collapse_time_s": 0.2,
    }
    u = upscale_summary(s, f)
    assert u["collapsed"] is True and u["max_rotation_rad"] == 0.1
    assert u["max_top_displacement_m"] == pytest.approx(1.0, rel=1e-12)
    assert u["delivered_impulse_Ns"][0] == pytest.approx(2.0 / 1e-7, rel=1e-12)  # momentum lambda^3.5
    assert u["points"]["P-1"]["max_velocity_m_s"] == pytest.approx(1.0, rel=1e-12)  # velocity sqrt(lambda)
    assert u["points"]["P-1"]["n_impacts"] == 3
    assert u["collapse_time_s"] == pytest.approx(2.0, rel=1e-12)  # time sqrt(lambda)


def test_column_plots_take_ax_and_return_it(short_comparison):
    import matplotlib.pyplot as plt

    from blastscale.plots.column import plot_column_snapshots, plot_point_histories
    from blastscale.plots.sim3d import drum_outline

    c = short_comparison
    fig, axs = plt.subplots(1, 3)
    assert plot_point_histories(c.prototype_dataset, c.upscaled_dataset, ax=axs[0]) is axs[0]
    assert len(axs[0].get_lines()) == 22  # 10 points x (prototype, model) + 2 style keys
    assert plot_point_histories(c.prototype_dataset, None, "point_velocity", points=["P-3"], ax=axs[1]) is axs[1]
    assert len(axs[1].get_lines()) == 1
    assert plot_column_snapshots(c.structure, c.prototype_dataset, times=[0.0, 0.5], ax=axs[2]) is axs[2]
    assert len(axs[2].get_lines()) == 2 * 10 + 1  # 2 times x 10 drums + the ground line
    plt.close(fig)
    # a drum rotated by theta about y: its top centre moves to (zt sin th, zt cos th)
    xy = drum_outline(0.0, 0.0, 0.2, 0.8, 0.7, -0.5, 0.5)
    top = 0.5 * (xy[2] + xy[3])
    assert top == pytest.approx([0.5 * math.sin(0.2), 0.5 * math.cos(0.2)], abs=1e-12)
    assert np.linalg.norm(xy[1] - xy[0]) == pytest.approx(1.6, rel=1e-12)


def test_column_plots_reject_unknown_names(short_comparison):
    from blastscale._validate import BlastscaleInputError
    from blastscale.plots.column import plot_column_snapshots, plot_point_histories

    c = short_comparison
    with pytest.raises(BlastscaleInputError, match="quantity"):
        plot_point_histories(c.prototype_dataset, quantity="spin")
    with pytest.raises(BlastscaleInputError, match="P-99"):
        plot_point_histories(c.prototype_dataset, points=["P-99"])
    with pytest.raises(BlastscaleInputError, match="n = 0"):
        plot_column_snapshots(c.structure, c.prototype_dataset, n=0)


def test_run_system_passes_extrapolate_to_the_load(patch_everywhere):
    """compare_structure3d / run_system hand ``extrapolate`` to make_load (E10's scenarios
    with blast.extrapolate = true); the load built is then used as is."""
    import blastscale.sim3d.load_methods as loads
    from blastscale.analysis.systems import Settings3D, Systems3D, run_system
    from blastscale.similitude import design_model
    from blastscale.structures import MultiDrumColumn

    seen = []
    real = loads.make_load

    def spy(*args, **kw):
        seen.append(kw.get("extrapolate"))
        return real(*args, **kw)

    patch_everywhere(loads, "make_load", spy)
    col = MultiDrumColumn(drums=2, height=2.0, top_width=1.6)
    for flag in (False, True):
        specimen = Systems3D.of_design(design_model(250.0, 10.0, 1 / 100), col, duration=0.01).specimen
        _, r, load_s, _ = run_system(specimen, Settings3D(record_every=8, extrapolate=flag))
        assert r.summary()["collapsed"] is False and 0 < load_s < 0.01
    assert seen == [False, True]


def test_collapsing_column_is_compared_up_to_the_earlier_collapse():
    """A slender 3-drum column (3 m, 0.5 -> 0.45 m) under 100 kg at 5 m topples in both systems
    within 0.17 s. The comparison stops at the earlier collapse (the fall amplifies any time
    shift, and a tumbling stack's impacts are not what the scaling laws describe): compared_to_collapse_s is
    that time, the per-point figures up to it are present, and the x displacement grows
    monotonically to it, so the "first peak" is the value there. Measured: collapse times
    0.1621 / 0.1632 s, top first-peak ratio 1.0018, difference up to collapse 0.7 % of the peak; since the step
    after the load doubled (issue #28) 0.1577 / 0.1643 s, 1.0049, 0.66 % (the switch to the longer step falls at a
    different moment of each system's fall, and a fall amplifies it); asserted: 0.01 s, 1 % and 2 %."""
    from blastscale.analysis.structure3d import compare_structure3d
    from blastscale.analysis.systems import Settings3D, Systems3D
    from blastscale.similitude import design_model
    from blastscale.structures import MultiDrumColumn

    col = MultiDrumColumn(drums=3, height=3.0, base_width=0.5, top_width=0.45)
    c = compare_structure3d(
        Systems3D.of_design(design_model(100.0, 5.0, 1 / 100), col, duration=0.6), Settings3D(record_every=8)
    )
    s = c.similarity()
    ps = c.prototype.summary()
    assert ps["collapsed"] and s["outcomes_agree"] is True
    assert s["compared_to_collapse_s"] == pytest.approx(
        min(ps["collapse_time_s"], ps["collapse_time_s"] + s["collapse_time_diff_s"]), rel=1e-12
    )
    assert abs(s["collapse_time_diff_s"]) <= 1e-2
    top = s["points"]["P-3"]
    assert top["first_peak_time_s"] == pytest.approx(s["compared_to_collapse_s"], abs=2e-3)
    assert top["first_peak_ratio"] == pytest.approx(1.0, abs=1e-2)
    assert top["max_abs_displacement_diff_to_collapse_rel_peak"] <= 2e-2
