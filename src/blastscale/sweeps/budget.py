"""The size and time guard of the commands that run many cases (sweeps, the similarity map, fragility,
capacity curves): the study's one rule (:func:`blastscale.study.memory.check_budget`) applied to the
number of cases, before any work.

Per-case costs on one core of the 2-core development machine (docs/sweeps.md, benchmarks/bench_sweeps.py):
outcome mode and the first-swing criterion ~70 us per case; one planar Study per case ~3 ms (20,000
cases a minute); any other case one Study (:func:`blastscale.study.memory.estimate_seconds`). The
store is assembled in memory at the end: about :data:`VALUES_PER_CASE` doubles per case, held ~4 times
(chunks read back, the assembled tree, Zarr's encoding).
"""

from __future__ import annotations

from typing import Optional

from .._validate import BlastscaleInputError
from ..study.memory import check_budget, estimate_seconds
from ..study.study import Study

__all__ = ["check_sweep_budget", "check_cases_budget", "FIRST_SWING_SECONDS", "PLANAR_STUDY_SECONDS", "VALUES_PER_CASE"]

#: Wall time of one case decided by the first-swing criterion (outcome mode, fragility draws) [s].
FIRST_SWING_SECONDS = 7e-5
#: Wall time of one planar Study (design, rocking, comparison) in a sweep [s].
PLANAR_STUDY_SECONDS = 3e-3
#: Values stored per case: outcome mode, planar Study, 3D Study.
VALUES_PER_CASE = {"outcomes": 8, "planar": 80, "3d": 400}


def check_cases_budget(
    n_cases: int,
    seconds_per_case: float,
    values_per_case: int,
    workers: Optional[int],
    name: str = "cases",
    hint: str = "",
) -> None:
    """Refuse ``n_cases`` whose computing (on ``workers`` processes; None: a scheduler's unknown number,
    no time limit) or whose values in memory exceed the shared rule (one line naming ``name``)."""
    need = float(n_cases) * values_per_case * 8 * 4
    seconds = 0.0 if workers is None else float(n_cases) * seconds_per_case / max(1, workers)
    check_budget(name, float(n_cases), "", need, seconds, hint=hint)


def check_sweep_budget(spec, workers: Optional[int]) -> None:
    """Refuse, before any work, a sweep too large for the shared rule (its number of cases named, with the
    largest that fits)."""
    if spec.outcomes:
        per, values = FIRST_SWING_SECONDS, VALUES_PER_CASE["outcomes"]
    elif spec.planar_only:
        per, values = PLANAR_STUDY_SECONDS, VALUES_PER_CASE["planar"]
    else:
        try:
            structure = Study(spec.base).structure()
        except BlastscaleInputError:
            structure = None
        per, values = estimate_seconds(spec.base, structure) + 0.05, VALUES_PER_CASE["3d"]
    check_cases_budget(spec.n_cases, per, values, workers, name="cases", hint="fewer --vary values or --samples")
