"""Cost of the sort-and-sweep neighbour search (:func:`blastscale.structures.interfaces.near_pairs`) on k x k
stack-bonded grids of unit boxes, as ratios to its cost at k = 100 (the baseline, measured in the same run):
the growth in n = k^2 next to n's (linear) and n^1.5's (the sweep along one axis of a square grid;
tests/unit/structures/test_near_pairs.py counts the comparisons instead). The timing moved here from that
test (issue #40: no clock in the test suite). Not a test: ``python benchmarks/bench_near_pairs.py [--json]``.
"""

from __future__ import annotations

import json
import sys
import time

import numpy as np

from blastscale.structures.interfaces import near_pairs

BASE_K = 100


def seconds(k: int, repeat: int = 3) -> float:
    """Least wall time [s] of ``repeat`` searches on a k x k grid."""
    x, z = np.meshgrid(np.arange(k, dtype=float), np.arange(k, dtype=float), indexing="ij")
    lo = np.column_stack([x.ravel(), np.zeros(k * k), z.ravel()])
    best = float("inf")
    for _ in range(repeat):
        t = time.perf_counter()
        near_pairs(lo, lo + 1.0)
        best = min(best, time.perf_counter() - t)
    return best


def main():
    base = seconds(BASE_K)
    rows = {f"k{BASE_K}_seconds": base}
    for k in (200, 300):
        n_ratio = (k / BASE_K) ** 2
        rows[f"k{k}_over_k{BASE_K}"] = seconds(k) / base
        rows[f"k{k}_n_ratio"] = n_ratio
        rows[f"k{k}_n15_ratio"] = n_ratio**1.5
    if "--json" in sys.argv:
        print(json.dumps(rows, indent=2))
    else:
        for k, v in rows.items():
            print(f"{k:24s} {v:10.3f}")


if __name__ == "__main__":
    main()
