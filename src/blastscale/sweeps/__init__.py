"""Many cases: parameter sweeps over scenario fields (grids and Monte Carlo samples) run in chunks,
in this process or on Dask, resumable; the outcome mode (a million planar cases a minute);
fragility curves; the similarity map. Above the Study: every case is a Study (docs/sweeps.md). The
sweep is driven here (:mod:`.run`); files are written by :mod:`blastscale.io` (the chunk store
:mod:`blastscale.io.sweep_store`, below the sweeps)."""

from .cases import evaluate_chunk, study_scalars
from .grids import Distribution, parse_distribution, parse_grid
from .layout import StoreLocation, select, store_location
from .outcomes import OUTCOME_KEYS, VALID_KEY, planar_outcomes
from .run import SweepRun
from .runner import default_chunk, run_chunks
from .spec import SweepAxis, SweepSample, SweepSpec

__all__ = [
    "VALID_KEY",
    "OUTCOME_KEYS",
    "SweepAxis",
    "SweepSample",
    "SweepSpec",
    "SweepRun",
    "Distribution",
    "parse_distribution",
    "parse_grid",
    "evaluate_chunk",
    "planar_outcomes",
    "study_scalars",
    "default_chunk",
    "run_chunks",
    "StoreLocation",
    "store_location",
    "select",
]
