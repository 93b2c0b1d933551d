"""The scalars of a sweep's cases: one Study per case (the one door; a planar block case costs
about 2 ms), or the outcome mode's vectorised first swing, and :func:`evaluate_chunk`, what a
worker runs. A case's values never depend on the other cases of its chunk."""

from __future__ import annotations

import math
import warnings

from .._threads import map_threads
from .._validate import BlastscaleInputError
from ..study.study import Study
from .outcomes import VALID_KEY, planar_outcomes
from .spec import SweepSpec

__all__ = ["study_scalars", "evaluate_chunk"]


def _scalars(scenario) -> dict:

    try:
        return {**Study(scenario).run().scalars(), VALID_KEY: True}
    except BlastscaleInputError:
        return {VALID_KEY: False}


def study_scalars(scenario) -> dict:
    """The Study path: ``Study(scenario).run().scalars()`` plus ``sweep.valid`` (warnings
    silenced: a sweep reports results, not one warning per case). A case the Study refuses
    (e.g. a model scaled distance outside the blast fits) gives ``{"sweep.valid": False}``:
    its other values are NaN in the store."""

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return _scalars(scenario)


def _chunk_rows(spec: SweepSpec, start: int, stop: int) -> list:
    """One Study per case; a chunk's 3D cases in parallel native threads (:mod:`blastscale._threads`:
    the scenario's ``simulation.threads``, default the process's share of the cores), planar ones in
    order (a planar Study is mostly Python, which holds the GIL; the outcome mode splits its kernel calls
    over the threads instead, :mod:`blastscale.rocking._batch`). Warnings are silenced once, here
    (``catch_warnings`` is process-wide)."""

    scenarios = [spec.scenario(k) for k in range(start, stop)]
    threads = 1 if spec.planar_only else scenarios[0].simulation.threads if scenarios else 1
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return map_threads(_scalars, scenarios, threads)


def evaluate_chunk(payload: dict, start: int, stop: int) -> dict:
    """Scalars of the cases ``start .. stop - 1`` of a sweep (``payload`` from
    :meth:`SweepSpec.to_payload`): ``{"start", "stop", "values": {key: list}}``: the outcome
    mode's arrays, or one Study per case."""
    spec = SweepSpec.from_payload(payload)
    if spec.outcomes:
        return {"start": start, "stop": stop, "values": planar_outcomes(spec, start, stop)}
    rows = _chunk_rows(spec, start, stop)
    keys = sorted({k for r in rows for k in r})
    return {"start": start, "stop": stop, "values": {k: [r.get(k, math.nan) for r in rows] for k in keys}}
