"""The sort-and-sweep neighbour search of block models (issue #27, deliverable 3): the same pairs as the
test of every pair, in the same order, and far below every pair's work (a file of 10^5 blocks must not take
O(n^2)): counted in comparisons, not timed."""

from __future__ import annotations

import numpy as np
import pytest

from blastscale.structures import interfaces
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


class _CountingNumpy:
    """numpy, counting the elements the sweep's box tests (``np.all``) look at: the work of the search."""

    def __init__(self):
        self.elements = 0

    def all(self, a, *args, **kwargs):
        self.elements += np.size(a)
        return np.all(a, *args, **kwargs)

    def __getattr__(self, name):
        return getattr(np, name)


def _grid_work(monkeypatch, k: int) -> tuple[int, int]:
    """Pairs found and box-coordinate comparisons made on a k x k stack-bonded grid of unit boxes."""
    x, z = np.meshgrid(np.arange(k, dtype=float), np.arange(k, dtype=float), indexing="ij")
    lo = np.column_stack([x.ravel(), np.zeros(k * k), z.ravel()])
    counting = _CountingNumpy()
    monkeypatch.setattr(interfaces, "np", counting)
    pairs = near_pairs(lo, lo + 1.0)
    monkeypatch.undo()
    return len(pairs), counting.elements


def test_a_grid_of_boxes_is_far_below_every_pair(monkeypatch):
    """Complexity by counting, not by the clock. On a k x k grid (n = k^2 boxes, each touching its 8
    neighbours) the sweep along one axis tests, for each box, the boxes of its own and the next column whose
    start lies within it: about 2 k candidates, 12 coordinate comparisons each (3 axes, 2 bounds, 2 tests), so
    O(n^1.5) comparisons: x8 from k = 100 to 200, where every pair would be x16 (and 4e9 at k = 300). Measured
    (k = 50, 100, 200): 441, 891, 1791 comparisons per box. Timing: benchmarks/bench_assemblies.py."""
    work = {}
    for k in (100, 200):
        found, work[k] = _grid_work(monkeypatch, k)
        # neighbours sharing a face or an edge (closed boxes touch): 2 k (k - 1) faces + 2 (k - 1)^2 diagonals
        assert found == 2 * k * (k - 1) + 2 * (k - 1) ** 2
        assert work[k] <= 12 * (k + 1) * k * k  # at most about 2 k candidates per box, ...
        assert work[k] < 0.02 * 6 * k * k * (k * k - 1)  # ... under 2 % of the comparisons of every pair
    assert work[200] / work[100] < 9.0  # n^1.5 (x8), not n^2 (x16)
