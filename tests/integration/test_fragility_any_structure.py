"""Fragility of any structure (issue #38): a three-drum column through `blastscale fragility` (damage states,
one Study per case) against an independent lognormal maximum-likelihood fit of the same runs; the block's
first-swing fragility unchanged (bitwise); inputs that cannot enter the chosen criterion refused in one line."""

from __future__ import annotations

import contextlib
import io
import json
import math

import numpy as np
import pytest
from scipy.optimize import minimize
from scipy.stats import norm

from blastscale.cli import main
from blastscale.scenario import Scenario
from blastscale.sweeps.fragility import fragility

#: A small column: three square drums, 3 m, 0.6 s after the arrival (the damage states settle within it at
#: these charges; a test, not a study), prototype alone.
COLUMN = """title = "Three-drum square column, 3 m"
[structure]
kind = "column"
section = "square"
drums = 3
height_m = 3.0
base_width_m = 0.6
top_width_m = 0.5
[blast]
charge_kg = 20.0
standoff_m = 5.0
blast_model = "masi2021"
[simulation]
engine = "3d"
duration_s = 0.6
"""

BLOCK = Scenario.default().with_values({"engine": "planar"})  # paper block, 2 m, masi2021, Friedlander


def _cli(argv, capsys):
    with pytest.raises(SystemExit) as e:
        main(argv)
    cap = capsys.readouterr()
    return e.value.code, cap.out, cap.err


@pytest.fixture(scope="module")
def column_run(tmp_path_factory):
    """`blastscale fragility column.toml`: 12 runs, charges 2, 3.5, 6 kg x 4 draws (charge x lognormal factor
    beta 0.3: the charge and its TNT equivalence; friction uniform 0.5-0.8), seed 1; its JSON and plot."""
    d = tmp_path_factory.mktemp("column")
    toml, png = d / "column.toml", d / "fragility.png"
    toml.write_text(COLUMN)
    argv = ["fragility", str(toml), "--charges", "2,3.5,6", "--lognormal", "charge_kg=0.3"]
    argv += ["--uniform", "friction=0.5:0.8", "--samples", "4", "--seed", "1", "--plot", str(png), "--json"]
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf), pytest.raises(SystemExit) as e:
        main(argv)
    assert e.value.code in (0, None)
    return json.loads(buf.getvalue()), png


def _independent_fit(W, k, n):
    """theta, beta maximising sum_j [k_j ln p_j + (n_j - k_j) ln(1 - p_j)], p_j = Phi(ln(W_j / theta) / beta)
    (the binomial likelihood of Baker 2015, Eq. 11, without its constant), written here with Phi itself, by
    Powell's method then Nelder-Mead on (theta, beta) (blastscale: Nelder-Mead on (ln theta, ln beta) with
    log Phi)."""

    def nll(x):
        theta, beta = x
        if theta <= 0 or beta <= 0:
            return math.inf
        p = np.clip(norm.cdf(np.log(W / theta) / beta), 1e-300, 1.0 - 1e-16)
        return -float(np.sum(k * np.log(p) + (n - k) * np.log1p(-p)))

    start = [float(np.exp(np.mean(np.log(W)))), 0.4]
    with np.errstate(invalid="ignore"):  # Powell's line search steps onto theta <= 0 (nll = inf)
        r = minimize(nll, start, method="Powell", options={"xtol": 1e-12, "ftol": 1e-15, "maxiter": 20000})
    r = minimize(nll, r.x, method="Nelder-Mead", options={"xatol": 1e-13, "fatol": 1e-15, "maxiter": 20000})
    return r.x


