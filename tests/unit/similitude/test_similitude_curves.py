"""Scaling-factor curves (paper Figs. 5 and 8): against design_model, the text's figures,
Hopkinson-Cranz identities, monotonicity and the valid mask."""

import math

import numpy as np
import pytest

from blastscale._validate import BlastscaleInputError, OutOfRangeError
from blastscale.blast.parameters import valid_scaled_distance_range
from blastscale.similitude import admissible_scales, design_model
from blastscale.similitude.curves import scaling_curves

MODELS = ("masi2021", "kingery-bulmash")
W, R = 50.0, 2.0  # the paper's case (a): 50 kg at 2 m, Z = 0.5429 m/kg^(1/3)


@pytest.mark.parametrize("model", MODELS)
@pytest.mark.parametrize("lam, gam", [(1 / 20, 1.0), (1 / 200, 1.0), (1 / 200, 0.07), (1 / 20, 0.05), (0.3, 2.0)])
def test_points_equal_design_model(model, lam, gam):
    # The same root and the same blast evaluation: relative 1e-12 (round-off of one division).
    c = scaling_curves(W, R, [lam], [gam], blast_model=model)
    d = design_model(W, R, lam, gam, blast_model=model)
    assert c.valid[0]
    for got, want in (
        (c.scaled_distance_factor[0], d.scaled_distance_factor),
        (c.model_scaled_distance[0], d.specimen.scaled_distance),
        (c.charge_ratio[0], d.factors.charge),
        (c.pressure_ratio[0], d.pressure_ratio),
        (c.impulse_ratio[0], d.impulse_ratio),
        (c.duration_ratio[0], d.duration_ratio),
    ):
        assert got == pytest.approx(want, rel=1e-12)


def test_sweep_equals_design_model_point_by_point():
    lam = np.logspace(-3, 0, 13)
    c = scaling_curves(W, R, lam, blast_model="masi2021")
    assert c.valid.all()
    for k, x in enumerate(lam):
        d = design_model(W, R, x, blast_model="masi2021")
        assert c.pressure_ratio[k] == pytest.approx(d.pressure_ratio, rel=1e-12)
        assert c.duration_ratio[k] == pytest.approx(d.duration_ratio, rel=1e-12)
        assert c.scaled_distance_factor[k] == pytest.approx(d.scaled_distance_factor, rel=1e-12)


def test_text_pressure_ratio_gamma_1_and_005():
    # Paper, Sec. "Different material modeling": lambda = 1/200 -> 5.8 % (gamma = 1) and 0.18 % (gamma = 0.05);
    # printed to 2 significant digits. Ours: 5.846 % and 0.1890 % -> tolerances +-0.05 % and the band
    # [0.18, 0.19] % (the paper truncates, docs/paper_slips.md #4).
    c = scaling_curves(W, R, 1 / 200, [1.0, 0.05], blast_model="masi2021")
    assert 100 * c.pressure_ratio[0] == pytest.approx(5.8, abs=0.05)
    assert 0.18 <= 100 * c.pressure_ratio[1] <= 0.19


def test_impulse_ratio_is_the_required_factor():
    # The general law matches the impulse exactly: gamma sqrt(varsigma lambda^3), rel 1e-10 (root tolerance 1e-15
    # in ln lambda_Z times the fits' slope, plus round-off).
    lam = np.array([1e-3, 1 / 200, 1 / 20, 0.5, 1.0])
    gam = np.array([1.0, 0.07, 0.5, 1.0, 1.0])
    c = scaling_curves(W, R, lam, gam, gravity_ratio=1.0, blast_model="kingery-bulmash")
    np.testing.assert_allclose(c.impulse_ratio, gam * np.sqrt(lam**3), rtol=1e-10)


@pytest.mark.parametrize("model", MODELS)
def test_hopkinson_cranz_identities(model):
    lam = np.logspace(-3, 0, 7)
    c = scaling_curves(W, R, lam, 0.3, blast_model=model)
    np.testing.assert_array_equal(c.hc_scaled_distance_factor, 1.0)
    np.testing.assert_array_equal(c.hc_pressure_ratio, 1.0)
    np.testing.assert_array_equal(c.hc_impulse_ratio, lam)
    np.testing.assert_array_equal(c.hc_duration_ratio, lam)
    np.testing.assert_allclose(c.hc_charge_ratio, lam**3, rtol=1e-15)
    np.testing.assert_allclose(c.hc_density_ratio, 1 / np.sqrt(lam), rtol=1e-15)
    # Hopkinson-Cranz is the general law at gamma = 1/sqrt(lambda): lambda_Z = 1, delivered ratios as above
    # (tolerance: the root's 1e-12).
    g = scaling_curves(W, R, lam, 1 / np.sqrt(lam), blast_model=model)
    np.testing.assert_allclose(g.scaled_distance_factor, 1.0, rtol=1e-12)
    np.testing.assert_allclose(g.pressure_ratio, 1.0, rtol=1e-11)
    np.testing.assert_allclose(g.impulse_ratio, lam, rtol=1e-11)
    np.testing.assert_allclose(g.duration_ratio, lam, rtol=1e-11)


