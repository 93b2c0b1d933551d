"""The sort-and-sweep neighbour search of block models (issue #27, deliverable 3): the same pairs as the
test of every pair, in the same order, and linear in practice (a file of 10^5 blocks must not take O(n^2))."""

from __future__ import annotations

import time

import numpy as np
import pytest

from blastscale.structures.interfaces import near_pairs


def _all_pairs(lo, hi, strict):
    out = []
    for i in range(len(lo)):
        for j in range(i + 1, len(lo)):
            if strict:
                ok = np.all(lo[j] < hi[i]) and np.all(hi[j] > lo[i])
            else:
                ok = np.all(lo[j] <= hi[i]) and np.all(hi[j] >= lo[i])
            if ok:
                out.append((i, j))
    return out


@pytest.mark.parametrize("strict", [False, True])
def test_same_pairs_as_every_pair(strict):
    # random boxes on a coarse grid: touching faces (equal coordinates) and ties in the sort occur often
    rng = np.random.default_rng(7)
    lo = rng.integers(0, 6, size=(300, 3)).astype(float)
    hi = lo + rng.integers(0, 3, size=(300, 3))
    assert near_pairs(lo, hi, strict) == _all_pairs(lo, hi, strict)


def test_a_grid_of_boxes_is_linear():
    # a 300 x 300 stack-bonded grid (90,000 unit boxes): each touches its 8 neighbours -> 2 (n-300) + ... pairs;
    # the all-pairs test would compare 4e9 boxes. Bound: a few seconds on a shared 2-core machine.
    k = 300
    x, z = np.meshgrid(np.arange(k, dtype=float), np.arange(k, dtype=float), indexing="ij")
    lo = np.column_stack([x.ravel(), np.zeros(k * k), z.ravel()])
    t = time.perf_counter()
    pairs = near_pairs(lo, lo + 1.0)
    elapsed = time.perf_counter() - t
    # neighbours sharing a face or an edge (closed boxes touch): 2 k (k - 1) faces + 2 (k - 1)^2 diagonals
    assert len(pairs) == 2 * k * (k - 1) + 2 * (k - 1) ** 2
    assert elapsed < 20.0