def test_column_fragility_equals_an_independent_lognormal_fit(column_run):
    """Median and beta of every state that has a transition within 1e-6 (relative) of the independent fit of the
    same counts: both optimisers converge to ~1e-10 in the parameters; 1e-6 leaves room for the flat direction of a
    12-run likelihood, and is far below any physical meaning."""
    out, _ = column_run
    assert out["criterion"] == "damage" and list(out["states"]) == ["slight", "moderate", "severe", "collapse"]
    W = np.asarray(out["charge_kg"])
    fitted = 0
    for name, st in out["states"].items():
        assert set(st) >= {"exceeded", "median_charge_kg", "beta", "median_charge_ci_kg", "beta_ci"}
        k, n = np.asarray(st["exceeded"]), np.asarray(st["trials"])
        assert np.all(n == 4) and np.all((0 <= k) & (k <= n))
        if not st["fit_bounded"]:
            # no maximum to compare (a flat ridge): the fit must say so with an open bound
            assert (
                st["beta"] is None
                or math.inf in (st["median_charge_ci_kg"][1], st["beta_ci"][1])
                or 0.0
                in (
                    st["median_charge_ci_kg"][0],
                    st["beta_ci"][0],
                )
            )
            continue
        theta, beta = _independent_fit(W, k, n)
        assert st["median_charge_kg"] == pytest.approx(theta, rel=1e-6) and st["beta"] == pytest.approx(beta, rel=1e-6)
        lo, hi = st["median_charge_ci_kg"]
        assert float(lo) <= st["median_charge_kg"] <= float(hi)
        fitted += 1
    assert fitted >= 1  # at least one state is bounded by these charges (slight: 1, 2, 4 of 4)
    # a draw that reaches a state reaches every milder one: counts never increase with severity
    ks = np.array([st["exceeded"] for st in out["states"].values()])
    assert np.all(np.diff(ks, axis=0) <= 0)
    # beside today's keys: the collapse state is the top level's
    assert out["collapsed"] == out["states"]["collapse"]["exceeded"]


def test_column_fragility_plot_is_written(column_run):
    _, png = column_run
    assert png.stat().st_size > 10_000


def test_block_first_swing_fragility_is_todays_bitwise():
    """Today's first-swing fragility of the paper's block (main at cad6f0c, before the damage criterion):
    counts, median, beta and log-likelihood reproduced bitwise; its one state is the collapse."""
    W = np.geomspace(50.0, 130.0, 5)
    r = fragility(BLOCK, W, lognormal={"charge_kg": 0.1}, uniform={"standoff_m": (1.9, 2.1)}, samples=200, seed=3)
    assert r.criterion == "first-swing" and list(r.states) == ["collapse"]
    assert r.collapsed.tolist() == [0, 4, 109, 197, 200]
    assert r.fit.median_charge_kg == 79.72524969366614 and r.fit.beta == 0.11276105733866033
    assert r.fit.log_likelihood == -173.05565783126585
    assert r.states["collapse"].fit is r.fit and r.states["collapse"].exceeded is r.collapsed
    # the plot's title in words: the uncertain fields, no internal names
    from blastscale.plots.fragility import plot_fragility

    title = plot_fragility(r).get_title()
    assert "charge x lognormal factor (beta 0.1)" in title and "standoff 1.9-2.1 m (uniform)" in title
    assert "charge_kg_factor" not in title and "_" not in title


@pytest.mark.parametrize(
    "argv, words",
    [
        # restitution acts only at an impact; a block pushed from rest is still swinging outward when the pulse ends
        (
            ["--uniform", "restitution=0.5:0.9"],
            "--uniform restitution: simulation.restitution cannot enter the first-swing",
        ),
        (["--uniform", "friction=0.5:0.9"], "planar rocking has no sliding"),
        # a damage fragility runs the prototype alone: the specimen's scale cannot enter it
        (
            ["--criterion", "damage", "--set", "engine=3d", "--uniform", "scale.length=0.01:0.1"],
            "cannot enter the damage",
        ),
        (["--criterion", "nonsense"], "criterion = 'nonsense' is not known"),
        # the first-swing criterion runs in this process: no store, no workers
        (["--workers", "2"], "--workers: the first-swing criterion runs vectorised in this process"),
    ],
)
def test_inputs_that_cannot_enter_the_criterion_are_refused_in_one_line(capsys, argv, words):
    with pytest.raises(SystemExit) as e:
        main(["fragility", "--charges", "50,80", "--lognormal", "charge_kg=0.2", "--samples", "10", *argv])
    err = capsys.readouterr().err
    assert e.value.code == 2 and words in err and err.count("\n") == 1


def test_a_column_by_the_first_swing_criterion_is_refused(tmp_path, capsys):
    toml = tmp_path / "column.toml"
    toml.write_text(COLUMN)
    with pytest.raises(SystemExit) as e:
        main(["fragility", str(toml), "--charges", "2,6", "--lognormal", "charge_kg=0.2", "--criterion", "first-swing"])
    err = capsys.readouterr().err
    assert e.value.code == 2 and "the first-swing criterion needs a block" in err and "--criterion damage" in err