def test_full_scale_same_material_is_the_identity():
    # lambda = gamma = 1: the model is the prototype; every ratio 1 to 1e-12.
    c = scaling_curves(W, R, 1.0, 1.0, blast_model="masi2021")
    for x in (c.scaled_distance_factor, c.pressure_ratio, c.impulse_ratio, c.duration_ratio, c.charge_ratio):
        assert float(x) == pytest.approx(1.0, rel=1e-12)


@pytest.mark.parametrize("model", MODELS)
def test_monotone_in_scale(model):
    # Smaller models (lambda down, gamma = 1) sit farther away in Z: lambda_Z falls as lambda grows; the
    # delivered pressure, impulse and charge ratios rise with lambda (Fig. 5). Strict monotonicity.
    lam = np.logspace(-3, 0, 60)
    c = scaling_curves(W, R, lam, blast_model=model)
    assert c.valid.all()
    assert np.all(np.diff(c.scaled_distance_factor) < 0)
    for x in (c.pressure_ratio, c.impulse_ratio, c.charge_ratio):
        assert np.all(np.diff(x) > 0)
    # below full scale the general law always gives less pressure than Hopkinson-Cranz (lambda_Z > 1)
    # and less impulse for gamma = 1 (lambda^1.5 < lambda)
    inner = lam < 1.0 - 1e-12
    assert np.all(c.pressure_ratio[inner] < 1.0) and np.all(c.impulse_ratio[inner] < c.hc_impulse_ratio[inner])


@pytest.mark.parametrize("model", MODELS)
@pytest.mark.parametrize("lam", [1 / 20, 1 / 200])
def test_monotone_in_density_ratio(model, lam):
    # Lighter models (gamma down) need less impulse, so a larger Z: lambda_Z falls and P, i rise with gamma (Fig. 8).
    gam = np.logspace(-1.2, 0, 40)
    c = scaling_curves(W, R, lam, gam, blast_model=model)
    v = c.valid
    assert v.sum() >= 30
    assert np.all(np.diff(c.scaled_distance_factor[v]) < 0)
    assert np.all(np.diff(c.pressure_ratio[v]) > 0)
    assert np.all(np.diff(c.impulse_ratio[v]) > 0)


def test_valid_mask_is_design_models_range():
    # masi2021 at lambda = 1/200: admissible gamma ends where the model Z reaches 6.5 m/kg^(1/3) (the duration fit).
    gam = np.logspace(-2, 0, 81)
    c = scaling_curves(W, R, 1 / 200, gam, blast_model="masi2021")
    assert c.valid.any() and not c.valid.all()
    zr = valid_scaled_distance_range("masi2021")
    for k, g in enumerate(gam):
        lo, hi = admissible_scales(c.prototype_scaled_distance, g, 1.0, "masi2021", zr)
        assert c.valid[k] == (lo <= 1 / 200 <= hi)
        if c.valid[k]:
            assert zr[0] <= c.model_scaled_distance[k] <= zr[1]
        else:
            with pytest.raises(OutOfRangeError):
                design_model(W, R, 1 / 200, g, blast_model="masi2021")
    bad = ~c.valid
    for x in (
        c.scaled_distance_factor,
        c.model_scaled_distance,
        c.charge_ratio,
        c.pressure_ratio,
        c.impulse_ratio,
        c.duration_ratio,
    ):
        assert np.all(np.isnan(x[bad])) and np.all(np.isfinite(x[c.valid]))
    # Hopkinson-Cranz needs no root: defined everywhere
    assert np.all(np.isfinite(c.hc_pressure_ratio)) and np.all(np.isfinite(c.hc_impulse_ratio))
    # the invalid points are the lightest: valid is a contiguous upper block of gamma
    first = int(np.argmax(c.valid))
    assert c.valid[first:].all() and not c.valid[:first].any()


def test_no_valid_point_gives_all_nan_not_an_error():
    c = scaling_curves(W, R, [1e-7, 1e-8], blast_model="masi2021")
    assert not c.valid.any()
    assert np.all(np.isnan(c.pressure_ratio)) and np.all(np.isnan(c.duration_ratio))


