"""The Study: the one door from a scenario to the similarity verdict (like pvlib's ModelChain).

* :class:`Study` (:mod:`.study`) -- design once, run the engines that apply, compare once; :class:`StudyPlan`,
  what :meth:`Study.check` built before simulating (the engine settings resolved once, typed);
  :meth:`Study.from_design` (one system of a design alone) and :meth:`Study.from_candidate` (the planner's);
* :data:`ENGINES`, :data:`ENSEMBLE` (:mod:`.engines`) -- planar rocking, 3D rigid bodies, ensembles;
* :class:`StudyResult` (:mod:`.result`) -- summary, scalars, histories;
* :func:`estimate_memory`, :func:`estimate_seconds`, :func:`check_budget` (:mod:`.memory`): the one size and
  time guard of every command that simulates.
"""

from .engines import ENGINES, ENSEMBLE, Engine, contact_settings
from .memory import (
    MEMORY_FRACTION,
    check_budget,
    check_memory,
    check_study_budget,
    estimate_memory,
    estimate_seconds,
    format_duration,
)
from .plan import StudyPlan
from .result import StudyResult
from .study import Progress, Study, StudyWarning

__all__ = [
    "Study",
    "StudyPlan",
    "StudyResult",
    "StudyWarning",
    "Progress",
    "ENGINES",
    "ENSEMBLE",
    "Engine",
    "estimate_memory",
    "MEMORY_FRACTION",
    "contact_settings",
    "check_memory",
    "check_budget",
    "check_study_budget",
    "estimate_seconds",
    "format_duration",
]
