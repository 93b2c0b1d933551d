"""The Friedlander decay on the package's one root finder against the 90-step bisection it replaced (issue #34).

:func:`blastscale.blast.friedlander.friedlander_decay` solves paper Eq. (2) for the decay d in u = asinh(d):
until issue #34 by its own 90-step vectorised bisection (plus a scalar fast path, ``_bisect_one``, bit for
bit the array path), now by :func:`blastscale.roots.bracketed_root` (Illinois regula falsi) on the same
bracket, as the root of ln k - ln k(sinh u); both end with the same 3-step Newton polish. The old solver is kept below, verbatim, as the
reference (:func:`bisection_decay`).

``accuracy``: the largest relative change of d over a dense grid of impulse ratios k in (0, e - 2): tiny k
(d up to ~1e12), k near 1/2 (d near 0), k > 1/2 (negative decays), near e - 2 (d -> -1), as one array call
and as scalar calls; where |d| < 1e-6 (no Newton step there) the absolute change, against the resolution
of the problem there (|dk/dd| = 1/6 at d = 0: one ulp of k = 1/2 moves d by 6.7e-16).

``speed``: seconds per call, old and new, interleaved in one run on the same load (best of ``--repeats``
rounds, and the median): one decay per call (:data:`SCALAR_RATIOS`, in turn), an array of 1e3 and of 1e5 decays
(k uniform over (1e-4, 0.499)).

Not a test: ``python benchmarks/bench_friedlander_decay.py [accuracy|speed] [--repeats 15]`` (prints JSON).
"""

from __future__ import annotations

import argparse
import json
import math
import statistics
import time
import warnings

import numpy as np

from blastscale._validate import BlastscaleInputError, check_positive
from blastscale.blast.friedlander import (
    MAX_IMPULSE_RATIO,
    NegativeDecayWarning,
    friedlander_decay,
    friedlander_impulse_ratio,
)


def _slope(d, k):
    """dk/dd of paper Eq. (2) (as the library's ``_impulse_ratio_slope``)."""
    return (-np.expm1(-d)) / d**2 - 2.0 * k / d


def bisection_decay(peak, duration, impulse, *, allow_negative: bool = True):
    """The decay as computed before issue #34: 90 bisection steps in asinh(d) (one decay: ``_bisect_one``,
    bit for bit the array path), then 3 Newton steps. Verbatim but for the names."""
    P = check_positive("peak pressure", peak, "Pa")
    t = check_positive("positive duration", duration, "s")
    i = check_positive("impulse", impulse, "Pa*s")
    k = np.broadcast_to(i / (P * t), np.broadcast_shapes(P.shape, t.shape, i.shape)).astype(float)
    if np.any(k >= MAX_IMPULSE_RATIO):
        kb = float(k[k >= MAX_IMPULSE_RATIO].ravel()[0])
        raise BlastscaleInputError(
            f"impulse ratio i/(P*t_o) = {kb:.6g} is out of range for a modified Friedlander pulse: "
            f"valid range is (0, {MAX_IMPULSE_RATIO:.6g}) (use a triangular or tabulated pulse)"
        )
    if np.any(k >= 0.5):
        kb = float(k[k >= 0.5].ravel()[0])
        msg = (
            f"impulse ratio i/(P*t_o) = {kb:.6g} >= 0.5: no positive Friedlander decay exists "
            "(the impulse exceeds that of the triangle with the same peak and duration)"
        )
        if not allow_negative:
            raise BlastscaleInputError(msg + "; valid range for a positive decay is (0, 0.5)")
        warnings.warn(msg + "; using the negative decay in (-1, 0]", NegativeDecayWarning, stacklevel=2)
    lo = np.full(k.shape, math.asinh(-1.0))
    hi = np.arcsinh(1.0 / k)
    one = k.size == 1 and float(hi.ravel()[0]) < 700.0
    if one:
        lo, hi = (np.full(k.shape, x) for x in _bisect_one(k, float(lo.ravel()[0]), float(hi.ravel()[0])))
    for _ in range(0 if one else 90):
        mid = 0.5 * (lo + hi)
        f = friedlander_impulse_ratio(np.sinh(mid)) - k
        lo = np.where(f > 0.0, mid, lo)
        hi = np.where(f > 0.0, hi, mid)
    d = np.sinh(0.5 * (lo + hi))
    for _ in range(3):
        kd = friedlander_impulse_ratio(d)
        dsafe = np.where(np.abs(d) < 1e-6, 1e-6, d)
        dk = _slope(dsafe, friedlander_impulse_ratio(dsafe))
        step = np.where(np.abs(d) < 1e-6, 0.0, (kd - k) / dk)
        d = d - step
    return d if d.ndim else float(d)


def _bisect_one(k, lo: float, hi: float) -> tuple:
    """The old scalar fast path: float decisions away from the root, the array expression near it."""
    kf = float(k.ravel()[0])
    for _ in range(90):
        mid = 0.5 * (lo + hi)
        if mid == lo or mid == hi:
            break
        d = math.sinh(mid)
        kd = 0.5 - d / 6.0 + d**2 / 24.0 - d**3 / 120.0 if abs(d) < 1e-3 else (math.expm1(-d) + d) / d**2
        if abs(kd - kf) <= 1e-9 * kf:
            kd = friedlander_impulse_ratio(np.sinh(np.full(k.shape, mid))) - k
            up = float(np.ravel(kd)[0]) > 0.0
        else:
            up = kd > kf
        lo, hi = (mid, hi) if up else (lo, mid)
    return lo, hi


