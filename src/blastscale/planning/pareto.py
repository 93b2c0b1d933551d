"""The Pareto-optimal designs of a plan: none other is at least as good on every objective and
better on one (docs/planning.md, "Trade-offs").

The objectives: the odds that the specimen's outcome agrees with the prototype's (``p_outcome_agree``,
higher is better), the predicted similarity error (``predicted_first_peak_error``, lower), the safety
radius (``safety_radius_m``, lower) and the charge (``tnt_equivalent_kg``, the TNT-equivalent impulse
mass, lower). A design without odds yet (screened, not run in 3D) is not compared: ``pareto`` None.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["OBJECTIVES", "pareto_mask", "mark_pareto"]

#: (key, sign): the sign turns each objective into one to minimise.
OBJECTIVES = (
    ("p_outcome_agree", -1.0),
    ("predicted_first_peak_error", 1.0),
    ("safety_radius_m", 1.0),
    ("tnt_equivalent_kg", 1.0),
)


def pareto_mask(costs) -> np.ndarray:
    """Which rows of ``costs`` (n, k), all to minimise, no other row dominates (at most as large in every
    column and smaller in one); equal rows are all kept."""
    c = np.asarray(costs, dtype=float)
    le = np.all(c[:, None, :] <= c[None, :, :], axis=-1)  # le[j, i]: j at most i everywhere
    lt = np.any(c[:, None, :] < c[None, :, :], axis=-1)
    return ~np.any(le & lt, axis=0)


def mark_pareto(designs: list) -> None:
    """Set ``pareto`` (True, False, or None without odds) on every design dict, in place."""
    rows = [
        i for i, d in enumerate(designs) if all(d.get(k) is not None and math.isfinite(d[k]) for k, _ in OBJECTIVES)
    ]
    for d in designs:
        d["pareto"] = None
    if not rows:
        return
    mask = pareto_mask([[s * designs[i][k] for k, s in OBJECTIVES] for i in rows])
    for i, m in zip(rows, mask):
        designs[i]["pareto"] = bool(m)
