"""Fragility: the known answer with the charge alone uncertain, the maximum-likelihood fit, CLI."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from scipy.stats import norm

from blastscale.cli import main
from blastscale.rocking import RockingSystem, critical_charge
from blastscale.scenario import Scenario
from blastscale.study import Study
from blastscale.sweeps.fragility import fit_lognormal_fragility, fragility

BASE = Scenario.default().with_values({"engine": "planar"})  # paper block, 2 m, masi2021, Friedlander


@pytest.fixture(scope="module")
def wc():
    sc = BASE
    return critical_charge(RockingSystem.from_block(Study(sc).structure()), 2.0, blast_model="masi2021").charge_kg


def test_charge_uncertainty_alone_gives_the_lognormal_with_median_the_critical_charge(wc):
    """W eps (eps lognormal, median 1, log-sd beta) overturns iff W eps > W_c, so
    P(overturn | W) = Phi(ln(W / W_c) / beta) exactly."""
    beta, n = 0.25, 3000
    W = np.geomspace(45.0, 140.0, 9)
    res = fragility(BASE, W, lognormal={"charge_kg": beta}, samples=n, seed=11)
    # exact: the counts are those of the draws beyond the threshold (the same draws at every charge)
    eps = np.exp(beta * np.random.default_rng(11).standard_normal(n))
    np.testing.assert_array_equal(res.collapsed, [(w * eps > wc).sum() for w in W])
    # and they sample Phi(ln(W/W_c)/beta): within 4 binomial standard errors at every charge
    p = norm.cdf(np.log(W / wc) / beta)
    assert np.all(np.abs(res.probability - p) <= 4 * np.sqrt(p * (1 - p) / n) + 1e-12)
    # the fit returns W_c and beta within sampling error: 3 standard errors from the observed
    # information (here se(ln theta) ~ 0.003, se(ln beta) ~ 0.014)
    f = res.fit
    assert abs(math.log(f.median_charge_kg / wc)) <= 3 * f.se_ln_median
    assert abs(math.log(f.beta / beta)) <= 3 * f.se_ln_beta
    assert f.median_ci_kg[0] < wc < f.median_ci_kg[1]
    assert f.se_ln_median < 0.01 and f.se_ln_beta < 0.03


def test_fit_recovers_exact_expected_counts():
    """Counts equal to N Phi(ln(W/theta)/beta) (no noise): the likelihood is maximal at the truth."""
    W = np.geomspace(10.0, 100.0, 12)
    k = 1e6 * norm.cdf(np.log(W / 31.6) / 0.35)
    f = fit_lognormal_fragility(W, k, 1e6)
    assert f.median_charge_kg == pytest.approx(31.6, rel=1e-6) and f.beta == pytest.approx(0.35, rel=1e-5)


def test_fragility_cli_json_plot_and_other_fields(tmp_path, capsys):
    png = tmp_path / "f.png"
    with pytest.raises(SystemExit) as e:
        main(
            [
                "fragility",
                "--charges",
                "50:130:5:log",
                "--lognormal",
                "charge_kg=0.1",
                "--uniform",
                "standoff_m=1.9:2.1",
                "--uniform",
                "alpha_deg=14:16",
                "--samples",
                "60",
                "--seed",
                "3",
                "--plot",
                str(png),
                "--json",
            ]
        )
    assert e.value.code in (0, None)
    out = json.loads(capsys.readouterr().out)
    assert len(out["probability"]) == 5 and out["samples"] == 60
    assert out["probability"][0] < 0.5 < out["probability"][-1]
    assert out["median_charge_kg"] is not None and out["beta"] > 0 and len(out["median_charge_ci_kg"]) == 2
    assert set(out["fields"]) == {"charge_kg_factor", "standoff_m", "alpha_deg"}
    # the block's one state, beside today's keys: the same counts and fit
    assert out["criterion"] == "first-swing" and set(out["states"]) == {"collapse"}
    st = out["states"]["collapse"]
    assert st["exceeded"] == out["collapsed"] and st["median_charge_kg"] == out["median_charge_kg"]
    assert st["beta"] == out["beta"] and st["median_charge_ci_kg"] == out["median_charge_ci_kg"]
    assert png.stat().st_size > 10_000


@pytest.mark.parametrize(
    "argv, word",
    [
        (["--charges", "50:130:5", "--lognormal", "charge_kg=-0.2"], "beta"),
        (["--charges", "50:130:5"], "uncertain fields"),
        (["--charges", "130:50:5", "--lognormal", "charge_kg=0.2"], "empty range"),
        (["--charges", "50:130:0", "--lognormal", "charge_kg=0.2"], "n = 0"),
        (["--charges", "50:130:5", "--uniform", "restitution=0.9:0.5"], "empty range"),
        (["--charges", "50:130:5", "--uniform", "nonsense=0.1:0.5"], "nonsense"),
    ],
)
def test_fragility_bad_input_one_line_exit_2(capsys, argv, word):
    with pytest.raises(SystemExit) as e:
        main(["fragility", *argv, "--samples", "10"])
    assert e.value.code == 2
    err = capsys.readouterr().err
    assert word in err and len(err.strip().splitlines()) <= 2


def test_prototype_only_fragility_through_the_cli_equals_the_scaled_scenarios(tmp_path, capsys):
    """A scenario without [scale] (the monument alone): fragility needs no specimen, and gives the
    same counts as the same prototype with a [scale] section (the first swing of the prototype
    does not depend on the specimen)."""
    data = BASE.to_dict()
    data.pop("scale")
    outs = []
    for name, sc in (("scaled", BASE), ("prototype", Scenario.from_dict(data, source="test: no [scale]"))):
        toml = tmp_path / f"{name}.toml"
        toml.write_text(sc.to_toml())
        with pytest.raises(SystemExit) as e:
            main(
                [
                    "fragility",
                    str(toml),
                    "--charges",
                    "50:130:5:log",
                    "--lognormal",
                    "charge_kg=0.2",
                    "--uniform",
                    "alpha_deg=14:16",
                    "--samples",
                    "200",
                    "--seed",
                    "5",
                    "--json",
                ]
            )
        assert e.value.code in (0, None)
        outs.append(json.loads(capsys.readouterr().out))
    assert outs[1]["collapsed"] == outs[0]["collapsed"] and outs[1]["median_charge_kg"] == outs[0]["median_charge_kg"]
    assert 0 < outs[1]["collapsed"][2] < 200


def test_complete_separation_gives_open_bounds_not_a_crash():
    """Issue #15, fault 3: every draw stands at 40 kg and overturns at 100 kg. The likelihood has no maximum
    (beta -> 0, the median anywhere between): the fit says so, with the median bracketed by the two charges and
    beta's bounds open, instead of an OverflowError."""
    f = fit_lognormal_fragility([40.0, 100.0], [0, 100], 100)
    assert f.beta is None and not f.bounded and f.median_ci_kg == (40.0, 100.0) and f.beta_ci == (0.0, math.inf)
    assert f.median_charge_kg == pytest.approx(math.sqrt(4000.0)) and "between them" in f.note
    assert list(f.probability([30.0, 90.0])) == [0.0, 1.0]
    # one informative charge only: a fit, with the bounds the data cannot close reported open: the profile
    # likelihood bounds the median (the 54 % at 80 kg puts it near 80 kg) but not beta from below (beta -> 0,
    # a step between 40 and 80 kg, explains the counts as well)
    g = fit_lognormal_fragility([40.0, 80.0], [0, 54], 100)
    assert g.beta_ci[0] == 0.0 and 0.0 < g.beta_ci[1] < math.inf and not g.bounded
    assert (
        "do not bound the beta" in g.note and 40.0 < g.median_ci_kg[0] < g.median_charge_kg < g.median_ci_kg[1] < 100.0
    )


