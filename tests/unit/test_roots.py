"""The one bracketed root finder (blastscale.roots): many increasing functions at once, to a stated
tolerance or to double precision."""

from __future__ import annotations

import math

import numpy as np
import pytest

from blastscale.roots import bracketed_root, root_of_bracket, vector_root


def test_bracketed_root_to_double_precision():
    """u^3 + u - c (increasing) for five c at once: within 4 spacings of the exact root (xtol = 0)."""
    c = np.array([-10.0, -0.5, 0.0, 2.0, 30.0])

    def f(idx, u):
        return u**3 + u - c[idx]

    lo, hi = np.full(5, -4.0), np.full(5, 4.0)
    out = bracketed_root(f, lo, hi, f(np.arange(5), lo), f(np.arange(5), hi))
    u = root_of_bracket(*out[:4])
    assert np.all(np.abs(u**3 + u - c) <= 1e-14 * np.maximum(1.0, np.abs(c)))
    assert np.all(out[4] <= 60)


def test_vector_root_from_a_start_to_xtol():
    """ln x of x^2 = a from a poor start: a bracket, then to xtol in u (= relative on x); status 1 / 2 where
    the function keeps its sign up to the bounds."""
    a = np.array([1e-3, 2.0, 5e4, 1e30, 1e-30])

    def f(idx, u):
        return 2.0 * u - np.log(a[idx])

    u0 = np.zeros(5)
    lo, hi, nev, status = vector_root(f, u0, np.full(5, -20.0), np.full(5, 20.0), 1e-9)
    ok = status == 0
    assert list(status) == [0, 0, 0, 1, 2]
    assert np.all(np.abs(np.exp(lo[ok]) - np.sqrt(a[ok])) <= 1e-9 * np.sqrt(a[ok]))
    assert np.all(hi[ok] - lo[ok] <= 1e-9) and np.all(2.0 * lo[ok] <= np.log(a[ok]))


def test_a_decreasing_function_by_the_sign_convention():
    """lo may lie above hi: what counts is f <= 0 at lo, >= 0 at hi."""

    def f(idx, u):
        return math.log(3.0) - u

    lo, hi = np.array([5.0]), np.array([-5.0])
    u = root_of_bracket(*bracketed_root(f, lo, hi, f(None, lo), f(None, hi))[:4])
    assert u[0] == pytest.approx(math.log(3.0), rel=1e-15)