def test_shapes_broadcast_and_scalars():
    c = scaling_curves(W, R, np.array([[0.1, 0.01]]), np.array([[1.0], [0.5], [0.07]]), blast_model="masi2021")
    assert c.pressure_ratio.shape == c.valid.shape == c.scale.shape == c.hc_density_ratio.shape == (3, 2)
    assert np.all(c.scale[:, 0] == 0.1) and np.all(c.density_ratio[2] == 0.07)
    s = scaling_curves(W, R, 0.005, blast_model="masi2021")
    assert s.pressure_ratio.shape == () and bool(s.valid)


@pytest.mark.parametrize(
    "kwargs, words",
    [
        ({"scale": [0.1, -1.0]}, ["scale", "-1", "> 0"]),
        ({"scale": 0.1, "density_ratio": [np.nan]}, ["density ratio", "nan", "finite"]),
        ({"scale": [0.1, 0.2], "density_ratio": [1.0, 0.5, 0.2]}, ["shapes", "broadcast"]),
        ({"scale": 0.1, "gravity_ratio": [1.0, 2.0]}, ["gravity ratio", "single number"]),
        ({"scale": 0.1, "charge": 0.0}, ["charge", "0", "> 0 kg"]),
    ],
)
def test_bad_inputs_are_named(kwargs, words):
    args = {"charge": W, "standoff": R, **kwargs}
    with pytest.raises(BlastscaleInputError) as e:
        scaling_curves(args.pop("charge"), args.pop("standoff"), **args)
    assert all(w in str(e.value) for w in words), str(e.value)


def test_prototype_outside_the_fits_raises():
    # Z = 100 / 1^(1/3) m/kg^(1/3) is beyond every fit: nothing to sweep, one named error.
    with pytest.raises(OutOfRangeError, match="scaled distance Z = 100"):
        scaling_curves(1.0, 100.0, [0.1, 0.01], blast_model="masi2021")


def test_fig5_values_at_lambda_1_over_200():
    # Fig. 5 at lambda = 1/200 (masi2021, 50 kg at 2 m): lambda_Z = 2.9927 (Table "Blast loading
    # characteristics": Z_m = 1.62 = 2.99 x 0.54), impulse ratio lambda^1.5 = 0.0354 %; rel 1e-4 on lambda_Z.
    c = scaling_curves(W, R, 1 / 200, blast_model="masi2021")
    assert float(c.scaled_distance_factor) == pytest.approx(2.9927, rel=1e-4)
    assert float(c.impulse_ratio) == pytest.approx(math.sqrt(1 / 200) ** 3, rel=1e-10)


# --- plots (blastscale.plots.similitude) -------------------------------------------------------


def test_plots_general_law_solid_hopkinson_cranz_dashed_on_log_axes():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from blastscale.plots.similitude import plot_pressure_ratio, plot_scaled_distance_factor, scaling_factors_figure

    c = scaling_curves(W, R, np.logspace(-3, 0, 20), blast_model="masi2021")
    ax = plot_pressure_ratio(c)
    solid, dashed = ax.lines
    assert solid.get_linestyle() == "-" and dashed.get_linestyle() == "--"
    assert solid.get_color() == dashed.get_color()
    np.testing.assert_array_equal(solid.get_ydata(), c.pressure_ratio)
    assert ax.get_xscale() == "log" and ax.get_yscale() == "log"
    assert "lambda" in ax.get_xlabel() and "[-]" in ax.get_ylabel()
    ax2 = plot_scaled_distance_factor(c)
    assert ax2.get_yscale() == "linear"
    g = scaling_curves(W, R, 1 / 200, np.logspace(-2, 0, 15), blast_model="masi2021")
    fig = scaling_factors_figure([g], labels=["lambda = 1/200"])
    assert len(fig.axes) == 3 and "gamma" in fig.axes[0].get_xlabel() and len(fig.legends) == 1
    plt.close("all")


def test_plot_errors_are_named():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from blastscale.plots.similitude import plot_scaling_factor, scaling_factors_figure

    c = scaling_curves(W, R, [0.1, 0.01], blast_model="masi2021")
    with pytest.raises(BlastscaleInputError, match="quantity = 'force' is not known"):
        plot_scaling_factor(c, "force")
    with pytest.raises(BlastscaleInputError, match="x = 'mass' is not known"):
        plot_scaling_factor(c, x="mass")
    with pytest.raises(BlastscaleInputError, match="labels has 2 entries"):
        scaling_factors_figure(c, labels=["a", "b"])
    plt.close("all")