def test_fragility_cli_when_the_fit_cannot_be_bounded(capsys, tmp_path):
    png = tmp_path / "f.png"
    with pytest.raises(SystemExit) as e:
        main(
            [
                "fragility",
                "--charges",
                "40,100",
                "--lognormal",
                "charge_kg=0.01",
                "--samples",
                "100",
                "--plot",
                str(png),
            ]
        )
    assert e.value.code in (0, None)
    cap = capsys.readouterr()
    assert "lognormal fit: not bounded: every draw stands at W <= 40 kg and overturns at W >= 100 kg" in cap.out
    assert png.stat().st_size > 10_000 and f"wrote {png} (" in cap.err
    with pytest.raises(SystemExit) as e:
        main(["fragility", "--charges", "40,100", "--lognormal", "charge_kg=0.01", "--samples", "100", "--json"])
    out = json.loads(capsys.readouterr().out)
    assert out["beta"] is None and out["beta_ci"] == [0.0, "inf"] and out["median_charge_ci_kg"] == [40.0, 100.0]
    assert out["fit_bounded"] is False and "add charges between 40 and 100 kg" in out["fit_note"]


def test_zero_dispersion_is_refused_in_one_line(capsys):
    with pytest.raises(SystemExit) as e:
        main(["fragility", "--charges", "40,80", "--lognormal", "charge_kg=0", "--samples", "100"])
    err = capsys.readouterr().err
    assert e.value.code == 2 and err.count("\n") == 1
    assert "beta is out of range: must be > 0 (beta = 0 is no uncertainty" in err and "blastscale critical" in err