def ratio_grid() -> np.ndarray:
    """Impulse ratios over (0, e - 2): log-spaced tiny ones, a dense linear sweep, k near 1/2 on both
    sides (down to 1e-16 away, and 1/2 itself), and k near e - 2."""
    rng = np.random.default_rng(34)
    return np.concatenate(
        [
            np.logspace(-15, -0.31, 3000),
            np.linspace(1e-6, MAX_IMPULSE_RATIO, 20000, endpoint=False)[1:],
            0.5 + np.linspace(-1e-3, 1e-3, 2001),
            0.5 - np.logspace(-16, -3, 500),
            0.5 + np.logspace(-16, -3, 500),
            [0.5, np.nextafter(0.5, 0.0), np.nextafter(0.5, 1.0)],
            MAX_IMPULSE_RATIO - np.logspace(-15, -2, 500),
            rng.uniform(0.0, MAX_IMPULSE_RATIO, 5000),
        ]
    )


def accuracy() -> dict:
    k = ratio_grid()
    k = k[(k > 0.0) & (k < MAX_IMPULSE_RATIO)]
    ones = np.ones_like(k)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", NegativeDecayWarning)
        old, new = bisection_decay(ones, ones, k), friedlander_decay(ones, ones, k)
        sample = np.linspace(0, k.size - 1, 4000).astype(int)
        old1 = np.array([bisection_decay(1.0, 1.0, float(k[j])) for j in sample])
        new1 = np.array([friedlander_decay(1.0, 1.0, float(k[j])) for j in sample])
    big = np.abs(old) >= 1e-6
    rel = np.abs(new - old)[big] / np.abs(old[big])
    worst = int(np.flatnonzero(big)[np.argmax(rel)])
    # how well k(d) = k is met: |k(d) - k| / k, old and new (the residual at the returned d)
    res_old = np.abs(friedlander_impulse_ratio(old) - k) / k
    res_new = np.abs(friedlander_impulse_ratio(new) - k) / k
    return {
        "section": "accuracy",
        "ratios": int(k.size),
        "d_range": [float(new.min()), float(new.max())],
        "max_rel_change_abs_d_ge_1e-6": float(rel.max()),
        "at_k": float(k[worst]),
        "median_rel_change": float(np.median(rel)),
        "bit_identical_fraction": float(np.mean(new == old)),
        "max_abs_change_abs_d_lt_1e-6": float(np.abs(new - old)[~big].max()) if np.any(~big) else 0.0,
        "cases_abs_d_lt_1e-6": int(np.count_nonzero(~big)),
        "max_rel_residual_old": float(res_old.max()),
        "max_rel_residual_new": float(res_new.max()),
        "scalar_calls": int(sample.size),
        "scalar_equals_array_new": bool(np.array_equal(new1, new[sample])),
        "scalar_equals_array_old": bool(np.array_equal(old1, old[sample])),
    }


#: One decay at a time: impulse ratios of the blast fits' decays (d ~ 0.6 to 20: k ~ 0.05 to 0.4), an
#: almost impulsive pulse (k = 1e-6, d ~ 1e6), one near the triangle (k = 0.45) and a negative decay (k = 0.6).
SCALAR_RATIOS = (0.05, 0.15, 0.3, 0.4, 0.45, 1e-6, 0.6)


def _time(fn, cases, calls: int) -> float:
    """Seconds per call of ``fn`` over ``calls`` rounds of ``cases`` (argument tuples)."""
    t0 = time.perf_counter()
    for _ in range(calls):
        for args in cases:
            fn(*args)
    return (time.perf_counter() - t0) / (calls * len(cases))


def speed(repeats: int) -> list[dict]:
    rng = np.random.default_rng(1)
    k3, k5 = rng.uniform(1e-4, 0.499, 1000), rng.uniform(1e-4, 0.499, 100_000)
    loads = {
        "scalar": ([(1.0, 1.0, k) for k in SCALAR_RATIOS], 30),
        "array_1e3": ([(np.ones(k3.size), np.ones(k3.size), k3)], 20),
        "array_1e5": ([(np.ones(k5.size), np.ones(k5.size), k5)], 1),
    }
    rows = []
    for name, (cases, calls) in loads.items():
        times: dict[str, list[float]] = {"old": [], "new": []}
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", NegativeDecayWarning)
            for fn in (bisection_decay, friedlander_decay):  # warm-up
                _time(fn, cases, 1)
            for r in range(repeats):  # interleaved, alternating which goes first
                order = (("old", bisection_decay), ("new", friedlander_decay))
                for label, fn in order if r % 2 == 0 else order[::-1]:
                    times[label].append(_time(fn, cases, calls))
        best = {k: min(v) for k, v in times.items()}
        med = {k: statistics.median(v) for k, v in times.items()}
        rows.append(
            {
                "section": "speed",
                "load": name,
                "old_s_best": best["old"],
                "new_s_best": best["new"],
                "new_over_old_best": best["new"] / best["old"],
                "old_s_median": med["old"],
                "new_s_median": med["new"],
                "new_over_old_median": med["new"] / med["old"],
            }
        )
    return rows


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("what", nargs="?", choices=("accuracy", "speed", "all"), default="all")
    ap.add_argument("--repeats", type=int, default=15)
    a = ap.parse_args()
    if a.what in ("accuracy", "all"):
        print(json.dumps(accuracy()), flush=True)
    if a.what in ("speed", "all"):
        for row in speed(a.repeats):
            print(json.dumps(row), flush=True)


if __name__ == "__main__":
    main()
