"""Binomial intervals: the odds of ``k`` successes in ``n`` trials, honest for small ensembles.

An ensemble of a few members (8 3D runs of a specimen, 16 members of a wobbling column) gives a
probability ``k / n``; its normal-approximation ("Wald") standard error ``sqrt(p (1 - p) / n)`` is
0 at ``k = 0`` and ``k = n``, so "8 of 8" would read "P 1.000 +- 0", which no ensemble of 8
supports. The Wilson (1927) score interval inverts the score test instead: it is never empty,
never leaves [0, 1], and its coverage stays close to the nominal level down to n of a few
(Brown, Cai & DasGupta 2001, who recommend it, with Jeffreys', for n < 40; Newcombe 1998, method 3).
8 of 8 bounds P only from below: P >= 0.676 at 95 %.

References
----------
.. [1] Wilson, E. B. (1927). Probable inference, the law of succession, and statistical inference.
   J. Am. Stat. Assoc. 22(158), 209-212. doi:10.1080/01621459.1927.10502953
.. [2] Brown, L. D., Cai, T. T., DasGupta, A. (2001). Interval estimation for a binomial
   proportion. Statistical Science 16(2), 101-133. doi:10.1214/ss/1009213286
.. [3] Newcombe, R. G. (1998). Two-sided confidence intervals for the single proportion:
   comparison of seven methods. Statistics in Medicine 17(8), 857-872.
"""

from __future__ import annotations

import math
import operator
from statistics import NormalDist

from .._validate import BlastscaleInputError, check_range

__all__ = ["wilson_interval", "odds_text", "probability_text", "Z95"]

#: The two-sided 95 % quantile of the standard normal distribution, ``NormalDist().inv_cdf(0.975)`` [-]: the
#: package's one 95 % multiplier (normal intervals of fits, records and tolerances).
Z95 = 1.959963984540054


def _count(name: str, value, lo: int, hi: float) -> int:
    """``value`` as an int; raise unless it is a whole number (not a bool) in [lo, hi]."""
    try:
        if isinstance(value, bool):
            raise TypeError
        k = operator.index(value)
    except TypeError:
        raise BlastscaleInputError(f"{name} = {value!r} is not a whole number (a count of ensemble members)") from None
    if not lo <= k <= hi:
        raise BlastscaleInputError(f"{name} = {k} is out of range: valid range is [{lo}, {hi:g}]")
    return k


def _checked(k, n, confidence) -> tuple:
    """(k, n, z) of valid inputs: ``n`` >= 1, ``0 <= k <= n``, ``confidence`` in (0, 1)."""
    n = _count("n", n, 1, math.inf)
    k = _count("k", k, 0, n)
    c = float(check_range("confidence", confidence, 0.0, 1.0, lo_open=True, hi_open=True))
    return k, n, NormalDist().inv_cdf(1.0 - (1.0 - c) / 2.0)


def wilson_interval(k: int, n: int, confidence: float = 0.95) -> tuple[float, float]:
    """Wilson's score interval of a binomial probability, two-sided.

    .. math::

        \\frac{\\hat p + \\frac{z^2}{2n} \\pm z \\sqrt{\\frac{\\hat p (1 - \\hat p)}{n} + \\frac{z^2}{4 n^2}}}
        {1 + \\frac{z^2}{n}}, \\qquad \\hat p = k / n, \\quad z = \\Phi^{-1}\\left(1 - \\frac{1 - c}{2}\\right)

    (Wilson 1927, Eq. on p. 210; Brown, Cai & DasGupta 2001, Eq. 4). The lower bound is exactly 0 at
    ``k = 0`` and the upper exactly 1 at ``k = n``.

    Parameters
    ----------
    k : int
        Successes (members whose outcome agrees, members that collapse) [-], ``0 <= k <= n``.
    n : int
        Trials (members) [-], >= 1.
    confidence : float
        Two-sided confidence level c [-], in (0, 1).

    Returns
    -------
    (float, float)
        The lower and upper bounds of the probability [-], in [0, 1].

    Raises
    ------
    BlastscaleInputError
        ``k`` or ``n`` not a whole number or out of range; ``confidence`` outside (0, 1).

    Examples
    --------
    >>> lo, hi = wilson_interval(8, 8)
    >>> round(lo, 4), hi
    (0.6756, 1.0)
    >>> [round(x, 4) for x in wilson_interval(81, 263)]  # Newcombe (1998), Table I: 0.2553-0.3662
    [0.2553, 0.3662]
    """
    k, n, z = _checked(k, n, confidence)
    p = k / n
    z2 = z * z
    centre = (p + z2 / (2 * n)) / (1 + z2 / n)
    half = z * math.sqrt(p * (1 - p) / n + z2 / (4 * n * n)) / (1 + z2 / n)
    lo = 0.0 if k == 0 else max(centre - half, 0.0)
    hi = 1.0 if k == n else min(centre + half, 1.0)
    return lo, hi


def odds_text(k: int, n: int, confidence: float = 0.95) -> str:
    """The odds of ``k`` of ``n`` in words, with their Wilson interval (:func:`wilson_interval`).

    One-sided where the ensemble is unanimous: ``k == n`` bounds the probability only from below,
    ``k == 0`` only from above; never "+- 0". Probabilities to 2 decimals, more where 2 would print a
    value strictly inside (0, 1) as 0 or 1 (2000 of 2000: "P >= 0.998", not "P >= 1.00").

    Parameters
    ----------
    k, n, confidence
        As :func:`wilson_interval`.

    Returns
    -------
    str

    Examples
    --------
    >>> odds_text(8, 8)
    'P >= 0.68 (95 %, 8 of 8)'
    >>> odds_text(0, 8)
    'P <= 0.32 (95 %, 0 of 8)'
    >>> odds_text(4, 8)
    'P 0.50 (0.22-0.78, 95 %, 4 of 8)'
    >>> odds_text(2000, 2000)
    'P >= 0.998 (95 %, 2000 of 2000)'
    """
    lo, hi = wilson_interval(k, n, confidence)
    level = f"{100 * float(confidence):g} %"
    if k == n:
        return f"P >= {probability_text(lo)} ({level}, {k} of {n})"
    if k == 0:
        return f"P <= {probability_text(hi)} ({level}, {k} of {n})"
    return f"P {probability_text(k / n)} ({probability_text(lo)}-{probability_text(hi)}, {level}, {k} of {n})"


def probability_text(x: float) -> str:
    """A probability [-] to 2 decimals, or to as many more (up to 6) as keep a value inside (0, 1) off 0 and 1.

    Examples
    --------
    >>> probability_text(0.6756), probability_text(0.99808), probability_text(1.0)
    ('0.68', '0.998', '1.00')
    """
    digits = 2
    while 0.0 < x < 1.0 and round(x, digits) in (0.0, 1.0) and digits < 6:
        digits += 1
    return f"{x:.{digits}f}"
