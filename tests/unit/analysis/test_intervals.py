"""Binomial intervals (analysis.intervals): Wilson's score interval against its closed form written
the other way (the roots of the score test's quadratic) and against Newcombe's (1998) published table,
and the odds in words."""

from __future__ import annotations

import math

import pytest
from scipy.stats import binom, norm

from blastscale._validate import BlastscaleInputError
from blastscale.analysis.intervals import odds_text, wilson_interval


def quadratic_roots(k: int, n: int, confidence: float) -> tuple[float, float]:
    """The Wilson bounds as the roots in p of ``(k - n p)^2 = z^2 n p (1 - p)`` (the score test at its
    critical value, Wilson 1927): ``(k + z^2/2 -+ z sqrt(k (n - k) / n + z^2 / 4)) / (n + z^2)``,
    z from scipy's normal quantile (the module uses the standard library's)."""
    z = norm.ppf(1.0 - (1.0 - confidence) / 2.0)
    root = z * math.sqrt(k * (n - k) / n + z * z / 4.0)
    return (k + z * z / 2.0 - root) / (n + z * z), (k + z * z / 2.0 + root) / (n + z * z)


@pytest.mark.parametrize("n", [4, 8, 16, 32])
@pytest.mark.parametrize("confidence", [0.95, 0.90])
def test_wilson_matches_the_quadratic_roots_for_every_k(n, confidence):
    """Every k of n = 4, 8, 16, 32 to 1e-9 absolute (two algebraically equal forms; the difference is
    rounding, ~1e-16, and the two normal quantiles agree to ~1e-15)."""
    for k in range(n + 1):
        lo, hi = wilson_interval(k, n, confidence)
        rlo, rhi = quadratic_roots(k, n, confidence)
        assert lo == pytest.approx(rlo, abs=1e-9) and hi == pytest.approx(rhi, abs=1e-9), (k, n)
        assert 0.0 <= lo <= k / n <= hi <= 1.0


def test_the_bounds_solve_the_score_test():
    """At each bound p the score statistic (k - n p) / sqrt(n p (1 - p)) equals -+ z (Wilson's definition),
    so the bounds are the interval's and not some other's; to 1e-9."""
    z = norm.ppf(0.975)
    for k, n in [(1, 8), (4, 8), (7, 8), (3, 16), (31, 32)]:
        lo, hi = wilson_interval(k, n)
        assert (k - n * lo) / math.sqrt(n * lo * (1 - lo)) == pytest.approx(z, abs=1e-9)
        assert (k - n * hi) / math.sqrt(n * hi * (1 - hi)) == pytest.approx(-z, abs=1e-9)


@pytest.mark.parametrize(
    ("k", "n", "lo", "hi"),
    [(81, 263, 0.2553, 0.3662), (15, 148, 0.0624, 0.1605), (0, 20, 0.0, 0.1611), (1, 29, 0.0061, 0.1718)],
)
def test_newcombe_1998_table(k, n, lo, hi):
    """Newcombe (1998), Statistics in Medicine 17, 857-872, Table II, method 3 (score, no continuity
    correction), 95 %: the published 4 decimals, to half a unit of the last (5e-5)."""
    got = wilson_interval(k, n)
    assert got[0] == pytest.approx(lo, abs=5e-5) and got[1] == pytest.approx(hi, abs=5e-5)


def test_eight_of_eight_is_not_certainty():
    """8 of 8 at 95 %: P >= 0.6756 (z^2 = 3.8415: 8 / (8 + z^2) = 0.67557), upper bound exactly 1; the
    "no": the lower bound is not 1 (what "P 1.000 +- 0" claimed)."""
    lo, hi = wilson_interval(8, 8)
    assert lo == pytest.approx(8.0 / (8.0 + norm.ppf(0.975) ** 2), abs=1e-12) and round(lo, 4) == 0.6756
    assert hi == 1.0 and lo < 0.7
    assert wilson_interval(0, 8) == (0.0, pytest.approx(1.0 - lo, abs=1e-12))


def test_coverage_is_close_to_nominal_for_small_n():
    """Exact coverage (binomial sums) of the 95 % interval for n = 8 at p = 0.05, 0.2, 0.5, 0.8: >= 0.92
    (measured 0.943, 0.944, 0.930, 0.944; Brown, Cai & DasGupta 2001, Fig. 4: Wilson's coverage oscillates
    about 0.95); the "no", the reason for Wilson: the Wald interval's at p = 0.2 is 0.822, at p = 0.05 0.336."""
    n = 8
    for p in (0.05, 0.2, 0.5, 0.8):
        cover = sum(
            binom.pmf(k, n, p) for k in range(n + 1) if wilson_interval(k, n)[0] <= p <= wilson_interval(k, n)[1]
        )
        assert cover >= 0.92, (p, cover)
    z = norm.ppf(0.975)
    wald = sum(binom.pmf(k, n, 0.2) for k in range(n + 1) if abs(k / n - 0.2) <= z * math.sqrt(k / n * (1 - k / n) / n))
    assert wald < 0.85


def test_odds_text():
    assert odds_text(8, 8) == "P >= 0.68 (95 %, 8 of 8)"
    assert odds_text(0, 8) == "P <= 0.32 (95 %, 0 of 8)"
    assert odds_text(4, 8) == "P 0.50 (0.22-0.78, 95 %, 4 of 8)"
    assert odds_text(3, 4, 0.9) == "P 0.75 (0.36-0.94, 90 %, 3 of 4)"
    assert "+-" not in odds_text(16, 16)
    # a large unanimous sample: a bound inside (0, 1) is never printed as 1 or 0
    assert odds_text(2000, 2000) == "P >= 0.998 (95 %, 2000 of 2000)"
    assert odds_text(1999, 2000) == "P 0.9995 (0.997-0.9999, 95 %, 1999 of 2000)"
    assert odds_text(0, 2000) == "P <= 0.002 (95 %, 0 of 2000)"


@pytest.mark.parametrize(
    ("args", "match"),
    [
        ((9, 8), r"k = 9 is out of range: valid range is \[0, 8\]"),
        ((-1, 8), r"k = -1 is out of range"),
        ((1.5, 8), r"k = 1.5 is not a whole number"),
        ((True, 8), r"k = True is not a whole number"),
        ((0, 0), r"n = 0 is out of range"),
        ((1, 8, 1.0), r"confidence = 1 is out of range: valid range is \(0, 1\)"),
        ((1, 8, 0.0), r"confidence = 0 is out of range"),
        ((1, 8, math.nan), r"confidence = nan is not a finite number"),
    ],
)
def test_bad_input_names_the_parameter(args, match):
    with pytest.raises(BlastscaleInputError, match=match):
        wilson_interval(*args)
    with pytest.raises(BlastscaleInputError, match=match):
        odds_text(*args)
